/*
** test_analysis.c -- order parameters (analysis.c) and pictures (svg.c).
**
** Hand-built configurations with known answers first (clusters, Omega,
** junctions, T1), then synthetic trajectories with known statistics (MSD,
** autocorrelation time), the mean-field point, the SVG output, and an
** end-to-end `afv analyze` of a synthetic run.  Unit of length: l = 1.
** Random numbers come from a fixed-seed splitmix64, so a failure repeats.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"   /* and afv_internal.h: afv_analyze_ring */

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* (Declared in test.h: test_sweep.c uses it too.  Here, not in fixtures.c,
** because it CHECKs, and test/twins.c links fixtures.c without the runner.) */
/* A trajectory of nframes frames of n cells in box b, zeroed (free with
** afv_traj_free); 0 (and a failed CHECK) if out of memory. */
int test_traj_alloc(afv_traj *tr, int n, int nframes, afv_box b)
{
  memset(tr, 0, sizeof *tr);
  tr->n = n;
  tr->nframes = nframes;
  tr->box = b;
  tr->step = calloc((size_t)nframes, sizeof *tr->step);
  tr->t = calloc((size_t)nframes, sizeof(double));
  tr->r = calloc((size_t)nframes * 2 * n, sizeof(double));
  tr->theta = calloc((size_t)nframes * n, sizeof(double));
  CHECK(tr->step && tr->t && tr->r && tr->theta, "out of memory");
  return tr->step && tr->t && tr->r && tr->theta;
}

#define PI 3.14159265358979323846

/* ---- fixtures ------------------------------------------------------------ */
/* Geometry (l = 1) and clusters of n cells; returns 0 on failure. */
static int analyse(int n, const double *r, const afv_box *b, afv_geom *g,
                   afv_clusters *c)
{
  afv_params p;
  int st;
  afv_params_default(&p);
  st = afv_geometry(g, n, r, &p, b);
  CHECK(st == AFV_OK, "afv_geometry: %s", afv_strerror(st));
  if (st != AFV_OK) return 0;
  st = afv_clusters_compute(c, g, r, 1.0, b);
  CHECK(st == AFV_OK, "afv_clusters_compute: %s", afv_strerror(st));
  return st == AFV_OK;
}

/* Periodic triangular lattice of mx x my cells (my even), spacing d. */
/* An mx x my periodic triangular lattice of spacing d; returns its size. */
static int tri_lattice(int mx, int my, double d, double *r, afv_box *b)
{
  *b = test_tri_lattice(mx, my, d, 0.25 * d, 0.25 * sqrt(3.0) * d, r);
  return mx * my;
}

static void free_both(afv_geom *g, afv_clusters *c)
{
  afv_geom_free(g);
  afv_clusters_free(c);
}

/* ---- clusters ------------------------------------------------------------ */
static void clusters_two_separate(void)
{
  /* two tight triangles (side 1.2 < sqrt 3: a junction each), 10 l apart */
  double r[12] = {0, 0, 1.2, 0, 0.6, 1.03923,
                  10, 0, 11.2, 0, 10.6, 1.03923};
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  if (!analyse(6, r, &b, &g, &c)) return;
  CHECK(c.count == 2, "clusters: got %d, want 2", c.count);
  CHECK(c.giant == 3, "giant: got %d, want 3", c.giant);
  CHECK(c.size[0] == 3 && c.size[1] == 3, "sizes %d %d", c.size[0], c.size[1]);
  CHECK(c.label[0] == c.label[2] && c.label[3] == c.label[5]
        && c.label[0] != c.label[3], "labels wrong");
  CHECK(c.n_pairs == 6, "pairs: got %d, want 6", c.n_pairs);
  CHECK(c.n_junctions == 2, "junctions: got %d, want 2", c.n_junctions);
  CHECK_CLOSE(c.omega, 1.0, 0, 1e-15, "Omega of two confluent triangles");
  free_both(&g, &c);
}

static void clusters_chain(void)
{
  double r[10];
  int i;
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  for (i = 0; i < 5; i++) {
    r[2*i] = 1.5 * i;
    r[2*i+1] = 0;
  }
  if (!analyse(5, r, &b, &g, &c)) return;
  CHECK(c.count == 1 && c.giant == 5, "count %d giant %d", c.count, c.giant);
  CHECK(c.ec[0] == 4 && c.v3[0] == 0, "Ec %d V3 %d, want 4 0", c.ec[0],
        c.v3[0]);
  CHECK(c.wraps[0] == 0, "an open chain does not wrap");
  CHECK_CLOSE(c.omega, 0.0, 0, 0, "Omega of a straight chain");
  free_both(&g, &c);
}

static void clusters_ring_wraps_box(void)
{
  /* 4 cells 1.5 apart along x in a 6 x 6 box: a ring through the boundary */
  double r[8] = {0.75, 3, 2.25, 3, 3.75, 3, 5.25, 3};
  afv_box b = test_periodic_box(6, 6);
  afv_geom g = {0};
  afv_clusters c = {0};
  if (!analyse(4, r, &b, &g, &c)) return;
  CHECK(c.count == 1, "ring: %d clusters, want 1", c.count);
  CHECK(c.wraps[0] == 1, "the ring winds around the box");
  CHECK(c.n_pairs == 4 && c.ec[0] == 4, "ring contacts %d, want 4", c.n_pairs);
  CHECK_CLOSE(c.omega, 0.0, 0, 0, "Omega of a ring");
  free_both(&g, &c);
  /* the same chain in a wider box is open: 3 contacts, no winding */
  b = test_periodic_box(12, 6);
  if (!analyse(4, r, &b, &g, &c)) return;
  CHECK(c.count == 1 && c.wraps[0] == 0 && c.n_pairs == 3,
        "wide box: count %d wraps %d pairs %d", c.count, c.wraps[0],
        c.n_pairs);
  free_both(&g, &c);
}

static void clusters_isolated(void)
{
  double r[8] = {0, 0, 3, 0, 0, 3, 3, 3};
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  if (!analyse(4, r, &b, &g, &c)) return;
  CHECK(c.count == 4 && c.giant == 1 && c.n_pairs == 0,
        "count %d giant %d pairs %d", c.count, c.giant, c.n_pairs);
  CHECK_CLOSE(c.omega, 0.0, 0, 0, "Omega of isolated cells");
  free_both(&g, &c);
}

/* Cells 0 and 2 are 1.8 l apart (< 2l, so neighbours), but cell 1 between
** them cuts both disks first: their bisector never reaches the boundary.
** Answer: NOT in contact (no shared edge), so 0-1-2 is a chain. */
static void clusters_shadowed_bisector(void)
{
  double r[6] = {0, 0, 0.9, 0, 1.8, 0};
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  int s, premise = 0;
  if (!analyse(3, r, &b, &g, &c)) return;
  for (s = g.nbr_start[0]; s < g.nbr_end[0]; s++) premise |= g.nbr[s] == 2;
  CHECK(premise, "premise: 0 and 2 are within 2l");
  CHECK(c.n_pairs == 2, "pairs: got %d, want 2", c.n_pairs);
  CHECK(c.n_pairs == 2 && c.pairs[0] == 0 && c.pairs[1] == 1
        && c.pairs[2] == 1 && c.pairs[3] == 2, "pairs are not (0,1), (1,2)");
  CHECK(c.count == 1 && c.ec[0] == 2 && c.v3[0] == 0, "count %d Ec %d V3 %d",
        c.count, c.ec[0], c.v3[0]);
  free_both(&g, &c);
}

