/*
** neighbours.c -- which centres can cut a cell: the neighbour search.
**
** Only centres closer than 2l can cut cell i's disk (the bisector of a
** pair at distance d lies d/2 from r_i, and d/2 >= l misses the open
** disk): that is our "radius of security".  afv_neighbours lists, for
** every cell, exactly those (minimum image in a periodic box), with their
** displacements D = r_j - r_i, sorted by direction (counter-clockwise from
** +x; the clipping in geom.c relies on this order), links each pair's two
** slots (nbr_rev) and fills each pair's edge cache (u = D/d, h = d/2,
** half-chord sqrt(l^2 - h^2)) once for both cells.  A cell's list sits at
** nbr[nbr_start[i] .. nbr_end[i] - 1]; the slots up to nbr_start[i+1]
** are unused room, so a loop stops at nbr_end[i].
**
** (The plainest search, all pairs, is in reference/afv_plain.c; make twins
** compares.)  The search finds the lists so:
**   - a cell list ("cell list": grid_periodic / grid_open, fill_bins) of
**     reach (2 + SKIN) l, scanned without a branch on the distance
**     (scan_cell), gives every cell its Verlet candidates ("Verlet
**     candidates"), rebuilt only when many cells have moved farther than
**     SKIN l / 2 from their anchors (a few such "MOVERS" are re-anchored
**     one by one);
**   - at every call each cell's candidates are filtered by the exact
**     distance and sorted (filter_cell), written in place ("neighbour
**     lists"), and the pairs linked.
** Cost: O(N) time and memory.  Dense input (a cell with more than
** DENSE_CANDIDATES candidates) takes the dense search instead: centres
** proposed in order of distance, each taken only if it cuts the cell
** the nearer ones leave, as geom.c clips it (DENSE, dense_candidates);
** long lists are merge-sorted and reverse slots found by binary search.
** These two searches, and no other: the dense one costs about twice the
** cell list's at the paper's densities, the cell list is quadratic on
** dense input (doc/performance.md, "Dense and degenerate input").  Every
** shape is computed by geom.c's clipping from the lists either gives.
** afv_cells_around reads the cell list for afv_force_check;
** afv_spatial_order numbers cells in its order, afv_spatial_renumber
** renumbers centres so (afv_protocol_start's generated starts, make
** bench).  The buffers of an afv_geom are grown here too (afv_grow,
** grow_cells).
** Every per-cell loop may run on OpenMP threads with the same result bits
** (afv_internal.h).
**
** Invariants of the lists after afv_neighbours (asserted where relied on,
** in a build without -DNDEBUG):
**   - symmetric: j is in i's list iff i is in j's, with D_t = -D_s
**     exactly (fold is odd), so nbr_rev[nbr_rev[s]] = s (link_cell;
**     gather_forces in afv.c);
**   - each list sorted by comes_after, the counter-clockwise order of the
**     edges (afv_slots_sorted; afv_cell_shape in geom.c);
**   - every pair closer than 2l and apart: the edge cache's h = d/2 is
**     in (0, l] (fill_edge_pair; the clipping's half-chords).
*/
#include "afv.h"
#include "afv_internal.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* At most BINS_PER_CELL bins per cell (plus BINS_SLACK for tiny N): a
** sparse periodic box or spread-out open points get wider bins, so that
** memory stays O(N) however large the box or far apart the points. */
#define BINS_PER_CELL 2
#define BINS_SLACK    16

/* ---- buffers ----------------------------------------------------------- */
int afv_grow(void **ptr, int *cap, int need, size_t elem)
{
  void *q;
  int newcap;
  if (need <= *cap) return AFV_OK;
  if (need > INT_MAX / 2) return AFV_ENOMEM;   /* doubling would overflow */
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
  if (afv_grow((void **)&g->area, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->perim, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->arc, &c, n + 1, sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->contacts, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->piece_start, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->n_pieces, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->nbr_start, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->nbr_end, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->bin_cell, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->bin_xy, &c, n + 1, 2 * sizeof(double)))
    return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->cand_r0, &c, n + 1, 2 * sizeof(double)))
    return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->rw, &c, n + 1, 2 * sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->cand_start, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->cand_end, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->cand_lim, &c, n + 1, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->anchor_node, &c, n + 1, sizeof(int)))
    return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->is_mover, &c, n + 1, 1)) return AFV_ENOMEM;
  g->cap_cells = c;
  return AFV_OK;
}

/* Neighbour slot arrays: nbr and nbr_rev (ints), nbr_d and grad (pairs),
** edge (quadruples). */
static int grow_nbr(afv_geom *g, int need)
{
  int cap = g->cap_nbr, c;
  if (need <= cap) return AFV_OK;
  c = cap;
  if (afv_grow((void **)&g->nbr, &c, need, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->nbr_rev, &c, need, sizeof(int))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->nbr_d, &c, need, 2 * sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->grad, &c, need, 2 * sizeof(double))) return AFV_ENOMEM;
  c = cap;
  if (afv_grow((void **)&g->edge, &c, need, 4 * sizeof(double))) return AFV_ENOMEM;
  g->cap_nbr = c;
  return AFV_OK;
}

void afv_geom_free(afv_geom *g)
{
  free(g->area); free(g->perim); free(g->arc); free(g->contacts);
  free(g->piece_start); free(g->n_pieces); free(g->pieces);
  free(g->nbr_start); free(g->nbr_end); free(g->nbr); free(g->nbr_d);
  free(g->nbr_rev);
  free(g->bin_start); free(g->bin_cell); free(g->bin_xy); free(g->edge);
  free(g->cand_start); free(g->cand); free(g->cand_r0); free(g->rw);
  free(g->grad); free(g->work); free(g->is_mover);
  free(g->cand_end); free(g->cand_lim); free(g->anchor_node);
  free(g->node_head); free(g->node_next); free(g->node_cell);
  free(g->node_xy);
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
  double w;
  if (x >= 0 && x < L) return x;   /* nearly always: no floor, no division
                                   ** (and x just below L stays x, where
                                   ** x / L rounds to 1 and w was -tiny) */
  w = x - L * floor(x / L);
  return w >= L ? 0.0 : w;   /* x = -tiny gives w = L after rounding */
}

void afv_wrap(const afv_box *b, double *x, double *y)
{
  if (!b || !b->periodic) return;
  *x = wrap1(*x, b->Lx);
  *y = wrap1(*y, b->Ly);
}

/* ---- cell list --------------------------------------------------------- */
/* The grid of bins.  Bins have sides >= 2 half_range, the argument of
** grid_periodic / grid_open (the candidates pass half their search range
** (2 + SKIN) l there), so a scan of the 3 x 3 bins around a cell finds
** every cell within that range. */
typedef afv_grid grid;   /* afv_internal.h: nbx, nby, periodic, x0, y0, wx, wy, Lx, Ly */

/* Bins of side >= 2 half_range dividing the box evenly, at most
** BINS_PER_CELL per cell (+ BINS_SLACK): a sparse box gets fewer, wider
** bins, so memory stays O(N) whatever the box size.  Counted in double
** until they are known to fit an int. */
static void grid_periodic(grid *G, const afv_box *b, double half_range,
                          int n)
{
  double fx = floor(b->Lx / (2 * half_range));
  double fy = floor(b->Ly / (2 * half_range));
  double most = (double)BINS_PER_CELL * n + BINS_SLACK;
  if (fx < 1) fx = 1;
  if (fy < 1) fy = 1;
  while (fx * fy > most) {
    fx = fx > 1 ? floor(fx / 2) : 1;
    fy = fy > 1 ? floor(fy / 2) : 1;
  }
  G->periodic = 1;
  G->nbx = (int)fx;
  G->nby = (int)fy;
  G->x0 = G->y0 = 0;
  G->wx = b->Lx / G->nbx;
  G->wy = b->Ly / G->nby;
  G->Lx = b->Lx;
  G->Ly = b->Ly;
}

/* The spans of the centres, xmax - xmin and ymax - ymin (halved and
** doubled back: no overflow; inf for centres near +-DBL_MAX). */
static void grid_span(int n, const double *r, double *sx, double *sy)
{
  double xmin = r[0], xmax = r[0], ymin = r[1], ymax = r[1];
  int i;
  for (i = 1; i < n; i++) {
    xmin = fmin(xmin, r[2*i]);
    xmax = fmax(xmax, r[2*i]);
    ymin = fmin(ymin, r[2*i+1]);
    ymax = fmax(ymax, r[2*i+1]);
  }
  *sx = 2 * (0.5 * xmax - 0.5 * xmin);
  *sy = 2 * (0.5 * ymax - 0.5 * ymin);
}

static void grid_open(grid *G, int n, const double *r, double half_range)
{
  double xmin = r[0], xmax = r[0], ymin = r[1], ymax = r[1], w = 2 * half_range;
  double hx, hy;
  int i;
  for (i = 1; i < n; i++) {
    if (r[2*i] < xmin) xmin = r[2*i];
    if (r[2*i] > xmax) xmax = r[2*i];
    if (r[2*i+1] < ymin) ymin = r[2*i+1];
    if (r[2*i+1] > ymax) ymax = r[2*i+1];
  }
  /* half spans: xmax - xmin itself overflows for coordinates near
  ** +-DBL_MAX; and w must stay finite (inf / inf in bin_of is NaN) */
  hx = 0.5 * xmax - 0.5 * xmin;
  hy = 0.5 * ymax - 0.5 * ymin;
  /* widen the bins until there are at most BINS_PER_CELL per cell */
  while ((2 * (hx / w) + 1) * (2 * (hy / w) + 1)
         > (double)BINS_PER_CELL * n + BINS_SLACK && isfinite(4 * w))
    w *= 2;
  G->periodic = 0;
  G->x0 = xmin;
  G->y0 = ymin;
  G->wx = G->wy = w;
  G->nbx = (int)floor(2 * (hx / w)) + 1;
  G->nby = (int)floor(2 * (hy / w)) + 1;
  G->Lx = G->Ly = 0;
}

