/*
** afv.c -- energy, exact analytic forces and the finite-difference check.
**
** Energy (paper, Eq. (3), label eq:energy, there in units KA = l = 1 with
** kP = KP/KA):  E = sum_i e_i,
**     e_i = KA_i (A_i - A0_i)^2 + KP_i (P_i - P0_i)^2 + Lambda L_i.
** Force (paper, after Eq. (3)):  F_i = -grad_i E.
** (The paper's equations are numbered (1) energy_eq_first, (2) its
** simplified form, (3) eq:energy, (4) the equation of motion, (5) eq:abp.)
**
** FORCES.  One derivation; the force code cites its labels.
**
** (E) Chain rule of Eq. (3): with wA = 2 KA (A_i - A0), wP = 2 KP (P_i -
**     P0) and wL = Lambda,
**         G_ij := de_i/dr_j = wA dA_i/dr_j + wP dP_i/dr_j + wL dL_i/dr_j.
** (F) Cell i's shape depends on r_i and on its neighbours j (|r_j - r_i| <
**     2l); translating all of them translates the shape, so de_i/dr_i =
**     - sum_j G_ij, and the force on j, F_j = -de_j/dr_j - sum_i G_ij, is
**         F_j = sum_{i in nbr(j)} (G_ji - G_ij).
**     Every cell computes its G_ij on its own ("gather" form): no cell
**     writes another's force, and sum_j F_j = 0 in exact arithmetic.
** (G) The frame of the pair, seen from cell i (centred on r_i): D = r_j -
**     r_i = d u, t = u turned by +90 degrees (counter-clockwise along the
**     edge ij), h = d/2; the edge lies on the bisector line x.u = h, its
**     points x = h u + tau t (afv_piece.tau: tau0 at its start, tau1 =
**     tau0 + ell at its end).  A move of r_j is dD = dd u + d dphi t (dd
**     away from r_i, dphi turning about it), so
**         G_ij = a u + (b / d) t,   a = de_i/dd,   b = de_i/dphi.
**     a and b are sums of bounded terms from the vertices' tau (to
**     relative precision, from the clipping); b / d is formed once per
**     pair from both cells' b (gather_forces), so nearly coincident
**     centres keep their digits (at d = 1e-16 l the vector form of these
**     formulas lost 39%, and 1e159 with the wrong sign below d^2 = 0).
** (N) Moving r_j moves only its line: h -> h + dd/2, u -> u + dphi t,
**     t -> t - dphi u, so the point of the line at tau moves by
**         dx = (dd/2 - tau dphi) u + h dphi t,
**     along the outward normal u by dd/2 - tau dphi.
** (A) Area: only the edge moves, A_i grows by the normal motion (N)
**     integrated over it:
**         a += wA ell / 2,           b -= wA ell (tau0 + tau1) / 2.
** Perimeter and arc length are sums of piece lengths between vertices; a
** vertex V moving by dV lengthens the piece arriving at V by t_in.dV and
** the piece leaving it by -t_out.dV (t_in, t_out their unit tangents at
** V; an arc keeps its circle).  So dP_i = (t_in - t_out).dV, and dL_i =
** t_in.dV if an arc arrives, -t_out.dV if one leaves.  Two kinds of
** vertex move with r_j:
** (V1) Arc end, on the circle |x| = l at tau = sigma s, s = sqrt(l^2 - h^2)
**     the half-chord, sigma = -1 at the edge's start (an arc arrives),
**     +1 at its end (an arc leaves).  Moving away, tau = sigma s moves by
**     -sigma h dd / (2s), so dV = (dd/2) u - sigma (h/(2s)) dd t; turning,
**     V turns with the line about r_i, along the circle, dV = dphi R V.
**     The circle's tangent at V is R V / l, the edge's is t; so, per end,
**         a += (wP (l - h) + wL l) / (2s),
**         b += -sigma (wP (l - h) + wL l)
**     (+ where the arc arrives, - where it leaves).  The 1/s diverges as
**     (2l - d)^(-1/2) as the contact is about to break: the exact force
**     does too (integrably).
** (V1c) The cap (afv_params.cap = delta > 0, PyAFV's contact truncation):
**     where 2s < delta, a uses the arc end's velocity along the edge with
**     2s replaced by delta (arc_end_radial); the force is then not
**     -grad E.
** (V2) Triple junction V of edge j (leaving V, V at tau0_j) and edge k
**     (arriving, V at tau1_k), c = u_j x u_k, q = u_j.u_k.  Moving r_j
**     slides V along line k (which does not move): V = V + sg t_k, with
**     V.u_j = h_j kept, i.e. by (N) sg (t_k.u_j) = dd/2 - tau0_j dphi,
**     t_k.u_j = -c; only P changes, by (t_k - t_j).t_k sg = (1 - q) sg.
**     With m = wP (1 - q) / c (= wP c / (1 + q), the same value without
**     the cancellation in 1 - q where q >= 0):
**         a_j -= m / 2,   b_j += tau0_j m,
**     and the same for r_k moving V along line j (t_j.u_k = c, and
**     (t_k - t_j).t_j = q - 1):
**         a_k -= m / 2,   b_k += tau1_k m.
** For two cells alone the b of both arc ends cancel exactly and b of the
** edge is 0 exactly (tau0 = -tau1), so the pair force is a u to rounding
** for any d > 0: the closed form of test_core.c holds from d = 1e-16 l to
** 2l (test_geometry.c).  Every formula is checked against central
** differences of E in the tests (afv_gradient_check, below).
**
** Invariants (asserted where relied on, in a build without -DNDEBUG): every
** edge piece of a cell belongs to one of its own neighbour slots (its G is
** written there), and every slot s has its reverse, nbr_rev[nbr_rev[s]] =
** s (gather_forces pairs G_js with G_rev(s); neighbours.c).
*/
#include "afv_internal.h"
#include "fastmath.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A macro's value as a string literal (the limits in the messages). */
#define STR(x) STR_(x)
#define STR_(x) #x

