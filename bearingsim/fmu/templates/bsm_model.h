/* bearingsim FMU runtime: declarations shared by the generic template files.
 *
 * The model-specific part is generated at export: model_config.h (sizes, work sizes, GUID) and
 * model_data.c (start values, parameter ranges, names, table of the CasADi-generated functions).
 * Nothing here depends on an FMI version; fmi2_api.c maps the FMI 2.0 API onto it.
 */
#ifndef BSM_MODEL_H
#define BSM_MODEL_H

#include <stddef.h>

#include "bsm_bdf.h"
#include "bsm_lu.h"
#include "model_config.h"

#ifndef BSM_STEPPER_BDF
#define BSM_STEPPER_BDF 0 /* the co-simulation stepper: the BDF core (bsm_bdf.c) */
#endif

#define BSM_DIM(n) ((n) > 0 ? (n) : 1)

typedef long long bsm_int; /* CasADi's default casadi_int */

typedef int (*bsm_eval_fn)(const double **arg, double **res, bsm_int *iw, double *w, int mem);
typedef const bsm_int *(*bsm_sparsity_fn)(bsm_int i);
typedef int (*bsm_checkout_fn)(void);
typedef void (*bsm_release_fn)(int mem);

/* One CasADi-generated function of (t, x, u, p) with a single (sparse) result. */
typedef struct {
    const char *name;
    bsm_eval_fn eval;
    bsm_sparsity_fn sparsity_out;
    bsm_checkout_fn checkout;
    bsm_release_fn release;
} BsmFunction;

/* Order of the function table (bearingsim.fmu.codegen.FUNCTION_NAMES). */
enum {
    FN_ODE, FN_JAC_X, FN_JAC_U, FN_JAC_T, FN_OUTPUT, FN_OUT_JAC_X, FN_OUT_JAC_U, FN_OUT_JAC_T,
    FN_COUNT
};

/* Bound flags of a parameter's or an input's range. */
enum { BSM_HAS_LOW = 1, BSM_LOW_INCLUSIVE = 2, BSM_HAS_HIGH = 4, BSM_HIGH_INCLUSIVE = 8 };

extern const BsmFunction bsm_functions[FN_COUNT];
extern const double bsm_x_start[BSM_DIM(NX)];
/* Typical magnitudes of the states (bearingsim.fmu.nominal), for importers' tolerances. */
extern const double bsm_x_nominal[BSM_DIM(NX)];
extern const double bsm_u_start[BSM_DIM(NU)];
extern const double bsm_p_start[BSM_DIM(NP)];
extern const double bsm_p_low[BSM_DIM(NP)];
extern const double bsm_p_high[BSM_DIM(NP)];
extern const unsigned char bsm_p_bounds[BSM_DIM(NP)];
/* Ranges of the inputs (refused outside) and the magnitude above which a value is warned
 * about (INFINITY: none), with what that limit is and what exceeding it means. */
extern const double bsm_u_low[BSM_DIM(NU)];
extern const double bsm_u_high[BSM_DIM(NU)];
extern const unsigned char bsm_u_bounds[BSM_DIM(NU)];
extern const double bsm_u_warn_above[BSM_DIM(NU)];
extern const char *const bsm_u_limit_names[BSM_DIM(NU)];
extern const char *const bsm_u_limit_effects[BSM_DIM(NU)];
extern const char *const bsm_x_names[BSM_DIM(NX)];
extern const char *const bsm_u_names[BSM_DIM(NU)];
extern const char *const bsm_y_names[BSM_DIM(NY)];
extern const char *const bsm_p_names[BSM_DIM(NP)];
extern const char *const bsm_u_units[BSM_DIM(NU)];
extern const char *const bsm_p_units[BSM_DIM(NP)];
/* Fill-reducing order of the states for the LU factorisation of the stepper (a permutation of
 * 0 .. NX-1, computed at export from the sparsity of d der(x)/dx), and the pattern of
 * W = I/(h gamma) - J in that order (compressed columns: the pattern of J and the diagonal). */
extern const int bsm_lu_order[BSM_DIM(NX)];
extern const int bsm_lu_start[BSM_DIM(NX + 1)];
extern const int bsm_lu_index[BSM_DIM(BSM_LU_NNZ)];

/* Same numbering as fmi2Status / fmi3Status. */
typedef enum { BSM_OK = 0, BSM_WARNING = 1, BSM_DISCARD = 2, BSM_ERROR = 3 } BsmStatus;

