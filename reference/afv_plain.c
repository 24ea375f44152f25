/*
** afv_plain.c -- the Active Finite Voronoi model in one plain C99 file.
**
** This file is the model of
**   J. Huang, H. Levine and D. Bi, "Bridging the gap between collective
**   motility and epithelial-mesenchymal transitions through the active
**   finite Voronoi model", Soft Matter 19, 9389 (2023) (arXiv:2303.08276),
** written to be read from top to bottom in one sitting.  It uses nothing
** but the C library: no afv header, no cell list, no hand-written maths,
** no sub-steps.  It is slow (all pairs: O(N^2) per step) and plain.  The
** library (afv.c, geom.c, neighbours.c, dynamics.c) computes the same
** numbers fast; `make twins` checks that both agree (test/twins.c):
** shapes, energy and forces to 1e-12, 100 Euler steps to 1e-9 l.
**
**   make plain && ./reference/afv_plain [N [P0 [v0 [steps [seed]]]]]
**
** THE MODEL.  A tissue is N cells, each given by its centre r_i.  Cell i
** is the disk of radius l about r_i cut by the perpendicular bisector of
** every other centre r_j closer than 2l (a centre farther away puts its
** bisector outside the disk):
**     cell_i = disk(r_i, l)  intersected with  { x : |x - r_i| <= |x - r_j| }.
** Its boundary is straight contact edges (one per touching neighbour) and
** circular arcs of radius l (where no neighbour is near).  With A_i its
** area, P_i its perimeter and L_i its arc length (the free boundary):
**
**   E = sum_i KA (A_i - A0)^2 + KP (P_i - P0)^2 + Lambda L_i            (3)
**   dr_i/dt = mu F_i + v0 n_i,   F_i = -dE/dr_i,
**                                n_i = (cos th_i, sin th_i)              (4)
**   d th_i/dt = eta_i,  <eta_i(t) eta_j(t')> = 2 Dr delta_ij delta(t-t')  (5)
**
** (the paper's equation numbers).  Lengths are in units of l.
** Where (3) comes from (paper, Eq. (1) and the lines after it): cortical
** tensions lambda_c on the contact edges and lambda_n on the arcs, and
** elastic area and perimeter terms.  Completing the square gives (3) with
**     P0 = -lambda_c / (2 KP l),   Lambda = (lambda_n - lambda_c) / KA:
** a large P0 means contacts pull outward (soft, "mesenchymal" cells), a
** positive Lambda makes an arc cost more than a contact, so cells stick.
** The force on a centre is F_i = -grad_i E (after Eq. (3)); v0 n_i is the
** cell's own crawling, along a polarity n_i that diffuses in angle (5).
** The paper's parameters: KA = KP = 1 (k_P = KP/KA = 1), A0 = pi (the
** area of a free cell), Lambda = 0.2, Dr = 0.1, mu = 1, dt = 0.01, and
** N = 400 cells at packing fraction phi = N pi l^2 / L^2 = 0.5 in a
** periodic box of side L; the knobs are P0 (4 to 8.8) and v0 (0 to 2.7).
**
** THE FILE, in reading order:
**   1. parameters and the tissue                      (struct model, tissue)
**   2. neighbours: all pairs closer than 2l, periodic minimum image
**   3. one cell: each bisector's chord clipped by the other half-planes;
**      the arcs; A, P, L
**   4. the energy (3)
**   5. the forces F = -grad E by the chain rule, labelled (F), (A), (V1),
**      (V2) as in the library's afv.c
**   6. a finite-difference check of the forces
**   7. random numbers: splitmix64 and Box-Muller
**   8. the Euler step of (4) and the polarity noise (5)
**   9. the authors' protocol: a random square, relaxation at v0 = 0, then
**      v0 switched on
**  10. the giant cluster N_GC/N, and main
** Compile with -DAFV_PLAIN_NO_MAIN to use the functions from another
** program (the twin check does).
**
** WHAT THE LIBRARY DOES DIFFERENTLY, and why (the same numbers to 1e-12):
**   - neighbours: a cell list and Verlet candidates, O(N) per step instead
**     of O(N^2) (neighbours.c);
**   - the boundary: neighbours sorted by direction, so the kept chords
**     come out in boundary order and the arcs are the gaps between them
**     (geom.c); here the arcs come from the union of the left-out angles;
**   - the forces: each cell writes only its own G_ij and each force is
**     gathered from both cells' G (afv.c, "gather" form), so cells can be
**     computed on threads; G_ij is split along u and t so that centres
**     1e-16 l apart still get the right force;
**   - the step: the same Euler step, in one pass over the cells that
**     also keeps what the step needs (dynamics.c, euler_all);
**   - the noise: Philox per (cell, step), the same for any thread count;
**   - atan2, sin, cos: its own arithmetic, the same bits on every machine.
*/
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* ======================================================================
** 1. Parameters and the tissue
** ====================================================================== */

/* The energy's parameters, Eq. (3) (the paper: l = KA = KP = 1,
** A0 = pi, Lambda = 0.2, P0 from 4 to 8.8). */
typedef struct model {
  double l;        /* maximal cell radius */
  double KA, A0;   /* area modulus and preferred area */
  double KP, P0;   /* perimeter modulus and preferred perimeter */
  double Lambda;   /* extra tension of the arcs */
} model;