/* A large random configuration: the union-find clusters against a plain
** flood fill over the contact pairs. */
static void clusters_match_flood_fill(void)
{
  enum { N = 300 };
  double r[2 * N];
  int seen[N], stack[N], i, k, sp, lab, bad = 0;
  afv_box b = test_periodic_box(30, 30);
  afv_geom g = {0};
  afv_clusters c = {0};
  test_rng_seed(7);
  for (i = 0; i < 2 * N; i++) r[i] = 30 * test_rng_uniform();
  if (!analyse(N, r, &b, &g, &c)) return;
  for (i = 0; i < N; i++) seen[i] = -1;
  for (lab = 0, i = 0; i < N; i++) {
    if (seen[i] >= 0) continue;
    sp = 0;
    stack[sp++] = i;
    seen[i] = lab;
    while (sp > 0) {
      int a = stack[--sp];
      for (k = 0; k < c.n_pairs; k++) {
        int o = c.pairs[2*k] == a ? c.pairs[2*k+1]
              : c.pairs[2*k+1] == a ? c.pairs[2*k] : -1;
        if (o >= 0 && seen[o] < 0) {
          seen[o] = lab;
          stack[sp++] = o;
        }
      }
    }
    lab++;
  }
  CHECK(lab == c.count, "flood fill %d clusters, union-find %d", lab, c.count);
  for (i = 0; i < N; i++)
    for (k = 0; k < N; k++)
      bad += (seen[i] == seen[k]) != (c.label[i] == c.label[k]);
  CHECK(bad == 0, "%d cell pairs disagree on sharing a cluster", bad);
  free_both(&g, &c);
}

/* ---- Omega and junctions ----------------------------------------------- */
static void omega_confluent_lattice(void)
{
  double r[2 * 16];
  afv_box b;
  afv_geom g = {0};
  afv_clusters c = {0};
  int n = tri_lattice(4, 4, 1.5, r, &b);   /* 1.5 < sqrt 3: no gaps */
  if (!analyse(n, r, &b, &g, &c)) return;
  CHECK(c.count == 1 && c.wraps[0], "count %d wraps %d", c.count, c.wraps[0]);
  CHECK(c.n_pairs == 3 * n, "contacts %d, want 3N = %d", c.n_pairs, 3 * n);
  CHECK(c.n_junctions == 2 * n, "junctions %d, want 2N = %d", c.n_junctions,
        2 * n);
  CHECK_CLOSE(c.omega, 1.0, 0, 1e-15, "Omega, confluent periodic lattice");
  free_both(&g, &c);
}

static void omega_sparse_lattice(void)
{
  double r[2 * 16];
  afv_box b;
  afv_geom g = {0};
  afv_clusters c = {0};
  int n = tri_lattice(4, 4, 1.85, r, &b);  /* sqrt 3 < 1.85 < 2: gaps */
  if (!analyse(n, r, &b, &g, &c)) return;
  CHECK(c.count == 1 && c.n_pairs == 3 * n, "count %d contacts %d", c.count,
        c.n_pairs);
  CHECK(c.n_junctions == 0, "junctions %d, want 0", c.n_junctions);
  CHECK_CLOSE(c.omega, 0.0, 0, 0, "Omega, sparse lattice");
  free_both(&g, &c);
}

/* By hand: cluster A = square of side 1.6 (a gap in its middle) plus cell 4
** below its bottom side making one junction with cells 0 and 1 (circumcentre
** (0.8, -1/3), 0.87 from each centre): N = 5, Ec = 6, V3 = 1, omega = 1/2.
** Cluster B = tight triangle, omega = 1, N = 3.  Cell 8 alone, omega = 0.
** Omega = (5 * 1/2 + 3 * 1 + 1 * 0) / 9 = 5.5 / 9. */
static void omega_mixed_by_hand(void)
{
  double r[18] = {0, 0, 1.6, 0, 1.6, 1.6, 0, 1.6, 0.8, -1.2,
                  10, 0, 11.2, 0, 10.6, 1.03923, -10, -10};
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  int a;
  if (!analyse(9, r, &b, &g, &c)) return;
  a = c.label[0];
  CHECK(c.count == 3, "clusters %d, want 3", c.count);
  CHECK(c.size[a] == 5 && c.ec[a] == 6 && c.v3[a] == 1,
        "cluster A: N %d Ec %d V3 %d, want 5 6 1", c.size[a], c.ec[a],
        c.v3[a]);
  CHECK_CLOSE(c.omega_c[a], 0.5, 0, 1e-15, "omega of cluster A");
  CHECK_CLOSE(c.omega, 5.5 / 9, 1e-15, 0, "Omega of the mixed tissue");
  free_both(&g, &c);
}

/* Four cells on a square of side 1.2 meet at one 4-fold vertex (the square's
** centre, 0.85 from each): the diagonal edge has length 0 or roundoff.  It
** is one junction (Ec = 4, N = 4: one face), omega = 1.  Moved by 1e-12 the
** diagonal edge is below AFV_CONTACT_TOL: still one junction.  Moved by
** 1e-2 the diagonal becomes a contact: two junctions, Ec = 5, omega = 1. */
static void omega_degenerate_vertex(void)
{
  static const double eps[3] = {0, 1e-12, 1e-2};
  static const int want_v3[3] = {1, 1, 2}, want_ec[3] = {4, 4, 5};
  int k;
  for (k = 0; k < 3; k++) {
    double r[8] = {0, 0, 1.2, 0, 1.2, 1.2, 0, 1.2};
    afv_box b = test_open_box();
    afv_geom g = {0};
    afv_clusters c = {0};
    r[0] += eps[k];
    r[1] += eps[k];
    if (!analyse(4, r, &b, &g, &c)) return;
    CHECK(c.n_junctions == want_v3[k] && c.ec[0] == want_ec[k],
          "shift %g: V3 %d Ec %d, want %d %d", eps[k], c.n_junctions, c.ec[0],
          want_v3[k], want_ec[k]);
    CHECK_CLOSE(c.omega, 1.0, 0, 1e-15, "Omega at a 4-fold vertex");
    free_both(&g, &c);
  }
  /* a square of side 1.6 has a gap in the middle: no junction */
  {
    double r[8] = {0, 0, 1.6, 0, 1.6, 1.6, 0, 1.6};
    afv_box b = test_open_box();
    afv_geom g = {0};
    afv_clusters c = {0};
    if (!analyse(4, r, &b, &g, &c)) return;
    CHECK(c.n_junctions == 0 && c.ec[0] == 4, "gapped square: V3 %d Ec %d",
          c.n_junctions, c.ec[0]);
    free_both(&g, &c);
  }
}

