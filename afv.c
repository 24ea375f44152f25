/*
** afv.c -- energy, exact analytic forces and the finite-difference check.
**
** Energy (paper, Eq. energy):  E = sum_i e_i,
**     e_i = KA_i (A_i - A0_i)^2 + KP_i (P_i - P0_i)^2 + Lambda L_i.
**
** FORCES.  By the chain rule, with wA = 2 KA (A_i - A0), wP = 2 KP (P_i - P0)
** and wL = Lambda,
**     G_ij := de_i/dr_j = wA dA_i/dr_j + wP dP_i/dr_j + wL dL_i/dr_j.
** Cell i's shape depends on r_i and on its neighbours j (|r_j - r_i| < 2l).
** Translating all of them together translates the shape, so
**     de_i/dr_i = - sum_j G_ij,
** and the force on j,  F_j = -dE/dr_j = -de_j/dr_j - sum_i G_ij, becomes
**     F_j = sum_{i in nbr(j)} (G_ji - G_ij).                           (F)
** Every cell computes its G_ij on its own ("gather" form): no cell writes
** another's force, and sum_j F_j = 0 exactly in exact arithmetic.
**
** It remains to differentiate A_i, P_i, L_i with respect to a neighbour r_j
** (r_i fixed, cell frame centred on r_i, D = r_j - r_i, d = |D|, u = D/d,
** t = (-u_y, u_x) the counter-clockwise direction along the edge ij, which
** lies on the bisector line x.u = d/2).  Moving r_j moves only that line.
**
** Area (Reynolds transport).  The bisector is |x - r_j| = |x - r_i|; moving
** r_j by dr moves its point x along u by (r_j - x).dr / d.  Integrating this
** normal velocity over the edge (length ell, midpoint m):
**     dA_i/dr_j = (ell / d) (D - m).                                    (A)
** The arcs and the other edges do not move, so they add nothing.
**
** Perimeter and arc length.  Both are sums of piece lengths between the
** vertices; moving one vertex V by dV changes the piece arriving at V by
** t_in.dV and the piece leaving V by -t_out.dV (t_in, t_out its unit
** tangents there; an arc keeps its circle, an edge's length is |V_b - V_a|).
** So, for every vertex V that moves with r_j,
**     dP_i += (dV/dr_j)^T (t_in - t_out),
**     dL_i += (dV/dr_j)^T (t_in if an arc arrives, - t_out if one leaves).
** Two kinds of vertex move with r_j:
**
** (1) Arc end: V = D/2 + sigma (s/d) R D on the circle, s = sqrt(l^2 - d^2/4)
**     the half-chord, R the rotation by +90 degrees, sigma = -1 where the
**     edge starts (the arc arrives), +1 where it ends.  Differentiating,
**       (dV/dD)^T w = w/2 + sigma (s/d) R^T w - sigma l^2/(d s) (t.w) u.  (V1)
**     The last term diverges like 1/s ~ (2l - d)^(-1/2) as the contact is
**     about to break: the exact force does too (integrably).  The optional
**     cap replaces 2s = sqrt(4l^2 - d^2) by max(2s, delta) there only.
** (2) Triple junction V of cells i, j, k: the circumcentre, on the lines ij
**     and ik.  Moving r_j slides V along line ik (direction e = t_k, which
**     does not move) by alpha, where |V - r_j|^2 = |V - r_i|^2 requires
**     alpha (r_i - r_j).e = (V - r_j).dr, hence
**       (dV/dr_j)^T w = (V - D_j) (e.w) / (-D_j . e),   e = t_k,      (V2)
**     and the same with j and k exchanged for the motion with r_k.
**     At a triple junction both pieces are edges, so only P changes.
** Every formula is checked against central differences of E in the tests.
*/
#include "afv.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
  case AFV_EUNSTABLE: return "unstable step (NaN force or a move > l/2)";
  default: return "unknown error";
  }
}

