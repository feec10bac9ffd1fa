/* LU factorisation of small sparse matrices held dense (bsm_lu.h). */
#include <math.h>

#include "bsm_lu.h"

/* LU factorisation with partial pivoting, in place, row major, skipping the structural zeros
 * of each pivot row and column. nzcol: work of n ints. Returns 0 or 1 + the column at which
 * the matrix is singular. */
int bsm_lu_factor(double *a, int n, int *piv, int *nzcol) {
    int i, j, k, p, q, nnz;
    for (k = 0; k < n; ++k) {
        double big = 0.0, inv;
        double *ak;
        p = k;
        for (i = k; i < n; ++i)
            if (fabs(a[i * n + k]) > big) {
                big = fabs(a[i * n + k]);
                p = i;
            }
        piv[k] = p;
        if (big == 0.0 || !isfinite(big)) return k + 1;
        if (p != k)
            for (j = 0; j < n; ++j) {
                double tmp = a[k * n + j];
                a[k * n + j] = a[p * n + j];
                a[p * n + j] = tmp;
            }
        ak = a + k * n;
        nnz = 0;
        for (j = k + 1; j < n; ++j)
            if (ak[j] != 0.0) nzcol[nnz++] = j;
        inv = 1.0 / ak[k];
        for (i = k + 1; i < n; ++i) {
            double *ai = a + i * n;
            double l = ai[k];
            if (l == 0.0) continue;
            l *= inv;
            ai[k] = l;
            for (q = 0; q < nnz; ++q) ai[nzcol[q]] -= l * ak[nzcol[q]];
        }
    }
    return 0;
}

/* Copy the nonzeros of the LU factors a (from bsm_lu_factor) row by row into c: the strictly
 * lower part (unit diagonal implied), then the strictly upper part, and the inverse diagonal, so
 * that a solve costs the factors' nonzeros, not n^2. */
void bsm_lu_compress(const double *a, int n, const BsmLu *c) {
    int i, j, k = 0;
    for (i = 0; i < n; ++i) {
        c->l_start[i] = k;
        for (j = 0; j < i; ++j)
            if (a[i * n + j] != 0.0) {
                c->col[k] = j;
                c->val[k++] = a[i * n + j];
            }
    }
    c->l_start[n] = k;
    for (i = 0; i < n; ++i) {
        c->u_start[i] = k;
        for (j = i + 1; j < n; ++j)
            if (a[i * n + j] != 0.0) {
                c->col[k] = j;
                c->val[k++] = a[i * n + j];
            }
        c->inv_diag[i] = 1.0 / a[i * n + i];
    }
    c->u_start[n] = k;
}

/* Solve A x = b in place with the row interchanges piv of bsm_lu_factor and the compressed
 * factors. */
void bsm_lu_solve(const BsmLu *c, int n, const int *piv, double *b) {
    int i, k;
    for (i = 0; i < n; ++i) {
        double tmp = b[piv[i]];
        b[piv[i]] = b[i];
        b[i] = tmp;
    }
    for (i = 1; i < n; ++i) {
        double s = b[i];
        for (k = c->l_start[i]; k < c->l_start[i + 1]; ++k) s -= c->val[k] * b[c->col[k]];
        b[i] = s;
    }
    for (i = n - 1; i >= 0; --i) {
        double s = b[i];
        for (k = c->u_start[i]; k < c->u_start[i + 1]; ++k) s -= c->val[k] * b[c->col[k]];
        b[i] = s * c->inv_diag[i];
    }
}