/* The position of cell i as the cell list sees it: wrapped into the box
** when periodic, so that the displacement of two such positions is less
** than a box side in each component (see fold). */
static void list_position(const grid *G, const double *r, int i, double *x,
                          double *y)
{
  *x = r[2*i];
  *y = r[2*i+1];
  if (G->periodic) {
    *x = wrap1(*x, G->Lx);
    *y = wrap1(*y, G->Ly);
  }
}

static int bin_of(const grid *G, double x, double y)
{
  /* clamp before the conversion to int: x - x0 overflows to inf for
  ** coordinates near +-DBL_MAX, and (int)inf is undefined */
  double fx = floor((x - G->x0) / G->wx), fy = floor((y - G->y0) / G->wy);
  int bx = !(fx > 0) ? 0 : fx >= G->nbx ? G->nbx - 1 : (int)fx;
  int by = !(fy > 0) ? 0 : fy >= G->nby ? G->nby - 1 : (int)fy;
  return by * G->nbx + bx;
}

/* Counting sort of the cells into bins: bin b holds
** bin_cell[bin_start[b] .. bin_start[b+1]-1], in increasing cell order, and
** bin_xy holds their list positions in the same order, so that a bin scan
** reads consecutive memory. */
static int fill_bins(afv_geom *g, const grid *G, int n, const double *r)
{
  int nb = G->nbx * G->nby, i, b;
  double x, y;
  if (afv_grow((void **)&g->bin_start, &g->cap_bins, nb + 1, sizeof(int)))
    return AFV_ENOMEM;
  memset(g->bin_start, 0, (size_t)(nb + 1) * sizeof(int));
  for (i = 0; i < n; i++) {
    list_position(G, r, i, &x, &y);
    g->bin_start[bin_of(G, x, y) + 1]++;
  }
  for (b = 0; b < nb; b++) g->bin_start[b + 1] += g->bin_start[b];
  for (i = 0; i < n; i++) {
    int k;
    list_position(G, r, i, &x, &y);
    k = g->bin_start[bin_of(G, x, y)]++;
    g->bin_cell[k] = i;
    g->bin_xy[2*k] = x;
    g->bin_xy[2*k+1] = y;
  }
  for (b = nb; b > 0; b--) g->bin_start[b] = g->bin_start[b - 1];
  g->bin_start[0] = 0;
  return AFV_OK;
}