/* ---- T1 ---------------------------------------------------------------- */
/* Cells A = (-x, 0), B = (x, 0), C = (0, -y), D = (0, y): from x = 0.9,
** y = 0.5 (C-D in contact, A-B not) to x = 0.5, y = 0.9 (A-B, not C-D). */
static void exchange_config(double s, const int *perm, double *r)
{
  double x = 0.9 - 0.4 * s, y = 0.5 + 0.4 * s;
  double base[8];
  int i;
  base[0] = -x; base[1] = 0; base[2] = x; base[3] = 0;
  base[4] = 0; base[5] = -y; base[6] = 0; base[7] = y;
  for (i = 0; i < 4; i++) {
    r[2*perm[i]] = base[2*i];
    r[2*perm[i]+1] = base[2*i+1];
  }
}

static double exchange_t1(const int *perm, int steps)
{
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  afv_t1 t = {0, NULL};
  double r[8], t1 = -1;
  int k;
  for (k = 0; k <= steps; k++) {
    exchange_config((double)k / steps, perm, r);
    if (!analyse(4, r, &b, &g, &c)) break;
    if (k == 0) afv_t1_start(&t, &c);
    t1 = afv_t1_count(&t, &c);
    CHECK(t1 == 0 || t1 == 0.5 || t1 == 1, "step %d: T1 = %g", k, t1);
  }
  free_both(&g, &c);
  afv_t1_free(&t);
  return t1;
}

static void t1_neighbour_exchange(void)
{
  static const int id[4] = {0, 1, 2, 3}, perm[4] = {2, 0, 3, 1};
  double a = exchange_t1(id, 20), p = exchange_t1(perm, 20);
  CHECK_CLOSE(a, 1.0, 0, 0, "T1 of one neighbour exchange");
  CHECK_CLOSE(p, a, 0, 0, "T1 after relabelling the cells");
}

static void t1_flicker_cancels(void)
{
  afv_box b = test_open_box();
  afv_geom g = {0};
  afv_clusters c = {0};
  afv_t1 t = {0, NULL};
  double r[4] = {0, 0, 1.8, 0};
  int flip;
  if (!analyse(2, r, &b, &g, &c)) return;
  afv_t1_start(&t, &c);
  for (flip = 1; flip <= 6; flip++) {
    r[2] = flip % 2 ? 2.2 : 1.8;           /* contact off, on, off, ... */
    if (!analyse(2, r, &b, &g, &c)) break;
    CHECK_CLOSE(afv_t1_count(&t, &c), flip % 2 ? 0.5 : 0.0, 0, 0,
                "T1 after flips");
  }
  free_both(&g, &c);
  afv_t1_free(&t);
}

/* ---- trajectories ------------------------------------------------------ */
/* A tight square of 4 cells drifting by v per frame across a 6 x 6 box,
** stored wrapped: after unwrapping, MSD = (v t)^2 and relative MSD = 0. */
static void msd_translation_and_unwrap(void)
{
  const double vx = 0.7, vy = -0.3, sq[8] = {1, 1, 2.2, 1, 2.2, 2.2, 1, 2.2};
  afv_traj tr;
  afv_msd m;
  int f, i, k, n = 4, nf = 60;
  double err_unwrap = 0, err_msd = 0, err_rel = 0;
  if (!test_traj_alloc(&tr, n, nf, test_periodic_box(6, 6))) return;
  for (f = 0; f < nf; f++) {
    tr.t[f] = 0.5 * f;
    for (i = 0; i < n; i++) {
      double *q = tr.r + (size_t)f * 2 * n + 2 * i;
      q[0] = sq[2*i] + vx * f;
      q[1] = sq[2*i+1] + vy * f;
      afv_wrap(&tr.box, &q[0], &q[1]);
    }
  }
  afv_traj_unwrap(&tr);
  for (f = 0; f < nf; f++)
    for (i = 0; i < n; i++) {
      double *q = tr.r + (size_t)f * 2 * n + 2 * i;
      double e = fabs(q[0] - sq[2*i] - vx * f) + fabs(q[1] - sq[2*i+1] - vy * f);
      if (e > err_unwrap) err_unwrap = e;
    }
  CHECK(err_unwrap < 1e-12, "unwrapped positions off by %.3e", err_unwrap);
  if (afv_msd_compute(&m, &tr, 0, 1.0) != AFV_OK) {
    CHECK(0, "afv_msd_compute failed");
    afv_traj_free(&tr);
    return;
  }
  CHECK(m.nlags > 10 && m.lag[m.nlags - 1] == nf - 1, "lags: %d, last %d",
        m.nlags, m.nlags ? m.lag[m.nlags - 1] : -1);
  for (k = 0; k < m.nlags; k++) {
    double L = m.lag[k], want = (vx * vx + vy * vy) * L * L;
    if (fabs(m.msd[k] - want) > err_msd) err_msd = fabs(m.msd[k] - want);
    if (fabs(m.msd_rel[k]) > err_rel) err_rel = fabs(m.msd_rel[k]);
    CHECK_CLOSE(m.dt[k], 0.5 * L, 1e-14, 0, "lag time");
  }
  CHECK(err_msd < 1e-9, "plain MSD differs from (v t)^2 by %.3e", err_msd);
  CHECK(err_rel < 1e-20, "relative MSD of a rigid translation: %.3e", err_rel);
  afv_msd_free(&m);
  afv_traj_free(&tr);
}

/* The MSD's standard error is across cells: isolated cells moving
** straight at speeds v_i = 0.01 (i + 1) have MSD_i(L) = (v_i L)^2 at every
** time origin, so the error is L^2 sd(v_i^2) / sqrt(n), whatever the
** number of origins (an error over all (origin, cell) samples would
** shrink with it); relative = plain without contacts. */
static void msd_standard_error_across_cells(void)
{
  enum { N = 12, NF = 30 };
  afv_traj tr;
  afv_msd m;
  double mean = 0, ss = 0, worst = 0;
  int f, i, k;
  if (!test_traj_alloc(&tr, N, NF, test_open_box())) return;
  for (i = 0; i < N; i++) {
    double v2 = pow(0.01 * (i + 1), 2);
    mean += v2 / N;
  }
  for (i = 0; i < N; i++) ss += pow(pow(0.01 * (i + 1), 2) - mean, 2);
  for (f = 0; f < NF; f++) {
    tr.t[f] = f;
    for (i = 0; i < N; i++) {
      tr.r[(size_t)f * 2 * N + 2 * i] = 5.0 * i + 0.01 * (i + 1) * f;
      tr.r[(size_t)f * 2 * N + 2 * i + 1] = 0;
    }
  }
  CHECK(afv_msd_compute(&m, &tr, 0, 1.0) == AFV_OK, "afv_msd_compute");
  for (k = 0; k < m.nlags; k++) {
    double L = m.lag[k], want = L * L * sqrt(ss / (N - 1) / N);
    worst = fmax(worst, fabs(m.msd_se[k] - want) / want);
    worst = fmax(worst, fabs(m.msd_rel_se[k] - want) / want);
  }
  CHECK(m.nlags > 3 && worst < 1e-9, "%d lags, standard error off by %.3g "
        "(relative)", m.nlags, worst);
  afv_msd_free(&m);
  afv_traj_free(&tr);
}

