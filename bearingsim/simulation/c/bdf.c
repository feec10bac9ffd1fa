/* Variable-order, variable-step BDF integrator (orders 1-5, numerical differentiation formulas)
 * on compiled model kernels: bearingsim.simulation.compiled_bdf.
 *
 * The algorithm is scipy's BDF (scipy.integrate.BDF: Shampine and Reichelt, "The MATLAB ODE
 * Suite", SIAM J. Sci. Comput. 18(1), 1997): backward differences D rescaled on a step-size
 * change, a simplified Newton iteration on the correction d, the error estimate
 * error_const[k] * d, the order chosen among k-1, k, k+1 after k+1 steps of equal size. Four
 * changes after CVODES (Hindmarsh et al., ACM TOMS 31(3), 2005; Byrne and Hindmarsh, ACM TOMS
 * 1(1), 1975), which keep evaluations and factorisations few: the LU of I - c J is kept while
 * c changes by less than 30 % (the Newton correction is scaled by 2 / (1 + c / c_lu), as
 * CVODES does with its gamma ratio); the Jacobian is re-evaluated on a convergence failure
 * or, at a new factorisation, when it is 50 steps old; the Newton iteration stops when its
 * correction moves the error estimate by 3 % of the tolerance, with the convergence rate
 * carried over from earlier steps (CVODES: 10 %; scipy: 0.3 % at rtol 1e-5, and two
 * iterations at least); and a step size that would grow by less than 1.5x is kept.
 * Constants chosen on the 6304 massive-ball level's start-up and steady running
 * (bench/sundials_compiled.py): 10 % took more steps and error-test failures, 1 % more
 * iterations, for the same or more time.
 *
 * The model functions are CasADi-generated C, called through pointers: ode(t, x, u, p) ->
 * xdot, jac(t, x, u, p, out) -> (d/dt, d/dx, d/du, d/dp) of which d/dx (compressed columns) is
 * used, and the input signal signal(t, q) -> u. The LU of I - c J is bsm_lu.c's sparse one,
 * on the unknowns in a fill-reducing order: the matrix in compressed columns on the pattern
 * of J and the diagonal in that order (bearingsim.simulation.ordering.newton_pattern, passed
 * in), the pivot order and fill pattern found once and reused while the pivots stay
 * acceptable (on the ball-level models a dense LU, LAPACK's, cost more than the right-hand
 * side).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bsm_lu.h"

typedef long long bsm_int;
typedef int (*bsm_fn)(const double **arg, double **res, bsm_int *iw, double *w, int mem);

#define MAX_ORDER 5
#define NEWTON_MAXITER 4
#define NEWTON_COEF 0.03
#define CRATE_DOWN 0.3
#define DIVERGENCE 2.0
#define MIN_FACTOR 0.2
#define MAX_FACTOR 10.0
#define LU_RATIO 0.3
#define KEEP_BELOW 1.5
#define JAC_AGE 50

enum { BSM_OK = 0, BSM_STEP_TOO_SMALL = 1, BSM_SINGULAR = 2, BSM_NOT_FINITE = 3,
       BSM_MODEL_FAILED = 4 };

enum { ST_STEPS, ST_FEVALS, ST_JEVALS, ST_LUS, ST_ERROR_FAILS, ST_NEWTON_FAILS, ST_PIVOTINGS,
       ST_N };

typedef struct {
  int n, n_u, n_p, n_q;
  bsm_fn ode, jac, signal;
  bsm_int jac_nnz;
  const int *jac_slot, *diag_slot; /* nonzero of J / of the diagonal in a_val */
  int *lu_order; /* unknown lu_order[i] is row and column i of the LU */
  double *p, *q, *u;
  double rtol, atol, max_step, t_bound;
  const double **arg;
  double **res;
  bsm_int *iw;
  double *w;
  double *jac_nz, *a_val, *D, *permuted;
  BsmLu factors;
  double *y_predict, *psi, *d, *y, *f, *dy, *scale, *tmp;
  double t, h_abs, c_lu, crate, safety, h_last;
  int order, n_equal_steps, lu_valid, jac_current, jac_age, order_last, adapt_pending;
  double gamma[MAX_ORDER + 2], alpha[MAX_ORDER + 2], error_const[MAX_ORDER + 2];
  long long stats[ST_N];
} bsm_bdf;

