/*
** fuzz_geometry.c -- libFuzzer harness for the geometry and the forces.
**
**   clang -g -O1 -fsanitize=fuzzer,address,undefined -I. \
**     fuzz/fuzz_geometry.c neighbours.c geom.c afv.c -lm -o fuzz_geometry
**   ./fuzz_geometry fuzz/corpus/geometry -max_total_time=60
**
** The input is read as a small recipe of 1 to 12 cells: each cell from
** four bytes, placed by one of six generators -- anywhere in a 6 l square
** (16-bit coordinates), on a triangular or square lattice site, on a
** collinear row, nearly coincident with an earlier cell (1e-6 l down to
** 2^-540 = 3.6e-163 l away, d^2 subnormal, or exactly on it), or nearly
** detaching from one (2l
** less 2^-k l) -- in open space or a periodic box (4l to 8l, a byte),
** with P0 from a byte.  Properties (a failed one aborts, which libFuzzer
** reports with its input):
**   - afv_compute succeeds, or names two cells with the same centre
**     (bitwise, or the same point of the periodic box);
**   - areas in [0, pi l^2], perimeters and arc lengths in [0, 2 pi l],
**     forces finite;
**   - the forces sum to zero, and in open space their torque too, to
**     rounding of the largest |F| |r|;
**   - on a smooth configuration (every pair farther than 0.1 l apart and
**     0.02 l from contact or detachment, no vertex within 1e-4 l of a
**     4-fold one, where the energy has a kink: a T1), afv_gradient_check
**     within 1e-5 of the tension scale.
** Every input that failed becomes a regression test (test_geometry.c).
** (Below 2^-540 the exact forces themselves can exceed DBL_MAX: a cell
** 1e-289 l from another, closed by two bisectors 1e-124 rad from
** opposite, has a vertex moving 1e124 times as fast as its neighbour,
** over d = 1e-289: 1e382.  Not a property to check.)
*/
#include "afv_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define MAX_CELLS 12

#include "require.h"   /* REQUIRE(cond) */

/* The next byte of the input, 0 past its end. */
typedef struct reader {
  const uint8_t *p;
  size_t left;
} reader;

static unsigned next(reader *R)
{
  if (R->left == 0) return 0;
  R->left--;
  return *R->p++;
}

/* A coordinate from two bytes in [0, span). */
static double coord(reader *R, double span)
{
  unsigned v = next(R) << 8;
  v |= next(R);
  return span * v / 65536.0;
}

/* Cell k from four bytes; returns 0 if it made the configuration not
** smooth (a special pair on purpose). */
static int place(reader *R, double *r, int k)
{
  unsigned kind = next(R) % 6, a = next(R), b = next(R), c = next(R);
  int j = k > 0 ? (int)(a % k) : 0;
  double ang = 2 * PI * b / 256.0;
  switch (kind) {
  case 0: {                                   /* anywhere */
    reader S = {NULL, 0};
    uint8_t buf[4];
    buf[0] = (uint8_t)a; buf[1] = (uint8_t)b; buf[2] = (uint8_t)c;
    buf[3] = (uint8_t)next(R);
    S.p = buf;
    S.left = 4;
    r[2*k] = coord(&S, 6);
    r[2*k+1] = coord(&S, 6);
    return 1;
  }
  case 1:                                     /* triangular lattice site */
    r[2*k] = 1.7 * (a % 4 + 0.5 * (b % 4 % 2));
    r[2*k+1] = 1.7 * 0.8660254037844386 * (b % 4);
    return 1;
  case 2:                                     /* square lattice site */
    r[2*k] = 1.5 * (a % 4);
    r[2*k+1] = 1.5 * (b % 4);
    return 1;
  case 3:                                     /* a collinear row */
    r[2*k] = 0.25 + 1.1 * (a % 6);
    r[2*k+1] = 3.0 + (c & 1 ? 1e-13 * b : 0);
    return 1;
  case 4: {                                   /* nearly coincident */
    double d = c == 0 ? 0 : ldexp(1.0, -(int)(20 + c * 520 / 255));
    if (k == 0) break;
    r[2*k] = r[2*j] + d * cos(ang);
    r[2*k+1] = r[2*j+1] + d * sin(ang);
    return 0;
  }
  default: {                                  /* nearly detaching */
    double d = 2 - ldexp(1.0, -(int)(1 + c % 52));
    if (k == 0) break;
    r[2*k] = r[2*j] + d * cos(ang);
    r[2*k+1] = r[2*j+1] + d * sin(ang);
    return 0;
  }
  }
  r[2*k] = 3;                                 /* first cell of kind 4/5 */
  r[2*k+1] = 3;
  return 1;
}

/* 1 if cells i and j sit at the same point (of the periodic box). */
static int same_point(const double *r, int i, int j, const afv_box *b)
{
  double dx = r[2*j] - r[2*i], dy = r[2*j+1] - r[2*i+1];
  if (b->periodic) {
    dx -= b->Lx * round(dx / b->Lx);
    dy -= b->Ly * round(dy / b->Ly);
  }
  return dx == 0 && dy == 0;
}

