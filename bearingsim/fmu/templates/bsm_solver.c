/* bearingsim FMU runtime: the co-simulation stepper, selected at export (BSM_STEPPER_BDF,
 * BSM_STEPPER_RODAS3 in model_config.h).
 *
 * - BDF: the variable-order BDF stepping core of the compiled BDF integrator (bsm_bdf.c, the
 *   same source), its history (bsm_bdf.h: order, step sizes, differences, the LU's c) in the
 *   FMU state and kept across doSteps. Each communication step is divided into equal internal
 *   steps no longer than the controller's step size (BSM_BDF_EVEN), so the last one ends on
 *   the communication point and the next doStep goes on with the same step size and order.
 *   It starts again (order 1, a new first step) when states or parameters were set, the
 *   history does not end at the instance's time and states, or an input moved by more than
 *   BSM_INPUT_JUMP from the value the history ended with. Where its Jacobian was evaluated is
 *   recorded in the state (jac_t, jac_x, jac_u), so a restored state re-creates J and the LU
 *   of I - c J and continues bit for bit.
 *
 * Or one of two linearly implicit one-step methods with an embedded order-2 solution for
 * step-size control:
 *
 * - ROS34PW2 (Rang and Angermann, BIT 45 (2005) 761-787): a 4-stage, order-3,
 *   stiffly accurate Rosenbrock-W method, L-stable for the exact Jacobian. It keeps its order
 *   with any matrix in place of the Jacobian (W-method), so the Jacobian and the LU
 *   factorisation of W = I/(h gamma) - J are reused over many steps and communication steps:
 *   J is evaluated again only after a rejected step taken with an old J, after
 *   BSM_JAC_MAX_AGE accepted steps, or when a doStep starts from a changed instance (inputs
 *   moved by more than BSM_INPUT_JUMP relative to those of J, parameters or states set). W is
 *   factorised again only when J is new or the step size changes: the controller keeps the
 *   factorised step size while its proposal is within [1, BSM_H_KEEP] times it, and the steps
 *   inside a communication step are of equal length, so one factorisation serves all of them
 *   and the following doSteps. Where J was evaluated is part of the FMU state, so a restored
 *   state continues bit for bit. Coefficients: the A, Gamma, b and
 *   b_hat of PETSc's TSROSWRA34PW2 (src/ts/impls/rosw/rosw.c, the same as the paper's
 *   Table), transformed to the form below (Hairer and Wanner, Solving ODEs II, IV.7
 *   (7.25)): a = A Gamma^-1, c = diag(1/gamma) - Gamma^-1, m = b Gamma^-1.
 * - Rodas3 (Sandu et al. 1997): a 4-stage, order-3, L-stable and stiffly accurate Rosenbrock
 *   method (the stepper of earlier versions). Its order needs the exact Jacobian, so J is
 *   evaluated and W factorised at every step.
 *
 * All use the exact Jacobian d der(x)/dx of the generated code when they evaluate one. The
 * Rosenbrock stage equations are (I/(h gamma) - J) k_s = f(t + alpha_s h, x + sum_j a_sj k_j)
 * + sum_j c_sj / h k_j + h gamma_s df/dt and x_new = x + sum_s m_s k_s. Inputs follow
 * u(t) = u0 + du (t - t0) + d2u (t - t0)^2 / 2 + d3u (t - t0)^3 / 6 over the communication
 * step (du = d2u = d3u = 0 unless input derivatives were set), so df/dt includes jac_u times
 * the input rate at the start of each internal step (and the BDF's right-hand side sees
 * u(t)); an FMI 3.0
 * importer may instead give the inputs at every stage or right-hand-side time (intermediate
 * update, BsmInstance.inputs_between), for every stepper. The LU factorisation (bsm_lu.c,
 * shared with the compiled BDF integrator) is a sparse one on W (BDF: I - c J) permuted by
 * the fill-reducing order bsm_lu_order (a minimum-degree order of the Jacobian's sparsity,
 * computed at export with W's pattern bsm_lu_start/bsm_lu_index): its pivot order and fill
 * pattern are found once and reused while the pivoting rule would choose the same pivots,
 * eliminating and solving on the nonzeros only.
 */
#include <math.h>
#include <string.h>

#include "bsm_model.h"

#ifndef BSM_STEPPER_RODAS3
#define BSM_STEPPER_RODAS3 0
#endif

