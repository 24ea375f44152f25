/*
** geom.c -- the exact shape of every finite-Voronoi cell: the clipping.
**
** The cell (paper, Model section: the Voronoi cell of r_i within the circle
** of radius l about it).  Invariant: after afv_geometry, cell i's boundary
** (pieces) is the boundary of
**     disk(r_i, l)  intersected with  { x : |x - r_i| <= |x - r_j| }  for all j,
** written as a counter-clockwise cycle of straight edges and circular arcs.
** Only centres closer than 2l can cut the disk (the bisector of a pair at
** distance d lies d/2 from r_i, and d/2 >= l misses the open disk): the
** neighbour lists hold exactly those, sorted by direction, with the edge
** cache of every pair (u = D/d, h = d/2, half-chord sqrt(l^2 - h^2)):
** neighbours.c finds them; this file starts from them.
**
** Invariants (asserted by afv_cell_shape in a build without -DNDEBUG):
** it relies on the lists being sorted by direction (neighbours.c), and a
** shape lies in the disk and is convex:  0 <= A_i <= pi l^2,
** 0 <= L_i <= P_i <= 2 pi l  (to AFV_SUM_ROUNDING), at most one edge per
** neighbour.
**
** Algorithm, per cell, in coordinates centred on r_i (afv_cell_shape):
**   1. Every neighbour j's bisector line x.u = d/2 (u = (r_j - r_i)/d)
**      cuts the disk in a chord (d < 2l).  The cell is the disk cut by the
**      half-planes x.u <= d/2, so its straight edges are exactly the parts
**      of these chords that lie in every other half-plane.
**   2. Clip each chord, as an interval of its line, by every other
**      half-plane (clip_chords): an end cut by another line is a triple
**      junction, an end left at the chord's end lies on the circle.
**   3. The kept parts, in the order of their directions u (the slots are
**      sorted so), are the edges in counter-clockwise boundary order; an
**      edge ending on the circle is joined to the next by an arc
**      (assemble_boundary: area, perimeter, arc length).
** (An earlier version clipped a square polygon by each half-plane
** (Sutherland-Hodgman) and then by the disk: the same boundary, but it
** copied every polygon vertex for every neighbour.  That polygon clipping
** is now the brute-force twin of the tests, test/test_reference.c.)
** Cost: O(k^2) per cell for k neighbours (k is about 6 in a tissue), so
** O(N) for the tissue.  Dense input (k > PRUNE_FROM = 16): the nearest
** neighbours only, as Voro++ (see "pruning"), O(k log k) per cell, the
** same bits (what it saves: doc/performance.md).
** The dense search (neighbours.c, DENSE) asks this file which centres
** can still cut a cell (afv_reach_of, afv_reach_cuts): the cell it has cut
** so far is shaped by the same clipping, so every shape has one clipper.
** afv_geometry_prepare is here, not in neighbours.c: after the lists it
** reserves the clipping's work space, sized by this file's segment type.
** Different cells may be shaped on OpenMP threads at once, with the same
** result bits (afv_internal.h).
*/
#include "afv.h"
#include "afv_internal.h"
#include "fastmath.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- one cell's shape --------------------------------------------------- */
/* The line of neighbour slot s, in the cell's frame: x.u = h, with
** u = D/d the unit vector to the neighbour, h = d/2, and t = (-u_y, u_x)
** the counter-clockwise direction along it; sc = sqrt(l^2 - h^2) is half
** the chord it cuts from the disk. */
typedef struct bisector {
  double ux, uy, h, d, sc;
} bisector;

/* The line of slot s, from the edge cache (link_cell). */
static bisector bisector_of(const afv_geom *g, int s)
{
  const double *e = g->edge + 4 * s;
  bisector B;
  B.ux = e[0];
  B.uy = e[1];
  B.d = 2 * e[2];
  B.h = e[2];
  B.sc = e[3];
  return B;
}

/* One kept part of a bisector line: from tau0 to tau1 along it, in the
** direction t; `*_on_circle` says whether the end is an arc end (else it is
** a triple junction, where the line of another neighbour cuts it). */
typedef struct segment {
  int slot;
  double tau0, tau1;
  int start_on_circle, end_on_circle;
} segment;