static double rms(const double *x, const double *scale, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    double v = x[i] / scale[i];
    s += v * v;
  }
  return sqrt(s / n);
}

static int all_finite(const double *x, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(x[i])) return 0;
  return 1;
}

/* u = signal(t, q) */
static int eval_u(bsm_bdf *b, double t) {
  if (b->n_u == 0) return 0;
  b->arg[0] = &t;
  b->arg[1] = b->q;
  b->res[0] = b->u;
  return b->signal(b->arg, b->res, b->iw, b->w, 0);
}

static int eval_f(bsm_bdf *b, double t, const double *x, double *out) {
  if (eval_u(b, t)) return BSM_MODEL_FAILED;
  b->arg[0] = &t;
  b->arg[1] = x;
  b->arg[2] = b->u;
  b->arg[3] = b->p;
  b->res[0] = out;
  b->stats[ST_FEVALS]++;
  if (b->ode(b->arg, b->res, b->iw, b->w, 0)) return BSM_MODEL_FAILED;
  return BSM_OK;
}

/* jac_nz = d ode / d x at (t, x), the nonzeros of the compressed columns */
static int eval_jac(bsm_bdf *b, double t, const double *x) {
  if (eval_u(b, t)) return BSM_MODEL_FAILED;
  b->arg[0] = &t;
  b->arg[1] = x;
  b->arg[2] = b->u;
  b->arg[3] = b->p;
  b->arg[4] = 0;
  b->res[0] = 0;
  b->res[1] = b->jac_nz;
  b->res[2] = 0;
  b->res[3] = 0;
  b->stats[ST_JEVALS]++;
  if (b->jac(b->arg, b->res, b->iw, b->w, 0)) return BSM_MODEL_FAILED;
  b->jac_current = 1;
  b->jac_age = 0;
  return all_finite(b->jac_nz, (int)b->jac_nnz) ? BSM_OK : BSM_NOT_FINITE;
}

/* The LU factors of I - c J with the unknowns in the LU order. */
static int factorize(bsm_bdf *b, double c) {
  memset(b->a_val, 0, sizeof(double) * (size_t)b->factors.a_start[b->n]);
  for (int i = 0; i < b->n; ++i) b->a_val[b->diag_slot[i]] = 1.0;
  for (bsm_int k = 0; k < b->jac_nnz; ++k) b->a_val[b->jac_slot[k]] -= c * b->jac_nz[k];
  int singular = bsm_lu_factor(&b->factors, b->a_val);
  b->stats[ST_LUS]++;
  b->stats[ST_PIVOTINGS] = b->factors.pivotings;
  b->c_lu = c;
  b->crate = 1.0;
  b->lu_valid = !singular;
  return singular ? BSM_SINGULAR : BSM_OK;
}

/* rhs = (I - c J)^-1 rhs */
static void solve(bsm_bdf *b, double *rhs) {
  bsm_lu_solve(&b->factors, b->lu_order, b->permuted, rhs);
}

/* D[0..order] = (R U)^T D[0..order]: the differences for the step size h * factor. */
static void change_D(bsm_bdf *b, double factor) {
  int k = b->order, n = b->n;
  double R[MAX_ORDER + 1][MAX_ORDER + 1], U[MAX_ORDER + 1][MAX_ORDER + 1];
  double RU[MAX_ORDER + 1][MAX_ORDER + 1];
  for (int pass = 0; pass < 2; ++pass) {
    double (*M)[MAX_ORDER + 1] = pass == 0 ? R : U;
    double f = pass == 0 ? factor : 1.0;
    for (int j = 0; j <= k; ++j) M[0][j] = 1.0;
    for (int i = 1; i <= k; ++i) {
      M[i][0] = 0.0;
      for (int j = 1; j <= k; ++j) M[i][j] = M[i - 1][j] * (i - 1 - f * j) / i;
    }
  }
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j) {
      double s = 0.0;
      for (int m = 0; m <= k; ++m) s += R[i][m] * U[m][j];
      RU[i][j] = s;
    }
  for (int col = 0; col < n; ++col) {
    double old[MAX_ORDER + 1];
    for (int i = 0; i <= k; ++i) old[i] = b->D[(size_t)i * n + col];
    for (int j = 0; j <= k; ++j) {
      double s = 0.0;
      for (int i = 0; i <= k; ++i) s += RU[i][j] * old[i];
      b->D[(size_t)j * n + col] = s;
    }
  }
}

