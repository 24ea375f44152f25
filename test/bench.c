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
** and afv run's defaults: the paper's Euler step with exact forces (no
** cap), see dynamics.c):
**   random   afv_init_random centres, P0 = 4.8, v0 = 1;
**   cluster  afv_init_lattice (spacing CLUSTER_SPACING), P0 = 4, v0 = 0.1;
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
**
** Two comparisons (make bench-compare) time two things in turn within one
** process, because separate runs of a virtual machine's wall clock compare
** poorly (doc/performance.md):
**   test/bench --vs-400 random|cluster N [COPIES]
**     the per-cell cost of N over that of 400 at the same age of the two
**     states (compare_sizes); prints
**     compare state=STATE N=N vs=400 us_400=X us_N=Y ratio=R copies=C
**       threads=T
**   test/bench --numbering random|cluster N [STEPS]
**     the state as numbered (afv_spatial_order) against the same state
**     with its cells numbered at random, as drawn centres come, stepped
**     one step each in turn (compare_numbering); prints
**     numbering state=STATE N=N us_spatial=X us_shuffled=Y ratio=R
**       steps=S threads=T
**   test/bench --relax-vs-400 N P0 [SECONDS]
**     the relaxation of the authors' square (afv_protocol_start, the
**     flow, as afv run makes it) at N against that at 400 cells, in one
**     process: every SECONDS (default 20) of the N-cell relaxation's CPU
**     time its monitor runs one whole 400-cell relaxation (seeds 1, 2,
**     ...), timed apart (compare_relax); prints
**     relax N=N P0=P0 steps=S stop=STOP us_N=X us_400=Y ratio=R
**       samples=K ms_per_cell=M peak_rss_kb=K
**     with X, Y the CPU time per cell and step (one step is 0.01 of
**     relaxed time) and M the N-cell relaxation's CPU time per cell.
**   test/bench --threads random|cluster N [CHUNKS]     (OpenMP build)
**     1 against 2 threads on the same steps, and what 2 threads give
**     for a loop of independent arithmetic at the same moments
**     (compare_threads); prints
**     threads state=STATE N=N speedup=X reference_speedup=Y chunks=C
*/
#define _POSIX_C_SOURCE 200809L
#include "afv_internal.h"

#include <errno.h>
#include <limits.h>
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
** (neighbours.c: one every 16.7 steps at N = 400, 12.5 at 40000, 10 at 400000,
** each costing about half a step): with 4 or 5 steps a repeat held
** a rebuild or none (at N = 40000 one with a rebuild took up to 1.8x one
** without). */
#define STEPS_PER_REPEAT 20

/* ---- states ------------------------------------------------------------ */
/* The random state at n = TILES^2 m cells (m >= 400): TILES x TILES copies
** of the relaxed random state of m cells (same seed), in a box TILES times
** as wide, with n fresh angles.  A relaxation of n cells within the budget
** would stop far from converged at large n (about 25 relaxation steps at
** n = 400000), and a less relaxed tissue costs more per cell (larger
** forces: more candidate rebuilds); the tiles give every n
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
    st = afv_spatial_renumber(n, r, 1.0, &b);
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
  if (cluster) st = afv_init_lattice(n, CLUSTER_SPACING, &b, r);
  else afv_init_random(n, SEED, &b, 0, r);
  if (st == AFV_OK) st = afv_spatial_renumber(n, r, 1.0, &b);
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

/* ---- comparisons ------------------------------------------------------- */
#define SMALL_N 400
#define COMPARE_WARM 20     /* untimed steps before the timed ones */

/* The per-cell cost of the n-cell state over that of the SMALL_N one, at
** the same age and in the same machine mode: `copies` fresh copies of the
** SMALL_N state are each stepped COMPARE_WARM steps untimed, then `copies`
** steps timed, alone (so that it runs from its own caches, as a small
** simulation does); between copies the n-cell state (stepped COMPARE_WARM
** steps first) takes one timed step.  Both are so timed over steps
** COMPARE_WARM to COMPARE_WARM + copies of their states, interleaved. */
static int compare_sizes(const char *name, int cluster, int n, int copies)
{
  afv_sim small, big, s;
  double t_small = 0, t_big = 0, t = 0, us_small, us_big;
  int c, st;
  memset(&small, 0, sizeof small);
  memset(&big, 0, sizeof big);
  st = make_state(&small, cluster, SMALL_N);
  if (st == AFV_OK) st = make_state(&big, cluster, n);
  if (st == AFV_OK && time_steps(&big, 0, COMPARE_WARM) < 0) st = -1;
  for (c = 0; c < copies && st == AFV_OK; c++) {
    memset(&s, 0, sizeof s);
    st = afv_sim_init(&s, SMALL_N, small.r, small.theta, &small.par,
                      &small.box, &small.dyn);
    if (st == AFV_OK && time_steps(&s, 0, COMPARE_WARM) < 0) st = -1;
    if (st == AFV_OK && (t = time_steps(&s, 0, copies)) < 0) st = -1;
    t_small += t;
    afv_sim_free(&s);
    if (st == AFV_OK && (t = time_steps(&big, 0, 1)) < 0) st = -1;
    t_big += t;
  }
  afv_sim_free(&small);
  afv_sim_free(&big);
  if (st != AFV_OK) {
    if (st > 0) fprintf(stderr, "bench: %s\n", afv_strerror(st));
    return 1;
  }
  us_small = 1e6 * t_small / ((double)copies * copies * SMALL_N);
  us_big = 1e6 * t_big / ((double)copies * n);
  printf("compare state=%s N=%d vs=%d us_%d=%.4g us_N=%.4g ratio=%.3f "
         "copies=%d threads=%d\n", name, n, SMALL_N, SMALL_N, us_small,
         us_big, us_big / us_small, copies, threads());
  return 0;
}