const char *afv_strerror(int status)
{
  switch (status) {
  case AFV_OK: return "success";
  case AFV_ENOMEM: return "out of memory";
  case AFV_EINVAL: return "parameter out of range";
  case AFV_EBOX: return "periodic box side smaller than 4l";
  case AFV_ENONFINITE: return "position is NaN or infinite";
  case AFV_ECOINCIDENT: return "two cell centres coincide";
  case AFV_EIO: return "input/output error";
  case AFV_EFORMAT: return "malformed file";
  case AFV_EUNSTABLE:
    return "unstable step (a force or position not finite, or a move "
           "beyond " STR(AFV_RUNAWAY_MOVE) " l)";
  default: return "unknown error";
  }
}

void afv_params_default(afv_params *p)
{
  assert(p != NULL);
  memset(p, 0, sizeof *p);
  p->l = 1;
  p->KA = 1;
  p->KP = 1;
  p->A0 = PI;
  p->P0 = 4.8;
  p->Lambda = 0.2;
  p->cap = 0;
}

/* The moduli and targets of cell i (per-cell value if given). */
typedef struct cell_targets {
  double KA, KP, A0, P0;
} cell_targets;

static cell_targets targets_of(const afv_params *p, int i)
{
  cell_targets c;
  c.KA = p->KA_i ? p->KA_i[i] : p->KA;
  c.KP = p->KP_i ? p->KP_i[i] : p->KP;
  c.A0 = p->A0_i ? p->A0_i[i] : p->A0;
  c.P0 = p->P0_i ? p->P0_i[i] : p->P0;
  return c;
}

/* 1 if every v[i] (i < n) is finite and >= lo; a NULL array passes. */
static int array_at_least(const double *v, int n, double lo)
{
  int i;
  if (!v) return 1;
  for (i = 0; i < n; i++)
    if (!(isfinite(v[i]) && v[i] >= lo)) return 0;
  return 1;
}

/* The largest energy e_i a cell with these values can have: a cell lies
** in its disk, 0 <= A_i <= pi l^2 and 0 <= P_i, L_i <= 2 pi l, so
**     e_i <= KA dA^2 + KP dP^2 + |Lambda| 2 pi l,
**     dA = max(|A0|, |pi l^2 - A0|),  dP = max(|P0|, |2 pi l - P0|).
** Where this overflows, so may E and the forces (l = 1e300: l^2 = inf,
** NaN forces; P0 = 1e300: E = inf). */
static double energy_bound(const afv_params *p, int i)
{
  cell_targets c = targets_of(p, i);
  double Amax = PI * p->l * p->l, Pmax = TWO_PI * p->l;
  double dA = fmax(fabs(c.A0), fabs(Amax - c.A0));
  double dP = fmax(fabs(c.P0), fabs(Pmax - c.P0));
  return c.KA * dA * dA + c.KP * dP * dP + fabs(p->Lambda) * Pmax;
}

/* 1 if the energy of n cells (at least 1) stays AFV_PARAMS_HEADROOM below
** overflow whatever their shapes: the sum of their energy_bound. */
static int energy_bounded(const afv_params *p, int n)
{
  double sum = 0;
  int i;
  if (!(p->KA_i || p->KP_i || p->A0_i || p->P0_i))
    sum = (n > 1 ? n : 1) * energy_bound(p, 0);
  else
    for (i = 0; i < n && isfinite(sum); i++) sum += energy_bound(p, i);
  return isfinite(sum * AFV_PARAMS_HEADROOM);
}

