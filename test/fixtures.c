/* fixtures.c -- small helpers shared by the test suites. */
#define _POSIX_C_SOURCE 200809L   /* sys/wait.h */
#include "test.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#define PI 3.14159265358979323846

/* ---- fixed-seed random numbers: splitmix64 (Steele, Lea, Flood 2014) -- */
static unsigned long long rng_state;

void test_rng_seed(unsigned long long s) { rng_state = s; }

unsigned long long test_rng_next(void)
{
  unsigned long long z = (rng_state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double test_rng_uniform(void)
{
  return (double)(test_rng_next() >> 11) * (1.0 / 9007199254740992.0);
}

double test_rng_normal(void)
{
  double u = 1 - test_rng_uniform();          /* (0, 1]: log is finite */
  return sqrt(-2 * log(u)) * cos(2 * PI * test_rng_uniform());
}

/* ---- boxes and lattices ------------------------------------------------ */
afv_box test_open_box(void)
{
  afv_box b;
  b.periodic = 0;
  b.Lx = b.Ly = 0;
  return b;
}

afv_box test_periodic_box(double Lx, double Ly)
{
  afv_box b;
  b.periodic = 1;
  b.Lx = Lx;
  b.Ly = Ly;
  return b;
}

afv_box test_tri_lattice(int nx, int ny, double D, double x0, double y0,
                         double *r)
{
  double rowh = D * sqrt(3.0) / 2;
  int i, j;
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      r[2 * (j * nx + i)] = x0 + (i + 0.5 * (j % 2)) * D;
      r[2 * (j * nx + i) + 1] = y0 + j * rowh;
    }
  return test_periodic_box(nx * D, ny * rowh);
}

/* ---- shell commands ----------------------------------------------------- */
int test_sh(const char *fmt, ...)
{
  char cmd[4096];
  va_list ap;
  int st;
  va_start(ap, fmt);
  vsnprintf(cmd, sizeof cmd, fmt, ap);
  va_end(ap);
  st = system(cmd);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* ---- configurations for the twin checks (test_reference.c, twins.c) ----- */
/* Each is a function filling c; l = 1 throughout. */

static int config_alloc(test_config *c, const char *name, int n, afv_box b)
{
  c->name = name;
  c->n = n;
  c->box = b;
  c->r = calloc((size_t)(2 * n + 1), sizeof(double));
  return c->r != NULL;
}

/* A pair at distance d with its axis at angle a, centred at (x, y). */
static void put_pair(double *r, double x, double y, double d, double a)
{
  r[0] = x - 0.5 * d * cos(a);
  r[1] = y - 0.5 * d * sin(a);
  r[2] = x + 0.5 * d * cos(a);
  r[3] = y + 0.5 * d * sin(a);
}

/* Two cells at 1.2 l: a lens, two arcs. */
static int config_lens(test_config *c)
{
  if (!config_alloc(c, "lens", 2, test_open_box())) return -1;
  put_pair(c->r, 0, 0, 1.2, 0);
  return 1;
}

/* Pairs about to detach, 2l - d = 1e-3 .. 1e-12 l, then five at random
** 2l - d in [1e-13, 1e-3] l, each turned at random, 10 l apart; and a
** triple: a pair 2l - 1e-8 apart with a third cell in contact with one. */
static int config_near_detachment(test_config *c)
{
  static const double eps[5] = {1e-3, 1e-6, 1e-9, 1e-11, 1e-12};
  int k;
  if (!config_alloc(c, "near_detachment", 23, test_open_box())) return -1;
  for (k = 0; k < 10; k++) {
    double e = k < 5 ? eps[k] : pow(10, -3 - 10 * test_rng_uniform());
    put_pair(c->r + 4 * k, 10.0 * k, 0, 2 - e, 2 * PI * test_rng_uniform());
  }
  put_pair(c->r + 40, 0, 10, 2 - 1e-8, 0.7);
  c->r[44] = c->r[40] - 1.5;
  c->r[45] = c->r[41] + 0.4;
  return 1;
}

/* Triples at the corners of an equilateral triangle of side sqrt(3) s:
** their triple junction lies s l from each centre, on the circle for s = 1
** (eight triangles turned by 0.4 + 0.7 k: the computed gap between the two
** edges then comes out a hair above or below 0), a hair inside or outside
** for s = 1 -+ 1e-9. */
static int config_junction_on_circle(test_config *c)
{
  int k, q;
  if (!config_alloc(c, "junction_on_circle", 30, test_open_box())) return -1;
  for (k = 0; k < 10; k++)
    for (q = 0; q < 3; q++) {
      double s = k == 8 ? 1 - 1e-9 : k == 9 ? 1 + 1e-9 : 1;
      double a = 0.4 + 0.7 * k + q * 2.0943951023931957;   /* 2 pi / 3 */
      c->r[6*k + 2*q] = 10.0 * k + s * cos(a);
      c->r[6*k + 2*q + 1] = s * sin(a);
    }
  return 1;
}

/* Three squares of four cells on a circle of radius l (within 3e-16 l), a
** junction of four cells on each one's circle, where the computed arc
** between two edges comes out a hair below 0, as 2 pi - 1e-15 (found among
** random such squares: 183 of 200000 do this). */
static int config_cocircular_on_circle(test_config *c)
{
  static const double r[24] = {
    2.7728860386578527, -0.026321498686697531, 2.7239825250278118,
    -1.5531607509317533, 4.2162105363021052, -1.3789266812938639,
    3.834781984698767, 0.086986304250814772,
    -1.8407266423988324, 2.6998548046903759, -0.73657126192405542,
    3.0710435391864581, -1.0612747999209886, 4.5296883813224254,
    -2.4159040153909213, 4.152108328350276,
    -4.3412415133625322, -4.6893574083649909, -3.8727033884207791,
    -3.3652376542521614, -5.30648249325096, -2.940821904806119,
    -5.6793360101372006, -4.223133495038601};
  if (!config_alloc(c, "cocircular_on_circle", 12, test_open_box()))
    return -1;
  memcpy(c->r, r, sizeof r);
  return 1;
}

/* Three cells on a line, 0.8 l apart: the middle cell's bisectors are
** parallel to each other, and the end cells' two are parallel (one behind
** the other); the same turned by 0.9 (parallel up to rounding). */
static int config_collinear(test_config *c)
{
  int k;
  if (!config_alloc(c, "collinear", 6, test_open_box())) return -1;
  for (k = 0; k < 3; k++) {
    c->r[2*k] = 0.8 * k;
    c->r[2*k+1] = 0;
    c->r[6 + 2*k] = 0.8 * k * cos(0.9);
    c->r[6 + 2*k + 1] = 10 + 0.8 * k * sin(0.9);
  }
  return 1;
}

/* An open 3 x 3 square cluster of spacing 1.3 l: its 2 x 2 blocks are
** cocircular squares (four cells at one vertex), the rim has arcs. */
static int config_square_cocircular(test_config *c)
{
  int k;
  if (!config_alloc(c, "square_cocircular", 9, test_open_box())) return -1;
  for (k = 0; k < 9; k++) {
    c->r[2*k] = 1.3 * (k % 3);
    c->r[2*k+1] = 1.3 * (k / 3);
  }
  return 1;
}

/* Periodic triangular lattices: spacing 1.8 l (hexagons with their corners
** cut by arcs), 1.7 l (whole hexagons), and 1.8 l with each centre moved by
** up to 0.05 l. */
static int config_lattice(test_config *c, const char *name, int side,
                          double D, double jitter)
{
  int k;
  if (!config_alloc(c, name, side * side, test_open_box())) return -1;
  c->box = test_tri_lattice(side, side, D, 0.3, 0.2, c->r);
  for (k = 0; k < 2 * c->n; k++)
    c->r[k] += jitter * (2 * test_rng_uniform() - 1);
  return 1;
}

/* The paper's state: 400 cells at packing fraction 0.5, uniform in a
** periodic box (afv_init_random), and a compact open cluster of 200 cells
** 1.7 l apart moved by up to 0.1 l. */
static int config_random_periodic(test_config *c)
{
  double side = sqrt(400 * PI / 0.5);
  if (!config_alloc(c, "random_periodic", 400, test_periodic_box(side, side)))
    return -1;
  afv_init_random(400, 7, &c->box, 0, c->r);
  return 1;
}

static int config_cluster(test_config *c)
{
  int k;
  if (!config_alloc(c, "cluster", 200, test_open_box())) return -1;
  if (afv_init_lattice(200, 1.7, &c->box, c->r) != AFV_OK) return -1;
  for (k = 0; k < 400; k++) c->r[k] += 0.1 * (2 * test_rng_uniform() - 1);
  return 1;
}

/* 80 cells uniform in an open square of side 14 l: most cells isolated or
** in small clusters, with arcs. */
static int config_random_open(test_config *c)
{
  int k;
  if (!config_alloc(c, "random_open", 80, test_open_box())) return -1;
  for (k = 0; k < 160; k++) c->r[k] = 14 * test_rng_uniform();
  return 1;
}

int test_config_make(int k, test_config *c)
{
  c->r = NULL;
  test_rng_seed(1000 + (unsigned long long)k);
  switch (k) {
  case 0: return config_lens(c);
  case 1: return config_near_detachment(c);
  case 2: return config_junction_on_circle(c);
  case 3: return config_square_cocircular(c);
  case 4: return config_lattice(c, "lattice_arcs", 6, 1.8, 0);
  case 5: return config_lattice(c, "lattice_closed", 6, 1.7, 0);
  case 6: return config_lattice(c, "lattice_jittered", 8, 1.8, 0.05);
  case 7: return config_random_periodic(c);
  case 8: return config_cluster(c);
  case 9: return config_random_open(c);
  case 10: return config_collinear(c);
  case 11: return config_cocircular_on_circle(c);
  default: return 0;
  }
}

void test_config_free(test_config *c)
{
  free(c->r);
  c->r = NULL;
}

/* ---- golden files ------------------------------------------------------- */
/* A two-column CSV/space file read with afv_points_read (NULL if it cannot
** be read): the golden data of test/golden/. */
double *test_read_pairs(const char *path, int *n)
{
  double *r = NULL;
  char err[256];
  if (afv_points_read(path, n, &r, err, sizeof err) != AFV_OK) return NULL;
  return r;
}
