/* LU factorisation of small sparse matrices held dense: partial pivoting that skips
 * structural zeros, and solves on the factors' nonzeros only. Shared by the compiled BDF
 * integrator (bdf.c) and the FMU's co-simulation stepper (fmu/templates/bsm_solver.c), which
 * both factorise I - c J of a model Jacobian in a fill-reducing order of its unknowns
 * (bearingsim.simulation.ordering: each ball's states before the ring and cage states every
 * ball couples to), where the factors keep the Jacobian's sparsity. */
#ifndef BSM_LU_H
#define BSM_LU_H

/* LU factors (bsm_lu_factor), compressed: step k interchanged rows k and piv[k], then
 * entries l_start[k] .. l_start[k+1]-1 of l_index/l_val are column k of L below the diagonal
 * (unit diagonal implied; row numbers as of step k), u_start[k] .. u_start[k+1]-1 of
 * u_index/u_val row k of U right of the diagonal, inv_diag[k] the inverse of its diagonal.
 * Sizes: piv and inv_diag n, l_start and u_start n + 1, l_index, l_val, u_index and u_val
 * n (n - 1) / 2 at most. */
typedef struct {
    int *piv;
    int *l_start;
    int *l_index;
    double *l_val;
    int *u_start;
    int *u_index;
    double *u_val;
    double *inv_diag;
} BsmLu;

int bsm_lu_factor(double *a, int n, const BsmLu *c, int *work);
void bsm_lu_solve(const BsmLu *c, int n, const int *order, double *work, double *x);

#endif