int afv_params_check(const afv_params *p, int n)
{
  assert(p != NULL);
  if (!(isfinite(p->l) && p->l > 0)) return AFV_EINVAL;
  if (!(isfinite(p->KA) && p->KA >= 0 && isfinite(p->KP) && p->KP >= 0))
    return AFV_EINVAL;
  if (!(isfinite(p->A0) && isfinite(p->P0) && isfinite(p->Lambda)))
    return AFV_EINVAL;
  if (!(isfinite(p->cap) && p->cap >= 0)) return AFV_EINVAL;
  if (!(array_at_least(p->KA_i, n, 0) && array_at_least(p->KP_i, n, 0)
        && array_at_least(p->A0_i, n, -HUGE_VAL)
        && array_at_least(p->P0_i, n, -HUGE_VAL)))
    return AFV_EINVAL;
  if (!energy_bounded(p, n)) return AFV_EINVAL;
  return AFV_OK;
}

static int box_check(const afv_box *b, double l)
{
  if (!b || !b->periodic) return AFV_OK;
  if (!(isfinite(b->Lx) && isfinite(b->Ly))) return AFV_EINVAL;
  if (b->Lx < 4 * l || b->Ly < 4 * l) return AFV_EBOX;
  return AFV_OK;
}

double afv_cell_energy(const afv_params *p, int i, double A, double P, double L)
{
  assert(p != NULL && i >= 0);
  cell_targets c = targets_of(p, i);
  /* e_i, the term of cell i in Eq. (3) of the paper */
  return c.KA * (A - c.A0) * (A - c.A0) + c.KP * (P - c.P0) * (P - c.P0)
       + p->Lambda * L;
}

/* ---- shape derivatives (the header's (G) .. (V2)) ---------------------- */
/* The edge of neighbour slot s, seen from its cell. */
typedef struct edge {
  double ux, uy;       /* u = D / d */
  double h;            /* d / 2 */
  double s;            /* half-chord sqrt(l^2 - h^2) */
} edge;

/* u, h and s come from the edge cache that afv_neighbours fills
** (neighbours.c), computed there once per neighbour pair. */
static edge edge_of(const afv_geom *g, int s)
{
  const double *e = g->edge + 4 * s;
  edge E;
  E.ux = e[0];
  E.uy = e[1];
  E.h = e[2];
  E.s = e[3];
  return E;
}

/* (A): the area of the edge piece pc, through a and b of its slot. */
static void area_terms(const afv_piece *pc, double wA, double *ab)
{
  double c = wA * pc->length;
  ab[0] += 0.5 * c;                            /* (A): a += wA ell / 2 */
  ab[1] -= c * (pc->tau + 0.5 * pc->length);   /* (A): b -= wA ell mid;
                                               ** tau0 + ell/2 = mid */
}

/* (V1): a of one arc end of edge E (the same at both ends), the end of an
** arc of length arc; the b terms are -+arc_turn (the header's (V1)).
** (V1c) THE CAP is PyAFV's contact truncation delta, so that the two codes
** give the same forces (test_geometry.c, golden data of PyAFV 0.4.16): where
** 2s < delta, the arc end's velocity along the edge, l^2/(d s) per unit
** change of d, becomes l^2/(d delta/2), i.e. it gains
**     Delta = (l^2/d) (2/delta - 1/s)        (per unit change of d),
** and that velocity is fed into P, L and A alike.  The capped velocity has
** a component off the circle, which moves the chord of the arc's circular
** segment; PyAFV's area (chord polygon + segments l^2 (theta - sin theta)/2)
** changes through it by (1/2) s Delta (-sin theta) per unit of d, theta =
** arc / l the arc's angle.  The energy is not changed: the capped force is
** not -grad E. */
static double arc_end_radial(const edge *E, double l, double cap, double wA,
                             double wP, double wL, double arc)
{
  double s = E->s, h = E->h, excess, sin_arc, cos_arc;
  if (!(s > 0)) return 0;              /* a chord of length 0 makes no edge */
  if (2 * s >= cap)                    /* (V1): a += (wP (l-h) + wL l) / 2s */
    return (wP * (l - h) + wL * l) * (0.5 / s);
  /* (V1c), in the vector form of the arc end's velocity that PyAFV
  ** differentiates, V = D/2 + sigma (s/d) R D: its part along u for a
  ** weight w = wP (t_in - t_out) + wL (arc tangent) is w.u/2 + sigma
  ** (s/d - l^2/(d s)) t.w, with l^2/(d s) -> l^2/(d cap/2); at either
  ** end -sigma t.w = (wP (h - l) + wL h) / l and w.u = (wP + wL) s / l */
  excess = l * l / (2 * h) * (1 / s - 2 / cap);        /* (V1c): -Delta */
  afv_sincos_inline(arc / l, &sin_arc, &cos_arc);     /* own: same bits */
  return (wP + wL) * s / (2 * l)                       /* (V1c): w.u / 2 */
         + (wP * (h - l) + wL * h) / l * (l * l - s * 0.5 * cap)
           / (2 * h * 0.5 * cap)                       /* (V1c): capped */
         + wA * 0.5 * s * excess * sin_arc;             /* the chord's area */
}