void bsm_bdf_free(bsm_bdf *b) {
  if (!b) return;
  free(b->p); free(b->q); free(b->u);
  free(b->arg); free(b->res); free(b->iw); free(b->w);
  free(b->jac_nz); free(b->a_val); free(b->D); free(b->permuted);
  free(b->lu_order);
  BsmLu *c = &b->factors;
  free(c->row_of); free(c->step_of); free(c->l_start); free(c->l_index); free(c->l_val);
  free(c->u_start); free(c->u_index); free(c->u_pos); free(c->u_val); free(c->ur_start);
  free(c->ur_index); free(c->ur_val); free(c->inv_diag); free(c->x); free(c->work);
  free(b->y_predict); free(b->psi); free(b->d); free(b->y); free(b->f); free(b->dy);
  free(b->scale); free(b->tmp);
  free(b);
}

/* A solver at (t0, x0) integrating towards t_bound; NULL if out of memory. sz_*: the largest
 * work sizes of the three functions; order: the unknowns in the order of the LU (a
 * permutation of 0 .. n-1); a_start, a_index: the pattern of I - c J in that order
 * (compressed columns); jac_slot, diag_slot: where J's nnz nonzeros and the diagonal are in
 * it (the pattern and slots are kept by the caller for the solver's life). */
bsm_bdf *bsm_bdf_new(int n, int n_u, int n_p, int n_q, bsm_fn ode, bsm_fn jac, bsm_fn signal,
                     bsm_int nnz, const int *order, const int *a_start, const int *a_index,
                     const int *jac_slot, const int *diag_slot, const double *p, const double *q,
                     bsm_int sz_arg, bsm_int sz_res, bsm_int sz_iw, bsm_int sz_w,
                     double rtol, double atol, double max_step, double t0, double t_bound,
                     const double *x0) {
  bsm_bdf *b = calloc(1, sizeof(bsm_bdf));
  if (!b) return 0;
  b->n = n; b->n_u = n_u; b->n_p = n_p; b->n_q = n_q;
  b->ode = ode; b->jac = jac; b->signal = signal;
  b->jac_nnz = nnz;
  b->jac_slot = jac_slot; b->diag_slot = diag_slot;
  b->rtol = rtol; b->atol = atol; b->max_step = max_step; b->t_bound = t_bound;
  size_t nn = (size_t)n * n;
  b->p = malloc(sizeof(double) * (n_p + 1));
  b->q = malloc(sizeof(double) * (n_q + 1));
  b->u = calloc(n_u + 1, sizeof(double));
  b->arg = calloc(sz_arg > 5 ? sz_arg : 5, sizeof(double *));
  b->res = calloc(sz_res > 4 ? sz_res : 4, sizeof(double *));
  b->iw = calloc(sz_iw + 1, sizeof(bsm_int));
  b->w = calloc(sz_w + 1, sizeof(double));
  b->jac_nz = calloc(nnz + 1, sizeof(double));
  b->a_val = calloc(a_start[n] + 1, sizeof(double));
  b->D = calloc((size_t)(MAX_ORDER + 3) * n, sizeof(double));
  b->lu_order = calloc(n, sizeof(int));
  BsmLu *c = &b->factors;
  size_t half = nn / 2 + 1; /* strictly lower or upper triangle */
  c->n = n; c->keep_order = 1; c->a_start = a_start; c->a_index = a_index;
  c->row_of = calloc(n + 1, sizeof(int));
  c->step_of = calloc(n + 1, sizeof(int));
  c->work = calloc(3 * (size_t)n + 1, sizeof(int));
  c->l_start = calloc(n + 1, sizeof(int));
  c->l_index = calloc(half, sizeof(int));
  c->l_val = calloc(half, sizeof(double));
  c->u_start = calloc(n + 1, sizeof(int));
  c->u_index = calloc(half, sizeof(int));
  c->u_pos = calloc(half, sizeof(int));
  c->u_val = calloc(half, sizeof(double));
  c->ur_start = calloc(n + 1, sizeof(int));
  c->ur_index = calloc(half, sizeof(int));
  c->ur_val = calloc(half, sizeof(double));
  c->inv_diag = calloc(n, sizeof(double));
  double **vectors[] = {&b->y_predict, &b->psi, &b->d, &b->y, &b->f, &b->dy, &b->scale,
                        &b->tmp, &b->permuted, &c->x};
  int ok = b->p && b->q && b->u && b->arg && b->res && b->iw && b->w && b->jac_nz &&
           b->a_val && b->D && b->lu_order && c->row_of && c->step_of && c->work &&
           c->l_start && c->l_index && c->l_val && c->u_start && c->u_index && c->u_pos &&
           c->u_val && c->ur_start && c->ur_index && c->ur_val && c->inv_diag;
  for (size_t k = 0; k < sizeof(vectors) / sizeof(vectors[0]); ++k) {
    *vectors[k] = calloc(n, sizeof(double));
    ok = ok && *vectors[k];
  }
  if (!ok) {
    bsm_bdf_free(b);
    return 0;
  }
  memcpy(b->p, p, sizeof(double) * n_p);
  memcpy(b->q, q, sizeof(double) * n_q);
  memcpy(b->lu_order, order, sizeof(int) * n);
  /* NDF coefficients (scipy.integrate.BDF) */
  const double kappa[MAX_ORDER + 2] = {0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0, 0.0};
  b->gamma[0] = 0.0;
  for (int k = 1; k <= MAX_ORDER + 1; ++k) b->gamma[k] = b->gamma[k - 1] + 1.0 / k;
  for (int k = 0; k <= MAX_ORDER + 1; ++k) {
    b->alpha[k] = (1.0 - kappa[k]) * b->gamma[k];
    b->error_const[k] = kappa[k] * b->gamma[k] + 1.0 / (k + 1);
  }
  b->t = t0;
  b->order = 1;
  memcpy(b->y, x0, sizeof(double) * n);
  return b;
}

