/*
** substeps.c -- the sub-steps: a step's fast cells moved in pieces.
**
** Not the paper's: its Euler step (dynamics.c) is all there is when no
** cell is fast, which is nearly always.  The exact force is singular as a
** contact breaks, and a cell that one Euler step would throw farther than
** max_move l takes its step in pieces, with the forces of the cells around
** it recomputed between pieces (SUB-STEPS, GROUPS below).  Entry point:
** afv_substeps, called by dynamics.c's advance after every other cell has
** taken its Euler step (afv_internal.h).
*/
#include "afv.h"
#include "afv_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* SUB-STEPS.  The exact force diverges like (2l - d)^(-1/2) as a contact
** is about to break (afv.c, (V1)): one Euler step of dt = 0.01 taken from
** within ~1e-5 l of detachment throws a cell across half its radius.  Over
** one step the polarity n_i is fixed, so the position equation has no noise
** inside the step and may be integrated more finely where it must be.
** The "fast" cells are those the force would move more than max_move l in
** the step.  If there are none -- nearly always -- the step is exactly the
** paper's Euler step.  Otherwise every other cell takes its Euler step, and
** the fast cells alone go on in pieces, group by group (GROUPS, below):
** each piece is the fraction of the time left that moves the fastest cell
** of the group max_move l, and the group's forces are recomputed between
** pieces from the cells around it (REGION_RADIUS), the rest held where
** their Euler step put them; at most AFV_MAX_SUBSTEPS pieces.  The
** singular force pulls the pair back into contact, away from the
** singularity, so one extra piece usually suffices.  Local pieces cost
** O(cells near the fast ones), so a large tissue with many contacts about
** to break does not pay a whole-tissue force evaluation per piece.  As
** max_move goes to 0 the fast cells' motion converges to the exact
** trajectory of the step with the others held (a test shows it); max_move
** bounds the kick a cell gets from landing next to detachment, it does not
** resolve the singularity.  AFV_EUNSTABLE if a force is not finite or a
** cell's whole move in the step exceeds AFV_MAX_STEP_DISP l (the caller then
** restores r_start). */

/* The force on a fast cell i depends on the shapes of i and of its
** neighbours j (closer than 2l), and those on their neighbours k: all
** within 4l of i.  i moves at most AFV_MAX_STEP_DISP l = l/2 in an accepted
** step, so the cells within 4.5 l of its start hold everything its pieces
** need; 5 l leaves a margin. */
#define REGION_RADIUS 5.0

/* GROUPS.  Fast cells closer than REGION_RADIUS to one another, directly
** or through other fast cells, form a group, and each group takes its own
** pieces in its own region.  Every group and its region are listed before
** any fast cell moves, so a region holds no fast cell of another group
** (one closer than REGION_RADIUS would have joined the group).  Two groups
** start at least 5 l apart and each cell moves at most l/2 in an accepted
** step, so a fast cell of one group stays at least 4 l from those of
** another: outside what its force depends on.  A group's motion is then
** that of the group alone, and does not depend on what happens elsewhere
** in the tissue (test_far_groups_step_alone, groups 10 l apart;
** test_near_groups_either_order, groups that end closer than 5 l).  So the
** groups may be moved in any order, or at once by OpenMP threads, each
** with its own work space (afv_group_work): the cells a group writes (its
** fast cells' positions and forces) are read by no other group, whose
** region holds, besides its own fast cells, only cells that have taken
** their whole step already.  One piece length for all the fast cells of
** the tissue would make every fast cell follow the finest pieces of any,
** and every piece recompute every region: the cost per cell would grow
** with N (doc/performance.md). */

/* Lists the fast cells (force move over dt above `split`; move_len holds
** its square, from euler_all) in increasing order; returns how many. */
static int list_fast(afv_sim *s, double split)
{
  double split2 = split * split;
  int i, nf = 0;
  for (i = 0; i < s->n; i++)
    if (s->move_len[i] > split2) s->fast[nf++] = i;
  return nf;
}

