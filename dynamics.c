/*
** dynamics.c -- active Brownian dynamics, relaxation, initial states, noise.
**
** Equation of motion (paper, Sec. Model), integrated by Euler-Maruyama:
**     r_i  <- r_i + dt (mu F_i + v0_i n_i),      n_i = (cos th_i, sin th_i)
**     th_i <- th_i + sqrt(2 Dr_i dt) xi_i,       xi_i ~ N(0, 1)
**     F    <- -grad E at the new r.
** Both updates use the state at the start of the step (Ito).  Positions stay
** unwrapped, so r_i(t) - r_i(0) is the true displacement (for the MSD); the
** geometry applies the minimum image itself.
**
** Invariant of afv_sim between calls: f, geom and geom.energy describe r.
**
** RANDOM NUMBERS.  Philox4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel
** random numbers: as easy as 1, 2, 3", SC'11), a counter-based generator:
** each output is a keyed bijection of a 128-bit counter, with no state to
** carry.  The normals of cells 2k and 2k + 1 at step s are drawn from the
** counter (k, s mod 2^32, s div 2^32, purpose) under the key seed.  So a
** run depends only on (seed, parameters): not on the order in which cells
** are visited (any number of threads gives the same bits), and a resumed
** run needs only the step count to continue the same streams.  Philox
** passes BigCrush and costs 10 multiply rounds.
** Normals come from the Box-Muller transform, both branches (cosine for
** the even cell of the pair, sine for the odd): it is exact, one counter
** gives two independent normals, so the generator, the log and the sincos
** are paid once per two cells (they were an eighth of a step's
** instructions with one counter per cell), and it takes a fixed number of
** uniforms per normal, so each (pair, step) uses exactly one counter; a
** rejection method (polar, ziggurat) would need a variable number and
** break the one-counter-per-draw bookkeeping.  The uniforms have 53 random
** bits and lie in (0, 1], so log(u) is finite and
** |xi| <= sqrt(2 * 53 ln 2) = 8.57.  Bit-for-bit equality across machines
** relies on the C library's log returning the same bits (cos and sin are
** afv_sincos's own arithmetic).
*/
#include "afv.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define TWO_PI 6.28318530717958647692

/* OpenMP (make OPENMP=1, see geom.c): the per-cell loops of a step touch
** only their own cell, the noise is drawn per (cell, step), and the only
** reductions are a maximum and an or, so every thread count gives the same
** bits.  The macros are in afv.h; empty in the plain C99 build. */

/* ---- sine and cosine ---------------------------------------------------- */
/* Every step needs cos and sin of every cell's angle (the polarity) and of
** one Box-Muller angle per two cells: the C library's sincos took about 130
** instructions a call, 200 per cell and step (callgrind), a sixth of a
** step.  afv_sincos takes about 70, in plain arithmetic without branches:
**   1. reduction: x = k pi/2 + r with k the integer nearest x (2/pi) (to
**      within 2^-32), so |r| <= pi/4 (1 + 2^-30);  r = x - k P1 - k P2 -
**      k P3, where P1 + P2 + P3 = pi/2 to about 2^-150 (fdlibm's split:
**      P1 and P2 have 33 significant bits, so k P1 and k P2 are exact for
**      |k| < 2^20, and x - k P1 is exact by Sterbenz' lemma); the error of
**      r is an ulp of r;
**   2. Taylor series on [-pi/4, pi/4]: sin to the term r^17/17!, cos to
**      r^16/16!; the first term left out is below (pi/4)^18/18! = 2e-18;
**   3. the quadrant k mod 4 picks +-sin r or +-cos r, as the sum
**      a sin r + b cos r with a, b in {-1, 0, 1} from a table: exact, and
**      free of a branch that a random quadrant would mispredict.
** Measured against the C library (test_dynamics.c): within 2.22e-16.
** |x| >= SINCOS_FAST_LIMIT (k would not fit the split), inf and NaN go to
** the C library. */
#define SINCOS_FAST_LIMIT 1e6
#define PIO2_1 1.57079632673412561417e+00   /* first 33 bits of pi/2 */
#define PIO2_2 6.07710050630396597660e-11   /* next 33 bits */
#define PIO2_3 2.02226624879595063154e-21   /* the rest */