static double arc_turn(const edge *E, double l, double wP, double wL)
{
  return wP * (l - E->h) + wL * l;    /* (V1): b = -sigma (wP (l-h) + wL l) */
}

/* (V2): the triple junction of edge E (the header's j: leaving the vertex,
** which lies at tau_e = tau0_j along it) and the previous edge K (k:
** arriving, at tau_k = tau1_k along it): a and b of both slots (abe, abk). */
static void junction_terms(const edge *E, const edge *K, double tau_e,
                           double tau_k, double wP, double *abe, double *abk)
{
  double c = E->ux * K->uy - E->uy * K->ux;   /* (V2): c = u_j x u_k */
  double q = E->ux * K->ux + E->uy * K->uy;   /* (V2): q = u_j . u_k */
  double m;
  if (c == 0) return;                 /* parallel lines make no vertex */
  m = q >= 0 ? wP * c / (1 + q) : wP * (1 - q) / c;   /* (V2): m */
  abe[0] -= 0.5 * m;                          /* (V2): a_j -= m / 2 */
  abe[1] += tau_e * m;                        /* (V2): b_j += tau0_j m */
  abk[0] -= 0.5 * m;                          /* (V2): a_k -= m / 2 */
  abk[1] += tau_k * m;                        /* (V2): b_k += tau1_k m */
}

/* One pass over the pieces in boundary order, accumulating (G)'s a and b
** per slot in grad (grad[2s] = a, grad[2s+1] = b).  The edge of the
** previous piece is carried along (K). */
void afv_cell_shape_gradient(const afv_geom *g, int i, double l, double cap,
                             double wA, double wP, double wL, double *grad)
{
  assert(g != NULL && grad != NULL && i >= 0 && i < g->n);
  const afv_piece *pieces = g->pieces + g->piece_start[i];
  int np = g->n_pieces[i], k;
  const afv_piece *prev;
  edge K = {0};     /* read only after an edge; zeroed: gcc -O2 cannot see that */
  if (np == 0) return;
  prev = &pieces[np - 1];                     /* the piece before piece 0 */
  if (prev->nbr != AFV_ARC) K = edge_of(g, prev->slot);
  for (k = 0; k < np; k++) {
    const afv_piece *pc = &pieces[k];
    int next_arc = pieces[k + 1 < np ? k + 1 : 0].nbr == AFV_ARC;
    double *ab;
    edge E;
    if (pc->nbr == AFV_ARC) {
      prev = pc;
      continue;
    }
    assert(pc->slot >= g->nbr_start[i] && pc->slot < g->nbr_end[i]);
    E = edge_of(g, pc->slot);
    ab = grad + 2 * pc->slot;
    area_terms(pc, wA, ab);                   /* (A) */
    if (prev->nbr == AFV_ARC) {               /* (V1): an arc arrives */
      ab[0] += arc_end_radial(&E, l, cap, wA, wP, wL, prev->length);
      ab[1] += arc_turn(&E, l, wP, wL);       /* (V1): sigma = -1 */
    } else {                                  /* (V2): junction (i,k,j) */
      junction_terms(&E, &K, pc->tau, prev->tau + prev->length, wP, ab,
                     grad + 2 * prev->slot);
    }
    if (next_arc) {                           /* (V1): an arc leaves */
      ab[0] += arc_end_radial(&E, l, cap, wA, wP, wL,
                              pieces[k + 1 < np ? k + 1 : 0].length);
      ab[1] -= arc_turn(&E, l, wP, wL);       /* (V1): sigma = +1 */
    }
    K = E;
    prev = pc;
  }
}

/* ---- the whole tissue -------------------------------------------------- */
/* (F): F_j = sum over neighbour slots s of j of (G_js - G_rev(s)).  With
** G = a u + (b / d) t in each cell's frame (u_rev = -u_s, t_rev = -t_s):
**     G_js - G_rev(s) = (a_s + a_rev) u_s + ((b_s + b_rev) / d) t_s,
** the two cells' b added before the division by d (a tiny d makes each
** b / d large where their sum is not).  d = 2h > 0 even for a subnormal
** d (neighbours.c), so b = 0 gives 0.  Each F_j is summed in its own slot
** order, whatever thread computes it. */
static void gather_forces(const afv_geom *g, int n, double *f)
{
  int j;
  AFV_PARALLEL_FOR(n)
  for (j = 0; j < n; j++) {
    double fx = 0, fy = 0;
    int s;
    for (s = g->nbr_start[j]; s < g->nbr_end[j]; s++) {
      int t = g->nbr_rev[s];
      /* the lists are symmetric (neighbours.c): every slot has its reverse */
      const double *e = g->edge + 4 * s;
      double a = g->grad[2*s] + g->grad[2*t];             /* (G): a's */
      double bt = (g->grad[2*s+1] + g->grad[2*t+1]) / (e[2] + e[2]); /* b/d */
      assert(g->nbr_rev[t] == s && g->nbr[t] == j);
      fx += a * e[0] - bt * e[1];       /* (F): F_j += G_js - G_rev(s), */
      fy += a * e[1] + bt * e[0];       /* (G): = a u + (b / d) t */
    }
    f[2*j] = fx;
    f[2*j+1] = fy;
  }
}

