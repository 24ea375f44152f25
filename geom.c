/*
** geom.c -- neighbour search and the exact shape of every finite-Voronoi cell.
**
** Invariant: after afv_geometry, cell i's boundary (pieces) is the boundary of
**     disk(r_i, l)  intersected with  { x : |x - r_i| <= |x - r_j| }  for all j,
** written as a counter-clockwise cycle of straight edges and circular arcs.
** Only centres closer than 2l can cut the disk (the bisector of a pair at
** distance d lies d/2 from r_i, and d/2 >= l misses the open disk): that is
** our "radius of security", and the cell list below finds exactly those.
**
** Algorithm, per cell, in coordinates centred on r_i:
**   1. Start from the square [-2l, 2l]^2, which contains the disk; its sides
**      lie outside the disk, so they never reach the final boundary.
**   2. Clip it (Sutherland-Hodgman) by the half-plane x.u <= d/2 of each
**      neighbour, u = (r_j - r_i)/d.  Each polygon side remembers its owner.
**   3. Intersect the convex polygon with the disk: a side keeps the part of
**      its line inside the disk; consecutive kept parts that do not meet at a
**      polygon vertex are joined by an arc of the circle.
** Cost: O(k^2) per cell for k neighbours (k is about 6 in a tissue), so
** O(N) for the tissue; the cell list is O(N) time and memory.
*/
#include "afv.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI     3.14159265358979323846
#define TWO_PI 6.28318530717958647692

/* Two kept parts of the boundary meet on the circle within roundoff: their
** computed gap may then come out as a hair below zero, which wraps around to
** a full turn.  A gap within ANGLE_TOL of 2 pi between two distinct edges is
** taken to be such a zero gap (a true gap that large would need every
** contact edge of the cell shorter than about 1e-12 l). */
#define ANGLE_TOL 1e-12

/* Open space: at most this many bins per cell; wider bins if the points are
** spread out, so that memory stays O(N) however far apart they are. */
#define OPEN_BINS_PER_CELL 2

/* ---- small vector helpers ---------------------------------------------- */
static double dot(double ax, double ay, double bx, double by)
{
  return ax * bx + ay * by;
}

/* ---- buffers ----------------------------------------------------------- */
static int grow(void **ptr, int *cap, int need, size_t elem)
{
  void *q;
  int newcap;
  if (need <= *cap) return AFV_OK;
  newcap = *cap > 0 ? *cap : 16;
  while (newcap < need) newcap *= 2;
  q = realloc(*ptr, (size_t)newcap * elem);
  if (!q) return AFV_ENOMEM;
  *ptr = q;
  *cap = newcap;
  return AFV_OK;
}