void afv_sincos(double x, double *sin_x, double *cos_x)
{
  static const double sa[5] = {1, 0, -1, 0, 1}, sb[5] = {0, 1, 0, -1, 0};
  double t, r, z, sr, cr;
  long m, k;
  unsigned q;
  /* the C library's also in the reference build (make REFERENCE=1) */
  if (AFV_REFERENCE_MODE || !(fabs(x) < SINCOS_FAST_LIMIT)) {
    *sin_x = sin(x);
    *cos_x = cos(x);
    return;
  }
  /* k = floor(x (2/pi) + 1/2), as m - 2^20 with m = (long)(positive): no
  ** branch on the sign of x (truncation of a negative value rounds up) */
  t = x * 0.63661977236758134308 + (0.5 + 1048576.0);
  m = (long)t;
  k = m - 1048576;
  r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
  z = r * r;
  sr = r + r * z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040
       + z * (1.0 / 362880 + z * (-1.0 / 39916800 + z * (1.0 / 6227020800.0
       + z * (-1.0 / 1307674368000.0 + z * (1.0 / 355687428096000.0))))))));
  cr = 1 + z * (-0.5 + z * (1.0 / 24 + z * (-1.0 / 720 + z * (1.0 / 40320
       + z * (-1.0 / 3628800 + z * (1.0 / 479001600.0
       + z * (-1.0 / 87178291200.0 + z * (1.0 / 20922789888000.0))))))));
  q = (unsigned)m & 3u;                      /* k mod 4 */
  /* sin(r + q pi/2) = sin r, cos r, -sin r, -cos r for q = 0..3, and
  ** cos(r + q pi/2) = sin(r + (q + 1) pi/2) */
  *sin_x = sa[q] * sr + sb[q] * cr;
  *cos_x = sa[q + 1] * sr + sb[q + 1] * cr;
}

/* ---- Philox4x32-10 ----------------------------------------------------- */
/* Multipliers and Weyl key increments from Random123 (philox.h). */
#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u  /* golden ratio */
#define PHILOX_W1 0xBB67AE85u  /* sqrt(3) - 1 */
#define PHILOX_ROUNDS 10

void afv_philox4x32(const uint32_t ctr[4], const uint32_t key[2],
                    uint32_t out[4])
{
  uint32_t c0 = ctr[0], c1 = ctr[1], c2 = ctr[2], c3 = ctr[3];
  uint32_t k0 = key[0], k1 = key[1];
  int round;
  for (round = 0; round < PHILOX_ROUNDS; round++) {
    uint64_t p0 = (uint64_t)PHILOX_M0 * c0, p1 = (uint64_t)PHILOX_M1 * c2;
    c0 = (uint32_t)(p1 >> 32) ^ c1 ^ k0;
    c1 = (uint32_t)p1;
    c2 = (uint32_t)(p0 >> 32) ^ c3 ^ k1;
    c3 = (uint32_t)p0;
    k0 += PHILOX_W0;          /* the key is bumped between rounds (the bump */
    k1 += PHILOX_W1;          /* after the last is unused: no branch) */
  }
  out[0] = c0; out[1] = c1; out[2] = c2; out[3] = c3;
}

/* 53 bits from two words -> (0, 1]: (k + 1) 2^-53, k in [0, 2^53). */
static double unit53(uint32_t hi, uint32_t lo)
{
  double k = (double)(hi >> 5) * 67108864.0 + (double)(lo >> 6);
  return (k + 1.0) * (1.0 / 9007199254740992.0);
}

void afv_rng_uniform2(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose, double u[2])
{
  uint32_t ctr[4], key[2], out[4];
  ctr[0] = cell;
  ctr[1] = (uint32_t)(step & 0xffffffffu);
  ctr[2] = (uint32_t)(step >> 32);
  ctr[3] = (uint32_t)purpose;
  key[0] = (uint32_t)(seed & 0xffffffffu);
  key[1] = (uint32_t)(seed >> 32);
  afv_philox4x32(ctr, key, out);
  u[0] = unit53(out[0], out[1]);
  u[1] = unit53(out[2], out[3]);
}

/* Box-Muller: two independent standard normals from two uniforms in (0, 1]
** (u[0] = 1 gives rho = 0; u[0] > 0 keeps the log finite). */
static void box_muller(const double u[2], double z[2])
{
  double rho = sqrt(-2.0 * log(u[0])), c, sn;
  afv_sincos(TWO_PI * u[1], &sn, &c);
  z[0] = rho * c;
  z[1] = rho * sn;
}

void afv_rng_normal2(unsigned long long seed, uint32_t pair,
                     unsigned long long step, unsigned purpose, double z[2])
{
  double u[2];
  afv_rng_uniform2(seed, pair, step, purpose, u);
  box_muller(u, z);
}

double afv_rng_normal(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose)
{
  double z[2];
  afv_rng_normal2(seed, cell / 2, step, purpose, z);
  return z[cell % 2];
}

/* ---- the simulation ---------------------------------------------------- */
void afv_dyn_default(afv_dyn *d)
{
  memset(d, 0, sizeof *d);
  d->mu = 1;
  d->v0 = 0;
  d->Dr = 0.1;
  d->dt = 0.01;
  d->max_move = 0.05;
  d->seed = 1;
}

static int dyn_check(const afv_dyn *d, int n)
{
  int i;
  if (!(isfinite(d->max_move) && d->max_move >= 0)) return AFV_EINVAL;
  if (!(isfinite(d->mu) && d->mu > 0 && isfinite(d->dt) && d->dt > 0
        && isfinite(d->v0) && isfinite(d->Dr) && d->Dr >= 0))
    return AFV_EINVAL;
  for (i = 0; i < n; i++) {
    if (d->v0_i && !isfinite(d->v0_i[i])) return AFV_EINVAL;
    if (d->Dr_i && !(isfinite(d->Dr_i[i]) && d->Dr_i[i] >= 0))
      return AFV_EINVAL;
  }
  return AFV_OK;
}