/* 1 if every pair is 0.1 l or more apart and 0.02 l or more from d = 2l. */
static int smooth(const double *r, int n, const afv_box *b)
{
  int i, j;
  for (i = 0; i < n; i++)
    for (j = i + 1; j < n; j++) {
      double dx = r[2*j] - r[2*i], dy = r[2*j+1] - r[2*i+1], d;
      afv_min_image(b, &dx, &dy);
      d = sqrt(dx * dx + dy * dy);
      if (d < 0.1 || fabs(d - 2) < 0.02) return 0;
    }
  return 1;
}

/* 1 if some vertex of a cell is within 1e-4 l of being equidistant to
** one more centre than makes it (a 4-fold vertex, or an arc end on a
** third bisector): there the energy has a kink (a T1), and central
** differences straddle it. */
static int degenerate(const afv_geom *g, int n)
{
  int i, q, s;
  for (i = 0; i < n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++) {
      const afv_piece *pc = &g->pieces[q];
      const afv_piece *pv = &g->pieces[q > g->piece_start[i] ? q - 1
                              : g->piece_start[i] + g->n_pieces[i] - 1];
      int near = 0, makers = (pc->nbr >= 0) + (pv->nbr >= 0);
      double v = sqrt(pc->x * pc->x + pc->y * pc->y);
      if (makers == 0) continue;
      for (s = g->nbr_start[i]; s < g->nbr_end[i]; s++) {
        double dx = pc->x - g->nbr_d[2*s], dy = pc->y - g->nbr_d[2*s+1];
        near += fabs(sqrt(dx * dx + dy * dy) - v) < 1e-4;
      }
      if (near > makers) return 1;
    }
  return 0;
}

/* The properties of a computed configuration (see the head). */
static void check_outputs(const afv_geom *g, const double *r, const double *f,
                          int n, const afv_box *b)
{
  double sx = 0, sy = 0, tq = 0, fr = 0, fbig = 0, cx = 0, cy = 0;
  int i;
  for (i = 0; i < n; i++) {
    cx += r[2*i] / n;
    cy += r[2*i+1] / n;
  }
  for (i = 0; i < n; i++) {
    double rx = r[2*i] - cx, ry = r[2*i+1] - cy;
    REQUIRE(g->area[i] >= 0 && g->area[i] <= PI * (1 + 1e-12));
    REQUIRE(g->perim[i] >= 0 && g->perim[i] <= 2 * PI * (1 + 1e-12));
    REQUIRE(g->arc[i] >= 0 && g->arc[i] <= g->perim[i] * (1 + 1e-12));
    REQUIRE(isfinite(f[2*i]) && isfinite(f[2*i+1]));
    sx += f[2*i];
    sy += f[2*i+1];
    tq += rx * f[2*i+1] - ry * f[2*i];
    fbig = fmax(fbig, fmax(fabs(f[2*i]), fabs(f[2*i+1])));
    fr = fmax(fr, (fabs(rx) + fabs(ry)) * fmax(fabs(f[2*i]), fabs(f[2*i+1])));
  }
  REQUIRE(fabs(sx) + fabs(sy) <= 1e-12 * n * fbig + 1e-300);
  if (!b->periodic) REQUIRE(fabs(tq) <= 1e-10 * n * (fr + fbig) + 1e-300);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  reader R;
  double r[2 * MAX_CELLS], f[2 * MAX_CELLS];
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_geom g;
  unsigned mode;
  int n, k, st, special = 0;
  R.p = data;
  R.left = size;
  mode = next(&R);
  n = 1 + (int)(next(&R) % MAX_CELLS);
  afv_params_default(&p);
  p.P0 = 3 + 6 * next(&R) / 255.0;
  if (mode & 1) {
    b.periodic = 1;
    b.Lx = 4 + 4 * next(&R) / 255.0;
    b.Ly = 4 + 4 * next(&R) / 255.0;
  }
  for (k = 0; k < n; k++) special |= !place(&R, r, k);
  memset(&g, 0, sizeof g);
  st = afv_compute(&g, n, r, &p, &b, f);
#ifdef FUZZ_DEBUG                   /* the case, for a replay build */
  fprintf(stderr, "box %d %.17g %.17g P0 %.17g status %d\n", b.periodic,
          b.Lx, b.Ly, p.P0, st);
  for (k = 0; k < n; k++)
    fprintf(stderr, "%d %.17g %.17g A %.17g P %.17g F %g %g\n", k, r[2*k],
            r[2*k+1], st ? 0 : g.area[k], st ? 0 : g.perim[k],
            st ? 0 : f[2*k], st ? 0 : f[2*k+1]);
#endif
  if (st == AFV_ECOINCIDENT) {
    REQUIRE(g.bad_i >= 0 && g.bad_i < g.bad_j && g.bad_j < n);
    REQUIRE(same_point(r, g.bad_i, g.bad_j, &b));
  } else {
    REQUIRE(st == AFV_OK);
    for (k = 1; k < n; k++) {
      int j;
      for (j = 0; j < k; j++) REQUIRE(!same_point(r, j, k, &b));
    }
    check_outputs(&g, r, f, n, &b);
    if (!special && (mode & 2) && smooth(r, n, &b) && !degenerate(&g, n)) {
      afv_check_report rep;
      REQUIRE(afv_gradient_check(n, r, &p, &b, 1e-6, &rep) == AFV_OK);
      REQUIRE(rep.max_tension_rel <= 1e-5);
    }
  }
  afv_geom_free(&g);
  return 0;
}
