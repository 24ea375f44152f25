/*
** analysis.c -- the paper's order parameters: clusters, confluency Omega,
** generalised T1 count, relative MSD, autocorrelation time, mean-field P0*.
**
** Everything here reads an afv_geom (afv_geometry's cell shapes); nothing
** changes the model.  Definitions follow the paper's sections on clustering,
** the epithelial-mesenchymal transition and glassy dynamics:
**
**   contact    two cells share a straight edge longer than AFV_CONTACT_TOL l
**              (a bisector shadowed by a third cell gives no edge: no
**              contact, although the centres are closer than 2l);
**   cluster    a connected component of the contact graph (union-find);
**   Omega      sum_j N_j omega_j / sum_j N_j, omega_j = V3_j / max(Ec_j -
**              N_j + 1 - w_j, 1), w_j = 1 if cluster j winds around the
**              periodic box (see cluster_omega for why), else 0;
**   T1(t)      |C(t) symmetric-difference C(0)| / 2, C = contacting pairs;
**   MSD        displacements relative to the contacting neighbours at the
**              time origin, from unwrapped positions.
**
** Vertices.  A vertex of the tissue is seen by every cell around it; here a
** vertex is a class of piece starts (union-find over the pieces of all
** cells) joined where two cells see the same point, and across every
** straight edge too short to be a contact (its two ends are the same vertex
** within AFV_CONTACT_TOL l).  A class is a triple junction when none of its
** members is an arc end.  So a near-degenerate 4-fold vertex (two junctions
** joined by an edge shorter than AFV_CONTACT_TOL l) is ONE junction: the
** contact graph has one (quadrilateral) face there, which keeps Euler's
** count V3 = Ec - N + 1 of a confluent cluster exact, omega = 1.  A real
** 4-fold vertex (edge exactly 0) is the same case.
**
** Invariants (asserted where relied on, in a build without -DNDEBUG):
** partner[] is an involution, partner[partner[q]] = q (a cell has at most
** one edge per neighbour: join_vertices identifies the two views of an
** edge by it); the clusters partition the cells, their sizes summing to N
** (N_GC and Omega's weights); a list of contacting pairs C is strictly
** increasing in (i, j), i < j (afv_t1_count merges two of them).
*/
#include "afv_internal.h"
#include "afv_tool.h"
#include "fastmath.h"

#include <assert.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Sokal's automatic window for the integrated autocorrelation time: the
** smallest W with W >= TAU_WINDOW_C * tau(W).  c = 5 keeps the truncation
** bias below exp(-5) ~ 0.7% for an exponential decay while the variance,
** which grows like W, stays small. */
#define TAU_WINDOW_C 5.0

/* Log-spaced MSD lags: this many per decade of frame lags. */
#define MSD_LAGS_PER_DECADE 10

/* msd_beta, the slope of log MSD_rel against log lag, is fitted on the
** lags from MSD_BETA_FROM to MSD_BETA_TO of the steady window: the
** upper end keeps at least 90% of the frames as time origins behind every
** lag; the lower end, a decade below, is past the polarity's persistence
** time 1/Dr = 10 once the window is longer than 1000 time units (10^5 steps
** at dt = 0.01).  As fractions of the window the slope does not change with
** the run's length: a caged (glassy) tissue has beta near 0, a fluid one
** near 1.  Fewer than MSD_BETA_MIN_LAGS lags in that range: beta is NaN. */
#define MSD_BETA_FROM 0.01
#define MSD_BETA_TO 0.1
#define MSD_BETA_MIN_LAGS 3

/* ---- buffers ----------------------------------------------------------- */
/* The private part of an afv_clusters (afv.h keeps it opaque): the
** capacities of its arrays and the union-find's work space. */
struct afv_clusters_work {
  int     cap_pairs, cap_junctions, cap_cells, cap_pieces;
  int    *parent, *root_label, *vparent;
  double *off;          /* offset of each cell from its union-find parent */
};

/* Grows several arrays of one capacity; each gets its own copy of cap. */
static int grow_cells(afv_clusters *c, int need)
{
  int cap = c->work->cap_cells, k;
  void **arr[9];
  size_t size[9];
  arr[0] = (void **)&c->label;   size[0] = sizeof(int);
  arr[1] = (void **)&c->size;    size[1] = sizeof(int);
  arr[2] = (void **)&c->ec;      size[2] = sizeof(int);
  arr[3] = (void **)&c->v3;      size[3] = sizeof(int);
  arr[4] = (void **)&c->wraps;   size[4] = sizeof(int);
  arr[5] = (void **)&c->omega_c; size[5] = sizeof(double);
  arr[6] = (void **)&c->work->parent;  size[6] = sizeof(int);
  arr[7] = (void **)&c->work->off;     size[7] = 2 * sizeof(double);
  arr[8] = (void **)&c->work->root_label; size[8] = sizeof(int);
  if (need <= cap) return AFV_OK;
  for (k = 0; k < 9; k++) {
    int cc = cap;
    if (afv_grow(arr[k], &cc, need, size[k])) return AFV_ENOMEM;
    if (k == 8) c->work->cap_cells = cc;
  }
  return AFV_OK;
}

static int grow_pieces(afv_clusters *c, int need)
{
  int cap = c->work->cap_pieces, k;
  void **arr[3];
  arr[0] = (void **)&c->partner;
  arr[1] = (void **)&c->contact;
  arr[2] = (void **)&c->work->vparent;
  if (need <= cap) return AFV_OK;
  for (k = 0; k < 3; k++) {
    int cc = cap;
    if (afv_grow(arr[k], &cc, need, sizeof(int))) return AFV_ENOMEM;
    if (k == 2) c->work->cap_pieces = cc;
  }
  return AFV_OK;
}

void afv_clusters_free(afv_clusters *c)
{
  free(c->pairs); free(c->junction); free(c->label); free(c->size);
  free(c->ec); free(c->v3); free(c->wraps); free(c->omega_c);
  free(c->partner); free(c->contact);
  if (c->work) {
    free(c->work->parent); free(c->work->off);
    free(c->work->root_label); free(c->work->vparent);
    free(c->work);
  }
  memset(c, 0, sizeof *c);
}