typedef void (*bsm_logger)(void *host, BsmStatus status, const char *category,
                           const char *message);

/* Inputs inside a co-simulation step from the API layer (FMI 3.0 intermediate update): the
 * stepper calls it with a time t in the step; it writes the inputs at t into u and returns 1,
 * or returns 0 to leave them to the polynomial of the input derivatives,
 * u0 + du (t - t0) + d2u (t - t0)^2 / 2 + d3u (t - t0)^3 / 6. */
typedef int (*bsm_inputs_fn)(void *host, double t, double *u);

/* Everything that defines where an instance is: saved and restored as one block
 * (FMU state get/set/serialize). */
typedef struct {
    int mode;           /* state machine of the API layer */
    int is_cs;          /* co-simulation instance */
    double time;
    double x[BSM_DIM(NX)];
    double u[BSM_DIM(NU)];
    double du[BSM_DIM(NU)]; /* input slopes for the next doStep */
    double d2u[BSM_DIM(NU)]; /* second and third time derivatives of the inputs at the step */
    double d3u[BSM_DIM(NU)]; /* start (FMI 2.0 input derivatives of order 2 and 3) */
    double p[BSM_DIM(NP)];
    double h_next;          /* proposed internal step of the stepper (0: none yet) */
    double rtol;
    long n_steps, n_rejected; /* accepted and rejected internal steps */
    long n_jac, n_lu;         /* Jacobian evaluations and LU factorisations of the stepper */
    /* Where the stepper's Jacobian belongs (so a restored state continues bit for bit: the
     * instance re-evaluates J there when its cached one belongs elsewhere). */
    int jac_set;                /* 0: no Jacobian yet, or parameters/states set since */
    long jac_age;               /* accepted internal steps since its evaluation */
    double jac_t;               /* time [s], states and inputs of its evaluation */
    double jac_x[BSM_DIM(NX)];
    double jac_u[BSM_DIM(NU)];
    double jac_h;               /* step size of the LU factorisation of W [s] (0: none) */
#if BSM_STEPPER_BDF
    /* the BDF stepper's history (bsm_bdf.h): its scalars, the differences D and the inputs
     * at its end (a jump from these restarts it) */
    BsmBdfHistory bdf;
    double bdf_D[BSM_BDF_D_ROWS * BSM_DIM(NX)];
    double bdf_u[BSM_DIM(NU)];
#endif
} BsmState;

typedef struct {
    BsmState s;
    /* cached evaluations at (s.time, s.x, s.u, s.p) */
    int dx_valid, y_valid;
    double dx[BSM_DIM(NX)];
    double y[BSM_DIM(NY)];
    /* CasADi work memory */
    const double *arg[BSM_DIM(BSM_SZ_ARG)];
    double *res[BSM_DIM(BSM_SZ_RES)];
    bsm_int iw[BSM_DIM(BSM_SZ_IW)];
    double w[BSM_DIM(BSM_SZ_W)];
    double nz[BSM_DIM(BSM_SZ_NZ)];
    /* dense Jacobians, row major */
    double jx[BSM_DIM(NX * NX)];
    double ju[BSM_DIM(NX * NU)];
    double jt[BSM_DIM(NX)];
    double yx[BSM_DIM(NY * NX)];
    double yu[BSM_DIM(NY * NU)];
    double yt[BSM_DIM(NY)];
    /* stepper work */
    double w_jx[BSM_DIM(NX * NX)]; /* the stepper's Jacobians (kept across doSteps) */
    double w_jt[BSM_DIM(NX)];
    double w_ju[BSM_DIM(NX * NU)];
    int w_valid;                   /* w_j* were evaluated at w_t, w_x, w_u, w_p */
    double w_t;
    double w_x[BSM_DIM(NX)];
    double w_u[BSM_DIM(NU)];
    double w_p[BSM_DIM(NP)];
    double w_h;                    /* step size of the factorisation in lu_a [s] (0: none);
                                    * BDF: its c [s] */
    double lu_a[BSM_DIM(BSM_LU_NNZ)]; /* W's (BDF: I - c J's) nonzeros on
                                       * bsm_lu_start/bsm_lu_index */
    /* its sparse factors (bsm_lu.h; lu_c's pointers are set to the arrays before each use) */
    BsmLu lu_c;
    int lu_row_of[BSM_DIM(NX)];
    int lu_step_of[BSM_DIM(NX)];
    int lu_l_start[BSM_DIM(NX) + 1];
    int lu_l_index[BSM_DIM(NX * NX / 2)];
    double lu_l_val[BSM_DIM(NX * NX / 2)];
    int lu_u_start[BSM_DIM(NX) + 1];
    int lu_u_index[BSM_DIM(NX * NX / 2)];
    int lu_u_pos[BSM_DIM(NX * NX / 2)];
    double lu_u_val[BSM_DIM(NX * NX / 2)];
    int lu_ur_start[BSM_DIM(NX) + 1];
    int lu_ur_index[BSM_DIM(NX * NX / 2)];
    double lu_ur_val[BSM_DIM(NX * NX / 2)];
    double lu_inv_diag[BSM_DIM(NX)];
    double lu_x[BSM_DIM(NX)];
    int lu_work[BSM_DIM(3 * NX)];
#if BSM_STEPPER_BDF
    double bdf_work[BSM_BDF_WORK_VECTORS * BSM_DIM(NX)];
#endif
    double k[4][BSM_DIM(NX)];
    double f[BSM_DIM(NX)];
    double xs[BSM_DIM(NX)];
    double x_new[BSM_DIM(NX)];
    double dfdt[BSM_DIM(NX)];
    double rate_u[BSM_DIM(NU)]; /* input rates at the start of the internal step */
    double ut[BSM_DIM(NU)];
    BsmState saved; /* state at the start of a doStep, restored on failure */
    /* host */
    const char *instance_name;
    void *host;
    bsm_logger logger;
    int debug_logging;
    unsigned char u_warned[BSM_DIM(NU)]; /* input k was warned about (bsm_u_warn_above) */
    unsigned char u_clamped[BSM_DIM(NU)]; /* input k was extrapolated out of its range */
    bsm_inputs_fn inputs_between; /* NULL: inputs follow their derivatives' polynomial */
} BsmInstance;

