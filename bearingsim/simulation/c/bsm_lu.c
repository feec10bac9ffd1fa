/* LU factorisation of small sparse matrices held dense (bsm_lu.h). */
#include <math.h>

#include "bsm_lu.h"

/* LU factorisation with partial pivoting of the dense row-major a (n x n, destroyed) into the
 * compressed factors c, eliminating only the structural nonzeros: at step k the rows with a
 * nonzero in column k (found with the pivot) take the pivot row's nonzeros right of k. The
 * row interchanges touch the columns not yet eliminated only (LINPACK's dgefa order; the
 * solve applies them between the columns of L). work: 2 n ints. Returns 0, or 1 + the step
 * at which the matrix is singular. */
int bsm_lu_factor(double *a, int n, const BsmLu *c, int *work) {
    int *rows = work, *cols = work + n;
    int nl = 0, nu = 0;
    for (int k = 0; k < n; ++k) {
        int p = k, nr = 0, nc = 0;
        double big = 0.0;
        for (int i = k; i < n; ++i) {
            double v = fabs(a[i * n + k]);
            if (v != 0.0) {
                rows[nr++] = i;
                if (!(v <= big)) { /* also NaN */
                    big = v;
                    p = i;
                }
            }
        }
        if (big == 0.0 || !isfinite(big)) return k + 1;
        c->piv[k] = p;
        double *ak = a + k * n;
        if (p != k) {
            double *ap = a + p * n;
            for (int j = k; j < n; ++j) {
                double tmp = ak[j];
                ak[j] = ap[j];
                ap[j] = tmp;
            }
        }
        double inv = 1.0 / ak[k];
        c->inv_diag[k] = inv;
        c->u_start[k] = nu;
        for (int j = k + 1; j < n; ++j)
            if (ak[j] != 0.0) {
                cols[nc++] = j;
                c->u_index[nu] = j;
                c->u_val[nu++] = ak[j];
            }
        c->l_start[k] = nl;
        for (int q = 0; q < nr; ++q) {
            int r = rows[q] == p ? k : rows[q] == k ? p : rows[q];
            if (r == k) continue;
            double *ar = a + r * n;
            double l = ar[k] * inv;
            c->l_index[nl] = r;
            c->l_val[nl++] = l;
            for (int m = 0; m < nc; ++m) ar[cols[m]] -= l * ak[cols[m]];
        }
    }
    c->l_start[n] = nl;
    c->u_start[n] = nu;
    return 0;
}

/* Solve A x = b in place with the factors of bsm_lu_factor, A's unknowns in the order
 * order (b and x in the original order; work: n doubles). */
void bsm_lu_solve(const BsmLu *c, int n, const int *order, double *work, double *x) {
    double *b = work;
    for (int i = 0; i < n; ++i) b[i] = x[order[i]];
    for (int k = 0; k < n; ++k) {
        int p = c->piv[k];
        double bk = b[p];
        b[p] = b[k];
        b[k] = bk;
        for (int q = c->l_start[k]; q < c->l_start[k + 1]; ++q) b[c->l_index[q]] -= c->l_val[q] * bk;
    }
    /* four partial sums: a single one would wait on each product's addition */
    for (int i = n - 1; i >= 0; --i) {
        const int *index = c->u_index;
        const double *val = c->u_val;
        double s0 = b[i], s1 = 0.0, s2 = 0.0, s3 = 0.0;
        int q = c->u_start[i], end = c->u_start[i + 1];
        for (; q + 4 <= end; q += 4) {
            s0 -= val[q] * b[index[q]];
            s1 -= val[q + 1] * b[index[q + 1]];
            s2 -= val[q + 2] * b[index[q + 2]];
            s3 -= val[q + 3] * b[index[q + 3]];
        }
        for (; q < end; ++q) s0 -= val[q] * b[index[q]];
        b[i] = ((s0 + s1) + (s2 + s3)) * c->inv_diag[i];
    }
    for (int i = 0; i < n; ++i) x[order[i]] = b[i];
}
