/*
** dynamics.c -- the equations of motion: active Brownian dynamics, then
** relaxation, initial states and the paper's protocol (PROTOCOL: start,
** relaxation at v0 = 0, v0 on).
**
** Equation of motion (paper, Eq. (4)) and polarity noise (Eq. (5),
** eq:abp: d th_i = eta_i dt, <eta_i(t) eta_j(t')> = 2 Dr delta_ij
** delta(t - t')), integrated by Euler-Maruyama:
**     r_i  <- r_i + dt (mu F_i + v0_i n_i),      n_i = (cos th_i, sin th_i)
**     th_i <- th_i + sqrt(2 Dr_i dt) xi_i,       xi_i ~ N(0, 1)
**     F    <- -grad E at the new r.
** Both updates use the state at the start of the step (Ito).  Positions stay
** unwrapped, so r_i(t) - r_i(0) is the true displacement (for the MSD); the
** geometry applies the minimum image itself.
**
** Read first: move_of (Eq. (4)) and rotate_block (Eq. (5), in blocks of
** cells), the step as the paper writes it; then euler_all (the same move
** for every cell, in one pass that also keeps what the step needs),
** euler_step and afv_sim_step; reference/afv_plain.c has the same step in
** its plainest form.  The random numbers (Philox4x32-10, Box-Muller):
** rng.h.
**
** Invariant of afv_sim between calls: f, geom and geom.energy describe r.
** afv_init_lattice's disk of radius sqrt(n sqrt(3) / (2 pi)) + 2 holds
** at least n lattice sites (asserted).
*/
#include "afv.h"
#include "afv_internal.h"
#include "fastmath.h"
#include "rng.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* OpenMP (make OPENMP=1, see afv_internal.h): the per-cell loops of a step
** touch only their own cell, the noise is drawn per (cell, step), and the only
** reductions are a maximum and an or, so every thread count gives the same
** bits.  The macros are in afv_internal.h; empty in the plain C99 build. */

/* ---- one step: the paper's equations (4) and (5) ------------------------ */
/* Displacement of cell i over a time h: h (mu F_i + v0_i n_i), the
** paper's equation of motion, Eq. (4), by Euler's method; needs pol, that
** is v0_i n_i, for this step (euler_all). */
static void move_of(const afv_sim *s, int i, double h, double *dx, double *dy)
{
  double mu = s->dyn.mu;
  *dx = h * (mu * s->f[2*i] + s->pol[2*i]);         /* Eq. (4) */
  *dy = h * (mu * s->f[2*i+1] + s->pol[2*i+1]);
}

/* The step's one pass over every cell (each cell's data read once):
**   r_start_i = r_i;
**   pol_i = v0_i n_i = v0_i (cos theta_i, sin theta_i), fixed during the
**     step, so computed once here, not in move_of;
**   move_len_i = |dt mu F_i|^2, the square of the force-driven move;
**   the paper's Euler step of dt.
** Returns the largest move_len_i: NaN if a force is NaN (the cells have
** then moved, and the refused step restores r_start).  Squares order the
** cells as the lengths do, and save a hypot per cell. */
static double euler_all(afv_sim *s, double dt)
{
  /* locals, not s->...: the stores through r could alias the struct */
  double *r = s->r, *r_start = s->r_start, *pol = s->pol, *m = s->move_len;
  const double *f = s->f, *theta = s->theta, *v0_i = s->dyn.v0_i;
  double most = 0, hmu = dt * s->dyn.mu, v0 = s->dyn.v0;
  int i, n = s->n, nan = 0;
  AFV_PARALLEL_REDUCE(n, reduction(max: most) reduction(|: nan))
  for (i = 0; i < n; i++) {
    double fx = f[2*i], fy = f[2*i+1], x = r[2*i], y = r[2*i+1];
    double v = v0_i ? v0_i[i] : v0, c, sn, px, py, mx, my, move2, dx, dy;
    afv_sincos_inline(theta[i], &sn, &c);
    px = v * c;
    py = v * sn;
    mx = hmu * fx;
    my = hmu * fy;
    move2 = mx * mx + my * my;
    r_start[2*i] = x;
    r_start[2*i+1] = y;
    pol[2*i] = px;
    pol[2*i+1] = py;
    m[i] = move2;
    if (isnan(move2)) nan = 1;
    else if (move2 > most) most = move2;
    move_of(s, i, dt, &dx, &dy);
    r[2*i] = x + dx;
    r[2*i+1] = y + dy;
  }
  return nan ? NAN : most;
}

