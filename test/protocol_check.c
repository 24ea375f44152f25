/*
** protocol_check.c -- evidence for the paper's protocol (make
** protocol-check; issue 19, items 2 and 3).  Not a unit test: it takes
** about an hour on two cores at its full size.
**
**   test/protocol_check [--N N] [--steps S] [--seeds-relax K] [--seeds-run M]
**                       [--P0 a,b,...] [--v0 a,b,...] [--jobs J]
**
** Defaults: N = 400, phi = 0.5, P0 in {4, 4.4, 4.8, 5.2, 5.6, 6, 6.4, 7.2,
** 8, 8.8}, seeds 1 .. 5 relaxed, seeds 1 .. 3 run, v0 in {0, 0.1, 0.5, 1,
** 1.85, 2.7}, 10^5 steps of dt = 0.01, the paper's other parameters, the
** paper's Euler step with the exact force (afv run's).
**
** For every P0: the lattice start (afv_init_lattice, spacing 1.8 l, afv
** run's init lattice) relaxed, for its mean area A_lat.  For every seed:
** the authors' start (afv run's init cluster: afv_init_cluster, side 0.3 L)
** relaxed by afv_relax with afv run's defaults (tol 1e-6, 100000 steps).
** The relaxation FAILS if its mean area is not within 10% of A_lat, or if
** it neither converged (max |F| <= tol) nor stopped at a kink, or if it
** says kink with max |F| above AFV_RELAX_KINK_FORCE.  For seeds 1 .. M, the
** relaxed state is then run for S steps at each v0 (the same library calls
** as afv run: afv_sim_step); the run FAILS unless every step is taken
** (exit status as afv run's: 0 done, 3 a refused step, 2 another error).
**
** One line per (P0, v0, seed) (v0 "-" for a seed only relaxed, printed
** when relaxed; the runs follow, see worker()):
**   P0 v0 seed relax_steps max_F stop mean_area area_vs_lattice exit
**   jumps wall (relaxation + run, s) [FAIL: why]
** (jumps: the Euler steps that moved a cell more than AFV_MAX_STEP_DISP l,
** in the relaxation or in the relaxation and the run.)
** and last `protocol: R runs, F failed` (R counts relaxations and runs).
** --jobs J: J worker processes share the P0 values (lines then come in
** the order they finish).  Wall times are on a shared machine.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define MAX_LIST 32
#define PI 3.14159265358979323846

typedef struct plan {
  int N;
  long long steps;
  int seeds_relax, seeds_run, jobs;
  double P0[MAX_LIST], v0[MAX_LIST];
  int nP0, nv0;
} plan;

static double wall(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int parse_list(const char *text, double *out)
{
  int n = 0;
  char *end;
  while (*text && n < MAX_LIST) {
    out[n++] = strtod(text, &end);
    if (end == text) return 0;
    text = *end == ',' ? end + 1 : end;
  }
  return n;
}

static double mean_area(const afv_sim *s)
{
  double A = 0;
  int i;
  for (i = 0; i < s->n; i++) A += s->geom.area[i];
  return A / s->n;
}

/* The model and dynamics of the check: the paper's values (afv run's
** defaults) at P0, in the periodic box of packing fraction 0.5. */
static void model(const plan *P, double P0, unsigned long long seed,
                  afv_params *p, afv_box *b, afv_dyn *d)
{
  afv_params_default(p);
  p->P0 = P0;
  afv_dyn_default(d);
  d->seed = seed;
  b->periodic = 1;
  b->Lx = b->Ly = sqrt(P->N * PI / 0.5);
}

/* Relaxes the start r (lattice or authors') at P0; the state stays in s. */
static int relax(const plan *P, double P0, unsigned long long seed,
                 int lattice, afv_sim *s, afv_relax_report *rep)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  double *r = malloc((size_t)(2 * P->N) * sizeof(double));
  double *th = malloc((size_t)P->N * sizeof(double));
  int st;
  if (!r || !th) return AFV_ENOMEM;
  model(P, P0, seed, &p, &b, &d);
  if (lattice) afv_init_lattice(P->N, 1.8, &b, r);
  else afv_init_cluster(P->N, seed, &b, 0.3 * b.Lx, r);
  afv_init_angles(P->N, seed, th);
  st = afv_sim_init(s, P->N, r, th, &p, &b, &d);
  if (st == AFV_OK) st = afv_relax(s, 1e-6, 100000, rep, NULL, NULL);
  free(r);
  free(th);
  return st;
}

