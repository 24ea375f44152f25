/*
** relax_fire.c -- a minimiser for when a true minimum of E is wanted:
** FIRE 2.0 (Guenole et al., Comput. Mater. Sci. 175, 109584 (2020)) with a
** per-cell move cap and a stop at kinks that keeps the best state.
**
** The paper's protocol is the overdamped flow at v0 = 0 (dynamics.c,
** afv_relax; `relax flow`, the default of afv run): every cell moves by its
** own force, which is what the authors did.  FIRE reaches a minimum of E
** far faster and lower (doc/performance.md), but it is not the paper's
** path to it: use it to study minima (energy landscapes, the mean field,
** a start that is really relaxed), not to reproduce the paper's runs.
**
** FIRE.  Positions r and velocities v (unit mass), forces F = -grad E.
** Each iteration: P = F.v; if P > 0 for more than FIRE_DELAY iterations
** in a row, dt grows by FIRE_INC (to FIRE_DT_MAX) and alpha shrinks by
** FIRE_F_ALPHA; if P <= 0 (uphill), dt shrinks by FIRE_DEC (not below
** FIRE_DT_MIN; not during the first FIRE_DELAY iterations), alpha goes back
** to FIRE_ALPHA0, every cell goes back half its last move and v = 0.  Then
** a semi-implicit Euler step: v += dt F, v = (1 - alpha) v + alpha |v|
** F/|F| (norms over the whole tissue), and each cell moves by dt v_i, cut
** to AFV_FIRE_MAX_MOVE l if longer (the cap: a contact about to break has a
** force like (2l - d)^(-1/2), which would throw its cells far).
**
** STOPS (the four of afv_relax_report):
**   converged  max_i |F_i| <= tol;
**   at_kink    the lowest energy seen has not dropped by more than
**              AFV_FIRE_STALL_DROP of |E| over AFV_FIRE_STALL iterations
**              while the max |F| of that state did not halve (a smooth minimum being
**              approached halves it), and that max |F| is at most
**              AFV_RELAX_KINK_FORCE: E
**              has a kink there (a triple junction on a cell's circle, where
**              the force jumps and does not vanish), so no step lowers E and
**              FIRE oscillates across it; its energy is not monotone there
**              (P0 >= 8, measured), hence the best state is kept;
**   refused    the same stall with a larger force, or more than
**              FIRE_MAX_UPHILL uphill restarts in a row: FIRE cannot step
**              down from there;
**   neither    max_iter iterations.
** Where more than half of a stall window's iterations were uphill
** restarts at a max |F| above AFV_RELAX_KINK_FORCE, FIRE gives way to
** steepest descent (descent_due), with the same cap and stops.
** Except when converged the tissue ends in the lowest-energy state seen;
** the forces and the geometry are those of the final positions. */
#include "afv_internal.h"
#include "fastmath.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FIRE_DT0 0.1          /* first time step (the brief's dt0) */
#define FIRE_DT_MAX 1.0       /* largest time step */
#define FIRE_DT_MIN 0.002     /* smallest: 0.02 dt0 (FIRE 2.0) */
#define FIRE_ALPHA0 0.25      /* FIRE 2.0's alpha_start */
#define FIRE_F_ALPHA 0.99
#define FIRE_INC 1.1
#define FIRE_DEC 0.5
#define FIRE_DELAY 20         /* N_delay */
#define FIRE_MAX_UPHILL 2000  /* N_P<0 max */
/* the largest move and the stall: AFV_FIRE_* (afv_config.h) */

/* Per-cell velocities, last moves and the best state: 6n doubles. */
typedef struct fire {
  double *v, *move, *best;
  double best_E, best_force, stall_E, stall_force;
  double dt, alpha;
  int n_up, n_down;     /* iterations in a row with P > 0, P <= 0 */
  int restarts;         /* uphill restarts in the current stall window */
  int descent;          /* 1: FIRE gave way to capped steepest descent */
} fire;

static int fire_alloc(fire *w, int n)
{
  memset(w, 0, sizeof *w);
  w->v = calloc((size_t)6 * (size_t)n + 1, sizeof(double));
  if (!w->v) return AFV_ENOMEM;
  w->move = w->v + 2 * n;
  w->best = w->move + 2 * n;
  w->dt = FIRE_DT0;
  w->alpha = FIRE_ALPHA0;
  return AFV_OK;
}

static double dot(const double *a, const double *b, int m)
{
  double s = 0;
  int k;
  for (k = 0; k < m; k++) s += a[k] * b[k];
  return s;
}

/* FIRE's time step and mixing after the power P = F.v; 1 if it gave up
** (too many uphill restarts). */
static int fire_adapt(afv_sim *s, fire *w, long iter)
{
  int k;
  if (dot(s->f, w->v, 2 * s->n) > 0) {
    w->n_down = 0;
    if (++w->n_up > FIRE_DELAY) {
      w->dt = fmin(w->dt * FIRE_INC, FIRE_DT_MAX);
      w->alpha *= FIRE_F_ALPHA;
    }
    return 0;
  }
  w->n_up = 0;
  w->restarts++;
  if (++w->n_down > FIRE_MAX_UPHILL) return 1;
  if (iter >= FIRE_DELAY) {
    if (w->dt * FIRE_DEC >= FIRE_DT_MIN) w->dt *= FIRE_DEC;
    w->alpha = FIRE_ALPHA0;
  }
  for (k = 0; k < 2 * s->n; k++) {     /* half of the last move back */
    s->r[k] -= 0.5 * w->move[k];
    w->v[k] = 0;
  }
  return 0;
}

