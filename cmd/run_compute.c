/*
** run_compute.c -- what a run can compute, checked before anything is
** made: no energy, force, clock or angle noise that overflows, and a state
** the outputs can record (finite)
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "run.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* ---- what a run can compute --------------------------------------------- */
/* The run later multiplies the energy and the squared force norm checked
** here by modest factors (the relaxation's energy window): a value within
** COMPUTE_HEADROOM of the largest double is refused, so those products stay
** finite: |F|^2 summed over the cells above 1.8e302, or an energy bound
** above 1.8e302 (at the paper's values, KA = KP = 1 and N = 400, the
** bound is about 1e4). */
#define COMPUTE_HEADROOM 1e6

/* The three terms of a cell's energy (paper, Eq. energy), by modulus key. */
enum { TERM_AREA, TERM_PERIM, TERM_ARC, N_TERMS };
static const char *const term_key[N_TERMS] = {"KA", "KP", "Lambda"};
static const char *const term_name[N_TERMS] = {
  "area term KA (A - A0)^2", "perimeter term KP (P - P0)^2",
  "arc term Lambda L"};

/* The modulus of term k of cell i and the target it pulls to (A0, P0). */
static double term_modulus(const afv_params *p, int i, int k, double *target)
{
  *target = 0;
  if (k == TERM_AREA) {
    *target = p->A0_i ? p->A0_i[i] : p->A0;
    return p->KA_i ? p->KA_i[i] : p->KA;
  }
  if (k == TERM_PERIM) {
    *target = p->P0_i ? p->P0_i[i] : p->P0;
    return p->KP_i ? p->KP_i[i] : p->KP;
  }
  return p->Lambda;
}

/* The largest value term k of cell i takes over every shape the cell can
** have: 0 <= A <= pi l^2 and 0 <= P, L <= 2 pi l (the cell is a convex set
** inside its disk of radius l, so its perimeter is at most the circle's).
** *dev2: the largest squared deviation alone, (A - A0)^2 or (P - P0)^2. */
static double term_bound(const afv_params *p, int i, int k, double *dev2)
{
  const double pi = 3.14159265358979323846;
  double target, m = term_modulus(p, i, k, &target), top, dev;
  top = k == TERM_AREA ? pi * p->l * p->l : 2 * pi * p->l;
  if (k == TERM_ARC) {
    *dev2 = 0;
    return fabs(m) * top;
  }
  dev = fmax(fabs(target), fabs(top - target));
  *dev2 = dev * dev;
  return m * *dev2;
}

/* "KEY: VALUE", or "KEY (cells file, cell 12): VALUE" when the value is
** the cell's own (column, of the cells file, is not NULL). */
static void value_label(char *buf, size_t len, const char *key,
                        const double *column, int cell, double value)
{
  if (column)
    snprintf(buf, len, "%s (cells file, cell %d): %g", key, cell, value);
  else
    snprintf(buf, len, "%s: %g", key, value);
}

/* value_label of term k's modulus (or, target_key = 1, of its target). */
static void term_label(char *buf, size_t len, const afv_params *p, int k,
                       int cell, int target_key)
{
  static const char *const target_key_name[N_TERMS] = {"A0", "P0", ""};
  const double *own[N_TERMS][2] = {{p->KA_i, p->A0_i}, {p->KP_i, p->P0_i},
                                   {NULL, NULL}};
  double target, m = term_modulus(p, cell, k, &target);
  value_label(buf, len, target_key ? target_key_name[k] : term_key[k],
              own[k][target_key], cell, target_key ? target : m);
}

static int huge(double x)
{
  return !isfinite(x * COMPUTE_HEADROOM);
}