/* Step 2: the part of each slot's chord (tau in [-sc, sc]) in the
** half-plane x.u_q <= h_q of every other slot q.  On the line of slot s,
** x = h_s u_s + tau t_s, so that half-plane is  tau c <= rhs  with
** c = t_s.u_q and rhs = h_q - h_s u_s.u_q: an upper bound on tau if c > 0,
** a lower bound if c < 0; a parallel line (c = 0) keeps the whole line or
** none of it.  (Where the polygon clipping this replaces copied every
** vertex for every neighbour, this is a few multiplications per pair.) */

/* tau <= rhs / c (c > 0): compared as rhs < tau1 c, so that the division
** is done only for a new tightest bound.  The interval only shrinks: once
** empty (tau0 >= tau1) it stays empty. */
static void bound_above(segment *S, double rhs, double c)
{
  if (rhs < S->tau1 * c) {
    S->tau1 = rhs / c;
    S->end_on_circle = 0;
  }
}

/* tau >= rhs / c (c < 0): compared as rhs < tau0 c. */
static void bound_below(segment *S, double rhs, double c)
{
  if (rhs < S->tau0 * c) {
    S->tau0 = rhs / c;
    S->start_on_circle = 0;
  }
}

/* Empties a segment for good: bounds only shrink it, and tau0 - tau1 = 2
** is far from the rounding of a sliver (keep_parts). */
static void drop(segment *S)
{
  S->tau0 = 1;
  S->tau1 = -1;
}

/* A half-plane bound tau c <= rhs on a segment: above, below, or for
** c = 0 (parallel lines) all or nothing. */
static void bound(segment *S, double rhs, double c)
{
  if (c > 0) bound_above(S, rhs, c);
  else if (c < 0) bound_below(S, rhs, c);
  else if (rhs < 0) drop(S);             /* a line behind the other */
}

/* The pair's bounds for nearly parallel lines a and b (slots a < b),
** |t_a.u_b| below AFV_NEAR_PARALLEL and u_a.u_b > 0 (lines on opposite sides
** of the centre meet far outside the disk, and the plain bounds serve).
** There h_b - h_a u_a.u_b and t_a.u_b are both small and lose their
** digits: two nearly coincident neighbours seen from afar gave each line
** its own junction, wrong by eps l / d, and areas above pi l^2.
** Multiplied by d_b, the bound on line a is  tau (t_a.e) <= e.D_b / 2
** with e = D_b - D_a (exact where the two are close, the only case where
** the junction falls in the disk), and the bound on line b is
** tau (-t_b.e) <= -e.D_a / 2: both accurate, one junction seen alike
** from both lines.  The boundary then runs from a to b, so b must turn
** counter-clockwise from a (sort_slots' order; cyclically, for a pair
** across the +x axis, where the list wraps: clockwise).  Where the sort's
** cross product has lost that sign to rounding (directions within
** ~1e-16), or the lines are exactly parallel (e along u), the pair is
** taken as parallel: the nearer line kept, the other dropped (one line
** twice, e = 0, kept once).  The shape is then off by about d l.  So are
** two neighbours in nearly one direction but not close to each other
** (|e| >= AFV_NEAR_PARALLEL_GAP |D_a|): their lines meet 1e6 l away or more,
** and the nearer line hides the other (the e-form's signs were noise
** there: a fuzzer case, test_geometry.c). */
static void clip_near_parallel(const double *Da, const double *Db,
                               const double *ea, const double *eb,
                               segment *Sa, segment *Sb)
{
  double ex = Db[0] - Da[0], ey = Db[1] - Da[1];
  double ra = 0.5 * (ex * Db[0] + ey * Db[1]);
  double rb = -0.5 * (ex * Da[0] + ey * Da[1]);
  double ca = ea[0] * ey - ea[1] * ex, cb = eb[1] * ex - eb[0] * ey;
  int ccw = lower_half(Da[0], Da[1]) == lower_half(Db[0], Db[1])
            || Da[0] < 0;               /* b should turn ccw from a */
  int close = fmax(fabs(ex), fabs(ey))
              < AFV_NEAR_PARALLEL_GAP * fmax(fabs(Da[0]), fabs(Da[1]));
  if (close && (ccw ? (ca > 0 && cb < 0) : (ca < 0 && cb > 0))) {
    bound(Sa, ra, ca);
    bound(Sb, rb, cb);
  } else if (ra < 0) {                  /* b nearer (or alike, below) */
    drop(Sa);
  } else {
    drop(Sb);
  }
}