/* Two cells in contact; cell 0 moves by (1, 0): each relative displacement
** is 1 in length, so relative MSD = 1 while plain MSD = 1/2. */
static void msd_relative_by_hand(void)
{
  afv_traj tr;
  afv_msd m;
  if (!test_traj_alloc(&tr, 2, 2, test_open_box())) return;
  tr.t[1] = 1;
  tr.r[2] = tr.r[6] = 1.5;
  tr.r[4] = 1;
  CHECK(afv_msd_compute(&m, &tr, 0, 1.0) == AFV_OK, "afv_msd_compute");
  CHECK(m.nlags == 1, "nlags %d", m.nlags);
  if (m.nlags == 1) {
    CHECK_CLOSE(m.msd[0], 0.5, 1e-15, 0, "plain MSD");
    CHECK_CLOSE(m.msd_rel[0], 1.0, 1e-15, 0, "relative MSD");
  }
  afv_msd_free(&m);
  afv_traj_free(&tr);
}

/* Independent Gaussian walks (isolated cells, step sd s per component per
** frame): MSD(L) = 2 s^2 L, D = s^2 / 2.  The estimate's relative standard
** error is about sqrt(2 L / (N (T - L))) (|dr|^2 is exponential in 2D, and
** overlapping origins are about L frames apart when independent). */
static void msd_random_walks(void)
{
  enum { N = 100, T = 400 };
  const double s = 0.1;
  afv_traj tr;
  afv_msd m;
  int f, i, k, checked = 0;
  if (!test_traj_alloc(&tr, N, T, test_open_box())) return;
  test_rng_seed(11);
  for (i = 0; i < N; i++) {
    /* 30 l apart: each walk spreads by s sqrt(T) = 2 l per coordinate, so
    ** two cells come within 2l of each other only at a 10-sigma excursion */
    tr.r[2*i] = 30.0 * (i % 10);
    tr.r[2*i+1] = 30.0 * (i / 10);
  }
  for (f = 1; f < T; f++) {
    tr.t[f] = f;
    for (i = 0; i < 2 * N; i++)
      tr.r[(size_t)f * 2 * N + i] = tr.r[(size_t)(f - 1) * 2 * N + i]
                                    + s * test_rng_normal();
  }
  if (afv_msd_compute(&m, &tr, 0, 1.0) != AFV_OK) {
    CHECK(0, "afv_msd_compute failed");
    afv_traj_free(&tr);
    return;
  }
  for (k = 0; k < m.nlags && m.lag[k] <= 40; k++) {
    double L = m.lag[k], want = 2 * s * s * L;
    double tol = 4 * sqrt(2 * L / (N * (T - L)));
    CHECK_CLOSE(m.msd[k] / (4 * m.dt[k]), s * s / 2, tol, 0,
                "D from random walks");
    CHECK_CLOSE(m.msd[k], want, tol, 0, "MSD of random walks");
    CHECK(m.msd_rel[k] == m.msd[k], "isolated cells: relative != plain");
    checked++;
  }
  CHECK(checked >= 10, "only %d lags checked", checked);
  afv_msd_free(&m);
  afv_traj_free(&tr);
}

/* ---- autocorrelation time ---------------------------------------------- */
/* AR(1) x_t = a x_{t-1} + noise: rho(t) = a^t, tau = (1 + a) / (1 - a).
** Sokal: var(tau) ~ 2 (2W + 1) / n tau^2; the test allows 4 sigma. */
static void tau_ar1(void)
{
  enum { NS = 400000 };
  const double a = 0.8, want = (1 + a) / (1 - a);
  double *x = malloc(NS * sizeof(double)), tau, sigma, c[50];
  int i, reliable, w = (int)ceil(5 * want);   /* Sokal's window, c = 5 */
  if (!x) {
    CHECK(0, "out of memory");
    return;
  }
  test_rng_seed(3);
  x[0] = test_rng_normal() / sqrt(1 - a * a);
  for (i = 1; i < NS; i++) x[i] = a * x[i - 1] + test_rng_normal();
  tau = afv_autocorr_time(x, NS, &reliable);
  sigma = want * sqrt(2.0 * (2 * w + 1) / NS);
  CHECK(reliable, "window not reached");
  CHECK_CLOSE(tau, want, 0, 4 * sigma, "AR(1) integrated autocorrelation");
  for (i = 0; i < 50; i++) c[i] = 0.25;
  CHECK(afv_autocorr_time(c, 50, NULL) == HUGE_VAL, "constant: not infinite");
  free(x);
}

/* ---- mean field -------------------------------------------------------- */
/* The paper prints P0* = 5.73 for Lambda = 0.2, A0 = pi, KP = 1. */
static void meanfield_paper_point(void)
{
  double p = afv_meanfield_p0(0.2, PI, 1), h = 1e-5, d;
  CHECK(fabs(p - 5.73) < 0.005, "P0* = %.6f, paper 5.73", p);
  /* the closed form is where dE/dtheta of the energy vanishes at pi/6 */
  d = (afv_meanfield_energy(PI / 6 + h, 0.2, PI, 1, p)
       - afv_meanfield_energy(PI / 6 - h, 0.2, PI, 1, p)) / (2 * h);
  CHECK(fabs(d) < 1e-8, "dE/dtheta at pi/6, P0 = P0*: %.3e", d);
  /* and one step of P0 either side changes its sign: a true crossing */
  d = afv_meanfield_energy(PI / 6 + h, 0.2, PI, 1, p + 0.1)
      - afv_meanfield_energy(PI / 6 - h, 0.2, PI, 1, p + 0.1);
  CHECK(d > 0, "P0 above P0*: energy should rise towards pi/6 (%.3e)", d);
}

/* The mean-field cell energy is that of the real model: a periodic
** triangular lattice at spacing d = 2 cos(theta), theta < pi/6. */
static void meanfield_matches_lattice(void)
{
  static const double thetas[3] = {0.2, 0.35, 0.5};
  double r[2 * 16];
  int k, n;
  for (k = 0; k < 3; k++) {
    afv_box b;
    afv_geom g = {0};
    afv_params p;
    afv_params_default(&p);
    p.P0 = 5.0;
    n = tri_lattice(4, 4, 2 * cos(thetas[k]), r, &b);
    CHECK(afv_compute(&g, n, r, &p, &b, NULL) == AFV_OK, "afv_compute");
    CHECK_CLOSE(g.energy / n,
                afv_meanfield_energy(thetas[k], p.Lambda, p.A0, p.KP, p.P0),
                1e-12, 0, "cell energy of the gapped honeycomb");
    afv_geom_free(&g);
  }
}

