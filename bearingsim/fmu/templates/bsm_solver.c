/* bearingsim FMU runtime: the co-simulation stepper.
 *
 * Rodas3 (Sandu et al. 1997): a 4-stage, order-3, L-stable and stiffly accurate Rosenbrock
 * method with an embedded order-2 solution for step-size control. It uses the exact Jacobian
 * d der(x)/dx of the generated code and one dense LU factorisation per step; inputs follow
 * u(t) = u0 + du * (t - t0) over the communication step (du = 0 unless input derivatives were
 * set), so the partial time derivative of the right-hand side includes jac_u * du.
 */
#include <math.h>
#include <string.h>

#include "bsm_model.h"

#define ROS_STAGES 4
#define ROS_ORDER 3.0 /* order of the local error estimate */
#define ROS_MAX_STEPS 100000L

static const double ros_gamma_diag = 0.5;
static const double ros_a[6] = {0.0, 2.0, 0.0, 2.0, 0.0, 1.0};
static const double ros_c[6] = {4.0, 1.0, -1.0, 1.0, -1.0, -8.0 / 3.0};
static const int ros_new_f[ROS_STAGES] = {1, 0, 1, 1};
static const double ros_m[ROS_STAGES] = {2.0, 0.0, 1.0, 1.0};
static const double ros_e[ROS_STAGES] = {0.0, 0.0, 0.0, 1.0};
static const double ros_alpha[ROS_STAGES] = {0.0, 0.0, 1.0, 1.0};
static const double ros_gamma[ROS_STAGES] = {0.5, 1.5, 0.0, 0.0};

/* LU factorisation with partial pivoting, in place, row major. Returns 0 or 1 + the column
 * at which the matrix is singular. */
int bsm_lu_factor(double *a, int n, int *piv) {
    int i, j, k, p;
    for (k = 0; k < n; ++k) {
        double big = 0.0;
        p = k;
        for (i = k; i < n; ++i)
            if (fabs(a[i * n + k]) > big) {
                big = fabs(a[i * n + k]);
                p = i;
            }
        piv[k] = p;
        if (big == 0.0 || !isfinite(big)) return k + 1;
        if (p != k)
            for (j = 0; j < n; ++j) {
                double tmp = a[k * n + j];
                a[k * n + j] = a[p * n + j];
                a[p * n + j] = tmp;
            }
        for (i = k + 1; i < n; ++i) {
            double l = a[i * n + k] / a[k * n + k];
            a[i * n + k] = l;
            if (l != 0.0)
                for (j = k + 1; j < n; ++j) a[i * n + j] -= l * a[k * n + j];
        }
    }
    return 0;
}

void bsm_lu_solve(const double *lu, int n, const int *piv, double *b) {
    int i, j;
    for (i = 0; i < n; ++i) {
        double tmp = b[piv[i]];
        b[piv[i]] = b[i];
        b[i] = tmp;
    }
    for (i = 1; i < n; ++i)
        for (j = 0; j < i; ++j) b[i] -= lu[i * n + j] * b[j];
    for (i = n - 1; i >= 0; --i) {
        for (j = i + 1; j < n; ++j) b[i] -= lu[i * n + j] * b[j];
        b[i] /= lu[i * n + i];
    }
}

static void inputs_at(BsmInstance *m, double t) {
    int i;
    for (i = 0; i < NU; ++i) m->ut[i] = m->saved.u[i] + m->saved.du[i] * (t - m->saved.time);
}