/* The n-cell state against a copy whose cells are numbered at random (a
** fixed shuffle), each stepped COMPARE_WARM steps untimed, then one timed
** step each in turn, `steps` times: the cost of memory order alone, at
** the same age and machine mode (the two are the same tissue relabelled,
** so their noise differs only in which cell draws which stream). */
static int compare_numbering(const char *name, int cluster, int n, int steps)
{
  afv_sim a, b;
  double t_a = 0, t_b = 0, t = 0, *r = NULL, *th = NULL;
  int *perm = NULL, k, st;
  unsigned long long x = 0x9e3779b97f4a7c15ULL;
  memset(&a, 0, sizeof a);
  memset(&b, 0, sizeof b);
  st = make_state(&a, cluster, n);
  r = malloc((size_t)n * 2 * sizeof *r);
  th = malloc((size_t)n * sizeof *th);
  perm = malloc((size_t)n * sizeof *perm);
  if (st == AFV_OK && (!r || !th || !perm)) st = AFV_ENOMEM;
  for (k = 0; st == AFV_OK && k < n; k++) perm[k] = k;
  for (k = n - 1; st == AFV_OK && k > 0; k--) {    /* Fisher-Yates */
    int j, tmp;
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    j = (int)((x >> 33) % (unsigned long long)(k + 1));
    tmp = perm[k]; perm[k] = perm[j]; perm[j] = tmp;
  }
  for (k = 0; st == AFV_OK && k < n; k++) {
    r[2*k] = a.r[2*perm[k]];
    r[2*k+1] = a.r[2*perm[k]+1];
    th[k] = a.theta[perm[k]];
  }
  if (st == AFV_OK) st = afv_sim_init(&b, n, r, th, &a.par, &a.box, &a.dyn);
  if (st == AFV_OK && (time_steps(&a, 0, COMPARE_WARM) < 0
                       || time_steps(&b, 0, COMPARE_WARM) < 0)) st = -1;
  for (k = 0; k < steps && st == AFV_OK; k++) {
    if ((t = time_steps(&a, 0, 1)) < 0) st = -1;
    t_a += t;
    if (st == AFV_OK && (t = time_steps(&b, 0, 1)) < 0) st = -1;
    t_b += t;
  }
  afv_sim_free(&a);
  afv_sim_free(&b);
  free(r);
  free(th);
  free(perm);
  if (st != AFV_OK) {
    if (st > 0) fprintf(stderr, "bench: %s\n", afv_strerror(st));
    return 1;
  }
  printf("numbering state=%s N=%d us_spatial=%.4g us_shuffled=%.4g "
         "ratio=%.3f steps=%d threads=%d\n", name, n,
         1e6 * t_a / ((double)steps * n), 1e6 * t_b / ((double)steps * n),
         t_b / t_a, steps, threads());
  return 0;
}

/* ---- the relaxation against N ---------------------------------------- */
static double cpu_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The authors' start at n cells and P0 relaxed by the flow to a kink or
** max |F| <= RELAX_TOL, as afv run makes it (seed: of the square and the
** angles); the status, the report in rep. */
static int relax_square(afv_sim *s, int n, double P0, unsigned long long seed,
                        afv_relax_report *rep, afv_relax_monitor mon,
                        void *ctx)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  afv_params_default(&p);
  p.P0 = P0;
  afv_dyn_default(&d);
  d.seed = seed;
  b.periodic = 1;
  b.Lx = b.Ly = sqrt(n * PI / PHI);
  memset(&pr, 0, sizeof pr);
  pr.start = AFV_START_CLUSTER;
  pr.side = AFV_AUTHORS_SQUARE * b.Lx;
  pr.relax = AFV_RELAX_FLOW;
  pr.relax_tol = RELAX_TOL;
  pr.relax_max_steps = 4000000;
  return afv_protocol_start(s, n, &p, &b, &d, &pr, rep, mon, ctx);
}

