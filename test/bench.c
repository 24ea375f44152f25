/*
** bench.c -- the afv benchmark (make bench, make bench-quick).
**
**   test/bench STATE N [STEPS]
**
** prints one line
**   bench state=STATE N=N steps=S us_per_cell_step=X peak_rss_kb=K threads=T
** where X is the median over REPEATS timed repeats (after one untimed
** warm-up repeat) of  (wall time of S steps) / (S N),  in microseconds,
** K is the peak resident memory of this process (VmHWM), and T the number
** of OpenMP threads (1 in the serial build).
**
** States (periodic, packing fraction N pi l^2 / (Lx Ly) = 0.5, l = 1, the
** paper's KA = KP = 1, A0 = pi, Lambda = 0.2, Dr = 0.1, dt = 0.01, mu = 1,
** and afv run's defaults: exact forces (no cap) with sub-steps where the
** force would move a cell more than max_move = 0.05 l, see dynamics.c):
**   random   afv_init_random centres, P0 = 4.8, v0 = 1;
**   cluster  afv_init_cluster (spacing CLUSTER_SPACING), P0 = 4, v0 = 0.1;
** in both the cells are then numbered in afv_spatial_order.
** Both are first relaxed at v0 = 0 by afv_relax, as afv run does (to
** max |F| <= RELAX_TOL, or RELAX_BUDGET cell-steps but at least
** RELAX_MIN_STEPS: the large cluster is only partly relaxed).  The random
** state at N >= TILED_FROM is TILES x TILES copies of the relaxed random
** state of N / TILES^2 cells (see tiled_random_state).
** A step is one afv_sim_step: the move of every cell, then neighbour
** search, shapes, energy and forces.  The states random-force and
** cluster-force time afv_compute alone (one force evaluation per "step")
** on the same starting configurations.
** Each measurement runs in its own process so that the peak memory is that
** of one N.  POSIX (clock_gettime, /proc) is fine here: this is not the
** library.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define PI 3.14159265358979323846
#define PHI 0.5            /* packing fraction N pi l^2 / (Lx Ly) */
#define REPEATS 5          /* timed repeats; the median is printed */
#define SEED 1             /* of the random centres and angles */
#define CLUSTER_SPACING 1.43 /* lattice constant of the initial cluster, in
                             ** l: the bulk spacing of the relaxed N = 400
                             ** cluster at P0 = 4 (measured), so that the
                             ** budgeted relaxation of large N gets close */
#define RELAX_TOL 1e-6     /* afv run's default relaxation tolerance */
#define RELAX_BUDGET 1e7   /* relaxation cell-steps: keeps make bench short */
#define RELAX_MIN_STEPS 20
#define TILES 10           /* the random state at N >= TILED_FROM: TILES^2 */
#define TILED_FROM 40000   /* copies of the relaxed state of N / TILES^2 */
/* Steps per repeat, the same for every N, so that every N is timed at the
** same age of its state (steps 20 to 120 after the relaxation): the random
** state costs more per cell as it ages (its active cells collide and make
** contacts; at N = 400 1.3x - 1.4x from steps 20 - 120 to steps 2000 -
** 12000), so repeats sized by N (2000 steps at N = 400, 20 at 40000, as in
** an earlier version) compared an old small state with a young large one.
** 20 steps also hold one to three rebuilds of the neighbour candidates
** (geom.c: one every 16.7 steps at N = 400, 12.5 at 40000, 10 at 400000,
** each costing about half a step): with 4 or 5 steps a repeat held
** a rebuild or none (at N = 40000 one with a rebuild took up to 1.8x one
** without). */
#define STEPS_PER_REPEAT 20

/* ---- states ------------------------------------------------------------ */
/* Renumbers the cells in the order of afv_spatial_order, so that neighbours
** are close in memory (the order a simulation should give its cells). */
static int spatial_order(int n, double *r, const afv_box *b)
{
  int *perm = malloc((size_t)n * sizeof *perm), k, st;
  double *copy = malloc((size_t)n * 2 * sizeof *copy);
  st = perm && copy ? afv_spatial_order(n, r, 1.0, b, perm) : AFV_ENOMEM;
  if (st == AFV_OK) {
    memcpy(copy, r, (size_t)n * 2 * sizeof *copy);
    for (k = 0; k < n; k++) {
      r[2*k] = copy[2*perm[k]];
      r[2*k+1] = copy[2*perm[k]+1];
    }
  }
  free(perm);
  free(copy);
  return st;
}

/* The random state at n = TILES^2 m cells (m >= 400): TILES x TILES copies
** of the relaxed random state of m cells (same seed), in a box TILES times
** as wide, with n fresh angles.  A relaxation of n cells within the budget
** would stop far from converged at large n (about 25 FIRE iterations at
** n = 400000), and a less relaxed tissue costs more per cell (larger
** forces: more sub-steps and candidate rebuilds); the tiles give every n
** the local structure of a relaxed random tissue, so that the per-cell
** figures compare the code at different n, not different states. */
static int make_state(afv_sim *s, int cluster, int n);