/* The rotational noise of cells 2 p and 2 p + 1 (if it exists) for the
** pairs p of [first, first + m), m <= NOISE_BLOCK: the two normals of pair
** p (afv_rng_normal2, the same bits).  All the block's uniforms are drawn
** before any is turned into normals: a pair's draw is one long chain of
** dependent operations (Philox's ten rounds, then a log and a sine), too
** long for the processor to overlap with the next pair's within one loop
** iteration; in two loops each chain is half as long (the same bits,
** faster: doc/performance.md). */
#define NOISE_BLOCK 32

static void rotate_block(afv_sim *s, int first, int m, unsigned long long seed,
                         unsigned long long step)
{
  double u[2 * NOISE_BLOCK];
  int q, k;
  for (q = 0; q < m; q++)
    rng_uniform2(seed, (uint32_t)(first + q), step, AFV_RNG_NOISE, u + 2 * q);
  for (q = 0; q < m; q++) {
    int i = 2 * (first + q);
    double z[2];
    rng_box_muller(u + 2 * q, z);
    for (k = 0; k < 2 && i + k < s->n; k++) {
      double Dr = s->dyn.Dr_i ? s->dyn.Dr_i[i + k] : s->dyn.Dr;
      if (Dr > 0) s->theta[i + k] += sqrt(2 * Dr * s->dyn.dt) * z[k]; /* (5) */
    }
  }
}

/* The first i with m[i] equal to `largest` (NaN if `largest` is NaN), for
** the report of a refused step: serial, and off the common path. */
static int first_at(const double *m, int n, double largest)
{
  int i;
  for (i = 0; i < n; i++)
    if (m[i] == largest || (isnan(m[i]) && isnan(largest))) return i;
  return 0;
}

/* The largest squared distance of a cell from its position at the start
** of the step (NaN if one is NaN); the squares stay in move_len. */
static double farthest_from_start(afv_sim *s)
{
  double *m = s->move_len, most = 0;
  int i, nan = 0;
  AFV_PARALLEL_REDUCE(s->n, reduction(max: most) reduction(|: nan))
  for (i = 0; i < s->n; i++) {
    double dx = s->r[2*i] - s->r_start[2*i];
    double dy = s->r[2*i+1] - s->r_start[2*i+1];
    m[i] = dx * dx + dy * dy;
    if (isnan(m[i])) nan = 1;
    else if (m[i] > most) most = m[i];
  }
  return nan ? NAN : most;
}

/* Records the cell of a refused step and its move (in l). */
static int unstable(afv_sim *s, int cell, double len)
{
  s->bad_cell = cell;
  s->bad_disp = len / s->par.l;
  return AFV_EUNSTABLE;
}

/* Puts every cell back at r0 and recomputes the forces there. */
static void back_to(afv_sim *s, const double *r0)
{
  size_t bytes = (size_t)(2 * s->n) * sizeof(double);
  if (memcmp(r0, s->r, bytes) != 0) {
    memcpy(s->r, r0, bytes);
    afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
  }
}

/* max_i |v0_i|. */
static double largest_v0(const afv_sim *s)
{
  int i, n = s->dyn.v0_i ? s->n : 1;
  double most = 0;
  for (i = 0; i < n; i++) {
    double v0 = s->dyn.v0_i ? fabs(s->dyn.v0_i[i]) : fabs(s->dyn.v0);
    if (v0 > most) most = v0;
  }
  return most;
}

