/* bearingsim FMU runtime: evaluation of the generated model functions, checks and logging. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "bsm_model.h"

void bsm_log(BsmInstance *m, BsmStatus status, const char *category, const char *fmt, ...) {
    char message[1024];
    va_list ap;
    if (m->logger == NULL || (status == BSM_OK && !m->debug_logging)) return;
    va_start(ap, fmt);
    vsnprintf(message, sizeof(message), fmt, ap);
    va_end(ap);
    m->logger(m->host, status, category, message);
}

const char *bsm_num(char buf[32], double v) {
    if (isnan(v)) return "NaN";
    snprintf(buf, 32, "%g", v);
    return buf;
}

void bsm_invalidate(BsmInstance *m) {
    m->dx_valid = 0;
    m->y_valid = 0;
}

void bsm_reset(BsmInstance *m) {
    memset(&m->s, 0, sizeof(m->s));
    memcpy(m->s.x, bsm_x_start, sizeof(m->s.x));
    memcpy(m->s.u, bsm_u_start, sizeof(m->s.u));
    memcpy(m->s.p, bsm_p_start, sizeof(m->s.p));
    m->s.rtol = 1e-6;
    m->w_valid = 0;
    memset(m->u_warned, 0, sizeof(m->u_warned));
    memset(m->u_clamped, 0, sizeof(m->u_clamped));
    bsm_invalidate(m);
}

/* Evaluate function `fn` at (t, x, u, p) into a dense row-major matrix.
 * Returns 0 on success, nonzero if the generated code reports a failure. */
int bsm_eval_dense(BsmInstance *m, int fn, double t, const double *x, const double *u,
                   double *out) {
    const BsmFunction *f = &bsm_functions[fn];
    const bsm_int *sp = f->sparsity_out(0);
    bsm_int nrow = sp[0], ncol = sp[1];
    const bsm_int *colind = sp + 2, *row = sp + 3 + ncol;
    bsm_int c, k;
    int mem, flag;
    m->arg[0] = &t;
    m->arg[1] = x;
    m->arg[2] = u;
    m->arg[3] = m->s.p;
    m->res[0] = m->nz;
    mem = f->checkout();
    flag = f->eval(m->arg, m->res, m->iw, m->w, mem);
    f->release(mem);
    if (colind[0] == 1) { /* CasADi's compact form of a dense matrix (column major) */
        for (c = 0; c < ncol; ++c)
            for (k = 0; k < nrow; ++k) out[k * ncol + c] = m->nz[c * nrow + k];
        return flag;
    }
    memset(out, 0, sizeof(double) * (size_t)(nrow * ncol > 0 ? nrow * ncol : 0));
    for (c = 0; c < ncol; ++c)
        for (k = colind[c]; k < colind[c + 1]; ++k) out[row[k] * ncol + c] = m->nz[k];
    return flag;
}

static int first_non_finite(const double *v, int n) {
    int i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) return i;
    return -1;
}

BsmStatus bsm_derivatives(BsmInstance *m, double t, const double *x, const double *u,
                          double *dx) {
    int bad;
    if (NX == 0) return BSM_OK;
    if (bsm_eval_dense(m, FN_ODE, t, x, u, dx) != 0) {
        bsm_log(m, BSM_ERROR, "logStatusError",
                "the model equations could not be evaluated at t = %g s", t);
        return BSM_ERROR;
    }
    bad = first_non_finite(dx, NX);
    if (bad >= 0) {
        char b1[32], b2[32];
        bsm_log(m, BSM_ERROR, "logStatusError", "der(%s) is not finite (%s) at t = %g s; %s = %s",
                bsm_x_names[bad], bsm_num(b1, dx[bad]), t, bsm_x_names[bad],
                bsm_num(b2, x[bad]));
        return BSM_ERROR;
    }
    return BSM_OK;
}

BsmStatus bsm_current_derivatives(BsmInstance *m) {
    BsmStatus st;
    if (m->dx_valid) return BSM_OK;
    st = bsm_derivatives(m, m->s.time, m->s.x, m->s.u, m->dx);
    m->dx_valid = (st == BSM_OK);
    return st;
}