/* Copies a caller's per-cell array into *next (advancing it), or NULL. */
static const double *own_copy(const double *src, int n, double **next)
{
  double *dst = *next;
  if (!src) return NULL;
  memcpy(dst, src, (size_t)n * sizeof(double));
  *next += n;
  return dst;
}

void afv_sim_free(afv_sim *s)
{
  int w;
  afv_geom_free(&s->geom);
  for (w = 0; w < s->n_work; w++) {
    afv_geom_free(&s->work[w].geom);
    free(s->work[w].sub);
  }
  free(s->work);
  free(s->groups);
  free(s->group_cells);
  free(s->own);
  free(s->iown);
  memset(s, 0, sizeof *s);
}

int afv_sim_init(afv_sim *s, int n, const double *r, const double *theta,
                 const afv_params *p, const afv_box *b, const afv_dyn *d)
{
  double *next;
  int st;
  afv_sim_free(s);
  if (n < 0 || dyn_check(d, n) != AFV_OK) return AFV_EINVAL;
  /* r, f, r_start, pol (2n each), theta, move_len (n each), six optional
  ** per-cell arrays (n each), r_step (2n) */
  s->own = malloc((size_t)(18 * n + 1) * sizeof(double));
  /* fast cells, region, in_region, around (n each) */
  s->iown = calloc((size_t)(4 * n + 1), sizeof(int));
  if (!s->own || !s->iown) {
    afv_sim_free(s);
    return AFV_ENOMEM;
  }
  s->fast = s->iown;
  s->region = s->iown + n;
  s->in_region = s->iown + 2 * n;
  s->around = s->iown + 3 * n;
  s->n = n;
  s->r = s->own;
  s->f = s->own + 2 * n;
  s->theta = s->own + 4 * n;
  s->r_start = s->own + 5 * n;
  s->move_len = s->own + 7 * n;
  s->pol = s->own + 8 * n;
  s->r_step = s->own + 16 * n;
  next = s->own + 10 * n;
  memcpy(s->r, r, (size_t)(2 * n) * sizeof(double));
  if (theta) memcpy(s->theta, theta, (size_t)n * sizeof(double));
  else memset(s->theta, 0, (size_t)n * sizeof(double));
  s->par = *p;
  s->par.KA_i = own_copy(p->KA_i, n, &next);
  s->par.KP_i = own_copy(p->KP_i, n, &next);
  s->par.A0_i = own_copy(p->A0_i, n, &next);
  s->par.P0_i = own_copy(p->P0_i, n, &next);
  s->dyn = *d;
  s->dyn.v0_i = own_copy(d->v0_i, n, &next);
  s->dyn.Dr_i = own_copy(d->Dr_i, n, &next);
  s->box = b ? *b : s->box;
  s->step = 0;
  s->t = 0;
  s->substeps = 0;
  s->halvings = 0;
  s->bad_time = 0;
  s->bad_cell = -1;
  s->bad_disp = 0;
  st = afv_compute(&s->geom, n, s->r, &s->par, &s->box, s->f);
  if (st != AFV_OK) {
    int bad_i = s->geom.bad_i, bad_j = s->geom.bad_j;  /* the cells named */
    afv_sim_free(s);
    s->geom.bad_i = bad_i;
    s->geom.bad_j = bad_j;
  }
  return st;
}

int afv_sim_refresh(afv_sim *s)
{
  if (afv_params_check(&s->par, s->n) != AFV_OK
      || dyn_check(&s->dyn, s->n) != AFV_OK)
    return AFV_EINVAL;
  /* the one cache of a step that depends on par, box and r: f and geom */
  return afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
}

double afv_sim_max_force(const afv_sim *s)
{
  double m2 = 0;
  int i;
  for (i = 0; i < s->n; i++) {
    double q = s->f[2*i] * s->f[2*i] + s->f[2*i+1] * s->f[2*i+1];
    if (!(q <= m2)) m2 = q;   /* a NaN wins, so it is seen */
  }
  return sqrt(m2);
}

/* Displacement of cell i over a time h: h (mu F_i + v0_i n_i); needs pol
** for this step (euler_all). */
static void move_of(const afv_sim *s, int i, double h, double *dx, double *dy)
{
  double mu = s->dyn.mu;
  *dx = h * (mu * s->f[2*i] + s->pol[2*i]);
  *dy = h * (mu * s->f[2*i+1] + s->pol[2*i+1]);
}

/* The first i with m[i] equal to `largest` (NaN if `largest` is NaN), for
** the report of a refused step: serial, and off the common path. */
static int first_at(const double *m, int n, double largest)
{
  int i;
  for (i = 0; i < n; i++)
    if (m[i] == largest || (isnan(m[i]) && isnan(largest))) return i;
  return 0;
}