/* ---- contacts ----------------------------------------------------------- */
/* partner[q]: the piece of cell j = nbr(q) that is the same edge seen from j
** (-1 for an arc, or for an edge so short that j's clipping lost it);
** contact[q]: 1 if the longer of the two views exceeds AFV_CONTACT_TOL l,
** so that both cells agree on it. */
static void match_edges(afv_clusters *c, const afv_geom *g, double l)
{
  int i, k, t;
  for (i = 0; i < g->n; i++)
    for (k = g->piece_start[i]; k < g->piece_start[i] + g->n_pieces[i]; k++) {
      const afv_piece *pc = &g->pieces[k];
      int j = pc->nbr;
      double len = pc->length;
      c->partner[k] = -1;
      c->contact[k] = 0;
      if (j < 0) continue;
      for (t = g->piece_start[j]; t < g->piece_start[j] + g->n_pieces[j]; t++)
        if (g->pieces[t].nbr == i) {
          c->partner[k] = t;
          if (g->pieces[t].length > len) len = g->pieces[t].length;
          break;
        }
      c->contact[k] = len > AFV_CONTACT_TOL * l;
    }
}

/* The sorted list C of contacting pairs (i < j), each once. */
static int collect_pairs(afv_clusters *c, const afv_geom *g)
{
  int i, k, m = 0;
  for (i = 0; i < g->n; i++)
    for (k = g->piece_start[i]; k < g->piece_start[i] + g->n_pieces[i]; k++) {
      int j = g->pieces[k].nbr;
      if (!c->contact[k] || j < i) continue;   /* the lower index records it */
      if (afv_grow((void **)&c->pairs, &c->work->cap_pairs, m + 1,
                   2 * sizeof(int)))
        return AFV_ENOMEM;
      c->pairs[2*m] = i;
      c->pairs[2*m+1] = j;
      m++;
    }
  c->n_pairs = m;
  /* cells are visited in order and a convex cell meets each neighbour in at
  ** most one edge; sort the j's within each i so the list is sorted */
  for (k = 1; k < m; k++) {
    int a = c->pairs[2*k], b = c->pairs[2*k+1], s = k;
    while (s > 0 && c->pairs[2*(s-1)] == a && c->pairs[2*(s-1)+1] > b) {
      c->pairs[2*s+1] = c->pairs[2*(s-1)+1];
      s--;
    }
    c->pairs[2*s+1] = b;
  }
  return AFV_OK;
}

/* ---- clusters: union-find that remembers where each cell sits ---------- */
/* off[i] is the unwrapped position of i minus that of parent[i], so two
** paths between the same cells that disagree by a box vector reveal a
** cluster winding around the periodic box. */
static int find(afv_clusters *c, int i)
{
  int p = c->work->parent[i], root;
  if (p == i) return i;
  root = find(c, p);                 /* depth O(log N): union by size */
  c->work->off[2*i] += c->work->off[2*p];        /* off[p] is now relative to root */
  c->work->off[2*i+1] += c->work->off[2*p+1];
  c->work->parent[i] = root;
  return root;
}

/* Joins i and j, D = r_j - r_i (minimum image).  A loop whose displacements
** do not add up to zero has gone around the box: the shortest box vector is
** at least 4l, the roundoff many orders below l, so l is a safe threshold. */
static void join(afv_clusters *c, int i, int j, double dx, double dy, double l)
{
  int a = find(c, i), b = find(c, j);
  double mx = c->work->off[2*i] + dx - c->work->off[2*j];  /* pos(b) - pos(a) */
  double my = c->work->off[2*i+1] + dy - c->work->off[2*j+1];
  if (a == b) {
    if (mx * mx + my * my > l * l) c->wraps[a] = 1;
    return;
  }
  if (c->size[a] < c->size[b]) {
    int t = a;
    a = b;
    b = t;
    mx = -mx;
    my = -my;
  }
  c->work->parent[b] = a;
  c->work->off[2*b] = mx;
  c->work->off[2*b+1] = my;
  c->size[a] += c->size[b];
  c->wraps[a] |= c->wraps[b];
}

static void find_clusters(afv_clusters *c, const afv_geom *g, double l)
{
  int i, k, n = g->n;
  for (i = 0; i < n; i++) {
    c->work->parent[i] = i;
    c->size[i] = 1;
    c->wraps[i] = 0;
    c->work->off[2*i] = c->work->off[2*i+1] = 0;
  }
  for (i = 0; i < n; i++)
    for (k = g->piece_start[i]; k < g->piece_start[i] + g->n_pieces[i]; k++) {
      const afv_piece *pc = &g->pieces[k];
      if (c->contact[k] && pc->nbr > i)
        join(c, i, pc->nbr, g->nbr_d[2*pc->slot], g->nbr_d[2*pc->slot+1], l);
    }
}

/* Renumbers the roots 0..count-1 (in order of their first cell) and moves
** size and wraps from root-indexed to label-indexed arrays. */
static void label_clusters(afv_clusters *c, int n)
{
  int i, m = 0;
  for (i = 0; i < n; i++) c->work->root_label[i] = -1;
  for (i = 0; i < n; i++) {
    int r = find(c, i);
    if (c->work->root_label[r] < 0) c->work->root_label[r] = m++;
    c->label[i] = c->work->root_label[r];
  }
  /* size/wraps of root r go to slot root_label[r]; labels are assigned in
  ** increasing order of first cell, so root_label[r] <= r: a forward pass
  ** overwrites only slots already read */
  for (i = 0; i < n; i++)
    if (c->work->parent[i] == i) {
      int s = c->size[i], w = c->wraps[i];
      c->size[c->work->root_label[i]] = s;
      c->wraps[c->work->root_label[i]] = w;
    }
  c->count = m;
  c->giant = 0;
  for (i = 0; i < m; i++) {
    c->ec[i] = c->v3[i] = 0;
    if (c->size[i] > c->giant) c->giant = c->size[i];
  }
}

/* ---- vertices ---------------------------------------------------------- */
static int vfind(int *vp, int q)
{
  while (vp[q] != q) {
    vp[q] = vp[vp[q]];   /* path halving */
    q = vp[q];
  }
  return q;
}

static void vjoin(int *vp, int a, int b)
{
  a = vfind(vp, a);
  b = vfind(vp, b);
  if (a != b) vp[a < b ? b : a] = a < b ? a : b;
}

/* The piece after piece q of cell i, cyclically. */
static int next_piece(const afv_geom *g, int i, int q)
{
  int s = g->piece_start[i];
  return s + (q - s + 1) % g->n_pieces[i];
}

static int prev_piece(const afv_geom *g, int i, int q)
{
  int s = g->piece_start[i], m = g->n_pieces[i];
  return s + (q - s + m - 1) % m;
}