/* EULER: the paper's step, Eq. (4), as it is written: every
** cell moves dt (mu F_i + v0_i n_i) with the exact force, however far;
** then the forces at the new positions.  Nothing is refused but a move or
** a force that is not finite (the state is then restored).  A step in
** which some cell moved more than AFV_MAX_STEP_DISP l counts as a jump
** (s->jumps): near a contact that breaks, the force diverges like
** (2l - d)^(-1/2), and such a jump is how a discrete step carries a pair
** over the barrier that holds it in continuous time.  The whole moves are
** measured only when the force moves and v0 dt could add up to a jump
** (every cell's move is at most max |dt mu F| + max |v0| dt).  v0 as it
** is in s->dyn (the relaxation sets it to 0); a refused step leaves the
** state as it was. */
static int euler_step(afv_sim *s)
{
  double dt = s->dyn.dt, v0_max = largest_v0(s);
  double most = euler_all(s, dt), far, limit = AFV_MAX_STEP_DISP;
  int st;
  if (!isfinite(most)) {                  /* NaN or inf force: refused */
    back_to(s, s->r_start);
    return unstable(s, first_at(s->move_len, s->n, most), most);
  }
  far = sqrt(most) + v0_max * dt;         /* a bound on every move */
  if (far > limit * s->par.l || far > s->largest_move * s->par.l) {
    double far2 = farthest_from_start(s);
    far = sqrt(far2) / s->par.l;          /* the largest move */
    if (far > AFV_RUNAWAY_MOVE) {         /* as good as not finite */
      int cell = first_at(s->move_len, s->n, far2);
      back_to(s, s->r_start);
      return unstable(s, cell, far * s->par.l);
    }
    if (far > limit) s->jumps++;
    if (far > s->largest_move) s->largest_move = far;
  }
  st = afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
  if (st != AFV_OK) {                     /* a position not finite */
    back_to(s, s->r_start);
    return st == AFV_ENONFINITE ? unstable(s, 0, INFINITY) : st;
  }
  return AFV_OK;
}

int afv_sim_step(afv_sim *s)
{
  assert(s != NULL);
  unsigned long long seed = s->dyn.seed, step = (unsigned long long)s->step;
  int i, pairs, st;
  if ((st = euler_step(s)) != AFV_OK) return st;
  pairs = (s->n + 1) / 2;          /* cells 2p and 2p + 1 share one draw */
  AFV_PARALLEL_FOR(s->n)
  for (i = 0; i < pairs; i += NOISE_BLOCK)
    rotate_block(s, i, pairs - i < NOISE_BLOCK ? pairs - i : NOISE_BLOCK,
                 seed, step);
  s->step++;
  s->t = (double)s->step * s->dyn.dt;   /* no drift from summing dt */
  return AFV_OK;
}

/* ---- the simulation ---------------------------------------------------- */
void afv_dyn_default(afv_dyn *d)
{
  assert(d != NULL);
  memset(d, 0, sizeof *d);
  d->mu = 1;
  d->v0 = 0;
  d->Dr = 0.1;
  d->dt = 0.01;
  d->seed = 1;
}

static int dyn_check(const afv_dyn *d, int n)
{
  int i;
  if (!(isfinite(d->mu) && d->mu > 0 && isfinite(d->dt) && d->dt > 0
        && isfinite(d->v0) && isfinite(d->Dr) && d->Dr >= 0))
    return AFV_EINVAL;
  for (i = 0; i < n; i++) {
    if (d->v0_i && !isfinite(d->v0_i[i])) return AFV_EINVAL;
    if (d->Dr_i && !(isfinite(d->Dr_i[i]) && d->Dr_i[i] >= 0))
      return AFV_EINVAL;
  }
  return AFV_OK;
}

/* Copies a caller's per-cell array into *next (advancing it), or NULL. */
static const double *own_copy(const double *src, int n, double **next)
{
  double *dst = *next;
  if (!src) return NULL;
  memcpy(dst, src, (size_t)n * sizeof(double));
  *next += n;
  return dst;
}