/* First step size (Hairer, Norsett and Wanner, Solving ODE I, sec. II.4; as scipy's
 * select_initial_step, order 1) and the start of D; status code. */
int bsm_bdf_start(bsm_bdf *b) {
  int n = b->n, status;
  double t0 = b->t, interval = b->t_bound - t0;
  if ((status = eval_f(b, t0, b->y, b->f))) return status;
  if (!all_finite(b->f, n)) return BSM_NOT_FINITE;
  for (int i = 0; i < n; ++i) b->scale[i] = b->atol + fabs(b->y[i]) * b->rtol;
  double d0 = rms(b->y, b->scale, n), d1 = rms(b->f, b->scale, n);
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = fmin(h0, interval);
  for (int i = 0; i < n; ++i) b->tmp[i] = b->y[i] + h0 * b->f[i];
  if ((status = eval_f(b, t0 + h0, b->tmp, b->dy))) return status;
  for (int i = 0; i < n; ++i) b->tmp[i] = b->dy[i] - b->f[i];
  double d2 = all_finite(b->tmp, n) ? rms(b->tmp, b->scale, n) / h0 : INFINITY;
  double h1 = (d1 <= 1e-15 && d2 <= 1e-15) ? fmax(1e-6, h0 * 1e-3)
                                           : pow(0.01 / fmax(d1, d2), 0.5);
  b->h_abs = fmin(fmin(100.0 * h0, h1), fmin(interval, b->max_step));
  memset(b->D, 0, sizeof(double) * (size_t)(MAX_ORDER + 3) * n);
  for (int i = 0; i < n; ++i) {
    b->D[i] = b->y[i];
    b->D[n + i] = b->f[i] * b->h_abs;
  }
  b->n_equal_steps = 0;
  b->lu_valid = 0;
  return eval_jac(b, t0, b->y);
}

/* The Newton iteration on the correction d at t_new; 1 if converged, iterations in *n_iter.
 * Convergence as in CVODES: the correction's norm times the rate estimate (kept across
 * steps, reset by a new factorisation) below NEWTON_COEF / error_const[order], i.e. its
 * effect on the error estimate NEWTON_COEF of the tolerance; divergence when a correction
 * grows by 2x. */
