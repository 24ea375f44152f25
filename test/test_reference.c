/*
** test_reference.c -- the model checked against its plainest statements
** (doc/reference.md):
**   - one step of afv_sim_step is the paper's equations of motion, bit for
**     bit, given the forces and the drawn normals;
**   - every cell's area and perimeter lie within the error of a brute-force
**     twin: the disk as a fine polygon clipped by the bisector half-planes
**     (Sutherland-Hodgman), on configurations with arcs, junctions on the
**     circle and pairs about to detach.
** (The twin of the two build modes is a separate program, test/twins.c,
** run by `make twins`: the modes are chosen at compile time.)
*/
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* ---- one step is the paper's equations ---------------------------------- */
/* Paper, Sec. Model, integrated by Euler-Maruyama with the state at the
** start of the step:
**     r_i'  = r_i + dt (mu F_i + v0_i n_i),   n_i = (cos th_i, sin th_i)
**     th_i' = th_i + sqrt(2 Dr_i dt) xi_i,    xi_i ~ N(0, 1)
** with F = -grad E from afv_compute at r, cos and sin from afv_sincos (the
** library's, as its polarity uses), xi_i = afv_rng_normal(seed, i, step,
** AFV_RNG_NOISE).  Every factor is away from 1 (mu, dt, v0_i, Dr_i), so a
** dropped or misplaced one shows; per-cell v0_i and Dr_i include 0 and a
** negative v0.  The step must equal these expressions exactly, for every
** test configuration (afv_sim_step is the plain Euler step, whatever the
** moves). */
static void check_one_step(const test_config *c, int per_cell)
{
  afv_params p;
  afv_dyn d;
  afv_sim s = {0};
  afv_geom g = {0};
  int n = c->n, i, st, moved = 0, turned = 0;
  double *theta = malloc((size_t)n * sizeof(double));
  double *v0 = malloc((size_t)n * sizeof(double));
  double *Dr = malloc((size_t)n * sizeof(double));
  double *r0 = malloc((size_t)(2 * n) * sizeof(double));
  double *f = malloc((size_t)(2 * n) * sizeof(double));
  double *th0 = malloc((size_t)n * sizeof(double));
  long long step0;
  CHECK(theta && v0 && Dr && r0 && f && th0, "out of memory");
  if (!(theta && v0 && Dr && r0 && f && th0)) goto out;
  afv_params_default(&p);
  p.P0 = 4.4;
  afv_dyn_default(&d);
  d.mu = 0.7;
  d.dt = 0.006;
  d.v0 = 0.35;
  d.Dr = 0.23;
  d.seed = 1234567;
  afv_init_angles(n, 99, theta);
  for (i = 0; i < n; i++) {
    v0[i] = i % 5 == 0 ? 0 : i % 5 == 1 ? -0.2 : 0.1 + 0.05 * i / n;
    Dr[i] = i % 4 == 0 ? 0 : 0.05 + 0.3 * i / n;
  }
  if (per_cell) {
    d.v0_i = v0;
    d.Dr_i = Dr;
  }
  st = afv_sim_init(&s, n, c->r, theta, &p, &c->box, &d);
  CHECK(st == AFV_OK, "%s: afv_sim_init: %s", c->name, afv_strerror(st));
  if (st != AFV_OK) goto out;
  /* the forces at r, from a geometry of its own */
  st = afv_compute(&g, n, c->r, &p, &c->box, f);
  CHECK(st == AFV_OK, "%s: afv_compute: %s", c->name, afv_strerror(st));
  memcpy(r0, s.r, (size_t)(2 * n) * sizeof(double));
  memcpy(th0, s.theta, (size_t)n * sizeof(double));
  step0 = s.step;
  st = afv_sim_step(&s);
  CHECK(st == AFV_OK, "%s: afv_sim_step: %s", c->name, afv_strerror(st));
  for (i = 0; st == AFV_OK && i < n; i++) {
    double v = per_cell ? v0[i] : d.v0, D = per_cell ? Dr[i] : d.Dr;
    double sn, cs, xi, x, y, th;
    afv_sincos(th0[i], &sn, &cs);
    xi = afv_rng_normal(d.seed, (uint32_t)i, (unsigned long long)step0,
                        AFV_RNG_NOISE);
    x = r0[2*i] + d.dt * (d.mu * f[2*i] + v * cs);
    y = r0[2*i+1] + d.dt * (d.mu * f[2*i+1] + v * sn);
    th = th0[i] + sqrt(2 * D * d.dt) * xi;    /* Dr_i = 0: th + 0 */
    if (s.r[2*i] != x || s.r[2*i+1] != y)
      moved++;
    if (s.theta[i] != th)
      turned++;
    if ((s.r[2*i] != x || s.r[2*i+1] != y || s.theta[i] != th)
        && moved + turned <= 3)
      test_fail(__FILE__, __LINE__, "%s%s cell %d: r' (%.17g, %.17g) th' "
                "%.17g, the equations give (%.17g, %.17g) %.17g", c->name,
                per_cell ? " (per-cell v0, Dr)" : "", i, s.r[2*i],
                s.r[2*i+1], s.theta[i], x, y, th);
  }
  CHECK(moved == 0 && turned == 0, "%s: %d positions and %d angles differ "
        "from the paper's equations", c->name, moved, turned);
out:
  afv_sim_free(&s);
  afv_geom_free(&g);
  free(theta); free(v0); free(Dr); free(r0); free(f); free(th0);
}