/* Moves a[root] down the max-heap a[0 .. n-1] to its place. */
static void sift_down(int *a, int root, int n)
{
  int v = a[root], child;
  while ((child = 2 * root + 1) < n) {
    if (child + 1 < n && a[child + 1] > a[child]) child++;
    if (a[child] <= v) break;
    a[root] = a[child];
    root = child;
  }
  a[root] = v;
}

/* Sorts a[0 .. n-1] increasing, in place: a heapsort, O(n log n) and no
** allocation (glibc 2.36's qsort allocates for 256 ints or more, and a
** step must not allocate once its buffers have grown). */
static void sort_cells(int *a, int n)
{
  int k;
  for (k = n / 2 - 1; k >= 0; k--) sift_down(a, k, n);
  for (k = n - 1; k > 0; k--) {
    int top = a[0];
    a[0] = a[k];
    a[k] = top;
    sift_down(a, 0, k);
  }
}

/* Marks in in_region while the groups are found (all 0 between calls). */
#define IN_REGION  1   /* listed in the region being built */
#define FAST_LEFT  2   /* a fast cell not yet in a group */
#define IN_GROUP   4   /* a fast cell of the group being built */

/* The group of the fast cell `first` (marked FAST_LEFT) and its region
** (GROUPS): the region, the cells within R of a fast cell of the group, in
** increasing order, into s->region; returns how many (the group's fast
** cells are among them).  The group's fast cells, in increasing order, go
** to around[0 .. *ng - 1].  The region list is its own work queue: every
** fast cell in it is expanded (its cells within R listed) once, so the
** group closes over every fast cell within R of one of its own.  Each
** fast cell asks the cell list of the last force evaluation for the
** cells around it (afv_cells_around): O(cells near the group), not O(N).
** Since that evaluation the other cells have moved, each by at most
** `moved` = split + max|v0| dt, and the fast cells not at all. */
static int group_region(afv_sim *s, int first, double R, double moved,
                        int *ng)
{
  int *mark = s->in_region, q, k, nr = 1;
  s->region[0] = first;
  mark[first] |= IN_REGION;
  for (q = 0; q < nr; q++) {
    int f = s->region[q], m;
    if (!(mark[f] & FAST_LEFT)) continue;
    mark[f] = (mark[f] & ~FAST_LEFT) | IN_GROUP;
    m = afv_cells_around(&s->geom, s->r[2*f], s->r[2*f+1], R, moved,
                         s->around);
    for (k = 0; k < m; k++) {
      int j = s->around[k];
      double dx = s->r[2*j] - s->r[2*f], dy = s->r[2*j+1] - s->r[2*f+1];
      if (mark[j] & IN_REGION) continue;
      afv_min_image(&s->box, &dx, &dy);
      if (dx * dx + dy * dy < R * R) {
        mark[j] |= IN_REGION;
        s->region[nr++] = j;
      }
    }
  }
  sort_cells(s->region, nr);
  *ng = 0;
  for (k = 0; k < nr; k++) {
    int j = s->region[k];
    if (mark[j] & IN_GROUP) s->around[(*ng)++] = j;
    mark[j] &= ~(IN_REGION | IN_GROUP);
  }
  return nr;
}

/* Appends the group of the fast cell `first` (group_region) to s->groups;
** `used`: the entries of group_cells taken so far. */
static int add_group(afv_sim *s, int first, double moved, int *used)
{
  afv_group *G;
  int ng, nr = group_region(s, first, REGION_RADIUS * s->par.l, moved, &ng);
  if (afv_grow((void **)&s->groups, &s->cap_groups, s->n_groups + 1,
               sizeof *s->groups) != AFV_OK
      || afv_grow((void **)&s->group_cells, &s->cap_group_cells,
                  *used + nr + ng, sizeof(int)) != AFV_OK)
    return AFV_ENOMEM;
  G = &s->groups[s->n_groups++];
  G->start = *used;
  G->nr = nr;
  G->nf = ng;
  memcpy(s->group_cells + *used, s->region, (size_t)nr * sizeof(int));
  memcpy(s->group_cells + *used + nr, s->around, (size_t)ng * sizeof(int));
  *used += nr + ng;
  return AFV_OK;
}