/* The largest squared distance of a cell from its position at the start
** of the step (NaN if one is NaN); the squares stay in move_len. */
static double farthest_from_start(afv_sim *s)
{
  double *m = s->move_len, most = 0;
  int i, nan = 0;
  AFV_PARALLEL_REDUCE(s->n, reduction(max: most) reduction(|: nan))
  for (i = 0; i < s->n; i++) {
    double dx = s->r[2*i] - s->r_start[2*i];
    double dy = s->r[2*i+1] - s->r_start[2*i+1];
    m[i] = dx * dx + dy * dy;
    if (isnan(m[i])) nan = 1;
    else if (m[i] > most) most = m[i];
  }
  return nan ? NAN : most;
}

static int unstable(afv_sim *s, int cell, double len)
{
  s->bad_cell = cell;
  s->bad_disp = len / s->par.l;
  return AFV_EUNSTABLE;
}

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
** the tissue, as before, made every fast cell follow the finest pieces of
** any: with more fast cells the pieces per step grew, and every piece
** recomputed every region -- in the random
** benchmark state (steps 20 - 220) 0.015 region cells per cell and step at
** N = 400 but 0.034 at N = 400000; by groups 0.014 - 0.015 at every N. */

/* Moves the m cells of list by h. */
static void move_cells(afv_sim *s, const int *list, int m, double h)
{
  int k;
  AFV_PARALLEL_FOR(m)
  for (k = 0; k < m; k++) {
    int i = list[k];
    double dx, dy;
    move_of(s, i, h, &dx, &dy);
    s->r[2*i] += dx;
    s->r[2*i+1] += dy;
  }
}

/* The step's one pass over every cell (each cell's data read once):
**   r_start_i = r_i;
**   pol_i = v0_i n_i = v0_i (cos theta_i, sin theta_i), fixed during the
**     step (sub-steps included), so computed once here, not in each move_of;
**   move_len_i = |dt mu F_i|^2, the square of the force-driven move;
**   the paper's Euler step of dt, for every cell whose force-driven move
**     is at most `split` (every cell if split <= 0); the others are the
**     fast cells (SUB-STEPS, below).
** Returns the largest move_len_i: NaN if a force is NaN (the cells have
** then moved, and the refused step restores r_start).  Squares order the
** cells as the lengths do, and save a hypot per cell (a square that
** overflows to inf still counts as fast). */
static double euler_all(afv_sim *s, double split, double dt)
{
  /* locals, not s->...: the stores through r could alias the struct */
  double *r = s->r, *r_start = s->r_start, *pol = s->pol, *m = s->move_len;
  const double *f = s->f, *theta = s->theta, *v0_i = s->dyn.v0_i;
  double split2 = split > 0 ? split * split : INFINITY, most = 0;
  double hmu = dt * s->dyn.mu, v0 = s->dyn.v0;
  int i, n = s->n, nan = 0;
  AFV_PARALLEL_REDUCE(n, reduction(max: most) reduction(|: nan))
  for (i = 0; i < n; i++) {
    double fx = f[2*i], fy = f[2*i+1], x = r[2*i], y = r[2*i+1];
    double v = v0_i ? v0_i[i] : v0, c, sn, px, py, mx, my, move2;
    afv_sincos(theta[i], &sn, &c);
    px = v * c;
    py = v * sn;
    mx = hmu * fx;
    my = hmu * fy;
    move2 = mx * mx + my * my;
    r_start[2*i] = x;
    r_start[2*i+1] = y;
    pol[2*i] = px;
    pol[2*i+1] = py;
    m[i] = move2;
    if (isnan(move2)) nan = 1;
    else if (move2 > most) most = move2;
    if (!(move2 > split2)) {
      double dx, dy;
      move_of(s, i, dt, &dx, &dy);
      r[2*i] = x + dx;
      r[2*i+1] = y + dy;
    }
  }
  return nan ? NAN : most;
}

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
    move_cells(s, fast, G->nf, h);
    if (h == left) return;
    G->pieces++;
    left -= h;
    if ((G->status = region_forces(s, G, W)) != AFV_OK) return;
  }
}

/* A group whose region has AFV_PARALLEL_MIN cells or more is moved on the
** calling thread alone, so that its region's force evaluations run their
** own parallel loops; the smaller groups are shared among the threads,
** unless there is only one, which is moved outside any parallel region.
** (Inside the task loop, a large region's loops would be nested parallel
** regions, and libgomp starts a new team of threads for each: thousands of
** thread creations in 50 steps of a tissue where one group spread over
** most of it.) */
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
      return unstable(s, G->bad_cell, G->bad_len);
    if (G->status != AFV_OK) return G->status;
  }
  return AFV_OK;
}

/* The moves of a time dt (the step's, or a part of it: HALVES), v0_max =
** max |v0_i| (from too_fast). */
static int advance(afv_sim *s, double v0_max, double dt)
{
  double split = s->dyn.max_move * s->par.l, most = euler_all(s, split, dt);
  double limit = AFV_MAX_STEP_DISP * s->par.l;
  int nf = 0, st;
  s->n_groups = 0;
  if (isnan(most))
    return unstable(s, first_at(s->move_len, s->n, most), most);
  if (split > 0 && most > split * split) nf = list_fast(s, split);
  if (nf > 0
      && (st = move_fast_cells(s, nf, split, split + v0_max * dt, dt))
         != AFV_OK)
    return st;
  /* Without fast cells every move is at most split + |v0_i| dt: when that
  ** cannot exceed the limit, the scan of all the moves is skipped. */
  if (nf > 0 || !(split > 0 && split + v0_max * dt <= limit)) {
    double far2 = farthest_from_start(s), far = sqrt(far2);
    if (!(far <= limit))
      return unstable(s, first_at(s->move_len, s->n, far2), far);
  }
  return afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
}