BsmStatus bsm_current_outputs(BsmInstance *m) {
    int bad;
    if (m->y_valid || NY == 0) return BSM_OK;
    if (bsm_eval_dense(m, FN_OUTPUT, m->s.time, m->s.x, m->s.u, m->y) != 0) {
        bsm_log(m, BSM_ERROR, "logStatusError",
                "the outputs could not be evaluated at t = %g s", m->s.time);
        return BSM_ERROR;
    }
    bad = first_non_finite(m->y, NY);
    if (bad >= 0) {
        char b[32];
        bsm_log(m, BSM_ERROR, "logStatusError", "output %s is not finite (%s) at t = %g s",
                bsm_y_names[bad], bsm_num(b, m->y[bad]), m->s.time);
        return BSM_ERROR;
    }
    m->y_valid = 1;
    return BSM_OK;
}

/* Whether v is finite and lies in the range (low, high) with the bound flags b (BSM_HAS_LOW
 * ...); if not, log why ("<kind> <name> = v [unit] is outside its valid range ...; value not
 * set"). */
static BsmStatus check_range(BsmInstance *m, const char *kind, const char *name,
                             const char *unit, double v, double low, double high,
                             unsigned char b) {
    int low_ok = !(b & BSM_HAS_LOW) || ((b & BSM_LOW_INCLUSIVE) ? v >= low : v > low);
    int high_ok = !(b & BSM_HAS_HIGH) || ((b & BSM_HIGH_INCLUSIVE) ? v <= high : v < high);
    char range[128], num[32];
    if (isfinite(v) && low_ok && high_ok) return BSM_OK;
    if (!isfinite(v)) {
        bsm_log(m, BSM_ERROR, "logStatusError", "%s %s must be finite, got %s; value not set",
                kind, name, bsm_num(num, v));
        return BSM_ERROR;
    }
    snprintf(range, sizeof(range), "%s%.17g, %.17g%s", (b & BSM_LOW_INCLUSIVE) ? "[" : "(",
             (b & BSM_HAS_LOW) ? low : -INFINITY, (b & BSM_HAS_HIGH) ? high : INFINITY,
             (b & BSM_HIGH_INCLUSIVE) ? "]" : ")");
    bsm_log(m, BSM_ERROR, "logStatusError",
            "%s %s = %s [%s] is outside its valid range %s; value not set", kind, name,
            bsm_num(num, v), unit, range);
    return BSM_ERROR;
}

BsmStatus bsm_check_parameter(BsmInstance *m, int k, double v) {
    return check_range(m, "parameter", bsm_p_names[k], bsm_p_units[k], v, bsm_p_low[k],
                       bsm_p_high[k], bsm_p_bounds[k]);
}

BsmStatus bsm_check_input(BsmInstance *m, int k, double v) {
    char num[32], limit[32];
    if (check_range(m, "input", bsm_u_names[k], bsm_u_units[k], v, bsm_u_low[k],
                    bsm_u_high[k], bsm_u_bounds[k]) != BSM_OK)
        return BSM_ERROR;
    if (!(fabs(v) > bsm_u_warn_above[k]) || m->u_warned[k]) return BSM_OK;
    m->u_warned[k] = 1;
    bsm_log(m, BSM_WARNING, "logStatusWarning",
            "input %s = %s [%s] is above %s, %s [%s]: %s (warned once per instance)",
            bsm_u_names[k], bsm_num(num, v), bsm_u_units[k], bsm_u_limit_names[k],
            bsm_num(limit, bsm_u_warn_above[k]), bsm_u_units[k], bsm_u_limit_effects[k]);
    return BSM_WARNING;
}

/* ------------------------------------------------------------------ values, derivatives */
BsmStatus bsm_get_real(BsmInstance *m, unsigned int r, double *value) {
    BsmStatus st;
    if (r < VR_DX) {
        *value = m->s.x[r - VR_X];
    } else if (r < VR_U) {
        st = bsm_current_derivatives(m);
        if (st != BSM_OK) return st;
        *value = m->dx[r - VR_DX];
    } else if (r < VR_Y) {
        *value = m->s.u[r - VR_U];
    } else if (r < VR_P) {
        st = bsm_current_outputs(m);
        if (st != BSM_OK) return st;
        *value = m->y[r - VR_Y];
    } else {
        *value = m->s.p[r - VR_P];
    }
    return BSM_OK;
}