/* The motion's parameters, Eqs. (4) and (5) (the paper: mu = 1,
** dt = 0.01, Dr = 0.1, v0 from 0 to 3). */
typedef struct motion {
  double mu, v0, Dr, dt;
} motion;

/* At most this many neighbours closer than 2l per cell.  Disks of radius
** l around centres closer than 2l: a cell of a tissue has about 6. */
#define MAX_NBR 64

/* The tissue: centres, polarity angles and everything computed from them.
** The box is periodic with sides Lx, Ly, or open space if Lx = 0. */
typedef struct tissue {
  int n;
  double Lx, Ly;
  double *r;          /* centres, r[2i], r[2i+1]; never wrapped into the box */
  double *theta;      /* polarity angles */
  /* computed by compute() from r: */
  int *n_nbr;         /* number of neighbours of cell i */
  int *nbr;           /* nbr[i * MAX_NBR + k]: the k-th neighbour of i */
  double *sep;        /* its separation r_j - r_i, minimum image (2 each) */
  double *edge_len;   /* the length of the contact edge with it (0: none) */
  double *A, *P, *L;  /* area, perimeter, arc length of each cell */
  double *F;          /* forces, F[2i], F[2i+1] */
  double E;           /* energy, Eq. (3) */
} tissue;

static int tissue_alloc(tissue *T, int n, double Lx, double Ly)
{
  memset(T, 0, sizeof *T);
  T->n = n;
  T->Lx = Lx;
  T->Ly = Ly;
  T->r = calloc(2 * (size_t)n + 1, sizeof(double));
  T->theta = calloc((size_t)n + 1, sizeof(double));
  T->n_nbr = calloc((size_t)n + 1, sizeof(int));
  T->nbr = calloc((size_t)n * MAX_NBR + 1, sizeof(int));
  T->sep = calloc(2 * (size_t)n * MAX_NBR + 1, sizeof(double));
  T->edge_len = calloc((size_t)n * MAX_NBR + 1, sizeof(double));
  T->A = calloc(3 * (size_t)n + 1, sizeof(double));
  T->P = T->A + n;
  T->L = T->A + 2 * n;
  T->F = calloc(2 * (size_t)n + 1, sizeof(double));
  return T->r && T->theta && T->n_nbr && T->nbr && T->sep && T->edge_len
         && T->A && T->F;
}

static void tissue_free(tissue *T)
{
  free(T->r);
  free(T->theta);
  free(T->n_nbr);
  free(T->nbr);
  free(T->sep);
  free(T->edge_len);
  free(T->A);
  free(T->F);
  memset(T, 0, sizeof *T);
}

/* ======================================================================
** 2. Neighbours: every centre closer than 2l
** ====================================================================== */

/* x wrapped into [0, L). */
static double wrap(double x, double L)
{
  double w = x - L * floor(x / L);
  return w >= L ? 0.0 : w;     /* x = -1e-17 gives L after rounding */
}

/* The separation r_j - r_i.  In a periodic box, both centres are wrapped
** into the box and the difference is folded to its nearest image (the
** minimum image: each component within half a side). */
static void separation(const tissue *T, int i, int j, double *dx, double *dy)
{
  if (T->Lx > 0) {
    *dx = wrap(T->r[2*j], T->Lx) - wrap(T->r[2*i], T->Lx);
    *dy = wrap(T->r[2*j+1], T->Ly) - wrap(T->r[2*i+1], T->Ly);
    *dx -= T->Lx * round(*dx / T->Lx);
    *dy -= T->Ly * round(*dy / T->Ly);
  } else {
    *dx = T->r[2*j] - T->r[2*i];
    *dy = T->r[2*j+1] - T->r[2*i+1];
  }
}

/* Every pair (i, j) closer than 2l, by trying all pairs: O(N^2), the
** plainest search (the library uses a cell list).  Why 2l is enough: the
** bisector of a pair at distance d lies d/2 from each centre, and d/2 >= l
** puts it outside the open disk, where it cuts nothing.  In a periodic
** box each pair counts once, at its nearest image; that is right while
** the box is wider than 4l (then no cell meets two images of another
** within 2l; the library refuses smaller boxes).  Returns 0, or -1 if two
** centres coincide (their bisector is undefined) or a cell has more than
** MAX_NBR neighbours. */
static int find_neighbours(tissue *T, double l)
{
  int i, j;
  for (i = 0; i < T->n; i++) T->n_nbr[i] = 0;
  for (i = 0; i < T->n; i++)
    for (j = i + 1; j < T->n; j++) {
      double dx, dy, d2;
      separation(T, i, j, &dx, &dy);
      d2 = dx * dx + dy * dy;
      if (!(d2 < 4 * l * l)) continue;
      if (d2 == 0 || T->n_nbr[i] == MAX_NBR || T->n_nbr[j] == MAX_NBR)
        return -1;
      /* the pair goes into both lists, each with its own separation */
      T->nbr[i * MAX_NBR + T->n_nbr[i]] = j;
      T->sep[2 * (i * MAX_NBR + T->n_nbr[i])] = dx;
      T->sep[2 * (i * MAX_NBR + T->n_nbr[i]) + 1] = dy;
      T->n_nbr[i]++;
      T->nbr[j * MAX_NBR + T->n_nbr[j]] = i;
      T->sep[2 * (j * MAX_NBR + T->n_nbr[j])] = -dx;
      T->sep[2 * (j * MAX_NBR + T->n_nbr[j]) + 1] = -dy;
      T->n_nbr[j]++;
    }
  return 0;
}