static void meanfield_command(void)
{
  FILE *fp;
  char line[256] = "";
  if (access("./afv", X_OK) != 0) {
    SKIP("./afv not built");
    return;
  }
  fp = popen("./afv meanfield --Lambda 0.2 --A0 3.141592653589793 --KP 1", "r");
  CHECK(fp != NULL, "popen failed");
  if (!fp) return;
  if (!fgets(line, sizeof line, fp)) line[0] = 0;
  CHECK(pclose(fp) == 0, "afv meanfield exit status non-zero");
  /* the paper's digits: 5.73 */
  CHECK(fabs(strtod(line, NULL) - 5.73) < 0.005, "afv meanfield printed '%s'",
        line);
}

/* ---- SVG --------------------------------------------------------------- */
/* A small well-formedness check: tags nest and close, attributes are
** name="value", numbers in attribute values are finite.  Returns 0 and
** says where on the first problem. */
static int svg_well_formed(const char *s)
{
  const char *stack[64];
  size_t len[64];
  int depth = 0, root_seen = 0;
  while ((s = strchr(s, '<')) != NULL) {
    const char *name;
    size_t nl;
    if (!strncmp(s, "<?", 2) || !strncmp(s, "<!--", 4)) {
      const char *e = strstr(s, s[1] == '?' ? "?>" : "-->");
      if (!e) return 0;
      s = e;
      continue;
    }
    if (s[1] == '/') {
      name = s + 2;
      nl = strcspn(name, " >");
      if (depth == 0 || nl != len[depth - 1]
          || strncmp(name, stack[depth - 1], nl)) {
        CHECK(0, "mismatched </%.*s>", (int)nl, name);
        return 0;
      }
      depth--;
      s = name + nl;
      continue;
    }
    name = s + 1;
    nl = strcspn(name, " \n/>");
    s = name + nl;
    for (;;) {
      const char *v;
      s += strspn(s, " \n");
      if (*s == '>' || !strncmp(s, "/>", 2)) break;
      s += strcspn(s, "=> \n");
      if (*s != '=' || s[1] != '"') {
        CHECK(0, "unquoted attribute in <%.*s>", (int)nl, name);
        return 0;
      }
      v = s + 2;
      s = strchr(v, '"');
      if (!s) return 0;
      while (v < s) {   /* every number-looking token must be finite */
        char *end;
        double x = strtod(v, &end);
        if (end > v && end <= s && !isfinite(x)) {
          CHECK(0, "non-finite number in <%.*s>", (int)nl, name);
          return 0;
        }
        v = end > v ? end : v + 1;
      }
      s++;
    }
    if (*s == '>') {
      if (depth == 64) return 0;
      stack[depth] = name;
      len[depth++] = nl;
      root_seen = 1;
    }
  }
  CHECK(depth == 0 && root_seen, "unclosed tags: depth %d", depth);
  return depth == 0 && root_seen;
}

static int count_class(const char *s, const char *cls)
{
  char key[64];
  int m = 0;
  snprintf(key, sizeof key, "class=\"%s\"", cls);
  while ((s = strstr(s, key)) != NULL) {
    m++;
    s++;
  }
  return m;
}

/* Reads a whole temporary file written by fn into a malloc'd string. */
static char *slurp(FILE *fp)
{
  long size;
  char *buf;
  fflush(fp);
  size = ftell(fp);
  rewind(fp);
  buf = malloc((size_t)size + 1);
  if (!buf) return NULL;
  buf[fread(buf, 1, (size_t)size, fp)] = 0;
  return buf;
}

/* The mixed configuration of omega_mixed_by_hand, drawn in open space:
** counts against the geometry, counted independently here. */
static void svg_counts_match_geometry(void)
{
  double r[18] = {0, 0, 1.6, 0, 1.6, 1.6, 0, 1.6, 0.8, -1.2,
                  10, 0, 11.2, 0, 10.6, 1.03923, -10, -10};
  double theta[9] = {0, 1, 2, 3, 4, 5, 6, 0.5, 1.5};
  afv_box b = test_open_box();
  afv_params p;
  afv_geom g = {0};
  FILE *fp = tmpfile();
  char *svg;
  int i, k, edges = 0, arcs = 0;
  afv_params_default(&p);
  CHECK(fp != NULL, "tmpfile");
  if (!fp || afv_geometry(&g, 9, r, &p, &b) != AFV_OK) return;
  for (i = 0; i < 9; i++)
    for (k = g.piece_start[i]; k < g.piece_start[i] + g.n_pieces[i]; k++) {
      if (g.pieces[k].length <= AFV_CONTACT_TOL) continue;
      if (g.pieces[k].nbr == AFV_ARC) arcs++;
      else edges++;
    }
  CHECK(afv_svg_write(fp, &g, 9, r, theta, &p, &b) == AFV_OK, "svg_write");
  svg = slurp(fp);
  if (svg) {
    CHECK(svg_well_formed(svg), "SVG not well formed");
    CHECK(count_class(svg, "edge") == edges / 2, "edges %d, want %d",
          count_class(svg, "edge"), edges / 2);
    CHECK(count_class(svg, "arc") == arcs, "arcs %d, want %d",
          count_class(svg, "arc"), arcs);
    CHECK(count_class(svg, "junction") == 2, "junctions %d, want 2 (by hand)",
          count_class(svg, "junction"));
    CHECK(count_class(svg, "centre") == 9 && count_class(svg, "polarity") == 9,
          "centres %d arrows %d, want 9", count_class(svg, "centre"),
          count_class(svg, "polarity"));
    CHECK(strstr(svg, " A 1 1 0 ") != NULL, "no SVG arc command");
  }
  free(svg);
  fclose(fp);
  afv_geom_free(&g);
}

/* Cells across the periodic boundary are drawn at their images (more
** elements than cells), clipped to the box; theta NULL: no arrows. */
static void svg_periodic_images(void)
{
  double r[2 * 16];
  afv_box b;
  afv_params p;
  afv_geom g = {0};
  FILE *fp = tmpfile();
  char *svg;
  int n = tri_lattice(4, 4, 1.5, r, &b);
  afv_params_default(&p);
  if (!fp || afv_geometry(&g, n, r, &p, &b) != AFV_OK) return;
  CHECK(afv_svg_write(fp, &g, n, r, NULL, &p, &b) == AFV_OK, "svg_write");
  svg = slurp(fp);
  if (svg) {
    CHECK(svg_well_formed(svg), "SVG not well formed");
    CHECK(count_class(svg, "polarity") == 0, "arrows without theta");
    CHECK(count_class(svg, "edge") > 3 * n, "edges %d: images missing",
          count_class(svg, "edge"));
    CHECK(count_class(svg, "box") == 1 && strstr(svg, "clip-path") != NULL,
          "box or clip path missing");
  }
  free(svg);
  fclose(fp);
  afv_geom_free(&g);
}