#define ROS_STAGES 4
#define ROS_ORDER 3.0 /* exponent of the step-size controller: local error ~ h^3 */
#define ROS_MAX_STEPS 100000L
#ifndef BSM_JAC_MAX_AGE
#define BSM_JAC_MAX_AGE 100  /* accepted steps after which the W-method evaluates J again */
#endif
#ifndef BSM_H_KEEP
#define BSM_H_KEEP 2.0       /* keep the factorised step while the proposal is <= this times it */
#endif
#ifndef BSM_INPUT_JUMP
#define BSM_INPUT_JUMP 1e-2  /* relative input change at a doStep start that renews J */
#endif

/* Input k extrapolated to v at time t, held within its range (a radial load extrapolated
 * below 0 is 0: the model is not evaluated where a set value would be refused); the first
 * time per input and instance it is logged. */
static double held_in_range(int k, double v) {
    unsigned char b = bsm_u_bounds[k];
    if ((b & BSM_HAS_LOW) && v < bsm_u_low[k]) return bsm_u_low[k];
    if ((b & BSM_HAS_HIGH) && v > bsm_u_high[k]) return bsm_u_high[k];
    return v;
}

static double within_range(BsmInstance *m, int k, double v, double t) {
    double held = held_in_range(k, v);
    char num[32], bound[32];
    if (held != v && !m->u_clamped[k]) {
        m->u_clamped[k] = 1;
        bsm_log(m, BSM_WARNING, "logStatusWarning",
                "input %s extrapolated from its derivatives reaches %s [%s] at t = %g s, "
                "outside its valid range; held at %s [%s] (warned once per instance)",
                bsm_u_names[k], bsm_num(num, v), bsm_u_units[k], t, bsm_num(bound, held),
                bsm_u_units[k]);
    }
    return held;
}

/* Input k at time t by the polynomial of its derivatives at the step start. */
static double extrapolated(const BsmInstance *m, int k, double t) {
    double tau = t - m->saved.time;
    return m->saved.u[k] + tau * (m->saved.du[k] + tau * (m->saved.d2u[k] / 2.0
                                                          + tau * m->saved.d3u[k] / 6.0));
}

/* Inputs at time t of the step into m->ut: from the API layer where it gives them (FMI 3.0
 * intermediate update), else the polynomial of the input derivatives at the step start, held
 * within the inputs' ranges. */
static void inputs_at(BsmInstance *m, double t) {
    int i;
    if (m->inputs_between != NULL && m->inputs_between(m->host, t, m->ut)) return;
    for (i = 0; i < NU; ++i) m->ut[i] = within_range(m, i, extrapolated(m, i, t), t);
}

