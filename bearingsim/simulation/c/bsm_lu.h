/* Sparse LU factorisation of a matrix with a fixed pattern, for repeated factorisations of
 * Newton matrices: left-looking (Gilbert and Peierls, SIAM J. Sci. Stat. Comput. 9(5), 1988,
 * as in Davis' CSparse cs_lu, "Direct Methods for Sparse Linear Systems", SIAM 2006, ch. 6)
 * with threshold partial pivoting that prefers the diagonal. The first factorisation finds
 * the pivot order and the fill pattern of L and U; later ones reuse both and touch the
 * nonzeros only (as KLU's refactor) until the pivot order must change, when it factorises
 * afresh. When it must change is the caller's choice (keep_order):
 * - 1: when a kept pivot falls below BSM_LU_TOL times the largest candidate of its column
 *   (the new order is then kept in turn): fewest fresh factorisations;
 * - 0: when the pivoting rule would choose another pivot, so that a factorisation's result
 *   depends on the matrix only, not on the factorisations before it (an FMU state restored
 *   continues bit for bit).
 *
 * Shared by the compiled BDF integrator (bdf.c) and the FMU's co-simulation stepper
 * (fmu/templates/bsm_solver.c), which both factorise I - c J of a model Jacobian with the
 * unknowns in a fill-reducing order (bearingsim.simulation.ordering: each ball's states
 * before the ring and cage states every ball couples to). */
#ifndef BSM_LU_H
#define BSM_LU_H

/* The diagonal is the pivot while |diagonal| >= BSM_LU_TOL times the largest candidate of its
 * column (KLU's default: Davis and Palamadai Natarajan, ACM TOMS 37(3), 2010, art. 36). On the
 * ball-level Newton matrices I - c J the diagonal then stays the pivot for c up to ~1e-4 s
 * (0.1 let the angle states' columns change pivots near the step sizes the runs take, each
 * change a fresh factorisation); the solves' residuals stay at rounding level. */
#ifndef BSM_LU_TOL
#define BSM_LU_TOL 1e-3
#endif

/* A matrix pattern and its LU factors P A = L U.
 * Caller's: n; keep_order (above); a_start (n + 1) and a_index (a_start[n]): the pattern
 * of A in compressed columns (rows of each column distinct, the diagonal included); the
 * arrays below, of the sizes given; pivoted = 0 before the first factorisation (and to force
 * a fresh one).
 * The factorisation's: row_of[k]: the row of A pivoted at step k, step_of its inverse;
 * entries l_start[k] .. l_start[k+1]-1 of l_index/l_val: column k of L below its unit
 * diagonal (rows numbered by step); u_start[k] .. u_start[k+1]-1 of u_index: the pattern of
 * column k of U above the diagonal (rows by step, in the order of elimination), u_pos: where
 * each of those entries is in U's rows; ur_start[i] .. ur_start[i+1]-1 of ur_index/ur_val:
 * row i of U right of the diagonal (columns increasing; the solves run on rows); u_val:
 * the fresh factorisation's work; inv_diag[k]: the inverse of U's diagonal; pivotings: the
 * fresh factorisations so far.
 * Sizes: row_of, step_of, inv_diag and x n; l_start, u_start and ur_start n + 1; l_index,
 * l_val, u_index, u_pos, u_val, ur_index and ur_val n (n - 1) / 2 (the worst case); work 3 n
 * ints. */
typedef struct {
    int n;
    int keep_order;
    const int *a_start;
    const int *a_index;
    int pivoted;
    long pivotings;
    int *row_of;
    int *step_of;
    int *l_start;
    int *l_index;
    double *l_val;
    int *u_start;
    int *u_index;
    int *u_pos;
    double *u_val;
    int *ur_start;
    int *ur_index;
    double *ur_val;
    double *inv_diag;
    double *x;
    int *work;
} BsmLu;

int bsm_lu_factor(BsmLu *c, const double *a_val);
void bsm_lu_solve(const BsmLu *c, const int *order, double *work, double *x);

#endif