static void svg_plot_well_formed(void)
{
  double x[5] = {1, 10, 100, 1000, 1e4}, y[5] = {0.1, 1, 5, 0, 30};
  afv_plot_series s;
  afv_plot loglog = {"t", "x", "y", 1, 1, 0, 0, NULL},
           linear = {"t", "x", "y", 0, 0, 0, 1.2, NULL};
  FILE *fp = tmpfile();
  char *svg;
  s.x = x;
  s.y = y;
  s.n = 5;
  s.label = "a < b & c";
  s.color = "#123456";
  s.points = 0;
  if (!fp) return;
  CHECK(afv_svg_plot(fp, &loglog, &s, 1) == AFV_OK, "plot");
  CHECK(afv_svg_plot(fp, &linear, &s, 1) == AFV_OK, "plot");
  svg = slurp(fp);
  if (svg) {
    char *second = strstr(svg + 1, "<?xml");
    CHECK(second != NULL, "two plots expected");
    if (second) {
      *second = 0;
      CHECK(svg_well_formed(svg), "log-log plot not well formed");
      *second = '<';
      CHECK(svg_well_formed(second), "linear plot not well formed");
    }
    CHECK(strstr(svg, "a &lt; b &amp; c") != NULL, "label not escaped");
  }
  free(svg);
  fclose(fp);
}

/* ---- afv analyze, end to end ------------------------------------------- */
/* A confluent lattice translating rigidly: one cluster throughout, Omega 1,
** T1 0, relative MSD 0, tau infinite; all files written. */
static void analyze_synthetic_run(void)
{
  double r0[2 * 16];
  afv_box b;
  afv_traj tr;
  afv_analysis a;
  char dir[64], path[128], err[256];
  int n = tri_lattice(4, 4, 1.5, r0, &b), f, i, k;
  static const char *files[] = {"summary.txt", "msd.csv", "csd.csv",
                                "csd_binned.csv", "series.csv"};
  if (!test_traj_alloc(&tr, n, 30, b)) return;
  for (f = 0; f < 30; f++) {
    tr.t[f] = 10.0 * f;
    for (i = 0; i < n; i++) {
      tr.r[(size_t)f * 2 * n + 2 * i] = r0[2*i] + 0.05 * f;
      tr.r[(size_t)f * 2 * n + 2 * i + 1] = r0[2*i+1];
    }
  }
  CHECK(afv_analyze(&a, &tr, 1.0, 0.1, 0.1, 100, 50) == AFV_OK, "analyze");
  CHECK(a.first == 10, "steady part starts at frame %d, want 10", a.first);
  CHECK_CLOSE(a.mean[0], 1.0, 0, 0, "mean N_GC/N");
  CHECK_CLOSE(a.mean[2], 1.0, 0, 1e-15, "mean Omega");
  CHECK_CLOSE(a.sd[0], 0.0, 0, 0, "sd N_GC/N");
  CHECK_CLOSE(a.t1_final, 0.0, 0, 0, "T1");
  CHECK_CLOSE(a.csd[n], 1.0, 0, 0, "p(N)");
  CHECK(a.tau_ngc == HUGE_VAL, "tau of a constant N_GC: %g", a.tau_ngc);
  CHECK_CLOSE(a.ds_lag, 50.0, 0, 0, "lag used for D_s");
  CHECK_CLOSE(a.ds, 0.0, 0, 1e-20, "D_s of a rigid translation");
  CHECK_CLOSE(a.ds_plain, 0.25 * 0.25 / (4 * 50), 1e-9, 0, "plain D_s");
  CHECK_CLOSE(a.d0, 0.05, 1e-15, 0, "D_0 = v0^2 / (2 Dr)");
  snprintf(dir, sizeof dir, "/tmp/afv_analysis_test_%ld", (long)getpid());
  CHECK(mkdir(dir, 0700) == 0, "mkdir %s", dir);
  CHECK(afv_analysis_write(&a, dir, err, sizeof err) == AFV_OK, "%s", err);
  for (k = 0; k < 5; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, files[k]);
    CHECK(access(path, R_OK) == 0, "%s missing", path);
    remove(path);
  }
  rmdir(dir);
  afv_analysis_free(&a);
  afv_traj_free(&tr);
}

/* D_eff = D_s / D_0 is nan where D_0 = v0^2 / (2 Dr) is 0 (v0 = 0) or
** undefined (Dr = 0), never 0, which afv collect would label glassy
** (before: 0 at Dr = 0, for v0 = 1 and for v0 = 0); and afv analyze
** refuses --Dr -1 (before: accepted). */
static void deff_undefined_without_rotational_diffusion(void)
{
  double r0[2 * 16];
  afv_box b;
  afv_traj tr;
  afv_analysis a;
  int n = tri_lattice(4, 4, 1.5, r0, &b), f, i, k;
  static const double v0[3] = {1, 0, 1}, Dr[3] = {0, 0, 0.1};
  if (!test_traj_alloc(&tr, n, 30, b)) return;
  for (f = 0; f < 30; f++) {
    tr.t[f] = 10.0 * f;
    for (i = 0; i < 2 * n; i++)    /* every cell jiggles: D_s > 0 */
      tr.r[(size_t)f * 2 * n + i] = r0[i] + 0.02 * sin(1.3 * f + 2.1 * i);
  }
  for (k = 0; k < 3; k++) {
    CHECK(afv_analyze(&a, &tr, 1.0, v0[k], Dr[k], 0, 50) == AFV_OK, "analyze");
    CHECK(a.ds > 0, "fixture: D_s %g", a.ds);
    if (k < 2)
      CHECK(isnan(a.deff) && isnan(a.d0), "v0 %g, Dr 0: D_eff %g, D_0 %g, "
            "want nan", v0[k], a.deff, a.d0);
    else
      CHECK_CLOSE(a.deff, a.ds / 5, 1e-12, 0, "D_eff at Dr 0.1, v0 1");
    afv_analysis_free(&a);
  }
  afv_traj_free(&tr);
  CHECK(test_sh("d=$(mktemp -d) && touch $d/trajectory.dat && ./afv analyze "
                "$d --Dr -1 2>&1 | grep -q 'Dr: -1: must be >= 0'; s=$?; "
                "rm -rf $d; exit $s") == 0, "afv analyze --Dr -1: not refused "
        "naming --Dr");
}