static int grow_cells(afv_geom *g, int n)
{
  int cap = g->cap_cells, c;
  if (n + 1 <= cap) return AFV_OK;
  c = cap;
  if (grow((void **)&g->area, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->perim, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->arc, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->contacts, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->piece_start, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->n_pieces, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->nbr_start, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->bin_cell, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  g->cap_cells = c;
  return AFV_OK;
}

/* Neighbour slot arrays: nbr and nbr_rev (ints), nbr_d and grad (pairs). */
static int grow_nbr(afv_geom *g, int need)
{
  int cap = g->cap_nbr, c;
  if (need <= cap) return AFV_OK;
  c = cap;
  if (grow((void **)&g->nbr, &c, need, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->nbr_rev, &c, need, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->nbr_d, &c, need, 2 * sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (grow((void **)&g->grad, &c, need, 2 * sizeof(double))) return AFV_ENOMEM;
  g->cap_nbr = c;
  return AFV_OK;
}

void afv_geom_free(afv_geom *g)
{
  free(g->area); free(g->perim); free(g->arc); free(g->contacts);
  free(g->piece_start); free(g->n_pieces); free(g->pieces);
  free(g->nbr_start); free(g->nbr); free(g->nbr_d); free(g->nbr_rev);
  free(g->bin_start); free(g->bin_cell); free(g->grad); free(g->work);
  memset(g, 0, sizeof *g);
}

/* ---- boundary conditions ----------------------------------------------- */
void afv_min_image(const afv_box *b, double *dx, double *dy)
{
  if (!b || !b->periodic) return;
  /* round() is symmetric (half away from zero), so the image of -D is -D':
  ** neighbour lists come out exactly symmetric. */
  *dx -= b->Lx * round(*dx / b->Lx);
  *dy -= b->Ly * round(*dy / b->Ly);
}

static double wrap1(double x, double L)
{
  double w = x - L * floor(x / L);
  return w >= L ? 0.0 : w;   /* x = -tiny gives w = L after rounding */
}

void afv_wrap(const afv_box *b, double *x, double *y)
{
  if (!b || !b->periodic) return;
  *x = wrap1(*x, b->Lx);
  *y = wrap1(*y, b->Ly);
}

/* ---- cell list --------------------------------------------------------- */
/* The grid of bins: nbx x nby bins of side wx x wy (each >= 2l), whose
** lower-left corner is (x0, y0). */
typedef struct grid {
  int nbx, nby, periodic;
  double x0, y0, wx, wy;
} grid;

static void grid_periodic(grid *G, const afv_box *b, double l)
{
  G->periodic = 1;
  G->nbx = (int)floor(b->Lx / (2 * l));
  G->nby = (int)floor(b->Ly / (2 * l));
  if (G->nbx < 1) G->nbx = 1;
  if (G->nby < 1) G->nby = 1;
  G->x0 = G->y0 = 0;
  G->wx = b->Lx / G->nbx;
  G->wy = b->Ly / G->nby;
}

static void grid_open(grid *G, int n, const double *r, double l)
{
  double xmin = r[0], xmax = r[0], ymin = r[1], ymax = r[1], w = 2 * l;
  int i;
  for (i = 1; i < n; i++) {
    if (r[2*i] < xmin) xmin = r[2*i];
    if (r[2*i] > xmax) xmax = r[2*i];
    if (r[2*i+1] < ymin) ymin = r[2*i+1];
    if (r[2*i+1] > ymax) ymax = r[2*i+1];
  }
  /* widen the bins until there are at most OPEN_BINS_PER_CELL per cell */
  while (((xmax - xmin) / w + 1) * ((ymax - ymin) / w + 1)
         > (double)OPEN_BINS_PER_CELL * n + 16)
    w *= 2;
  G->periodic = 0;
  G->x0 = xmin;
  G->y0 = ymin;
  G->wx = G->wy = w;
  G->nbx = (int)floor((xmax - xmin) / w) + 1;
  G->nby = (int)floor((ymax - ymin) / w) + 1;
}

static int bin_of(const grid *G, double x, double y)
{
  int bx, by;
  if (G->periodic) {
    x = wrap1(x, G->wx * G->nbx);
    y = wrap1(y, G->wy * G->nby);
  }
  bx = (int)floor((x - G->x0) / G->wx);
  by = (int)floor((y - G->y0) / G->wy);
  if (bx < 0) bx = 0;
  if (bx >= G->nbx) bx = G->nbx - 1;
  if (by < 0) by = 0;
  if (by >= G->nby) by = G->nby - 1;
  return by * G->nbx + bx;
}

/* Counting sort of the cells into bins: bin b holds
** bin_cell[bin_start[b] .. bin_start[b+1]-1], in increasing cell order. */
static int fill_bins(afv_geom *g, const grid *G, int n, const double *r)
{
  int nb = G->nbx * G->nby, i, b;
  if (grow((void **)&g->bin_start, &g->cap_bins, nb + 1, sizeof(int)))
    return AFV_ENOMEM;
  memset(g->bin_start, 0, (size_t)(nb + 1) * sizeof(int));
  for (i = 0; i < n; i++) g->bin_start[bin_of(G, r[2*i], r[2*i+1]) + 1]++;
  for (b = 0; b < nb; b++) g->bin_start[b + 1] += g->bin_start[b];
  for (i = 0; i < n; i++) {
    b = bin_of(G, r[2*i], r[2*i+1]);
    g->bin_cell[g->bin_start[b]++] = i;
  }
  for (b = nb; b > 0; b--) g->bin_start[b] = g->bin_start[b - 1];
  g->bin_start[0] = 0;
  return AFV_OK;
}

/* The bin offsets to visit along one axis of nb bins: -1..1, except that
** with fewer than 3 periodic bins -1 and +1 are the same bin (or bin 0). */
static void stencil(int nb, int periodic, int *lo, int *hi)
{
  *lo = -1;
  *hi = 1;
  if (periodic && nb < 3) {
    *lo = 0;
    *hi = nb - 1;
  }
}

/* Appends to cell i's list every j in bin (bx, by) closer than 2l. */
static int scan_bin(afv_geom *g, const grid *G, const double *r,
                    const afv_box *b, double l, int i, int bx, int by,
                    int *count)
{
  int k, bin;
  if (G->periodic) {
    bx = (bx + G->nbx) % G->nbx;
    by = (by + G->nby) % G->nby;
  } else if (bx < 0 || by < 0 || bx >= G->nbx || by >= G->nby) {
    return AFV_OK;
  }
  bin = by * G->nbx + bx;
  for (k = g->bin_start[bin]; k < g->bin_start[bin + 1]; k++) {
    int j = g->bin_cell[k];
    double dx = r[2*j] - r[2*i], dy = r[2*j+1] - r[2*i+1], d2;
    if (j == i) continue;
    afv_min_image(b, &dx, &dy);
    d2 = dx * dx + dy * dy;
    if (d2 == 0) {
      g->bad_i = i < j ? i : j;
      g->bad_j = i < j ? j : i;
      return AFV_ECOINCIDENT;
    }
    if (d2 >= 4 * l * l) continue;
    if (grow_nbr(g, *count + 1)) return AFV_ENOMEM;
    g->nbr[*count] = j;
    g->nbr_d[2 * *count] = dx;
    g->nbr_d[2 * *count + 1] = dy;
    (*count)++;
  }
  return AFV_OK;
}

/* nbr_rev[s]: the slot of i in the list of j = nbr[s].  The lists are
** symmetric (same minimum-image distance both ways), so it exists. */
static void link_reverse_slots(afv_geom *g, int n)
{
  int i, s, t;
  for (i = 0; i < n; i++)
    for (s = g->nbr_start[i]; s < g->nbr_start[i + 1]; s++) {
      int j = g->nbr[s];
      g->nbr_rev[s] = -1;
      for (t = g->nbr_start[j]; t < g->nbr_start[j + 1]; t++)
        if (g->nbr[t] == i) {
          g->nbr_rev[s] = t;
          break;
        }
    }
}

int afv_neighbours(afv_geom *g, int n, const double *r, double l,
                   const afv_box *b)
{
  grid G;
  int i, count = 0, xlo, xhi, ylo, yhi, st;
  if (grow_cells(g, n)) return AFV_ENOMEM;
  g->n = n;
  g->nbr_start[0] = 0;
  if (n == 0) return AFV_OK;
  if (b && b->periodic) grid_periodic(&G, b, l);
  else grid_open(&G, n, r, l);
  if ((st = fill_bins(g, &G, n, r)) != AFV_OK) return st;
  stencil(G.nbx, G.periodic, &xlo, &xhi);
  stencil(G.nby, G.periodic, &ylo, &yhi);
  for (i = 0; i < n; i++) {
    int cell = bin_of(&G, r[2*i], r[2*i+1]);
    int bx = cell % G.nbx, by = cell / G.nbx, ox, oy;
    for (oy = ylo; oy <= yhi; oy++)
      for (ox = xlo; ox <= xhi; ox++)
        if ((st = scan_bin(g, &G, r, b, l, i, bx + ox, by + oy, &count)))
          return st;
    g->nbr_start[i + 1] = count;
  }
  link_reverse_slots(g, n);
  return AFV_OK;
}

/* ---- one cell's shape --------------------------------------------------- */
/* A polygon vertex during clipping; the side from it to the next vertex is
** owned by neighbour slot `slot` (-1: a side of the initial square). */
typedef struct pvert {
  double x, y;
  int slot;
} pvert;

/* The line of neighbour slot s, in the cell's frame: x.u = h, with
** u = D/d the unit vector to the neighbour, h = d/2, and t = (-u_y, u_x)
** the counter-clockwise direction along it. */
typedef struct bisector {
  double ux, uy, h, d;
} bisector;

static bisector bisector_of(const afv_geom *g, int s)
{
  bisector B;
  double dx = g->nbr_d[2*s], dy = g->nbr_d[2*s+1];
  B.d = sqrt(dx * dx + dy * dy);
  B.ux = dx / B.d;
  B.uy = dy / B.d;
  B.h = 0.5 * B.d;
  return B;
}

/* Clips the convex polygon in[0..m-1] by x.u <= h (the half-plane of slot
** s); writes the result to out and returns its vertex count.  A vertex
** exactly on the line counts as inside and, if the polygon leaves there,
** starts the new side (so no duplicate vertices are made). */
static int clip_polygon(const pvert *in, int m, pvert *out, bisector B, int s)
{
  int k, o = 0;
  for (k = 0; k < m; k++) {
    const pvert *P = &in[k], *Q = &in[(k + 1) % m];
    double sp = dot(P->x, P->y, B.ux, B.uy) - B.h;
    double sq = dot(Q->x, Q->y, B.ux, B.uy) - B.h;
    if (sp <= 0) {
      out[o] = *P;
      if (sq > 0) {                      /* leaving: the new side starts */
        if (sp < 0) {
          double t = sp / (sp - sq);
          o++;
          out[o].x = P->x + t * (Q->x - P->x);
          out[o].y = P->y + t * (Q->y - P->y);
        }
        out[o].slot = s;
      }
      o++;
    } else if (sq < 0) {                 /* entering: the old side resumes */
      double t = sp / (sp - sq);
      out[o].x = P->x + t * (Q->x - P->x);
      out[o].y = P->y + t * (Q->y - P->y);
      out[o].slot = P->slot;
      o++;
    }
  }
  return o;
}

/* Steps 1 and 2: the polygon of cell i.  buf and spare each hold
** nn + 4 vertices; returns the buffer that holds the result, count in *m. */
static pvert *clipped_polygon(const afv_geom *g, int i, double l, pvert *buf,
                              pvert *spare, int *m)
{
  static const double corner[4][2] = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  int k, s;
  for (k = 0; k < 4; k++) {
    buf[k].x = corner[k][0] * l;
    buf[k].y = corner[k][1] * l;
    buf[k].slot = -1;
  }
  *m = 4;
  for (s = g->nbr_start[i]; s < g->nbr_start[i + 1]; s++) {
    pvert *t = buf;
    *m = clip_polygon(buf, *m, spare, bisector_of(g, s), s);
    buf = spare;
    spare = t;
  }
  return buf;
}

/* One kept part of a polygon side: from tau0 to tau1 along its line, in
** the direction t; `*_on_circle` says whether the end is an arc end (else
** it is the polygon vertex, a triple junction). */
typedef struct segment {
  int slot;
  double tau0, tau1;
  int start_on_circle, end_on_circle;
} segment;

/* Step 3 for one polygon side P->Q of slot s: the part inside the disk.
** in_p, in_q say whether P and Q are in the closed disk; they are computed
** once per vertex so that the two sides sharing a vertex agree on it. */
static int keep_inside(const pvert *P, const pvert *Q, int in_p, int in_q,
                       bisector B, double l, segment *seg)
{
  double tx = -B.uy, ty = B.ux;
  double ta = dot(P->x, P->y, tx, ty), tb = dot(Q->x, Q->y, tx, ty);
  /* half-chord of the line in the disk; (l-h)(l+h) is exact where
  ** l*l - h*h would cancel for h near l */
  double sc = sqrt((l - B.h) * (l + B.h));
  seg->slot = P->slot;
  seg->start_on_circle = !in_p;
  seg->end_on_circle = !in_q;
  seg->tau0 = in_p ? ta : -sc;
  seg->tau1 = in_q ? tb : sc;
  if (!in_p && !in_q) return ta < -sc && tb > sc && sc > 0;
  if (seg->tau1 < seg->tau0) seg->tau1 = seg->tau0;   /* roundoff at a touch */
  return 1;
}

static double angle_of(bisector B, double tau)
{
  return atan2(B.h * B.uy + tau * B.ux, B.h * B.ux - tau * B.uy);
}

static void store_piece(afv_geom *g, int i, int slot, double x, double y,
                        double length)
{
  afv_piece *pc = &g->pieces[g->piece_start[i] + g->n_pieces[i]++];
  pc->slot = slot;
  pc->nbr = slot >= 0 ? g->nbr[slot] : AFV_ARC;
  pc->x = x;
  pc->y = y;
  pc->length = length;
}

/* The arc from the end of segment a to the start of segment b (counter-
** clockwise), as an angle in [0, 2 pi); `single` if a and b are the same. */
static double gap_angle(const afv_geom *g, const segment *a, const segment *b,
                        int single)
{
  double phi = angle_of(bisector_of(g, b->slot), b->tau0)
             - angle_of(bisector_of(g, a->slot), a->tau1);
  while (phi < 0) phi += TWO_PI;
  while (phi >= TWO_PI) phi -= TWO_PI;
  if (single && phi == 0) phi = TWO_PI;
  if (!single && phi > TWO_PI - ANGLE_TOL) phi = 0;
  return phi;
}

static void isolated_cell(afv_geom *g, int i, double l)
{
  store_piece(g, i, -1, l, 0, TWO_PI * l);
  g->area[i] = PI * l * l;
  g->perim[i] = g->arc[i] = TWO_PI * l;
}

/* Writes the pieces of cell i from its kept segments seg[0..ns-1] and sums
** A (triangles h*len/2 on the edges, sectors l^2 phi/2 on the arcs), P, L. */
static void assemble_boundary(afv_geom *g, int i, double l, const segment *seg,
                              int ns)
{
  double A = 0, P = 0, L = 0;
  int k;
  g->contacts[i] = 0;
  for (k = 0; k < ns; k++) {
    const segment *S = &seg[k];
    bisector B = bisector_of(g, S->slot);
    double len = S->tau1 - S->tau0;
    store_piece(g, i, S->slot, B.h * B.ux - S->tau0 * B.uy,
                B.h * B.uy + S->tau0 * B.ux, len);
    A += 0.5 * B.h * len;
    P += len;
    if (len > AFV_CONTACT_TOL * l) g->contacts[i]++;
    if (S->end_on_circle) {
      const segment *next = &seg[(k + 1) % ns];
      double phi = gap_angle(g, S, next, ns == 1);
      double x = B.h * B.ux - S->tau1 * B.uy, y = B.h * B.uy + S->tau1 * B.ux;
      store_piece(g, i, -1, x, y, l * phi);
      A += 0.5 * l * l * phi;
      L += l * phi;
    }
  }
  g->area[i] = A;
  g->perim[i] = P + L;
  g->arc[i] = L;
}

void afv_cell_shape(afv_geom *g, int i, double l)
{
  int nn = g->nbr_start[i + 1] - g->nbr_start[i];
  pvert *buf = (pvert *)g->work, *spare = buf + (nn + 4), *poly, *flags;
  segment *seg = (segment *)(spare + (nn + 4));
  int m, k, ns = 0;
  g->n_pieces[i] = 0;
  g->contacts[i] = 0;
  poly = clipped_polygon(g, i, l, buf, spare, &m);
  /* the other buffer is free again: it holds the "in the disk" flags */
  flags = poly == buf ? spare : buf;
  for (k = 0; k < m; k++)
    flags[k].slot = poly[k].x * poly[k].x + poly[k].y * poly[k].y <= l * l;
  for (k = 0; k < m; k++) {
    int b = (k + 1) % m;
    if (poly[k].slot < 0) continue;
    if (keep_inside(&poly[k], &poly[b], flags[k].slot, flags[b].slot,
                    bisector_of(g, poly[k].slot), l, &seg[ns]))
      ns++;
  }
  if (ns == 0) isolated_cell(g, i, l);
  else assemble_boundary(g, i, l, seg, ns);
}

/* Work space for one cell with up to max_nn neighbours: two polygons of at
** most max_nn + 4 vertices and max_nn + 4 segments. */
static int reserve_work(afv_geom *g, int max_nn)
{
  size_t bytes = (size_t)(max_nn + 4) * (2 * sizeof(pvert) + sizeof(segment));
  int doubles = (int)(bytes / sizeof(double)) + 1;
  return grow((void **)&g->work, &g->cap_work, doubles, sizeof(double));
}

/* Piece storage: cell i with k neighbours has at most 2k + 1 pieces (an
** edge per neighbour, an arc after each, or one full circle). */
static int reserve_pieces(afv_geom *g, int n, int *max_nn)
{
  int i, total = 0;
  *max_nn = 0;
  for (i = 0; i < n; i++) {
    int k = g->nbr_start[i + 1] - g->nbr_start[i];
    if (k > *max_nn) *max_nn = k;
    g->piece_start[i] = total;
    total += 2 * k + 1;
  }
  g->piece_start[n] = total;
  return grow((void **)&g->pieces, &g->cap_pieces, total + 1,
              sizeof(afv_piece));
}

/* Everything afv_cell_shape needs: neighbour lists, piece and work space. */
int afv_geometry_prepare(afv_geom *g, int n, const double *r, double l,
                         const afv_box *b)
{
  int st, max_nn, i;
  g->bad_i = g->bad_j = -1;
  for (i = 0; i < 2 * n; i++)
    if (!isfinite(r[i])) {
      g->bad_i = i / 2;
      return AFV_ENONFINITE;
    }
  if ((st = afv_neighbours(g, n, r, l, b)) != AFV_OK) return st;
  if ((st = reserve_pieces(g, n, &max_nn)) != AFV_OK) return st;
  return reserve_work(g, max_nn);
}