/* Clips the chords of nn slots (edge cache `edge`, displacements D; slot
** numbers from s0 on), one pass over the pairs
** a < b: c and u_a.u_b serve both (t_b.u_a = -t_a.u_b exactly, as the
** products commute), and each slot still meets its bounds in increasing
** slot order.  A pair of nearly parallel lines on one side of the centre
** (clip_near_parallel) is handled only if `careful`; else the pass stops
** there and returns 1, and the caller runs it again with care: the common
** pass then carries no code for the rare case (which, inline, cost the
** common case instructions). */
static inline int clip_pairs(const double *edge, const double *D, int s0,
                             int nn, segment *seg, int careful)
{
  int a, b;
  for (a = 0; a < nn; a++) {
    seg[a].slot = s0 + a;
    seg[a].tau0 = -edge[4*a+3];
    seg[a].tau1 = edge[4*a+3];
    seg[a].start_on_circle = seg[a].end_on_circle = 1;
  }
  for (a = 0; a < nn; a++) {
    /* slot a's line in locals: stores to seg[] could alias edge[] for all
    ** the compiler knows, and would force a reload for every pair */
    const double uax = edge[4*a], uay = edge[4*a+1], ha = edge[4*a+2];
    for (b = a + 1; b < nn; b++) {
      const double *eb = edge + 4 * b;
      double c = uax * eb[1] - uay * eb[0];             /* t_a.u_b */
      double cu = uax * eb[0] + uay * eb[1];            /* u_a.u_b */
      double ra = eb[2] - ha * cu, rb = ha - eb[2] * cu;
      if (c > AFV_NEAR_PARALLEL) {
        bound_above(&seg[a], ra, c);
        bound_below(&seg[b], rb, -c);
      } else if (c < -AFV_NEAR_PARALLEL) {
        bound_below(&seg[a], ra, c);
        bound_above(&seg[b], rb, -c);
      } else if (cu < 0) {             /* (nearly) opposite lines */
        bound(&seg[a], ra, c);
        bound(&seg[b], rb, -c);
      } else if (!careful) {
        return 1;
      } else {                         /* rare: nearly parallel lines */
        clip_near_parallel(D + 2 * a, D + 2 * b, edge + 4 * a, edge + 4 * b,
                           &seg[a], &seg[b]);
      }
    }
  }
  return 0;
}

/* A part bounded at both ends by other lines may come out of zero or,
** by rounding, negative length where in truth it is a sliver: the edge
** of a line crossing a cell narrower than eps l (between two nearly
** opposite bisectors, three nearly coincident centres in a row).
** Dropped, it left the two nearly opposite edges to meet in a junction
** that cannot exist, with a derivative ~ 1 / (u_a x u_b): forces of
** 1e223 and then inf (a fuzzer case, test_geometry.c).  So such a part
** is kept, of length 0, where the kept parts before and after it are
** nearly opposite; elsewhere (a 4-fold vertex of a lattice) it goes as
** before.  sliver_kept decides for part a, the parts before it already
** compacted into seg[0..ns) and those after it untouched; e gives the
** edge cache of a part (at 4 (slot - slot0)). */
static COLD int sliver_kept(segment *seg, int ns, int a, int nn,
                            const double *e, int slot0)
{
  const segment *p = ns > 0 ? &seg[ns - 1] : NULL, *q = NULL;
  const double *up, *uq;
  int b;
  for (b = a + 1; b < nn && !q; b++)          /* the next kept part */
    if (seg[b].tau0 < seg[b].tau1) q = &seg[b];
  for (b = nn - 1; b > a && !p; b--)          /* none before: the last */
    if (seg[b].tau0 < seg[b].tau1) p = &seg[b];
  if (!q && ns > 0) q = &seg[0];              /* none after: the first */
  if (!p || !q || p == q || p->end_on_circle || q->start_on_circle)
    return 0;                       /* no junction between them */
  up = e + 4 * (p->slot - slot0);
  uq = e + 4 * (q->slot - slot0);
  if (!(up[0] * uq[0] + up[1] * uq[1] < 0
        && fabs(up[0] * uq[1] - up[1] * uq[0]) < AFV_NEAR_PARALLEL))
    return 0;
  seg[a].tau1 = seg[a].tau0;
  return 1;
}