static int newton(bsm_bdf *b, double t_new, double c, int order, int *n_iter, int *status) {
  int n = b->n;
  double del_old = 0.0, ratio = 2.0 / (1.0 + c / b->c_lu);
  double tol = NEWTON_COEF / b->error_const[order];
  memcpy(b->y, b->y_predict, sizeof(double) * n);
  memset(b->d, 0, sizeof(double) * n);
  *status = BSM_OK;
  for (int k = 0; k < NEWTON_MAXITER; ++k) {
    *n_iter = k + 1;
    if ((*status = eval_f(b, t_new, b->y, b->f))) return 0;
    if (!all_finite(b->f, n)) return 0;
    for (int i = 0; i < n; ++i) b->dy[i] = c * b->f[i] - b->psi[i] - b->d[i];
    solve(b, b->dy);
    if (ratio != 1.0)
      for (int i = 0; i < n; ++i) b->dy[i] *= ratio;
    double del = rms(b->dy, b->scale, n);
    for (int i = 0; i < n; ++i) {
      b->y[i] += b->dy[i];
      b->d[i] += b->dy[i];
    }
    if (k > 0) b->crate = fmax(CRATE_DOWN * b->crate, del / del_old);
    if (del * fmin(1.0, b->crate) <= tol) return 1;
    if (k > 0 && del > DIVERGENCE * del_old) return 0;
    del_old = del;
  }
  return 0;
}

static void adapt(bsm_bdf *b);

/* One step. D[0..order_last] are then the backward differences at t with spacing h_last
 * (the dense output of the step) until the next step adapts order and step size. */
static int step(bsm_bdf *b) {
  int n = b->n, status;
  if (b->adapt_pending) adapt(b);
  b->adapt_pending = 0;
  double t = b->t;
  double min_step = 10.0 * fabs(nextafter(t, INFINITY) - t);
  if (b->h_abs > b->max_step) {
    change_D(b, b->max_step / b->h_abs);
    b->h_abs = b->max_step;
    b->n_equal_steps = 0;
  } else if (b->h_abs < min_step) {
    change_D(b, min_step / b->h_abs);
    b->h_abs = min_step;
    b->n_equal_steps = 0;
  }
  double h_abs = b->h_abs, t_new, error_norm;
  int order = b->order;
  for (;;) {
    if (h_abs < min_step) return BSM_STEP_TOO_SMALL;
    t_new = t + h_abs;
    if (t_new > b->t_bound) {
      t_new = b->t_bound;
      change_D(b, (t_new - t) / h_abs);
      b->n_equal_steps = 0;
    }
    h_abs = t_new - t;
    for (int i = 0; i < n; ++i) {
      double s = 0.0, ps = 0.0;
      for (int j = 0; j <= order; ++j) s += b->D[(size_t)j * n + i];
      for (int j = 1; j <= order; ++j) ps += b->gamma[j] * b->D[(size_t)j * n + i];
      b->y_predict[i] = s;
      b->psi[i] = ps / b->alpha[order];
      b->scale[i] = b->atol + b->rtol * fabs(s);
    }
    double c = h_abs / b->alpha[order];
    int converged = 0, n_iter = 0;
    for (;;) {
      if (!b->lu_valid || fabs(c / b->c_lu - 1.0) > LU_RATIO) {
        if (!b->jac_current && b->jac_age >= JAC_AGE &&
            (status = eval_jac(b, t_new, b->y_predict)))
          return status;
        if ((status = factorize(b, c))) return status;
      }
      converged = newton(b, t_new, c, order, &n_iter, &status);
      if (status) return status;
      if (converged || b->jac_current) break;
      if ((status = eval_jac(b, t_new, b->y_predict))) return status;
      b->lu_valid = 0;
    }
    if (!converged) {
      b->stats[ST_NEWTON_FAILS]++;
      h_abs *= 0.5;
      change_D(b, 0.5);
      b->n_equal_steps = 0;
      b->lu_valid = 0;
      continue;
    }
    b->safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter);
    for (int i = 0; i < n; ++i) {
      b->scale[i] = b->atol + b->rtol * fabs(b->y[i]);
      b->tmp[i] = b->error_const[order] * b->d[i];
    }
    error_norm = rms(b->tmp, b->scale, n);
    if (!(error_norm <= 1.0)) {  /* also NaN */
      b->stats[ST_ERROR_FAILS]++;
      double factor = isfinite(error_norm)
                          ? fmax(MIN_FACTOR, b->safety * pow(error_norm, -1.0 / (order + 1)))
                          : MIN_FACTOR;
      h_abs *= factor;
      change_D(b, factor);
      b->n_equal_steps = 0;
      continue;
    }
    break;
  }
  b->stats[ST_STEPS]++;
  b->n_equal_steps++;
  b->jac_current = 0;
  b->jac_age++;
  b->t = t_new;
  b->h_abs = h_abs;
  /* D^{j+1} y_n = D^j y_n - D^j y_{n-1} */
  for (int i = 0; i < n; ++i) {
    b->D[(size_t)(order + 2) * n + i] = b->d[i] - b->D[(size_t)(order + 1) * n + i];
    b->D[(size_t)(order + 1) * n + i] = b->d[i];
  }
  for (int j = order; j >= 0; --j)
    for (int i = 0; i < n; ++i) b->D[(size_t)j * n + i] += b->D[(size_t)(j + 1) * n + i];
  b->h_last = h_abs;
  b->order_last = order;
  b->adapt_pending = 1;
  return BSM_OK;
}