void afv_sim_free(afv_sim *s)
{
  afv_geom_free(&s->geom);
  free(s->own);
  memset(s, 0, sizeof *s);
}

int afv_sim_init(afv_sim *s, int n, const double *r, const double *theta,
                 const afv_params *p, const afv_box *b, const afv_dyn *d)
{
  assert(s != NULL && p != NULL && d != NULL && (r != NULL || n <= 0));
  double *next;
  int st;
  afv_sim_free(s);
  if (n < 0 || dyn_check(d, n) != AFV_OK) return AFV_EINVAL;
  /* r, f, r_start, pol (2n each), theta, move_len (n each), six optional
  ** per-cell arrays (n each) */
  s->own = malloc((size_t)(16 * n + 1) * sizeof(double));
  if (!s->own) return AFV_ENOMEM;
  s->n = n;
  s->r = s->own;
  s->f = s->own + 2 * n;
  s->theta = s->own + 4 * n;
  s->r_start = s->own + 5 * n;
  s->move_len = s->own + 7 * n;
  s->pol = s->own + 8 * n;
  next = s->own + 10 * n;
  memcpy(s->r, r, (size_t)(2 * n) * sizeof(double));
  if (theta) memcpy(s->theta, theta, (size_t)n * sizeof(double));
  else memset(s->theta, 0, (size_t)n * sizeof(double));
  s->par = *p;
  s->par.KA_i = own_copy(p->KA_i, n, &next);
  s->par.KP_i = own_copy(p->KP_i, n, &next);
  s->par.A0_i = own_copy(p->A0_i, n, &next);
  s->par.P0_i = own_copy(p->P0_i, n, &next);
  s->dyn = *d;
  s->dyn.v0_i = own_copy(d->v0_i, n, &next);
  s->dyn.Dr_i = own_copy(d->Dr_i, n, &next);
  s->box = b ? *b : s->box;
  s->step = 0;
  s->t = 0;
  s->jumps = 0;
  s->largest_move = 0;
  s->bad_cell = -1;
  s->bad_disp = 0;
  st = afv_compute(&s->geom, n, s->r, &s->par, &s->box, s->f);
  if (st != AFV_OK) {
    int bad_i = s->geom.bad_i, bad_j = s->geom.bad_j;  /* the cells named */
    afv_sim_free(s);
    s->geom.bad_i = bad_i;
    s->geom.bad_j = bad_j;
  }
  return st;
}

int afv_sim_refresh(afv_sim *s)
{
  assert(s != NULL);
  if (afv_params_check(&s->par, s->n) != AFV_OK
      || dyn_check(&s->dyn, s->n) != AFV_OK)
    return AFV_EINVAL;
  /* the one cache of a step that depends on par, box and r: f and geom */
  return afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
}

double afv_sim_max_force(const afv_sim *s)
{
  assert(s != NULL);
  double m2 = 0;
  int i;
  for (i = 0; i < s->n; i++) {
    double q = s->f[2*i] * s->f[2*i] + s->f[2*i+1] * s->f[2*i+1];
    if (!(q <= m2)) m2 = q;   /* a NaN wins, so it is seen */
  }
  return sqrt(m2);
}