/* Vertex q is the start of piece q.  The end of edge q (cell i, towards j)
** is the start of j's piece for the same edge, partner[q]: that identifies
** each point across cells.  Both ends of a non-contact edge are one vertex. */
static void join_vertices(afv_clusters *c, const afv_geom *g)
{
  int i, q;
  for (i = 0; i < g->n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++)
      c->work->vparent[q] = q;
  for (i = 0; i < g->n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++) {
      int nq = next_piece(g, i, q);
      if (g->pieces[q].nbr < 0) continue;
      assert(c->partner[q] < 0 || c->partner[c->partner[q]] == q);
      if (c->partner[q] >= 0) vjoin(c->work->vparent, nq, c->partner[q]);
      if (!c->contact[q]) vjoin(c->work->vparent, q, nq);
    }
}

/* A class is a junction when no member is an arc end, i.e. every member
** starts an edge that follows an edge.  Marks classes in c->contact's
** spare bit (bit 1 = "class has an arc end") and counts junctions. */
static int count_junctions(afv_clusters *c, const afv_geom *g,
                           const double *r, const afv_box *b)
{
  int i, q, m = 0;
  for (i = 0; i < g->n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++) {
      int corner = g->pieces[q].nbr >= 0
                   && g->pieces[prev_piece(g, i, q)].nbr >= 0;
      if (!corner) c->contact[vfind(c->work->vparent, q)] |= 2;
    }
  for (i = 0; i < g->n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++) {
      double x, y;
      if (vfind(c->work->vparent, q) != q || (c->contact[q] & 2)) continue;
      if (afv_grow((void **)&c->junction, &c->work->cap_junctions, m + 1,
               2 * sizeof(double)))
        return AFV_ENOMEM;
      x = r[2*i] + g->pieces[q].x;
      y = r[2*i+1] + g->pieces[q].y;
      afv_wrap(b, &x, &y);
      c->junction[2*m] = x;
      c->junction[2*m+1] = y;
      c->v3[c->label[i]]++;
      m++;
    }
  for (i = 0; i < g->n; i++)
    for (q = g->piece_start[i]; q < g->piece_start[i] + g->n_pieces[i]; q++)
      c->contact[q] &= 1;
  c->n_junctions = m;
  return AFV_OK;
}

/* omega_j = V3 / max(Ec - N + 1 - w, 1).  Euler: the contact graph of a
** cluster has Ec - N + 1 independent cycles.  In open space (or a cluster
** not winding around the box) each bounded face is a junction or a gap, so
** a confluent cluster has V3 = Ec - N + 1 (the paper).  A cluster winding
** around the periodic box has exactly one more independent cycle than faces
** that are junctions or gaps (the winding loop; when it winds both ways the
** faces tile the torus and their sum is a relation, which cancels the second
** winding loop), so confluent means V3 = Ec - N there: w = 1.  With this a
** confluent periodic lattice has omega = 1, as it must. */
static void cluster_omega(afv_clusters *c, int n)
{
  int k;
  double sum = 0;
  for (k = 0; k < c->count; k++) {
    int den = c->ec[k] - c->size[k] + 1 - c->wraps[k];
    c->omega_c[k] = (double)c->v3[k] / (den > 1 ? den : 1);
    sum += c->size[k] * c->omega_c[k];
  }
  c->omega = n > 0 ? sum / n : 0;
}

#ifndef NDEBUG
/* 1 if the count clusters of c hold the n cells between them. */
static int clusters_partition(const afv_clusters *c, int n)
{
  long cells = 0;
  int k;
  for (k = 0; k < c->count; k++) cells += c->size[k];
  return cells == n;
}

/* 1 if the m pairs p are strictly increasing in (i, j), each with i < j. */
static int pairs_increasing(const int *p, int m)
{
  int k;
  for (k = 0; k < m; k++)
    if (!(p[2*k] < p[2*k+1])
        || (k > 0 && !(p[2*k-2] < p[2*k]
                       || (p[2*k-2] == p[2*k] && p[2*k-1] < p[2*k+1]))))
      return 0;
  return 1;
}
#endif

int afv_clusters_compute(afv_clusters *c, const afv_geom *g, const double *r,
                         double l, const afv_box *b)
{
  assert(c != NULL && g != NULL && (r != NULL || g->n == 0));
  int n = g->n, k, st, npieces = 0;
  /* the pieces' extent: a cell's block may lie after the last cell's (a
  ** list moved to the spare room, neighbours.c MOVERS) */
  for (k = 0; k < n; k++)
    if (g->piece_start[k] + g->n_pieces[k] > npieces)
      npieces = g->piece_start[k] + g->n_pieces[k];
  if (!(l > 0)) return AFV_EINVAL;
  if (!c->work && !(c->work = calloc(1, sizeof *c->work))) return AFV_ENOMEM;
  if (grow_cells(c, n + 1) || grow_pieces(c, npieces + 1)) return AFV_ENOMEM;
  c->n = n;
  match_edges(c, g, l);
  if ((st = collect_pairs(c, g)) != AFV_OK) return st;
  find_clusters(c, g, l);
  label_clusters(c, n);
  assert(clusters_partition(c, n));
  for (k = 0; k < c->n_pairs; k++) c->ec[c->label[c->pairs[2*k]]]++;
  join_vertices(c, g);
  if ((st = count_junctions(c, g, r, b)) != AFV_OK) return st;
  cluster_omega(c, n);
  return AFV_OK;
}

/* ---- T1 ---------------------------------------------------------------- */
void afv_t1_free(afv_t1 *t)
{
  free(t->pairs0);
  memset(t, 0, sizeof *t);
}

int afv_t1_start(afv_t1 *t, const afv_clusters *c)
{
  assert(t != NULL && c != NULL);
  int *p = NULL;
  if (c->n_pairs > 0) {
    p = malloc((size_t)c->n_pairs * 2 * sizeof(int));
    if (!p) return AFV_ENOMEM;
    memcpy(p, c->pairs, (size_t)c->n_pairs * 2 * sizeof(int));
  }
  free(t->pairs0);
  t->pairs0 = p;
  t->n_pairs0 = c->n_pairs;
  return AFV_OK;
}

static int pair_cmp(const int *a, const int *b)
{
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  if (a[1] != b[1]) return a[1] < b[1] ? -1 : 1;
  return 0;
}

/* |C(t) sym-diff C(0)| / 2 by a merge of the two sorted lists. */
double afv_t1_count(const afv_t1 *t, const afv_clusters *c)
{
  assert(t != NULL && c != NULL);
  int a = 0, b = 0;
  long diff = 0;
  assert(pairs_increasing(t->pairs0, t->n_pairs0));
  assert(pairs_increasing(c->pairs, c->n_pairs));
  while (a < t->n_pairs0 || b < c->n_pairs) {
    int cmp;
    if (a == t->n_pairs0) cmp = 1;
    else if (b == c->n_pairs) cmp = -1;
    else cmp = pair_cmp(&t->pairs0[2*a], &c->pairs[2*b]);
    if (cmp != 0) diff++;
    if (cmp <= 0) a++;
    if (cmp >= 0) b++;
  }
  return 0.5 * (double)diff;
}

