/*
** test_perf.c -- suite_perf: what the speed work must not break.
**
** Timing targets live in the benchmark (test/bench.c, make bench), never
** here.  These tests check the properties the fast code relies on or
** promises: the OpenMP build gives the same bits for every thread count,
** and a repeated evaluation does not allocate.
*/
#include "test.h"
#include "afv.h"

#include <math.h>
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
    dp = memcmp(g1.nbr_start, g2.nbr_start, (size_t)(n + 1) * sizeof(int));
    if (dp == 0)
      dp = memcmp(g1.nbr, g2.nbr, (size_t)g1.nbr_start[n] * sizeof(int));
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
  int cap[5];
  CHECK(r && f, "out of memory");
  if (!r || !f) goto done;
  memset(&g, 0, sizeof g);
  afv_params_default(&p);
  random_tissue(n, 0.9, r, &b);
  st = afv_compute(&g, n, r, &p, &b, f);
  CHECK(st == AFV_OK, "afv_compute: %s", afv_strerror(st));
  cap[0] = g.cap_cells; cap[1] = g.cap_nbr; cap[2] = g.cap_pieces;
  cap[3] = g.cap_bins; cap[4] = g.cap_work;
  for (i = 0; i < 2 * n; i++) r[i] += 1e-4 * (uniform01() - 0.5);
  st = afv_compute(&g, n, r, &p, &b, f);
  CHECK(st == AFV_OK, "afv_compute: %s", afv_strerror(st));
  CHECK(cap[0] == g.cap_cells && cap[1] == g.cap_nbr && cap[2] == g.cap_pieces
        && cap[3] == g.cap_bins && cap[4] == g.cap_work,
        "a buffer grew in a repeated evaluation: capacities cells %d->%d "
        "slots %d->%d pieces %d->%d bins %d->%d work %d->%d", cap[0],
        g.cap_cells, cap[1], g.cap_nbr, cap[2], g.cap_pieces, cap[3],
        g.cap_bins, cap[4], g.cap_work);
done:
  afv_geom_free(&g);
  free(r);
  free(f);
}

void suite_perf(void)
{
  RUN(test_threads_bit_identical);
  RUN(test_no_allocation_when_repeated);
}