/* Keeps the parts of positive length, in order, at the front of seg[]
** (sc = 0, a line that only touches the circle, and NaN go too), and
** slivers (sliver_kept); returns their number. */
static inline int keep_parts(segment *seg, int nn, const double *e,
                             int slot0)
{
  int a, ns = 0;
  for (a = 0; a < nn; a++) {
    double t0 = seg[a].tau0, t1 = seg[a].tau1;
    if (!(t0 < t1)
        && !(t0 - t1 <= AFV_SLIVER_ROUNDING * (fabs(t0) + fabs(t1))
             && !seg[a].start_on_circle && !seg[a].end_on_circle
             && sliver_kept(seg, ns, a, nn, e, slot0)))
      continue;
    if (ns < a) seg[ns] = seg[a];   /* copies only after a dropped one */
    ns++;
  }
  return ns;
}

/* ---- pruning (dense input) --------------------------------------------- */
/* A cell with more than PRUNE_FROM neighbours is clipped by its nearest
** ones first, as Voro++ does: the cell they leave lies within R of the
** centre (R its farthest vertex, l if an arc remains), and a neighbour
** whose bisector lies farther than R + AFV_PRUNE_MARGIN l cannot cut it: its
** half-plane holds the whole disk of radius R.  So the neighbours are
** taken in order of distance (h = d/2), the cell clipped by those with
** h <= R, R recomputed, until no more come in: about the nearest 16 in
** a dense tissue, whatever its density, so the cost per cell is the sort,
** O(k log k), not k^2 pairs.  Every bound a pruned line would have given
** a kept part is looser than the part's end by the margin, which covers
** rounding, so the kept parts come out in the same bits as without
** pruning.  At the paper's densities cells have fewer neighbours, and the
** plain clipping serves. */
#define PRUNE_FROM   16

/* The work space of a pruned clipping, past nn + 1 segments: the slots in
** order of distance, their ranks, and the edge cache and displacements
** of the slots in use. */
typedef struct prune_work {
  int *order, *rank, *use;
  double *edge, *D;
} prune_work;

/* Sorts the slot offsets 0..nn-1 by h = edge[4a + 2] (merge sort, stable:
** ties by offset), into order[]; tmp has room for nn. */
static void order_by_distance(const double *edge, int nn, int *order,
                              int *tmp)
{
  int w, k, *A = order, *B = tmp, *T;
  for (k = 0; k < nn; k++) order[k] = k;
  for (w = 1; w < nn; w *= 2) {
    for (k = 0; k < nn; k += 2 * w) {
      int p = k, q = k + w < nn ? k + w : nn, pe = q,
          qe = k + 2 * w < nn ? k + 2 * w : nn, o = k;
      while (p < pe && q < qe)
        B[o++] = edge[4 * A[q] + 2] < edge[4 * A[p] + 2] ? A[q++] : A[p++];
      while (p < pe) B[o++] = A[p++];
      while (q < qe) B[o++] = A[q++];
    }
    T = A; A = B; B = T;
  }
  if (A != order) memcpy(order, A, (size_t)nn * sizeof(int));
}

/* The farthest point of the cell that the parts seg[0..ns-1] bound from
** the centre (l if an arc is left, or no part). */
static double farthest_vertex(const double *edge, const segment *seg, int ns,
                              double l)
{
  double R2 = 0;
  int k;
  if (ns == 0) return l;
  for (k = 0; k < ns; k++) {
    double h = edge[4 * k + 2], t0 = seg[k].tau0, t1 = seg[k].tau1;
    if (seg[k].start_on_circle || seg[k].end_on_circle) return l;
    R2 = fmax(R2, h * h + fmax(t0 * t0, t1 * t1));
  }
  return sqrt(R2);
}