/* ---- trajectories: unwrapping and MSD ---------------------------------- */
void afv_traj_unwrap(afv_traj *tr)
{
  int f, i, n = tr->n;
  if (!tr->box.periodic) return;
  for (f = 1; f < tr->nframes; f++) {
    const double *a = tr->r + (size_t)(f - 1) * 2 * n;
    double *q = tr->r + (size_t)f * 2 * n;
    for (i = 0; i < n; i++) {
      double dx = q[2*i] - a[2*i], dy = q[2*i+1] - a[2*i+1];
      afv_min_image(&tr->box, &dx, &dy);
      q[2*i] = a[2*i] + dx;
      q[2*i+1] = a[2*i+1] + dy;
    }
  }
}

void afv_msd_free(afv_msd *m)
{
  free(m->lag); free(m->dt); free(m->msd); free(m->msd_rel);
  free(m->samples); free(m->msd_se); free(m->msd_rel_se); free(m->per_cell);
  memset(m, 0, sizeof *m);
}

/* Log-spaced frame lags 1 .. maxlag: round(10^(k / per_decade)), distinct,
** plus maxlag itself.  The C library's pow may differ between machines in
** its last bit, but not the lags: for per_decade 10 and every lag up to
** 2^31, 10^(k/10) lies at least 1.6e-11 of itself (k = 83) from a half
** integer (computed to 40 digits), far beyond an ulp (2.2e-16). */
static int make_lags(afv_msd *m, int maxlag)
{
  int k = 0, last = 0, cap = 0;
  double e = 0;
  while (last < maxlag) {
    int L = (int)floor(pow(10.0, e / MSD_LAGS_PER_DECADE) + 0.5);
    e += 1;
    if (L > maxlag) L = maxlag;
    if (L <= last) continue;
    if (afv_grow((void **)&m->lag, &cap, k + 1, sizeof(int)))
      return AFV_ENOMEM;
    m->lag[k++] = L;
    last = L;
  }
  m->nlags = k;
  return AFV_OK;
}

/* The lags' sums, and each cell's (plain, relative) for the standard
** errors: 2 n nlags doubles. */
static int msd_alloc(afv_msd *m, int n)
{
  size_t k = (size_t)m->nlags + 1;
  m->dt = calloc(k, sizeof(double));
  m->msd = calloc(k, sizeof(double));
  m->msd_rel = calloc(k, sizeof(double));
  m->samples = calloc(k, sizeof(long));
  m->msd_se = calloc(k, sizeof(double));
  m->msd_rel_se = calloc(k, sizeof(double));
  m->per_cell = calloc(2 * k * (size_t)n, sizeof(double));
  return m->dt && m->msd && m->msd_rel && m->samples && m->msd_se
         && m->msd_rel_se && m->per_cell ? AFV_OK : AFV_ENOMEM;
}

/* Contacting neighbours of every cell at one frame, in CSR form from the
** pair list: nb[ns[i] .. ns[i+1]-1]. */
static void neighbour_csr(const afv_clusters *c, int n, int *ns, int *nb)
{
  int k, i;
  for (i = 0; i <= n; i++) ns[i] = 0;
  for (k = 0; k < c->n_pairs; k++) {
    ns[c->pairs[2*k] + 1]++;
    ns[c->pairs[2*k+1] + 1]++;
  }
  for (i = 0; i < n; i++) ns[i + 1] += ns[i];
  for (k = 0; k < c->n_pairs; k++) {
    int a = c->pairs[2*k], b = c->pairs[2*k+1];
    nb[ns[a]++] = b;
    nb[ns[b]++] = a;
  }
  for (i = n; i > 0; i--) ns[i] = ns[i - 1];
  ns[0] = 0;
}

/* Adds the displacements of the n cells from an origin frame (centres a at
** time t0, contacting neighbours ns, nb) to the frame lag[k] later (centres
** q at time t1). */
static void msd_accumulate(afv_msd *m, int k, int n, const double *a,
                           const double *q, double t0, double t1,
                           const int *ns, const int *nb)
{
  int i, s;
  double *cell = m->per_cell + 2 * (size_t)k * n;
  for (i = 0; i < n; i++) {
    double dx = q[2*i] - a[2*i], dy = q[2*i+1] - a[2*i+1], mx = 0, my = 0;
    int deg = ns[i + 1] - ns[i];
    for (s = ns[i]; s < ns[i + 1]; s++) {
      mx += q[2*nb[s]] - a[2*nb[s]];
      my += q[2*nb[s]+1] - a[2*nb[s]+1];
    }
    m->msd[k] += dx * dx + dy * dy;
    cell[2*i] += dx * dx + dy * dy;
    if (deg > 0) {
      dx -= mx / deg;
      dy -= my / deg;
    }
    m->msd_rel[k] += dx * dx + dy * dy;
    cell[2*i+1] += dx * dx + dy * dy;
  }
  m->dt[k] += n * (t1 - t0);
  m->samples[k] += n;
}

/* The standard error of a lag's MSD across the n cells: each cell's mean
** over the time origins (every cell has the same origins) is one sample;
** se = sd of the n cell means / sqrt(n).  Across cells, not time origins:
** a lag's origins overlap (at lag 5000 of a 9000-long window every
** origin shares most of its path with the others), so they are not
** independent samples; the cells are, up to their spatial correlation,
** which this error leaves out (it is a lower bound where cells move
** together).  NaN with one cell. */
static double cell_se(const double *cell, int n, long origins, double mean,
                      int which)
{
  double ss = 0;
  int i;
  if (n < 2 || origins < 1) return NAN;
  for (i = 0; i < n; i++) {
    double d = cell[2*i + which] / origins - mean;
    ss += d * d;
  }
  return sqrt(ss / (n - 1) / n);
}

static void msd_normalise(afv_msd *m, int n)
{
  int k;
  for (k = 0; k < m->nlags; k++) {
    const double *cell = m->per_cell + 2 * (size_t)k * n;
    if (m->samples[k] > 0) {
      m->dt[k] /= m->samples[k];
      m->msd[k] /= m->samples[k];
      m->msd_rel[k] /= m->samples[k];
    }
    m->msd_se[k] = cell_se(cell, n, m->samples[k] / n, m->msd[k], 0);
    m->msd_rel_se[k] = cell_se(cell, n, m->samples[k] / n, m->msd_rel[k], 1);
  }
  free(m->per_cell);
  m->per_cell = NULL;
}