static int check_inputs(int n, const afv_params *p, const afv_box *b)
{
  int st;
  if (n < 0) return AFV_EINVAL;
  if ((st = afv_params_check(p, n)) != AFV_OK) return st;
  return box_check(b, p->l);
}

/* Every cell's shape and, if `gradient`, its G_ij in grad (its own slots,
** which afv_geometry_prepare has zeroed).  A cell writes only its own
** entries, so the cells may be shared among threads.  In cell order, not
** cell-list order: the per-cell arrays are in cell order. */
static void shape_all(afv_geom *g, int n, const afv_params *p, int gradient)
{
  int i;
  AFV_PARALLEL_FOR(n)
  for (i = 0; i < n; i++) {
    cell_targets c = targets_of(p, i);
    afv_cell_shape(g, i, p->l);
    if (!gradient) continue;
    /* (E): wA = de_i/dA_i, wP = de_i/dP_i, wL = de_i/dL_i */
    afv_cell_shape_gradient(g, i, p->l, p->cap, 2 * c.KA * (g->area[i] - c.A0),
                            2 * c.KP * (g->perim[i] - c.P0), p->Lambda,
                            g->grad);
  }
}

/* E summed in cell order after the parallel loop: the same bits for every
** thread count (a reduction clause would add in a varying order). */
static double total_energy(const afv_geom *g, int n, const afv_params *p)
{
  double E = 0;
  int i;
  for (i = 0; i < n; i++)                   /* Eq. (3): E = sum_i e_i */
    E += afv_cell_energy(p, i, g->area[i], g->perim[i], g->arc[i]);
  return E;
}

int afv_geometry(afv_geom *g, int n, const double *r, const afv_params *p,
                 const afv_box *b)
{
  assert(g != NULL && p != NULL && (r != NULL || n <= 0));
  int st;
  if ((st = check_inputs(n, p, b)) != AFV_OK) return st;
  if ((st = afv_geometry_prepare(g, n, r, p->l, b)) != AFV_OK) return st;
  shape_all(g, n, p, 0);
  g->energy = total_energy(g, n, p);
  return AFV_OK;
}

int afv_compute(afv_geom *g, int n, const double *r, const afv_params *p,
                const afv_box *b, double *f)
{
  assert(g != NULL && p != NULL && (r != NULL || n <= 0));
  int st;
  if (!f) return afv_geometry(g, n, r, p, b);
  if ((st = check_inputs(n, p, b)) != AFV_OK) return st;
  if ((st = afv_geometry_prepare(g, n, r, p->l, b)) != AFV_OK) return st;
  shape_all(g, n, p, 1);
  g->energy = total_energy(g, n, p);
  gather_forces(g, n, f);                   /* F = -grad E, by (F) */
  return AFV_OK;
}

/* ---- finite-difference check ------------------------------------------ */
/* The cells near cell c, as a small open-space tissue in coordinates
** centred on c (cell 0 of it is c): every cell within 4l + 2h, so that
** every cell within 2l + 2h (the ones whose energy moving c by h can
** change, `affected`) has all its neighbours in it. */
typedef struct local_tissue {
  int m, affected_n;
  int *cell;             /* cell[k]: the tissue's number of local cell k */
  double *r;             /* local centres, relative to c */
  double *KA, *KP, *A0, *P0;   /* per-cell values, if p has them */
  afv_params p;
  afv_geom g;
  int cap;
  int *around;           /* scratch for afv_cells_around (n) */
} local_tissue;

static int local_grow(local_tissue *T, int m)
{
  int k = T->cap;
  double *q;
  int *c;
  if (m <= T->cap) return AFV_OK;
  while (k < m) k = k ? 2 * k : 64;
  c = realloc(T->cell, (size_t)k * sizeof(int));
  if (!c) return AFV_ENOMEM;
  T->cell = c;
  q = realloc(T->r, (size_t)k * 6 * sizeof(double));
  if (!q) return AFV_ENOMEM;
  T->r = q;
  T->KA = q + 2 * k;
  T->KP = q + 3 * k;
  T->A0 = q + 4 * k;
  T->P0 = q + 5 * k;
  T->cap = k;
  return AFV_OK;
}