/* Puts every cell back at r0 and recomputes the forces there. */
static void back_to(afv_sim *s, const double *r0)
{
  size_t bytes = (size_t)(2 * s->n) * sizeof(double);
  if (memcmp(r0, s->r, bytes) != 0) {
    memcpy(s->r, r0, bytes);
    afv_compute(&s->geom, s->n, s->r, &s->par, &s->box, s->f);
  }
}

/* HALVES.  A time dt whose moves carry some cell farther than
** AFV_MAX_STEP_DISP l (sub-steps included) is not refused when sub-steps
** are on (max_move > 0): it is taken again from its start as two halves,
** each of which may be halved in turn, down to dt / 2^AFV_MAX_HALVINGS.
** Such a move is physics, not a fault: a cell pushed by a force of 50 or
** more for a whole step (two centres that start nearly on top of each
** other in a random start, or a cell leaving a kink of E while its
** neighbours rearrange) travels that far in dt = 0.01, and the halves
** follow it, where a single step left the range in which Euler's method
** and the sub-steps' regions (REGION_RADIUS) are valid.  Each half keeps
** the rule (no cell moves more than l/2 in it), so everything the
** sub-steps rely on holds inside it.  The polarity and the noise are
** unchanged: the noise is drawn once, after the whole step.  The bound
** keeps a step's cost finite: at most 2^AFV_MAX_HALVINGS parts, each with
** at most AFV_MAX_SUBSTEPS pieces.  A force that moves a cell l/2 in
** dt / 2^AFV_MAX_HALVINGS (|F| above 0.5 * 256 / 0.01 = 12800 for a whole
** part, at the paper's dt) is refused: it means a parameter far too stiff
** for dt (KA = 1e5, say), not a contact about to break (whose pieces pull
** it back within max_move l).  Without sub-steps (max_move = 0, plain
** Euler) the step is refused as before.  The first refused part saves the
** step's start in r_step (r_start then moves on with the parts), so a
** refused step still leaves the state as it was. */
static int advance_in_halves(afv_sim *s, double v0_max, double dt, int depth)
{
  int st = advance(s, v0_max, dt);
  s->bad_time = dt;
  if (st != AFV_EUNSTABLE || !isfinite(s->bad_disp)
      || s->dyn.max_move <= 0 || depth >= AFV_MAX_HALVINGS)
    return st;
  if (depth == 0)
    memcpy(s->r_step, s->r_start, (size_t)(2 * s->n) * sizeof(double));
  back_to(s, s->r_start);
  s->halvings++;
  if ((st = advance_in_halves(s, v0_max, dt / 2, depth + 1)) != AFV_OK)
    return st;
  return advance_in_halves(s, v0_max, dt / 2, depth + 1);
}

/* Self-propulsion alone moves cell i by v0_i dt in a step, sub-steps or
** not: a step where that exceeds AFV_MAX_STEP_DISP l is refused.  Sets
** *v0_max = max |v0_i|. */
static int too_fast(afv_sim *s, double *v0_max)
{
  int i, n = s->dyn.v0_i ? s->n : 1;
  *v0_max = 0;
  for (i = 0; i < n; i++) {
    double v0 = s->dyn.v0_i ? fabs(s->dyn.v0_i[i]) : fabs(s->dyn.v0);
    if (v0 * s->dyn.dt > AFV_MAX_STEP_DISP * s->par.l)
      return unstable(s, i, v0 * s->dyn.dt);
    if (v0 > *v0_max) *v0_max = v0;
  }
  return AFV_OK;
}

/* The rotational noise of cells 2 p and 2 p + 1 (if it exists) for the
** pairs p of [first, first + m), m <= NOISE_BLOCK: the two normals of pair
** p (afv_rng_normal2, the same bits).  All the block's uniforms are drawn
** before any is turned into normals: a pair's draw is one long chain of
** dependent operations (Philox's ten rounds, then a log and a sine), too
** long for the processor to overlap with the next pair's within one loop
** iteration; in two loops each chain is half as long.  (perf: the noise
** and polarity took about a tenth of the N = 400 cluster's step, more
** than their share of its instructions; in blocks the step measured 2.4%
** faster, with the same bits.) */
#define NOISE_BLOCK 32

static void rotate_block(afv_sim *s, int first, int m, unsigned long long seed,
                         unsigned long long step)
{
  double u[2 * NOISE_BLOCK];
  int q, k;
  for (q = 0; q < m; q++)
    afv_rng_uniform2(seed, (uint32_t)(first + q), step, AFV_RNG_NOISE,
                     u + 2 * q);
  for (q = 0; q < m; q++) {
    int i = 2 * (first + q);
    double z[2];
    box_muller(u + 2 * q, z);
    for (k = 0; k < 2 && i + k < s->n; k++) {
      double Dr = s->dyn.Dr_i ? s->dyn.Dr_i[i + k] : s->dyn.Dr;
      if (Dr > 0) s->theta[i + k] += sqrt(2 * Dr * s->dyn.dt) * z[k];
    }
  }
}