/* ======================================================================
** 3. One cell: the disk clipped by the bisector half-planes
** ====================================================================== */
/* Work in coordinates centred on r_i.  Neighbour k sits at D = r_k - r_i,
** d = |D|, u = D/d; t = (-u_y, u_x) turns u by +90 degrees.  Its bisector
** is the line x.u = h with h = d/2, and the cell lies on the side
** x.u <= h.  The line cuts the disk in a chord: the points
**     x = h u + tau t,   -s <= tau <= s,   s = sqrt(l^2 - h^2),
** with tau increasing counter-clockwise around the cell.  The contact
** edge with k is the part of this chord inside every other half-plane. */
typedef struct chord {
  double Dx, Dy, d;      /* D = r_k - r_i and d = |D| */
  double ux, uy, tx, ty; /* u = D/d and t = (-u_y, u_x) */
  double h, s;           /* the line x.u = h; half-chord s */
  double tau0, tau1;     /* the kept part (an edge if tau0 < tau1) */
  int from, to;          /* the neighbour (index into the chords) whose
                         ** line cut it at tau0, at tau1; -1: the circle */
} chord;

/* The chord of the neighbour at D. */
static chord chord_of(double Dx, double Dy, double l)
{
  chord c;
  c.Dx = Dx;
  c.Dy = Dy;
  c.d = sqrt(Dx * Dx + Dy * Dy);
  c.ux = Dx / c.d;
  c.uy = Dy / c.d;
  c.tx = -c.uy;
  c.ty = c.ux;
  c.h = 0.5 * c.d;
  /* (l - h)(l + h), not l*l - h*h: exact where h is close to l, where a
  ** contact is about to break and the force depends on s sharply */
  c.s = sqrt((l - c.h) * (l + c.h));
  c.tau0 = -c.s;
  c.tau1 = c.s;
  c.from = c.to = -1;
  return c;
}

/* Clips chord a by the half-plane x.u_b <= h_b of chord b.  On a's line,
** x = h_a u_a + tau t_a, so the half-plane reads  tau c <= rhs  with
** c = t_a.u_b and rhs = h_b - h_a u_a.u_b: an upper bound on tau if
** c > 0, a lower bound if c < 0.  Parallel lines (c = 0): the half-plane
** holds the whole line or none of it. */
/* An end cut by b's line is a triple junction: the point as far from r_i
** as from r_a and r_b, the centre of the circle through the three
** centres.  An end left at tau = -+s lies on the circle: an arc meets the
** edge there. */
static void clip(chord *a, const chord *b, int b_index)
{
  double c = a->tx * b->ux + a->ty * b->uy;
  double rhs = b->h - a->h * (a->ux * b->ux + a->uy * b->uy);
  if (c > 0 && rhs / c < a->tau1) {
    a->tau1 = rhs / c;
    a->to = b_index;            /* a triple junction: a's edge ends on b */
  } else if (c < 0 && rhs / c > a->tau0) {
    a->tau0 = rhs / c;
    a->from = b_index;          /* a's edge starts on b */
  } else if (c == 0 && rhs < 0) {
    a->tau1 = a->tau0;          /* b's half-plane holds none of a's line */
  }
}