/* Adds cell j at displacement (dx, dy) from c to T if within R. */
static int local_add(local_tissue *T, const afv_params *p, int j, double dx,
                     double dy, double R)
{
  int k = T->m;
  if (!(dx * dx + dy * dy < R * R)) return AFV_OK;
  if (local_grow(T, k + 1)) return AFV_ENOMEM;
  T->cell[k] = j;
  T->r[2*k] = dx;
  T->r[2*k+1] = dy;
  {
    cell_targets t = targets_of(p, j);
    T->KA[k] = t.KA;
    T->KP[k] = t.KP;
    T->A0[k] = t.A0;
    T->P0[k] = t.P0;
  }
  T->m++;
  return AFV_OK;
}

/* The local tissue around c: c first, then the others within 4l + 2h
** (found in g's cell list), the affected ones (within 2l + 2h) first. */
static int local_build(local_tissue *T, const afv_geom *g, const double *r,
                       const afv_params *p, const afv_box *b, int c, double h)
{
  double R = 4 * p->l + 2 * h, Raff = 2 * p->l + 2 * h;
  int q, pass, st = AFV_OK;
  int found = afv_cells_around(g, r[2*c], r[2*c+1], R, 0, T->around);
  T->m = 0;
  if ((st = local_add(T, p, c, 0, 0, 1)) != AFV_OK) return st;
  for (pass = 0; pass < 2 && st == AFV_OK; pass++) {   /* affected first */
    for (q = 0; q < found && st == AFV_OK; q++) {
      int j = T->around[q];
      double dx = r[2*j] - r[2*c], dy = r[2*j+1] - r[2*c+1], d2;
      if (j == c) continue;
      afv_min_image(b, &dx, &dy);
      d2 = dx * dx + dy * dy;
      if ((d2 < Raff * Raff) != (pass == 0)) continue;
      st = local_add(T, p, j, dx, dy, R);
    }
    if (pass == 0) T->affected_n = T->m;
  }
  T->p = *p;
  T->p.KA_i = p->KA_i ? T->KA : NULL;
  T->p.KP_i = p->KP_i ? T->KP : NULL;
  T->p.A0_i = p->A0_i ? T->A0 : NULL;
  T->p.P0_i = p->P0_i ? T->P0 : NULL;
  return st;
}

/* The size of cell k's energy for its rounding: |e_k| and each term's
** derivative times its argument (the energy of a cell is formed from A,
** P and L, each rounded to about eps times itself). */
static double energy_magnitude(const afv_params *p, int k, double A, double P,
                               double L)
{
  cell_targets t = targets_of(p, k);
  return fabs(afv_cell_energy(p, k, A, P, L))
         + fabs(2 * t.KA * (A - t.A0)) * fabs(A)
         + fabs(2 * t.KP * (P - t.P0)) * fabs(P) + fabs(p->Lambda * L);
}

/* The energy of the affected cells of T with its cell 0 at (x, y); adds
** their energy_magnitude to *mag. */
static int local_energy(local_tissue *T, double x, double y, double *E,
                        double *mag)
{
  afv_box open = {0, 0, 0};
  int k, st;
  T->r[0] = x;
  T->r[1] = y;
  st = afv_geometry(&T->g, T->m, T->r, &T->p, &open);
  *E = 0;
  for (k = 0; k < T->affected_n && st == AFV_OK; k++) {
    *E += afv_cell_energy(&T->p, k, T->g.area[k], T->g.perim[k], T->g.arc[k]);
    *mag += energy_magnitude(&T->p, k, T->g.area[k], T->g.perim[k],
                             T->g.arc[k]);
  }
  return st;
}

/* The whole tissue's energy with coordinate q of r moved by dx (the
** fallback for a small periodic box); adds its energy_magnitude to *mag. */
static int global_energy(afv_geom *g, int n, double *rr, const double *r,
                         const afv_params *p, const afv_box *b, int q,
                         double dx, double *E, double *mag)
{
  int st, k;
  rr[q] = r[q] + dx;
  st = afv_geometry(g, n, rr, p, b);
  rr[q] = r[q];
  *E = g->energy;
  for (k = 0; k < n && st == AFV_OK; k++)
    *mag += energy_magnitude(p, k, g->area[k], g->perim[k], g->arc[k]);
  return st;
}

/* rms over cells of |2 KA (A - A0)| l + |2 KP (P - P0)| + |Lambda|, formed
** over the largest term (squares of terms near 1e300 would overflow). */
static double tension_scale(const afv_geom *g, int n, const afv_params *p)
{
  double s = 0, top = 0;
  int i, pass;
  for (pass = 0; pass < 2; pass++)
    for (i = 0; i < n; i++) {
      cell_targets t = targets_of(p, i);
      double T = fabs(2 * t.KA * (g->area[i] - t.A0)) * p->l
                 + fabs(2 * t.KP * (g->perim[i] - t.P0)) + fabs(p->Lambda);
      if (pass == 0) top = fmax(top, T);
      else s += (T / top) * (T / top);
    }
  return n > 0 && top > 0 && isfinite(top) ? top * sqrt(s / n) : top;
}