/* 1 if no state can overflow the energy: each term's bound, summed over
** the cells, and their total are within the headroom.  Else names the key
** (the target A0 or P0 when the deviation alone overflows). */
int energy_computable(const afv_params *p, int n, char *err, size_t errlen)
{
  double sum[N_TERMS] = {0, 0, 0};
  int i, k, worst_cell[N_TERMS] = {0, 0, 0}, worst_k = 0;
  for (k = 0; k < N_TERMS; k++) {
    double worst = -1;
    for (i = 0; i < n; i++) {
      double dev2, b = term_bound(p, i, k, &dev2);
      if (huge(dev2)) {   /* A0 or P0 far out, or the cell's size */
        char label[96];
        double target;
        term_modulus(p, i, k, &target);
        if (huge(target * target))
          term_label(label, sizeof label, p, k, i, 1);
        else
          snprintf(label, sizeof label, "l: %g", p->l);
        afv_errorf(err, errlen, "%s: the %s cannot be computed: its squared "
                   "deviation reaches %g", label, term_name[k], dev2);
        return 0;
      }
      if (!(b <= worst)) {
        worst = b;
        worst_cell[k] = i;
      }
      sum[k] += b;
    }
    if (!(sum[k] <= sum[worst_k])) worst_k = k;
  }
  if (!huge(sum[0] + sum[1] + sum[2])) return 1;
  for (k = 0; k < N_TERMS; k++)
    if (huge(sum[k])) break;
  if (k == N_TERMS) k = worst_k;
  {
    char label[96];
    term_label(label, sizeof label, p, k, worst_cell[k], 0);
    afv_errorf(err, errlen, "%s: the %s can reach %g summed over the %d "
               "cells, beyond %g (the largest double over a margin of %g "
               "for the sums the run forms)", label, term_name[k], sum[k],
               n, DBL_MAX / COMPUTE_HEADROOM, COMPUTE_HEADROOM);
  }
  return 0;
}

/* The term of the largest energy in the current state (its key names
** what makes the forces large). */
static int largest_term(afv_sim *s)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *A = afv_geom_area(g), *P = afv_geom_perim(g);
  const double *L = afv_geom_arc(g);
  double sum[N_TERMS] = {0, 0, 0};
  int i, k, best = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    double target, m;
    m = term_modulus(afv_sim_params(s), i, TERM_AREA, &target);
    sum[TERM_AREA] += fabs(m * (A[i] - target) * (A[i] - target));
    m = term_modulus(afv_sim_params(s), i, TERM_PERIM, &target);
    sum[TERM_PERIM] += fabs(m * (P[i] - target) * (P[i] - target));
    sum[TERM_ARC] += fabs(afv_sim_params(s)->Lambda * L[i]);
  }
  for (k = 1; k < N_TERMS; k++)
    if (sum[k] > sum[best]) best = k;
  return best;
}

/* 1 if the forces of the current state can be computed with: |F|^2 summed
** over the cells (what the relaxation forms) within the headroom. */
static int forces_computable(afv_sim *s, char *err, size_t errlen)
{
  char label[96];
  const double *f = afv_sim_forces(s);
  double f2 = 0, fmax = -1;
  int i, k, worst = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    double q = f[2*i] * f[2*i] + f[2*i+1] * f[2*i+1];
    if (!(q <= fmax)) {
      fmax = q;
      worst = i;
    }
    f2 += q;
  }
  if (!huge(f2)) return 1;
  k = largest_term(s);
  term_label(label, sizeof label, afv_sim_params(s), k, worst, 0);
  afv_errorf(err, errlen, "%s: the forces of the state overflow (|F|^2 "
             "summed over the cells is %g, beyond %g; largest at cell %d), "
             "and the %s dominates its energy", label, f2,
             DBL_MAX / COMPUTE_HEADROOM, worst, term_name[k]);
  return 0;
}

/* 1 if the clock, the step's factors and the angle noise stay finite for
** the whole run: t = step dt up to steps; mu dt and v0 dt (a step moves a
** cell by mu dt F + v0 dt n, so an overflow there would blame a finite
** force); sqrt(2 Dr dt) (as the step computes it;
** then |theta| grows by at most 8.57 sqrt(2 Dr dt) a step, which cannot
** reach the largest double within 2^63 steps). */
static int dynamics_computable(afv_sim *s, long long steps, char *err,
                               size_t errlen)
{
  const afv_dyn *d = afv_sim_dyn(s);
  int i;
  if (huge((double)steps * d->dt)) {
    afv_errorf(err, errlen, "dt: %g: the time of the last step, steps x dt "
               "= %lld x %g, overflows", d->dt, steps, d->dt);
    return 0;
  }
  if (huge(d->mu * d->dt)) {
    afv_errorf(err, errlen, "mu: %g: the step's factor mu dt overflows (dt "
               "= %g)", d->mu, d->dt);
    return 0;
  }
  for (i = 0; i < afv_sim_n(s); i++) {
    double v0 = d->v0_i ? d->v0_i[i] : d->v0;
    double Dr = d->Dr_i ? d->Dr_i[i] : d->Dr;
    char label[96];
    if (huge(v0 * d->dt)) {
      value_label(label, sizeof label, "v0", d->v0_i, i, v0);
      afv_errorf(err, errlen, "%s: the step's self-propulsion v0 dt "
                 "overflows (dt = %g)", label, d->dt);
      return 0;
    }
    if (!isfinite(sqrt(2 * Dr * d->dt))) {
      value_label(label, sizeof label, "Dr", d->Dr_i, i, Dr);
      afv_errorf(err, errlen, "%s: the angle noise sqrt(2 Dr dt) overflows "
                 "(dt = %g)", label, d->dt);
      return 0;
    }
  }
  return 1;
}