/* Minimum image of a component dx of the displacement of two wrapped
** positions (|dx| < L): one fold suffices, and replaces the division and
** round() of afv_min_image in the innermost loop.  It is exactly odd
** (fold(-dx) = -fold(dx)), so neighbour lists stay symmetric. */
static double fold(double dx, double L)
{
  if (dx > 0.5 * L) return dx - L;
  if (dx < -0.5 * L) return dx + L;
  return dx;
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

/* Bin coordinate c (one off the grid at most) on an axis of nb bins:
** wrapped if periodic, -1 if it lies outside an open grid.  *shift is the
** displacement of the image of that bin next to the cell's own bin: with
** 3 or more periodic bins, the image of a cell within 2l lies in the bin
** column (row) c unwrapped, so r_j + shift - r_i is its minimum image
** (the same sum fold would form).  *shift = 0 when there is nothing to do
** or when fold must decide (fewer than 3 bins). */
static int bin_coord(int c, int nb, int periodic, double L, double *shift)
{
  *shift = 0;
  if (c >= 0 && c < nb) return c;
  if (!periodic) return -1;
  if (nb >= 3) *shift = c < 0 ? -L : L;
  return c < 0 ? c + nb : c - nb;
}

/* A run of consecutive positions in bin order, bin_xy[first .. end-1],
** and the shift (sx, sy) that carries their cells next to the scanning
** cell's bin (bin_coord). */
typedef struct bin_run {
  int first, end;
  double sx, sy;
} bin_run;

/* The 3 x 3 bins around bin (bx, by) as runs, in the order a scan visits
** them (rows, then columns): bins side by side in a row with the same
** shift are consecutive in bin order and make one run, so an interior bin
** has three runs, one per row, not nine bins.  Returns how many (<= 9);
** fewer bins at the edges of an open grid, or with fewer than 3 periodic
** bins along an axis (stencil). */
static int stencil_runs(const afv_geom *g, const grid *G, int bx, int by,
                        bin_run *run)
{
  int xlo, xhi, ylo, yhi, ox, oy, nr = 0, last = -2;
  stencil(G->nbx, G->periodic, &xlo, &xhi);
  stencil(G->nby, G->periodic, &ylo, &yhi);
  for (oy = ylo; oy <= yhi; oy++) {
    double sy, sx;
    int cy = bin_coord(by + oy, G->nby, G->periodic, G->Ly, &sy);
    if (cy < 0) continue;
    for (ox = xlo; ox <= xhi; ox++) {
      int cx = bin_coord(bx + ox, G->nbx, G->periodic, G->Lx, &sx), bin;
      if (cx < 0) continue;
      bin = cy * G->nbx + cx;
      if (bin == last + 1 && run[nr - 1].sx == sx && run[nr - 1].sy == sy) {
        run[nr - 1].end = g->bin_start[bin + 1];   /* extends the run */
      } else {
        run[nr].first = g->bin_start[bin];
        run[nr].end = g->bin_start[bin + 1];
        run[nr].sx = sx;
        run[nr].sy = sy;
        nr++;
      }
      last = bin;
    }
  }
  return nr;
}

/* The cells closer than `range` to the cell at bin-order position k, found
** in the nr runs of its bin's stencil (stencil_runs), written to out[] (if
** not NULL; it has room for exactly `room` of them, the count of the
** counting pass) in the order of the runs.  Returns their number.  A
** cell with the same wrapped centre is a candidate like any other:
** filter_cell decides on the exact displacement whether two centres
** coincide (wrapping can round two distinct centres onto one).
** The loop has no branch on the distance, which a predictor cannot learn
** in a random tissue (where a minority of the cells scanned are
** candidates, in no order).  Every cell scanned is stored at
** the next free place, which the next candidate overwrites if it was
** none; once the list is full the stores go to a scratch word instead. */
static int scan_cell(const afv_geom *g, const grid *G, int k,
                     const bin_run *run, int nr, double range, int *out,
                     int room)
{
  double xi = g->bin_xy[2*k], yi = g->bin_xy[2*k+1], range2 = range * range;
  int count = 0, scratch, q, m;
  int small = G->periodic && (G->nbx < 3 || G->nby < 3);
  for (q = 0; q < nr; q++) {
    double sx = run[q].sx, sy = run[q].sy;
    int end = run[q].end;
    for (m = run[q].first; m < end; m++) {
      double dx = g->bin_xy[2*m] - xi + sx, dy = g->bin_xy[2*m+1] - yi + sy;
      double d2;
      int other = m != k;
      if (small) {
        dx = fold(dx, G->Lx);
        dy = fold(dy, G->Ly);
      }
      d2 = dx * dx + dy * dy;
      if (out) *(count < room ? out + count : &scratch) = g->bin_cell[m];
      count += (d2 < range2) & other;
    }
  }
  return count;
}

/* Runs scan_cell for every cell, bin by bin: the cells of a bin share its
** stencil's runs, and neighbouring cells are visited together, which keeps
** the scanned bins in cache.  Counting pass (fill = 0): cand_start[i+1] =
** count of cell i.  Filling pass:
** the lists, at cand_start[i].  Each cell writes only its own entries, so
** the bins may be shared among threads. */
static void scan_all(afv_geom *g, const grid *G, double range, int fill)
{
  int nb = G->nbx * G->nby, b;
  AFV_PARALLEL_FOR(nb)
  for (b = 0; b < nb; b++) {
    bin_run run[9];
    int k, nr;
    if (g->bin_start[b] == g->bin_start[b + 1]) continue;
    nr = stencil_runs(g, G, b % G->nbx, b / G->nbx, run);
    for (k = g->bin_start[b]; k < g->bin_start[b + 1]; k++) {
      int i = g->bin_cell[k];
      int *out = fill ? g->cand + g->cand_start[i] : NULL;
      int room = fill ? g->cand_start[i + 1] - g->cand_start[i] : 0;
      int c = scan_cell(g, G, k, run, nr, range, out, room);
      if (!fill) g->cand_start[i + 1] = c;
    }
  }
}

/* After a pass that left count[i] = -1 - j where cells i and j coincide
** (list_cell): names the pair with the smallest cell number (the same
** whatever the thread count), or returns AFV_OK. */
static int find_coincident(afv_geom *g, const int *count, int n)
{
  int i;
  for (i = 0; i < n; i++)
    if (count[i] < 0) {
      int j = -1 - count[i];
      g->bad_i = i < j ? i : j;
      g->bad_j = i < j ? j : i;
      return AFV_ECOINCIDENT;
    }
  return AFV_OK;
}

/* ---- Verlet candidates ------------------------------------------------- */

/* The cell list is not searched at every call: the candidate list of cell
** i holds every cell that was closer than (2 + SKIN) l when it was built,
** and it stays valid while no cell has moved more than SKIN l / 2 since
** (a pair then approaches by less than SKIN l, so none closer than 2l can
** be missing).  Each call filters the candidates by the exact distance and
** sorts them by direction, so the neighbour lists are a function of the
** positions alone: the same bits whether or not the candidates were rebuilt
** (a resumed run repeats an uninterrupted one).
** A few cells that have moved farther do not force a rebuild (MOVERS,
** below).  SKIN = 0.3 l: (2.3/2)^2 = 1.3x the pairs of a 2l search, and
** the fewest instructions per step of the skins tried in the two
** benchmark states (doc/performance.md). */
#define SKIN 0.3

static int same_box(const afv_box *a, const afv_box *b)
{
  if (!b || !b->periodic) return !a->periodic;
  return a->periodic && a->Lx == b->Lx && a->Ly == b->Ly;
}

/* The centre of cell i as the lists see it: wrapped into the box. */
static void wrap_all(afv_geom *g, int n, const double *r, const afv_box *b)
{
  int i;
  AFV_PARALLEL_FOR(n)
  for (i = 0; i < 2 * n; i += 2) {
    g->rw[i] = r[i];
    g->rw[i+1] = r[i+1];
    afv_wrap(b, &g->rw[i], &g->rw[i+1]);
  }
}

/* D = r_j - r_i from the wrapped centres, minimum image by fold (the
** wrapped centres differ by less than a box side). */
static void displacement(const afv_geom *g, int i, int j, const afv_box *b,
                         double *dx, double *dy)
{
  *dx = g->rw[2*j] - g->rw[2*i];
  *dy = g->rw[2*j+1] - g->rw[2*i+1];
  if (b && b->periodic) {
    *dx = fold(*dx, b->Lx);
    *dy = fold(*dy, b->Ly);
  }
}

/* The bins along one axis (nb bins of side w from x0) that come within Q of
** the coordinate x (wrapped into the box if periodic): *count of them from
** *first on, to be wrapped mod nb if periodic (each bin once). */
static void bin_range(double x, double Q, double x0, double w, int nb,
                      int periodic, int *first, int *count)
{
  double lo = floor((x - Q - x0) / w), hi = floor((x + Q - x0) / w);
  if (periodic) {
    *first = (int)fmax(lo, -nb);    /* fmax: no int overflow for a huge Q */
    *count = hi - lo + 1 >= nb ? nb : (int)(hi - lo) + 1;
    *first = ((*first % nb) + nb) % nb;
    return;
  }
  lo = fmin(fmax(lo, 0), nb - 1);   /* cells beyond the grid sit in its */
  hi = fmin(fmax(hi, 0), nb - 1);   /* edge bins (bin_of clamps them) */
  *first = (int)lo;
  *count = (int)(hi - lo) + 1;
}

/* A window of bins of the rebuild's cell list: nx by ny bins from (fx, fy)
** on (wrapped mod the grid if periodic). */
typedef struct bin_window {
  int fx, nx, fy, ny;
} bin_window;

/* MOVERS.  The candidates hold every pair whose anchors are closer than
** (2 + SKIN) l, a cell's anchor (cand_r0) being its centre when its list
** was made.  While every cell lies within SKIN l / 2 of its anchor, a pair
** closer than 2l has anchors closer than (2 + SKIN) l, so it is a candidate
** pair.  A cell farther from its anchor (a "mover": a cell thrown far by a
** large force, which the paper's Euler step moves by F dt however far) is
** re-anchored (reanchor): its list is made anew about its centre, and it
** is added to the lists of the cells now within reach and taken out of
** those no longer within it; so one fast cell anywhere costs a few
** updates, not a rebuild of the whole tissue.  (The Euler step of afv
** 0.3.0 moves a cell of the benchmark's random state by up to 8 l in one
** step, hundreds of cells a step at N = 400000: with a rebuild whenever a
** mover had a pair that was not a candidate, the candidates were rebuilt
** at nearly every step there, and a step cost 2.5x its N = 400 cost per
** cell: doc/performance.md, "Movers".)
** The anchors of the cells not re-anchored since the rebuild are their
** places in the rebuild's bins (bin_xy); a re-anchored cell is found in a
** second index on the same bins (anchor_node, node_*: a list of nodes per
** bin, a cell's node replaced when it is re-anchored again).  A list that
** outgrows its room moves to the spare room after the rebuild's lists,
** with twice the room.  The candidates are rebuilt instead when the movers
** are more than MOVERS_MAX, or the re-anchoring work since the rebuild
** reaches CHECKS_PER_CELL per cell (about the cost of a rebuild: the
** ski-rental rule, never more than twice the cost of the better choice
** made in hindsight), or the spare room or the nodes run out. */
#define MOVERS_MAX(n) ((n) / 8 + 16)
#define CHECKS_PER_CELL 25
#define SPARE_ROOM(used) ((used) / 4 + 64)   /* cand[] slots after the lists */
#define NODES_MAX(n) ((n) / 4 + 16)
#define REANCHOR_MOST 256      /* candidates a re-anchored cell may have */

/* The bins of the rebuild's grid within Q of (x, y) (wrapped, if periodic). */
static bin_window window_at(const afv_geom *g, double x, double y, double Q)
{
  const grid *G = &g->cand_grid;
  bin_window w;
  bin_range(x, Q, G->x0, G->wx, G->nbx, G->periodic, &w.fx, &w.nx);
  bin_range(y, Q, G->y0, G->wy, G->nby, G->periodic, &w.fy, &w.ny);
  return w;
}

/* The bins that may hold a cell now within R of (x, y): every anchor lies
** within cand_moved of its cell, and cells moved at most `moved` since. */
static bin_window window_around(const afv_geom *g, double x, double y,
                                double R, double moved)
{
  const grid *G = &g->cand_grid;
  if (G->periodic) {
    x = wrap1(x, G->Lx);
    y = wrap1(y, G->Ly);
  }
  return window_at(g, x, y, R + g->cand_moved + moved
                            + AFV_REACH_MARGIN * g->cand_l);
}

/* Bin q (0 <= q < nx ny) of the window, row by row. */
static int window_bin(const afv_geom *g, const bin_window *w, int q)
{
  const grid *G = &g->cand_grid;
  int bx = (w->fx + q % w->nx) % G->nbx, by = (w->fy + q / w->nx) % G->nby;
  return by * G->nbx + bx;
}

/* Calls visit(ctx, j, x, y) for every cell j anchored in bin `bin`, at
** its anchor (x, y) (wrapped): the cells still at their rebuild places,
** then the re-anchored ones (their current nodes only). */
typedef int (*anchor_visit)(void *ctx, int j, double x, double y);

static int visit_bin(const afv_geom *g, int bin, anchor_visit visit,
                     void *ctx)
{
  int k, node;
  for (k = g->bin_start[bin]; k < g->bin_start[bin + 1]; k++) {
    int j = g->bin_cell[k];
    if (g->anchor_node[j] < 0
        && visit(ctx, j, g->bin_xy[2*k], g->bin_xy[2*k+1]))
      return 1;
  }
  for (node = g->node_head[bin]; node >= 0; node = g->node_next[node]) {
    int j = g->node_cell[node];
    if (g->anchor_node[j] == node
        && visit(ctx, j, g->node_xy[2*node], g->node_xy[2*node+1]))
      return 1;
  }
  return 0;
}

typedef struct around_ctx {
  int *out, m;
} around_ctx;

static int put_cell(void *ctx, int j, double x, double y)
{
  around_ctx *c = ctx;
  (void)x; (void)y;
  c->out[c->m++] = j;
  return 0;
}

int afv_cells_around(const afv_geom *g, double x, double y, double R,
                     double moved, int *out)
{
  bin_window w = window_around(g, x, y, R, moved);
  around_ctx c;
  int q;
  c.out = out;
  c.m = 0;
  for (q = 0; q < w.nx * w.ny; q++) visit_bin(g, window_bin(g, &w, q),
                                              put_cell, &c);
  return c.m;
}

/* The search of a re-anchored cell m: the cells whose anchors lie within
** range of (x, y), m's new anchor, into found[] (at most REANCHOR_MOST). */
typedef struct reach_ctx {
  const afv_geom *g;
  int m, count, found[REANCHOR_MOST];
  double x, y, range2, tests;
} reach_ctx;

static int reach_cell(void *ctx, int j, double x, double y)
{
  reach_ctx *c = ctx;
  const grid *G = &c->g->cand_grid;
  double dx = x - c->x, dy = y - c->y;
  c->tests++;
  if (G->periodic) {
    dx = fold(dx, G->Lx);
    dy = fold(dy, G->Ly);
  }
  if (j == c->m || !(dx * dx + dy * dy < c->range2)) return 0;
  if (c->count == REANCHOR_MOST) return 1;         /* too many: rebuild */
  c->found[c->count++] = j;
  return 0;
}

static int in_list(const int *a, int m, int j)
{
  int k;
  for (k = 0; k < m; k++)
    if (a[k] == j) return 1;
  return 0;
}

/* Gives cell i's list room for `need` candidates: moved, if it has not,
** to the spare room with twice that.  0 if the spare room is used up. */
static int make_room(afv_geom *g, int i, int need)
{
  int len = g->cand_end[i] - g->cand_start[i], room = 2 * need + 2;
  int at = g->cand_used;
  if (g->cand_start[i] + need <= g->cand_lim[i]) return 1;
  if (at + room > g->cand_top) return 0;
  memcpy(g->cand + at, g->cand + g->cand_start[i], (size_t)len * sizeof(int));
  g->cand_start[i] = at;
  g->cand_end[i] = at + len;
  g->cand_lim[i] = at + room;
  g->moved_lists++;
  g->cand_used = at + room;
  return 1;
}

/* Adds j to cell i's list (room permitting: 0 if not). */
static int add_candidate(afv_geom *g, int i, int j)
{
  if (!make_room(g, i, g->cand_end[i] - g->cand_start[i] + 1)) return 0;
  g->cand[g->cand_end[i]++] = j;
  return 1;
}

/* Takes j out of cell i's list (keeping the order of the others, which
** the sort after the rebuild left nearly sorted). */
static void remove_candidate(afv_geom *g, int i, int j)
{
  int *c = g->cand + g->cand_start[i], m = g->cand_end[i] - g->cand_start[i];
  int k;
  for (k = 0; k < m && c[k] != j; k++) {}
  if (k == m) return;
  memmove(c + k, c + k + 1, (size_t)(m - k - 1) * sizeof(int));
  g->cand_end[i]--;
}

/* Re-anchors mover m at its centre r_m (wrapped: g->rw): its list made
** anew from the anchors within (2 + SKIN) l, the pair added to or taken
** from the lists of the others, a node for m's new anchor.  0 if the
** candidates must be rebuilt instead (too many found, no room left). */
static int reanchor(afv_geom *g, int m, const double *r, double l)
{
  const grid *G = &g->cand_grid;
  double range = (2 + SKIN) * l + AFV_REACH_MARGIN * l;
  reach_ctx c;
  bin_window w;
  int q, k, *old = g->cand + g->cand_start[m];
  int n_old = g->cand_end[m] - g->cand_start[m], node, bin;
  if (g->n_nodes == g->cap_nodes) return 0;
  c.g = g;
  c.m = m;
  c.count = 0;
  c.x = g->rw[2*m];
  c.y = g->rw[2*m+1];
  c.range2 = range * range;
  c.tests = 0;
  w = window_at(g, c.x, c.y, range);
  for (q = 0; q < w.nx * w.ny; q++)
    if (visit_bin(g, window_bin(g, &w, q), reach_cell, &c)) return 0;
  g->cand_checks += c.tests + n_old + c.count;
  for (k = 0; k < n_old; k++)
    if (!in_list(c.found, c.count, old[k])) remove_candidate(g, old[k], m);
  for (k = 0; k < c.count; k++)
    if (!in_list(old, n_old, c.found[k])
        && !add_candidate(g, c.found[k], m))
      return 0;
  if (!make_room(g, m, c.count)) return 0;
  if (c.count > 0)           /* (memcpy from a NULL buffer is undefined) */
    memcpy(g->cand + g->cand_start[m], c.found, (size_t)c.count * sizeof(int));
  g->cand_end[m] = g->cand_start[m] + c.count;
  node = g->n_nodes++;
  bin = bin_of(G, c.x, c.y);
  g->node_cell[node] = m;
  g->node_xy[2*node] = c.x;
  g->node_xy[2*node+1] = c.y;
  g->node_next[node] = g->node_head[bin];
  g->node_head[bin] = node;
  g->anchor_node[m] = node;
  g->cand_r0[2*m] = r[2*m];
  g->cand_r0[2*m+1] = r[2*m+1];
  return 1;
}

/* Piece storage: cell i with room for k candidates has at most k
** neighbours and 2k + 1 pieces (an edge per neighbour, an arc after each,
** or one full circle), so its pieces go at piece_start[i], the sum of
** 2k + 1 over the cells before it: in cell order whichever lists have moved
** (afv_clusters_compute's junctions are numbered in the pieces' order).
** Placed at a rebuild, and again only when a list has moved: no pass per
** call.  g->max_cand sizes the work space. */
static void place_pieces(afv_geom *g, int n)
{
  int i, at = 0;
  g->max_cand = 0;
  for (i = 0; i < n; i++) {
    int k = g->cand_lim[i] - g->cand_start[i];
    if (k > g->max_cand) g->max_cand = k;
    g->piece_start[i] = at;
    at += 2 * k + 1;
  }
  g->piece_start[n] = at;
}

/* 1 if the candidates were built for this n, l and box and hold every
** pair closer than 2l: no cell lies farther than SKIN l / 2 from its
** anchor, or the few that do (is_mover) have been re-anchored.  Sets
** g->cand_moved, the largest distance of a cell from its anchor. */
static int candidates_valid(afv_geom *g, int n, const double *r, double l,
                            const afv_box *b)
{
  double lim2 = 0.25 * SKIN * SKIN * l * l, most2 = 0;
  int i, movers = 0, nonfinite = 0, moved;
  if (g->cand_n != n || g->cand_l != l || !same_box(&g->cand_box, b)
      || g->cand_dense)
    return 0;
  AFV_PARALLEL_REDUCE(n, reduction(max: most2) reduction(+: movers)
                      reduction(|: nonfinite))
  for (i = 0; i < n; i++) {
    double dx = r[2*i] - g->cand_r0[2*i], dy = r[2*i+1] - g->cand_r0[2*i+1];
    double d2 = dx * dx + dy * dy;
    g->is_mover[i] = !(d2 <= lim2);
    movers += g->is_mover[i];
    if (!isfinite(d2)) nonfinite = 1;
    else if (d2 > most2 && d2 <= lim2) most2 = d2;
  }
  if (nonfinite || movers > MOVERS_MAX(n)) return 0;
  g->cand_moved = sqrt(most2);      /* a re-anchored mover is at 0 */
  moved = g->moved_lists;
  for (i = 0; i < n && movers > 0; i++)
    if (g->is_mover[i]) {
      if (g->cand_checks >= (double)CHECKS_PER_CELL * n
          || !reanchor(g, i, r, l))
        return 0;
      movers--;
    }
  if (g->moved_lists > moved) place_pieces(g, n);
  return 1;
}

/* ---- dense input ------------------------------------------------------ */
/* DENSE.  Far above the paper's densities (8000 cells in a 12 x 12 box: 55
** per l^2), or on degenerate layouts (thousands of centres on a line or a
** circle, or in a square of 0.01 l), each cell has hundreds or thousands
** of centres within 2l, nearly all of which cannot reach it.  There the
** candidates are proposed in order of distance, with a stop: the bins of
** a fine grid (about a cell each) are visited ring by ring about cell i's
** bin; a centre is taken if it cuts the cell that the centres taken so far
** leave (geom.c's clipping shapes that cell, afv_reach_of, and decides,
** afv_reach_cuts); a bin none of whose points can cut that cell is
** skipped (afv_reach_meets_rect), and the walk stops at the first ring of
** skipped bins (the points that cut a cell form a region star-shaped about
** its centre, so no farther ring can hold one).  Within a bin the centres
** that cut are taken nearest first, so that later ones are tested against
** the cell the nearer ones left.  Every centre that cuts the final cell
** cuts each larger cell before it, so it is taken: the candidates of i
** hold every centre that cuts cell i (but those that cut it by less than
** AFV_CUT_DEPTH l, as every other centre of a circle does at its centre
** by rounding), and the lists, made symmetric, are clipped by geom.c as
** any others.  These lists depend on the positions (no skin), so they are
** made at every call (cand_dense).  Cost O(N) in time and memory for the
** layouts measured (doc/performance.md, "Dense and degenerate input").
** DENSE_CANDIDATES: a cell of a tissue at the paper's densities has 6 to
** 20 centres within (2 + SKIN) l (the authors' compressed start about 28);
** 64 is more than twice that, so their lists never take this path. */
#define DENSE_CANDIDATES 64

static void sort_slots(int *nbr, double *d, int m);
static inline void edge_entry(double dx, double dy, double l, double *e);
static double near_limit2(const afv_box *b);

/* The bin offsets along one axis of nb bins that a walk may visit, each
** bin once: -lo .. hi (periodic: at most half the bins each way; open:
** those on the grid). */
static void walk_range(int c, int nb, int periodic, int *lo, int *hi)
{
  if (periodic) {
    *lo = (nb - 1) / 2;
    *hi = nb - 1 - *lo;
  } else {
    *lo = c;
    *hi = nb - 1 - c;
  }
}

/* A centre met in a bin that cuts the cell: its displacement, d^2. */
typedef struct cutter {
  double dx, dy, d2;
  int j;
} cutter;

/* Nearest first, ties by cell: a total order, so the walk takes the same
** centres whatever the sort. */
static int nearer(const void *a, const void *b)
{
  const cutter *p = a, *q = b;
  if (p->d2 != q->d2) return p->d2 < q->d2 ? -1 : 1;
  return (p->j > q->j) - (p->j < q->j);
}

/* Walk state for cell i: its wrapped centre; the centres taken (cell,
** displacement, edge cache, sorted by direction) and the reach of the
** cell they leave; the centres closer than the NEAR limit, taken without
** a test (filter_cell decides on them); the centres of one bin that cut. */
typedef struct dense_walk {
  double x, y, l, near2;
  int *take, n_take, cap_take, cap_d, cap_e, cap_v, cap_a, cap_w;
  double *take_d, *take_e;
  afv_reach R;
  void *work;
  struct cutter *cut;        /* the cutters met in one bin */
  int n_cut, cap_cut;
  int *near, n_near, cap_near;
} dense_walk;

/* Keeps a centre nearly on cell i's (NEAR), untested. */
static int take_near(dense_walk *W, int j)
{
  if (afv_grow((void **)&W->near, &W->cap_near, W->n_near + 1, sizeof(int)))
    return AFV_ENOMEM;
  W->near[W->n_near++] = j;
  return AFV_OK;
}

static int grow_walk(dense_walk *W, int k)
{
  if (afv_grow((void **)&W->take, &W->cap_take, k, sizeof(int))
      || afv_grow((void **)&W->take_d, &W->cap_d, k, 2 * sizeof(double))
      || afv_grow((void **)&W->take_e, &W->cap_e, k, 4 * sizeof(double))
      || afv_grow((void **)&W->R.v, &W->cap_v, 2 * k + 2, 2 * sizeof(double))
      || afv_grow((void **)&W->R.arc, &W->cap_a, k + 1, 4 * sizeof(double))
      || afv_grow((void **)&W->work, &W->cap_w, (int)afv_reach_work(k) + 1,
                  1))
    return AFV_ENOMEM;
  return AFV_OK;
}

/* Takes centre j at (dx, dy): into the sorted lists, and the reach anew. */
static int take_centre(dense_walk *W, int j, double dx, double dy)
{
  int k = W->n_take, q;
  if (grow_walk(W, k + 1)) return AFV_ENOMEM;
  W->take[k] = j;
  W->take_d[2*k] = dx;
  W->take_d[2*k+1] = dy;
  W->n_take = k + 1;
  sort_slots(W->take, W->take_d, W->n_take);  /* one insertion */
  for (q = 0; q < W->n_take; q++)
    edge_entry(W->take_d[2*q], W->take_d[2*q+1], W->l, W->take_e + 4 * q);
  afv_reach_of(W->take_e, W->take_d, W->n_take, W->l, W->work, &W->R);
  return AFV_OK;
}

/* Visits bin `bin` for the walk W of cell i: each centre that cuts the
** cell is taken, nearest first; a NEAR one is kept untested. */
static int walk_bin(const afv_geom *g, const grid *G, int i, int bin,
                    dense_walk *W)
{
  int k, st;
  W->n_cut = 0;
  for (k = g->bin_start[bin]; k < g->bin_start[bin + 1]; k++) {
    int j = g->bin_cell[k];
    double dx = g->bin_xy[2*k] - W->x, dy = g->bin_xy[2*k+1] - W->y, d2;
    if (j == i) continue;
    if (G->periodic) {
      dx = fold(dx, G->Lx);
      dy = fold(dy, G->Ly);
    }
    d2 = dx * dx + dy * dy;
    if (d2 < W->near2) {
      if ((st = take_near(W, j)) != AFV_OK) return st;
      continue;
    }
    if (!(d2 < 4 * W->l * W->l) || !afv_reach_cuts(&W->R, dx, dy)) continue;
    if (afv_grow((void **)&W->cut, &W->cap_cut, W->n_cut + 1,
                 sizeof(cutter)))
      return AFV_ENOMEM;
    W->cut[W->n_cut].dx = dx;
    W->cut[W->n_cut].dy = dy;
    W->cut[W->n_cut].d2 = d2;
    W->cut[W->n_cut++].j = j;
  }
  if (W->n_cut > 1) qsort(W->cut, (size_t)W->n_cut, sizeof(cutter), nearer);
  for (k = 0; k < W->n_cut; k++) {
    const cutter *c = &W->cut[k];
    if (k > 0 && !afv_reach_cuts(&W->R, c->dx, c->dy)) continue;
    if ((st = take_centre(W, c->j, c->dx, c->dy)) != AFV_OK) return st;
  }
  return AFV_OK;
}

/* Bin of offset (ox, oy) from (bx, by): -1 off an open grid. */
static int offset_bin(const grid *G, int bx, int by, int ox, int oy)
{
  int cx = bx + ox, cy = by + oy;
  if (G->periodic) {
    cx = ((cx % G->nbx) + G->nbx) % G->nbx;
    cy = ((cy % G->nby) + G->nby) % G->nby;
  } else if (cx < 0 || cx >= G->nbx || cy < 0 || cy >= G->nby) {
    return -1;
  }
  return cy * G->nbx + cx;
}

/* The walk of cell i (bin-order position q): rings of bins about its bin;
** a bin whose rectangle cannot hold a cutter is skipped, and the walk
** stops after a ring of such bins.  Where a ring's centres may lie half a
** periodic box away (the minimum image could then be another image than
** the bin's), its bins are all visited and the walk goes on to the end. */
static int walk_cell(const afv_geom *g, const grid *G, int q, dense_walk *W)
{
  int i = g->bin_cell[q], bin = bin_of(G, g->bin_xy[2*q], g->bin_xy[2*q+1]);
  int bx = bin % G->nbx, by = bin / G->nbx, xlo, xhi, ylo, yhi, k, K, st;
  W->x = g->bin_xy[2*q];
  W->y = g->bin_xy[2*q+1];
  W->n_take = W->n_near = 0;
  W->R.nv = 0;
  W->R.na = -1;                     /* the whole disk */
  W->R.l = W->l;
  walk_range(bx, G->nbx, G->periodic, &xlo, &xhi);
  walk_range(by, G->nby, G->periodic, &ylo, &yhi);
  K = xlo > xhi ? xlo : xhi;
  if (ylo > K) K = ylo;
  if (yhi > K) K = yhi;
  for (k = 0; k <= K; k++) {
    int ox, oy, met = 0;
    int exact = !G->periodic || ((k + 1) * G->wx < 0.5 * G->Lx
                                 && (k + 1) * G->wy < 0.5 * G->Ly);
    for (oy = -k; oy <= k; oy++) {
      int step = (oy == -k || oy == k) ? 1 : 2 * k;   /* the ring only */
      if (oy < -ylo || oy > yhi) continue;
      for (ox = -k; ox <= k; ox += step > 0 ? step : 1) {
        int b2;
        if (ox < -xlo || ox > xhi) continue;
        if ((b2 = offset_bin(G, bx, by, ox, oy)) < 0) continue;
        if (exact) {
          double rect[4];
          rect[0] = G->x0 + (bx + ox) * G->wx - W->x;
          rect[1] = rect[0] + G->wx;
          rect[2] = G->y0 + (by + oy) * G->wy - W->y;
          rect[3] = rect[2] + G->wy;
          if (!afv_reach_meets_rect(&W->R, rect)) continue;
        }
        met = 1;
        if ((st = walk_bin(g, G, i, b2, W)) != AFV_OK) return st;
      }
    }
    if (exact && !met) break;
  }
  return AFV_OK;
}

/* 1 if the first cell of the fullest bin has more than DENSE_CANDIDATES
** within range: dense input found without counting every cell's (which
** takes seconds there); 0 says nothing (the count decides). */
static int dense_probe(const afv_geom *g, const grid *G, double range)
{
  bin_run run[9];
  int nb = G->nbx * G->nby, b, best = 0, k, nr;
  for (b = 1; b < nb; b++)
    if (g->bin_start[b + 1] - g->bin_start[b]
        > g->bin_start[best + 1] - g->bin_start[best])
      best = b;
  k = g->bin_start[best];
  if (g->bin_start[best + 1] - k <= DENSE_CANDIDATES) return 0;
  nr = stencil_runs(g, G, best % G->nbx, best / G->nbx, run);
  return scan_cell(g, G, k, run, nr, range, NULL, 0) > DENSE_CANDIDATES;
}

/* Sorts a few ints (insertion; a dense cell's list holds ~10 to 30). */
static void sort_ints(int *a, int m)
{
  int k, q;
  for (k = 1; k < m; k++) {
    int v = a[k];
    for (q = k; q > 0 && a[q - 1] > v; q--) a[q] = a[q - 1];
    a[q] = v;
  }
}

/* Every cell's walk: the centres that cut cell i (and the NEAR ones) go
** to out[first[i] .. first[i] + len[i] - 1] (out grown as needed). */
static int walk_all(const afv_geom *g, const grid *G, int n, double l,
                    double near2, int **out, int *cap_out, int *first,
                    int *len)
{
  dense_walk W;
  int q, total = 0, st = AFV_OK;
  memset(&W, 0, sizeof W);
  W.l = l;
  W.near2 = near2;
  st = grow_walk(&W, 16);
  for (q = 0; q < n && st == AFV_OK; q++) {   /* in bin order */
    int i = g->bin_cell[q];
    if ((st = walk_cell(g, G, q, &W)) != AFV_OK) break;
    if (afv_grow((void **)out, cap_out, total + W.n_take + W.n_near + 1,
                 sizeof(int))) {
      st = AFV_ENOMEM;
      break;
    }
    first[i] = total;
    if (W.n_take > 0)        /* (memcpy from a NULL buffer is undefined) */
      memcpy(*out + total, W.take, (size_t)W.n_take * sizeof(int));
    if (W.n_near > 0)
      memcpy(*out + total + W.n_take, W.near, (size_t)W.n_near * sizeof(int));
    total += W.n_take + W.n_near;
    len[i] = total - first[i];
  }
  free(W.take); free(W.take_d); free(W.take_e); free(W.R.v); free(W.R.arc);
  free(W.work); free(W.cut); free(W.near);
  return st;
}

/* The candidate lists from the walks' out-lists: each pair i -> j put in
** both lists, then each list sorted and each pair kept once. */
static int symmetric_lists(afv_geom *g, int n, const int *out,
                           const int *first, const int *len)
{
  int *at = malloc((size_t)(n + 1) * sizeof(int)), i, c, w = 0;
  if (!at) return AFV_ENOMEM;
  memset(g->cand_start, 0, (size_t)(n + 1) * sizeof(int));
  for (i = 0; i < n; i++) {
    g->cand_start[i + 1] += len[i];
    for (c = first[i]; c < first[i] + len[i]; c++)
      g->cand_start[out[c] + 1]++;
  }
  for (i = 0; i < n; i++) g->cand_start[i + 1] += g->cand_start[i];
  if (afv_grow((void **)&g->cand, &g->cap_cand, g->cand_start[n] + 1,
               sizeof(int))) {
    free(at);
    return AFV_ENOMEM;
  }
  for (i = 0; i < n; i++) at[i] = g->cand_start[i];
  for (i = 0; i < n; i++)
    for (c = first[i]; c < first[i] + len[i]; c++) {
      g->cand[at[i]++] = out[c];
      g->cand[at[out[c]]++] = i;
    }
  for (i = 0; i < n; i++) {           /* compact: each pair once */
    int s0 = g->cand_start[i], m = g->cand_start[i + 1] - s0;
    g->cand_start[i] = w;
    sort_ints(g->cand + s0, m);
    for (c = 0; c < m; c++)
      if (c == 0 || g->cand[s0 + c] != g->cand[s0 + c - 1])
        g->cand[w++] = g->cand[s0 + c];
  }
  g->cand_start[n] = w;
  free(at);
  return AFV_OK;
}

/* The dense search: every cell's walk (the centres that cut it), then the
** lists made symmetric.  G is replaced by the fine grid
** (about one cell a bin), whose bins stay in g for afv_cells_around. */
static int dense_candidates(afv_geom *g, int n, const double *r, double l,
                            const afv_box *b, grid *G)
{
  int *out = NULL, *first, *len, cap_out = 0, st;
  double half;
  if (b && b->periodic) {
    half = 0.5 * sqrt(b->Lx * b->Ly / n);
  } else {      /* open: bins of the centres' bounding box, about n of
                ** them (n along a line of centres) */
    double sx, sy;
    grid_span(n, r, &sx, &sy);
    half = 0.5 * fmax(sqrt(sx / n * sy), fmax(sx, sy) / n);
  }
  if (!(half > 0) || !isfinite(half) || half > l) half = l;
  if (b && b->periodic) grid_periodic(G, b, half, n);
  else grid_open(G, n, r, half);
  if ((st = fill_bins(g, G, n, r)) != AFV_OK) return st;
  first = malloc((size_t)(2 * n + 2) * sizeof(int));
  if (!first) return AFV_ENOMEM;
  len = first + n + 1;
  st = walk_all(g, G, n, l, near_limit2(b), &out, &cap_out, first, len);
  if (st == AFV_OK) st = symmetric_lists(g, n, out, first, len);
  free(first);
  free(out);
  return st;
}

/* After a rebuild: every cell anchored at its place in the bins, its list
** with no room beyond it; the spare room and the nodes (MOVERS) unused. */
static int reset_anchors(afv_geom *g, const grid *G, int n)
{
  int nb = G->nbx * G->nby, i, c = g->cap_nodes;
  if (afv_grow((void **)&g->node_head, &g->cap_heads, nb + 1, sizeof(int)))
    return AFV_ENOMEM;
  if (afv_grow((void **)&g->node_next, &c, NODES_MAX(n), sizeof(int)))
    return AFV_ENOMEM;
  c = g->cap_nodes;
  if (afv_grow((void **)&g->node_cell, &c, NODES_MAX(n), sizeof(int)))
    return AFV_ENOMEM;
  c = g->cap_nodes;
  if (afv_grow((void **)&g->node_xy, &c, NODES_MAX(n), 2 * sizeof(double)))
    return AFV_ENOMEM;
  g->cap_nodes = c;
  for (i = 0; i < nb; i++) g->node_head[i] = -1;
  for (i = 0; i < n; i++) {
    g->anchor_node[i] = -1;
    g->cand_end[i] = g->cand_lim[i] = g->cand_start[i + 1];
  }
  g->n_nodes = 0;
  g->moved_lists = 0;
  g->cand_used = g->cand_start[n];
  return AFV_OK;
}

/* Two passes over the cell list (count, then fill) let every cell write its
** list in place, in parallel, at the cost of scanning the bins twice.
** Where some cell has more than DENSE_CANDIDATES, the counts are dropped
** and the dense search (dense_candidates) lists the candidates instead. */
static int build_candidates(afv_geom *g, int n, const double *r, double l,
                            const afv_box *b)
{
  double range = (2 + SKIN) * l;
  grid G;
  int i, st, most = 0, probed;
  g->cand_n = 0;
  if (b && b->periodic) grid_periodic(&G, b, 0.5 * range, n);
  else grid_open(&G, n, r, 0.5 * range);
  if ((st = fill_bins(g, &G, n, r)) != AFV_OK) return st;
  g->cand_start[0] = 0;
  probed = dense_probe(g, &G, range);
  if (!probed) {
    scan_all(g, &G, range, 0);
    for (i = 0; i < n; i++) {
      if (g->cand_start[i + 1] > most) most = g->cand_start[i + 1];
      g->cand_start[i + 1] += g->cand_start[i];
    }
  }
  g->cand_dense = probed || most > DENSE_CANDIDATES;
  if (g->cand_dense) {
    if ((st = dense_candidates(g, n, r, l, b, &G)) != AFV_OK) return st;
    g->cand_top = g->cand_start[n];       /* no re-anchoring (DENSE) */
  } else {
    g->cand_top = g->cand_start[n] + SPARE_ROOM(g->cand_start[n]);
    if (afv_grow((void **)&g->cand, &g->cap_cand, g->cand_top + 1,
                 sizeof(int)))
      return AFV_ENOMEM;
    scan_all(g, &G, range, 1);
  }
  if ((st = reset_anchors(g, &G, n)) != AFV_OK) return st;
  g->cand_grid = G;
  memcpy(g->cand_r0, r, (size_t)(2 * n) * sizeof(double));
  g->cand_box.periodic = b && b->periodic;
  g->cand_box.Lx = g->cand_box.periodic ? b->Lx : 0;
  g->cand_box.Ly = g->cand_box.periodic ? b->Ly : 0;
  g->cand_l = l;
  g->cand_n = n;
  g->cand_checks = 0;
  g->cand_moved = 0;
  g->n_rebuilds++;
  return AFV_OK;
}

/* ---- neighbour lists --------------------------------------------------- */

/* e, the binary exponent of the larger of |x|, |y| (0 for a zero
** vector): ldexp(x, -e), ldexp(y, -e) is the vector scaled exactly by a
** power of 2 to a length in [0.5, 1.5). */
static int unit_exponent(double x, double y)
{
  int e = 0;
  frexp(fmax(fabs(x), fabs(y)), &e);
  return e;
}

/* a x b where a x b computed as is came out 0: two displacements whose
** products underflow (below ~1e-154 l, or one tiny and the other not
** large enough) would sort two distinct directions as one.  Each vector
** scaled by a power of 2 to length ~1 keeps the sign, and scaling is
** exact, so where nothing underflowed this is a x b times a power of 2,
** 0 again; and b x a = -(a x b) exactly, as before. */
static double tiny_cross(double ax, double ay, double bx, double by)
{
  int ka = unit_exponent(ax, ay), kb = unit_exponent(bx, by);
  return ldexp(ax, -ka) * ldexp(by, -kb) - ldexp(ay, -ka) * ldexp(bx, -kb);
}

/* comes_after for two displacements in one direction as far as a x b
** computed as is can tell (rare): tiny_cross, then distance, then cell. */
static COLD int comes_after_tied(double ax, double ay, int ja, double bx,
                                 double by, int jb)
{
  double cross = tiny_cross(ax, ay, bx, by);
  if (cross != 0) return cross < 0;
  if (ax * ax + ay * ay != bx * bx + by * by)
    return ax * ax + ay * ay > bx * bx + by * by;
  return ja > jb;
}

/* 1 if neighbour ja at displacement (ax, ay) comes after jb at (bx, by) in
** a cell's list: by the direction of the displacement (counter-clockwise
** from +x; compared by half-plane, then by the sign of the cross product,
** so without atan2), then by distance, then by cell.  A total order: the
** sorted list does not depend on the order the candidates come in.
** (inline: it is called about once per slot and step, and the call cost
** more than the comparison.) */
static inline int comes_after(double ax, double ay, int ja, double bx,
                              double by, int jb)
{
  double cross;
  int ha = lower_half(ax, ay), hb = lower_half(bx, by);
  if (ha != hb) return ha > hb;
  cross = ax * by - ay * bx;
  if (cross != 0) return cross < 0;
  return comes_after_tied(ax, ay, ja, bx, by, jb);
}

static int slot_after(const int *nbr, const double *d, int a, int b)
{
  return comes_after(d[2*a], d[2*a+1], nbr[a], d[2*b], d[2*b+1], nbr[b]);
}

int afv_slots_sorted(const afv_geom *g, int i)
{
  int s;
  for (s = g->nbr_start[i]; s + 1 < g->nbr_end[i]; s++)
    if (slot_after(g->nbr, g->nbr_d, s, s + 1)) return 0;
  return 1;
}

/* Insertion sort of a cell's m slots by direction (lists hold ~6).  The
** order is the counter-clockwise order of the edges (clip_chords relies on
** it) and fixes the order in which each chord meets its bounds, which
** decides, where four or more centres are cocircular, which of the
** coincident vertices survive: an order set by the geometry alone treats
** every cell of a lattice alike, so the forces there cancel as they
** should.  The candidates come nearly sorted (sort_candidates), so this
** is about one comparison per slot. */
static void sort_slots(int *nbr, double *d, int m)
{
  int k, q;
  for (k = 1; k < m; k++)
    for (q = k; q > 0 && slot_after(nbr, d, q - 1, q); q--) {
      int tj = nbr[q];
      double tx = d[2*q], ty = d[2*q+1];
      nbr[q] = nbr[q - 1];
      d[2*q] = d[2*q - 2];
      d[2*q+1] = d[2*q - 1];
      nbr[q - 1] = tj;
      d[2*q - 2] = tx;
      d[2*q - 1] = ty;
    }
}

/* Right after a rebuild, sorts each cell's candidates by comes_after (their
** directions now).  Cells turn little about each other between rebuilds,
** so the lists filter_cell takes from them are then nearly sorted, and its
** insertion sort does about one comparison per slot instead of k^2/4.
** This only saves time: filter_cell sorts anyway, into a total order, so
** the lists are the same whatever order the candidates are in. */
/* A candidate with its displacement, for merge_sort_cell. */
typedef struct cand_key {
  double x, y;
  int j;
} cand_key;

/* Sorts the m candidates c[] of cell i by comes_after in O(m log m)
** (bottom-up merge sort, stable): for long lists (dense input, where m
** is in the hundreds and the insertion sort took m^2/4 steps).  Returns
** 0 if out of memory (the caller then sorts by insertion). */
static int merge_sort_cell(const afv_geom *g, int i, const afv_box *b, int *c,
                           int m)
{
  cand_key *A = malloc((size_t)m * 2 * sizeof *A), *B, *T;
  int w, k;
  if (!A) return 0;
  B = A + m;
  for (k = 0; k < m; k++) {
    A[k].j = c[k];
    displacement(g, i, c[k], b, &A[k].x, &A[k].y);
  }
  for (w = 1; w < m; w *= 2) {
    for (k = 0; k < m; k += 2 * w) {
      int p = k, q = k + w < m ? k + w : m, pe = q, qe = k + 2 * w < m
                                                   ? k + 2 * w : m, o = k;
      while (p < pe && q < qe)
        B[o++] = comes_after(A[p].x, A[p].y, A[p].j, A[q].x, A[q].y, A[q].j)
                 ? A[q++] : A[p++];
      while (p < pe) B[o++] = A[p++];
      while (q < qe) B[o++] = A[q++];
    }
    T = A; A = B; B = T;
  }
  for (k = 0; k < m; k++) c[k] = A[k].j;
  free(A < B ? A : B);
  return 1;
}

/* Lists longer than this are merge-sorted (merge_sort_cell); at the
** paper's densities a cell has about 6 to 12 candidates. */
#define LONG_LIST 32

static void sort_candidates(afv_geom *g, int n, const afv_box *b)
{
  int i;
  AFV_PARALLEL_FOR(n)
  for (i = 0; i < n; i++) {
    int *c = g->cand + g->cand_start[i], m = g->cand_end[i]
             - g->cand_start[i], k, q;
    if (m > LONG_LIST && merge_sort_cell(g, i, b, c, m)) continue;
    for (k = 1; k < m; k++) {
      int j = c[k];
      double jx, jy, px, py;
      displacement(g, i, j, b, &jx, &jy);
      for (q = k; q > 0; q--) {
        displacement(g, i, c[q - 1], b, &px, &py);
        if (!comes_after(px, py, c[q - 1], jx, jy, j)) break;
        c[q] = c[q - 1];
      }
      c[q] = j;
    }
  }
}

/* NEAR.  Wrapping rounds a centre to a multiple of eps L, so the
** displacement of two wrapped centres is off by up to ~eps L: nothing next
** to a distance of l, everything next to one of 1e-16 l.  Below
** AFV_NEAR_IMAGE max(Lx, Ly) (afv_internal.h) it is taken from the
** unwrapped centres instead (exact_image).  Never reached in a tissue
** (cells there are 1e-5 l apart at the very least).
** near_limit2: below this d^2 a displacement is taken from the unwrapped
** centres (periodic box); in open space, below the smallest normal
** double, where d^2 may be 0 for centres that differ. */
static double near_limit2(const afv_box *b)
{
  double L;
  if (!b || !b->periodic) return DBL_MIN;
  L = b->Lx > b->Ly ? b->Lx : b->Ly;
  return AFV_NEAR_IMAGE * AFV_NEAR_IMAGE * L * L;
}

/* The minimum image of r_j - r_i from the unwrapped centres, for each
** component whose unwrapped difference is already its minimum image (the
** subtraction of two nearby doubles is exact); the other components keep
** (*dx, *dy), from the wrapped centres.  Odd under i <-> j, as fold is:
** the lists stay symmetric.  In open space the wrapped centres are the
** centres, and (*dx, *dy) is kept. */
static void exact_image(const double *r, int i, int j, const afv_box *b,
                        double *dx, double *dy)
{
  double ex = r[2*j] - r[2*i], ey = r[2*j+1] - r[2*i+1];
  if (!b || !b->periodic) return;
  if (fabs(ex) < 0.5 * b->Lx) *dx = ex;
  if (fabs(ey) < 0.5 * b->Ly) *dy = ey;
}

/* The neighbours of cell i (count of them in nbr, their displacements in
** nbr_d) closer than sqrt(near2) get their displacement from exact_image;
** returns the first whose displacement is then exactly 0 (the same
** centre), or -1.  (A pass of its own after filter_cell's loop: inline in
** the loop, gcc computed exact_image for every candidate, branch-free;
** and COLD.) */
static COLD int exact_near(const double *r, int i, const afv_box *b,
                           double near2, const int *nbr, double *nbr_d,
                           int count)
{
  int k;
  for (k = 0; k < count; k++) {
    double *D = nbr_d + 2 * k;
    if (D[0] * D[0] + D[1] * D[1] >= near2) continue;
    exact_image(r, i, nbr[k], b, &D[0], &D[1]);
    if (D[0] == 0 && D[1] == 0) return k;
  }
  return -1;
}

/* The candidates of cell i closer than 2l, written to nbr[] with their
** displacements D = r_j - r_i to nbr_d[] and sorted by sort_slots; returns
** their number, or -1 - j if cell j has the same centre (the exact
** displacement is 0: only then).  Minimum image by fold: the wrapped
** centres differ by less than a box side.  (The box and
** the list end are read into locals: the stores to nbr_d could alias them,
** which would force a reload per candidate.) */
static int filter_cell(const afv_geom *g, int i, const double *r, double l,
                       const afv_box *b, int *nbr, double *nbr_d)
{
  double xi = g->rw[2*i], yi = g->rw[2*i+1], range2 = 4 * l * l;
  int periodic = b && b->periodic, count = 0, c, end = g->cand_end[i];
  double Lx = periodic ? b->Lx : 0, Ly = periodic ? b->Ly : 0;
  double near2 = near_limit2(b);
  int near = 0;
  for (c = g->cand_start[i]; c < end; c++) {
    int j = g->cand[c];
    double dx = g->rw[2*j] - xi, dy = g->rw[2*j+1] - yi, d2;
    if (periodic) {
      dx = fold(dx, Lx);
      dy = fold(dy, Ly);
    }
    d2 = dx * dx + dy * dy;
    if (d2 >= range2) continue;
    near |= d2 < near2;             /* nearly coincident centres */
    nbr[count] = j;
    nbr_d[2*count] = dx;
    nbr_d[2*count+1] = dy;
    count++;
  }
  if (near) {                       /* rare: see NEAR */
    int k = exact_near(r, i, b, near2, nbr, nbr_d, count);
    if (k >= 0) return -1 - nbr[k];
  }
  sort_slots(nbr, nbr_d, count);
  return count;
}

/* |(dx, dy)| where dx^2 + dy^2 underflows (below ~1e-154 l): computed on
** the vector scaled by a power of 2 (exact), then scaled back. */
static COLD double tiny_length(double dx, double dy)
{
  int e = unit_exponent(dx, dy);
  double x = ldexp(dx, -e), y = ldexp(dy, -e);
  return ldexp(sqrt(x * x + y * y), e);
}

/* The edge cache of a displacement D = (dx, dy) of a pair closer than 2l
** (4 doubles: u = D/d, h = d/2, sc = sqrt(l^2 - h^2)). */
static inline void edge_entry(double dx, double dy, double l, double *e)
{
  double d2 = dx * dx + dy * dy, d, h;
  if (d2 >= DBL_MIN) {
    d = sqrt(d2);
    h = 0.5 * d;
  } else {                          /* rare: d below ~1e-154 l */
    d = tiny_length(dx, dy);
    h = 0.5 * d > 0 ? 0.5 * d : d;  /* h > 0 for the smallest subnormal d
                                    ** too: keeps b / 2h finite (afv.c) */
  }
  assert(h > 0 && h <= l);          /* a pair apart and closer than 2l */
  e[0] = dx / d;
  e[1] = dy / d;
  e[2] = h;                         /* h, not d: clip_chords' inner loop
                                    ** needs h; d = 2h is exact */
  e[3] = sqrt((l - h) * (l + h));   /* (l-h)(l+h) is exact where l*l - h*h
                                    ** would cancel for h near l */
}

/* The edge cache of slot s (g->edge, 4 doubles per slot: u = D/d, h = d/2,
** sc = sqrt(l^2 - h^2)) and of its reverse slot t, from the displacement
** D of s: the clipping, the boundary assembly and the forces (afv.c) all
** need these.  D_t = -D_s exactly (fold is odd), so d, h and sc are the
** same bits from both cells and u_t = -u_s exactly: one computation (two
** square roots, two divisions) serves the pair. */
static inline void fill_edge_pair(afv_geom *g, int s, int t, double l)
{
  double *e = g->edge + 4 * s, *f = g->edge + 4 * t;
  edge_entry(g->nbr_d[2*s], g->nbr_d[2*s+1], l, e);
  f[0] = -e[0];
  f[1] = -e[1];
  f[2] = e[2];
  f[3] = e[3];
}

/* The slot of cell i in the list of j, where i sits at displacement
** (x, y) from j: in a long list (more than LONG_LIST slots) a binary
** search by comes_after (the list is sorted by it); else, or if that
** misses, a scan. */
static int reverse_slot(const afv_geom *g, int i, int j, double x, double y)
{
  int lo = g->nbr_start[j], hi = g->nbr_end[j], t;
  if (hi - lo > LONG_LIST) {
    while (lo < hi) {
      int mid = lo + (hi - lo) / 2;
      if (comes_after(x, y, i, g->nbr_d[2*mid], g->nbr_d[2*mid+1],
                      g->nbr[mid]))
        lo = mid + 1;
      else
        hi = mid;
    }
    if (lo < g->nbr_end[j] && g->nbr[lo] == i) return lo;
  }
  for (t = g->nbr_start[j]; t < g->nbr_end[j]; t++)
    if (g->nbr[t] == i) return t;
  return -1;                        /* never: the lists are symmetric */
}

/* Links slot s (of i) and t (of j), its reverse. */
static void link_pair(afv_geom *g, int s, int t, double l)
{
  g->nbr_rev[s] = t;
  g->nbr_rev[t] = s;
  fill_edge_pair(g, t, s, l);
  g->grad[2*s] = g->grad[2*s+1] = 0;
  g->grad[2*t] = g->grad[2*t+1] = 0;
}

/* link_cell for a cell with a long list (dense input): each reverse slot
** found in O(log k), not by a scan. */
static COLD void link_long_cell(afv_geom *g, int i, double l)
{
  int s, t;
  for (s = g->nbr_start[i]; s < g->nbr_end[i]; s++) {
    int j = g->nbr[s];
    if (j > i) continue;
    t = reverse_slot(g, i, j, -g->nbr_d[2*s], -g->nbr_d[2*s+1]);
    assert(t >= 0);                 /* the lists are symmetric */
    if (t >= 0) link_pair(g, s, t, l);
  }
}

/* The pairs of cell i with its smaller neighbours j < i: for the slot s of
** j in the list of i, nbr_rev[s] = t, the slot of i in the list of j, and
** nbr_rev[t] = s; the edge cache of both slots (fill_edge_pair); and zero
** in both gradient slots, where afv_cell_shape_gradient adds.  The lists
** are exactly symmetric (fold is odd, so d^2 has the same bits both ways),
** so the reverse slot exists.  Each pair is linked once, from its larger
** cell, which writes both directions: every entry has exactly one writer.
** j's list must be filtered already. */
static void link_cell(afv_geom *g, int i, double l)
{
  int s, t;
  if (g->nbr_end[i] - g->nbr_start[i] > LONG_LIST) {
    link_long_cell(g, i, l);
    return;
  }
  for (s = g->nbr_start[i]; s < g->nbr_end[i]; s++) {
    int j = g->nbr[s];
    if (j > i) continue;
    for (t = g->nbr_start[j]; t < g->nbr_end[j]; t++)
      if (g->nbr[t] == i) {
        g->nbr_rev[s] = t;
        g->nbr_rev[t] = s;
        fill_edge_pair(g, t, s, l);
        g->grad[2*s] = g->grad[2*s+1] = 0;
        g->grad[2*t] = g->grad[2*t+1] = 0;
        break;
      }
    assert(t < g->nbr_end[j]);      /* the lists are symmetric */
  }
}

/* Cell i's list, written in place at its candidate offset, nbr_start[i] =
** cand_start[i] (room for every candidate), up to nbr_end[i]; the slots
** between nbr_end[i] and nbr_start[i+1] are unused: no compaction to pay
** for.  Returns 0, or -1 - j if cell j has the same centre as i. */
static int list_cell(afv_geom *g, int i, const double *r, double l,
                     const afv_box *b)
{
  int c = g->cand_start[i];
  int count = filter_cell(g, i, r, l, b, g->nbr + c, g->nbr_d + 2 * c);
  g->nbr_start[i] = c;
  g->nbr_end[i] = count < 0 ? count : c + count;
  return count < 0 ? count : 0;
}

/* The pieces placed after a rebuild (place_pieces: at 2 cand_start[i] + i,
** the lists being packed), with room for 2 cand_top + n: the rooms of the
** lists, moved or not, never sum to more than cand_top. */
static int reserve_pieces(afv_geom *g, int n)
{
  place_pieces(g, n);
  return afv_grow((void **)&g->pieces, &g->cap_pieces, 2 * g->cand_top + n + 1,
                  sizeof(afv_piece));
}

/* The exact lists from the candidates, then the pairs linked.  Serially,
** one pass: cell i is linked right after it is listed, to its smaller
** neighbours, listed moments before, whose slots are still in cache (in a
** large tissue a second pass finds them evicted).  With OpenMP, a smaller
** neighbour may belong to another thread, so every list is filtered
** before any is linked.  Either way each entry gets the same bits. */
int afv_neighbours(afv_geom *g, int n, const double *r, double l,
                   const afv_box *b)
{
  int i, st;
  if (grow_cells(g, n)) return AFV_ENOMEM;
  g->n = n;
  g->nbr_start[0] = g->piece_start[0] = 0;
  if (n == 0) return AFV_OK;
  wrap_all(g, n, r, b);
  if (!candidates_valid(g, n, r, l, b)) {
    if ((st = build_candidates(g, n, r, l, b)) != AFV_OK) return st;
    if (grow_nbr(g, g->cand_top + 1) || reserve_pieces(g, n)) {
      g->cand_n = 0;                /* no space: rebuild at the next call */
      return AFV_ENOMEM;
    }
    sort_candidates(g, n, b);
  }
  g->nbr_start[n] = g->cand_start[n];
#ifdef _OPENMP
  {
    int first = n;                  /* the first cell with a coincidence */
    AFV_PARALLEL_REDUCE(n, reduction(min: first))
    for (i = 0; i < n; i++)
      if (list_cell(g, i, r, l, b) < 0 && i < first) first = i;
    if (first < n) return find_coincident(g, g->nbr_end, first + 1);
  }
  AFV_PARALLEL_FOR(n)
  for (i = 0; i < n; i++) link_cell(g, i, l);
#else
  for (i = 0; i < n; i++) {
    if (list_cell(g, i, r, l, b) < 0)   /* the first such cell: as after */
      return find_coincident(g, g->nbr_end, i + 1);   /* a whole pass */
    link_cell(g, i, l);
  }
#endif
  return AFV_OK;
}

int afv_spatial_order(int n, const double *r, double l, const afv_box *b,
                      int *perm)
{
  afv_geom tmp;
  grid G;
  int st;
  if (n <= 0) return AFV_OK;
  memset(&tmp, 0, sizeof tmp);
  if (b && b->periodic) grid_periodic(&G, b, l, n);
  else grid_open(&G, n, r, l);
  st = grow_cells(&tmp, n);
  if (st == AFV_OK) st = fill_bins(&tmp, &G, n, r);
  if (st == AFV_OK) memcpy(perm, tmp.bin_cell, (size_t)n * sizeof(int));
  afv_geom_free(&tmp);
  return st;
}

int afv_spatial_renumber(int n, double *r, double l, const afv_box *b)
{
  int *perm = malloc((size_t)(n + 1) * sizeof(int)), i;
  double *q = malloc((size_t)(2 * n + 1) * sizeof(double));
  int st = perm && q ? afv_spatial_order(n, r, l, b, perm) : AFV_ENOMEM;
  if (st == AFV_OK) {
    for (i = 0; i < n; i++) {
      q[2*i] = r[2 * perm[i]];
      q[2*i+1] = r[2 * perm[i] + 1];
    }
    memcpy(r, q, (size_t)(2 * n) * sizeof(double));
  }
  free(perm);
  free(q);
  return st;
}