/* Clips cell i (nn slots from s0 on) by the m nearest ones, order[0..m),
** in slot order: the parts of positive length to seg[] (slots set),
** returns their number. */
static int clip_nearest(const afv_geom *g, int s0, int nn, int m,
                        const prune_work *w, segment *seg)
{
  const double *edge = g->edge + 4 * s0, *D = g->nbr_d + 2 * s0;
  int a, k = 0, ns, q;
  for (a = 0; a < nn; a++) {
    if (w->rank[a] >= m) continue;
    w->use[k] = a;
    memcpy(w->edge + 4 * k, edge + 4 * a, 4 * sizeof(double));
    memcpy(w->D + 2 * k, D + 2 * a, 2 * sizeof(double));
    k++;
  }
  if (clip_pairs(w->edge, w->D, 0, m, seg, 0))
    clip_pairs(w->edge, w->D, 0, m, seg, 1);
  for (q = 0; q < m; q++) seg[q].slot = q;      /* index into use[] */
  ns = keep_parts(seg, m, w->edge, 0);
  return ns;
}

static int clip_pruned(const afv_geom *g, int i, double l, segment *seg,
                       const prune_work *w)
{
  int s0 = g->nbr_start[i], nn = g->nbr_end[i] - s0, m = PRUNE_FROM, ns, k;
  const double *edge = g->edge + 4 * s0;
  order_by_distance(edge, nn, w->order, w->use);
  for (k = 0; k < nn; k++) w->rank[w->order[k]] = k;
  for (;;) {
    double R;
    int more = m;
    ns = clip_nearest(g, s0, nn, m, w, seg);
    for (k = 0; k < ns; k++) {        /* the edge data of kept parts, */
      int q = seg[k].slot;            /* in place for farthest_vertex */
      if (q != k) memcpy(w->edge + 4 * k, w->edge + 4 * q, 4 * sizeof(double));
    }
    R = farthest_vertex(w->edge, seg, ns, l) + AFV_PRUNE_MARGIN * l;
    while (more < nn && edge[4 * w->order[more] + 2] <= R) more++;
    if (more == m) break;
    m = more;
  }
  for (k = 0; k < ns; k++) seg[k].slot = s0 + w->use[seg[k].slot];
  return ns;
}

/* The part of each slot's chord in every other slot's half-plane
** (clip_pairs; for a cell of many neighbours, of the nearest ones that
** can reach it, clip_pruned), written to seg[] in slot order if of
** positive length (seg must hold one entry per slot); returns their
** number. */
static int clip_chords(const afv_geom *g, int i, double l, segment *seg)
{
  int s0 = g->nbr_start[i], nn = g->nbr_end[i] - s0;
  const double *edge = g->edge + 4 * s0, *D = g->nbr_d + 2 * s0;
  if (nn > PRUNE_FROM) {
    prune_work w;
    w.order = (int *)(seg + nn + 1);
    w.rank = w.order + nn;
    w.use = w.rank + nn;
    w.edge = (double *)(void *)(w.use + nn + (nn & 1)); /* 8-byte aligned */
    w.D = w.edge + 4 * nn;
    return clip_pruned(g, i, l, seg, &w);
  }
  if (clip_pairs(edge, D, s0, nn, seg, 0))
    clip_pairs(edge, D, s0, nn, seg, 1);
  return keep_parts(seg, nn, edge, s0);
}

/* ---- the reach of a cell (the dense search) ---------------------------- */
/* Which centres can still cut a cell, given the centres that cut it so far
** (neighbours.c, DENSE, proposes them in order of distance): the cell they
** leave is shaped by this file's clipping (clip_pairs, keep_parts), and a
** centre at p cuts it iff the cell reaches beyond p's bisector, i.e. its
** support h(p) = max over the cell of x.p exceeds |p|^2 / 2.  The cell's
** boundary is edges and arcs, so h(p) is the largest v.p over its vertices
** v, or l|p| where p's direction lies within an arc.  (Voro++ bounds the
** cell by its farthest vertex R and takes every centre within 2R: on a
** line of centres or a circle of them R stays about l, and every centre
** within 2l passed.) */