/* The reference twin of the noise (make REFERENCE=1), one plain loop over
** the cells: th_i <- th_i + sqrt(2 Dr_i dt) xi_i (paper, Eq. abp), xi_i the
** normal of cell i at this step (afv_rng_normal: the draw of rotate_block,
** which gets the two normals of a pair from one counter). */
static void rotate_plain(afv_sim *s, unsigned long long seed,
                         unsigned long long step)
{
  int i;
  for (i = 0; i < s->n; i++) {
    double Dr = s->dyn.Dr_i ? s->dyn.Dr_i[i] : s->dyn.Dr;
    double xi = afv_rng_normal(seed, (uint32_t)i, step, AFV_RNG_NOISE);
    if (Dr > 0) s->theta[i] += sqrt(2 * Dr * s->dyn.dt) * xi;
  }
}

int afv_sim_step(afv_sim *s)
{
  unsigned long long seed = s->dyn.seed, step = (unsigned long long)s->step;
  long long substeps = s->substeps, halvings = s->halvings;
  double v0_max;
  int i, pairs, st;
  s->bad_time = s->dyn.dt;
  if ((st = too_fast(s, &v0_max)) != AFV_OK) return st;
  if ((st = advance_in_halves(s, v0_max, s->dyn.dt, 0)) != AFV_OK) {
    /* a refused step leaves the state as it was, sub-steps included */
    back_to(s, s->halvings > halvings ? s->r_step : s->r_start);
    s->substeps = substeps;
    s->halvings = halvings;
    return st;
  }
  if (AFV_REFERENCE_MODE) {
    rotate_plain(s, seed, step);
  } else {
    pairs = (s->n + 1) / 2;        /* cells 2p and 2p + 1 share one draw */
    AFV_PARALLEL_FOR(s->n)
    for (i = 0; i < pairs; i += NOISE_BLOCK)
      rotate_block(s, i, pairs - i < NOISE_BLOCK ? pairs - i : NOISE_BLOCK,
                   seed, step);
  }
  s->step++;
  s->t = (double)s->step * s->dyn.dt;   /* no drift from summing dt */
  return AFV_OK;
}

/* ---- relaxation (overdamped flow at v0 = 0) ----------------------------- */
/* RELAXATION.  The paper relaxes its start "at zero temperature" before it
** switches v0 on: the equation of motion with v0 = 0, dr_i/dt = mu F_i,
** by Euler steps of dt (the authors' code: 30 time units of them).  That
** is what afv_relax does, step after step, with the sub-steps and halves
** of afv_sim_step (the same code, polarity and noise off), until
**   max_i |F_i| <= tol                                   (converged), or
**   a kink of E is reached (at_kink, below), or max_iter steps.
** Why this and not a global minimiser: every cell moves by its own force,
** so a cell sitting at a kink of E (where the force jumps and does not
** vanish) only chatters across it, by about dt mu |F| ~ 0.01 l, while
** every other cell goes on relaxing.  The FIRE minimiser used before
** accepted or undid a trial move of the whole tissue by the change of the
** total energy; near one kink every trial move raised E, so it undid the
** moves of all cells and stopped with max |F| of 84 to 1035 and the
** tissue nowhere near relaxed (the authors' random start at N = 400,
** phi = 0.5, P0 = 4 to 8: mean area 0.75 where the relaxed tissue has
** 1.8).  The flow is slower near a smooth minimum than FIRE (linear
** convergence), but from that start it reaches max |F| <= 1e-6 in about
** 10^4 steps at P0 = 4 and 8.8 (measured), far below the default limit.
**
** KINKS.  E has a kink wherever a triple junction crosses a cell's circle
** (a gap opens or closes), and above P0* ~ 5.7 relaxed tissues sit on
** such kinks: the flow then ends chattering, max |F| stays at the one-sided
** force (about 2 at P0 = 6, measured) and never reaches tol.  What shows
** a genuine kink, measured over windows of AFV_RELAX_WINDOW steps:
**   drift: every cell's mean force over the window, its displacement
**     over the window / (window time mu), is at most AFV_RELAX_KINK_DRIFT
**     (a chattering cell goes back and forth; a cell still sliding down a
**     slope, however slowly, drifts);
**   chatter: that drift is at most AFV_RELAX_KINK_CHATTER max_i |F_i|: the
**     forces cancel over the window, as across a kink (measured at
**     P0 = 6: drift 5e-5 against max |F| 2).  Near a smooth minimum the
**     force decays steadily, so the window's mean force is larger than
**     the force at its end, not a tenth of it: that convergence goes on
**     to tol (at P0 = 4 the drift fell below 1e-3 while max |F| was still
**     2e-4, a few thousand steps before max |F| <= 1e-6);
**   drop: the window's mean energy fell by at most AFV_RELAX_KINK_DROP
**     sum_i |e_i| since the previous window;
**   force: max_i |F_i| <= AFV_RELAX_KINK_FORCE (the one-sided forces of a
**     kink are of order 1; a larger force is not a kink but a tissue still
**     moving, or a contact about to break).
** All three must hold at the end of a window.  Otherwise the flow goes
** on, up to max_iter steps: then neither flag is set, and the report
** holds the figures. */