static int all_finite(const double *v, int n) {
    int i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* Right-hand side at (t, y) with interpolated inputs, without logging: the stepper treats a
 * non-finite value as a rejected step. Returns 1 if finite. */
static int rhs(BsmInstance *m, double t, const double *y, double *f) {
    inputs_at(m, t);
    if (bsm_eval_dense(m, FN_ODE, t, y, m->ut, f) != 0) return 0;
    return all_finite(f, NX);
}

/* One Rodas3 step of size h from (t, x). Result in m->x_new; returns the weighted RMS error
 * estimate, or -1 if a stage was not finite or the iteration matrix is singular. */
static double rodas3_step(BsmInstance *m, double t, const double *x, double h) {
    int i, j, s;
    double err = 0.0;
    const double *xx = x;
    inputs_at(m, t);
    if (!rhs(m, t, x, m->f)) return -1.0;
    bsm_eval_dense(m, FN_JAC_X, t, x, m->ut, m->jx);
    bsm_eval_dense(m, FN_JAC_T, t, x, m->ut, m->jt);
    if (NU > 0) bsm_eval_dense(m, FN_JAC_U, t, x, m->ut, m->ju);
    m->s.n_jac++;
    for (i = 0; i < NX; ++i) {
        m->dfdt[i] = m->jt[i];
        for (j = 0; j < NU; ++j) m->dfdt[i] += m->ju[i * NU + j] * m->saved.du[j];
    }
    for (i = 0; i < NX * NX; ++i) m->lu[i] = -m->jx[i];
    for (i = 0; i < NX; ++i) m->lu[i * NX + i] += 1.0 / (h * ros_gamma_diag);
    if (!all_finite(m->lu, NX * NX) || !all_finite(m->dfdt, NX)) return -1.0;
    if (bsm_lu_factor(m->lu, NX, m->piv) != 0) return -1.0;
    for (s = 0; s < ROS_STAGES; ++s) {
        double *ks = m->k[s];
        if (s > 0 && ros_new_f[s]) {
            for (i = 0; i < NX; ++i) {
                m->xs[i] = x[i];
                for (j = 0; j < s; ++j) m->xs[i] += ros_a[s * (s - 1) / 2 + j] * m->k[j][i];
            }
            xx = m->xs;
            if (!rhs(m, t + ros_alpha[s] * h, xx, m->f)) return -1.0;
        }
        for (i = 0; i < NX; ++i) {
            ks[i] = m->f[i] + h * ros_gamma[s] * m->dfdt[i];
            for (j = 0; j < s; ++j) ks[i] += ros_c[s * (s - 1) / 2 + j] / h * m->k[j][i];
        }
        bsm_lu_solve(m->lu, NX, m->piv, ks);
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

static BsmStatus step_failed(BsmInstance *m, const char *reason, double t, double hs) {
    double t0 = m->saved.time;
    m->s = m->saved;
    bsm_invalidate(m);
    bsm_log(m, BSM_DISCARD, "logStatusDiscard",
            "doStep from t = %g s: %s at t = %g s (internal step %g s); state restored to t = %g s",
            t0, reason, t, hs, t0);
    return BSM_DISCARD;
}

/* Integrate from s.time over one communication step h. If the right-hand side is not finite at
 * the start, BSM_ERROR is returned; if the stepper fails later (step size too small, too many
 * steps), the instance is restored to the start of the step and BSM_DISCARD is returned. */
BsmStatus bsm_do_step(BsmInstance *m, double h) {
    double t, t_end, h_prop, err;
    long n = 0;
    int rejected = 0;
    BsmStatus st;
    m->saved = m->s;
    t = m->s.time;
    t_end = t + h;
    st = bsm_derivatives(m, t, m->s.x, m->s.u, m->dx);
    if (st != BSM_OK) return st;
    h_prop = (m->s.h_next > 0.0) ? m->s.h_next : h;
    while (NX > 0 && t_end - t > 1e-13 * fmax(1.0, fabs(t_end))) {
        double remaining = t_end - t;
        double hs = (h_prop >= remaining || remaining - h_prop < 1e-3 * h_prop) ? remaining
                                                                              : h_prop;
        if (++n > ROS_MAX_STEPS) return step_failed(m, "too many internal steps", t, hs);
        err = rodas3_step(m, t, m->s.x, hs);
        if (err >= 0.0 && err <= 1.0) {
            double fac = (err > 0.0) ? 0.9 * pow(err, -1.0 / ROS_ORDER) : 5.0;
            fac = fmin(rejected ? 1.0 : 5.0, fmax(0.2, fac));
            t += hs;
            memcpy(m->s.x, m->x_new, sizeof(double) * NX);
            m->s.n_steps++;
            h_prop = (hs < h_prop) ? fmax(h_prop, hs * fac) : hs * fac;
            rejected = 0;
        } else {
            double fac = (err > 0.0) ? fmax(0.1, 0.9 * pow(err, -1.0 / ROS_ORDER)) : 0.25;
            m->s.n_rejected++;
            h_prop = hs * fmin(fac, 0.5);
            rejected = 1;
            if (h_prop < 1e-14 * fmax(1.0, fabs(t)))
                return step_failed(m,
                                   err < 0.0 ? "the equations are not finite or singular"
                                             : "the step size became too small",
                                   t, h_prop);
        }
    }
    m->s.h_next = h_prop;
    m->s.time = t_end;
    inputs_at(m, t_end);
    memcpy(m->s.u, m->ut, sizeof(m->s.u));
    memset(m->s.du, 0, sizeof(m->s.du));
    bsm_invalidate(m);
    return BSM_OK;
}