/* Cell i cut by the k centres at D (cell frame, sorted by direction as the
** slots are; edge as neighbours.c's edge cache: u, d/2, half-chord):
** its vertices and arcs into *R (arrays of room 2k + 2 points and k + 1
** arcs); seg: work room for k + 1 segments. */
void afv_reach_of(const double *edge, const double *D, int k, double l,
                  void *work, afv_reach *R)
{
  segment *seg = work;
  int ns, q;
  R->nv = R->na = 0;
  R->l = l;
  if (k > 0 && clip_pairs(edge, D, 0, k, seg, 0))
    clip_pairs(edge, D, 0, k, seg, 1);
  ns = k > 0 ? keep_parts(seg, k, edge, 0) : 0;
  if (ns == 0) {                    /* the whole disk */
    R->na = -1;
    return;
  }
  for (q = 0; q < ns; q++) {
    const double *e = edge + 4 * seg[q].slot;
    double *a = R->v + 2 * R->nv;
    a[0] = e[2] * e[0] - seg[q].tau0 * e[1];
    a[1] = e[2] * e[1] + seg[q].tau0 * e[0];
    a[2] = e[2] * e[0] - seg[q].tau1 * e[1];
    a[3] = e[2] * e[1] + seg[q].tau1 * e[0];
    R->nv += 2;
    if (seg[q].end_on_circle) {       /* an arc to the next part's start */
      const segment *nx = &seg[q + 1 < ns ? q + 1 : 0];
      const double *f = edge + 4 * nx->slot;
      double *arc = R->arc + 4 * R->na++;
      arc[0] = a[2];
      arc[1] = a[3];
      arc[2] = f[2] * f[0] - nx->tau0 * f[1];
      arc[3] = f[2] * f[1] + nx->tau0 * f[0];
    }
  }
}

/* 1 if the direction of (x, y) lies within arc k of R (counter-clockwise
** from its start a to its end b), or R is the whole disk: by the signs of
** cross products, no angle.  An arc of a point to itself counts as the
** whole circle (a superset serves both callers). */
static int in_arc(const afv_reach *R, int k, double x, double y)
{
  const double *a = R->arc + 4 * k;
  double ab = a[0] * a[3] - a[1] * a[2];           /* a x b */
  double ap = a[0] * y - a[1] * x, pb = x * a[3] - y * a[2];
  if (R->na < 0) return 1;
  if (ab > 0) return ap >= 0 && pb >= 0;           /* less than a half */
  if (ab < 0) return !(ap < 0 && pb < 0);          /* more than a half */
  if (a[0] * a[2] + a[1] * a[3] < 0) return ap >= 0;   /* a half */
  return 1;
}

/* 1 if a centre at (x, y) cuts the cell of R deeper than AFV_CUT_DEPTH l:
** h(p) - |p|^2 / 2 > AFV_CUT_DEPTH l |p| (a centre on the cell's boundary
** circle, as every centre of a circle is for the others, is not taken:
** its bisector only touches the cell). */
int afv_reach_cuts(const afv_reach *R, double x, double y)
{
  double p2 = x * x + y * y, p = sqrt(p2), h = -HUGE_VAL;
  double need = 0.5 * p2 + AFV_CUT_DEPTH * R->l * p;
  int k;
  for (k = 0; k < R->nv; k++) {
    double s = R->v[2*k] * x + R->v[2*k+1] * y;
    if (s > h) h = s;
  }
  if (h > need) return 1;
  if (!(R->l * p > need)) return 0;  /* nor can an arc */
  for (k = 0; k < (R->na < 0 ? 1 : R->na); k++)
    if (in_arc(R, k, x, y)) return 1;
  return 0;
}

/* The squared distance from (x, y) to the rectangle [x0, x1] x [y0, y1]. */
static double rect_dist2(double x, double y, double x0, double x1, double y0,
                         double y1)
{
  double dx = x < x0 ? x0 - x : x > x1 ? x - x1 : 0;
  double dy = y < y0 ? y0 - y : y > y1 ? y - y1 : 0;
  return dx * dx + dy * dy;
}

/* 1 if the ray from the origin in direction (x, y) meets the rectangle
** (slab test). */
static int ray_meets_rect(double x, double y, const double *q)
{
  double t0 = 0, t1 = HUGE_VAL;
  int a;
  for (a = 0; a < 2; a++) {
    double d = a ? y : x, lo = q[2*a], hi = q[2*a+1];
    if (d == 0) {
      if (lo > 0 || hi < 0) return 0;
    } else {
      double s = lo / d, t = hi / d;
      if (s > t) { double w = s; s = t; t = w; }
      if (s > t0) t0 = s;
      if (t < t1) t1 = t;
    }
  }
  return t0 <= t1;
}