/* ---- streaming over the frames ----------------------------------------- */
/* STREAMING.  afv analyze reads a trajectory frame by frame and holds only
** the last W frames (a ring of their centres and contacting neighbours):
** the MSD of every lag up to W - 1 frames is summed as the lag's later
** frame arrives.  The longer lags (few: they are log-spaced) are summed in
** a second pass that reads each origin and the frames a lag later back
** from the file.  For each lag the sum runs over the origins in increasing
** order, as it did over frames all held in memory: the same bits.  W is
** what ring_bytes holds (AFV_ANALYSIS_RING_BYTES by default; at least 2
** frames, at most the steady window), so the memory is O(N W) and not
** O(N frames). */
typedef struct frame_src {
  int n, nframes;
  afv_box box;
  const double *t;
  const afv_traj *mem;        /* frames in memory, or */
  afv_traj_file *file;        /* frames read from a file */
  char *err;
  size_t errlen;
} frame_src;

static int src_frame(const frame_src *s, int k, double *r)
{
  size_t m = 2 * (size_t)s->n;
  if (s->mem) {
    memcpy(r, s->mem->r + (size_t)k * m, m * sizeof(double));
    return AFV_OK;
  }
  return afv_traj_frame(s->file, k, r, NULL, s->err, s->errlen);
}

/* A frame held: its centres and contacting neighbours (CSR). */
typedef struct held {
  double *r;
  int *ns, *nb, cap_nb;
} held;

static void held_free(held *h, int count)
{
  int k;
  for (k = 0; h && k < count; k++) {
    free(h[k].r);
    free(h[k].ns);
    free(h[k].nb);
  }
  free(h);
}

static held *held_alloc(int count, int n)
{
  held *h = calloc((size_t)count, sizeof *h);
  int k;
  for (k = 0; h && k < count; k++) {
    h[k].r = malloc((2 * (size_t)n + 1) * sizeof(double));
    h[k].ns = malloc(((size_t)n + 1) * sizeof(int));
    if (!h[k].r || !h[k].ns) {
      held_free(h, count);
      return NULL;
    }
  }
  return h;
}

/* The contacting neighbours of c into h. */
static int hold_neighbours(held *h, const afv_clusters *c, int n)
{
  if (afv_grow((void **)&h->nb, &h->cap_nb, 2 * c->n_pairs + 1, sizeof(int)))
    return AFV_ENOMEM;
  neighbour_csr(c, n, h->ns, h->nb);
  return AFV_OK;
}

/* Shapes and contacts of the n cells at r. */
static int frame_contacts(afv_geom *g, afv_clusters *c, int n,
                          const double *r, const afv_params *p,
                          const afv_box *b)
{
  int st = afv_geometry(g, n, r, p, b);
  return st == AFV_OK ? afv_clusters_compute(c, g, r, p->l, b) : st;
}

/* The per-frame order parameters of an analysis, carried from frame to
** frame: T1 against frame 0 and against the frame before. */
typedef struct order_state {
  afv_t1 t1, prev;
  double nclusters, changes;
} order_state;

/* Frame f's order parameters; cluster sizes of steady frames into csd;
** contact changes between consecutive steady frames into changes. */
static int frame_order(afv_analysis *a, order_state *o, int f, double t,
                       const afv_clusters *c)
{
  int k, st;
  if (f == 0 && (st = afv_t1_start(&o->t1, c)) != AFV_OK) return st;
  a->t[f] = t;
  a->ngc_frac[f] = (double)c->giant / a->n;
  a->n_clusters[f] = c->count;
  a->omega[f] = c->omega;
  a->t1[f] = afv_t1_count(&o->t1, c);
  if (f < a->first) return AFV_OK;
  if (f > a->first) o->changes += afv_t1_count(&o->prev, c);
  if ((st = afv_t1_start(&o->prev, c)) != AFV_OK) return st;
  for (k = 0; k < c->count; k++) a->csd[c->size[k]] += 1;
  o->nclusters += c->count;
  return AFV_OK;
}

/* The cluster-size distribution normalised, and t1_rate: T1 events per
** cell per unit time (each neighbour exchange between two frames changes
** one pair lost and one gained, |C(f) sym-diff C(f-1)|/2 counts it once;
** exchanges undone within one frame interval are missed, so the rate is a
** lower bound that depends on frame_every). */
static void order_finish(afv_analysis *a, const order_state *o,
                         const double *t)
{
  int k, f = a->nframes - 1;
  for (k = 1; k <= a->n && o->nclusters > 0; k++) a->csd[k] /= o->nclusters;
  a->t1_rate = f > a->first
               ? o->changes / (a->n * (t[f] - t[a->first])) : NAN;
}

/* The one pass over the frames (from frame 0 with an analysis a, else from
** first): a's order parameters, and the MSD m of the lags below W. */
static int stream_pass(afv_analysis *a, afv_msd *m, const frame_src *src,
                       int first, double l, int W)
{
  afv_geom g;
  afv_clusters c;
  afv_params p;
  order_state o;
  held *ring = held_alloc(W, src->n);
  int f, k, st = ring ? AFV_OK : AFV_ENOMEM, n = src->n;
  memset(&g, 0, sizeof g);
  memset(&c, 0, sizeof c);
  memset(&o, 0, sizeof o);
  afv_params_default(&p);
  p.l = l;
  for (f = a ? 0 : first; st == AFV_OK && f < src->nframes; f++) {
    held *h = &ring[f % W];
    if ((st = src_frame(src, f, h->r)) != AFV_OK
        || (st = frame_contacts(&g, &c, n, h->r, &p, &src->box)) != AFV_OK
        || (a && (st = frame_order(a, &o, f, src->t[f], &c)) != AFV_OK))
      break;
    if (m->nlags == 0 || f < first) continue;
    if ((st = hold_neighbours(h, &c, n)) != AFV_OK) break;
    for (k = 0; k < m->nlags && m->lag[k] < W && f - m->lag[k] >= first;
         k++) {
      const held *q = &ring[(f - m->lag[k]) % W];
      msd_accumulate(m, k, n, q->r, h->r, src->t[f - m->lag[k]], src->t[f],
                     q->ns, q->nb);
    }
  }
  if (a && st == AFV_OK) order_finish(a, &o, src->t);
  held_free(ring, W);
  afv_geom_free(&g);
  afv_clusters_free(&c);
  afv_t1_free(&o.t1);
  afv_t1_free(&o.prev);
  return st;
}

