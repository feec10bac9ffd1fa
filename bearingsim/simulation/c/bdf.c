/* The compiled BDF integrator (bearingsim.simulation.compiled_bdf): the BDF stepping core
 * (bsm_bdf.c, shared with the FMU's co-simulation stepper) on compiled model kernels, with
 * output times interpolated from the steps.
 *
 * The model functions are CasADi-generated C, called through pointers: ode(t, x, u, p) ->
 * xdot, jac(t, x, u, p, out) -> (d/dt, d/dx, d/du, d/dp) of which d/dx (compressed columns) is
 * used, the input signal signal(t, q) -> u, and observe(t, x, u, p) -> the observed variables
 * at the output times (bsm_bdf_observe). The LU of I - c J is bsm_lu.c's sparse one,
 * on the unknowns in a fill-reducing order: the matrix in compressed columns on the pattern
 * of J and the diagonal in that order (bearingsim.simulation.ordering.newton_pattern, passed
 * in), the pivot order and fill pattern found once and reused while the pivots stay
 * acceptable (on the ball-level models a dense LU, LAPACK's, cost more than the right-hand
 * side).
 *
 * Built with -DBSM_BDF_PROFILE (bench/compiled_bdf_core.py), each call of the four model
 * operations is timed (monotonic clock) and bsm_bdf_start/bsm_bdf_advance too (CPU time of the
 * thread), and bsm_bdf_profile returns the seconds: the run less the operations is the
 * stepping core's own work.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bsm_bdf.h"
#include "bsm_lu.h"

typedef long long bsm_int;
typedef int (*bsm_fn)(const double **arg, double **res, bsm_int *iw, double *w, int mem);

typedef struct {
  BsmBdf core;
  BsmBdfHistory history;
  int n, n_u, n_p, n_q;
  bsm_fn ode, jac, signal, observe;
  bsm_int jac_nnz;
  const int *diag_slot; /* the diagonal's entries in a_val */
  int *a_jac; /* the nonzero of J in each entry of a_val (jac_nnz: none, jac_nz[jac_nnz] = 0) */
  int *lu_order; /* unknown lu_order[i] is row and column i of the LU */
  double *p, *q, *u;
  double t_bound;
  const double **arg;
  double **res;
  bsm_int *iw;
  double *w;
  double *jac_nz, *a_val, *permuted, *x0;
  BsmLu factors;
#ifdef BSM_BDF_PROFILE
  double profile[13]; /* the operations' and the run's time (BSM_BDF_PROFILE, below) */
#endif
} bsm_bdf;