/* 1 if some point of the rectangle q = {x0, x1, y0, y1} (cell frame) may
** cut the cell of R: it comes within |v| of a vertex v (the points that
** cut by a vertex form the disk about v through the centre), or within 2l
** of the centre in the directions of an arc (the points that cut by an
** arc's inner points).  A superset, for the bins of the walk. */
int afv_reach_meets_rect(const afv_reach *R, const double *q)
{
  double l = R->l;
  int k, c;
  if (q[0] <= 0 && q[1] >= 0 && q[2] <= 0 && q[3] >= 0) return 1;
  for (k = 0; k < R->nv; k++) {
    double vx = R->v[2*k], vy = R->v[2*k+1];
    if (rect_dist2(vx, vy, q[0], q[1], q[2], q[3]) < vx * vx + vy * vy)
      return 1;
  }
  if (!(rect_dist2(0, 0, q[0], q[1], q[2], q[3]) < 4 * l * l)) return 0;
  for (k = 0; k < (R->na < 0 ? 1 : R->na); k++) {
    if (R->na < 0) return 1;
    for (c = 0; c < 4; c++)
      if (in_arc(R, k, q[c & 1], q[2 + (c >> 1)])) return 1;
    if (ray_meets_rect(R->arc[4*k], R->arc[4*k+1], q)) return 1;
  }
  return 0;
}

/* The size of afv_reach_of's work room for k centres, in bytes. */
size_t afv_reach_work(int k)
{
  return (size_t)(k + 1) * sizeof(segment);
}

/* The point at parameter tau on the line of B (cell frame). */
static void point_on(bisector B, double tau, double *x, double *y)
{
  *x = B.h * B.ux - tau * B.uy;
  *y = B.h * B.uy + tau * B.ux;
}

/* Writes one piece at *pc; returns the place of the next one.  (Counting
** through a pointer, not g->n_pieces[i], lets the compiler keep the count
** in a register: the stores to pieces could alias n_pieces.) */
static afv_piece *store_piece(const afv_geom *g, afv_piece *pc, int slot,
                              double x, double y, double length, double tau)
{
  pc->slot = slot;
  pc->nbr = slot >= 0 ? g->nbr[slot] : AFV_ARC;
  pc->x = x;
  pc->y = y;
  pc->length = length;
  pc->tau = tau;
  return pc + 1;
}

/* The arc from (ax, ay), the end of a segment, to the start of segment b
** (counter-clockwise), as an angle in [0, 2 pi); `single` if b is that same
** segment. */
static double gap_angle(const afv_geom *g, double ax, double ay,
                        const segment *b, int single)
{
  double bx, by, phi;
  point_on(bisector_of(g, b->slot), b->tau0, &bx, &by);
  /* the angle from a to b as the angle of (dot, cross): half the cost of
  ** two polar angles, and as accurate */
  phi = afv_angle_inline(ax * by - ay * bx, ax * bx + ay * by);
  if (phi >= TWO_PI) phi -= TWO_PI;
  if (phi < 0) phi = 0;   /* afv_angle's absolute error: an angle of ~0
                          ** came out as -3e-17 (a fuzzer case: area < 0) */
  if (single && phi == 0) phi = TWO_PI;
  if (!single && phi > TWO_PI - AFV_ANGLE_TOL) phi = 0;
  return phi;
}

static void isolated_cell(afv_geom *g, int i, double l)
{
  store_piece(g, g->pieces + g->piece_start[i], -1, l, 0, TWO_PI * l, 0);
  g->n_pieces[i] = 1;
  g->area[i] = PI * l * l;
  g->perim[i] = g->arc[i] = TWO_PI * l;
}