/* The second pass: the MSD of the lags of W frames or more, each origin's
** frame and contacts, then the frames those lags later, read again. */
static int long_lags(afv_msd *m, const frame_src *src, int first, double l,
                     int W)
{
  afv_geom g;
  afv_clusters c;
  afv_params p;
  held *o;
  double *q;
  int f0, k, k0 = 0, st = AFV_OK, n = src->n;
  while (k0 < m->nlags && m->lag[k0] < W) k0++;
  if (k0 == m->nlags) return AFV_OK;
  o = held_alloc(1, n);
  q = malloc((2 * (size_t)n + 1) * sizeof(double));
  if (!o || !q) st = AFV_ENOMEM;
  memset(&g, 0, sizeof g);
  memset(&c, 0, sizeof c);
  afv_params_default(&p);
  p.l = l;
  for (f0 = first; st == AFV_OK && f0 + m->lag[k0] < src->nframes; f0++) {
    if ((st = src_frame(src, f0, o->r)) != AFV_OK
        || (st = frame_contacts(&g, &c, n, o->r, &p, &src->box)) != AFV_OK
        || (st = hold_neighbours(o, &c, n)) != AFV_OK)
      break;
    for (k = k0; st == AFV_OK && k < m->nlags
                 && f0 + m->lag[k] < src->nframes; k++)
      if ((st = src_frame(src, f0 + m->lag[k], q)) == AFV_OK)
        msd_accumulate(m, k, n, o->r, q, src->t[f0], src->t[f0 + m->lag[k]],
                       o->ns, o->nb);
  }
  held_free(o, 1);
  free(q);
  afv_geom_free(&g);
  afv_clusters_free(&c);
  return st;
}

int afv_msd_compute(afv_msd *m, const afv_traj *tr, int first, double l)
{
  assert(m != NULL && tr != NULL);
  frame_src src;
  int st;
  memset(m, 0, sizeof *m);
  if (first < 0 || first >= tr->nframes - 1 || tr->n < 1 || !(l > 0))
    return AFV_EINVAL;
  memset(&src, 0, sizeof src);
  src.n = tr->n;
  src.nframes = tr->nframes;
  src.box = tr->box;
  src.t = tr->t;
  src.mem = tr;
  if ((st = make_lags(m, tr->nframes - 1 - first)) == AFV_OK
      && (st = msd_alloc(m, tr->n)) == AFV_OK
      && (st = stream_pass(NULL, m, &src, first, l,
                           tr->nframes - first)) == AFV_OK)
    msd_normalise(m, tr->n);
  if (st != AFV_OK) afv_msd_free(m);
  return st;
}

int afv_msd_lag_index(const afv_msd *m, double lag)
{
  int k, best = -1;
  for (k = 0; k < m->nlags; k++)
    if (best < 0 || fabs(m->dt[k] - lag) < fabs(m->dt[best] - lag)) best = k;
  return best;
}

/* ---- autocorrelation time ---------------------------------------------- */
/* tau = 1 + 2 sum_{t=1}^{W} rho(t) in units of the sampling interval, with
** rho the normalised autocovariance (mean subtracted, 1/n normalisation) and
** Sokal's window: the smallest W >= TAU_WINDOW_C tau(W).  If no such W < n
** exists the series is too short and the estimate at W = n - 1 is returned
** with *reliable = 0.  A constant series never decorrelates: HUGE_VAL. */
double afv_autocorr_time(const double *x, int n, int *reliable)
{
  double mean = 0, c0 = 0, tau = 1;
  int i, t;
  if (reliable) *reliable = 0;
  if (n < 2) return HUGE_VAL;
  for (i = 0; i < n; i++) mean += x[i];
  mean /= n;
  for (i = 0; i < n; i++) c0 += (x[i] - mean) * (x[i] - mean);
  if (!(c0 > 0)) return HUGE_VAL;
  for (t = 1; t < n; t++) {
    double ct = 0;
    for (i = 0; i + t < n; i++) ct += (x[i] - mean) * (x[i + t] - mean);
    tau += 2 * ct / c0;
    if (t >= TAU_WINDOW_C * tau) {
      if (reliable) *reliable = 1;
      return tau;
    }
  }
  return tau;
}

/* ---- mean field -------------------------------------------------------- */
/* Hexagonal packing, l = 1, KA = 1 (the paper's reduced units).  Each cell
** has 6 neighbours at distance d = 2 cos(theta); each contact edge subtends
** the central angle 2 theta, so its length is 2 sin(theta) and its distance
** from the centre cos(theta).  For theta <= pi/6 (gaps at the corners):
**   L = 2 pi - 12 theta                         (six arcs between edges)
**   A = (pi - 6 theta) + 6 sin(theta) cos(theta) (sectors + six triangles)
**   P = L + 12 sin(theta)
** (the paper prints 3 sin cos in A: six triangles of base 2 sin and height
** cos give 6 sin cos).  With e = (A - A0)^2 + KP (P - P0)^2 + Lambda L and
**   dA/dtheta = -6 + 6 cos(2 theta) = -12 sin^2(theta),
**   dP/dtheta = -12 (1 - cos(theta)),  dL/dtheta = -12,
**   de/dtheta = 24 KP (1 - cos)(12 theta - 12 sin + P0 - 2 pi)
**             + 24 sin^2 (A0 - pi + 6 theta - 3 sin(2 theta)) - 12 Lambda.
** The cells close their gaps (a confluent honeycomb) when the minimum
** reaches theta = pi/6, where sin = 1/2, cos = sqrt(3)/2, P = 6 and
** A = 3 sqrt(3)/2:  0 = 24 KP (1 - sqrt(3)/2)(P0 - 6)
**                     + 6 (A0 - 3 sqrt(3)/2) - 12 Lambda,  so
**   P0* = 6 + (2 Lambda - A0 + 3 sqrt(3)/2) / (4 KP (1 - sqrt(3)/2)).
** For general KA pass KP/KA and Lambda/KA. */
double afv_meanfield_p0(double Lambda, double A0, double KP)
{
  double s3 = sqrt(3.0);
  return 6 + (2 * Lambda - A0 + 1.5 * s3) / (4 * KP * (1 - 0.5 * s3));
}

double afv_meanfield_energy(double theta, double Lambda, double A0, double KP,
                            double P0)
{
  double L = 2 * PI - 12 * theta, sn, cs, A, P;
  afv_sincos_inline(theta, &sn, &cs);
  A = PI - 6 * theta + 6 * sn * cs;
  P = L + 12 * sn;
  return (A - A0) * (A - A0) + KP * (P - P0) * (P - P0) + Lambda * L;
}

/* ---- a whole trajectory: afv analyze ----------------------------------- */
void afv_analysis_free(afv_analysis *a)
{
  free(a->t); free(a->ngc_frac); free(a->n_clusters); free(a->omega);
  free(a->t1); free(a->csd);
  afv_msd_free(&a->msd);
  memset(a, 0, sizeof *a);
}