/* Outcome of a shared API operation: done; refused without harm (bad arguments or a call in
 * the wrong mode; logged); failed in the model (logged; the caller puts the instance in its
 * error state); done with a warning (logged). */
typedef enum {
    BSM_CALL_DONE = 0, BSM_CALL_REFUSED = 1, BSM_CALL_FAILED = 2, BSM_CALL_WARNED = 3
} BsmCall;

/* bsm_eval.c */
const char *bsm_num(char buf[32], double v);
void bsm_log(BsmInstance *m, BsmStatus status, const char *category, const char *fmt, ...);
void bsm_reset(BsmInstance *m);
void bsm_invalidate(BsmInstance *m);
int bsm_eval_dense(BsmInstance *m, int fn, double t, const double *x, const double *u,
                   double *out);
BsmStatus bsm_derivatives(BsmInstance *m, double t, const double *x, const double *u,
                          double *dx);
BsmStatus bsm_current_derivatives(BsmInstance *m);
BsmStatus bsm_current_outputs(BsmInstance *m);
BsmStatus bsm_check_parameter(BsmInstance *m, int k, double value);
BsmStatus bsm_check_input(BsmInstance *m, int k, double value);
/* Value of the Float64 variable ``r`` below VR_END (the caller rejects other references). */
BsmStatus bsm_get_real(BsmInstance *m, unsigned int r, double *value);
/* Set a state start value, an input or a parameter (each checked; states and parameters only
 * when the caller's mode allows it). */
BsmCall bsm_set_real(BsmInstance *m, unsigned int r, double v, int states_settable,
                     int parameters_settable, const char *function);
/* out = d(unknowns)/d(knowns) seed, knowns states or inputs, at the current state. */
BsmCall bsm_directional_derivative(BsmInstance *m, const unsigned int *unknowns, size_t n_unknown,
                                   const unsigned int *knowns, size_t n_known,
                                   const double *seed, double *out, const char *function);
/* First time derivatives of outputs (states reported as outputs included) at the current state,
 * with the input slopes set by SetRealInputDerivatives: dy/dt = dy/dx der(x) + dy/du du +
 * partial dy/dt. */
BsmCall bsm_output_derivatives(BsmInstance *m, const unsigned int *vr, size_t n,
                               const int *order, double *values, const char *function);
size_t bsm_serialized_size(void);
BsmStatus bsm_serialize(BsmInstance *m, const BsmState *s, unsigned int magic, void *buffer,
                        size_t size, const char *function);
BsmStatus bsm_deserialize(BsmInstance *m, unsigned int magic, const void *buffer, size_t size,
                          BsmState *s, const char *function);

/* bsm_solver.c */
BsmStatus bsm_do_step(BsmInstance *m, double h);

#endif