static int all_finite(const double *v, int n) {
    int i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* The sparse LU factors of the instance (its pivot order kept in lu_c between calls, changed
 * when the pivoting rule would choose other pivots: the factors depend on W only, so a
 * restored state continues bit for bit). */
static BsmLu *lu_factors(BsmInstance *m) {
    BsmLu *c = &m->lu_c;
    c->n = NX;
    c->keep_order = 0;
    c->a_start = bsm_lu_start;
    c->a_index = bsm_lu_index;
    c->row_of = m->lu_row_of;
    c->step_of = m->lu_step_of;
    c->l_start = m->lu_l_start;
    c->l_index = m->lu_l_index;
    c->l_val = m->lu_l_val;
    c->u_start = m->lu_u_start;
    c->u_index = m->lu_u_index;
    c->u_pos = m->lu_u_pos;
    c->u_val = m->lu_u_val;
    c->ur_start = m->lu_ur_start;
    c->ur_index = m->lu_ur_index;
    c->ur_val = m->lu_ur_val;
    c->inv_diag = m->lu_inv_diag;
    c->x = m->lu_x;
    c->work = m->lu_work;
    return c;
}

/* Factorise diag I - scale J (W = I/(h gamma) - J, or the BDF's I - c J) on W's pattern in
 * the order bsm_lu_order. Returns 0, or nonzero if singular. */
static int factor_w(BsmInstance *m, double diag, double scale) {
    int i, j, q;
    const int *o = bsm_lu_order;
    for (j = 0; j < NX; ++j)
        for (q = bsm_lu_start[j]; q < bsm_lu_start[j + 1]; ++q) {
            i = bsm_lu_index[q];
            m->lu_a[q] = -scale * m->w_jx[o[i] * NX + o[j]];
            if (i == j) m->lu_a[q] += diag;
        }
    return bsm_lu_factor(lu_factors(m), m->lu_a);
}

/* Solve W k = b in place (b in the model's state order). */
static void solve(BsmInstance *m, double *b) {
    bsm_lu_solve(lu_factors(m), bsm_lu_order, m->xs, b);
}

/* The instance at the end t_end of a communication step: the inputs there, no slopes. */
static void end_step(BsmInstance *m, double t_end) {
    m->s.time = t_end;
    inputs_at(m, t_end);
    memcpy(m->s.u, m->ut, sizeof(m->s.u));
    memset(m->s.du, 0, sizeof(m->s.du));
    memset(m->s.d2u, 0, sizeof(m->s.d2u));
    memset(m->s.d3u, 0, sizeof(m->s.d3u));
    bsm_invalidate(m);
}

static BsmStatus step_failed(BsmInstance *m, const char *reason, double t, double hs) {
    double t0 = m->saved.time;
    m->s = m->saved;
    bsm_invalidate(m);
    bsm_log(m, BSM_DISCARD, "logStatusDiscard",
            "doStep from t = %g s: %s at t = %g s (internal step %g s); state restored to t = %g s",
            t0, reason, t, hs, t0);
    return BSM_DISCARD;
}

#if BSM_STEPPER_BDF
/* ------------------------------------------------------------------ BDF stepper */
/* The model of the BDF core (bsm_bdf.h): der(x) with the inputs of the communication step,
 * the Jacobian d der(x)/dx (recorded in the state: where it was evaluated) and the LU of
 * I - c J in the order bsm_lu_order. */
static int bdf_rhs(void *model, double t, const double *x, double *f) {
    BsmInstance *m = (BsmInstance *)model;
    inputs_at(m, t);
    return bsm_eval_dense(m, FN_ODE, t, x, m->ut, f) ? BSM_BDF_MODEL_FAILED : BSM_BDF_OK;
}

/* J at (t, x, u) into the instance's cache. Returns a status code. */
static int bdf_eval_jacobian(BsmInstance *m, double t, const double *x, const double *u) {
    m->w_valid = 0;
    m->w_h = 0.0;
    if (bsm_eval_dense(m, FN_JAC_X, t, x, u, m->w_jx) != 0) return BSM_BDF_MODEL_FAILED;
    if (!all_finite(m->w_jx, NX * NX)) return BSM_BDF_NOT_FINITE;
    m->w_t = t;
    memcpy(m->w_x, x, sizeof(m->w_x));
    memcpy(m->w_u, u, sizeof(m->w_u));
    memcpy(m->w_p, m->s.p, sizeof(m->w_p));
    m->w_valid = 1;
    return BSM_BDF_OK;
}

static int bdf_jacobian(void *model, double t, const double *x) {
    BsmInstance *m = (BsmInstance *)model;
    inputs_at(m, t);
    m->s.jac_set = 0;
    m->s.jac_t = t;
    memcpy(m->s.jac_x, x, sizeof(m->s.jac_x));
    memcpy(m->s.jac_u, m->ut, sizeof(m->s.jac_u));
    int status = bdf_eval_jacobian(m, t, x, m->ut);
    m->s.jac_set = status == BSM_BDF_OK;
    return status;
}

static int bdf_factor(void *model, double c) {
    BsmInstance *m = (BsmInstance *)model;
    m->w_h = 0.0;
    if (factor_w(m, 1.0, c) != 0) return 1;
    m->w_h = c;
    return 0;
}

static void bdf_solve(void *model, double *x) { solve((BsmInstance *)model, x); }

static const BsmBdfOps bdf_ops = {bdf_rhs, bdf_jacobian, bdf_factor, bdf_solve};

/* The core on the instance's state (its history) and work. */
static BsmBdf bdf_core(BsmInstance *m) {
    BsmBdf b;
    b.n = NX;
    b.rtol = m->s.rtol;
    b.atol = 0.01 * m->s.rtol; /* as the Rosenbrock steppers' error weights */
    b.max_step = HUGE_VAL;
    b.ops = &bdf_ops;
    b.model = m;
    b.h = &m->s.bdf;
    b.D = m->s.bdf_D;
    b.work = m->bdf_work;
    bsm_bdf_init(&b);
    return b;
}

/* Whether the history continues at the start of this doStep: it ends at s.time (within the
 * API's tolerance) at the states s.x, no state or parameter was set since, and the inputs are
 * within BSM_INPUT_JUMP of those it ended with. If so, the instance's J and LU are made those
 * the history names (evaluated and factorised again only if the cached ones belong
 * elsewhere). */
static int bdf_history_continues(BsmInstance *m) {
    int i;
    BsmBdfHistory *h = &m->s.bdf;
    if (!m->s.jac_set || fabs(h->t - m->s.time) > 1e-9 * fmax(1.0, fabs(m->s.time)) ||
        memcmp(m->s.bdf_D, m->s.x, sizeof(double) * NX) != 0)
        return 0;
    for (i = 0; i < NU; ++i)
        if (fabs(m->s.u[i] - m->s.bdf_u[i]) > BSM_INPUT_JUMP * fabs(m->s.bdf_u[i])) return 0;
    h->t = m->s.time;
    if (!(m->w_valid && m->w_t == m->s.jac_t &&
          memcmp(m->w_x, m->s.jac_x, sizeof(m->w_x)) == 0 &&
          memcmp(m->w_u, m->s.jac_u, sizeof(m->w_u)) == 0 &&
          memcmp(m->w_p, m->s.p, sizeof(m->w_p)) == 0) &&
        bdf_eval_jacobian(m, m->s.jac_t, m->s.jac_x, m->s.jac_u) != BSM_BDF_OK)
        return 0;
    if (h->lu_valid && m->w_h != h->c_lu && bdf_factor(m, h->c_lu) != 0) h->lu_valid = 0;
    return 1;
}

static const char *bdf_reason(int status) {
    switch (status) {
    case BSM_BDF_STEP_TOO_SMALL: return "the step size became too small";
    case BSM_BDF_SINGULAR: return "the Newton matrix is singular";
    case BSM_BDF_NOT_FINITE: return "the Jacobian is not finite";
    default: return "the model equations could not be evaluated";
    }
}

/* One communication step h with the BDF core: steps of equal size to t + h (BSM_BDF_EVEN),
 * the history kept across doSteps. */
static BsmStatus bdf_do_step(BsmInstance *m, double h) {
    BsmBdf b = bdf_core(m);
    double t = m->s.time, t_end = t + h;
    long n = 0;
    int status = BSM_BDF_OK;
    BsmStatus st;
    m->saved = m->s;
    st = bsm_derivatives(m, t, m->s.x, m->s.u, m->dx);
    if (st != BSM_OK) return st;
    if (NX > 0 && !bdf_history_continues(m))
        status = bsm_bdf_first_step(&b, t, m->s.x, t_end);
    while (NX > 0 && status == BSM_BDF_OK && m->s.bdf.t < t_end) {
        if (++n > ROS_MAX_STEPS)
            return step_failed(m, "too many internal steps", m->s.bdf.t, m->s.bdf.h_abs);
        status = bsm_bdf_step(&b, t_end, BSM_BDF_EVEN);
    }
    if (status != BSM_BDF_OK)
        return step_failed(m, bdf_reason(status), m->s.bdf.t, m->s.bdf.h_abs);
    memcpy(m->s.x, m->s.bdf_D, sizeof(double) * NX);
    end_step(m, t_end);
    memcpy(m->s.bdf_u, m->s.u, sizeof(m->s.bdf_u));
    m->s.n_steps = (long)m->s.bdf.stats[BSM_BDF_STEPS];
    m->s.n_rejected = (long)(m->s.bdf.stats[BSM_BDF_ERROR_FAILS] +
                             m->s.bdf.stats[BSM_BDF_NEWTON_FAILS]);
    m->s.n_jac = (long)m->s.bdf.stats[BSM_BDF_JEVALS];
    m->s.n_lu = (long)m->s.bdf.stats[BSM_BDF_LUS];
    return BSM_OK;
}

#else /* the Rosenbrock steppers */
#if BSM_STEPPER_RODAS3
/* Rodas3 in the transformed form (a, c lower triangular, row by row). */
static const double ros_gamma_diag = 0.5;
static const double ros_a[6] = {0.0, 2.0, 0.0, 2.0, 0.0, 1.0};
static const double ros_c[6] = {4.0, 1.0, -1.0, 1.0, -1.0, -8.0 / 3.0};
static const int ros_new_f[ROS_STAGES] = {1, 0, 1, 1};
static const double ros_m[ROS_STAGES] = {2.0, 0.0, 1.0, 1.0};
static const double ros_e[ROS_STAGES] = {0.0, 0.0, 0.0, 1.0};
static const double ros_alpha[ROS_STAGES] = {0.0, 0.0, 1.0, 1.0};
static const double ros_gamma[ROS_STAGES] = {0.5, 1.5, 0.0, 0.0};
static const int ros_reuse = 0;
#else
/* ROS34PW2 in the transformed form; ros_e = m - m_hat; ros_alpha, ros_gamma: row sums of A
 * and Gamma. */
static const double ros_gamma_diag = 4.3586652150845900e-01;
static const double ros_a[6] = {2.0000000000000004e+00, 1.4192173174557652e+00,
                                -2.5923221167296978e-01, 4.1847604823191613e+00,
                                -2.8519201735549599e-01, 2.2942803602790423e+00};
static const double ros_c[6] = {-4.5885607205580836e+00, -4.1847604823191613e+00,
                                2.8519201735549599e-01, -6.3681792001283597e+00,
                                -6.7956209444668367e+00, 2.8700986043310555e+00};
static const int ros_new_f[ROS_STAGES] = {1, 1, 1, 1};
static const double ros_m[ROS_STAGES] = {4.1847604823191613e+00, -2.8519201735549599e-01,
                                         2.2942803602790423e+00, 1.0};
static const double ros_e[ROS_STAGES] = {2.7774994764796903e-01, -1.4032398951759988e+00,
                                         1.7726301276675507e+00, 0.5};
static const double ros_alpha[ROS_STAGES] = {0.0, 8.7173304301691801e-01,
                                             7.3157995778885238e-01, 1.0};
static const double ros_gamma[ROS_STAGES] = {4.3586652150845900e-01, -4.3586652150845900e-01,
                                             -4.1333337623388650e-01, 0.0};
static const int ros_reuse = 1;
#endif

/* Right-hand side at (t, y) with interpolated inputs, without logging: the stepper treats a
 * non-finite value as a rejected step. Returns 1 if finite. */
static int rhs(BsmInstance *m, double t, const double *y, double *f) {
    inputs_at(m, t);
    if (bsm_eval_dense(m, FN_ODE, t, y, m->ut, f) != 0) return 0;
    return all_finite(f, NX);
}

/* df/dt = jac_t + jac_u * du/dt [unit of x / s^2] at time t of the step from the stepper's
 * Jacobians, du/dt the rate of the inputs' polynomial there (0 where it is held at a bound). */
static void time_derivative(BsmInstance *m, double t) {
    int i, j;
    double tau = t - m->saved.time;
    for (j = 0; j < NU; ++j) {
        double v = extrapolated(m, j, t);
        m->rate_u[j] = (held_in_range(j, v) != v) ? 0.0 :
            m->saved.du[j] + tau * (m->saved.d2u[j] + tau * m->saved.d3u[j] / 2.0);
    }
    for (i = 0; i < NX; ++i) {
        m->dfdt[i] = m->w_jt[i];
        for (j = 0; j < NU; ++j) m->dfdt[i] += m->w_ju[i * NU + j] * m->rate_u[j];
    }
}

/* Evaluate the stepper's Jacobians at (t, x, u) into the instance's cache. Returns 1 if
 * finite. */
static int eval_jacobian(BsmInstance *m, double t, const double *x, const double *u) {
    m->w_valid = 0;
    m->w_h = 0.0;
    m->s.n_jac++;
    if (bsm_eval_dense(m, FN_JAC_X, t, x, u, m->w_jx) != 0) return 0;
    if (bsm_eval_dense(m, FN_JAC_T, t, x, u, m->w_jt) != 0) return 0;
    if (NU > 0 && bsm_eval_dense(m, FN_JAC_U, t, x, u, m->w_ju) != 0) return 0;
    if (!all_finite(m->w_jx, NX * NX) || !all_finite(m->w_jt, NX) ||
        !all_finite(m->w_ju, NX * NU))
        return 0;
    m->w_t = t;
    memcpy(m->w_x, x, sizeof(m->w_x));
    memcpy(m->w_u, u, sizeof(m->w_u));
    memcpy(m->w_p, m->s.p, sizeof(m->w_p));
    m->w_valid = 1;
    return 1;
}

/* A new Jacobian at (t, x) and the inputs at t, recorded in the state. Returns 1 if
 * finite. */
static int new_jacobian(BsmInstance *m, double t, const double *x) {
    inputs_at(m, t);
    m->s.jac_set = 0;
    m->s.jac_h = 0.0;
    if (!eval_jacobian(m, t, x, m->ut)) return 0;
    m->s.jac_set = 1;
    m->s.jac_age = 0;
    m->s.jac_t = t;
    memcpy(m->s.jac_x, x, sizeof(m->s.jac_x));
    memcpy(m->s.jac_u, m->ut, sizeof(m->s.jac_u));
    return 1;
}

/* Factorise W = I/(h gamma) - J in the order bsm_lu_order. Returns 1 if not singular. */
static int factorise(BsmInstance *m, double h) {
    m->w_h = 0.0;
    m->s.jac_h = 0.0;
    m->s.n_lu++;
    if (factor_w(m, 1.0 / (h * ros_gamma_diag), 1.0) != 0) return 0;
    m->w_h = h;
    m->s.jac_h = h;
    return 1;
}

/* Make the instance's Jacobian and factorisation those the state names (after a restored FMU
 * state, or a parameter set since), evaluating and factorising again only if the cached ones
 * belong elsewhere. Returns 1 if they are usable. */
static int restore_jacobian(BsmInstance *m) {
    double h = m->s.jac_h;
    if (!(m->w_valid && m->w_t == m->s.jac_t &&
          memcmp(m->w_x, m->s.jac_x, sizeof(m->w_x)) == 0 &&
          memcmp(m->w_u, m->s.jac_u, sizeof(m->w_u)) == 0 &&
          memcmp(m->w_p, m->s.p, sizeof(m->w_p)) == 0)) {
        if (!eval_jacobian(m, m->s.jac_t, m->s.jac_x, m->s.jac_u)) return 0;
    }
    if (h > 0.0 && m->w_h != h) return factorise(m, h);
    m->s.jac_h = m->w_h;
    return 1;
}

/* One step of size h from (t, x) with the current factorisation (built for a step size near
 * h). Result in m->x_new; returns the weighted RMS error estimate, or -1 if a stage was not
 * finite. */
static double ros_step(BsmInstance *m, double t, const double *x, double h) {
    int i, j, s;
    double err = 0.0;
    if (!rhs(m, t, x, m->f)) return -1.0;
    for (s = 0; s < ROS_STAGES; ++s) {
        double *ks = m->k[s];
        if (s > 0 && ros_new_f[s]) {
            for (i = 0; i < NX; ++i) {
                m->xs[i] = x[i];
                for (j = 0; j < s; ++j) m->xs[i] += ros_a[s * (s - 1) / 2 + j] * m->k[j][i];
            }
            if (!rhs(m, t + ros_alpha[s] * h, m->xs, m->f)) return -1.0;
        }
        for (i = 0; i < NX; ++i) {
            ks[i] = m->f[i] + h * ros_gamma[s] * m->dfdt[i];
            for (j = 0; j < s; ++j) ks[i] += ros_c[s * (s - 1) / 2 + j] / h * m->k[j][i];
        }
        solve(m, ks);
    }
    for (i = 0; i < NX; ++i) {
        double e = 0.0, sc;
        m->x_new[i] = x[i];
        for (s = 0; s < ROS_STAGES; ++s) {
            m->x_new[i] += ros_m[s] * m->k[s][i];
            e += ros_e[s] * m->k[s][i];
        }
        sc = 0.01 * m->s.rtol + m->s.rtol * fmax(fabs(x[i]), fabs(m->x_new[i]));
        err += (e / sc) * (e / sc);
    }
    err = sqrt(err / (NX > 0 ? NX : 1));
    return (isfinite(err) && all_finite(m->x_new, NX)) ? err : -1.0;
}

/* Whether the W-method can go on with the Jacobian the state names: there is one, no state
 * or parameter was set since, and the inputs are within BSM_INPUT_JUMP of those of J. Makes
 * the instance's cached J and LU those of the state. */
static int jacobian_current(BsmInstance *m) {
    int i;
    if (!m->s.jac_set) return 0;
    for (i = 0; i < NU; ++i)
        if (fabs(m->s.u[i] - m->s.jac_u[i]) > BSM_INPUT_JUMP * fabs(m->s.jac_u[i])) return 0;
    return restore_jacobian(m);
}

/* Length of the next internal step [s]. Rodas3 takes the proposed step h_prop and shortens
 * the last one. The W-method keeps the step size h_lu of its factorisation while the proposal
 * is in [h_lu, BSM_H_KEEP h_lu] and divides what is left of the communication step into equal
 * steps no longer than that, so that one factorisation serves all of them and, for the same
 * communication step, the next doStep. */
static double next_step(double h_prop, double remaining, double h_lu) {
    double h;
    if (!ros_reuse)
        return (h_prop >= remaining || remaining - h_prop < 1e-3 * h_prop) ? remaining : h_prop;
    h = (h_lu > 0.0 && h_prop >= h_lu && h_prop <= BSM_H_KEEP * h_lu) ? h_lu : h_prop;
    return remaining / fmax(1.0, ceil(remaining / h - 1e-6));
}

/* One communication step h with the Rosenbrock stepper. */
static BsmStatus ros_do_step(BsmInstance *m, double h) {
    double t, t_end, h_prop, err;
    long n = 0;
    int rejected = 0, need_jac;
    BsmStatus st;
    m->saved = m->s;
    t = m->s.time;
    t_end = t + h;
    st = bsm_derivatives(m, t, m->s.x, m->s.u, m->dx);
    if (st != BSM_OK) return st;
    h_prop = (m->s.h_next > 0.0) ? m->s.h_next : h;
    need_jac = !ros_reuse || !jacobian_current(m);
    while (NX > 0 && t_end - t > 1e-13 * fmax(1.0, fabs(t_end))) {
        double hs = next_step(h_prop, t_end - t, m->w_h);
        int ok = 1;
        if (++n > ROS_MAX_STEPS) return step_failed(m, "too many internal steps", t, hs);
        if (need_jac) ok = new_jacobian(m, t, m->s.x);
        need_jac = !ros_reuse;
        /* equal steps of a communication step differ from the factorised one by rounding only;
         * W of a nearby h is I/(hs gamma) - (J + delta I), still a W-method */
        if (ok && !(ros_reuse && fabs(hs - m->w_h) <= 1e-6 * hs))
            ok = factorise(m, hs);
        if (ok) time_derivative(m, t); /* the inputs' rate at the internal step's start */
        err = ok ? ros_step(m, t, m->s.x, hs) : -1.0;
        if (err >= 0.0 && err <= 1.0) {
            double fac = (err > 0.0) ? 0.9 * pow(err, -1.0 / ROS_ORDER) : 5.0;
            fac = fmin(rejected ? 1.0 : 5.0, fmax(0.2, fac));
            t += hs;
            memcpy(m->s.x, m->x_new, sizeof(double) * NX);
            m->s.n_steps++;
            h_prop = (hs < h_prop) ? fmax(h_prop, hs * fac) : hs * fac;
            rejected = 0;
            if (++m->s.jac_age >= BSM_JAC_MAX_AGE) need_jac = 1;
        } else {
            double fac = (err > 0.0) ? fmax(0.1, 0.9 * pow(err, -1.0 / ROS_ORDER)) : 0.25;
            m->s.n_rejected++;
            h_prop = hs * fmin(fac, 0.5);
            rejected = 1;
            if (m->s.jac_age > 0 || !m->s.jac_set) need_jac = 1; /* an old J may be the cause */
            if (h_prop < 1e-14 * fmax(1.0, fabs(t)))
                return step_failed(m,
                                   err < 0.0 ? "the equations are not finite or singular"
                                             : "the step size became too small",
                                   t, h_prop);
        }
    }
    m->s.h_next = h_prop;
    end_step(m, t_end);
    return BSM_OK;
}
#endif

/* Integrate from s.time over one communication step h. If the right-hand side is not finite at
 * the start, BSM_ERROR is returned; if the stepper fails later (step size too small, too many
 * steps), the instance is restored to the start of the step and BSM_DISCARD is returned. */
BsmStatus bsm_do_step(BsmInstance *m, double h) {
#if BSM_STEPPER_BDF
    return bdf_do_step(m, h);
#else
    return ros_do_step(m, h);
#endif
}