/* ---- physics smoke checks (short real runs) ------------------------------ */
/* The paper's protocol at small size: 100 cells at phi = 0.5 in a periodic
** box, a compact cluster relaxed at v0 = 0, then 3000 steps (t = 30) at
** v0 = 0.1, sampled every 500 steps.  Omega's extremes at the sample states
** of the paper's summary figure, P0 = 4 and 8.8, are far from 0.5, so the
** checks are robust; min and max over the samples are what is checked. */
static int smoke_run(double P0, double *ngc_min, double *om_min,
                     double *om_max)
{
  enum { N = 100 };
  double r[2 * N], L = sqrt(N * PI / 0.5);
  afv_params p;
  afv_dyn d;
  afv_box b = test_periodic_box(L, L);
  afv_sim s;
  afv_clusters c = {0};
  afv_relax_report rep;
  int k, st;
  afv_params_default(&p);
  p.P0 = P0;
  afv_dyn_default(&d);
  d.v0 = 0.1;
  memset(&s, 0, sizeof s);
  *ngc_min = *om_min = 2;
  *om_max = -1;
  st = afv_init_lattice(N, 1.8, &b, r);
  if (st == AFV_OK) st = afv_sim_init(&s, N, r, NULL, &p, &b, &d);
  if (st == AFV_OK) st = afv_relax(&s, 1e-6, 100000, &rep, NULL, NULL);
  for (k = 0; st == AFV_OK && k <= 3000; k++) {
    if (k % 500 == 0) {
      if ((st = afv_clusters_compute(&c, &s.geom, s.r, 1.0, &b)) != AFV_OK)
        break;
      if ((double)c.giant / N < *ngc_min) *ngc_min = (double)c.giant / N;
      if (c.omega < *om_min) *om_min = c.omega;
      if (c.omega > *om_max) *om_max = c.omega;
    }
    if (k < 3000) st = afv_sim_step(&s);
  }
  CHECK(st == AFV_OK, "P0 %g: %s", P0, afv_strerror(st));
  afv_sim_free(&s);
  afv_clusters_free(&c);
  return st == AFV_OK;
}

static void smoke_epithelial_cluster(void)
{
  double ngc, lo, hi;
  if (!smoke_run(4.0, &ngc, &lo, &hi)) return;
  CHECK(ngc == 1, "P0 4, v0 0.1: min N_GC/N %g, want 1", ngc);
  CHECK(lo > 0.5, "P0 4, v0 0.1: min Omega %g, want > 0.5", lo);
}

static void smoke_mesenchymal_cluster(void)
{
  double ngc, lo, hi;
  if (!smoke_run(8.8, &ngc, &lo, &hi)) return;
  CHECK(hi < 0.5, "P0 8.8, v0 0.1: max Omega %g, want < 0.5", hi);
}