typedef struct relax_compare {
  double P0, every;        /* seconds of the big relaxation between samples */
  double next, aside;      /* CPU time of the next sample; time in samples */
  double small_time;       /* CPU seconds of the 400-cell relaxations */
  double small_steps;      /* and their steps */
  int samples, status;
} relax_compare;

/* The monitor of the N-cell relaxation: when its CPU time (less the time
** of earlier samples) passes the next mark, one 400-cell relaxation. */
static void sample_small(void *ctx, long iter, double energy, double max_force)
{
  relax_compare *c = ctx;
  afv_sim *small;
  afv_relax_report rep;
  double t0 = cpu_seconds(), t1;
  (void)iter; (void)energy; (void)max_force;
  if (t0 - c->aside < c->next || c->status != AFV_OK) return;
  if (!(small = afv_sim_new())) { c->status = AFV_ENOMEM; return; }
  c->status = relax_square(small, SMALL_N, c->P0,
                           (unsigned long long)(c->samples + 1), &rep, NULL,
                           NULL);
  afv_sim_delete(small);
  t1 = cpu_seconds();
  c->small_time += t1 - t0;
  c->small_steps += (double)rep.iterations;
  c->samples++;
  c->aside += t1 - t0;
  c->next += c->every;
}

static int compare_relax(int n, double P0, double every)
{
  relax_compare c;
  afv_relax_report rep;
  afv_sim *big = afv_sim_new();
  double t0, t_big, us_n, us_small;
  int st;
  memset(&c, 0, sizeof c);
  c.P0 = P0;
  c.every = every;
  if (!big) return 1;
  t0 = cpu_seconds();
  c.next = t0;                          /* a first sample at the start */
  st = relax_square(big, n, P0, SEED, &rep, sample_small, &c);
  c.next = -HUGE_VAL;
  sample_small(&c, 0, 0, 0);            /* and one at the end */
  t_big = cpu_seconds() - t0 - c.aside;
  afv_sim_delete(big);
  if (st == AFV_OK) st = c.status;
  if (st != AFV_OK || rep.iterations == 0 || c.small_steps == 0) {
    fprintf(stderr, "bench: %s\n", st != AFV_OK ? afv_strerror(st)
            : "no relaxation step");
    return 1;
  }
  us_n = 1e6 * t_big / ((double)rep.iterations * n);
  us_small = 1e6 * c.small_time / (c.small_steps * SMALL_N);
  printf("relax N=%d P0=%g steps=%ld stop=%s us_N=%.4g us_400=%.4g "
         "ratio=%.3f samples=%d ms_per_cell=%.4g peak_rss_kb=%ld\n", n, P0,
         rep.iterations, rep.converged ? "converged" : rep.at_kink ? "kink"
         : rep.refused ? "refused" : "max_steps", us_n, us_small,
         us_n / us_small, c.samples, 1e3 * t_big / n, peak_rss_kb());
  return 0;
}

#ifdef _OPENMP
#define CHUNK_STEPS 12
#define REFERENCE_ITERATIONS 2000000L

/* Seconds for a loop of independent arithmetic with `threads` threads: no
** memory traffic and no synchronisation inside, so what 2 threads give
** here is what the machine gives at that moment. */
static double reference_loop(int threads)
{
  double t0 = now_seconds(), sum = 0;
  long i;
  omp_set_num_threads(threads);
#pragma omp parallel for schedule(static) reduction(+: sum)
  for (i = 0; i < REFERENCE_ITERATIONS; i++) {
    double x = 1e-9 * (double)i, y = 1;
    int k;
    for (k = 0; k < 50; k++) y = 0.999 * y + x;
    sum += y;
  }
  if (sum < 0) printf("%g\n", sum);     /* keeps the loop */
  return now_seconds() - t0;
}

