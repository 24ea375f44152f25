/*
** test_perf.c -- suite_perf: what the speed work must not break.
**
** Timing targets live in the benchmark (test/bench.c, make bench), never
** here.  These tests check the properties the fast code relies on or
** promises: the OpenMP build gives the same bits for every thread count,
** and neither a repeated evaluation nor a step allocates once its buffers
** have grown.
*/
#include "test.h"
#include "afv.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define PI 3.14159265358979323846

/* splitmix64: a fixed, portable sequence for the fixtures below */
static unsigned long long perf_rng = 7;

static double uniform01(void)
{
  unsigned long long z = (perf_rng += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* n uniform random centres in a periodic box at packing fraction phi. */
static void random_tissue(int n, double phi, double *r, afv_box *b)
{
  int i;
  b->periodic = 1;
  b->Lx = b->Ly = sqrt(n * PI / phi);
  for (i = 0; i < 2 * n; i++) r[i] = b->Lx * uniform01();
}

#ifdef _OPENMP
/* Number of entries where two double arrays differ in any bit. */
static int bits_differ(const double *a, const double *b, int n)
{
  int i, k = 0;
  for (i = 0; i < n; i++)
    if (memcmp(&a[i], &b[i], sizeof a[i]) != 0) k++;
  return k;
}

/* Forces, energy and every cell's shape with `threads` OpenMP threads. */
static int compute_with(int threads, int n, const double *r,
                        const afv_params *p, const afv_box *b, afv_geom *g,
                        double *f)
{
  omp_set_num_threads(threads);
  return afv_compute(g, n, r, p, b, f);
}

static void compare_runs(const char *what, int n, const double *r,
                         const afv_params *p, const afv_box *b)
{
  static const int threads[] = {2, 3};
  afv_geom g1, g2;
  double *f1 = malloc((size_t)(2 * n) * sizeof(double));
  double *f2 = malloc((size_t)(2 * n) * sizeof(double));
  int saved = omp_get_max_threads(), t;
  memset(&g1, 0, sizeof g1);
  CHECK(f1 && f2, "out of memory");
  if (!f1 || !f2) goto done;
  CHECK(compute_with(1, n, r, p, b, &g1, f1) == AFV_OK, "%s: 1 thread", what);
  for (t = 0; t < 2; t++) {
    int df, da, dp, np = 0, i;
    memset(&g2, 0, sizeof g2);
    CHECK(compute_with(threads[t], n, r, p, b, &g2, f2) == AFV_OK,
          "%s: %d threads", what, threads[t]);
    df = bits_differ(f1, f2, 2 * n);
    da = bits_differ(g1.area, g2.area, n) + bits_differ(g1.perim, g2.perim, n)
       + bits_differ(g1.arc, g2.arc, n);
    dp = memcmp(g1.nbr_start, g2.nbr_start, (size_t)(n + 1) * sizeof(int))
       | memcmp(g1.nbr_end, g2.nbr_end, (size_t)n * sizeof(int));
    for (i = 0; i < n && dp == 0; i++)
      dp = memcmp(g1.nbr + g1.nbr_start[i], g2.nbr + g2.nbr_start[i],
                  (size_t)(g1.nbr_end[i] - g1.nbr_start[i]) * sizeof(int));
    for (i = 0; i < n && dp == 0; i++)
      if (g1.n_pieces[i] != g2.n_pieces[i]
          || memcmp(g1.pieces + g1.piece_start[i],
                    g2.pieces + g2.piece_start[i],
                    (size_t)g1.n_pieces[i] * sizeof(afv_piece)) != 0)
        np++;
    CHECK(df == 0, "%s: %d of %d force components differ in bits between 1 "
          "and %d threads", what, df, 2 * n, threads[t]);
    CHECK(da == 0, "%s: %d areas/perimeters/arcs differ (1 vs %d threads)",
          what, da, threads[t]);
    CHECK(dp == 0 && np == 0, "%s: neighbour lists or pieces differ (%d "
          "cells), 1 vs %d threads", what, np, threads[t]);
    CHECK(memcmp(&g1.energy, &g2.energy, sizeof g1.energy) == 0,
          "%s: energy %.17g (1 thread) vs %.17g (%d threads)", what,
          g1.energy, g2.energy, threads[t]);
    afv_geom_free(&g2);
  }
done:
  omp_set_num_threads(saved);
  afv_geom_free(&g1);
  free(f1);
  free(f2);
}
#endif

/* The OpenMP build gives bit-identical results for 1, 2 and 3 threads. */
static void test_threads_bit_identical(void)
{
#ifdef _OPENMP
  afv_params p;
  afv_box b, open = {0, 0, 0};
  int n = 3000;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  CHECK(r != NULL, "out of memory");
  if (!r) return;
  CHECK(n >= AFV_PARALLEL_MIN, "%d cells: every loop would run on one "
        "thread (AFV_PARALLEL_MIN %d)", n, AFV_PARALLEL_MIN);
  afv_params_default(&p);
  random_tissue(n, 0.5, r, &b);
  compare_runs("random periodic phi 0.5", n, r, &p, &b);
  random_tissue(n, 1.2, r, &b);
  p.P0 = 4.0;
  compare_runs("dense periodic phi 1.2", n, r, &p, &b);
  compare_runs("dense open", n, r, &p, &open);
  free(r);
#else
  SKIP("serial build (make OPENMP=1 test runs it)");
#endif
}

/* An active tissue with large forces to come: n random cells (packing
** fraction 0.5, P0 4.8) relaxed only partly, so that many contacts are
** still to break, with random polarities and v0 = 1.  Fills r (2n), th
** (n), p, b and d; returns afv_sim_init's status. */
static int active_tissue(int n, double *r, double *th, afv_params *p,
                         afv_box *b, afv_dyn *d)
{
  afv_sim relax;
  afv_relax_report rep;
  int st;
  memset(&relax, 0, sizeof relax);
  afv_params_default(p);
  p->P0 = 4.8;
  afv_dyn_default(d);
  random_tissue(n, 0.5, r, b);
  if ((st = afv_sim_init(&relax, n, r, NULL, p, b, d)) == AFV_OK) {
    afv_relax(&relax, 1e-3, 200, &rep, NULL, NULL);
    memcpy(r, relax.r, 2 * (size_t)n * sizeof(double));
  }
  afv_sim_free(&relax);
  afv_init_angles(n, 5, th);
  d->v0 = 1;
  return st;
}

#ifdef _OPENMP
/* Steps a copy of the state (n cells at r, theta) with `threads` threads. */
static int steps_with(int threads, int n, const double *r, const double *th,
                      const afv_params *p, const afv_box *b, const afv_dyn *d,
                      int steps, afv_sim *s)
{
  int k, st;
  omp_set_num_threads(threads);
  if ((st = afv_sim_init(s, n, r, th, p, b, d)) != AFV_OK) return st;
  for (k = 0; k < steps; k++)
    if ((st = afv_sim_step(s)) != AFV_OK) return st;
  return AFV_OK;
}
#endif

/* The steps on threads (dynamics.c): the trajectory of an active tissue
** whose contacts break, with 1 thread against 2 and 3, bit for bit (the
** per-cell loops write their own cells; the reductions are a maximum, an
** or, and integer sums). */
static void test_threads_steps_bit_identical(void)
{
#ifdef _OPENMP
  enum { N = 2000, STEPS = 30 };
  static const int threads[] = {2, 3};
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_sim s1, s2;
  double *r = malloc(2 * N * sizeof(double)), *th = malloc(N * sizeof(double));
  int saved = omp_get_max_threads(), t;
  memset(&s1, 0, sizeof s1);
  CHECK(r && th, "out of memory");
  if (!r || !th) goto done;
  CHECK(active_tissue(N, r, th, &p, &b, &d) == AFV_OK, "init");
  CHECK(steps_with(1, N, r, th, &p, &b, &d, STEPS, &s1) == AFV_OK,
        "1 thread: step refused");
  for (t = 0; t < 2; t++) {
    memset(&s2, 0, sizeof s2);
    CHECK(steps_with(threads[t], N, r, th, &p, &b, &d, STEPS, &s2) == AFV_OK,
          "%d threads: step refused", threads[t]);
    CHECK(memcmp(s1.r, s2.r, 2 * (size_t)N * sizeof(double)) == 0
          && memcmp(s1.f, s2.f, 2 * (size_t)N * sizeof(double)) == 0
          && s1.jumps == s2.jumps && s1.largest_move == s2.largest_move,
          "1 and %d threads: positions, forces or jumps differ after %d "
          "steps", threads[t], STEPS);
    afv_sim_free(&s2);
  }
done:
  omp_set_num_threads(saved);
  afv_sim_free(&s1);
  free(r);
  free(th);
#else
  SKIP("serial build (make OPENMP=1 test runs it)");
#endif
}

/* A second evaluation of a slightly moved tissue reuses every buffer: no
** allocation inside a time step once the buffers have grown. */
static void test_no_allocation_when_repeated(void)
{
  afv_params p;
  afv_box b;
  afv_geom g;
  int n = 2000, i, st;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *f = malloc((size_t)(2 * n) * sizeof(double));
  int cap[6];
  CHECK(r && f, "out of memory");
  if (!r || !f) goto done;
  memset(&g, 0, sizeof g);
  afv_params_default(&p);
  random_tissue(n, 0.9, r, &b);
  st = afv_compute(&g, n, r, &p, &b, f);
  CHECK(st == AFV_OK, "afv_compute: %s", afv_strerror(st));
  cap[0] = g.cap_cells; cap[1] = g.cap_nbr; cap[2] = g.cap_pieces;
  cap[3] = g.cap_bins; cap[4] = g.cap_work; cap[5] = g.cap_cand;
  for (i = 0; i < 2 * n; i++) r[i] += 1e-4 * (uniform01() - 0.5);
  st = afv_compute(&g, n, r, &p, &b, f);
  CHECK(st == AFV_OK, "afv_compute: %s", afv_strerror(st));
  CHECK(cap[0] == g.cap_cells && cap[1] == g.cap_nbr && cap[2] == g.cap_pieces
        && cap[3] == g.cap_bins && cap[4] == g.cap_work
        && cap[5] == g.cap_cand,
        "a buffer grew in a repeated evaluation: capacities cells %d->%d "
        "slots %d->%d pieces %d->%d bins %d->%d work %d->%d cand %d->%d",
        cap[0], g.cap_cells, cap[1], g.cap_nbr, cap[2], g.cap_pieces, cap[3],
        g.cap_bins, cap[4], g.cap_work, cap[5], g.cap_cand);
done:
  afv_geom_free(&g);
  free(r);
  free(f);
}

/* Where a simulation's buffers are and how large: the geometry's.  Two
** equal fingerprints mean that no buffer moved or grew in between.  (Addresses are kept as integers: a pointer
** freed by a realloc may not even be compared.) */
enum { MAX_BUFFERS = 16 };
typedef struct fingerprint {
  int n;
  uintptr_t addr[MAX_BUFFERS];
  int cap[MAX_BUFFERS];
} fingerprint;

static void note_buffer(fingerprint *fp, const void *ptr, int cap)
{
  if (fp->n < MAX_BUFFERS) {
    fp->addr[fp->n] = (uintptr_t)ptr;
    fp->cap[fp->n] = cap;
  }
  fp->n++;
}

static void note_geom(fingerprint *fp, const afv_geom *g)
{
  note_buffer(fp, g->area, g->cap_cells);
  note_buffer(fp, g->nbr, g->cap_nbr);
  note_buffer(fp, g->edge, g->cap_nbr);
  note_buffer(fp, g->grad, g->cap_nbr);
  note_buffer(fp, g->pieces, g->cap_pieces);
  note_buffer(fp, g->bin_start, g->cap_bins);
  note_buffer(fp, g->work, g->cap_work);
  note_buffer(fp, g->cand, g->cap_cand);
}

static fingerprint fingerprint_of(const afv_sim *s)
{
  fingerprint fp;
  fp.n = 0;
  note_geom(&fp, &s->geom);
  return fp;
}

static int same_fingerprint(const fingerprint *a, const fingerprint *b)
{
  int k;
  if (a->n != b->n) return 0;
  for (k = 0; k < a->n && k < MAX_BUFFERS; k++)
    if (a->addr[k] != b->addr[k] || a->cap[k] != b->cap[k]) return 0;
  return 1;
}

/* afv_sim_step allocates nothing once its buffers have grown.  The same
** steps are taken twice: the first run grows every buffer to what these
** steps need; the replay, from the same state (the candidates rebuilt at
** the start, as afv_sim_init does), must then leave every buffer where it
** is and as large as it is after every step, and end on the same bits.
** One thread, as in the other tests of buffers. */
static void test_steps_reuse_their_buffers(void)
{
  enum { N = 2000, STEPS = 30 };
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_sim s;
  fingerprint grown, now;
  double *r = malloc(2 * N * sizeof(double)), *th = malloc(N * sizeof(double));
  double *f0 = malloc(2 * N * sizeof(double));
  double *r_end = malloc(2 * N * sizeof(double));
  int k, regrown = -1, st;
#ifdef _OPENMP
  int saved = omp_get_max_threads();
  omp_set_num_threads(1);
#endif
  memset(&s, 0, sizeof s);
  CHECK(r && th && f0 && r_end, "out of memory");
  if (!r || !th || !f0 || !r_end) goto done;
  st = active_tissue(N, r, th, &p, &b, &d);
  if (st == AFV_OK) st = afv_sim_init(&s, N, r, th, &p, &b, &d);
  CHECK(st == AFV_OK, "init: %s", afv_strerror(st));
  if (st != AFV_OK) goto done;
  memcpy(f0, s.f, 2 * N * sizeof(double));     /* r, th: the start too */
  for (k = 0; k < STEPS && st == AFV_OK; k++) st = afv_sim_step(&s);
  CHECK(st == AFV_OK, "first run: %s", afv_strerror(st));
  if (st != AFV_OK) goto done;
  grown = fingerprint_of(&s);
  CHECK(grown.n <= MAX_BUFFERS, "%d buffers, room for %d", grown.n,
        MAX_BUFFERS);
  memcpy(r_end, s.r, 2 * N * sizeof(double));
  /* back to the start */
  memcpy(s.r, r, 2 * N * sizeof(double));
  memcpy(s.f, f0, 2 * N * sizeof(double));
  memcpy(s.theta, th, N * sizeof(double));
  s.step = 0;
  s.t = 0;
  s.geom.cand_n = 0;
  st = afv_compute(&s.geom, N, s.r, &s.par, &s.box, s.f);
  CHECK(st == AFV_OK, "replay start: %s", afv_strerror(st));
  for (k = 0; k < STEPS && st == AFV_OK; k++) {
    st = afv_sim_step(&s);
    now = fingerprint_of(&s);
    if (regrown < 0 && !same_fingerprint(&now, &grown)) regrown = k + 1;
  }
  CHECK(st == AFV_OK, "replay: %s", afv_strerror(st));
  CHECK(regrown < 0, "replay step %d moved or resized a buffer", regrown);
  CHECK(memcmp(s.r, r_end, 2 * N * sizeof(double)) == 0,
        "the replay ended elsewhere: not the same steps");
done:
#ifdef _OPENMP
  omp_set_num_threads(saved);
#endif
  afv_sim_free(&s);
  free(r);
  free(th);
  free(f0);
  free(r_end);
}

/* The number of neighbour slots in use (each pair counts twice). */
static int slot_count(const afv_geom *g)
{
  int i, m = 0;
  for (i = 0; i < g->n; i++) m += g->nbr_end[i] - g->nbr_start[i];
  return m;
}

/* Largest |a - b| over n entries, and the number of entries that differ
** in any bit. */
static double max_diff(const double *a, const double *b, int n, int *nbits)
{
  double worst = 0;
  int i;
  *nbits = 0;
  for (i = 0; i < n; i++) {
    if (memcmp(&a[i], &b[i], sizeof a[i]) != 0) (*nbits)++;
    if (fabs(a[i] - b[i]) > worst) worst = fabs(a[i] - b[i]);
  }
  return worst;
}

/* The Verlet candidates (neighbours.c) are only a shortcut: a geometry whose
** candidates were built at earlier positions gives the same bits as a fresh
** one, both while they are reused (moves below half the skin) and after a
** rebuild (larger moves), in a dense periodic tissue where many pairs are
** near 2l. */
static void test_candidates_change_nothing(void)
{
  afv_params p;
  afv_box b;
  afv_geom kept, fresh;
  int n = 1500, i, round, nbits, rebuilds;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *f1 = malloc((size_t)(2 * n) * sizeof(double));
  double *f2 = malloc((size_t)(2 * n) * sizeof(double));
  static const double move[] = {0.02, 0.05, 0.12, 0.4};  /* in l, per step */
  CHECK(r && f1 && f2, "out of memory");
  if (!r || !f1 || !f2) goto done;
  memset(&kept, 0, sizeof kept);
  afv_params_default(&p);
  random_tissue(n, 1.0, r, &b);
  CHECK(afv_compute(&kept, n, r, &p, &b, f1) == AFV_OK, "first evaluation");
  for (round = 0; round < 4; round++) {
    double worst;
    rebuilds = kept.n_rebuilds;
    for (i = 0; i < 2 * n; i++) r[i] += move[round] * (uniform01() - 0.5);
    memset(&fresh, 0, sizeof fresh);
    CHECK(afv_compute(&kept, n, r, &p, &b, f1) == AFV_OK, "kept geometry");
    CHECK(afv_compute(&fresh, n, r, &p, &b, f2) == AFV_OK, "fresh geometry");
    worst = max_diff(f1, f2, 2 * n, &nbits);
    CHECK(nbits == 0, "moves of %g l: %d force components differ from a "
          "fresh evaluation (largest difference %.3e)", move[round], nbits,
          worst);
    CHECK(memcmp(&kept.energy, &fresh.energy, sizeof kept.energy) == 0,
          "moves of %g l: energy %.17g, fresh %.17g", move[round],
          kept.energy, fresh.energy);
    CHECK(slot_count(&kept) == slot_count(&fresh), "moves of %g l: %d "
          "neighbour slots, fresh %d", move[round], slot_count(&kept),
          slot_count(&fresh));
    /* half-diagonal moves up to 0.7 move: a rebuild exactly when needed */
    if (move[round] * 0.71 < 0.15)
      CHECK(kept.n_rebuilds == rebuilds, "moves of %g l rebuilt the "
            "candidates", move[round]);
    else
      CHECK(kept.n_rebuilds == rebuilds + 1, "moves of %g l did not rebuild "
            "the candidates", move[round]);
    afv_geom_free(&fresh);
  }
  afv_geom_free(&kept);
done:
  free(r);
  free(f1);
  free(f2);
}

/* Kept candidates with a few cells moved beyond the skin ("movers",
** neighbours.c): the same bits as a fresh evaluation, and no rebuild: the
** movers are re-anchored.  Trials from a random tissue: one cell moved
** 0.2 l (beyond SKIN l / 2 = 0.15 l) in a random direction; and two cells
** 2.4 l apart (not a candidate pair, which needs 2.3 l) moved 0.25 l
** towards each other, into contact range, with every other cell held:
** that pair is new; two cells 4.5 l apart brought to 1.9 l by moves of
** 1.2 l and 1.4 l; and two cells alone in a corridor of a sparse lattice,
** 8 l apart, brought to 1.9 l.  (A re-anchoring that does not put the
** mover into its new neighbours' lists makes this fail, and so does one
** that does not search the cells re-anchored before it (the corridor:
** the second mover must find the first at its new anchor).) */
static int movers_trial(const double *r0, int n, const afv_params *p,
                        const afv_box *b, int a, double ax, double ay, int c,
                        double cx, double cy, int *rebuilt)
{
  afv_geom kept, fresh;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *f1 = malloc((size_t)(2 * n) * sizeof(double));
  double *f2 = malloc((size_t)(2 * n) * sizeof(double));
  int nbits = -1, rebuilds;
  *rebuilt = 0;
  memset(&kept, 0, sizeof kept);
  memset(&fresh, 0, sizeof fresh);
  if (r && f1 && f2 && afv_compute(&kept, n, r0, p, b, f1) == AFV_OK) {
    memcpy(r, r0, (size_t)(2 * n) * sizeof(double));
    r[2*a] += ax;
    r[2*a+1] += ay;
    if (c >= 0) {
      r[2*c] += cx;
      r[2*c+1] += cy;
    }
    rebuilds = kept.n_rebuilds;
    if (afv_compute(&kept, n, r, p, b, f1) == AFV_OK
        && afv_compute(&fresh, n, r, p, b, f2) == AFV_OK) {
      max_diff(f1, f2, 2 * n, &nbits);
      if (memcmp(&kept.energy, &fresh.energy, sizeof kept.energy) != 0)
        nbits++;
    }
    *rebuilt = kept.n_rebuilds > rebuilds;
  }
  afv_geom_free(&kept);
  afv_geom_free(&fresh);
  free(r);
  free(f1);
  free(f2);
  return nbits;
}

/* A mover re-anchored (2 + SKIN) l - 5e-7 l from a cell's anchor (SKIN
** = 0.3 l), then each brought 0.15 l - 1e-7 l (just within SKIN / 2 of
** its anchor, so neither is re-anchored again) towards the other, to
** 2 l - 3e-7 l: they touch, an edge of 1.1e-3 l, which the kept
** candidates must find as a fresh evaluation does.  The reach is widened
** by AFV_REACH_MARGIN (1e-9 l) for the rounding of the positions; a
** reach 1e-6 l short of (2 + SKIN) l missed the pair. */
static void test_mover_at_the_reach(void)
{
  double r[4] = {0, 0, 10, 0}, f[4], reach = 2.3 - 5e-7, in = 0.15 - 1e-7;
  afv_geom kept, fresh;
  afv_params p;
  afv_box b = {0, 0, 0};
  memset(&kept, 0, sizeof kept);
  memset(&fresh, 0, sizeof fresh);
  afv_params_default(&p);
  CHECK(afv_compute(&kept, 2, r, &p, &b, f) == AFV_OK, "start");
  r[2] = reach;                            /* cell 1 moved 7.7 l */
  CHECK(afv_compute(&kept, 2, r, &p, &b, f) == AFV_OK, "mover");
  CHECK(kept.contacts[1] == 0, "2.3 l apart, in contact");
  r[0] = in;
  r[2] = reach - in;
  CHECK(afv_compute(&kept, 2, r, &p, &b, f) == AFV_OK
        && afv_compute(&fresh, 2, r, &p, &b, f) == AFV_OK, "moved in");
  CHECK(fresh.contacts[0] == 1, "fixture: %.17g l apart, %d contacts",
        r[2] - r[0], fresh.contacts[0]);
  CHECK(kept.contacts[0] == fresh.contacts[0] && kept.n_rebuilds == 1,
        "kept candidates: %d contacts (fresh %d), %d rebuilds",
        kept.contacts[0], fresh.contacts[0], kept.n_rebuilds);
  afv_geom_free(&kept);
  afv_geom_free(&fresh);
}

/* movers_trial for the first `want` pairs of cells about d apart (within
** 0.05 l), brought towards each other by moves of mi and mj: the same bits
** as a fresh evaluation (the pair ends closer than 2l), without a
** rebuild. */
static void check_pairs(const double *r, int n, const afv_params *p,
                        const afv_box *b, double d0, double mi, double mj,
                        int want)
{
  int i, j, pair = 0, bad, rebuilt = 0;
  for (i = 0; i < n && pair < want; i++)
    for (j = i + 1; j < n && pair < want; j++) {
      double dx = r[2*j] - r[2*i], dy = r[2*j+1] - r[2*i+1], d;
      afv_min_image(b, &dx, &dy);
      d = hypot(dx, dy);
      if (fabs(d - d0) > 0.05) continue;
      pair++;
      bad = movers_trial(r, n, p, b, i, mi * dx / d, mi * dy / d, j,
                         -mj * dx / d, -mj * dy / d, &rebuilt);
      CHECK(bad == 0 && !rebuilt, "cells %d and %d brought from %.3f l to "
            "%.3f l: %d values differ from a fresh evaluation, %s", i, j, d,
            d - mi - mj, bad, rebuilt ? "rebuilt" : "re-anchored");
    }
  CHECK(pair == want, "only %d pairs at %g l", pair, d0);
}

static void test_candidates_with_movers(void)
{
  afv_params p;
  afv_box b;
  int n = 1500, trial, skipped = 0, rebuilt = 0, bad;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  CHECK(r != NULL, "out of memory");
  if (!r) return;
  afv_params_default(&p);
  random_tissue(n, 1.0, r, &b);
  for (trial = 0; trial < 20; trial++) {
    double t = 2 * PI * uniform01();
    int a = (int)(n * uniform01());
    bad = movers_trial(r, n, &p, &b, a, 0.2 * cos(t), 0.2 * sin(t), -1, 0,
                       0, &rebuilt);
    CHECK(bad == 0, "cell %d moved 0.2 l: %d values differ from a fresh "
          "evaluation", a, bad);
    skipped += !rebuilt;
  }
  CHECK(skipped == 20, "%d single movers forced a rebuild", 20 - skipped);
  check_pairs(r, n, &p, &b, 2.4, 0.25, 0.25, 3);
  /* two movers: cells 4.5 l apart come 1.2 l and 1.4 l towards each
  ** other; neither's place in the cell list is near the other */
  check_pairs(r, n, &p, &b, 4.5, 1.2, 1.4, 5);
  {   /* two cells 8 l apart in a corridor of a sparse lattice (spacing
      ** 2.6 l, so the cell list has bins of 2.3 l), brought to 1.9 l by
      ** moves of 3 l and 3.1 l: only their own pair is new, and neither's
      ** place in the cell list is near the other */
    afv_box box = {1, 39, 39};
    double *q = malloc(2 * 230 * sizeof(double));
    int m = 2, x, y;
    if (q) {
      q[0] = 10;
      q[1] = 19.5;
      q[2] = 18;
      q[3] = 19.5;
      for (x = 0; x < 15; x++)
        for (y = 0; y < 15; y++)
          if (fabs(2.6 * y + 1 - 19.5) > 3.5) {
            q[2*m] = 2.6 * x + 1;
            q[2*m+1] = 2.6 * y + 1;
            m++;
          }
      bad = movers_trial(q, m, &p, &box, 0, 3, 0, 1, -3.1, 0, &rebuilt);
      CHECK(bad == 0 && !rebuilt, "two cells brought from 8 l to 1.9 l: "
            "%d values differ from a fresh evaluation, %s", bad,
            rebuilt ? "rebuilt" : "re-anchored");
    }
    free(q);
  }
  free(r);
}

/* Many calls in a row, each with a few cells thrown 0.2 l to 3 l (as the
** Euler step throws a cell of the random state) and every other cell
** moved a little: each call gives the same bits as a fresh evaluation,
** while the kept candidates re-anchor the movers (lists moved to the
** spare room, cells re-anchored twice) and are rebuilt at most a few
** times; and the junctions afv_clusters_compute finds come in the same
** order, with the same bits (they are numbered in the pieces' order,
** which must stay the cells' order).  (Forgetting to take a mover out of
** the lists it leaves does not fail this, the lists being filtered;
** forgetting to add it, or to search the re-anchored nodes, does, and so
** did pieces placed after the moved lists: junctions in another order.) */
static int same_junctions(const afv_geom *a, const afv_geom *b,
                          const double *r, const afv_params *p,
                          const afv_box *box)
{
  afv_clusters ca, cb;
  int same;
  memset(&ca, 0, sizeof ca);
  memset(&cb, 0, sizeof cb);
  same = afv_clusters_compute(&ca, a, r, p->l, box) == AFV_OK
         && afv_clusters_compute(&cb, b, r, p->l, box) == AFV_OK
         && ca.n_junctions == cb.n_junctions
         && memcmp(ca.junction, cb.junction,
                   2 * (size_t)ca.n_junctions * sizeof(double)) == 0;
  afv_clusters_free(&ca);
  afv_clusters_free(&cb);
  return same;
}

static void test_movers_over_many_calls(void)
{
  enum { N = 1500, CALLS = 60, THROWN = 6 };
  afv_params p;
  afv_box b;
  afv_geom kept;
  double *r = malloc((size_t)(2 * N) * sizeof(double));
  double *f1 = malloc((size_t)(2 * N) * sizeof(double));
  double *f2 = malloc((size_t)(2 * N) * sizeof(double));
  int call, k, bad = 0, rebuilds = 0, nbits;
  CHECK(r && f1 && f2, "out of memory");
  if (!r || !f1 || !f2) goto done;
  memset(&kept, 0, sizeof kept);
  afv_params_default(&p);
  random_tissue(N, 0.8, r, &b);
  CHECK(afv_compute(&kept, N, r, &p, &b, f1) == AFV_OK, "first evaluation");
  rebuilds = kept.n_rebuilds;
  for (call = 0; call < CALLS && !bad; call++) {
    afv_geom fresh;
    for (k = 0; k < 2 * N; k++) r[k] += 0.004 * (uniform01() - 0.5);
    for (k = 0; k < THROWN; k++) {
      int a = (int)(N * uniform01());
      double t = 2 * PI * uniform01(), len = 0.2 + 2.8 * uniform01();
      r[2*a] += len * cos(t);
      r[2*a+1] += len * sin(t);
    }
    memset(&fresh, 0, sizeof fresh);
    if (afv_compute(&kept, N, r, &p, &b, f1) != AFV_OK
        || afv_compute(&fresh, N, r, &p, &b, f2) != AFV_OK) {
      bad = -1;
    } else {
      max_diff(f1, f2, 2 * N, &nbits);
      bad = nbits + (memcmp(&kept.energy, &fresh.energy,
                            sizeof kept.energy) != 0)
            + (slot_count(&kept) != slot_count(&fresh))
            + !same_junctions(&kept, &fresh, r, &p, &b);
    }
    afv_geom_free(&fresh);
  }
  CHECK(bad == 0, "call %d: %d values differ from a fresh evaluation", call,
        bad);
  rebuilds = kept.n_rebuilds - rebuilds;
  CHECK(rebuilds <= CALLS / 6 && kept.moved_lists > 0, "%d calls with %d thrown "
        "cells each: %d rebuilds, %d lists moved", CALLS, THROWN, rebuilds,
        kept.moved_lists);
  afv_geom_free(&kept);
done:
  free(r);
  free(f1);
  free(f2);
}

/* afv_cells_around (afv_force_check's region search) misses no cell, in the
** worst case: for each query point p the candidates stay those built at
** r0, every cell moves 0.14 l straight towards p (within the skin: no
** rebuild), the lists are refreshed there, and every cell moves `moved`
** further towards p.  Every cell then within R of p must be listed, none
** twice.  Periodic boxes of many and of few bins a side, and open space.
** (Leaving out either slack, the moves since the rebuild or moved, makes
** this fail.) */
static void toward(const afv_box *b, double px, double py, double len,
                   double *r, int n)
{
  int i;
  for (i = 0; i < n; i++) {
    double dx = px - r[2*i], dy = py - r[2*i+1], d;
    afv_min_image(b, &dx, &dy);
    d = hypot(dx, dy);
    if (d > len) {
      r[2*i] += len * dx / d;
      r[2*i+1] += len * dy / d;
    }
  }
}

static void check_cells_around(int n, int periodic, double R, double moved)
{
  afv_box b;
  afv_geom g;
  double *r0 = malloc((size_t)(2 * n) * sizeof(double));
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  int *out = malloc((size_t)n * sizeof(int));
  int *seen = calloc((size_t)n, sizeof(int));
  int i, q, missed = 0, twice = 0, total = 0, rebuilds;
  memset(&g, 0, sizeof g);
  CHECK(r0 && r && out && seen, "out of memory");
  if (!r0 || !r || !out || !seen) goto done;
  random_tissue(n, 0.5, r0, &b);
  b.periodic = periodic;
  CHECK(afv_neighbours(&g, n, r0, 1.0, &b) == AFV_OK, "lists");
  rebuilds = g.n_rebuilds;
  for (q = 0; q < 200; q++) {
    double px = b.Lx * (1.2 * uniform01() - 0.1);
    double py = b.Ly * (1.2 * uniform01() - 0.1);
    int m, k;
    memcpy(r, r0, (size_t)(2 * n) * sizeof(double));
    toward(&b, px, py, 0.14, r, n);
    CHECK(afv_neighbours(&g, n, r, 1.0, &b) == AFV_OK, "lists");
    toward(&b, px, py, moved, r, n);
    m = afv_cells_around(&g, px, py, R, moved, out);
    total += m;
    for (k = 0; k < m; k++) twice += seen[out[k]]++ > 0;
    for (i = 0; i < n; i++) {
      double dx = r[2*i] - px, dy = r[2*i+1] - py;
      afv_min_image(&b, &dx, &dy);
      if (dx * dx + dy * dy < R * R && !seen[i]) missed++;
    }
    for (k = 0; k < m; k++) seen[out[k]] = 0;
  }
  CHECK(g.n_rebuilds == rebuilds, "the moves rebuilt the candidates");
  CHECK(missed == 0 && twice == 0, "%s, %d cells, R %g, moved %g: %d "
        "cells missed, %d listed twice", periodic ? "periodic" : "open", n,
        R, moved, missed, twice);
  if (n >= 2000)
    CHECK(total < 200 * n / 10, "the search is not local: %d cells per "
          "query", total / 200);
done:
  afv_geom_free(&g);
  free(r0);
  free(r);
  free(out);
  free(seen);
}

/* The same search when one cell has moved farther than the skin allows (a
** mover, neighbours.c: MOVERS) and the candidates still hold: the search must
** widen by that cell's move.  For each query point p, every cell moves
** 0.14 l towards p, then the cell nearest to 0.45 l beyond R moves another
** 0.5 l, to just inside R; the lists are refreshed; the query must list
** it if it is within R.  (A search widened by the skin's 0.15 l only, as
** in an earlier version, missed it in 4 of the 124 queries tested.)  A
** query whose mover made a new pair closer than 2l rebuilds the
** candidates, and tests nothing, as does a mover left outside R: at least
** half of the queries must test the far move. */
static void check_cells_around_mover(int n, double R)
{
  afv_box b;
  afv_geom g;
  double *r0 = malloc((size_t)(2 * n) * sizeof(double));
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  int *out = malloc((size_t)n * sizeof(int));
  int q, missed = 0, tested = 0;
  memset(&g, 0, sizeof g);
  CHECK(r0 && r && out, "out of memory");
  if (!r0 || !r || !out) goto done;
  random_tissue(n, 0.5, r0, &b);
  for (q = 0; q < 200; q++) {
    double px = b.Lx * uniform01(), py = b.Ly * uniform01(), best = 1e300;
    double dx, dy;
    int i, k, m, mover = 0, rebuilds, found = 0;
    g.cand_n = 0;                           /* rebuild at r0 */
    CHECK(afv_neighbours(&g, n, r0, 1.0, &b) == AFV_OK, "lists");
    rebuilds = g.n_rebuilds;
    memcpy(r, r0, (size_t)(2 * n) * sizeof(double));
    toward(&b, px, py, 0.14, r, n);
    for (i = 0; i < n; i++) {
      double off;
      dx = r[2*i] - px;
      dy = r[2*i+1] - py;
      afv_min_image(&b, &dx, &dy);
      off = fabs(hypot(dx, dy) - (R + 0.45));
      if (off < best) {
        best = off;
        mover = i;
      }
    }
    toward(&b, px, py, 0.5, r + 2 * mover, 1);
    CHECK(afv_neighbours(&g, n, r, 1.0, &b) == AFV_OK, "lists");
    dx = r[2 * mover] - px;
    dy = r[2 * mover + 1] - py;
    afv_min_image(&b, &dx, &dy);
    if (g.n_rebuilds != rebuilds || hypot(dx, dy) >= R) continue;
    tested++;
    m = afv_cells_around(&g, px, py, R, 0, out);
    for (k = 0; k < m; k++) found |= out[k] == mover;
    missed += !found;
  }
  CHECK(missed == 0 && tested >= 100, "a mover 0.64 l from where it was "
        "binned: missed in %d of %d queries tested (of 200)", missed, tested);
done:
  afv_geom_free(&g);
  free(r0);
  free(r);
  free(out);
}

static void test_cells_around(void)
{
  check_cells_around_mover(2000, 5.0);
  check_cells_around(2000, 1, 5.0, 0.06);
  check_cells_around(2000, 1, 5.0, 0.3);
  check_cells_around(2000, 0, 5.0, 0.06);
  check_cells_around(300, 1, 5.0, 0.06);     /* 43 l box: 18 bins a side */
  check_cells_around(25, 1, 5.0, 0.06);      /* 12.5 l box: 5 bins a side,
                                             ** all within reach */
}

/* afv_spatial_order is a permutation, and renumbering the cells by it
** changes no cell's shape or force in any bit: a list is ordered by the
** directions of the neighbours, not by their numbers. */
static void test_spatial_order_renumbering(void)
{
  afv_params p;
  afv_box b;
  afv_geom g1, g2;
  int n = 2000, i, bad = 0, *perm = malloc((size_t)n * sizeof(int));
  int *seen = calloc((size_t)n, sizeof(int));
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *q = malloc((size_t)(2 * n) * sizeof(double));
  double *f1 = malloc((size_t)(2 * n) * sizeof(double));
  double *f2 = malloc((size_t)(2 * n) * sizeof(double));
  CHECK(perm && seen && r && q && f1 && f2, "out of memory");
  if (!perm || !seen || !r || !q || !f1 || !f2) goto done;
  memset(&g1, 0, sizeof g1);
  memset(&g2, 0, sizeof g2);
  afv_params_default(&p);
  random_tissue(n, 0.8, r, &b);
  CHECK(afv_spatial_order(n, r, 1.0, &b, perm) == AFV_OK, "status");
  for (i = 0; i < n; i++)
    if (perm[i] < 0 || perm[i] >= n || seen[perm[i]]++) bad++;
  CHECK(bad == 0, "not a permutation: %d bad entries", bad);
  if (bad) goto done;
  for (i = 0; i < n; i++) {
    q[2*i] = r[2*perm[i]];
    q[2*i+1] = r[2*perm[i]+1];
  }
  CHECK(afv_compute(&g1, n, r, &p, &b, f1) == AFV_OK, "status");
  CHECK(afv_compute(&g2, n, q, &p, &b, f2) == AFV_OK, "status");
  for (i = 0; i < n; i++) {
    int j = perm[i];
    if (memcmp(&g1.area[j], &g2.area[i], sizeof(double))
        || memcmp(&g1.perim[j], &g2.perim[i], sizeof(double))
        || memcmp(&f1[2*j], &f2[2*i], 2 * sizeof(double)))
      bad++;
  }
  CHECK(bad == 0, "%d of %d cells changed by the renumbering", bad, n);
  CHECK_CLOSE(g2.energy, g1.energy, 1e-12, 0, "energy");
  afv_geom_free(&g1);
  afv_geom_free(&g2);
done:
  free(perm);
  free(seen);
  free(r);
  free(q);
  free(f1);
  free(f2);
}

void suite_perf(void)
{
  RUN(test_threads_bit_identical);
  RUN(test_threads_steps_bit_identical);
  RUN(test_no_allocation_when_repeated);
  RUN(test_steps_reuse_their_buffers);
  RUN(test_candidates_change_nothing);
  RUN(test_candidates_with_movers);
  RUN(test_mover_at_the_reach);
  RUN(test_movers_over_many_calls);
  RUN(test_cells_around);
  RUN(test_spatial_order_renumbering);
}