static int analysis_alloc(afv_analysis *a, int nframes, int n)
{
  size_t k = (size_t)nframes + 1;
  a->t = calloc(k, sizeof(double));
  a->ngc_frac = calloc(k, sizeof(double));
  a->n_clusters = calloc(k, sizeof(double));
  a->omega = calloc(k, sizeof(double));
  a->t1 = calloc(k, sizeof(double));
  a->csd = calloc((size_t)n + 1, sizeof(double));
  return a->t && a->ngc_frac && a->n_clusters && a->omega && a->t1 && a->csd
         ? AFV_OK : AFV_ENOMEM;
}

static void mean_sd(const double *x, int m, double *mean, double *sd)
{
  double s = 0, v = 0;
  int k;
  for (k = 0; k < m; k++) s += x[k];
  s /= m;
  for (k = 0; k < m; k++) v += (x[k] - s) * (x[k] - s);
  *mean = s;
  *sd = m > 1 ? sqrt(v / (m - 1)) : 0;
}

/* D_s (relative and plain) at the lag nearest to `lag`, and D_eff. */
static void diffusivity(afv_analysis *a, double v0, double Dr, double lag)
{
  int k = afv_msd_lag_index(&a->msd, lag);
  /* Dr = 0: no rotational diffusion, the self-propelled motion has no
  ** diffusive limit and D_0 = v0^2 / (2 Dr) is undefined (infinite) */
  a->d0 = Dr > 0 ? v0 * v0 / (2 * Dr) : NAN;
  a->ds = a->ds_plain = a->ds_lag = 0;
  a->ds_origins = 0;
  if (k >= 0 && a->msd.dt[k] > 0) {
    a->ds_lag = a->msd.dt[k];
    a->ds = a->msd.msd_rel[k] / (4 * a->ds_lag);
    a->ds_plain = a->msd.msd[k] / (4 * a->ds_lag);
    a->ds_origins = a->n > 0 ? a->msd.samples[k] / a->n : 0;
  }
  /* v0 = 0 (D_0 = 0) or Dr = 0 (D_0 undefined): D_eff = D_s / D_0 is
  ** undefined, neither infinite nor 0 (which would read as glassy) */
  a->deff = a->d0 > 0 && isfinite(a->d0) ? a->ds / a->d0 : NAN;
}