/* The total angle of the circle |x| = l that lies in every half-plane,
** i.e. the arcs of the cell.  The half-plane of chord k leaves out of the
** circle the angles within w_k = atan2(s_k, h_k) of u_k's direction (the
** chord's ends, h u +- s t, lie at exactly these angles); the arcs are
** what is left of 2 pi after the union of these intervals.  Example: two
** cells at distance d = 1.2 l: w = atan2(0.8, 0.6) = 0.927, so each keeps
** an arc of 2 pi - 1.855 = 4.43 (L = 4.43 l), and their shared edge is
** the whole chord, 2s = 1.6 l long.  The union is measured after sorting
** the intervals by their start (qsort); an interval that crosses angle 0
** is split in two. */
static int by_start(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double arc_angle(const chord *c, int m)
{
  double iv[4 * MAX_NBR];       /* intervals [start, end] within [0, 2 pi] */
  double covered = 0, reach = 0;
  int k, q = 0;
  for (k = 0; k < m; k++) {
    double w = atan2(c[k].s, c[k].h), lo = atan2(c[k].uy, c[k].ux) - w;
    if (lo < 0) lo += 2 * PI;
    if (lo + 2 * w <= 2 * PI) {
      iv[2*q] = lo;
      iv[2*q+1] = lo + 2 * w;
      q++;
    } else {                    /* wraps past 2 pi: two pieces */
      iv[2*q] = lo;
      iv[2*q+1] = 2 * PI;
      iv[2*q+2] = 0;
      iv[2*q+3] = lo + 2 * w - 2 * PI;
      q += 2;
    }
  }
  qsort(iv, (size_t)q, 2 * sizeof(double), by_start);
  for (k = 0; k < q; k++) {     /* the union's length, left to right */
    double lo = iv[2*k] > reach ? iv[2*k] : reach;
    if (iv[2*k+1] > lo) covered += iv[2*k+1] - lo;
    if (iv[2*k+1] > reach) reach = iv[2*k+1];
  }
  return covered >= 2 * PI ? 0 : 2 * PI - covered;
}

/* The shape of cell i: its chords, clipped (c[0 .. m-1], m = its
** neighbours), and A, P, L.  In polar form about r_i, the area is half the
** integral of x cross dx around the boundary: an edge at distance h from
** r_i adds h ell / 2 (a triangle of height h), an arc of angle phi adds
** l^2 phi / 2 (a sector).  The perimeter is the edges' lengths plus the
** arcs' l phi, and the arc length L is l phi.  None of these sums needs
** the pieces in boundary order (the library sorts its neighbours by
** direction to walk the boundary; here nothing is sorted but the arcs'
** intervals).  The cell is convex and holds r_i (r_i is nearer to itself
** than to any r_j), so every triangle and sector is counted with a
** positive sign.  A neighbour closer than 2l whose chord is clipped away
** entirely (another neighbour's half-plane hides it) has no edge: it
** shapes nothing and is no contact. */
static int cell_shape(tissue *T, int i, double l, chord *c)
{
  int m = T->n_nbr[i], a, b;
  double phi, A = 0, P = 0;
  for (a = 0; a < m; a++) {
    const double *D = T->sep + 2 * (i * MAX_NBR + a);
    c[a] = chord_of(D[0], D[1], l);
  }
  /* every chord by every other half-plane: O(m^2) for m neighbours, about
  ** 36 clips for a cell of a tissue */
  for (a = 0; a < m; a++)
    for (b = 0; b < m; b++)
      if (b != a) clip(&c[a], &c[b], b);
  for (a = 0; a < m; a++) {
    double ell = c[a].tau1 > c[a].tau0 ? c[a].tau1 - c[a].tau0 : 0;
    T->edge_len[i * MAX_NBR + a] = ell;
    A += 0.5 * c[a].h * ell;
    P += ell;
  }
  phi = arc_angle(c, m);       /* 2 pi for a cell without neighbours */
  /* Worked example, the lens (two cells 1.2 l apart, l = 1): each has the
  ** edge 2s = 1.6 at h = 0.6 and phi = 4.428595, so
  **   A = 0.6 * 1.6 / 2 + 4.428595 / 2 = 2.694297,
  **   P = 1.6 + 4.428595 = 6.028595,   L = 4.428595. */
  T->A[i] = A + 0.5 * l * l * phi;
  T->P[i] = P + l * phi;
  T->L[i] = l * phi;
  return m;
}

/* ======================================================================
** 4. The energy, Eq. (3)
** ====================================================================== */

/* e_i, the term of cell i in Eq. (3). */
static double cell_energy(const model *M, double A, double P, double L)
{
  return M->KA * (A - M->A0) * (A - M->A0) + M->KP * (P - M->P0) * (P - M->P0)
         + M->Lambda * L;
}

/* ======================================================================
** 5. The forces F_i = -dE/dr_i (paper, after Eq. (3))
** ====================================================================== */
/* The chain rule.  With wA = 2 KA (A_i - A0), wP = 2 KP (P_i - P0) and
** wL = Lambda (de_i/dA_i, de_i/dP_i, de_i/dL_i),
**     G_ij := de_i/dr_j = wA dA_i/dr_j + wP dP_i/dr_j + wL dL_i/dr_j.
** Cell i's shape depends on r_i and on its neighbours' r_j.  Moving all of
** them together moves the shape rigidly, so de_i/dr_i = - sum_j G_ij, and
**     F_i = -de_i/dr_i - sum_{k != i} de_k/dr_i
**         = sum_j G_ij - sum_k G_ki.                                   (F)
** So each cell i, for each neighbour j, adds G_ij to F_i and takes it
** from F_j (forces sum to zero).
**
** It remains to find dA_i, dP_i, dL_i for a move of one neighbour r_j,
** r_i fixed (cell frame, D = r_j - r_i).  Moving r_j moves only j's line.
**
** Area (Reynolds transport).  A point x of the bisector moves, along u,
** by (D - x).dr / d when D moves by dr.  Over the edge (length ell,
** midpoint m) this sweeps
**     dA_i/dr_j = (ell / d) (D - m).                                    (A)
**
** Perimeter and arc length.  Both are sums of the lengths of the pieces
** between the boundary's vertices.  Moving one vertex V by dV changes the
** piece arriving at V (counter-clockwise) by t_in.dV and the piece
** leaving it by -t_out.dV (t_in, t_out: their unit tangents at V; an arc
** keeps its circle, so only its angle changes).  So for a vertex V that
** moves with r_j:
**     dP_i/dr_j += (dV/dr_j)^T (t_in - t_out),
**     dL_i/dr_j += (dV/dr_j)^T (t_in if an arc arrives, -t_out if one leaves).
** Two kinds of vertex move with r_j:
**
** (V1) an end of j's edge on the circle.  V = D/2 + sigma (s/d) R D, with
**     R the rotation by +90 degrees, sigma = -1 at the edge's start (an
**     arc arrives there) and +1 at its end (an arc leaves).  Since
**     s = sqrt(l^2 - d^2/4), ds/dd = -d/(4s), and d(D/d) = (I - u u^T)/d,
**       (dV/dD)^T w = w/2 + sigma (s/d) R^T w - sigma l^2/(d s) (t.w) u.
**     The last term diverges like (2l - d)^(-1/2) as the contact is about
**     to break: the exact force does too (integrably).
** (V2) a triple junction of j's line and another neighbour k's line.
**     Moving r_j slides V along k's line (direction e = t_k, fixed) by
**     alpha, where V stays equidistant from r_i and r_j: V.D = |D|^2 / 2
**     gives alpha (e.D) = (D - V).dr, so
**       (dV/dD)^T w = (D - V) (e.w) / (e.D),    e = t_k.
**     Both pieces at a junction are edges, so only P changes there.
** Every formula is checked against central differences of E (section 6).
**
** Where the chain rule is steep.  As a contact is about to break
** (d -> 2l) the edge's length 2s -> 0 like (2l - d)^(1/2), and its ends
** race along the circle: ds/dd = -d/(4s) diverges.  So does the force,
** like (2l - d)^(-1/2), yet E stays continuous (the divergence is
** integrable).  An Euler step that lands a pair just inside 2l can throw
** it far apart; the paper's Euler step does so, and so do this file and
** the library.
** At a triple junction exactly on the circle E has a kink: moving a cell
** outward opens an arc there and moving it inward does not, so the two
** one-sided derivatives differ and F is not defined; a random tissue
** meets that with probability zero. */

/* (dV/dD)^T w for an arc end of chord c, (V1). */
static void arc_end_pull(const chord *c, double sigma, double l, double wx,
                         double wy, double *gx, double *gy)
{
  double tw = c->tx * wx + c->ty * wy;      /* t.w */
  double radial = sigma * l * l / (c->d * c->s) * tw;
  /* R^T w = (w_y, -w_x) */
  *gx += 0.5 * wx + sigma * (c->s / c->d) * wy - radial * c->ux;
  *gy += 0.5 * wy - sigma * (c->s / c->d) * wx - radial * c->uy;
}

/* (dV/dD)^T w for the junction V of chord c's line with the line of
** direction (ex, ey), (V2). */
static void junction_pull(const chord *c, double Vx, double Vy, double ex,
                          double ey, double wx, double wy, double *gx,
                          double *gy)
{
  double k = (ex * wx + ey * wy) / (ex * c->Dx + ey * c->Dy);
  *gx += (c->Dx - Vx) * k;
  *gy += (c->Dy - Vy) * k;
}

/* G_ij for every neighbour of cell i (chords c, clipped by cell_shape),
** added to the forces by (F). */
static void cell_forces(tissue *T, int i, const model *M, const chord *c)
{
  double wA = 2 * M->KA * (T->A[i] - M->A0);
  double wP = 2 * M->KP * (T->P[i] - M->P0);
  double wL = M->Lambda, l = M->l;
  double G[2 * MAX_NBR];
  int m = T->n_nbr[i], a;
  memset(G, 0, sizeof G);
  /* Walk the edges.  Edge a runs counter-clockwise from V0 (tau0) to V1
  ** (tau1).  At V0 the boundary arrives from an arc (if V0 is on the
  ** circle) or from another edge (a junction); at V1 it leaves along an
  ** arc or along the edge of e->to.  Every junction is the end V1 of
  ** exactly one edge, so handling junctions at V1 alone counts each once;
  ** every arc end is V0 or V1 of its own edge. */
  for (a = 0; a < m; a++) {
    const chord *e = &c[a];
    double ell, mid, x0, y0, x1, y1;
    if (!(e->tau1 > e->tau0)) continue;     /* no edge: nothing moves */
    ell = e->tau1 - e->tau0;
    mid = 0.5 * (e->tau0 + e->tau1);
    /* (A): (ell/d)(D - m), with D - m = h u - mid t (D = 2h u) */
    G[2*a] += wA * ell / e->d * (e->h * e->ux - mid * e->tx);
    G[2*a+1] += wA * ell / e->d * (e->h * e->uy - mid * e->ty);
    x0 = e->h * e->ux + e->tau0 * e->tx;    /* the edge's start V0 */
    y0 = e->h * e->uy + e->tau0 * e->ty;
    x1 = e->h * e->ux + e->tau1 * e->tx;    /* and its end V1 */
    y1 = e->h * e->uy + e->tau1 * e->ty;
    /* The circle's counter-clockwise tangent at a point V on it is R V / l
    ** = (-V_y, V_x) / l.  The weights w below are wP (t_in - t_out) for P
    ** plus wL times t_in (an arc arrives) or -t_out (an arc leaves) for L,
    ** as in the rule above. */
    if (e->from < 0) {
      /* (V1) at V0: the arc arrives (tangent R V0 / l), the edge leaves */
      double ax = -y0 / l, ay = x0 / l;
      arc_end_pull(e, -1, l, wP * (ax - e->tx) + wL * ax,
                   wP * (ay - e->ty) + wL * ay, &G[2*a], &G[2*a+1]);
    }
    if (e->to < 0) {
      /* (V1) at V1: the edge arrives, the arc leaves (tangent R V1 / l) */
      double ax = -y1 / l, ay = x1 / l;
      arc_end_pull(e, +1, l, wP * (e->tx - ax) - wL * ax,
                   wP * (e->ty - ay) - wL * ay, &G[2*a], &G[2*a+1]);
    } else {
      /* (V2) at V1: a's edge arrives, b's edge leaves; V1 is on both
      ** lines, so it moves with r_a (along b's line) and with r_b (along
      ** a's line); w = t_in - t_out = t_a - t_b for the perimeter */
      int b = e->to;
      const chord *f = &c[b];
      double wx = wP * (e->tx - f->tx), wy = wP * (e->ty - f->ty);
      junction_pull(e, x1, y1, f->tx, f->ty, wx, wy, &G[2*a], &G[2*a+1]);
      junction_pull(f, x1, y1, e->tx, e->ty, wx, wy, &G[2*b], &G[2*b+1]);
    }
  }
  /* (F): G_ia is de_i/dr_a; it pushes a by -G_ia and, since de_i/dr_i
  ** = -sum_a G_ia, pushes i by +G_ia (Newton's third law, pair by pair) */
  for (a = 0; a < m; a++) {                 /* (F) */
    int j = T->nbr[i * MAX_NBR + a];
    T->F[2*i] += G[2*a];
    T->F[2*i+1] += G[2*a+1];
    T->F[2*j] -= G[2*a];
    T->F[2*j+1] -= G[2*a+1];
  }
}

/* Neighbours, shapes, the energy (3) and, if `forces`, F = -grad E.
** Returns 0, or -1 if two centres coincide or a cell is too crowded. */
static int compute(tissue *T, const model *M, int forces)
{
  chord c[MAX_NBR];
  int i;
  if (find_neighbours(T, M->l) != 0) return -1;
  T->E = 0;
  for (i = 0; i < 2 * T->n; i++) T->F[i] = 0;
  for (i = 0; i < T->n; i++) {
    cell_shape(T, i, M->l, c);
    T->E += cell_energy(M, T->A[i], T->P[i], T->L[i]);     /* Eq. (3) */
    if (forces) cell_forces(T, i, M, c);
  }
  return 0;
}

/* ======================================================================
** 6. The finite-difference check
** ====================================================================== */
/* Each force component against the central difference
**     -(E(r + h e_q) - E(r - h e_q)) / (2h),
** which is off by O(h^2 E''') from truncation and by about eps E / h from
** rounding (eps = 2.2e-16): h = 1e-6 l balances the two for E of order
** 100 and gives a few 1e-8 of max |F| in a relaxed tissue.  Near a
** contact about to break E''' grows like (2l - d)^(-5/2), and there the
** difference quotient, not the analytic force, is what is off.  The whole
** tissue's E is recomputed for every component: O(N^3) with the all-pairs
** search, fine for the tens of cells it is meant for.  Returns the largest
** difference, relative to max(max |F|, 1); F stays that of r. */
static double fd_check(tissue *T, const model *M, double h)
{
  double *F = malloc(2 * (size_t)T->n * sizeof(double) + 1);
  double worst = 0, scale = 1;
  int q;
  if (!F || compute(T, M, 1) != 0) {
    free(F);
    return INFINITY;
  }
  memcpy(F, T->F, 2 * (size_t)T->n * sizeof(double));
  for (q = 0; q < 2 * T->n; q++)
    if (fabs(F[q]) > scale) scale = fabs(F[q]);
  for (q = 0; q < 2 * T->n; q++) {
    double r = T->r[q], Ep, Em, diff;
    T->r[q] = r + h;
    compute(T, M, 0);
    Ep = T->E;
    T->r[q] = r - h;
    compute(T, M, 0);
    Em = T->E;
    T->r[q] = r;
    diff = fabs(-(Ep - Em) / (2 * h) - F[q]);
    if (!(diff <= worst)) worst = diff;      /* NaN counts as worst */
  }
  compute(T, M, 1);
  free(F);
  return worst / scale;
}

/* ======================================================================
** 7. Random numbers
** ====================================================================== */
/* splitmix64 (Steele, Lea and Flood 2014): a 64-bit state advanced by a
** constant, then mixed.  Good enough for noise, and four lines long; one
** seed gives one run, on every machine whose libm rounds alike.  (The
** library draws the noise of cell i at step s from a counter-based
** generator, Philox, so that its runs do not depend on the order in which
** threads draw; a single sequence is plainer.) */
typedef struct rng {
  unsigned long long state;
} rng;

static unsigned long long rng_next(rng *g)
{
  unsigned long long z = (g->state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1): the top 53 bits. */
static double rng_uniform(rng *g)
{
  return (double)(rng_next(g) >> 11) * (1.0 / 9007199254740992.0);
}

/* Standard normal, by Box-Muller (one of the pair is used). */
static double rng_normal(rng *g)
{
  double u = 1 - rng_uniform(g);             /* (0, 1]: log(u) is finite */
  return sqrt(-2 * log(u)) * cos(2 * PI * rng_uniform(g));
}

/* ======================================================================
** 8. The Euler step: Eqs. (4) and (5)
** ====================================================================== */
/* One step of dt, Euler-Maruyama, as the paper integrates ("10^6
** integration steps with a step size dt = 0.01 using Euler's method"):
**     r_i  <- r_i + dt (mu F_i + v0 n_i),    n_i = (cos th_i, sin th_i)  (4)
**     th_i <- th_i + sqrt(2 Dr dt) xi_i,     xi_i ~ N(0, 1)              (5)
** both from the state at the start of the step, then F at the new r.
** Why sqrt(2 Dr dt): over a time dt the white noise eta_i of (5), with
** <eta_i(t) eta_i(t')> = 2 Dr delta(t - t'), adds up to a normal angle of
** variance 2 Dr dt; the polarity forgets its direction in a time 1/Dr.
** Every cell moves by the whole step: no sub-steps and no refusal of a
** large move (the library's step is this one).  Centres are never wrapped, so
** r_i(t) - r_i(0) is the true displacement.  T->F must be the force at r
** (compute).  Returns compute's status at the new r. */
static int euler_step(tissue *T, const model *M, const motion *mo, rng *g)
{
  int i;
  for (i = 0; i < T->n; i++) {
    T->r[2*i] += mo->dt * (mo->mu * T->F[2*i] + mo->v0 * cos(T->theta[i]));
    T->r[2*i+1] += mo->dt * (mo->mu * T->F[2*i+1] + mo->v0 * sin(T->theta[i]));
  }
  if (mo->Dr > 0)
    for (i = 0; i < T->n; i++)
      T->theta[i] += sqrt(2 * mo->Dr * mo->dt) * rng_normal(g);   /* (5) */
  return compute(T, M, 1);
}

/* ======================================================================
** 9. The authors' protocol
** ====================================================================== */
/* The periodic box side for N cells at packing fraction phi = N pi l^2 / L^2
** (the paper: phi = 0.5). */
static double box_side(int n, double phi, double l)
{
  return sqrt(n * PI * l * l / phi);
}

/* The start: N centres uniform in a square of side 0.3 L centred in the
** box, and polarity angles uniform in [0, 2 pi).  The paper: "We
** initialize systems as one large connected cluster and relax it to
** steady state at zero temperature ... We then turn on v0".  At N = 400
** and phi = 0.5, L = 50.1 l and the square's side is 15 l: 1.8 centres
** per l^2, far denser than a tissue of cells of area pi (0.32 per l^2),
** so the relaxation first spreads the cluster out; being random, a few
** pairs start nearly on top of each other and are pushed apart hard. */
static void start_square(tissue *T, rng *g)
{
  double side = 0.3 * T->Lx, x0 = 0.5 * (T->Lx - side);
  double y0 = 0.5 * (T->Ly - side);
  int i;
  for (i = 0; i < T->n; i++) {
    T->r[2*i] = x0 + side * rng_uniform(g);
    T->r[2*i+1] = y0 + side * rng_uniform(g);
  }
  for (i = 0; i < T->n; i++) T->theta[i] = 2 * PI * rng_uniform(g);
}

/* max_i |F_i| of the forces last computed. */
static double max_force(const tissue *T)
{
  double most = 0;
  int i;
  for (i = 0; i < T->n; i++) {
    double f = hypot(T->F[2*i], T->F[2*i+1]);
    if (f > most) most = f;
  }
  return most;
}

/* Relaxation: Euler steps at v0 = 0 and Dr = 0 (overdamped descent of E:
** dr_i/dt = mu F_i = -mu grad_i E, so E can only decrease, to first order
** in dt) until max |F| <= tol or `steps` steps.  Returns the steps taken,
** or -1; max_force(T) <= tol tells whether it got there.  (The library's
** afv_relax also stops when E no longer decreases because the tissue
** sits at a kink of E: the plain file runs on to the cap there.) */
static int relax(tissue *T, const model *M, const motion *mo, int steps,
                 double tol, rng *g)
{
  motion still = *mo;
  int k;
  still.v0 = 0;
  still.Dr = 0;
  if (compute(T, M, 1) != 0) return -1;
  for (k = 0; k < steps && max_force(T) > tol; k++)
    if (euler_step(T, M, &still, g) != 0) return -1;
  return k;
}

/* ======================================================================
** 10. The giant cluster, and main
** ====================================================================== */
/* The paper's first order parameter: "two cells belong to the same
** contiguous cluster if they share a contacting edge"; the giant cluster
** is the largest, and N_GC/N its share of the cells.  Two cells are in
** contact here if they share an edge longer than 1e-9 l (the library's
** AFV_CONTACT_TOL), seen from either cell.  (The paper adds "or
** equivalently, when the distance between their centers is less than
** 2l"; not quite: a pair closer than 2l can be hidden from each other by a
** third cell, as in section 3.)  Clusters are the connected parts of the
** contact graph, by union-find: each cell points towards the root of its
** cluster, and a contact joins two roots.  The paper finds N_GC/N = 1 at
** small v0 and a dispersal as v0 grows, the curves of all P0 crossing
** near v0* = 1.85. */
static int root_of(int *parent, int i)
{
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

static double giant_cluster_fraction(const tissue *T, double l)
{
  int *parent = malloc((size_t)T->n * 2 * sizeof(int) + 1), *size, i, k;
  int largest = 0;
  if (!parent || T->n == 0) {
    free(parent);
    return 0;
  }
  size = parent + T->n;
  for (i = 0; i < T->n; i++) {
    parent[i] = i;
    size[i] = 0;
  }
  for (i = 0; i < T->n; i++)
    for (k = 0; k < T->n_nbr[i]; k++)
      if (T->edge_len[i * MAX_NBR + k] > 1e-9 * l) {
        int a = root_of(parent, i);
        int b = root_of(parent, T->nbr[i * MAX_NBR + k]);
        if (a != b) parent[a] = b;
      }
  for (i = 0; i < T->n; i++) {
    int s = ++size[root_of(parent, i)];
    if (s > largest) largest = s;
  }
  free(parent);
  return (double)largest / T->n;
}

#ifndef AFV_PLAIN_NO_MAIN
/* A tissue of N cells (default 100) at the paper's parameters and
** phi = 0.5: the random square, relaxed (at most 2000 steps, until
** max |F| <= 1e-3), the forces checked against finite differences, then
** `steps` (default 5000) active steps at v0, printing the time, E and
** N_GC/N every 500 steps.  What to expect: at P0 = 4.8 and v0 = 0.5 the
** relaxed cluster stays whole (N_GC/N = 1) and E fluctuates about its
** relaxed value; at v0 = 2.6 it breaks up and N_GC/N falls.  The paper's
** runs are 400 cells for 10^6 steps: about an hour here, where the
** library (afv run) takes a few minutes. */
#define RELAX_STEPS 2000   /* the relaxation's cap, in Euler steps */
#define RELAX_TOL 1e-3     /* ... and the max |F| it relaxes to */

int main(int argc, char **argv)
{
  model M = {1, 1, PI, 1, 4.8, 0.2};     /* l, KA, A0, KP, P0, Lambda */
  motion mo = {1, 0.5, 0.1, 0.01};       /* mu, v0, Dr, dt */
  int n = argc > 1 ? atoi(argv[1]) : 100, steps = 5000, k, relaxed;
  rng g;
  tissue T;
  double L, fd;
  if (argc > 2) M.P0 = atof(argv[2]);
  if (argc > 3) mo.v0 = atof(argv[3]);
  if (argc > 4) steps = atoi(argv[4]);
  g.state = argc > 5 ? strtoull(argv[5], NULL, 10) : 1;
  if (n < 2 || steps < 0 || argc > 6) {
    fprintf(stderr, "usage: afv_plain [N [P0 [v0 [steps [seed]]]]]\n");
    return 2;
  }
  L = box_side(n, 0.5, M.l);
  if (!tissue_alloc(&T, n, L, L)) {
    fprintf(stderr, "afv_plain: out of memory\n");
    return 1;
  }
  start_square(&T, &g);
  relaxed = relax(&T, &M, &mo, RELAX_STEPS, RELAX_TOL, &g);
  if (relaxed < 0) {
    fprintf(stderr, "afv_plain: two centres coincide or a cell has more "
            "than %d neighbours\n", MAX_NBR);
    tissue_free(&T);
    return 1;
  }
  fd = fd_check(&T, &M, 1e-6);
  printf("# N %d, box %.4g l, P0 %g, v0 %g, Dr %g, dt %g\n", n, L, M.P0,
         mo.v0, mo.Dr, mo.dt);
  if (max_force(&T) <= RELAX_TOL)
    printf("# relaxed to max |F| <= %g in %d steps", RELAX_TOL, relaxed);
  else     /* the cap: a kink of E, or a start too far from a minimum */
    printf("# not relaxed: max |F| %.3g after the cap of %d steps",
           max_force(&T), RELAX_STEPS);
  printf("; forces against finite differences: %.2g of max |F|\n", fd);
  /* one line per 500 steps: the time t = k dt, E (Eq. (3),
  ** summed over all cells) and the giant cluster's share of the cells */
  printf("%10s %16s %8s\n", "t", "E", "N_GC/N");
  for (k = 0; k <= steps; k++) {
    if (k % 500 == 0)
      printf("%10.2f %16.8f %8.4f\n", k * mo.dt, T.E,
             giant_cluster_fraction(&T, M.l));
    if (k < steps && euler_step(&T, &M, &mo, &g) != 0) {
      fprintf(stderr, "afv_plain: two centres coincide at step %d\n", k);
      tissue_free(&T);
      return 1;
    }
  }
  tissue_free(&T);
  return 0;
}
#endif