/* ---- a state the outputs can record ------------------------------------ */
/* What of cell i is not finite, with its value, into buf ("" if none). */
static void cell_nonfinite(afv_sim *s, int i, char *buf, size_t len)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *r = afv_sim_positions(s) + 2 * i;
  const double *f = afv_sim_forces(s) + 2 * i, th = afv_sim_angles(s)[i];
  const double A = afv_geom_area(g)[i], P = afv_geom_perim(g)[i];
  const double L = afv_geom_arc(g)[i];
  buf[0] = 0;
  if (!isfinite(r[0]) || !isfinite(r[1]))
    snprintf(buf, len, "position (%g, %g)", r[0], r[1]);
  else if (!isfinite(th))
    snprintf(buf, len, "polarity angle %g", th);
  else if (!isfinite(f[0]) || !isfinite(f[1]))
    snprintf(buf, len, "force (%g, %g)", f[0], f[1]);
  else if (!isfinite(A) || !isfinite(P) || !isfinite(L))
    snprintf(buf, len, "shape (area %g, perimeter %g, arc length %g)", A, P,
             L);
  else if (!isfinite(afv_cell_energy(afv_sim_params(s), i, A, P, L)))
    snprintf(buf, len, "energy");
}

/* 1 if everything the outputs record of the state is finite; else msg
** says what is not: the first three such cells and their values, or the
** total energy or the time. */
int state_finite(afv_sim *s, char *msg, size_t len)
{
  char what[192];
  int i, named = 0;
  msg[0] = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    cell_nonfinite(s, i, what, sizeof what);
    if (!what[0]) continue;
    if (named < 3)
      afv_errorf(msg + strlen(msg), len - strlen(msg), "%scell %d's %s",
                 named ? ", " : "not finite: ", i, what);
    named++;
  }
  if (named > 3)
    afv_errorf(msg + strlen(msg), len - strlen(msg), " (and %d more cells)",
               named - 3);
  else if (!named && !isfinite(afv_geom_energy(afv_sim_geom(s))))
    afv_errorf(msg, len, "not finite: the total energy (%g), each cell's "
               "being finite", afv_geom_energy(afv_sim_geom(s)));
  else if (!named && !isfinite(afv_sim_time(s)))
    afv_errorf(msg, len, "not finite: the time t = %g", afv_sim_time(s));
  return msg[0] == 0;
}

/* Everything the run will compute from the state R->sim (the start, or a
** checkpoint: where names it): the state itself finite, no energy overflow
** in any state, the forces of this one, the clock and the angle noise.
** Else err names the key, or the cells and what of them is not finite. */
int run_computable(const run_state *R, const char *where, char *err,
                          size_t errlen)
{
  char what[512];
  if (!energy_computable(afv_sim_params(R->sim), afv_sim_n(R->sim), err,
                         errlen)
      || !dynamics_computable(R->sim, R->cfg.steps, err, errlen))
    return 0;
  if (!state_finite(R->sim, what, sizeof what)) {
    afv_errorf(err, errlen, "%s: %s", where, what);
    return 0;
  }
  return forces_computable(R->sim, err, errlen);
}

/* The start of cfg (cells cl, borrowed) built and checked as afv run
** checks it before it creates anything (run_start, run_computable). */
int start_computable(const run_cfg *cfg, const afv_cells *cl,
                            char *err, size_t errlen)
{
  run_state *R = calloc(1, sizeof *R);
  int ok;
  if (!R) {
    afv_errorf(err, errlen, "out of memory");
    return 0;
  }
  R->cfg = *cfg;
  R->cells = *cl;
  R->lock_fd = R->dir_fd = -1;
  ok = (R->sim = afv_sim_new()) != NULL && run_start(R, err, errlen) == AFV_OK
       && run_computable(R, "the start", err, errlen);
  if (!R->sim) afv_errorf(err, errlen, "out of memory");
  afv_sim_delete(R->sim);
  free(R);
  return ok;
}