/* Least-squares slope of log MSD_rel against log lag over the lags between
** MSD_BETA_FROM and MSD_BETA_TO of the steady window (see there). */
static double msd_beta(const afv_msd *m, double window)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k, n = 0;
  for (k = 0; k < m->nlags; k++) {
    double x, y;
    if (m->dt[k] < MSD_BETA_FROM * window || m->dt[k] > MSD_BETA_TO * window
        || !(m->msd_rel[k] > 0))
      continue;
    x = afv_log_inline(m->dt[k]);
    y = afv_log_inline(m->msd_rel[k]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    n++;
  }
  if (n < MSD_BETA_MIN_LAGS) return NAN;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* Frames a ring of ring_bytes holds (centres, neighbour lists of about six
** contacts a cell), at least 2 and at most the window. */
static int ring_frames(long ring_bytes, int n, int window)
{
  double per_frame = 44.0 * n + 64;
  double w = (double)ring_bytes / per_frame;
  if (w > window) w = window;
  return w < 2 ? 2 : (int)w;
}

static int analyze_src(afv_analysis *a, const frame_src *src, double l,
                       double v0, double Dr, double steady_from, double lag,
                       long ring_bytes)
{
  int st, k, m, nf = src->nframes, W;
  const double *t = src->t;
  memset(a, 0, sizeof *a);
  if (nf < 1 || src->n < 1 || !(l > 0)) return AFV_EINVAL;
  if ((st = analysis_alloc(a, nf, src->n)) != AFV_OK) {
    afv_analysis_free(a);
    return st;
  }
  a->n = src->n;
  a->nframes = nf;
  a->first = 0;
  while (a->first < nf - 1 && t[a->first] < steady_from) a->first++;
  if (a->first < nf - 1 && ((st = make_lags(&a->msd, nf - 1 - a->first))
                            != AFV_OK || (st = msd_alloc(&a->msd, src->n)) != AFV_OK))
    a->msd.nlags = 0;
  W = ring_frames(ring_bytes, src->n, nf - a->first);
  if (st == AFV_OK)
    st = stream_pass(a, &a->msd, src, a->first, l, W);
  if (st == AFV_OK) st = long_lags(&a->msd, src, a->first, l, W);
  if (st != AFV_OK) {
    afv_analysis_free(a);
    return st;
  }
  msd_normalise(&a->msd, src->n);
  m = nf - a->first;
  mean_sd(a->ngc_frac + a->first, m, &a->mean[0], &a->sd[0]);
  mean_sd(a->n_clusters + a->first, m, &a->mean[1], &a->sd[1]);
  mean_sd(a->omega + a->first, m, &a->mean[2], &a->sd[2]);
  a->t1_final = a->t1[nf - 1];
  diffusivity(a, v0, Dr, lag);
  a->msd_beta = msd_beta(&a->msd, t[nf - 1] - t[a->first]);
  a->tau_ngc = afv_autocorr_time(a->ngc_frac + a->first, m, &a->tau_reliable);
  k = nf - 1;
  if (m > 1 && a->tau_ngc < HUGE_VAL)
    a->tau_ngc *= (t[k] - t[a->first]) / (m - 1);
  return AFV_OK;
}

int afv_analyze_ring(afv_analysis *a, const afv_traj *tr, afv_traj_file *f,
                     double l, double v0, double Dr, double steady_from,
                     double lag, long ring_bytes, char *err, size_t errlen)
{
  frame_src src;
  memset(&src, 0, sizeof src);
  src.n = tr ? tr->n : f->n;
  src.nframes = tr ? tr->nframes : f->nframes;
  src.box = tr ? tr->box : f->box;
  src.t = tr ? tr->t : f->t;
  src.mem = tr;
  src.file = f;
  src.err = err;
  src.errlen = errlen;
  return analyze_src(a, &src, l, v0, Dr, steady_from, lag, ring_bytes);
}

int afv_analyze(afv_analysis *a, const afv_traj *tr, double l, double v0,
                double Dr, double steady_from, double lag)
{
  assert(a != NULL && tr != NULL);
  return afv_analyze_ring(a, tr, NULL, l, v0, Dr, steady_from, lag,
                          AFV_ANALYSIS_RING_BYTES, NULL, 0);
}

int afv_analyze_file(afv_analysis *a, afv_traj_file *f, double l, double v0,
                     double Dr, double steady_from, double lag, char *err,
                     size_t errlen)
{
  assert(a != NULL && f != NULL);
  return afv_analyze_ring(a, NULL, f, l, v0, Dr, steady_from, lag,
                          AFV_ANALYSIS_RING_BYTES, err, errlen);
}

/* Bin k holds the sizes 2^k .. 2^(k+1) - 1 (the last bin ends at n): equal
** widths on a log axis, and integer ends, so every size is in exactly one
** bin and the bins' p sum to the distribution's. */
int afv_csd_log_bins(const double *csd, int n, int *lo, int *hi, double *p)
{
  int m = 0, s;
  for (s = 1; s <= n; s++) {
    if ((s & (s - 1)) == 0) {       /* a power of two opens a bin */
      lo[m] = s;
      p[m++] = 0;
    }
    hi[m - 1] = s;
    p[m - 1] += csd[s];
  }
  return m;
}

/* ---- writing the results ------------------------------------------------ */
typedef void (*writer_fn)(FILE *fp, const afv_analysis *a);

/* "inf" for HUGE_VAL and "nan" for NaN (the C library's spelling varies),
** so that summary.txt stays KEY VALUE */
static void put_value(FILE *fp, const char *key, double v)
{
  if (v >= HUGE_VAL) fprintf(fp, "%s inf\n", key);
  else if (isnan(v)) fprintf(fp, "%s nan\n", key);
  else fprintf(fp, "%s %.10g\n", key, v);
}

static void write_summary(FILE *fp, const afv_analysis *a)
{
  static const char *names[3] = {"ngc_frac", "n_clusters", "omega"};
  int k;
  fprintf(fp, "# afv analyze: steady part = frames %d..%d (t >= %.10g)\n",
          a->first, a->nframes - 1, a->t[a->first]);
  fprintf(fp, "cells %d\nframes %d\nsteady_from %.10g\nsteady_to %.10g\n"
          "steady_frames %d\n", a->n, a->nframes, a->t[a->first],
          a->t[a->nframes - 1], a->nframes - a->first);
  for (k = 0; k < 3; k++) {
    fprintf(fp, "%s_mean %.10g\n", names[k], a->mean[k]);
    fprintf(fp, "%s_sd %.10g\n", names[k], a->sd[k]);
  }
  fprintf(fp, "t1_final %.10g\n", a->t1_final);
  put_value(fp, "D_s", a->ds);
  put_value(fp, "D_s_lag", a->ds_lag);
  fprintf(fp, "D_s_origins %ld\n", a->ds_origins);
  put_value(fp, "D_s_plain", a->ds_plain);
  put_value(fp, "D_0", a->d0);
  put_value(fp, "D_eff", a->deff);
  put_value(fp, "tau_NGC", a->tau_ngc);
  fprintf(fp, "tau_NGC_reliable %d\n", a->tau_reliable);
  put_value(fp, "t1_rate", a->t1_rate);
  put_value(fp, "msd_beta", a->msd_beta);
}

static void write_msd(FILE *fp, const afv_analysis *a)
{
  int k;
  fprintf(fp, "lag,msd,msd_rel,lag_frames,samples,msd_se,msd_rel_se\n");
  for (k = 0; k < a->msd.nlags; k++)
    fprintf(fp, "%.10g,%.10g,%.10g,%d,%ld,%.6g,%.6g\n", a->msd.dt[k],
            a->msd.msd[k], a->msd.msd_rel[k], a->msd.lag[k],
            a->msd.samples[k], a->msd.msd_se[k], a->msd.msd_rel_se[k]);
}

static void write_csd(FILE *fp, const afv_analysis *a)
{
  int s;
  fprintf(fp, "n,p\n");
  for (s = 1; s <= a->n; s++)
    if (a->csd[s] > 0) fprintf(fp, "%d,%.10g\n", s, a->csd[s]);
}

static void write_series(FILE *fp, const afv_analysis *a)
{
  int f;
  fprintf(fp, "time,ngc_frac,n_clusters,omega,t1\n");
  for (f = 0; f < a->nframes; f++)
    fprintf(fp, "%.10g,%.10g,%g,%.10g,%g\n", a->t[f], a->ngc_frac[f],
            a->n_clusters[f], a->omega[f], a->t1[f]);
}

/* The log bins of csd.csv (afv_csd_log_bins): n_lo, n_hi, the probability
** of the bin and that probability per size in it (what csd.svg plots). */
static void write_csd_binned(FILE *fp, const afv_analysis *a)
{
  int lo[AFV_CSD_MAX_BINS], hi[AFV_CSD_MAX_BINS], k;
  double p[AFV_CSD_MAX_BINS];
  int m = afv_csd_log_bins(a->csd, a->n, lo, hi, p);
  fprintf(fp, "n_lo,n_hi,p_bin,p_per_n\n");
  for (k = 0; k < m; k++)
    fprintf(fp, "%d,%d,%.10g,%.10g\n", lo[k], hi[k], p[k],
            p[k] / (hi[k] - lo[k] + 1));
}

static int write_one(const char *dir, const char *name, writer_fn fn,
                     const afv_analysis *a, char *err, size_t errlen)
{
  char path[4096], tmp[4200];
  FILE *fp;
  if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path) {
    afv_errorf(err, errlen, "%s: path too long", dir);
    return AFV_EIO;
  }
  fp = afv_atomic_open(path, tmp, sizeof tmp);
  if (!fp) {
    afv_errorf(err, errlen, "%s: cannot create: %s", path, strerror(errno));
    return AFV_EIO;
  }
  fn(fp, a);
  if (afv_atomic_commit(fp, tmp, path) != AFV_OK) {   /* errno: the reason */
    afv_errorf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
    return AFV_EIO;
  }
  return AFV_OK;
}

int afv_analysis_write(const afv_analysis *a, const char *dir, char *err,
                       size_t errlen)
{
  /* summary.txt last: once it is in place, every file is (a sweep's job
  ** counts as done by it, and a job killed before it is run again) */
  static const char *names[] = {"msd.csv", "csd.csv", "csd_binned.csv",
                                "series.csv", "summary.txt"};
  writer_fn fns[5];
  int k, st;
  fns[0] = write_msd; fns[1] = write_csd; fns[2] = write_csd_binned;
  fns[3] = write_series; fns[4] = write_summary;
  for (k = 0; k < 5; k++)
    if ((st = write_one(dir, names[k], fns[k], a, err, errlen)) != AFV_OK)
      return st;
  return AFV_OK;
}
