/* The stepping core of the variable-order BDF integrator (orders 1-5, numerical
 * differentiation formulas), shared by the compiled BDF integrator (bdf.c, driven by
 * bearingsim.simulation.compiled_bdf) and the FMU's co-simulation stepper
 * (fmu/templates/bsm_solver.c). The algorithm is described in bsm_bdf.c.
 *
 * The core knows the model only through BsmBdfOps: the right-hand side, the Jacobian and the
 * LU factorisation of I - c J with its solve (the caller keeps J and the factors). Everything
 * the next step depends on besides the model, J and the factors is the history: the scalars of
 * BsmBdfHistory and the backward differences D (with the last step's inverse error weights). A
 * caller that saves both, and re-creates J and the factors where the history says they were
 * made (jac_t, jac_x: its own record; c_lu), takes the same steps again bit for bit.
 */
#ifndef BSM_BDF_H
#define BSM_BDF_H

#define BSM_BDF_MAX_ORDER 5
/* rows of n values in D: the differences of orders 0 .. MAX_ORDER + 2, then the inverse error
 * weights of the last step */
#define BSM_BDF_D_ROWS (BSM_BDF_MAX_ORDER + 4)
#define BSM_BDF_WORK_VECTORS 8                 /* work vectors of n values */

/* Status codes (bearingsim.simulation.compiled_bdf.STATUS). */
enum {
    BSM_BDF_OK = 0,
    BSM_BDF_STEP_TOO_SMALL = 1,
    BSM_BDF_SINGULAR = 2,
    BSM_BDF_NOT_FINITE = 3,
    BSM_BDF_MODEL_FAILED = 4
};

/* Counters (bearingsim.simulation.compiled_bdf.STAT_NAMES). */
enum {
    BSM_BDF_STEPS, BSM_BDF_FEVALS, BSM_BDF_JEVALS, BSM_BDF_LUS, BSM_BDF_ERROR_FAILS,
    BSM_BDF_NEWTON_FAILS, BSM_BDF_N_STATS
};

/* How a step ends at t_stop: cut the step that would pass it (the steps before keep the
 * controller's size), or divide what is left into equal steps no longer than the
 * controller's (so a run stopped at many points keeps its step size and order). */
enum { BSM_BDF_CLIP = 0, BSM_BDF_EVEN = 1 };

typedef struct {
    /* f = der(x) at (t, x): a status code */
    int (*rhs)(void *model, double t, const double *x, double *f);
    /* evaluate and keep J = d der(x)/dx at (t, x): a status code */
    int (*jacobian)(void *model, double t, const double *x);
    /* factorise I - c J of the kept J: 0, or nonzero if singular */
    int (*factor)(void *model, double c);
    /* x = (I - c J)^-1 x with the kept factors */
    void (*solve)(void *model, double *x);
} BsmBdfOps;

/* The history's scalars. */
typedef struct {
    double t;      /* time of D [s] */
    double h_abs;  /* spacing of D [s] */
    double h_want; /* the controller's step size [s] (BSM_BDF_EVEN) */
    double h_last; /* the last step [s] (interpolation) */
    double c_lu;   /* c of the factors [s] */
    double crate;  /* Newton convergence rate estimate */
    double safety; /* step-size safety factor of the last step */
    int order, order_last, n_equal_steps;
    int lu_valid, jac_current, jac_age, adapt_pending;
    int jac_wanted; /* a new Jacobian at the next step (the last converged slowly) */
    long long stats[BSM_BDF_N_STATS];
} BsmBdfHistory;

typedef struct {
    int n;
    double rtol, atol; /* error weights atol + rtol |y| */
    double max_step;   /* [s] */
    const BsmBdfOps *ops;
    void *model;
    BsmBdfHistory *h;
    double *D;    /* BSM_BDF_D_ROWS x n: the backward differences (history) */
    double *work; /* BSM_BDF_WORK_VECTORS x n */
    double gamma[BSM_BDF_MAX_ORDER + 2], alpha[BSM_BDF_MAX_ORDER + 2];
    double error_const[BSM_BDF_MAX_ORDER + 2];
} BsmBdf;

/* Set the NDF coefficients of b (its other fields are the caller's). */
void bsm_bdf_init(BsmBdf *b);
/* Start at (t0, x0): the first step size for a run towards t_stop, D, order 1 and a Jacobian
 * at the start (the counters are kept). A status code. */
int bsm_bdf_first_step(BsmBdf *b, double t0, const double *x0, double t_stop);
/* One step towards t_stop (not past it), ending there as `mode` says. A status code. */
int bsm_bdf_step(BsmBdf *b, double t_stop, int mode);
/* The state at t in [t - h_last, t] (the last step's interpolating polynomial), or at the
 * start time before the first step. */
void bsm_bdf_interpolate(const BsmBdf *b, double t, double *out);

#endif