/* Lists the groups of the nf fast cells (s->fast, increasing) and their
** regions (GROUPS), in the order of their first fast cells, before any
** fast cell moves.  Leaves in_region all 0, also on an error. */
static int find_groups(afv_sim *s, int nf, double moved)
{
  int q, used = 0, st = AFV_OK;
  s->n_groups = 0;
  for (q = 0; q < nf; q++) s->in_region[s->fast[q]] = FAST_LEFT;
  for (q = 0; q < nf && st == AFV_OK; q++)
    if (s->in_region[s->fast[q]] & FAST_LEFT)
      st = add_group(s, s->fast[q], moved, &used);
  for (q = 0; q < nf; q++) s->in_region[s->fast[q]] = 0;
  return st;
}

/* One work space per thread that may move a group (afv_group_work). */
static int reserve_work(afv_sim *s)
{
  int threads = 1, w;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  if (threads <= s->n_work) return AFV_OK;
  w = s->n_work;
  if (afv_grow((void **)&s->work, &w, threads, sizeof *s->work) != AFV_OK)
    return AFV_ENOMEM;
  memset(s->work + s->n_work, 0,
         (size_t)(w - s->n_work) * sizeof *s->work);
  s->n_work = w;
  return AFV_OK;
}

/* The calling thread's work space: a thread number is below the team
** size, at most omp_get_max_threads() as reserve_work read it just
** before. */
static afv_group_work *own_work(afv_sim *s)
{
#ifdef _OPENMP
  return s->work + omp_get_thread_num();
#else
  return s->work;
#endif
}

/* The forces on the group's fast cells, from its region's cells alone (at
** their present positions): exact, since the region holds every cell they
** depend on.  Per-cell parameters are carried over to the region. */
static int region_forces(afv_sim *s, const afv_group *G, afv_group_work *W)
{
  const int *region = s->group_cells + G->start, *fast = region + G->nr;
  int nr = G->nr, q, c, k, st;
  afv_params p = s->par;
  double *sub_r, *sub_f, *col;
  const double *per[4];
  const double **dst[4];
  if (afv_grow((void **)&W->sub, &W->cap_sub, nr, 8 * sizeof(double))
      != AFV_OK)
    return AFV_ENOMEM;
  sub_r = W->sub;
  sub_f = W->sub + 2 * nr;
  col = W->sub + 4 * nr;
  per[0] = s->par.KA_i; per[1] = s->par.KP_i;
  per[2] = s->par.A0_i; per[3] = s->par.P0_i;
  dst[0] = &p.KA_i; dst[1] = &p.KP_i; dst[2] = &p.A0_i; dst[3] = &p.P0_i;
  for (c = 0; c < 4; c++)
    if (per[c]) {
      for (q = 0; q < nr; q++) col[q] = per[c][region[q]];
      *dst[c] = col;
      col += nr;
    }
  for (q = 0; q < nr; q++) {
    sub_r[2*q] = s->r[2 * region[q]];
    sub_r[2*q+1] = s->r[2 * region[q] + 1];
  }
  st = afv_compute(&W->geom, nr, sub_r, &p, &s->box, sub_f);
  if (st != AFV_OK) return st;
  for (k = 0, q = 0; k < G->nf; k++) {   /* both lists are increasing */
    while (region[q] != fast[k]) q++;
    s->f[2 * fast[k]] = sub_f[2*q];
    s->f[2 * fast[k] + 1] = sub_f[2*q+1];
  }
  return AFV_OK;
}

/* The forces on group G's fast cells at the present positions. */
static int piece_forces(afv_sim *s, const afv_group *G, afv_group_work *W)
{
  return region_forces(s, G, W);
}