/* Order and step size for the next step, from the last one's error estimates. */
static void adapt(bsm_bdf *b) {
  int n = b->n, order = b->order;
  if (b->n_equal_steps < order + 1) return;
  double norms[3];
  for (int i = 0; i < n; ++i) b->tmp[i] = b->error_const[order] * b->d[i];
  norms[1] = rms(b->tmp, b->scale, n);
  if (order > 1) {
    for (int i = 0; i < n; ++i) b->tmp[i] = b->error_const[order - 1] * b->D[(size_t)order * n + i];
    norms[0] = rms(b->tmp, b->scale, n);
  } else {
    norms[0] = INFINITY;
  }
  if (order < MAX_ORDER) {
    for (int i = 0; i < n; ++i)
      b->tmp[i] = b->error_const[order + 1] * b->D[(size_t)(order + 2) * n + i];
    norms[2] = rms(b->tmp, b->scale, n);
  } else {
    norms[2] = INFINITY;
  }
  int best = 0;
  double factors[3];
  for (int k = 0; k < 3; ++k) {
    factors[k] = norms[k] == 0.0 ? INFINITY : pow(norms[k], -1.0 / (order + k));
    if (factors[k] > factors[best]) best = k;
  }
  double factor = fmin(MAX_FACTOR, b->safety * factors[best]);
  if (factor >= 1.0 && factor < KEEP_BELOW) return;  /* not worth a new LU (CVODES) */
  b->order = order + best - 1;
  b->h_abs *= factor;
  change_D(b, factor);
  b->n_equal_steps = 0;
}

/* The state at t in [t - h_last, t] (the last step's interpolating polynomial: Newton's
 * backward formula through its last order + 1 points), or at the start time. */
static void interpolate(const bsm_bdf *b, double t, double *out) {
  int n = b->n;
  memcpy(out, b->D, sizeof(double) * n);
  if (b->stats[ST_STEPS] == 0 || t == b->t) return;
  double p = 1.0;
  for (int j = 0; j < b->order_last; ++j) {
    p *= (t - (b->t - b->h_last * j)) / (b->h_last * (j + 1));
    for (int i = 0; i < n; ++i) out[i] += p * b->D[(size_t)(j + 1) * n + i];
  }
}

/* Integrate until every output time t_out[0..n_out-1] (increasing, not before the start of
 * the last step, at most t_bound) is reached, or for at most max_steps steps; x_out[k*n + i] =
 * state i at t_out[k]. Returns a status code; *n_done: the outputs written (fewer than n_out
 * when the steps ran out: call again with the rest). */
int bsm_bdf_advance(bsm_bdf *b, int n_out, const double *t_out, double *x_out, int max_steps,
                    int *n_done) {
  int n = b->n, k = 0, steps = 0, status;
  *n_done = 0;
  for (;;) {
    while (k < n_out && t_out[k] <= b->t) {
      interpolate(b, t_out[k], x_out + (size_t)k * n);
      *n_done = ++k;
    }
    if (k == n_out || steps++ == max_steps) return BSM_OK;
    if ((status = step(b))) return status;
  }
}

double bsm_bdf_time(const bsm_bdf *b) { return b->t; }
void bsm_bdf_state(const bsm_bdf *b, double *x) { memcpy(x, b->D, sizeof(double) * b->n); }
void bsm_bdf_stats(const bsm_bdf *b, long long *out) {
  memcpy(out, b->stats, sizeof(long long) * ST_N);
}