/* ---- the commands, end to end -------------------------------------------- */
/* Exit status of a shell command (-1 if it did not exit normally). */
static int run_status(const char *cmd)
{
  int st = system(cmd);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* afv run (short), then afv analyze and afv draw on its output; and the
** bad inputs of the three commands, each exit status 2. */
static void commands_end_to_end(void)
{
  char dir[64], cmd[512], path[128];
  FILE *fp;
  char line[512];
  int found = 0;
  if (access("./afv", X_OK) != 0) {
    SKIP("./afv not built");
    return;
  }
  snprintf(dir, sizeof dir, "/tmp/afv_analysis_cli_%ld", (long)getpid());
  snprintf(cmd, sizeof cmd, "./afv run --out %s --N 30 --steps 400 "
           "--frame_every 50 --sample_every 100 --svg_every 0 --quiet", dir);
  CHECK(run_status(cmd) == 0, "%s failed", cmd);
  snprintf(path, sizeof path, "%s/observables.csv", dir);
  fp = fopen(path, "r");
  CHECK(fp && fgets(line, sizeof line, fp)
        && strstr(line, "ngc_frac,n_clusters,omega,t1") != NULL,
        "observables.csv lacks the analysis columns");
  if (fp) fclose(fp);
  snprintf(cmd, sizeof cmd, "./afv analyze %s --lag 2 > /dev/null", dir);
  CHECK(run_status(cmd) == 0, "%s failed", cmd);
  snprintf(path, sizeof path, "%s/analysis/summary.txt", dir);
  fp = fopen(path, "r");
  while (fp && fgets(line, sizeof line, fp)) found += !strncmp(line, "D_eff ", 6);
  if (fp) fclose(fp);
  CHECK(found == 1, "summary.txt has no D_eff line");
  snprintf(cmd, sizeof cmd, "./afv draw %s/trajectory.dat --frame 2 > "
           "%s/f2.svg", dir, dir);
  CHECK(run_status(cmd) == 0, "%s failed", cmd);
  snprintf(cmd, sizeof cmd, "./afv draw %s/trajectory.dat --frame 99 > "
           "/dev/null 2>&1", dir);
  CHECK(run_status(cmd) == 2, "draw of a missing frame: not exit 2");
  CHECK(run_status("./afv draw /nonexistent.xy > /dev/null 2>&1") == 2,
        "draw of a missing file: not exit 2");
  CHECK(run_status("./afv analyze /nonexistent_dir > /dev/null 2>&1") == 2,
        "analyze of a missing run: not exit 2");
  CHECK(run_status("./afv meanfield --KP 0 > /dev/null 2>&1") == 2,
        "meanfield --KP 0: not exit 2");
  CHECK(run_status("./afv meanfield --bogus 1 > /dev/null 2>&1") == 2,
        "meanfield --bogus: not exit 2");
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  CHECK(run_status(cmd) == 0, "cleanup of %s", dir);
}

/* afv analyze on afv's own (unwrapped) trajectory: two cells jump 7 l per
** frame in a 10 l box.  Folding those jumps into the minimum image (as an
** earlier version did) would give 9 l^2 at one frame; the true MSD is
** 49 l^2. */
static void analyze_keeps_unwrapped_jumps(void)
{
  char dir[64], cmd[256], path[128], line[256];
  afv_box b = test_periodic_box(10, 10);
  double r[4], th[2] = {0, 0}, lag = 0, msd = 0;
  FILE *fp;
  int f;
  if (access("./afv", X_OK) != 0) {
    SKIP("./afv not built");
    return;
  }
  snprintf(dir, sizeof dir, "/tmp/afv_unwrapped_%ld", (long)getpid());
  snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
  CHECK(run_status(cmd) == 0, "mkdir");
  snprintf(path, sizeof path, "%s/trajectory.dat", dir);
  fp = fopen(path, "w");
  CHECK(fp != NULL, "cannot write %s", path);
  if (!fp) return;
  afv_traj_write_header(fp, 2, &b);
  for (f = 0; f < 6; f++) {
    r[0] = 1 + 7.0 * f;  r[1] = 2;
    r[2] = 1 + 7.0 * f;  r[3] = 7;
    afv_traj_write_frame(fp, f, f, 2, r, th);
  }
  fclose(fp);
  snprintf(cmd, sizeof cmd, "./afv analyze %s --l 1 --v0 1 --Dr 0.1 "
           "--lag 1 > /dev/null 2>&1", dir);
  CHECK(run_status(cmd) == 0, "%s failed", cmd);
  snprintf(path, sizeof path, "%s/analysis/msd.csv", dir);
  fp = fopen(path, "r");
  CHECK(fp != NULL, "no %s", path);
  while (fp && fgets(line, sizeof line, fp))
    if (sscanf(line, "%lf,%lf", &lag, &msd) == 2) break;
  if (fp) fclose(fp);
  CHECK(lag == 1 && fabs(msd - 49) < 1e-9, "MSD at lag %g: %.17g, want 49",
        lag, msd);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  run_status(cmd);
}

/* Two analyses hold the same results, bit for bit. */
static int same_analysis(const afv_analysis *x, const afv_analysis *y)
{
  size_t f = (size_t)x->nframes, L = (size_t)x->msd.nlags;
  return x->nframes == y->nframes && x->first == y->first
         && x->msd.nlags == y->msd.nlags
         && !memcmp(x->t, y->t, f * sizeof(double))
         && !memcmp(x->ngc_frac, y->ngc_frac, f * sizeof(double))
         && !memcmp(x->n_clusters, y->n_clusters, f * sizeof(double))
         && !memcmp(x->omega, y->omega, f * sizeof(double))
         && !memcmp(x->t1, y->t1, f * sizeof(double))
         && !memcmp(x->csd, y->csd, ((size_t)x->n + 1) * sizeof(double))
         && !memcmp(x->msd.lag, y->msd.lag, L * sizeof(int))
         && !memcmp(x->msd.dt, y->msd.dt, L * sizeof(double))
         && !memcmp(x->msd.msd, y->msd.msd, L * sizeof(double))
         && !memcmp(x->msd.msd_rel, y->msd.msd_rel, L * sizeof(double))
         && !memcmp(x->msd.samples, y->msd.samples, L * sizeof(long))
         && !memcmp(x->mean, y->mean, sizeof x->mean)
         && !memcmp(x->sd, y->sd, sizeof x->sd)
         && !memcmp(&x->ds, &y->ds, sizeof x->ds)
         && !memcmp(&x->t1_rate, &y->t1_rate, sizeof x->t1_rate)
         && !memcmp(&x->msd_beta, &y->msd_beta, sizeof x->msd_beta)
         && !memcmp(&x->tau_ngc, &y->tau_ngc, sizeof x->tau_ngc);
}

/* afv analyze's streaming (analysis.c, STREAMING): from the file with a
** ring of 2, 5 or 40 frames (the shorter ones send most lags to the second
** pass) the same bits as from every frame in memory. */
static void analyze_streaming_same_bits(void)
{
  static const long ring[3] = {2, 5, 40};
  char dir[64], cmd[512], path[128], err[512] = "";
  afv_traj tr;
  afv_traj_file f;
  afv_analysis whole, part;
  int k;
  if (access("./afv", X_OK) != 0) {
    SKIP("./afv not built");
    return;
  }
  snprintf(dir, sizeof dir, "/tmp/afv_stream_%ld", (long)getpid());
  snprintf(cmd, sizeof cmd, "rm -rf %s && ./afv run --N 64 --P0 6 --v0 1 "
           "--steps 1200 --frame_every 20 --svg_every 0 --relax_max_steps "
           "200 --quiet --out %s > /dev/null 2>&1", dir, dir);
  CHECK(run_status(cmd) == 0, "%s failed", cmd);
  snprintf(path, sizeof path, "%s/trajectory.dat", dir);
  if (afv_traj_read(path, &tr, err, sizeof err) != AFV_OK) {
    CHECK(0, "%s", err);
    return;
  }
  CHECK(afv_analyze(&whole, &tr, 1, 1, 0.1, 3, 5) == AFV_OK
        && whole.msd.nlags > 10, "analysis in memory");
  for (k = 0; k < 3; k++) {
    long bytes = ring[k] * (44 * 64 + 64) + 1;
    CHECK(afv_traj_open(&f, path, err, sizeof err) == AFV_OK, "%s", err);
    CHECK(afv_analyze_ring(&part, NULL, &f, 1, 1, 0.1, 3, 5, bytes, err,
                           sizeof err) == AFV_OK, "%s", err);
    CHECK(same_analysis(&whole, &part), "ring of %ld frames: not the same "
          "bits (msd[last] %.17g vs %.17g)", ring[k],
          part.msd.msd[part.msd.nlags - 1],
          whole.msd.msd[whole.msd.nlags - 1]);
    afv_analysis_free(&part);
    afv_traj_close(&f);
  }
  afv_analysis_free(&whole);
  afv_traj_free(&tr);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  run_status(cmd);
}

/* The trajectory reader: a last line cut by an interrupted writer drops
** its frame; a frame short of cells in the middle of the file is an error
** that names the line. */
static void traj_reader_truncation(void)
{
  char path[64], err[256];
  afv_traj tr;
  FILE *fp;
  snprintf(path, sizeof path, "/tmp/afv_traj_%ld.dat", (long)getpid());
  fp = fopen(path, "w");
  CHECK(fp != NULL, "cannot write");
  if (!fp) return;
  fputs("# afv trajectory cells 2 box open\n# step 0 time 0\n1 2 0\n3 4 0\n"
        "\n\n# step 1 time 1\n1 2 0\n3 4", fp);      /* cut mid-line */
  fclose(fp);
  CHECK(afv_traj_read(path, &tr, err, sizeof err) == AFV_OK && tr.nframes == 1,
        "cut last line: %s, %d frames", err, tr.nframes);
  afv_traj_free(&tr);
  fp = fopen(path, "w");
  fputs("# afv trajectory cells 2 box open\n# step 0 time 0\n1 2 0\n\n\n"
        "# step 1 time 1\n1 2 0\n3 4 0\n", fp);      /* frame 0 is short */
  fclose(fp);
  CHECK(afv_traj_read(path, &tr, err, sizeof err) == AFV_EFORMAT
        && strstr(err, ":6:") != NULL, "short middle frame: '%s'", err);
  remove(path);
}

void suite_analysis(void)
{
  RUN(clusters_two_separate);
  RUN(clusters_chain);
  RUN(clusters_ring_wraps_box);
  RUN(clusters_isolated);
  RUN(clusters_shadowed_bisector);
  RUN(clusters_match_flood_fill);
  RUN(omega_confluent_lattice);
  RUN(omega_sparse_lattice);
  RUN(omega_mixed_by_hand);
  RUN(omega_degenerate_vertex);
  RUN(t1_neighbour_exchange);
  RUN(t1_flicker_cancels);
  RUN(msd_translation_and_unwrap);
  RUN(msd_relative_by_hand);
  RUN(msd_standard_error_across_cells);
  RUN(msd_random_walks);
  RUN(tau_ar1);
  RUN(meanfield_paper_point);
  RUN(meanfield_matches_lattice);
  RUN(meanfield_command);
  RUN(svg_counts_match_geometry);
  RUN(svg_periodic_images);
  RUN(svg_plot_well_formed);
  RUN(analyze_synthetic_run);
  RUN(deff_undefined_without_rotational_diffusion);
  RUN(smoke_epithelial_cluster);
  RUN(smoke_mesenchymal_cluster);
  RUN(commands_end_to_end);
  RUN(analyze_keeps_unwrapped_jumps);
  RUN(traj_reader_truncation);
  RUN(analyze_streaming_same_bits);
}