/* The largest force move of the cells fast[0 .. nf-1] over a time h, or
** NaN at the first cell whose move is NaN (a comparison with a NaN is
** false, so a later finite move would have replaced it). */
static double fastest(const afv_sim *s, const int *fast, int nf, double h,
                      int *cell)
{
  double best = -1;
  int k;
  *cell = nf ? fast[0] : 0;
  for (k = 0; k < nf; k++) {
    int i = fast[k];
    double m = h * s->dyn.mu * hypot(s->f[2*i], s->f[2*i+1]);
    if (isnan(m)) {
      *cell = i;
      return m;
    }
    if (m > best) {
      best = m;
      *cell = i;
    }
  }
  return best;
}

/* Moves group G's fast cells over the time dt in pieces (the other cells
** have moved), with the work space W; sets G's status and pieces. */
static void fast_pieces(afv_sim *s, afv_group *G, afv_group_work *W,
                        double split, double dt)
{
  const int *fast = s->group_cells + G->start + G->nr;
  double left = dt;
  int piece, cell;
  G->pieces = 0;
  G->status = AFV_OK;
  W->geom.cand_n = 0;          /* a new region: no Verlet candidates yet */
  for (piece = 1;; piece++) {
    double h = left, len = fastest(s, fast, G->nf, left, &cell);
    /* an infinite move too: its piece, left split / len, would be 0 long,
    ** and the cell would move by 0 inf = NaN */
    if (!isfinite(len)) {
      G->status = AFV_EUNSTABLE;
      G->bad_cell = cell;
      G->bad_len = len;
      return;
    }
    if (len > split && piece < AFV_MAX_SUBSTEPS) h = left * (split / len);
    afv_move_cells(s, fast, G->nf, h);
    if (h == left) return;
    G->pieces++;
    left -= h;
    if ((G->status = piece_forces(s, G, W)) != AFV_OK) return;
  }
}

/* A group whose region has AFV_PARALLEL_MIN cells or more is moved on the
** calling thread alone, so that its region's force evaluations run their
** own parallel loops; the smaller groups are shared among the threads,
** unless there is only one, which is moved outside any parallel region.
** (Inside the task loop, a large region's loops would be nested parallel
** regions, and libgomp starts a new team of threads for each.) */
static int is_large(const afv_group *G)
{
  return G->nr >= AFV_PARALLEL_MIN;
}

/* The nf fast cells (s->fast) moved over dt, group by group (GROUPS): on
** the calling thread the large groups (and a single small one), then the
** small groups at once on OpenMP threads.  The groups are independent, so
** the order changes no bit; any error reported is that of the first group
** (in the order of find_groups) that failed. */
static int move_fast_cells(afv_sim *s, int nf, double split, double moved,
                           double dt)
{
  int g, st, small = 0;
  if ((st = find_groups(s, nf, moved)) != AFV_OK
      || (st = reserve_work(s)) != AFV_OK)
    return st;
  for (g = 0; g < s->n_groups; g++) small += !is_large(&s->groups[g]);
  for (g = 0; g < s->n_groups; g++)
    if (is_large(&s->groups[g]) || small == 1)
      fast_pieces(s, &s->groups[g], own_work(s), split, dt);
  if (small > 1) {
    AFV_PARALLEL_TASKS
    for (g = 0; g < s->n_groups; g++)
      if (!is_large(&s->groups[g]))
        fast_pieces(s, &s->groups[g], own_work(s), split, dt);
  }
  for (g = 0; g < s->n_groups; g++) {
    const afv_group *G = &s->groups[g];
    s->substeps += G->pieces;
    if (G->status == AFV_EUNSTABLE)
      return afv_unstable(s, G->bad_cell, G->bad_len);
    if (G->status != AFV_OK) return G->status;
  }
  return AFV_OK;
}

int afv_substeps(afv_sim *s, double split, double moved, double dt, int *nf)
{
  *nf = list_fast(s, split);
  return *nf > 0 ? move_fast_cells(s, *nf, split, moved, dt) : AFV_OK;
}