static void test_step_is_the_papers_equations(void)
{
  test_config c;
  int k, made;
  for (k = 0; (made = test_config_make(k, &c)) == 1; k++) {
    check_one_step(&c, 0);
    check_one_step(&c, 1);
    test_config_free(&c);
  }
  CHECK(made == 0, "out of memory");
  CHECK(k >= 6, "%d configurations tested, want 6 or more", k);
}

/* ---- a brute-force twin of the cell shape -------------------------------- */
/* The cell of i is K = D cap H: the disk D of radius l about r_i and the
** half-planes H of the bisectors of every centre closer than 2l.  Its
** twin: the regular M-gon P_M inscribed in the circle (vertices on it),
** clipped by the same half-planes one by one (Sutherland-Hodgman),
** K_M = P_M cap H, with area A_M and perimeter P_M.  The error, derived:
**   K_M in K, since P_M in D; so A_M <= A, and P_M <= P (K_M and K are
**     convex, and the perimeter of a convex set grows with the set);
**   K in K_M / c, c = cos(pi/M): P_M / c has inradius l, so holds D; H
**     holds the centre and is convex, so H in H / c; then D cap H in
**     (P_M cap H) / c.  Hence A <= A_M / c^2 and P <= P_M / c, the relative
**     errors tan^2(pi/M) ~ (pi/M)^2 and 1/c - 1 ~ (pi/M)^2 / 2;
**   K minus K_M lies in D minus P_M, of area pi l^2 (1 - sin(2pi/M) / (2pi/M)).
** With M = 16384: A within 3.7e-8 A and 1.2e-7 l^2, P within 1.8e-8 P,
** where the polygon's own rounding is about 1e-15.  The half-planes come
** from an all-pairs search with the minimum image, not from the library's
** neighbour lists. */
#define BRUTE_M     16384
#define BRUTE_ROUND 1e-12   /* rounding slack of the polygon, in l, l^2 */

/* Clips the convex polygon (x, y), m vertices, by p.u <= h into (xo, yo);
** returns the new vertex count (at most m + 1). */
static int clip_halfplane(const double *x, const double *y, int m, double ux,
                          double uy, double h, double *xo, double *yo)
{
  int k, mo = 0;
  for (k = 0; k < m; k++) {
    int k1 = k + 1 < m ? k + 1 : 0;
    double s0 = x[k] * ux + y[k] * uy - h, s1 = x[k1] * ux + y[k1] * uy - h;
    if (s0 <= 0) {
      xo[mo] = x[k];
      yo[mo++] = y[k];
    }
    if ((s0 < 0 && s1 > 0) || (s0 > 0 && s1 < 0)) {
      double t = s0 / (s0 - s1);
      xo[mo] = x[k] + t * (x[k1] - x[k]);
      yo[mo++] = y[k] + t * (y[k1] - y[k]);
    }
  }
  return mo;
}