static const char *stop_reason(const afv_relax_report *rep)
{
  return rep->converged ? "converged" : rep->at_kink ? "kink"
         : rep->refused ? "refused" : "not-reached";
}

/* Why the relaxation failed ("" if it did not). */
static const char *relax_failure(int st, const afv_relax_report *rep,
                                 double area, double area_lat)
{
  if (st != AFV_OK) return "relaxation error";
  if (rep->refused) return "relaxation refused a step";
  if (!rep->converged && !rep->at_kink) return "relaxation not reached";
  if (rep->at_kink && !(rep->max_force <= AFV_RELAX_KINK_FORCE))
    return "kink claimed with a large force";
  if (!(fabs(area / area_lat - 1) <= 0.1)) return "mean area off by > 10%";
  return "";
}

/* afv run's exit status for a library status of afv_sim_step. */
static int exit_status(int st)
{
  if (st == AFV_OK) return 0;
  if (st == AFV_EUNSTABLE || st == AFV_ECOINCIDENT || st == AFV_ENONFINITE)
    return 3;
  return 2;
}

/* A relaxed start kept for the runs (seeds 1 .. M). */
typedef struct relaxed {
  afv_sim s;
  afv_relax_report rep;
  double area, area_lat, wall;
  int ok;
} relaxed;

/* Relaxes the authors' start of (P0, seed) into R; prints the line of a
** seed that is only relaxed (or whose relaxation failed); returns the
** failures (0 or 1). */
static int relax_pair(const plan *P, double P0, int seed, double area_lat,
                      relaxed *R)
{
  double t0 = wall();
  const char *why;
  int st;
  memset(R, 0, sizeof *R);
  st = relax(P, P0, (unsigned long long)seed, 0, &R->s, &R->rep);
  R->wall = wall() - t0;
  R->area = st == AFV_OK ? mean_area(&R->s) : NAN;
  R->area_lat = area_lat;
  R->ok = st == AFV_OK;
  why = relax_failure(st, &R->rep, R->area, area_lat);
  if (seed > P->seeds_run || why[0]) {
    printf("P0 %-4g v0 -    seed %d relax %6ld max_F %.3e %-11s area %.4f "
           "(%+.1f%%) exit - jumps %lld wall %.1f s%s%s\n",
           P0, seed, R->rep.iterations, R->rep.max_force,
           stop_reason(&R->rep), R->area, 100 * (R->area / area_lat - 1),
           R->rep.jumps, R->wall, why[0] ? "  FAIL: " : "", why);
    fflush(stdout);
  }
  return why[0] != 0;
}

/* Runs the relaxed start R at v0 for P->steps steps; prints its line;
** returns the failures (0 or 1). */
static int run_pair(const plan *P, double P0, int seed, double v0,
                    const relaxed *R)
{
  afv_sim s;
  long long i;
  double t0 = wall();
  int st = AFV_ENOMEM, code;
  memset(&s, 0, sizeof s);
  if (R->ok)
    st = afv_sim_init(&s, R->s.n, R->s.r, R->s.theta, &R->s.par, &R->s.box,
                      &R->s.dyn);
  s.dyn.v0 = v0;
  for (i = 0; i < P->steps && st == AFV_OK; i++) st = afv_sim_step(&s);
  code = exit_status(st);
  printf("P0 %-4g v0 %-4g seed %d relax %6ld max_F %.3e %-11s area %.4f "
         "(%+.1f%%) exit %d jumps %lld wall %.1f+%.1f s",
         P0, v0, seed, R->rep.iterations, R->rep.max_force,
         stop_reason(&R->rep), R->area, 100 * (R->area / R->area_lat - 1),
         code, R->rep.jumps + s.jumps, R->wall, wall() - t0);
  if (code != 0)
    printf("  FAIL: step %lld: %s, cell %d would move %g l in %g", s.step + 1,
           afv_strerror(st), s.bad_cell, s.bad_disp, s.dyn.dt);
  printf("\n");
  fflush(stdout);
  afv_sim_free(&s);
  return code != 0;
}

/* The lattice reference of every P0: its relaxed mean area. */
static void lattice_areas(const plan *P, double *area_lat)
{
  int k;
  for (k = 0; k < P->nP0; k++) {
    afv_sim s;
    afv_relax_report rep;
    memset(&s, 0, sizeof s);
    if (relax(P, P->P0[k], 1, 1, &s, &rep) != AFV_OK) {
      area_lat[k] = NAN;
      continue;
    }
    area_lat[k] = mean_area(&s);
    printf("# lattice start P0 %g: relax %ld steps, max_F %.3e %s, mean "
           "area %.4f\n", P->P0[k], rep.iterations, rep.max_force,
           stop_reason(&rep), area_lat[k]);
    afv_sim_free(&s);
  }
  fflush(stdout);
}