/* sum_i |e_i|: the scale of the rounding error of E. */
static double energy_scale(const afv_sim *s)
{
  const afv_geom *g = &s->geom;
  double sum = 0;
  int i;
  for (i = 0; i < s->n; i++)
    sum += fabs(afv_cell_energy(&s->par, i, g->area[i], g->perim[i],
                                g->arc[i]));
  return sum;
}

/* Adds every cell's position to sum (2n). */
static void add_positions(const afv_sim *s, double *sum)
{
  int k;
  for (k = 0; k < 2 * s->n; k++) sum[k] += s->r[k];
}

/* max_i |a_i - b_i| / m, a and b sums of m positions (unwrapped, so a
** plain difference): the largest move of a cell's mean position. */
static double largest_mean_move(int n, const double *a, const double *b,
                                long m)
{
  double most = 0;
  int i;
  for (i = 0; i < n; i++) {
    double d = hypot(a[2*i] - b[2*i], a[2*i+1] - b[2*i+1]) / (double)m;
    if (!(d <= most)) most = d;
  }
  return most;
}

/* One step of the flow, or a refusal with the state unchanged (as
** afv_sim_step, whose moves it shares). */
static int flow_step(afv_sim *s, double dt)
{
  long long substeps = s->substeps, halvings = s->halvings;
  int st;
  s->bad_time = dt;
  if ((st = advance_in_halves(s, 0, dt, 0)) != AFV_OK) {
    back_to(s, s->halvings > halvings ? s->r_step : s->r_start);
    s->substeps = substeps;
    s->halvings = halvings;
  }
  return st;
}

/* The relaxation's running sums over the present and the previous window:
** positions (2n each) and energy. */
typedef struct window {
  double *r_sum, *r_sum_prev;
  double E_sum, E_sum_prev;
  int full;            /* complete windows so far */
} window;

/* The end of a window: sets rep's drift and drop (from the window's mean
** positions and energy against the previous window's, which cancels the
** chatter at kinks); 1 if they and max |F| show a kink. */
static int window_shows_kink(const afv_sim *s, afv_relax_report *rep,
                             window *W, double scale)
{
  long K = AFV_RELAX_WINDOW;
  double time = (double)K * s->dyn.dt * s->dyn.mu, *t;
  int kink = 0;
  if (W->full++ > 0) {
    rep->drift = largest_mean_move(s->n, W->r_sum, W->r_sum_prev, K) / time;
    rep->drop = (W->E_sum_prev - W->E_sum) / (double)K / scale;
    kink = rep->drift <= AFV_RELAX_KINK_DRIFT
           && rep->drift <= AFV_RELAX_KINK_CHATTER * rep->max_force
           && fabs(rep->drop) <= AFV_RELAX_KINK_DROP
           && rep->max_force <= AFV_RELAX_KINK_FORCE;
  }
  t = W->r_sum_prev;                   /* this window becomes the previous */
  W->r_sum_prev = W->r_sum;
  W->r_sum = t;
  memset(W->r_sum, 0, (size_t)(2 * s->n) * sizeof(double));
  W->E_sum_prev = W->E_sum;
  W->E_sum = 0;
  return kink;
}

int afv_relax(afv_sim *s, double tol, long max_iter, afv_relax_report *rep,
              afv_relax_monitor mon, void *ctx)
{
  afv_dyn saved = s->dyn;
  long long substeps = s->substeps, halvings = s->halvings;
  window W;
  int st = AFV_OK;
  memset(rep, 0, sizeof *rep);
  memset(&W, 0, sizeof W);
  rep->energy0 = rep->energy = s->geom.energy;
  rep->max_force = afv_sim_max_force(s);
  rep->drift = rep->drop = NAN;
  W.r_sum = calloc((size_t)(4 * s->n + 1), sizeof(double));
  if (!W.r_sum) return AFV_ENOMEM;
  W.r_sum_prev = W.r_sum + 2 * s->n;
  s->dyn.v0 = 0;                   /* zero temperature: no self-propulsion */
  s->dyn.v0_i = NULL;
  while (!(rep->max_force <= tol) && rep->iterations < max_iter) {
    if ((st = flow_step(s, s->dyn.dt)) != AFV_OK) {
      /* a finite move beyond l/2 even in the smallest half: forces too
      ** large for dt, which no relaxation by steps of dt can follow; the
      ** caller hears it (refused, afv_sim's bad_*) and goes on, as when
      ** max_iter is reached.  A force that is not finite is an error. */
      if (st == AFV_EUNSTABLE && isfinite(s->bad_disp)) {
        rep->refused = 1;
        st = AFV_OK;
      }
      break;
    }
    rep->iterations++;
    rep->max_force = afv_sim_max_force(s);
    add_positions(s, W.r_sum);
    W.E_sum += s->geom.energy;
    if (mon) mon(ctx, rep->iterations, s->geom.energy, rep->max_force);
    if (rep->iterations % AFV_RELAX_WINDOW == 0
        && window_shows_kink(s, rep, &W, energy_scale(s))
        && !(rep->max_force <= tol)) {
      rep->at_kink = 1;
      break;
    }
  }
  s->dyn = saved;
  rep->energy = s->geom.energy;
  rep->converged = rep->max_force <= tol;
  rep->time = (double)rep->iterations * s->dyn.dt;
  rep->substeps = s->substeps - substeps;
  rep->halvings = s->halvings - halvings;
  free(W.r_sum < W.r_sum_prev ? W.r_sum : W.r_sum_prev);
  return st;
}