void afv_params_default(afv_params *p)
{
  memset(p, 0, sizeof *p);
  p->l = 1;
  p->KA = 1;
  p->KP = 1;
  p->A0 = 3.14159265358979323846;
  p->P0 = 4.8;
  p->Lambda = 0.2;
  p->cap = 0;
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

int afv_params_check(const afv_params *p, int n)
{
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
  return AFV_OK;
}

static int box_check(const afv_box *b, double l)
{
  if (!b || !b->periodic) return AFV_OK;
  if (!(isfinite(b->Lx) && isfinite(b->Ly))) return AFV_EINVAL;
  if (b->Lx < 4 * l || b->Ly < 4 * l) return AFV_EBOX;
  return AFV_OK;
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

double afv_cell_energy(const afv_params *p, int i, double A, double P, double L)
{
  cell_targets c = targets_of(p, i);
  return c.KA * (A - c.A0) * (A - c.A0) + c.KP * (P - c.P0) * (P - c.P0)
       + p->Lambda * L;
}

/* ---- shape derivatives -------------------------------------------------- */
/* The edge of neighbour slot s, seen from its cell. */
typedef struct edge {
  double dx, dy;       /* D = r_j - r_i, of length d */
  double inv_d;        /* 1 / d: one division per edge serves its terms */
  double ux, uy;       /* u = D / d */
  double tx, ty;       /* t = R u, counter-clockwise along the edge */
  double s;            /* half-chord sqrt(l^2 - d^2/4) */
} edge;

/* u, d and s come from the edge cache that afv_neighbours fills (geom.c),
** computed there once per neighbour pair. */
static edge edge_of(const afv_geom *g, int s)
{
  const double *e = g->edge + 4 * s;
  edge E;
  E.dx = g->nbr_d[2*s];
  E.dy = g->nbr_d[2*s+1];
  E.ux = e[0];
  E.uy = e[1];
  E.inv_d = 0.5 / e[2]; /* the cache holds h = d/2 (exactly); 0.5/h is
                        ** 1/d rounded once, the same bits as 1/(2h) */
  E.s = e[3];
  E.tx = -E.uy;
  E.ty = E.ux;
  return E;
}

static void add(double *v, double ax, double ay)
{
  v[0] += ax;
  v[1] += ay;
}

/* (A): wA (ell/d) (D - m), m the midpoint of the edge starting at (x, y). */
static void area_term(const edge *E, const afv_piece *pc, double wA,
                      double *grad)
{
  double mx = pc->x + 0.5 * pc->length * E->tx;
  double my = pc->y + 0.5 * pc->length * E->ty;
  double c = wA * pc->length * E->inv_d;
  add(grad, c * (E->dx - mx), c * (E->dy - my));
}

/* (V1): adds (dV/dD)^T w for the arc end with side sigma of edge E. */
static void arc_end_term(const edge *E, double l, double cap, int sigma,
                         double wx, double wy, double *grad)
{
  double s = E->s;
  double s_div = 2 * s < cap ? 0.5 * cap : s;
  double tw = E->tx * wx + E->ty * wy;
  double gx = 0.5 * wx + sigma * (s * E->inv_d) * wy; /* R^T w = (w_y, -w_x) */
  double gy = 0.5 * wy - sigma * (s * E->inv_d) * wx;
  if (s_div > 0) {
    double c = sigma * l * l * E->inv_d / s_div * tw;
    gx -= c * E->ux;
    gy -= c * E->uy;
  }
  add(grad, gx, gy);
}

/* (V2): adds (dV/dr_j)^T w for the triple junction V of edges Ej and Ek
** to gj, and (dV/dr_k)^T w to gk: V slides along the other edge, so
**   (dV/dr_j)^T w = (V - D_j) (t_k.w) / den_j,  den_j = -D_j.t_k
**                                                     = d_j (u_j x u_k),
**   (dV/dr_k)^T w = (V - D_k) (t_j.w) / den_k,  den_k = -D_k.t_j
**                                                     = -d_k (u_j x u_k),
** with a x b = a_x b_y - a_y b_x: one division, 1 / (u_j x u_k), serves
** both.  Parallel lines make no junction, so a zero cross product only
** arises for a degenerate, zero-length vertex. */
static void junction_terms(const edge *Ej, const edge *Ek, double vx,
                           double vy, double wx, double wy, double *gj,
                           double *gk)
{
  double cross = Ej->ux * Ek->uy - Ej->uy * Ek->ux, q, cj, ck;
  if (cross == 0) return;
  q = 1 / cross;
  cj = (Ek->tx * wx + Ek->ty * wy) * q * Ej->inv_d;
  ck = -(Ej->tx * wx + Ej->ty * wy) * q * Ek->inv_d;
  add(gj, cj * (vx - Ej->dx), cj * (vy - Ej->dy));
  add(gk, ck * (vx - Ek->dx), ck * (vy - Ek->dy));
}

/* The tangent of the circle (counter-clockwise) at the point (x, y) on it. */
static void circle_tangent(double x, double y, double l, double *tx,
                           double *ty)
{
  *tx = -y / l;
  *ty = x / l;
}

/* Contributions of the vertex at the start of edge piece pc (edge *E) and,
** if an arc follows (next_arc), of its end vertex.  The piece before pc is
** an arc if prev_arc, else the edge *K of slot prev_slot. */
static void edge_vertex_terms(const edge *E, const afv_piece *pc, int prev_arc,
                              const edge *K, int prev_slot, int next_arc,
                              double l, double cap, double wP, double wL,
                              double *grad)
{
  double ax, ay;
  if (prev_arc) {                             /* arc arrives: sigma = -1 */
    circle_tangent(pc->x, pc->y, l, &ax, &ay);
    arc_end_term(E, l, cap, -1, wP * (ax - E->tx) + wL * ax,
                 wP * (ay - E->ty) + wL * ay, grad + 2 * pc->slot);
  } else {                                    /* triple junction (i,k,j) */
    double wx = wP * (K->tx - E->tx), wy = wP * (K->ty - E->ty);
    junction_terms(E, K, pc->x, pc->y, wx, wy, grad + 2 * pc->slot,
                   grad + 2 * prev_slot);
  }
  if (next_arc) {                             /* arc leaves: sigma = +1 */
    double vx = pc->x + pc->length * E->tx, vy = pc->y + pc->length * E->ty;
    circle_tangent(vx, vy, l, &ax, &ay);
    arc_end_term(E, l, cap, +1, wP * (E->tx - ax) - wL * ax,
                 wP * (E->ty - ay) - wL * ay, grad + 2 * pc->slot);
  }
}

/* One pass over the pieces in boundary order.  The edge of the previous
** piece is carried along (K) rather than fetched again: the same values,
** and the same additions to grad in the same order as visiting each edge
** with its two cyclic neighbours. */
void afv_cell_shape_gradient(const afv_geom *g, int i, double l, double cap,
                             double wA, double wP, double wL, double *grad)
{
  const afv_piece *pieces = g->pieces + g->piece_start[i];
  int np = g->n_pieces[i], k, prev_slot, prev_arc;
  edge K = {0};     /* read only after an edge; zeroed: gcc -O2 cannot see that */
  if (np == 0) return;
  prev_slot = pieces[np - 1].slot;            /* the piece before piece 0 */
  prev_arc = pieces[np - 1].nbr == AFV_ARC;
  if (!prev_arc) K = edge_of(g, prev_slot);
  for (k = 0; k < np; k++) {
    const afv_piece *pc = &pieces[k];
    int next_arc = pieces[k + 1 < np ? k + 1 : 0].nbr == AFV_ARC;
    edge E;
    if (pc->nbr == AFV_ARC) {
      prev_arc = 1;
      continue;
    }
    E = edge_of(g, pc->slot);
    area_term(&E, pc, wA, grad + 2 * pc->slot);
    edge_vertex_terms(&E, pc, prev_arc, &K, prev_slot, next_arc, l, cap, wP,
                      wL, grad);
    K = E;
    prev_slot = pc->slot;
    prev_arc = 0;
  }
}

/* ---- the whole tissue -------------------------------------------------- */
/* (F): F_j = sum over neighbour slots s of j of (G_js - G_rev(s)).  Each
** F_j is summed in its own slot order, whatever thread computes it. */
static void gather_forces(const afv_geom *g, int n, double *f)
{
  int j;
  AFV_PARALLEL_FOR(n)
  for (j = 0; j < n; j++) {
    double fx = 0, fy = 0;
    int s;
    for (s = g->nbr_start[j]; s < g->nbr_end[j]; s++) {
      int t = g->nbr_rev[s];
      /* the lists are symmetric (geom.c), so every slot has its reverse */
      fx += g->grad[2*s] - g->grad[2*t];
      fy += g->grad[2*s+1] - g->grad[2*t+1];
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
** entries, so the cells may be shared among threads.  (Visiting them in
** cell-list order instead was measured slower for cells given in random
** order: the per-cell arrays are in cell order.) */
static void shape_all(afv_geom *g, int n, const afv_params *p, int gradient)
{
  int i;
  AFV_PARALLEL_FOR(n)
  for (i = 0; i < n; i++) {
    cell_targets c = targets_of(p, i);
    afv_cell_shape(g, i, p->l);
    if (!gradient) continue;
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
  for (i = 0; i < n; i++)
    E += afv_cell_energy(p, i, g->area[i], g->perim[i], g->arc[i]);
  return E;
}

int afv_geometry(afv_geom *g, int n, const double *r, const afv_params *p,
                 const afv_box *b)
{
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
  int st;
  if (!f) return afv_geometry(g, n, r, p, b);
  if ((st = check_inputs(n, p, b)) != AFV_OK) return st;
  if ((st = afv_geometry_prepare(g, n, r, p->l, b)) != AFV_OK) return st;
  shape_all(g, n, p, 1);
  g->energy = total_energy(g, n, p);
  gather_forces(g, n, f);
  return AFV_OK;
}

/* ---- finite-difference check ------------------------------------------ */
static int energy_at(afv_geom *g, int n, const double *r, const afv_params *p,
                     const afv_box *b, double *E)
{
  int st = afv_geometry(g, n, r, p, b);
  *E = g->energy;
  return st;
}

int afv_force_check(int n, const double *r, const afv_params *p,
                    const afv_box *b, double h, const double *f,
                    afv_check_report *rep)
{
  afv_geom g;
  double *rr = malloc((size_t)(2 * n + 1) * sizeof(double));
  int st = AFV_OK, c;
  memset(&g, 0, sizeof g);
  memset(rep, 0, sizeof *rep);
  rep->worst_cell = -1;
  if (!rr) return AFV_ENOMEM;
  if (n > 0) memcpy(rr, r, (size_t)(2 * n) * sizeof(double));
  for (c = 0; c < 2 * n; c++)
    if (fabs(f[c]) > rep->force_scale) rep->force_scale = fabs(f[c]);
  for (c = 0; c < 2 * n; c++) {
    double Ep, Em, fd, err;
    rr[c] = r[c] + h;
    if ((st = energy_at(&g, n, rr, p, b, &Ep)) != AFV_OK) break;
    rr[c] = r[c] - h;
    if ((st = energy_at(&g, n, rr, p, b, &Em)) != AFV_OK) break;
    rr[c] = r[c];
    fd = -(Ep - Em) / (2 * h);
    err = fabs(fd - f[c]);
    if (!(err <= rep->max_abs) || rep->worst_cell < 0) {  /* NaN counts */
      rep->max_abs = err;
      rep->worst_cell = c / 2;
      rep->worst_comp = c % 2;
    }
  }
  rep->max_rel = rep->force_scale > 0 ? rep->max_abs / rep->force_scale
                                      : rep->max_abs;
  afv_geom_free(&g);
  free(rr);
  return st;
}

int afv_gradient_check(int n, const double *r, const afv_params *p,
                       const afv_box *b, double h, afv_check_report *rep)
{
  afv_geom g;
  double *f = malloc((size_t)(2 * n + 1) * sizeof(double));
  int st;
  memset(&g, 0, sizeof g);
  memset(rep, 0, sizeof *rep);
  rep->worst_cell = -1;
  if (!f) return AFV_ENOMEM;
  st = afv_compute(&g, n, r, p, b, f);
  afv_geom_free(&g);
  if (st == AFV_OK) st = afv_force_check(n, r, p, b, h, f, rep);
  free(f);
  return st;
}