/* The semi-implicit Euler step with mixing, each cell's move capped. */
static void fire_move(afv_sim *s, fire *w)
{
  double vn, fn, cap = AFV_FIRE_MAX_MOVE * s->par.l;
  int i, k, m = 2 * s->n;
  for (k = 0; k < m; k++) w->v[k] += w->dt * s->f[k];
  vn = sqrt(dot(w->v, w->v, m));
  fn = sqrt(dot(s->f, s->f, m));
  if (fn > 0)
    for (k = 0; k < m; k++)
      w->v[k] = (1 - w->alpha) * w->v[k] + w->alpha * vn * s->f[k] / fn;
  for (i = 0; i < s->n; i++) {
    double dx = w->dt * w->v[2*i], dy = w->dt * w->v[2*i+1];
    double len = afv_hypot_inline(dx, dy);
    if (len > cap) {          /* the velocity becomes the capped move's */
      dx *= cap / len;
      dy *= cap / len;
      w->v[2*i] = dx / w->dt;
      w->v[2*i+1] = dy / w->dt;
    }
    w->move[2*i] = dx;
    w->move[2*i+1] = dy;
    s->r[2*i] += dx;
    s->r[2*i+1] += dy;
  }
}

/* A step of steepest descent, each cell by dt mu F cut to AFV_FIRE_MAX_MOVE
** l (descent_due says when). */
static void descent_move(afv_sim *s, fire *w)
{
  double cap = AFV_FIRE_MAX_MOVE * s->par.l, step = s->dyn.dt * s->dyn.mu;
  int i;
  for (i = 0; i < s->n; i++) {
    double dx = step * s->f[2*i], dy = step * s->f[2*i+1];
    double len = afv_hypot_inline(dx, dy);
    if (len > cap) {
      dx *= cap / len;
      dy *= cap / len;
    }
    w->move[2*i] = dx;
    w->move[2*i+1] = dy;
    s->r[2*i] += dx;
    s->r[2*i+1] += dy;
  }
}

/* At the end of a stall window: 1 if FIRE should give way to steepest
** descent for good, because most of the window's iterations were uphill
** restarts (the global power F.v <= 0).  That happens where a few cells'
** forces reverse every step (kinks of E with |F| ~ 1000: at Lambda 0 and
** P0 8.8, cells 0.2 l apart in the dense start) while the rest still
** descend: each restart keeps FIRE's time step at its smallest, and its
** moves, dt^2 F, become far shorter than the flow's dt F (FIRE stopped
** at E 10574, max |F| 1041, where the flow reaches 2533.74).  Steepest
** descent needs no power test.  Not at a kink of small force (at most
** AFV_RELAX_KINK_FORCE), where FIRE's stall test stops as before. */
static int descent_due(fire *w)
{
  int due = w->restarts > AFV_FIRE_STALL / 2
            && w->best_force > AFV_RELAX_KINK_FORCE;
  w->restarts = 0;
  return due;
}

/* Remembers the state if its energy is the lowest so far. */
static void keep_best(const afv_sim *s, fire *w, double max_force)
{
  if (!(s->geom.energy < w->best_E)) return;
  w->best_E = s->geom.energy;
  w->best_force = max_force;
  memcpy(w->best, s->r, (size_t)(2 * s->n) * sizeof(double));
}

/* At the end of a stall window: 1 if the best energy has stopped falling
** and the force of the best state has not halved (a smooth convergence,
** however slow in E, halves it). */
static int stalled(fire *w)
{
  int stop = w->stall_E - w->best_E <= AFV_FIRE_STALL_DROP * fabs(w->best_E)
             && !(w->best_force < 0.5 * w->stall_force);
  w->stall_E = w->best_E;
  w->stall_force = w->best_force;
  return stop;
}

int afv_relax_fire(afv_sim *s, double tol, long max_iter,
                   afv_relax_report *rep, afv_relax_monitor mon, void *ctx)
{
  assert(s != NULL && rep != NULL);
  fire w;
  int st = AFV_OK, stop = 0;
  memset(rep, 0, sizeof *rep);
  rep->energy0 = rep->energy = s->geom.energy;
  rep->max_force = afv_sim_max_force(s);
  rep->drift = rep->drop = NAN;
  if (fire_alloc(&w, s->n) != AFV_OK) return AFV_ENOMEM;
  w.best_E = w.stall_E = HUGE_VAL;
  keep_best(s, &w, rep->max_force);
  w.stall_E = w.best_E;
  w.stall_force = w.best_force;
  while (!(rep->max_force <= tol) && rep->iterations < max_iter && !stop) {
    if (!w.descent && fire_adapt(s, &w, rep->iterations)) {
      rep->refused = 1;
      break;
    }
    if (w.descent) descent_move(s, &w);
    else fire_move(s, &w);
    if ((st = afv_sim_refresh(s)) != AFV_OK) break;
    rep->iterations++;
    rep->time += w.dt;
    rep->max_force = afv_sim_max_force(s);
    keep_best(s, &w, rep->max_force);
    if (mon) mon(ctx, rep->iterations, s->geom.energy, rep->max_force);
    if (rep->iterations % AFV_FIRE_STALL == 0 && (stop = stalled(&w)) != 0) {
      rep->at_kink = w.best_force <= AFV_RELAX_KINK_FORCE;
      rep->refused = !rep->at_kink;
    }
    if (rep->iterations % AFV_FIRE_STALL == 0 && descent_due(&w)) w.descent = 1;
  }
  rep->converged = rep->max_force <= tol;
  if (!rep->converged && w.best_E < HUGE_VAL && st == AFV_OK) {
    memcpy(s->r, w.best, (size_t)(2 * s->n) * sizeof(double));
    st = afv_sim_refresh(s);
    rep->max_force = afv_sim_max_force(s);
  }
  rep->energy = s->geom.energy;
  free(w.v);
  return st;
}