/* Worker w of J takes the P0 with k % J == w: first it relaxes them for
** every seed (item 2), then runs them seed by seed, the largest v0 first,
** so that a partial output covers the whole range of P0 and the v0 that
** stress the step most. */
static int worker(const plan *P, const double *area_lat, int w)
{
  relaxed *R = calloc((size_t)(P->nP0 * P->seeds_run) + 1, sizeof *R);
  int k, seed, q, failed = 0;
  if (!R) return 1;
  for (seed = 1; seed <= P->seeds_relax; seed++)
    for (k = w; k < P->nP0; k += P->jobs) {
      relaxed tmp, *dst = seed <= P->seeds_run
                          ? &R[(seed - 1) * P->nP0 + k] : &tmp;
      failed += relax_pair(P, P->P0[k], seed, area_lat[k], dst);
      if (dst == &tmp) afv_sim_free(&tmp.s);
    }
  for (seed = 1; seed <= P->seeds_run; seed++)
    for (q = P->nv0 - 1; q >= 0; q--)
      for (k = w; k < P->nP0; k += P->jobs)
        failed += run_pair(P, P->P0[k], seed, P->v0[q],
                           &R[(seed - 1) * P->nP0 + k]);
  for (k = 0; k < P->nP0 * P->seeds_run; k++) afv_sim_free(&R[k].s);
  free(R);
  return failed;
}

static int parse_args(int argc, char **argv, plan *P)
{
  static const double P0s[] = {4, 4.4, 4.8, 5.2, 5.6, 6, 6.4, 7.2, 8, 8.8};
  static const double v0s[] = {0, 0.1, 0.5, 1, 1.85, 2.7};
  int k;
  P->N = 400;
  P->steps = 100000;
  P->seeds_relax = 5;
  P->seeds_run = 3;
  P->jobs = 1;
  P->nP0 = 10;
  P->nv0 = 6;
  memcpy(P->P0, P0s, sizeof P0s);
  memcpy(P->v0, v0s, sizeof v0s);
  for (k = 1; k + 1 < argc; k += 2) {
    const char *o = argv[k], *v = argv[k + 1];
    if (!strcmp(o, "--N")) P->N = atoi(v);
    else if (!strcmp(o, "--steps")) P->steps = atoll(v);
    else if (!strcmp(o, "--seeds-relax")) P->seeds_relax = atoi(v);
    else if (!strcmp(o, "--seeds-run")) P->seeds_run = atoi(v);
    else if (!strcmp(o, "--jobs")) P->jobs = atoi(v);
    else if (!strcmp(o, "--P0")) P->nP0 = parse_list(v, P->P0);
    else if (!strcmp(o, "--v0")) P->nv0 = parse_list(v, P->v0);
    else return 0;
  }
  return k == argc && P->N > 0 && P->jobs > 0 && P->nP0 > 0 && P->nv0 > 0
         && P->seeds_run <= P->seeds_relax;
}

int main(int argc, char **argv)
{
  plan P;
  double area_lat[MAX_LIST];
  int w, failed = 0, runs;
  if (!parse_args(argc, argv, &P)) {
    fprintf(stderr, "usage: protocol_check [--N N] [--steps S] "
            "[--seeds-relax K] [--seeds-run M<=K] [--P0 a,b] [--v0 a,b] "
            "[--jobs J]\n");
    return 2;
  }
  printf("# protocol check: N %d, phi 0.5, %lld steps of dt 0.01, seeds "
         "1..%d relaxed, 1..%d run (timings on a shared machine)\n", P.N,
         P.steps, P.seeds_relax, P.seeds_run);
  lattice_areas(&P, area_lat);
  runs = P.nP0 * (P.seeds_relax + P.seeds_run * P.nv0);
  if (P.jobs == 1) failed = worker(&P, area_lat, 0);
  else {
    for (w = 0; w < P.jobs; w++)
      if (fork() == 0) {
        int f = worker(&P, area_lat, w);
        _exit(f > 250 ? 250 : f);
      }
    for (w = 0; w < P.jobs; w++) {
      int status;
      if (wait(&status) < 0 || !WIFEXITED(status)) failed++;
      else failed += WEXITSTATUS(status);
    }
  }
  printf("protocol: %d runs, %d failed\n", runs, failed);
  return failed != 0;
}