/* ---- relaxation (overdamped flow at v0 = 0) ----------------------------- */
/* RELAXATION.  The paper relaxes its start "at zero temperature" before it
** switches v0 on: the equation of motion with v0 = 0, dr_i/dt = mu F_i,
** by Euler steps of dt (the authors' code: 30 time units of them).  That
** is what afv_relax does, step after step, with the Euler step of
** afv_sim_step (the same code, polarity and noise off), until
**   max_i |F_i| <= tol                                   (converged), or
**   a kink of E is reached (at_kink, below), or max_iter steps.
** Why this and not a global minimiser: every cell moves by its own force,
** so a cell sitting at a kink of E (where the force jumps and does not
** vanish) only chatters across it, by about dt mu |F| ~ 0.01 l, while
** every other cell goes on relaxing.  The FIRE minimiser used before
** accepted or undid a trial move of the whole tissue by the change of the
** total energy; near one kink every trial move raised E, so it undid the
** moves of all cells and stopped with max |F| of 84 to 1035 and the
** tissue nowhere near relaxed (the authors' random start at N = 400,
** phi = 0.5, P0 = 4 to 8: mean area 0.75 where the relaxed tissue has
** 1.8).  The flow is slower near a smooth minimum than FIRE (linear
** convergence), but from that start it reaches max |F| <= 1e-6 in about
** 10^4 steps at P0 = 4 and 8.8 (measured), far below the default limit.
**
** KINKS.  E has a kink wherever a triple junction crosses a cell's circle
** (a gap opens or closes), and above P0* ~ 5.7 relaxed tissues sit on
** such kinks: the flow then ends chattering, max |F| stays at the one-sided
** force (about 2 at P0 = 6, measured) and never reaches tol.  What shows
** a genuine kink, measured over windows of AFV_RELAX_WINDOW steps:
**   drift: every cell's mean force over the window, its displacement
**     over the window / (window time mu), is at most AFV_RELAX_KINK_DRIFT
**     (a chattering cell goes back and forth; a cell still sliding down a
**     slope, however slowly, drifts);
**   chatter: that drift is at most AFV_RELAX_KINK_CHATTER max_i |F_i|: the
**     forces cancel over the window, as across a kink (measured at
**     P0 = 6: drift 5e-5 against max |F| 2).  Near a smooth minimum the
**     force decays steadily, so the window's mean force is larger than
**     the force at its end, not a tenth of it: that convergence goes on
**     to tol (at P0 = 4 the drift fell below 1e-3 while max |F| was still
**     2e-4, a few thousand steps before max |F| <= 1e-6);
**   drop: the window's mean energy fell by at most AFV_RELAX_KINK_DROP
**     sum_i |e_i| since the previous window;
**   force: max_i |F_i| <= AFV_RELAX_KINK_FORCE (the one-sided forces of a
**     kink are of order 1; a larger force is not a kink but a tissue still
**     moving, or a contact about to break).
** All three must hold at the end of a window.  Otherwise the flow goes
** on, up to max_iter steps: then neither flag is set, and the report
** holds the figures. */

/* sum_i |e_i|: the scale of the rounding error of E. */
static double energy_scale(const afv_sim *s)
{
  const afv_geom *g = &s->geom;
  double sum = 0;
  int i;
  for (i = 0; i < s->n; i++)
    sum += fabs(afv_cell_energy(&s->par, i, g->area[i], g->perim[i],
                                g->arc[i]));
  return sum;
}

/* Adds every cell's position to sum (2n). */
static void add_positions(const afv_sim *s, double *sum)
{
  int k;
  for (k = 0; k < 2 * s->n; k++) sum[k] += s->r[k];
}

/* max_i |a_i - b_i| / m, a and b sums of m positions (unwrapped, so a
** plain difference): the largest move of a cell's mean position. */
static double largest_mean_move(int n, const double *a, const double *b,
                                long m)
{
  double most = 0;
  int i;
  for (i = 0; i < n; i++) {
    double d = afv_hypot_inline(a[2*i] - b[2*i], a[2*i+1] - b[2*i+1])
               / (double)m;
    if (!(d <= most)) most = d;
  }
  return most;
}

/* The relaxation's running sums over the present and the previous window:
** positions (2n each) and energy. */
typedef struct window {
  double *r_sum, *r_sum_prev;
  double E_sum, E_sum_prev;
  int full;            /* complete windows so far */
} window;