static int tiled_random_state(afv_sim *s, int n)
{
  afv_sim tile;
  afv_params p;
  afv_box b;
  afv_dyn d;
  int m = n / (TILES * TILES), a, c, k, st;
  double *r = malloc((size_t)n * 2 * sizeof *r);
  double *th = malloc((size_t)n * sizeof *th);
  memset(&tile, 0, sizeof tile);
  st = r && th ? make_state(&tile, 0, m) : AFV_ENOMEM;
  if (st == AFV_OK) {
    b = tile.box;
    b.Lx *= TILES;
    b.Ly *= TILES;
    for (a = 0; a < TILES; a++)
      for (c = 0; c < TILES; c++)
        for (k = 0; k < m; k++) {
          double x = tile.r[2*k], y = tile.r[2*k+1];
          int q = (a * TILES + c) * m + k;
          afv_wrap(&tile.box, &x, &y);
          r[2*q] = x + a * tile.box.Lx;
          r[2*q+1] = y + c * tile.box.Ly;
        }
    p = tile.par;
    d = tile.dyn;
    afv_init_angles(n, SEED, th);
    st = spatial_order(n, r, &b);
  }
  if (st == AFV_OK) st = afv_sim_init(s, n, r, th, &p, &b, &d);
  afv_sim_free(&tile);
  free(r);
  free(th);
  return st;
}

/* The starting simulation of a state; 0 on success, else a status. */
static int make_state(afv_sim *s, int cluster, int n)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_relax_report rep;
  double *r = malloc((size_t)n * 2 * sizeof *r);
  double *th = malloc((size_t)n * sizeof *th);
  int st = AFV_ENOMEM;
  if (!cluster && n >= TILED_FROM && n % (TILES * TILES) == 0) {
    free(r);
    free(th);
    return tiled_random_state(s, n);
  }
  if (!r || !th) goto done;
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.seed = SEED;
  d.v0 = 0;
  b.periodic = 1;
  b.Lx = b.Ly = sqrt(n * PI / PHI);
  afv_init_angles(n, SEED, th);
  p.P0 = cluster ? 4.0 : 4.8;
  st = AFV_OK;
  if (cluster) st = afv_init_cluster(n, CLUSTER_SPACING, &b, r);
  else afv_init_random(n, SEED, &b, 0, r);
  if (st == AFV_OK) st = spatial_order(n, r, &b);
  if (st == AFV_OK) st = afv_sim_init(s, n, r, th, &p, &b, &d);
  if (st == AFV_OK)
    st = afv_relax(s, RELAX_TOL, (long)fmax(RELAX_MIN_STEPS, RELAX_BUDGET / n),
                   &rep, NULL, NULL);
  s->dyn.v0 = cluster ? 0.1 : 1.0;
done:
  free(r);
  free(th);
  return st;
}

/* ---- measurement ------------------------------------------------------- */
static double now_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Peak resident set in kB: VmHWM from /proc, else getrusage (kB on Linux). */
static long peak_rss_kb(void)
{
  char line[256];
  long kb = -1;
  FILE *fp = fopen("/proc/self/status", "r");
  if (fp) {
    while (fgets(line, sizeof line, fp))
      if (strncmp(line, "VmHWM:", 6) == 0) kb = strtol(line + 6, NULL, 10);
    fclose(fp);
  }
  if (kb < 0) {
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) == 0) kb = ru.ru_maxrss;
  }
  return kb;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static int threads(void)
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/* Times `steps` steps (force evaluations only if force_only); returns
** seconds, or -1 on a library error. */
static double time_steps(afv_sim *s, int force_only, int steps)
{
  double t0 = now_seconds();
  int k, st = AFV_OK;
  for (k = 0; k < steps && st == AFV_OK; k++)
    st = force_only ? afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f)
                    : afv_sim_step(s);
  if (st != AFV_OK) {
    fprintf(stderr, "bench: %s\n", afv_strerror(st));
    return -1;
  }
  return now_seconds() - t0;
}

int main(int argc, char **argv)
{
  static const char *states[] = {"random", "cluster", "random-force",
                                 "cluster-force"};
  afv_sim sim;
  double t[REPEATS];
  int n, steps, k, state = -1, st;
  if (argc >= 2)
    for (k = 0; k < 4; k++)
      if (strcmp(argv[1], states[k]) == 0) state = k;
  if (argc < 3 || argc > 4 || state < 0) {
    fprintf(stderr, "usage: bench random|cluster|random-force|cluster-force "
            "N [STEPS]\n");
    return 2;
  }
  n = atoi(argv[2]);
  if (n < 2) {
    fprintf(stderr, "bench: N must be >= 2\n");
    return 2;
  }
  steps = argc > 3 ? atoi(argv[3]) : STEPS_PER_REPEAT;
  if (steps < 1) {
    fprintf(stderr, "bench: STEPS must be >= 1\n");
    return 2;
  }
  memset(&sim, 0, sizeof sim);
  if ((st = make_state(&sim, state % 2, n)) != AFV_OK) {
    fprintf(stderr, "bench: %s\n", afv_strerror(st));
    return 1;
  }
  if (time_steps(&sim, state >= 2, steps) < 0) return 1;   /* warm-up */
  for (k = 0; k < REPEATS; k++)
    if ((t[k] = time_steps(&sim, state >= 2, steps)) < 0) return 1;
  qsort(t, REPEATS, sizeof t[0], cmp_double);
  printf("bench state=%s N=%d steps=%d us_per_cell_step=%.4g "
         "peak_rss_kb=%ld threads=%d\n", argv[1], n, steps,
         1e6 * t[REPEATS / 2] / ((double)steps * n), peak_rss_kb(), threads());
  afv_sim_free(&sim);
  return 0;
}
