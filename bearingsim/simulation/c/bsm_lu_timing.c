/* Timing loops of the sparse LU (bsm_lu.h) for its Python binding
 * (bearingsim.simulation.sparse_lu.SparseLu.time_calls): the calls repeated inside C, so that
 * a call's cost is measured without the caller's share (Python, ctypes). Not part of the
 * integrators. */
#include <string.h>

#include "bsm_lu.h"

/* repeats factorisations of a_val in the kept pivot order */
void bsm_lu_factor_repeat(BsmLu *c, const double *a_val, int repeats) {
    for (int k = 0; k < repeats; ++k) bsm_lu_factor(c, a_val);
}

/* repeats x = b, then the solve of x in place (solve = 0: the copies alone, to take them out) */
void bsm_lu_solve_repeat(const BsmLu *c, const int *order, double *work, const double *b,
                         double *x, int repeats, int solve) {
    for (int k = 0; k < repeats; ++k) {
        memcpy(x, b, sizeof(double) * (size_t)c->n);
        if (solve) bsm_lu_solve(c, order, work, x);
    }
}