/* The end of a window: sets rep's drift and drop (from the window's mean
** positions and energy against the previous window's, which cancels the
** chatter at kinks); 1 if they and max |F| show a kink. */
static int window_shows_kink(const afv_sim *s, afv_relax_report *rep,
                             window *W, double scale)
{
  long K = AFV_RELAX_WINDOW;
  double time = (double)K * s->dyn.dt * s->dyn.mu, *t;
  int kink = 0;
  if (W->full++ > 0) {
    rep->drift = largest_mean_move(s->n, W->r_sum, W->r_sum_prev, K) / time;
    rep->drop = (W->E_sum_prev - W->E_sum) / (double)K / scale;
    kink = rep->drift <= AFV_RELAX_KINK_DRIFT
           && rep->drift <= AFV_RELAX_KINK_CHATTER * rep->max_force
           && fabs(rep->drop) <= AFV_RELAX_KINK_DROP
           && rep->max_force <= AFV_RELAX_KINK_FORCE;
  }
  t = W->r_sum_prev;                   /* this window becomes the previous */
  W->r_sum_prev = W->r_sum;
  W->r_sum = t;
  memset(W->r_sum, 0, (size_t)(2 * s->n) * sizeof(double));
  W->E_sum_prev = W->E_sum;
  W->E_sum = 0;
  return kink;
}

int afv_relax(afv_sim *s, double tol, long max_iter, afv_relax_report *rep,
              afv_relax_monitor mon, void *ctx)
{
  assert(s != NULL && rep != NULL);
  afv_dyn saved = s->dyn;
  long long jumps = s->jumps;
  window W;
  int st = AFV_OK;
  memset(rep, 0, sizeof *rep);
  memset(&W, 0, sizeof W);
  rep->energy0 = rep->energy = s->geom.energy;
  rep->max_force = afv_sim_max_force(s);
  rep->drift = rep->drop = NAN;
  W.r_sum = calloc((size_t)(4 * s->n + 1), sizeof(double));
  if (!W.r_sum) return AFV_ENOMEM;
  W.r_sum_prev = W.r_sum + 2 * s->n;
  s->dyn.v0 = 0;                   /* zero temperature: no self-propulsion */
  s->dyn.v0_i = NULL;
  while (!(rep->max_force <= tol) && rep->iterations < max_iter) {
    /* one step of the flow (v0 = 0 above): afv_sim_step's Euler step,
    ** without the noise */
    if ((st = euler_step(s)) != AFV_OK) {
      /* a finite runaway move (beyond AFV_RUNAWAY_MOVE l): forces too
      ** large for dt, which no relaxation by steps of dt can follow; the
      ** caller hears it (refused, afv_sim's bad_*) and goes on, as when
      ** max_iter is reached.  A force that is not finite is an error. */
      if (st == AFV_EUNSTABLE && isfinite(s->bad_disp)) {
        rep->refused = 1;
        st = AFV_OK;
      }
      break;
    }
    rep->iterations++;
    rep->max_force = afv_sim_max_force(s);
    add_positions(s, W.r_sum);
    W.E_sum += s->geom.energy;
    if (mon) mon(ctx, rep->iterations, s->geom.energy, rep->max_force);
    if (rep->iterations % AFV_RELAX_WINDOW == 0
        && window_shows_kink(s, rep, &W, energy_scale(s))
        && !(rep->max_force <= tol)) {
      rep->at_kink = 1;
      break;
    }
  }
  s->dyn = saved;
  rep->energy = s->geom.energy;
  rep->converged = rep->max_force <= tol;
  rep->time = (double)rep->iterations * s->dyn.dt;
  rep->jumps = s->jumps - jumps;
  free(W.r_sum < W.r_sum_prev ? W.r_sum : W.r_sum_prev);
  return st;
}

/* ---- initial configurations -------------------------------------------- */
/* A triangular-lattice site (i, j): position a (i + j/2, j sqrt(3)/2), and
** squared distance from the origin a^2 (i^2 + i j + j^2), exact in integers. */
typedef struct site {
  long d2;   /* i^2 + i j + j^2 */
  int i, j;  /* lattice indices */
} site;