/* Writes the pieces of cell i from its kept segments seg[0..ns-1] and sums
** A (triangles h*len/2 on the edges, sectors l^2 phi/2 on the arcs), P, L:
** the A_i, P_i and L_i of the paper's energy, Eq. (3). */
static void assemble_boundary(afv_geom *g, int i, double l, const segment *seg,
                              int ns)
{
  afv_piece *first = g->pieces + g->piece_start[i], *pc = first;
  double A = 0, P = 0, L = 0;
  int k, contacts = 0;
  for (k = 0; k < ns; k++) {
    const segment *S = &seg[k];
    bisector B = bisector_of(g, S->slot);
    double len = S->tau1 - S->tau0;
    double x, y;
    point_on(B, S->tau0, &x, &y);
    pc = store_piece(g, pc, S->slot, x, y, len, S->tau0);
    A += 0.5 * B.h * len;
    P += len;
    if (len > AFV_CONTACT_TOL * l) contacts++;
    if (S->end_on_circle) {
      const segment *next = &seg[k + 1 < ns ? k + 1 : 0];
      double phi;
      point_on(B, S->tau1, &x, &y);
      phi = gap_angle(g, x, y, next, ns == 1);
      pc = store_piece(g, pc, -1, x, y, l * phi, 0);
      A += 0.5 * l * l * phi;
      L += l * phi;
    }
  }
  g->n_pieces[i] = (int)(pc - first);
  g->contacts[i] = contacts;
  g->area[i] = A;
  g->perim[i] = P + L;
  g->arc[i] = L;
}

/* The work block of the calling thread (afv_geometry_prepare reserves one
** per OpenMP thread), so that different cells may be shaped in parallel. */
static double *thread_work(const afv_geom *g)
{
#ifdef _OPENMP
  return g->work + (size_t)g->work_stride * omp_get_thread_num();
#else
  return g->work;
#endif
}

#ifndef NDEBUG
/* 1 if cell i's shape lies within the bounds of a convex part of the disk
** (the header's invariant), to rounding. */
static int shape_in_bounds(const afv_geom *g, int i, double l)
{
  double most = 1 + AFV_SUM_ROUNDING, A = g->area[i], P = g->perim[i],
         L = g->arc[i];
  return A >= 0 && A <= PI * l * l * most && L >= 0 && L <= P * most
         && P <= TWO_PI * l * most
         && g->contacts[i] <= g->nbr_end[i] - g->nbr_start[i];
}
#endif

void afv_cell_shape(afv_geom *g, int i, double l)
{
  segment *seg = (segment *)thread_work(g);
  int ns;
  assert(afv_slots_sorted(g, i));
  g->n_pieces[i] = 0;
  g->contacts[i] = 0;
  /* the slots are sorted by the direction of u (sort_slots), which is the
  ** counter-clockwise order of the edges of a convex cell: the kept parts
  ** come out in boundary order */
  ns = clip_chords(g, i, l, seg);
  if (ns == 0) isolated_cell(g, i, l);
  else assemble_boundary(g, i, l, seg, ns);
  assert(shape_in_bounds(g, i, l));
}

/* Work space for one cell with up to max_nn neighbours: max_nn segments;
** one such block per OpenMP thread. */
static int reserve_work(afv_geom *g, int max_nn)
{
  size_t bytes = (size_t)(max_nn + 1) * sizeof(segment);
  if (max_nn > PRUNE_FROM)          /* clip_chords' prune_work */
    bytes += (size_t)(3 * max_nn + 1) * sizeof(int)
             + (size_t)6 * max_nn * sizeof(double);
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  g->work_stride = (int)(bytes / sizeof(double)) + 1;
  return afv_grow((void **)&g->work, &g->cap_work, g->work_stride * threads,
              sizeof(double));
}

/* Everything afv_cell_shape needs: neighbour lists, piece and work space. */
int afv_geometry_prepare(afv_geom *g, int n, const double *r, double l,
                         const afv_box *b)
{
  int st, i, first = 2 * n;       /* the first coordinate not finite */
  g->bad_i = g->bad_j = -1;
  AFV_PARALLEL_REDUCE(n, reduction(min: first))
  for (i = 0; i < 2 * n; i++)
    if (!isfinite(r[i]) && i < first) first = i;
  if (first < 2 * n) {
    g->bad_i = first / 2;
    return AFV_ENONFINITE;
  }
  if ((st = afv_neighbours(g, n, r, l, b)) != AFV_OK) return st;
  return reserve_work(g, g->max_cand);
}
