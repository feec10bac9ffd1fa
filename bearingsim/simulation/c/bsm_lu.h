/* Sparse LU factorisation of a matrix with a fixed pattern, for repeated factorisations of
 * Newton matrices: left-looking (Gilbert and Peierls, SIAM J. Sci. Stat. Comput. 9(5), 1988,
 * as in Davis' CSparse cs_lu, "Direct Methods for Sparse Linear Systems", SIAM 2006, ch. 6)
 * with threshold partial pivoting that prefers the diagonal. The first factorisation finds
 * the pivot order and the fill pattern of L and U; later ones reuse both and touch the
 * nonzeros only (as KLU's refactor), until the pivoting rule would choose another pivot, when
 * it factorises afresh. A factorisation's result depends on the matrix only, not on the
 * factorisations before it (the reused order is kept only while the rule would choose it).
 *
 * Shared by the compiled BDF integrator (bdf.c) and the FMU's co-simulation stepper
 * (fmu/templates/bsm_solver.c), which both factorise I - c J of a model Jacobian with the
 * unknowns in a fill-reducing order (bearingsim.simulation.ordering: each ball's states
 * before the ring and cage states every ball couples to). */
#ifndef BSM_LU_H
#define BSM_LU_H

/* Pivots are kept while |pivot| >= BSM_LU_TOL times the largest candidate of its column. */
#define BSM_LU_TOL 0.1

/* A matrix pattern and its LU factors P A = L U.
 * Caller's: n; a_start (n + 1) and a_index (a_start[n]): the pattern of A in compressed
 * columns (rows of each column distinct, the diagonal included); the arrays below, of the
 * sizes given; pivoted = 0 before the first factorisation (and to force a fresh one).
 * The factorisation's: row_of[k]: the row of A pivoted at step k, step_of its inverse;
 * entries l_start[k] .. l_start[k+1]-1 of l_index/l_val: column k of L below its unit
 * diagonal (rows numbered by step); u_start[k] .. u_start[k+1]-1 of u_index/u_val: column k
 * of U above the diagonal (rows by step, in the order of elimination); inv_diag[k]: the
 * inverse of U's diagonal; pivotings: the fresh factorisations so far.
 * Sizes: row_of, step_of, inv_diag and x n; l_start and u_start n + 1; l_index, l_val,
 * u_index and u_val n (n - 1) / 2 (the worst case); work 3 n ints. */
typedef struct {
    int n;
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
    double *u_val;
    double *inv_diag;
    double *x;
    int *work;
} BsmLu;

int bsm_lu_factor(BsmLu *c, const double *a_val);
void bsm_lu_solve(const BsmLu *c, const int *order, double *work, double *x);

#endif