static int all_finite(const double *x, bsm_int n) {
  for (bsm_int i = 0; i < n; ++i)
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

/* arg = (t, x, u = signal(t, q), p), the inputs of ode and jac; nonzero if the signal failed */
static int model_args(bsm_bdf *b, const double *t, const double *x) {
  if (eval_u(b, *t)) return 1;
  b->arg[0] = t;
  b->arg[1] = x;
  b->arg[2] = b->u;
  b->arg[3] = b->p;
  return 0;
}

static int eval_f(void *model, double t, const double *x, double *out) {
  bsm_bdf *b = model;
  if (model_args(b, &t, x)) return BSM_BDF_MODEL_FAILED;
  b->res[0] = out;
  if (b->ode(b->arg, b->res, b->iw, b->w, 0)) return BSM_BDF_MODEL_FAILED;
  return BSM_BDF_OK;
}

/* jac_nz = d ode / d x at (t, x), the nonzeros of the compressed columns */
static int eval_jac(void *model, double t, const double *x) {
  bsm_bdf *b = model;
  if (model_args(b, &t, x)) return BSM_BDF_MODEL_FAILED;
  b->arg[4] = 0;
  b->res[0] = 0;
  b->res[1] = b->jac_nz;
  b->res[2] = 0;
  b->res[3] = 0;
  if (b->jac(b->arg, b->res, b->iw, b->w, 0)) return BSM_BDF_MODEL_FAILED;
  return all_finite(b->jac_nz, b->jac_nnz) ? BSM_BDF_OK : BSM_BDF_NOT_FINITE;
}

/* The LU factors of I - c J with the unknowns in the LU order; nonzero if singular. */
static int factorize(void *model, double c) {
  bsm_bdf *b = model;
  int nnz = b->factors.a_start[b->n];
  for (int s = 0; s < nnz; ++s) b->a_val[s] = -c * b->jac_nz[b->a_jac[s]];
  for (int i = 0; i < b->n; ++i) b->a_val[b->diag_slot[i]] += 1.0;
  return bsm_lu_factor(&b->factors, b->a_val);
}

/* rhs = (I - c J)^-1 rhs */
static void solve(void *model, double *rhs) {
  bsm_bdf *b = model;
  bsm_lu_solve(&b->factors, b->lu_order, b->permuted, rhs);
}

#ifdef BSM_BDF_PROFILE
#include <time.h>

/* profile: 0-3 seconds in rhs, jac, factor, solve (the calls not interrupted); 4 CPU seconds
 * of bsm_bdf_start and bsm_bdf_advance; 5-8 the calls timed; 9-12 the calls interrupted */
enum { PROFILE_RUN_S = 4, PROFILE_CALLS = 5, PROFILE_INTERRUPTED = 9, PROFILE_SIZE = 13 };

/* A call longer than this was interrupted by the machine's other work (the operations take
 * microseconds, a time slice milliseconds): its time is not counted. */
#define INTERRUPTED_S 1e-3

static double clock_s(clockid_t clock) {
  struct timespec ts;
  clock_gettime(clock, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* count a call of operation k that began at t0 (monotonic clock) */
static void spent(void *model, int k, double t0) {
  double *profile = ((bsm_bdf *)model)->profile, dt = clock_s(CLOCK_MONOTONIC) - t0;
  if (dt > INTERRUPTED_S) {
    profile[PROFILE_INTERRUPTED + k] += 1.0;
    return;
  }
  profile[k] += dt;
  profile[PROFILE_CALLS + k] += 1.0;
}

static int timed_f(void *model, double t, const double *x, double *out) {
  double t0 = clock_s(CLOCK_MONOTONIC);
  int status = eval_f(model, t, x, out);
  spent(model, 0, t0);
  return status;
}

static int timed_jac(void *model, double t, const double *x) {
  double t0 = clock_s(CLOCK_MONOTONIC);
  int status = eval_jac(model, t, x);
  spent(model, 1, t0);
  return status;
}

static int timed_factor(void *model, double c) {
  double t0 = clock_s(CLOCK_MONOTONIC);
  int status = factorize(model, c);
  spent(model, 2, t0);
  return status;
}

static void timed_solve(void *model, double *rhs) {
  double t0 = clock_s(CLOCK_MONOTONIC);
  solve(model, rhs);
  spent(model, 3, t0);
}

static const BsmBdfOps KERNEL_OPS = {timed_f, timed_jac, timed_factor, timed_solve};

/* out[0..12]: the profile (above); out[13]: the cost of one monotonic clock reading [s] (the
 * least mean of 100 batches of 1000) */
void bsm_bdf_profile(const bsm_bdf *b, double *out) {
  memcpy(out, b->profile, sizeof(b->profile));
  out[PROFILE_SIZE] = INFINITY;
  for (int batch = 0; batch < 100; ++batch) {
    double t0 = clock_s(CLOCK_MONOTONIC);
    for (int k = 0; k < 1000; ++k) clock_s(CLOCK_MONOTONIC);
    out[PROFILE_SIZE] = fmin(out[PROFILE_SIZE], (clock_s(CLOCK_MONOTONIC) - t0) / 1000);
  }
}
#define PROFILE_RUN(status)                                                                   \
  do {                                                                                        \
    double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);                                             \
    int result = (status);                                                                    \
    b->profile[PROFILE_RUN_S] += clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;                       \
    return result;                                                                            \
  } while (0)
#else
static const BsmBdfOps KERNEL_OPS = {eval_f, eval_jac, factorize, solve};
#define PROFILE_RUN(status) return (status)
#endif

void bsm_bdf_free(bsm_bdf *b) {
  if (!b) return;
  free(b->p); free(b->q); free(b->u);
  free(b->arg); free(b->res); free(b->iw); free(b->w);
  free(b->jac_nz); free(b->a_val); free(b->permuted); free(b->x0);
  free(b->lu_order); free(b->a_jac);
  BsmLu *c = &b->factors;
  free(c->row_of); free(c->step_of); free(c->l_start); free(c->l_index); free(c->l_val);
  free(c->u_start); free(c->u_index); free(c->u_pos); free(c->u_val); free(c->ur_start);
  free(c->ur_index); free(c->ur_val); free(c->inv_diag); free(c->x); free(c->work);
  free(b->core.D); free(b->core.work);
  free(b);
}

/* A solver of a model with n states, n_u inputs, n_p parameters and n_q input parameters,
 * kept for many runs (bsm_bdf_reset starts each); NULL if out of memory. sz_*: the largest
 * work sizes of the four functions; order: the unknowns in the order of the LU (a permutation
 * of 0 .. n-1); a_start, a_index: the pattern of I - c J in that order (compressed columns);
 * jac_slot, diag_slot: where J's nnz nonzeros and the diagonal are in it (the pattern and
 * slots are kept by the caller for the solver's life). */
bsm_bdf *bsm_bdf_new(int n, int n_u, int n_p, int n_q, bsm_fn ode, bsm_fn jac, bsm_fn signal,
                     bsm_fn observe, bsm_int nnz, const int *order, const int *a_start,
                     const int *a_index, const int *jac_slot, const int *diag_slot,
                     bsm_int sz_arg, bsm_int sz_res, bsm_int sz_iw, bsm_int sz_w) {
  bsm_bdf *b = calloc(1, sizeof(bsm_bdf));
  if (!b) return 0;
  b->n = n; b->n_u = n_u; b->n_p = n_p; b->n_q = n_q;
  b->ode = ode; b->jac = jac; b->signal = signal; b->observe = observe;
  b->jac_nnz = nnz;
  b->diag_slot = diag_slot;
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
  b->permuted = calloc(n, sizeof(double));
  b->x0 = calloc(n, sizeof(double));
  b->lu_order = calloc(n, sizeof(int));
  b->a_jac = malloc(sizeof(int) * ((size_t)a_start[n] + 1));
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
  c->x = calloc(n, sizeof(double));
  BsmBdf *core = &b->core;
  core->D = calloc((size_t)BSM_BDF_D_ROWS * n, sizeof(double));
  core->work = calloc((size_t)BSM_BDF_WORK_VECTORS * n, sizeof(double));
  int ok = b->p && b->q && b->u && b->arg && b->res && b->iw && b->w && b->jac_nz &&
           b->a_val && b->permuted && b->x0 && b->lu_order && b->a_jac && c->row_of && c->step_of &&
           c->work && c->l_start && c->l_index && c->l_val && c->u_start && c->u_index &&
           c->u_pos && c->u_val && c->ur_start && c->ur_index && c->ur_val && c->inv_diag &&
           c->x && core->D && core->work;
  if (!ok) {
    bsm_bdf_free(b);
    return 0;
  }
  memcpy(b->lu_order, order, sizeof(int) * n);
  for (int s = 0; s < a_start[n]; ++s) b->a_jac[s] = (int)nnz;
  for (bsm_int k = 0; k < nnz; ++k) b->a_jac[jac_slot[k]] = (int)k;
  core->n = n;
  core->ops = &KERNEL_OPS;
  core->model = b;
  core->h = &b->history;
  bsm_bdf_init(core);
  return b;
}

/* Start a run at (t0, x0) towards t_bound with the parameters p and input parameters q, given
 * one after the other in values = (p, q, x0), and the tolerances and largest step [s]: the
 * solver as bsm_bdf_new left it (history, counters and work zero; the LU finds a fresh pivot
 * order at its first factorisation), so that a run's result does not depend on the runs the
 * solver made before. */
void bsm_bdf_reset(bsm_bdf *b, const double *values, double rtol, double atol,
                   double max_step, double t0, double t_bound) {
  int n = b->n;
  memcpy(b->p, values, sizeof(double) * b->n_p);
  memcpy(b->q, values + b->n_p, sizeof(double) * b->n_q);
  memcpy(b->x0, values + b->n_p + b->n_q, sizeof(double) * n);
  memset(b->u, 0, sizeof(double) * (b->n_u + 1));
  memset(b->jac_nz, 0, sizeof(double) * (b->jac_nnz + 1));
  memset(b->a_val, 0, sizeof(double) * (b->factors.a_start[n] + 1));
  memset(b->permuted, 0, sizeof(double) * n);
  memset(b->core.D, 0, sizeof(double) * BSM_BDF_D_ROWS * n);
  memset(b->core.work, 0, sizeof(double) * BSM_BDF_WORK_VECTORS * n);
  memset(&b->history, 0, sizeof(b->history));
  b->factors.pivoted = 0;
  b->factors.pivotings = 0;
#ifdef BSM_BDF_PROFILE
  memset(b->profile, 0, sizeof(b->profile));
#endif
  b->core.rtol = rtol;
  b->core.atol = atol;
  b->core.max_step = max_step;
  b->t_bound = t_bound;
  b->history.t = t0;
}

/* First step size and the start of D; status code. */
int bsm_bdf_start(bsm_bdf *b) {
  PROFILE_RUN(bsm_bdf_first_step(&b->core, b->history.t, b->x0, b->t_bound));
}

/* bsm_bdf_advance's loop */
static int advance(bsm_bdf *b, int n_out, const double *t_out, double *x_out, int max_steps,
                   int *n_done) {
  int n = b->n, k = 0, steps = 0, status;
  *n_done = 0;
  for (;;) {
    while (k < n_out && t_out[k] <= b->history.t) {
      bsm_bdf_interpolate(&b->core, t_out[k], x_out + (size_t)k * n);
      *n_done = ++k;
    }
    if (k == n_out || steps++ == max_steps) return BSM_BDF_OK;
    if ((status = bsm_bdf_step(&b->core, b->t_bound, BSM_BDF_CLIP))) return status;
  }
}

/* Integrate until every output time t_out[0..n_out-1] (increasing, not before the start of
 * the last step, at most t_bound) is reached, or for at most max_steps steps; x_out[k*n + i] =
 * state i at t_out[k]. Returns a status code; *n_done: the outputs written (fewer than n_out
 * when the steps ran out: call again with the rest). */
int bsm_bdf_advance(bsm_bdf *b, int n_out, const double *t_out, double *x_out, int max_steps,
                    int *n_done) {
  PROFILE_RUN(advance(b, n_out, t_out, x_out, max_steps, n_done));
}

/* y_out[k*n_y + i] = observed variable i = observe(t, x, u(t), p) at t = t_out[k], x =
 * x_out[k*n .. k*n + n-1], for k < n_out: the output times' variables of the run. Returns a
 * status code. */
int bsm_bdf_observe(bsm_bdf *b, int n_out, const double *t_out, const double *x_out, int n_y,
                    double *y_out) {
  for (int k = 0; k < n_out; ++k) {
    double t = t_out[k];
    if (model_args(b, &t, x_out + (size_t)k * b->n)) return BSM_BDF_MODEL_FAILED;
    b->res[0] = y_out + (size_t)k * n_y;
    if (b->observe(b->arg, b->res, b->iw, b->w, 0)) return BSM_BDF_MODEL_FAILED;
  }
  return BSM_BDF_OK;
}

double bsm_bdf_time(const bsm_bdf *b) { return b->history.t; }
void bsm_bdf_state(const bsm_bdf *b, double *x) { memcpy(x, b->core.D, sizeof(double) * b->n); }
/* The core's counters, then the LU's fresh factorisations (pivot order and fill pattern found
 * anew) */
void bsm_bdf_stats(const bsm_bdf *b, long long *out) {
  memcpy(out, b->history.stats, sizeof(long long) * BSM_BDF_N_STATS);
  out[BSM_BDF_N_STATS] = b->factors.pivotings;
}
