/* Sparse LU factorisation of a matrix with a fixed pattern (bsm_lu.h). */
#include <math.h>

#include "bsm_lu.h"

/* Whether candidate row a (value va) beats the best so far, row b (value vb): the larger
 * magnitude, on a tie the lower row of A (so the choice does not depend on the order in
 * which the candidates are visited). */
static int better(double va, int a, double vb, int b) {
    return va > vb || (va == vb && a < b);
}

/* The rows of A reached from column col in the graph of L (a pivoted row leads to the rows of
 * its column of L), children before parents: xi[top .. n-1], top returned (Gilbert and
 * Peierls' depth-first search, CSparse's cs_reach; xi[0 .. top-1] is the search's stack).
 * mark[i] == col: row i reached. */
static int reach(const BsmLu *c, int col, int *xi, int *pstack, int *mark) {
    int top = c->n;
    for (int p = c->a_start[col]; p < c->a_start[col + 1]; ++p) {
        if (mark[c->a_index[p]] == col) continue;
        int head = 0;
        xi[0] = c->a_index[p];
        while (head >= 0) {
            int r = xi[head], s = c->step_of[r];
            if (mark[r] != col) {
                mark[r] = col;
                pstack[head] = s < 0 ? 0 : c->l_start[s];
            }
            int end = s < 0 ? 0 : c->l_start[s + 1], q = pstack[head];
            while (q < end && mark[c->l_index[q]] == col) ++q;
            if (q < end) {
                pstack[head] = q + 1;
                xi[++head] = c->l_index[q];
            } else {
                --head;
                xi[--top] = r;
            }
        }
    }
    return top;
}

/* The factorisation with a new pivot order and pattern: at step k, x = L \ A(:, k) on the
 * rows reached (in their topological order: each row's value is final before it updates
 * others), U(:, k) the pivoted rows' values, and the pivot among the others: the diagonal
 * row k if within BSM_LU_TOL of the largest, else the largest. Returns 0 or 1 + the
 * singular step. */
static int factor_fresh(BsmLu *c, const double *a_val) {
    int n = c->n, *xi = c->work, *pstack = c->work + n, *mark = c->work + 2 * n;
    double *x = c->x;
    int nl = 0, nu = 0;
    c->pivoted = 0;
    c->pivotings++;
    for (int i = 0; i < n; ++i) c->step_of[i] = mark[i] = -1;
    for (int k = 0; k < n; ++k) {
        c->l_start[k] = nl;
        c->u_start[k] = nu;
        int top = reach(c, k, xi, pstack, mark);
        for (int p = top; p < n; ++p) x[xi[p]] = 0.0;
        for (int p = c->a_start[k]; p < c->a_start[k + 1]; ++p) x[c->a_index[p]] = a_val[p];
        for (int p = top; p < n; ++p) {
            int s = c->step_of[xi[p]];
            if (s < 0) continue;
            double xj = x[xi[p]];
            c->u_index[nu] = s;
            c->u_val[nu++] = xj;
            for (int q = c->l_start[s]; q < c->l_start[s + 1]; ++q)
                x[c->l_index[q]] -= c->l_val[q] * xj;
        }
        int pivot = -1;
        double big = 0.0;
        for (int p = top; p < n; ++p) {
            int i = xi[p];
            if (c->step_of[i] >= 0) continue;
            double v = fabs(x[i]);
            if (!isfinite(v)) return k + 1;
            if (pivot < 0 || better(v, i, big, pivot)) {
                big = v;
                pivot = i;
            }
        }
        if (pivot < 0 || big == 0.0) return k + 1;
        if (c->step_of[k] < 0 && mark[k] == k && fabs(x[k]) >= BSM_LU_TOL * big) pivot = k;
        double inv = 1.0 / x[pivot];
        c->inv_diag[k] = inv;
        c->row_of[k] = pivot;
        c->step_of[pivot] = k;
        for (int p = top; p < n; ++p) {
            int i = xi[p];
            if (c->step_of[i] >= 0) continue;
            c->l_index[nl] = i;
            c->l_val[nl++] = x[i] * inv;
        }
    }
    c->l_start[n] = nl;
    c->u_start[n] = nu;
    for (int q = 0; q < nl; ++q) c->l_index[q] = c->step_of[c->l_index[q]];
    /* U by rows: counted, then filled column by column (so each row's columns increase) */
    int *next = c->work;
    for (int i = 0; i <= n; ++i) c->ur_start[i] = 0;
    for (int q = 0; q < nu; ++q) c->ur_start[c->u_index[q] + 1]++;
    for (int i = 0; i < n; ++i) c->ur_start[i + 1] += c->ur_start[i];
    for (int i = 0; i < n; ++i) next[i] = c->ur_start[i];
    for (int k = 0; k < n; ++k)
        for (int q = c->u_start[k]; q < c->u_start[k + 1]; ++q) {
            int p = next[c->u_index[q]]++;
            c->ur_index[p] = k;
            c->ur_val[p] = c->u_val[q];
            c->u_pos[q] = p;
        }
    c->pivoted = 1;
    return 0;
}