/* Area (shoelace) and perimeter of the polygon (x, y), m vertices. */
static void polygon_measures(const double *x, const double *y, int m,
                             double *A, double *P)
{
  int k;
  *A = *P = 0;
  for (k = 0; k < m; k++) {
    int k1 = k + 1 < m ? k + 1 : 0;
    *A += 0.5 * (x[k] * y[k1] - x[k1] * y[k]);
    *P += hypot(x[k1] - x[k], y[k1] - y[k]);
  }
}

/* The brute-force area and perimeter of cell i (work: 4 (M + n) doubles). */
static void brute_cell(const test_config *c, int i, double l, double *work,
                       double *A, double *P)
{
  int room = BRUTE_M + c->n, m = BRUTE_M, j, k;
  double *x = work, *y = work + room, *xo = work + 2 * room,
         *yo = work + 3 * room;
  for (k = 0; k < BRUTE_M; k++) {
    x[k] = l * cos(2 * PI * k / BRUTE_M);
    y[k] = l * sin(2 * PI * k / BRUTE_M);
  }
  for (j = 0; j < c->n && m > 0; j++) {
    double dx = c->r[2*j] - c->r[2*i], dy = c->r[2*j+1] - c->r[2*i+1], d;
    double *t;
    afv_min_image(&c->box, &dx, &dy);
    d = hypot(dx, dy);
    if (j == i || d >= 2 * l) continue;
    m = clip_halfplane(x, y, m, dx / d, dy / d, 0.5 * d, xo, yo);
    t = x; x = xo; xo = t;
    t = y; y = yo; yo = t;
  }
  polygon_measures(x, y, m, A, P);
}

/* Checks every cell of c against its brute-force twin; adds the largest
** relative errors A/A_M - 1, P/P_M - 1 seen to *eA, *eP. */
static void check_brute(const test_config *c, double *eA, double *eP)
{
  afv_params p;
  afv_geom g = {0};
  double l = 1, cm = cos(PI / BRUTE_M), a = 2 * PI / BRUTE_M;
  double disk_loss = PI * l * l * (1 - sin(a) / a);
  double *work = malloc((size_t)(4 * (BRUTE_M + c->n)) * sizeof(double));
  int i, st, bad = 0;
  afv_params_default(&p);
  p.l = l;
  st = afv_geometry(&g, c->n, c->r, &p, &c->box);
  CHECK(st == AFV_OK && work, "%s: afv_geometry: %s", c->name,
        afv_strerror(st));
  for (i = 0; st == AFV_OK && work && i < c->n; i++) {
    double AM, PM, A = g.area[i], P = g.perim[i];
    brute_cell(c, i, l, work, &AM, &PM);
    if (!(AM - BRUTE_ROUND <= A && A <= AM / (cm * cm) + BRUTE_ROUND
          && A - AM <= disk_loss + BRUTE_ROUND
          && PM - BRUTE_ROUND <= P && P <= PM / cm + BRUTE_ROUND)) {
      if (bad++ < 3)
        test_fail(__FILE__, __LINE__, "%s cell %d: A %.15g, P %.15g; the "
                  "%d-gon gives A in [%.15g, %.15g], P in [%.15g, %.15g]",
                  c->name, i, A, P, BRUTE_M, AM, fmin(AM / (cm * cm),
                  AM + disk_loss), PM, PM / cm);
    }
    if (AM > 0) *eA = fmax(*eA, A / AM - 1);
    if (PM > 0) *eP = fmax(*eP, P / PM - 1);
  }
  CHECK(bad == 0, "%s: %d cells outside the polygon's error", c->name, bad);
  afv_geom_free(&g);
  free(work);
}