/* Two copies of the state, equal bit for bit, step in turn: CHUNK_STEPS
** steps of one with 1 thread, then the same steps of the other with 2 (the
** results do not depend on the thread count, so the work is the same; the
** positions are compared at the end), `chunks` times; after each pair of
** chunks the reference loop with 1 and with 2 threads.  The virtual
** cores of a shared machine do not always give 2 threads twice the
** throughput of one; the reference shows how far they did. */
static int compare_threads(const char *name, int cluster, int n, int chunks)
{
  afv_sim one, two;
  double t1 = 0, t2 = 0, ref1 = 0, ref2 = 0, t = 0;
  int saved = omp_get_max_threads(), c, st, same;
  memset(&one, 0, sizeof one);
  memset(&two, 0, sizeof two);
  st = make_state(&one, cluster, n);
  if (st == AFV_OK) st = make_state(&two, cluster, n);
  for (c = 0; c < chunks && st == AFV_OK; c++) {
    omp_set_num_threads(1);
    if ((t = time_steps(&one, 0, CHUNK_STEPS)) < 0) st = -1;
    t1 += t;
    omp_set_num_threads(2);
    if (st == AFV_OK && (t = time_steps(&two, 0, CHUNK_STEPS)) < 0) st = -1;
    t2 += t;
    ref1 += reference_loop(1);
    ref2 += reference_loop(2);
  }
  omp_set_num_threads(saved);
  same = st == AFV_OK && memcmp(one.r, two.r, (size_t)n * 2 * sizeof *one.r)
                         == 0;
  afv_sim_free(&one);
  afv_sim_free(&two);
  if (st != AFV_OK) {
    if (st > 0) fprintf(stderr, "bench: %s\n", afv_strerror(st));
    return 1;
  }
  if (!same) {
    fprintf(stderr, "bench: 1 and 2 threads gave different positions\n");
    return 1;
  }
  printf("threads state=%s N=%d speedup=%.3f reference_speedup=%.3f "
         "chunks=%d\n", name, n, t1 / t2, ref1 / ref2, chunks);
  return 0;
}
#endif

/* A whole decimal argument in [lo, INT_MAX] into *v, else 0. */
static int parse_int(const char *text, long lo, int *v)
{
  char *end;
  long x;
  errno = 0;
  x = strtol(text, &end, 10);
  if (errno || end == text || *end != '\0' || x < lo || x > INT_MAX)
    return 0;
  *v = (int)x;
  return 1;
}

static int usage(void)
{
  fprintf(stderr,
          "usage: bench random|cluster|random-force|cluster-force N [STEPS]\n"
          "       bench --vs-400 random|cluster N [COPIES]   (default 100)\n"
          "       bench --numbering random|cluster N [STEPS] (default 20)\n"
          "       bench --relax-vs-400 N P0 [SECONDS]      (default 20)\n"
          "       bench --threads random|cluster N [CHUNKS]  (default 20; "
          "OpenMP build)\n");
  return 2;
}

/* The comparisons' command lines: argv[1] is --vs-400, --numbering or
** --threads. */
static int compare_main(int argc, char **argv)
{
  int threads_mode = strcmp(argv[1], "--threads") == 0, cluster, n, count;
  int numbering = strcmp(argv[1], "--numbering") == 0;
  if (argc < 4 || argc > 5) return usage();
  if (strcmp(argv[2], "random") != 0 && strcmp(argv[2], "cluster") != 0)
    return usage();
  cluster = strcmp(argv[2], "cluster") == 0;
  count = threads_mode || numbering ? 20 : 100;
  if (!parse_int(argv[3], 2, &n)
      || (argc > 4 && !parse_int(argv[4], 1, &count))) {
    fprintf(stderr, "bench: N must be an integer >= 2 and the count an "
            "integer >= 1\n");
    return 2;
  }
  if (numbering) return compare_numbering(argv[2], cluster, n, count);
  if (!threads_mode) return compare_sizes(argv[2], cluster, n, count);
#ifdef _OPENMP
  return compare_threads(argv[2], cluster, n, count);
#else
  fprintf(stderr, "bench: --threads needs the OpenMP build (make "
          "OPENMP=1 test/bench)\n");
  return 2;
#endif
}

int main(int argc, char **argv)
{
  static const char *states[] = {"random", "cluster", "random-force",
                                 "cluster-force"};
  afv_sim sim;
  double t[REPEATS];
  int n, steps, k, state = -1, st;
  if (argc >= 4 && argc <= 5 && strcmp(argv[1], "--relax-vs-400") == 0) {
    double P0 = strtod(argv[3], NULL), every = argc > 4 ? strtod(argv[4], NULL)
                                                     : 20;
    if (!parse_int(argv[2], 2, &n) || !(P0 > 0) || !(every > 0))
      return usage();
    return compare_relax(n, P0, every);
  }
  if (argc >= 2 && (strcmp(argv[1], "--vs-400") == 0
                    || strcmp(argv[1], "--numbering") == 0
                    || strcmp(argv[1], "--threads") == 0))
    return compare_main(argc, argv);
  if (argc >= 2)
    for (k = 0; k < 4; k++)
      if (strcmp(argv[1], states[k]) == 0) state = k;
  if (argc < 3 || argc > 4 || state < 0) return usage();
  if (!parse_int(argv[2], 2, &n)) {
    fprintf(stderr, "bench: N must be an integer >= 2, not '%s'\n", argv[2]);
    return 2;
  }
  steps = STEPS_PER_REPEAT;
  if (argc > 3 && !parse_int(argv[3], 1, &steps)) {
    fprintf(stderr, "bench: STEPS must be an integer >= 1, not '%s'\n",
            argv[3]);
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