static int site_cmp(const void *pa, const void *pb)
{
  const site *a = pa, *b = pb;
  if (a->d2 != b->d2) return a->d2 < b->d2 ? -1 : 1;
  if (a->j != b->j) return a->j < b->j ? -1 : 1;
  return (a->i > b->i) - (a->i < b->i);
}

int afv_init_lattice(int n, double a, const afv_box *b, double *r)
{
  assert(r != NULL || n <= 0);
  /* the n nearest sites lie within radius sqrt(n / pi * sqrt(3)/2) + 2;
  ** site (i, j) is at distance^2 i^2 + ij + j^2 >= 3 j^2 / 4, so the rows
  ** that reach the disk have |j| <= J = 2R / sqrt(3) */
  int R = (int)ceil(sqrt(n * 0.8660254037844386 / PI) + 2);
  int J = (int)ceil(2 * R / 1.7320508075688772);
  int m = 0, i, j, k;
  long maxd2 = 0;
  double cx = 0, cy = 0;
  site *S = malloc((size_t)(4 * R + 1) * (size_t)(2 * J + 1) * sizeof *S);
  if (!S) return AFV_ENOMEM;
  for (j = -J; j <= J; j++)
    for (i = -2 * R; i <= 2 * R; i++) {
      long d2 = (long)i * i + (long)i * j + (long)j * j;
      if (d2 > (long)R * R) continue;
      S[m].d2 = d2;
      S[m].i = i;
      S[m].j = j;
      m++;
    }
  assert(m >= n);              /* the disk holds >= n sites */
  if (m < n) {                 /* (without asserts: refused, not overrun) */
    free(S);
    return AFV_EINVAL;
  }
  qsort(S, (size_t)m, sizeof *S, site_cmp);
  for (k = 0; k < n; k++)
    if (S[k].d2 > maxd2) maxd2 = S[k].d2;
  if (b && b->periodic) {
    /* keep a gap of a between the cluster and its periodic images */
    double side = b->Lx < b->Ly ? b->Lx : b->Ly;
    double amax = side / (2 * sqrt((double)maxd2) + 1);
    if (a > amax) a = amax;
    cx = 0.5 * b->Lx;
    cy = 0.5 * b->Ly;
  }
  for (k = 0; k < n; k++) {
    r[2*k] = cx + a * (S[k].i + 0.5 * S[k].j);
    r[2*k+1] = cy + a * 0.8660254037844386 * S[k].j;
  }
  free(S);
  return AFV_OK;
}

/* Centres uniform in the square of side `side` centred on (cx, cy). */
static void uniform_square(int n, unsigned long long seed, double cx,
                           double cy, double side, double *r)
{
  int i;
  for (i = 0; i < n; i++) {
    double u[2];
    rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_POS, u);
    r[2*i] = cx + side * (0.5 - u[0]);
    r[2*i+1] = cy + side * (0.5 - u[1]);
  }
}

void afv_init_random(int n, unsigned long long seed, const afv_box *b,
                     double side, double *r)
{
  assert(r != NULL || n <= 0);
  int i;
  if (!(b && b->periodic)) {
    uniform_square(n, seed, 0, 0, side, r);
    return;
  }
  for (i = 0; i < n; i++) {
    double u[2];
    rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_POS, u);
    r[2*i] = b->Lx * (1 - u[0]);          /* 1 - u lies in [0, 1) */
    r[2*i+1] = b->Ly * (1 - u[1]);
  }
}

void afv_init_cluster(int n, unsigned long long seed, const afv_box *b,
                      double side, double *r)
{
  assert(r != NULL || n <= 0);
  int periodic = b && b->periodic;
  uniform_square(n, seed, periodic ? 0.5 * b->Lx : 0,
                 periodic ? 0.5 * b->Ly : 0, side, r);
}