/* KINKS.  The energy is smooth in a cell's position except where a pair
** detaches (d = 2l: the arc length changes as sqrt(2l - d), so the force
** grows as 1 / sqrt(2l - d) near it) or two centres meet (d = 0: the
** bisector turns over).  A central difference whose step reaches a kink
** differences across it, and one close to it needs steps much smaller
** than the distance to it, where the Taylor series converges.  So the
** step for cell c is at most AFV_CHECK_KINK_STEPS times smaller than c's
** distance to its nearest kink (afv_config.h).  The finite-difference
** error is called resolved when it is more than AFV_CHECK_UNRESOLVED
** times the difference's own uncertainty (both steps' disagreement and
** rounding, the energy's relative rounding AFV_SUM_ROUNDING of its
** energy_magnitude): only a resolved error can fail the check. */

/* Distance of c (at the origin of the local centres x, cells 1 .. m-1)
** to its nearest kink: min over the others of d and |d - 2l|. */
static double kink_distance(const double *x, int m, double l)
{
  double delta = HUGE_VAL;
  int k;
  for (k = 1; k < m; k++) {
    double d = afv_hypot_inline(x[2*k], x[2*k+1]);
    delta = fmin(delta, fmin(d, fabs(d - 2 * l)));
  }
  return delta;
}

/* The same for cell c of the whole tissue (minimum image). */
static double kink_distance_global(int n, const double *r, const afv_box *b,
                                   int c, double l)
{
  double delta = HUGE_VAL;
  int j;
  for (j = 0; j < n; j++) {
    double dx = r[2*j] - r[2*c], dy = r[2*j+1] - r[2*c+1], d;
    if (j == c) continue;
    afv_min_image(b, &dx, &dy);
    d = afv_hypot_inline(dx, dy);
    delta = fmin(delta, fmin(d, fabs(d - 2 * l)));
  }
  return delta;
}

/* 1 if err is to replace max as the largest error: NaN is larger than
** any number, and stays the largest once recorded. */
static int exceeds(double err, double max)
{
  return !isnan(max) && !(err <= max);
}

/* Records the error of component q: fd, the extrapolated central
** difference, and u, its uncertainty (see KINKS).  A NaN
** error (a NaN force) is resolved: a wrong force, never a pass. */
static void check_record(afv_check_report *rep, int q, double fd, double f,
                         double u)
{
  double err = fabs(fd - f);
  int resolved = !(err <= AFV_CHECK_UNRESOLVED * u);
  if (exceeds(err, rep->max_abs) || rep->worst_cell < 0) {
    rep->max_abs = err;
    rep->worst_cell = q / 2;
    rep->worst_comp = q % 2;
  }
  if (resolved && exceeds(err, rep->max_resolved)) rep->max_resolved = err;
  if (!resolved && exceeds(err, rep->max_unresolved)) {
    rep->max_unresolved = err;
    rep->unresolved_cell = q / 2;
  }
}

/* What the check of one cell needs: the local tissue or the whole one. */
typedef struct fd_context {
  int local, n;
  local_tissue *T;
  afv_geom *g;
  double *rr;
  const double *r;
  const afv_params *p;
  const afv_box *b;
  double reach;          /* size of the coordinates the energies are
                         ** computed from (see check_component) */
} fd_context;

/* -(E(+s) - E(-s)) / 2s along component q; adds the energies'
** magnitudes to *mag. */
static int central_difference(const fd_context *C, int q, double s,
                              double *D, double *mag)
{
  double Ep = 0, Em = 0, x = q % 2 ? 0 : s, y = q % 2 ? s : 0;
  int st;
  if (C->local) {
    if ((st = local_energy(C->T, x, y, &Ep, mag)) == AFV_OK)
      st = local_energy(C->T, -x, -y, &Em, mag);
  } else if ((st = global_energy(C->g, C->n, C->rr, C->r, C->p, C->b, q, s,
                                 &Ep, mag)) == AFV_OK) {
    st = global_energy(C->g, C->n, C->rr, C->r, C->p, C->b, q, -s, &Em, mag);
  }
  *D = -(Ep - Em) / (2 * s);
  return st;
}