/* The factorisation in the kept pivot order and pattern: the same operations as
 * factor_fresh's in the same order, on the nonzeros only. Returns 0, 1 + the singular step,
 * or -1 if at some step the pivot order must change (bsm_lu.h: keep_order). */
static int factor_again(BsmLu *c, const double *a_val) {
    int n = c->n;
    double *x = c->x;
    for (int k = 0; k < n; ++k) {
        int l0 = c->l_start[k], l1 = c->l_start[k + 1];
        int u0 = c->u_start[k], u1 = c->u_start[k + 1];
        for (int q = u0; q < u1; ++q) x[c->u_index[q]] = 0.0;
        for (int q = l0; q < l1; ++q) x[c->l_index[q]] = 0.0;
        x[k] = 0.0;
        for (int p = c->a_start[k]; p < c->a_start[k + 1]; ++p)
            x[c->step_of[c->a_index[p]]] = a_val[p];
        for (int q = u0; q < u1; ++q) {
            int s = c->u_index[q];
            double xj = x[s];
            c->ur_val[c->u_pos[q]] = xj;
            for (int r = c->l_start[s]; r < c->l_start[s + 1]; ++r)
                x[c->l_index[r]] -= c->l_val[r] * xj;
        }
        int pivot = k;
        double big = fabs(x[k]);
        if (!isfinite(big)) return k + 1;
        for (int q = l0; q < l1; ++q) {
            int i = c->l_index[q];
            double v = fabs(x[i]);
            if (!isfinite(v)) return k + 1;
            if (better(v, c->row_of[i], big, c->row_of[pivot])) {
                big = v;
                pivot = i;
            }
        }
        if (big == 0.0) return k + 1;
        if (c->keep_order) {
            if (!(fabs(x[k]) >= BSM_LU_TOL * big)) return -1;
        } else {
            int diag = c->step_of[k]; /* where row k of A is */
            if (diag >= k && fabs(x[diag]) >= BSM_LU_TOL * big) pivot = diag;
            if (pivot != k) return -1;
        }
        double inv = 1.0 / x[k];
        c->inv_diag[k] = inv;
        for (int q = l0; q < l1; ++q) c->l_val[q] = x[c->l_index[q]] * inv;
    }
    return 0;
}

/* P A = L U for A's nonzeros a_val (on c's pattern): in the kept pivot order and pattern
 * while the pivoting rule would choose it, else afresh. Returns 0, or 1 + the step at which
 * A is singular (or not finite). */
int bsm_lu_factor(BsmLu *c, const double *a_val) {
    if (c->pivoted) {
        int status = factor_again(c, a_val);
        if (status >= 0) return status;
    }
    return factor_fresh(c, a_val);
}

/* Solve A y = b in place, A's unknowns and equations in the order order (A's row and column
 * i are unknown and equation order[i]; x: b in, y out, in the original order; work: n
 * doubles). */
void bsm_lu_solve(const BsmLu *c, const int *order, double *work, double *x) {
    int n = c->n;
    double *b = work;
    for (int k = 0; k < n; ++k) b[k] = x[order[c->row_of[k]]];
    for (int k = 0; k < n; ++k) {
        double bk = b[k];
        for (int q = c->l_start[k]; q < c->l_start[k + 1]; ++q)
            b[c->l_index[q]] -= c->l_val[q] * bk;
    }
    /* four partial sums: a single one would wait on each product's addition */
    const int *index = c->ur_index;
    const double *val = c->ur_val;
    for (int i = n - 1; i >= 0; --i) {
        double s0 = b[i], s1 = 0.0, s2 = 0.0, s3 = 0.0;
        int q = c->ur_start[i], end = c->ur_start[i + 1];
        for (; q + 4 <= end; q += 4) {
            s0 -= val[q] * b[index[q]];
            s1 -= val[q + 1] * b[index[q + 1]];
            s2 -= val[q + 2] * b[index[q + 2]];
            s3 -= val[q + 3] * b[index[q + 3]];
        }
        for (; q < end; ++q) s0 -= val[q] * b[index[q]];
        b[i] = ((s0 + s1) + (s2 + s3)) * c->inv_diag[i];
    }
    for (int k = 0; k < n; ++k) x[order[k]] = b[k];
}
