/* LU factorisation of small sparse matrices held dense: partial pivoting that skips
 * structural zeros, and solves on the factors' nonzeros only. Shared by the compiled BDF
 * integrator (bdf.c) and the FMU's co-simulation stepper (fmu/templates/bsm_solver.c), which
 * both factorise I - c J of a model Jacobian in a fill-reducing order of its unknowns
 * (bearingsim.simulation.ordering), where the factors keep few nonzeros: about 600 of 5625
 * for the 75-state massive-ball 6304 bearing. */
#ifndef BSM_LU_H
#define BSM_LU_H

/* LU factors in compressed rows (bsm_lu_compress): entries l_start[i] .. l_start[i+1]-1 of
 * col/val are row i of L below the diagonal, u_start[i] .. u_start[i+1]-1 row i of U right of
 * it. Sizes: l_start and u_start n + 1, col and val n * n, inv_diag n. */
typedef struct {
    int *l_start;
    int *u_start;
    int *col;
    double *val;
    double *inv_diag;
} BsmLu;

int bsm_lu_factor(double *a, int n, int *piv, int *nzcol);
void bsm_lu_compress(const double *a, int n, const BsmLu *c);
void bsm_lu_solve(const BsmLu *c, int n, const int *piv, double *b);

#endif