BsmCall bsm_set_real(BsmInstance *m, unsigned int r, double v, int states_settable,
                     int parameters_settable, const char *function) {
    if (r < VR_DX) {
        if (!states_settable) {
            bsm_log(m, BSM_ERROR, "logStatusError",
                    "%s of a state must not be called in this state", function);
            return BSM_CALL_REFUSED;
        }
        if (!isfinite(v)) {
            char num[32];
            bsm_log(m, BSM_ERROR, "logStatusError", "start value of %s must be finite, got %s",
                    bsm_x_names[r], bsm_num(num, v));
            return BSM_CALL_FAILED;
        }
        m->s.x[r - VR_X] = v;
        m->s.jac_set = 0;
    } else if (r >= VR_U && r < VR_Y) {
        BsmStatus st = bsm_check_input(m, (int)(r - VR_U), v);
        if (st == BSM_ERROR) return BSM_CALL_FAILED;
        m->s.u[r - VR_U] = v;
        if (st == BSM_WARNING) return BSM_CALL_WARNED;
    } else if (r >= VR_P && r < VR_END) {
        if (!parameters_settable) {
            bsm_log(m, BSM_ERROR, "logStatusError",
                    "%s of a parameter must not be called in this state", function);
            return BSM_CALL_REFUSED;
        }
        if (bsm_check_parameter(m, (int)(r - VR_P), v) != BSM_OK) return BSM_CALL_FAILED;
        m->s.p[r - VR_P] = v;
        m->s.jac_set = 0;
    } else {
        bsm_log(m, BSM_ERROR, "logStatusError",
                "%s: value reference %u is not a state start value, input or parameter",
                function, r);
        return BSM_CALL_REFUSED;
    }
    return BSM_CALL_DONE;
}

BsmCall bsm_directional_derivative(BsmInstance *m, const unsigned int *unknowns, size_t n_unknown,
                                   const unsigned int *knowns, size_t n_known,
                                   const double *seed, double *out, const char *function) {
    size_t i, j;
    for (j = 0; j < n_known; ++j)
        if (knowns[j] >= VR_DX && !(knowns[j] >= VR_U && knowns[j] < VR_Y)) {
            bsm_log(m, BSM_ERROR, "logStatusError", "%s: known %u must be a state or an input",
                    function, knowns[j]);
            return BSM_CALL_REFUSED;
        }
    bsm_eval_dense(m, FN_JAC_X, m->s.time, m->s.x, m->s.u, m->jx);
    if (NU > 0) bsm_eval_dense(m, FN_JAC_U, m->s.time, m->s.x, m->s.u, m->ju);
    if (NY > 0) {
        bsm_eval_dense(m, FN_OUT_JAC_X, m->s.time, m->s.x, m->s.u, m->yx);
        if (NU > 0) bsm_eval_dense(m, FN_OUT_JAC_U, m->s.time, m->s.x, m->s.u, m->yu);
    }
    for (i = 0; i < n_unknown; ++i) {
        unsigned int r = unknowns[i];
        double sum = 0.0;
        for (j = 0; j < n_known; ++j) {
            unsigned int q = knowns[j];
            int is_state = q < VR_DX;
            int col = is_state ? (int)(q - VR_X) : (int)(q - VR_U);
            double d;
            if (r < VR_DX) d = (is_state && q == r) ? 1.0 : 0.0;
            else if (r < VR_U) d = is_state ? m->jx[(r - VR_DX) * NX + col]
                                            : m->ju[(r - VR_DX) * NU + col];
            else if (r >= VR_Y && r < VR_P) d = is_state ? m->yx[(r - VR_Y) * NX + col]
                                                         : m->yu[(r - VR_Y) * NU + col];
            else if (r >= VR_U && r < VR_Y) d = (!is_state && q == r) ? 1.0 : 0.0;
            else {
                bsm_log(m, BSM_ERROR, "logStatusError",
                        "%s (unknown): value reference %u is not valid", function, r);
                return BSM_CALL_REFUSED;
            }
            sum += d * seed[j];
        }
        if (!isfinite(sum)) {
            bsm_log(m, BSM_ERROR, "logStatusError", "%s: derivative of %u is not finite at "
                    "t = %g s", function, r, m->s.time);
            return BSM_CALL_FAILED;
        }
        out[i] = sum;
    }
    return BSM_CALL_DONE;
}