void afv_init_angles(int n, unsigned long long seed, double *theta)
{
  assert(theta != NULL || n <= 0);
  int i;
  for (i = 0; i < n; i++) {
    double u[2];
    rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_ANGLE, u);
    theta[i] = TWO_PI * (1 - u[0]);
  }
}

/* ---- the paper's protocol ---------------------------------------------- */
/* PROTOCOL.  The paper (Sec. Model) starts from one large connected
** cluster (the authors' code: centres uniform at random in a square of
** side 0.3 L, AFV_START_CLUSTER), relaxes it "at zero temperature" (the
** flow at v0 = 0, afv_relax), then switches self-propulsion on.
** afv_protocol_start is that order in one place: afv run calls it, with
** the other starts (lattice, random, given) and FIRE as options.  v0 is
** the active run's from the first call on: the relaxation sets it to 0
** only for its own steps, so it is on again when the function returns. */

/* The start's 2n positions into r. */
static int start_positions(int n, const afv_box *b, const afv_dyn *d,
                           const afv_protocol *pr, double *r)
{
  switch (pr->start) {
  case AFV_START_CLUSTER:
    afv_init_cluster(n, d->seed, b, pr->side, r);
    return AFV_OK;
  case AFV_START_LATTICE:
    return afv_init_lattice(n, pr->spacing, b, r);
  case AFV_START_RANDOM:
    afv_init_random(n, d->seed, b, pr->side, r);
    return AFV_OK;
  case AFV_START_GIVEN:
    if (!pr->r) return AFV_EINVAL;
    memcpy(r, pr->r, (size_t)(2 * n) * sizeof(double));
    return AFV_OK;
  default:
    return AFV_EINVAL;
  }
}

/* The report of a start left unrelaxed: its energy and force. */
static void unrelaxed(const afv_sim *s, double tol, afv_relax_report *rep)
{
  memset(rep, 0, sizeof *rep);
  rep->energy0 = rep->energy = s->geom.energy;
  rep->max_force = afv_sim_max_force(s);
  rep->drift = rep->drop = NAN;
  rep->converged = rep->max_force <= tol;
}

int afv_protocol_start(afv_sim *s, int n, const afv_params *p,
                       const afv_box *b, const afv_dyn *d,
                       const afv_protocol *pr, afv_relax_report *rep,
                       afv_relax_monitor mon, void *ctx)
{
  assert(s != NULL && p != NULL && d != NULL && pr != NULL);
  double *r, *theta;
  afv_relax_report none;
  int st;
  if (!rep) rep = &none;
  memset(rep, 0, sizeof *rep);
  if (n < 0) return AFV_EINVAL;
  r = malloc((size_t)(2 * n + 1) * sizeof(double));
  theta = malloc((size_t)(n + 1) * sizeof(double));
  st = r && theta ? start_positions(n, b, d, pr, r) : AFV_ENOMEM;
  /* A generated start's centres are drawn independently (or a lattice),
  ** so their numbering means nothing; in the order drawn a cell's
  ** neighbours lie anywhere in memory, which at N = 400000 made each step
  ** 1.8 - 2.8 times dearer (doc/performance.md, "Cell numbering"). */
  if (st == AFV_OK && pr->start != AFV_START_GIVEN
      && afv_params_check(p, n) == AFV_OK)     /* else afv_sim_init refuses */
    st = afv_spatial_renumber(n, r, p->l, b);
  if (st == AFV_OK) {
    if (pr->theta) memcpy(theta, pr->theta, (size_t)n * sizeof(double));
    else afv_init_angles(n, d->seed, theta);
    st = afv_sim_init(s, n, r, theta, p, b, d);
  }
  free(r);
  free(theta);
  if (st != AFV_OK) return st;
  if (pr->relax_max_steps <= 0) {
    unrelaxed(s, pr->relax_tol, rep);
    return AFV_OK;
  }
  return (pr->relax == AFV_RELAX_FIRE ? afv_relax_fire : afv_relax)
         (s, pr->relax_tol, pr->relax_max_steps, rep, mon, ctx);
}