/* Component q checked with step s and s/2: the Richardson extrapolation
** (4 D(s/2) - D(s)) / 3 against f[q]; its uncertainty is the two steps'
** disagreement (an O(s^2) bound on an O(s^4) error) plus the rounding
** of the energies, 3 eps_E / s in the extrapolation.  eps_E has two
** parts: the energy's own sums (AFV_SUM_ROUNDING of its magnitude), and
** the distances between centres, each rounded to AFV_COORD_ROUNDING of
** the coordinates' size (C->reach), which move the energy by up to the
** force times that much: where the step is only a few ulps of the
** coordinates (a pair an ulp from detaching), the difference
** cannot resolve the force, and says so instead of failing. */
static int check_component(const fd_context *C, int q, double s,
                           const double *f, afv_check_report *rep)
{
  double D1, D2, mag = 0, u, F;
  int st = central_difference(C, q, s, &D1, &mag);
  if (st == AFV_OK) st = central_difference(C, q, 0.5 * s, &D2, &mag);
  if (st != AFV_OK) return st;
  F = fmax(fabs(f[q]), fmax(fabs(D1), fabs(D2)));
  u = fabs(D1 - D2) + 3 * (AFV_SUM_ROUNDING * (mag / 4)
                           + F * AFV_COORD_ROUNDING * C->reach) / s;
  check_record(rep, q, D2 + (D2 - D1) / 3, f[q], u);
  return AFV_OK;
}

int afv_force_check(int n, const double *r, const afv_params *p,
                    const afv_box *b, double h, const double *f,
                    afv_check_report *rep)
{
  assert(p != NULL && rep != NULL && (n <= 0 || (r != NULL && f != NULL)));
  afv_geom g;
  local_tissue T;
  fd_context C;
  double *rr = NULL;
  int st, c, q, local;
  memset(&g, 0, sizeof g);
  memset(&T, 0, sizeof T);
  memset(rep, 0, sizeof *rep);
  rep->worst_cell = rep->unresolved_cell = -1;
  if (!(h > 0 && isfinite(h))) return AFV_EINVAL;
  if ((st = afv_geometry(&g, n, r, p, b)) != AFV_OK) {
    afv_geom_free(&g);
    return st;
  }
  for (q = 0; q < 2 * n; q++)
    if (fabs(f[q]) > rep->force_scale) rep->force_scale = fabs(f[q]);
  rep->tension_scale = tension_scale(&g, n, p);
  /* the local tissue of 4l + 2h about c must not meet its own images */
  local = !(b && b->periodic)
          || fmin(b->Lx, b->Ly) > 4 * (4 * p->l + 2 * h);
  if (local) T.around = malloc((size_t)(n + 1) * sizeof(int));
  else rr = malloc((size_t)(2 * n + 1) * sizeof(double));
  if (local ? !T.around : !rr) st = AFV_ENOMEM;
  if (rr && n > 0) memcpy(rr, r, (size_t)(2 * n) * sizeof(double));
  C.local = local; C.n = n; C.T = &T; C.g = &g; C.rr = rr; C.r = r;
  C.p = p; C.b = b;
  C.reach = 4 * p->l + 2 * h;             /* local: centres within it */
  for (c = 0; c < n && st == AFV_OK; c++) {
    double s;
    if (local && (st = local_build(&T, &g, r, p, b, c, h)) != AFV_OK) break;
    s = fmin(h, (local ? kink_distance(T.r, T.m, p->l)
                 : kink_distance_global(n, r, b, c, p->l)) / AFV_CHECK_KINK_STEPS);
    s = fmax(s, DBL_MIN);   /* a kink 1e-320 l away: no step resolves it */
    if (!local)             /* global: the coordinates of the whole box */
      C.reach = fmax(fabs(r[2*c]), fabs(r[2*c+1])) + fmax(b->Lx, b->Ly);
    for (q = 2 * c; q < 2 * c + 2 && st == AFV_OK; q++)
      st = check_component(&C, q, s, f, rep);
  }
  rep->max_rel = rep->force_scale > 0 ? rep->max_abs / rep->force_scale
                                      : rep->max_abs;
  rep->max_tension_rel = rep->tension_scale > 0
                         ? rep->max_abs / rep->tension_scale : rep->max_abs;
  afv_geom_free(&g);
  afv_geom_free(&T.g);
  free(T.cell);
  free(T.r);
  free(T.around);
  free(rr);
  return st;
}

int afv_gradient_check(int n, const double *r, const afv_params *p,
                       const afv_box *b, double h, afv_check_report *rep)
{
  assert(p != NULL && rep != NULL && (r != NULL || n <= 0));
  afv_geom g;
  double *f = malloc((size_t)(2 * n + 1) * sizeof(double));
  int st;
  memset(&g, 0, sizeof g);
  memset(rep, 0, sizeof *rep);
  rep->worst_cell = rep->unresolved_cell = -1;
  if (!(h > 0 && isfinite(h))) {
    free(f);
    return AFV_EINVAL;
  }
  if (!f) return AFV_ENOMEM;
  st = afv_compute(&g, n, r, p, b, f);
  afv_geom_free(&g);
  if (st == AFV_OK) st = afv_force_check(n, r, p, b, h, f, rep);
  free(f);
  return st;
}