/* ---- initial configurations -------------------------------------------- */
/* A triangular-lattice site (i, j): position a (i + j/2, j sqrt(3)/2), and
** squared distance from the origin a^2 (i^2 + i j + j^2), exact in integers. */
typedef struct site {
  long d2;   /* i^2 + i j + j^2 */
  int i, j;  /* lattice indices */
} site;

static int site_cmp(const void *pa, const void *pb)
{
  const site *a = pa, *b = pb;
  if (a->d2 != b->d2) return a->d2 < b->d2 ? -1 : 1;
  if (a->j != b->j) return a->j < b->j ? -1 : 1;
  return (a->i > b->i) - (a->i < b->i);
}

int afv_init_cluster(int n, double a, const afv_box *b, double *r)
{
  /* the n nearest sites lie within radius sqrt(n / pi * sqrt(3)/2) + 2;
  ** site (i, j) is at distance^2 i^2 + ij + j^2 >= 3 j^2 / 4, so the rows
  ** that reach the disk have |j| <= J = 2R / sqrt(3) */
  int R = (int)ceil(sqrt(n * 0.8660254037844386 / 3.14159265358979) + 2);
  int J = (int)ceil(2 * R / 1.7320508075688772);
  int m = 0, i, j, k;
  long maxd2 = 0;
  double cx = 0, cy = 0;
  site *S = malloc((size_t)(4 * R + 1) * (size_t)(2 * J + 1) * sizeof *S);
  if (!S) return AFV_ENOMEM;
  for (j = -J; j <= J; j++)
    for (i = -2 * R; i <= 2 * R; i++) {
      long d2 = (long)i * i + (long)i * j + (long)j * j;
      if (d2 > (long)R * R) continue;
      S[m].d2 = d2;
      S[m].i = i;
      S[m].j = j;
      m++;
    }
  if (m < n) {                 /* cannot happen: the disk holds >= n sites */
    free(S);
    return AFV_EINVAL;
  }
  qsort(S, (size_t)m, sizeof *S, site_cmp);
  for (k = 0; k < n; k++)
    if (S[k].d2 > maxd2) maxd2 = S[k].d2;
  if (b && b->periodic) {
    /* keep a gap of a between the cluster and its periodic images */
    double side = b->Lx < b->Ly ? b->Lx : b->Ly;
    double amax = side / (2 * sqrt((double)maxd2) + 1);
    if (a > amax) a = amax;
    cx = 0.5 * b->Lx;
    cy = 0.5 * b->Ly;
  }
  for (k = 0; k < n; k++) {
    r[2*k] = cx + a * (S[k].i + 0.5 * S[k].j);
    r[2*k+1] = cy + a * 0.8660254037844386 * S[k].j;
  }
  free(S);
  return AFV_OK;
}

/* Centres uniform in the square of side `side` centred on (cx, cy). */
static void uniform_square(int n, unsigned long long seed, double cx,
                           double cy, double side, double *r)
{
  int i;
  for (i = 0; i < n; i++) {
    double u[2];
    afv_rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_POS, u);
    r[2*i] = cx + side * (0.5 - u[0]);
    r[2*i+1] = cy + side * (0.5 - u[1]);
  }
}

void afv_init_random(int n, unsigned long long seed, const afv_box *b,
                     double side, double *r)
{
  int i;
  if (!(b && b->periodic)) {
    uniform_square(n, seed, 0, 0, side, r);
    return;
  }
  for (i = 0; i < n; i++) {
    double u[2];
    afv_rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_POS, u);
    r[2*i] = b->Lx * (1 - u[0]);          /* 1 - u lies in [0, 1) */
    r[2*i+1] = b->Ly * (1 - u[1]);
  }
}

void afv_init_square(int n, unsigned long long seed, const afv_box *b,
                     double side, double *r)
{
  int periodic = b && b->periodic;
  uniform_square(n, seed, periodic ? 0.5 * b->Lx : 0,
                 periodic ? 0.5 * b->Ly : 0, side, r);
}

void afv_init_angles(int n, unsigned long long seed, double *theta)
{
  int i;
  for (i = 0; i < n; i++) {
    double u[2];
    afv_rng_uniform2(seed, (uint32_t)i, 0, AFV_RNG_INIT_ANGLE, u);
    theta[i] = TWO_PI * (1 - u[0]);
  }
}