static void test_shapes_match_clipped_polygons(void)
{
  test_config c;
  int k, made, configs = 0;
  double eA = 0, eP = 0, cm = cos(PI / BRUTE_M);
  for (k = 0; (made = test_config_make(k, &c)) == 1; k++) {
    check_brute(&c, &eA, &eP);
    configs++;
    test_config_free(&c);
  }
  CHECK(made == 0, "out of memory");
  CHECK(configs >= 10, "%d configurations", configs);
  printf("  %d-gon: largest A/A_M - 1 = %.3g (bound %.3g), P/P_M - 1 = %.3g "
         "(bound %.3g)\n", BRUTE_M, eA, 1 / (cm * cm) - 1, eP, 1 / cm - 1);
}

/* Degenerate dense layouts (neighbours.c, DENSE: the candidates proposed
** by the cut test): centres evenly on a line (300 on 0.3 l), on a circle
** (200 on a radius of 1 l: every cell's vertex at the circle's centre is
** shared by all), and at random in a square of 0.001 l (300: inner cells
** tiny, outer ones reaching the circle), open space, and the line and
** circle in a periodic box: each cell's area and perimeter within the
** error of the all-pairs polygon twin.  (Not timed; their cost is in
** doc/performance.md.  A walk stopped after the first ring, or a bin test
** that ignores the arcs, fails this.) */
static void degenerate_config(int kind, int n, int periodic, test_config *c)
{
  int i;
  c->n = n;
  c->r = malloc((size_t)(2 * n) * sizeof(double));
  c->box.periodic = periodic;
  c->box.Lx = c->box.Ly = periodic ? 5 : 0;
  c->name = kind == 0 ? "line" : kind == 1 ? "circle" : "square";
  if (!c->r) return;
  test_rng_seed(38);
  for (i = 0; i < n; i++) {
    double x = 0.3 * i / n, y = 0;
    if (kind == 1) {
      x = cos(2 * PI * i / n);
      y = sin(2 * PI * i / n);
    } else if (kind == 2) {
      x = 0.001 * test_rng_uniform();
      y = 0.001 * test_rng_uniform();
    }
    c->r[2*i] = x + (periodic ? 2.5 : 0);
    c->r[2*i+1] = y + (periodic ? 2.5 : 0);
  }
}

/* The most neighbour slots a cell of c has (the lists are linear in N
** only if this stays small: on the circle every centre touches every
** cell at the circle's centre; 2, 5 and 15 on the line, circle and
** square, 199 on the circle if the cut test takes the centres that only
** touch, AFV_CUT_DEPTH -1e-9). */
static double most_slots(const test_config *c)
{
  afv_params p;
  afv_geom g = {0};
  int i, most = -1;
  afv_params_default(&p);
  if (afv_geometry(&g, c->n, c->r, &p, &c->box) == AFV_OK)
    for (i = 0, most = 0; i < c->n; i++)
      if (g.nbr_end[i] - g.nbr_start[i] > most)
        most = g.nbr_end[i] - g.nbr_start[i];
  afv_geom_free(&g);
  return most < 0 ? HUGE_VAL : most;
}

static void test_degenerate_shapes_match_clipped_polygons(void)
{
  static const int kinds[5][3] = {{0, 300, 0}, {1, 200, 0}, {2, 300, 0},
                                  {0, 300, 1}, {1, 200, 1}};
  double eA = 0, eP = 0, most = 0;
  int k;
  for (k = 0; k < 5; k++) {
    test_config c;
    degenerate_config(kinds[k][0], kinds[k][1], kinds[k][2], &c);
    CHECK(c.r != NULL, "out of memory");
    if (c.r) {
      check_brute(&c, &eA, &eP);
      most = fmax(most, most_slots(&c));
    }
    test_config_free(&c);
  }
  printf("  degenerate layouts: largest A/A_M - 1 = %.3g, P/P_M - 1 = %.3g, "
         "at most %g neighbour slots a cell\n", eA, eP, most);
  CHECK(most <= 32, "a cell lists %g neighbours (the cut test keeps the "
        "lists short: AFV_CUT_DEPTH)", most);
}

void suite_reference(void)
{
  RUN(test_step_is_the_papers_equations);
  RUN(test_shapes_match_clipped_polygons);
  RUN(test_degenerate_shapes_match_clipped_polygons);
}