BsmCall bsm_output_derivatives(BsmInstance *m, const unsigned int *vr, size_t n,
                               const int *order, double *values, const char *function) {
    size_t i;
    int j;
    if (n == 0) return BSM_CALL_DONE;
    for (i = 0; i < n; ++i)
        if (order[i] != 1 || !(vr[i] < VR_DX || (vr[i] >= VR_Y && vr[i] < VR_P))) {
            bsm_log(m, BSM_ERROR, "logStatusError", "%s: only first derivatives of outputs "
                    "(got value reference %u, order %d)", function, vr[i], order[i]);
            return BSM_CALL_REFUSED;
        }
    if (bsm_current_derivatives(m) != BSM_OK) return BSM_CALL_FAILED;
    if (NY > 0) {
        bsm_eval_dense(m, FN_OUT_JAC_X, m->s.time, m->s.x, m->s.u, m->yx);
        if (NU > 0) bsm_eval_dense(m, FN_OUT_JAC_U, m->s.time, m->s.x, m->s.u, m->yu);
        bsm_eval_dense(m, FN_OUT_JAC_T, m->s.time, m->s.x, m->s.u, m->yt);
    }
    for (i = 0; i < n; ++i) {
        double sum;
        if (vr[i] < VR_DX) {
            sum = m->dx[vr[i] - VR_X];
        } else {
            int k = (int)(vr[i] - VR_Y);
            sum = m->yt[k];
            for (j = 0; j < NX; ++j) sum += m->yx[k * NX + j] * m->dx[j];
            for (j = 0; j < NU; ++j) sum += m->yu[k * NU + j] * m->s.du[j];
        }
        if (!isfinite(sum)) {
            bsm_log(m, BSM_ERROR, "logStatusError", "%s: derivative of %u is not finite at "
                    "t = %g s", function, vr[i], m->s.time);
            return BSM_CALL_FAILED;
        }
        values[i] = sum;
    }
    return BSM_CALL_DONE;
}

/* ------------------------------------------------------------------ FMU state serialization */
typedef struct {
    unsigned int magic;
    unsigned int size;
    BsmState s;
} BsmSerialState;

size_t bsm_serialized_size(void) { return sizeof(BsmSerialState); }

BsmStatus bsm_serialize(BsmInstance *m, const BsmState *s, unsigned int magic, void *buffer,
                        size_t size, const char *function) {
    BsmSerialState out;
    if (s == NULL || size < sizeof(BsmSerialState)) {
        bsm_log(m, BSM_ERROR, "logStatusError", "%s: no state or buffer smaller than %u bytes",
                function, (unsigned)sizeof(BsmSerialState));
        return BSM_ERROR;
    }
    memset(&out, 0, sizeof(out));
    out.magic = magic;
    out.size = (unsigned int)sizeof(BsmSerialState);
    out.s = *s;
    memcpy(buffer, &out, sizeof(out));
    return BSM_OK;
}

BsmStatus bsm_deserialize(BsmInstance *m, unsigned int magic, const void *buffer, size_t size,
                          BsmState *s, const char *function) {
    BsmSerialState in;
    if (size != sizeof(BsmSerialState)) {
        bsm_log(m, BSM_ERROR, "logStatusError", "%s: expected %u bytes, got %u", function,
                (unsigned)sizeof(BsmSerialState), (unsigned)size);
        return BSM_ERROR;
    }
    memcpy(&in, buffer, sizeof(in));
    if (in.magic != magic || in.size != sizeof(BsmSerialState)) {
        bsm_log(m, BSM_ERROR, "logStatusError", "%s: the data is not a state of this FMU",
                function);
        return BSM_ERROR;
    }
    *s = in.s;
    return BSM_OK;
}
