/*
** afv.h -- the Active Finite Voronoi (AFV) model: public C99 API.
**
** A tissue is N cells, each given by its centre r_i.  Cell i is the disk of
** radius l about r_i, clipped by the perpendicular-bisector half-plane of
** every other centre closer than 2l.  Its boundary is a cyclic sequence of
** straight contact edges (shared with one neighbour) and circular arcs of
** radius l (free, non-contacting boundary).  The energy (paper, Eq. (3)) is
**
**     E = sum_i KA_i (A_i - A0_i)^2 + KP_i (P_i - P0_i)^2 + Lambda L_i
**
** with A_i the area, P_i the perimeter and L_i the arc length of cell i.
** Forces are F_i = -dE/dr_i, exact and analytic (see afv.c).
**
** Conventions: positions are interleaved, r[2i] = x_i, r[2i+1] = y_i; so are
** forces.  The caller owns positions and forces; the library owns what is in
** an afv_geom.  Library functions never exit: they return a status code.
**
** Contents (in this order below)
**   version, status codes              AFV_VERSION, afv_strerror
**   status codes and tolerances        afv_config.h (AFV_OK, AFV_CONTACT_TOL, ..)
**   parameters, boundary               afv_params, afv_box
**   geometry, energy and forces        afv_geom, afv_geometry, afv_compute
**   cell order                         afv_spatial_order
**   gradient check                     afv_gradient_check, afv_force_check
**   simulation                         afv_dyn, afv_sim, afv_sim_step,
**                                      afv_relax, afv_relax_fire
**   initial configurations             afv_init_cluster, afv_init_lattice, ..
**   the paper's protocol               afv_protocol, afv_protocol_start
**   files a user reads or writes       POINTS, trajectories, CELLS
**   order parameters and analysis      afv_clusters, afv_t1, afv_msd,
**                                      afv_analysis, afv_meanfield_p0
**   pictures                           afv_svg_write, afv_svg_draw
**   bindings (Python's ctypes)         afv_version, afv_dyn_new, ..,
**                                      afv_order_parameters, afv_svg_save,
**                                      afv_traj_new, afv_analysis_new, ..
** Names: afv_<object>_<verb> (afv_sim_step, afv_traj_read), with the
** model's two calls afv_geometry and afv_compute.  What only the afv
** program uses (line readers, checkpoints, plots, fits, the noise
** streams) is in afv_tool.h, which is not installed.
*/
#ifndef AFV_H
#define AFV_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* ---- version ------------------------------------------------------------ */
/* The library's version (semantic versioning); the program prints it with
** `afv --version`, and the Makefile reads it from here. */
#define AFV_VERSION_MAJOR 0
#define AFV_VERSION_MINOR 5
#define AFV_VERSION_PATCH 0
#define AFV_VERSION "0.5.0"

/* ---- status codes and tolerances (afv_config.h) ------------------------- */
/* The status codes AFV_OK, AFV_ENOMEM, ..., AFV_EUNSTABLE and every
** tolerance (AFV_CONTACT_TOL, AFV_MAX_STEP_DISP, AFV_RUNAWAY_MOVE,
** AFV_RELAX_KINK_*, ...), each with its meaning: */
#include "afv_config.h"

const char *afv_strerror(int status);   /* one-line description of a status */

/* ---- parameters -------------------------------------------------------- */
typedef struct afv_params {
  double l;        /* maximal cell radius; the length unit (> 0) */
  double KA;       /* area modulus (>= 0) */
  double KP;       /* perimeter modulus (>= 0) */
  double A0;       /* preferred area */
  double P0;       /* preferred perimeter */
  double Lambda;   /* extra tension of the free (arc) boundary */
  double cap;      /* contact cap delta >= 0; 0 = exact gradient.  With
                   ** delta > 0 the arc-end derivatives use
                   ** max(sqrt(4l^2 - d^2), delta): the force is then NOT
                   ** -grad E, only close to it.  Default 0. */
  const double *KA_i, *KP_i, *A0_i, *P0_i;
                   /* optional per-cell values (length N, caller-owned);
                   ** NULL means every cell uses the scalar above */
} afv_params;

/* Paper defaults: l = 1, KA = KP = 1, A0 = pi, P0 = 4.8, Lambda = 0.2, cap 0. */
void afv_params_default(afv_params *p);
/* AFV_OK if every value (and per-cell value, for n cells) is finite and in range. */
int  afv_params_check(const afv_params *p, int n);

/* ---- boundary ---------------------------------------------------------- */
typedef struct afv_box {
  int    periodic;  /* 0: open space; 1: periodic Lx x Ly, minimum image */
  double Lx, Ly;    /* box sides (periodic only); each must be >= 4 l so a
                    ** cell meets at most one image of any other cell */
} afv_box;

/* Minimum-image displacement: replaces (*dx, *dy) by its nearest image. */
void afv_min_image(const afv_box *b, double *dx, double *dy);
/* Wraps a position into [0, Lx) x [0, Ly) (no-op in open space). */
void afv_wrap(const afv_box *b, double *x, double *y);

/* ---- geometry ---------------------------------------------------------- */
#define AFV_ARC (-1)   /* afv_piece.nbr of a circular arc */

/* One piece of a cell boundary.  Pieces run counter-clockwise; piece k
** starts where piece k-1 ends (cyclically).  The vertex at the start of
** piece k is a triple junction of (i, nbr[k-1], nbr[k]) when both pieces are
** edges, and an arc end on the bisector of i and the edge's owner when one of
** them is an arc.  An isolated cell has one arc piece and no vertex. */
typedef struct afv_piece {
  int    nbr;     /* cell on the other side of this edge, or AFV_ARC */
  int    slot;    /* for an edge: the library's index of this neighbour
                  ** (afv_internal.h: nbr_start[i] <= slot < nbr_end[i]);
                  ** -1 for an arc */
  double x, y;    /* start vertex, relative to the cell centre */
  double length;  /* edge length or arc length (>= 0) */
  double tau;     /* for an edge: where its start vertex lies along the
                  ** bisector, x = h u + tau t (u = D/d, h = d/2, t = u
                  ** turned by +90 degrees), so that the end is at
                  ** tau + length; as computed by the clipping, to
                  ** relative precision even where h is tiny (afv.c needs
                  ** it there: the forces of nearly coincident cells);
                  ** 0 for an arc */
} afv_piece;

/* Geometry of a whole tissue, filled by afv_compute (or afv_geometry).
** Opaque: its buffers grow as needed and are reused between calls; read
** it through the calls below.  Every pointer returned stays valid until
** the next afv_compute/afv_geometry on g or afv_geom_delete(g). */
typedef struct afv_geom afv_geom;

/* A new, empty geometry (NULL if out of memory); delete with afv_geom_delete. */
afv_geom *afv_geom_new(void);
void      afv_geom_delete(afv_geom *g);   /* NULL is allowed */

int           afv_geom_n(const afv_geom *g);        /* number of cells */
const double *afv_geom_area(const afv_geom *g);     /* A_i (n values) */
const double *afv_geom_perim(const afv_geom *g);    /* P_i */
const double *afv_geom_arc(const afv_geom *g);      /* L_i, free boundary */
/* Number of straight edges of cell i longer than AFV_CONTACT_TOL l (n values). */
const int    *afv_geom_contacts(const afv_geom *g);
double        afv_geom_energy(const afv_geom *g);   /* total energy E */
/* The pieces of cell i's boundary (counter-clockwise, see afv_piece):
** *pieces points to the first; returns how many. */
int afv_geom_pieces(const afv_geom *g, int i, const afv_piece **pieces);
/* The neighbours of cell i (centres closer than 2l), sorted by direction
** counter-clockwise from +x: *nbr their indices and, if d != NULL, *d
** their minimum-image displacements r_j - r_i (interleaved); returns how
** many. */
int afv_geom_neighbours(const afv_geom *g, int i, const int **nbr,
                        const double **d);
/* After AFV_ECOINCIDENT: the two coincident cells. */
void afv_geom_bad_pair(const afv_geom *g, int *i, int *j);


/* Geometry only: neighbour lists and every cell's shape (no energy, no force). */
int afv_geometry(afv_geom *g, int n, const double *r, const afv_params *p,
                 const afv_box *b);

/* Geometry, total energy (afv_geom_energy) and, if f != NULL, the forces
** f[2i], f[2i+1] = -dE/dr_i.  O(N) time and memory. */
int afv_compute(afv_geom *g, int n, const double *r, const afv_params *p,
                const afv_box *b, double *f);

/* Energy of one cell from its shape: KA (A-A0)^2 + KP (P-P0)^2 + Lambda L. */
double afv_cell_energy(const afv_params *p, int i, double A, double P, double L);

/* ---- cell order -------------------------------------------------------- */
/* A spatial order of the cells (the cell list's, bins of side >= 2l row by
** row): perm[k] = the cell to put k-th.  Numbering cells in this order
** keeps neighbours close in memory: large N runs faster than with a random
** numbering.  AFV_OK or AFV_ENOMEM. */
int  afv_spatial_order(int n, const double *r, double l, const afv_box *b,
                       int *perm);

/* ---- finite-difference gradient check --------------------------------- */
typedef struct afv_check_report {
  double max_abs;     /* max |F_analytic - F_fd| over all components */
  double force_scale; /* max |F_analytic| over all components */
  double max_rel;     /* max_abs / force_scale (max_abs if the scale is 0) */
  double tension_scale; /* rms over cells of |2 KA (A - A0)| l
                      ** + |2 KP (P - P0)| + |Lambda|: the size of one
                      ** cell's pressure and tension terms, of which every
                      ** force is a sum; unlike force_scale it does not
                      ** vanish where forces cancel by symmetry */
  double max_tension_rel; /* max_abs / tension_scale (max_abs if 0): the
                      ** criterion of afv check */
  int    worst_cell;  /* where max_abs occurs */
  int    worst_comp;  /* 0 = x, 1 = y */
  double max_resolved;   /* largest error more than twice the difference's
                      ** own uncertainty (its two steps' disagreement and
                      ** rounding): a wrong force */
  double max_unresolved; /* largest error within that uncertainty (a kink
                      ** of the energy within reach of the step): finite
                      ** differences cannot tell it from a wrong force */
  int    unresolved_cell; /* where max_unresolved occurs (-1: none) */
} afv_check_report;

/* Central differences of the energy with step h (a length): compares
** -dE/dr from E(r +- s) and E(r +- s/2), extrapolated, with afv_compute's
** forces, s = min(h, a hundredth of the cell's distance to a kink: a
** pair at d = 2l or d = 0).  Moving cell c changes
** only the energies of the cells within 2l + h of it, so each difference
** is taken of their energies alone, computed on the cells within
** 4l + 2h of c, in coordinates centred on c: O(N) in all, and exact
** steps h however large the coordinates (a periodic box narrower than
** 4 (4l + 2h) takes the whole tissue's energy instead, O(N^2)). */
int afv_gradient_check(int n, const double *r, const afv_params *p,
                       const afv_box *b, double h, afv_check_report *rep);
/* The same comparison for forces f supplied by the caller (2n values):
** lets a test prove that the check catches a wrong force. */
int afv_force_check(int n, const double *r, const afv_params *p,
                    const afv_box *b, double h, const double *f,
                    afv_check_report *rep);

/* ---- dynamics (dynamics.c) -------------------------------------------- */
/* Overdamped active Brownian dynamics (paper, Eqs. of motion and abp):
**     dr_i/dt = mu F_i + v0_i n_i,  n_i = (cos th_i, sin th_i),
**     th_i(t + dt) = th_i(t) + sqrt(2 Dr_i dt) xi_i,  xi_i standard normal,
** integrated by Euler-Maruyama.  The noise comes from a counter-based
** generator (Philox4x32-10) keyed by the seed, so a run depends only on
** (seed, parameters), whatever the order cells are visited in. */

/* afv_sim_step is the paper's Euler step, r_i += dt (mu F_i + v0_i n_i),
** with the exact force however far a cell moves: a move beyond
** AFV_MAX_STEP_DISP l is a jump, counted (afv_sim_jumps); only a move
** beyond AFV_RUNAWAY_MOVE l or a force that is not finite is refused
** (afv_config.h says why). */

typedef struct afv_dyn {
  double mu;          /* mobility (inverse friction), > 0 */
  double v0;          /* self-propulsion speed, in l per unit time */
  double Dr;          /* rotational diffusion constant, 1/time, >= 0 */
  double dt;          /* time step, > 0 */
  const double *v0_i; /* optional per-cell v0 (length n), NULL = scalar v0 */
  const double *Dr_i; /* optional per-cell Dr (length n), NULL = scalar Dr */
  unsigned long long seed; /* key of the random streams */
} afv_dyn;

/* Paper defaults: mu 1, v0 0, Dr 0.1, dt 0.01, seed 1. */
void afv_dyn_default(afv_dyn *d);


/* A running simulation (opaque).  afv_sim_new, then afv_sim_init; delete
** with afv_sim_delete.  Invariant between calls: the forces
** (afv_sim_forces) and the geometry (afv_sim_geom) are those at the
** positions, and the geometry's energy the energy there.
**
** What a caller may change between afv_sim_step calls (a quench, a
** mixture switched on, ...); the next step then continues exactly as a
** simulation started from that state with the new values would
** (test/test_docs.c):
**   - no call needed (afv_sim_step reads them afresh every step): through
**     afv_sim_dyn, v0, Dr, mu, seed; the angles (afv_sim_angles);
**     the step count (afv_sim_set_steps: the noise of a step is drawn for
**     (seed, cell, step)); dt too, but the time is recomputed as step * dt,
**     so keep your own clock across a change of dt; v0_i and Dr_i may be
**     pointed at arrays of n values that the caller owns and keeps alive
**     (or set to NULL: the scalar is then used), but not written through
**     (they point into the simulation's own copies);
**   - then afv_sim_refresh (the forces and the geometry are cached from
**     the end of the last step): the parameters (afv_sim_params, any
**     field; per-cell arrays as for v0_i), the box (afv_sim_box), the
**     positions (afv_sim_positions).
** Everything else is the library's: read it through the calls below. */
typedef struct afv_sim afv_sim;

/* A new, empty simulation (NULL if out of memory); give it its cells with
** afv_sim_init, delete it with afv_sim_delete (NULL is allowed). */
afv_sim *afv_sim_new(void);
void     afv_sim_delete(afv_sim *s);

int        afv_sim_n(const afv_sim *s);         /* number of cells */
long long  afv_sim_steps(const afv_sim *s);     /* steps taken since the
                                                ** start of the active run */
void       afv_sim_set_steps(afv_sim *s, long long step);  /* and the
                                                ** time to step * dt */
double     afv_sim_time(const afv_sim *s);      /* step * dt after a step */
/* The 2n centres, UNWRAPPED (minimum image inside), interleaved; writable
** (then afv_sim_refresh). */
double    *afv_sim_positions(afv_sim *s);
/* The n polarity angles (radians, not reduced); writable. */
double    *afv_sim_angles(afv_sim *s);
const double   *afv_sim_forces(const afv_sim *s);  /* 2n forces -dE/dr */
const afv_geom *afv_sim_geom(const afv_sim *s);    /* geometry at the
                                                   ** positions (energy, ...) */
/* The model, boundary and dynamics in use; writable as listed above. */
afv_params *afv_sim_params(afv_sim *s);
afv_box    *afv_sim_box(afv_sim *s);
afv_dyn    *afv_sim_dyn(afv_sim *s);
/* The steps so far (active and relaxation) in which some cell
** moved more than AFV_MAX_STEP_DISP l, and the largest move of a cell in
** one step so far, in l (0 before a step; NaN never: such a step is refused). */
long long  afv_sim_jumps(const afv_sim *s);
double     afv_sim_largest_move(const afv_sim *s);
/* After AFV_EUNSTABLE: the offending cell (else -1) and its step length
** / l in dt (NaN or inf if the force was not finite). */
int        afv_sim_bad_cell(const afv_sim *s);
double     afv_sim_bad_disp(const afv_sim *s);

/* Copies r (2n), theta (n; NULL = all 0), the parameters and their per-cell
** arrays, and computes the forces.  Status as afv_compute, or AFV_EINVAL. */
int  afv_sim_init(afv_sim *s, int n, const double *r, const double *theta,
                  const afv_params *p, const afv_box *b, const afv_dyn *d);
/* One Euler-Maruyama step: r += dt (mu F + v0 n); th += sqrt(2 Dr dt) xi;
** then the forces at the new r.  Allocation-free once the geometry's
** buffers have grown.  AFV_EUNSTABLE (state unchanged) if a force or a
** position is not finite, or a move exceeds AFV_RUNAWAY_MOVE l. */
int  afv_sim_step(afv_sim *s);
/* Recomputes the geometry, energy and forces at r with par and box: call
** it after changing any of them between steps (see afv_sim).  AFV_EINVAL
** (nothing changed) if a value of par or dyn is out of range, else as
** afv_compute (on an error, set valid values and call it again before the
** next step). */
int  afv_sim_refresh(afv_sim *s);
/* Largest |F_i| over the cells (0 if n = 0). */
double afv_sim_max_force(const afv_sim *s);

/* Relaxation at zero activity (paper: "relax ... at zero temperature"):
** the overdamped flow dr_i/dt = mu F_i (v0 = 0, angles unchanged) by
** afv_sim_step's Euler steps of dyn.dt.  Stops when
** max_i |F_i| <= tol (converged), at a kink of E shown by the criterion
** below (at_kink), at a step it cannot take (refused), or after max_iter
** steps (none of these flags: not reached).  Status AFV_OK in all these
** cases; an error only for a force that is not finite (AFV_EUNSTABLE) or
** as afv_compute.
** Kink criterion (dynamics.c, KINKS; the constants AFV_RELAX_WINDOW and
** AFV_RELAX_KINK_* in afv_config.h), at the end of a window of
** AFV_RELAX_WINDOW steps: every cell's mean force over the window is
** small in absolute terms and against max_i |F_i| (the cells chatter
** across a kink), the mean energy has stopped dropping, and max_i |F_i|
** is moderate. */
typedef struct afv_relax_report {
  long   iterations;   /* flow steps taken */
  double time;         /* iterations dt */
  double max_force;    /* max_i |F_i| at the end */
  double energy0;      /* energy before */
  double energy;       /* energy after */
  double drift;        /* at the last full window (NaN before the second):
                       ** max_i |displacement_i| / (window time mu) */
  double drop;         /* and its drop of the mean energy / sum_i |e_i| */
  long long jumps;     /* steps that moved a cell more than
                       ** AFV_MAX_STEP_DISP l (afv_sim_jumps) */
  int    converged;    /* 1 if max_force <= tol */
  int    at_kink;      /* 1 if stopped at a kink by the criterion above */
  int    refused;      /* 1 if stopped because a step of dt would move a
                       ** cell farther than AFV_RUNAWAY_MOVE l (afv_sim's
                       ** bad_cell, bad_disp say which; forces far too
                       ** large for dt) */
} afv_relax_report;
/* Optional observer, called after every step (may be NULL). */
typedef void (*afv_relax_monitor)(void *ctx, long iter, double energy,
                                  double max_force);
/* Moves the positions (step, time and angles unchanged); the forces and
** the geometry end at the final positions.  Status as afv_compute, or AFV_ENOMEM. */
int afv_relax(afv_sim *s, double tol, long max_iter, afv_relax_report *rep,
              afv_relax_monitor mon, void *ctx);
/* The same job by FIRE 2.0 (relax_fire.c): a minimiser, much faster to a
** minimum of E than the flow but not the paper's protocol.  Each cell moves
** at most 0.1 l a step; the same four stops (iterations: FIRE steps, time:
** the sum of their time steps, drift and drop NaN, jumps 0); unless
** converged it ends in the lowest-energy state it saw. */
int afv_relax_fire(afv_sim *s, double tol, long max_iter,
                   afv_relax_report *rep, afv_relax_monitor mon, void *ctx);

/* ---- initial configurations -------------------------------------------- */
/* Each start shares its name with afv run's init key: init lattice,
** init random, init cluster (the authors' start).  (Until 0.4.0:
** afv_init_cluster was the lattice, afv_init_square the authors' start.) */
/* A lattice patch: the n sites of a triangular lattice of spacing a nearest
** to the centre of the box (the origin in open space); a is reduced if the
** disk would not fit in the periodic box.  r has 2n entries.  Returns
** AFV_OK, or AFV_ENOMEM (temporary list of lattice sites). */
int  afv_init_lattice(int n, double a, const afv_box *b, double *r);
/* Uniform random centres in [0, Lx) x [0, Ly) (open space: in a square of
** side side centred on the origin), from the streams of seed. */
void afv_init_random(int n, unsigned long long seed, const afv_box *b,
                     double side, double *r);
/* The authors' start (afv run's init cluster, with side 0.3 L): a
** cluster of centres uniform at random in a square of side `side`
** centred in the periodic box (on the origin in open space), from the
** streams of seed (open space: the same centres as afv_init_random). */
void afv_init_cluster(int n, unsigned long long seed, const afv_box *b,
                      double side, double *r);
/* Uniform random angles in [0, 2 pi) from the streams of seed. */
void afv_init_angles(int n, unsigned long long seed, double *theta);

/* ---- the paper's protocol (dynamics.c, PROTOCOL) ----------------------- */
/* From a start to the active run, as the paper does it: the start, its
** relaxation at v0 = 0, then v0 switched on.  The authors' start is
** AFV_START_CLUSTER with side AFV_AUTHORS_SQUARE L (L the periodic box
** side) and AFV_RELAX_FLOW. */
#define AFV_AUTHORS_SQUARE 0.3
enum { AFV_START_CLUSTER,   /* afv_init_cluster(seed, side) */
       AFV_START_LATTICE,   /* afv_init_lattice(spacing) */
       AFV_START_RANDOM,    /* afv_init_random(seed, side) */
       AFV_START_GIVEN };   /* the positions r */
enum { AFV_RELAX_FLOW,      /* afv_relax: the paper's overdamped flow */
       AFV_RELAX_FIRE };    /* afv_relax_fire */
typedef struct afv_protocol {
  int start;             /* AFV_START_* */
  double side;           /* CLUSTER, RANDOM (open space): the square's side */
  double spacing;        /* LATTICE: the spacing (reduced to fit the box) */
  const double *r;       /* GIVEN: 2n positions */
  const double *theta;   /* n angles, or NULL: afv_init_angles(d->seed) */
  int relax;             /* AFV_RELAX_FLOW or AFV_RELAX_FIRE */
  double relax_tol;      /* max |F| to relax to (afv_relax's tol) */
  long relax_max_steps;  /* 0: no relaxation (the start as built) */
} afv_protocol;
/* Initialises s (afv_sim_new'd) at the start of pr for n cells with p, b,
** d, relaxes it at v0 = 0 as pr says (rep: its report; mon, ctx as for
** afv_relax), and leaves it at step 0 with d's v0 on, ready for
** afv_sim_step.  A generated start's centres (all but GIVEN) are numbered
** in afv_spatial_order before the angles are drawn, for memory locality.
** Status as afv_sim_init (the start), then as afv_relax. */
int afv_protocol_start(afv_sim *s, int n, const afv_params *p,
                       const afv_box *b, const afv_dyn *d,
                       const afv_protocol *pr, afv_relax_report *rep,
                       afv_relax_monitor mon, void *ctx);

/* ---- files a user reads or writes (io.c) ------------------------------- */
/* Reads a POINTS file: one cell "x y" per line, separated by spaces, tabs
** or commas, '#' lines and blank lines ignored.  On success *r is a malloc'd
** array of 2 *n coordinates (caller frees).  On failure, err holds a
** one-line message naming the file and line. */
int  afv_points_read(const char *path, int *n, double **r, char *err,
                     size_t errlen);
/* A trajectory (format in io.c): frames of unwrapped centres and angles. */
typedef struct afv_traj {
  int        n;        /* cells per frame */
  int        nframes;  /* complete frames read */
  afv_box    box;      /* from the header line */
  long long *step;     /* step of frame k */
  double    *t;        /* time of frame k */
  double    *r;        /* frame k: r[k*2n .. k*2n + 2n-1], unwrapped */
  double    *theta;    /* frame k: theta[k*n .. k*n + n-1] */
} afv_traj;

/* Writes the header line of a format-2 trajectory of n cells in box b, then
** one frame (step, time, the 2n centres r and n angles theta) per call;
** AFV_OK, or AFV_EIO if the stream has an error. */
int  afv_traj_write_header(FILE *fp, int n, const afv_box *b);
int  afv_traj_write_frame(FILE *fp, long long step, double t, int n,
                          const double *r, const double *theta);
/* Reads every complete frame (a truncated last frame is dropped) of a
** format 2 or format 1 file into memory. */
int  afv_traj_read(const char *path, afv_traj *tr, char *err, size_t errlen);
/* Every *_free below releases the struct's buffers and zeroes it (it may be
** filled again); every *_close also closes the file. */
void afv_traj_free(afv_traj *tr);

/* A trajectory file read one frame at a time.  afv_traj_open reads the
** header and every frame's step and time (format 2: 16 bytes a frame;
** format 1, text: the whole file, into memory), and refuses frames that
** do not run forward; afv_traj_frame reads the centres of frame k into r
** (2n values) and, if theta is not NULL, its angles (n values). */
typedef struct afv_traj_file {
  int        n;         /* cells per frame */
  int        nframes;   /* complete frames */
  afv_box    box;
  long long *step;      /* step of frame k */
  double    *t;         /* time of frame k */
  int        format;    /* 2 (binary frames) or 1 (text) */
  /* private */
  const char *path;     /* as given, for messages */
  FILE      *fp;
  long long  head, record;  /* bytes before frame 0; bytes a frame */
  unsigned char *buf;   /* one frame's cells (format 2) */
  afv_traj   text;      /* every frame (format 1) */
} afv_traj_file;
int  afv_traj_open(afv_traj_file *f, const char *path, char *err,
                   size_t errlen);
int  afv_traj_frame(afv_traj_file *f, int k, double *r, double *theta,
                    char *err, size_t errlen);
void afv_traj_close(afv_traj_file *f);

/* Columns of a CELLS file (format in io.c), by index. */
enum { AFV_COL_X, AFV_COL_Y, AFV_COL_THETA, AFV_COL_V0, AFV_COL_DR,
       AFV_COL_KA, AFV_COL_KP, AFV_COL_A0, AFV_COL_P0, AFV_NCOLS };
extern const char *const afv_cell_columns[AFV_NCOLS]; /* "x", "y", ... */

typedef struct afv_cells {
  int     n;                /* number of cells (rows) */
  int     has[AFV_NCOLS];   /* 1 if the file has that column */
  double *col[AFV_NCOLS];   /* col[k][i]: column k of cell i (NULL if absent) */
} afv_cells;

/* Reads a CELLS file into c (zero-initialised or freed); on failure err
** names file:line. */
int  afv_cells_read(const char *path, afv_cells *c, char *err, size_t errlen);
/* Writes c in the CELLS format (%.17g, so it reads back exactly). */
int  afv_cells_write(FILE *fp, const afv_cells *c);
void afv_cells_free(afv_cells *c);

/* ---- analysis (analysis.c) --------------------------------------------- */
/* Contacts, clusters and confluency of one configuration (paper: clustering
** and EMT sections).  A contact is a straight edge longer than
** AFV_CONTACT_TOL l (the longer of the two cells' views, so both agree);
** a cluster is a connected set of cells under contact.  A cluster that
** winds around the periodic box is one cluster, its cells counted once.
** Zero-initialise; free with afv_clusters_free. */
typedef struct afv_clusters {
  int     n;            /* cells */
  int     count;        /* number of clusters (isolated cells included) */
  int     giant;        /* N_GC: cells in the largest cluster */
  double  omega;        /* Omega = sum_j N_j omega_j / N (0 if n = 0) */
  int     n_pairs;      /* |C|: contacting pairs, each once */
  int    *pairs;        /* C, sorted: pairs[2k] < pairs[2k+1] */
  int     n_junctions;  /* triple junctions (tissue vertices), each once */
  double *junction;     /* their positions, interleaved, wrapped into box */
  int    *label;        /* label[i] in [0, count): cluster of cell i */
  int    *size;         /* size[c] = N_c, cells of cluster c */
  int    *ec;           /* ec[c] = Ec_c, contacting edges of cluster c */
  int    *v3;           /* v3[c] = V3_c, triple junctions of cluster c */
  int    *wraps;        /* wraps[c] = 1 if cluster c winds around the box */
  double *omega_c;      /* omega_c[c] = V3 / max(Ec - N + 1 - wraps, 1) */
  int    *contact;      /* per piece q of the geom: 1 if a contacting edge */
  int    *partner;      /* per piece: the same edge in the other cell, -1 */
  struct afv_clusters_work *work;  /* the library's own: capacities and
                        ** work space (allocated by afv_clusters_compute) */
} afv_clusters;

/* Clusters, Omega and junctions of the configuration r whose geometry g
** has been computed (afv_geometry) with cell radius l and box b. */
int  afv_clusters_compute(afv_clusters *c, const afv_geom *g, const double *r,
                          double l, const afv_box *b);
void afv_clusters_free(afv_clusters *c);

/* Generalised T1 count (paper, glassy dynamics section):
** T1(t) = |C(t) symmetric-difference C(0)| / 2. */
typedef struct afv_t1 {
  int  n_pairs0;        /* |C(0)| */
  int *pairs0;          /* C(0), sorted as afv_clusters.pairs */
} afv_t1;
int    afv_t1_start(afv_t1 *t, const afv_clusters *c);  /* C(0) := c's C */
double afv_t1_count(const afv_t1 *t, const afv_clusters *c);
void   afv_t1_free(afv_t1 *t);
/* Mean-squared displacement on log-spaced lags, plain and relative to the
** contacting neighbours at the time origin (a cell with none: plain). */
typedef struct afv_msd {
  int     nlags;        /* number of lags */
  int    *lag;          /* lag k in frames, increasing */
  double *dt;           /* its mean length in time */
  double *msd;          /* plain MSD */
  double *msd_rel;      /* relative MSD */
  long   *samples;      /* (origin, cell) pairs averaged */
  double *msd_se;       /* standard error of msd across the cells (each
                        ** cell's mean over the origins one sample; the
                        ** origins overlap, the cells do not; NaN: 1 cell) */
  double *msd_rel_se;   /* the same for msd_rel */
  double *per_cell;     /* private: each cell's sums while computing */
} afv_msd;
/* Makes a trajectory continuous: each frame-to-frame displacement becomes
** its minimum image.  A no-op on unwrapped trajectories whose cells move
** less than half a box per frame; needed for wrapped ones. */
void afv_traj_unwrap(afv_traj *tr);
/* MSD over time origins first .. nframes-2 (frames equally spaced in time);
** tr must be unwrapped. */
int  afv_msd_compute(afv_msd *m, const afv_traj *tr, int first, double l);
int  afv_msd_lag_index(const afv_msd *m, double lag);  /* nearest lag */
void afv_msd_free(afv_msd *m);

/* Integrated autocorrelation time 1 + 2 sum_t rho(t), in samples, Sokal's
** window c = 5; HUGE_VAL for a constant series.  *reliable (may be NULL)
** is 0 when the series is too short for the window. */
double afv_autocorr_time(const double *x, int n, int *reliable);

/* Hexagonal mean-field E/M point (paper, EMT section; units l = KA = 1):
** the P0 below which the honeycomb closes its gaps.  5.732 for the paper's
** Lambda = 0.2, A0 = pi, KP = 1. */
double afv_meanfield_p0(double Lambda, double A0, double KP);
/* Energy of one cell of the gapped honeycomb, contact half-angle theta. */
double afv_meanfield_energy(double theta, double Lambda, double A0, double KP,
                            double P0);

/* Everything `afv analyze` reports for a trajectory. */
typedef struct afv_analysis {
  int     n;            /* cells */
  int     nframes;      /* frames analysed */
  int     first;        /* first frame of the steady part */
  double *t;            /* time of frame k */
  double *ngc_frac;     /* N_GC / N at frame k */
  double *n_clusters;   /* number of clusters at frame k */
  double *omega;        /* Omega at frame k */
  double *t1;           /* T1 at frame k, from frame 0 */
  double *csd;          /* csd[s], s = 1..n: p(s), fraction of the clusters
                        ** of the steady frames that have s cells */
  afv_msd msd;          /* from the steady frames (nlags 0 if < 2) */
  double  mean[3], sd[3]; /* steady means, standard deviations of
                        ** N_GC/N, number of clusters, Omega */
  double  t1_final;     /* T1 at the last frame */
  double  ds, ds_lag;   /* D_s = MSD_rel / (4 lag) at the lag used */
  double  ds_plain;     /* same from the plain MSD */
  double  d0, deff;     /* D_0 = v0^2 / (2 Dr), D_eff = D_s / D_0 */
  double  tau_ngc;      /* autocorrelation time of N_GC (time units) */
  int     tau_reliable; /* 0 if the series was too short for the window */
  long    ds_origins;   /* time origins behind the lag of D_s */
  double  t1_rate;      /* T1 events per cell per unit time between
                        ** consecutive steady frames (NaN: < 2 frames) */
  double  msd_beta;     /* slope of log MSD_rel vs log lag over the lags
                        ** of 1% to 10% of the steady window (analysis.c:
                        ** MSD_BETA_*): ~0 caged, ~1 diffusing; NaN if
                        ** fewer than 3 lags there */
} afv_analysis;
/* Analyses every frame of tr (unwrapped); steady part: t >= steady_from;
** D_s at the computed lag nearest to `lag`. */
int  afv_analyze(afv_analysis *a, const afv_traj *tr, double l, double v0,
                 double Dr, double steady_from, double lag);
/* The same from a trajectory file, read in one streaming pass (two when
** the MSD has lags longer than the frames held; analysis.c, STREAMING):
** the same bits as afv_analyze on the file's frames in memory, in memory
** O(N x frames held) instead of O(N x frames).  A frame that cannot be
** read: its status, the message in err. */
int  afv_analyze_file(afv_analysis *a, afv_traj_file *f, double l, double v0,
                      double Dr, double steady_from, double lag, char *err,
                      size_t errlen);
void afv_analysis_free(afv_analysis *a);

/* Log-binned cluster-size distribution: bin k holds the sizes 2^k ..
** 2^(k+1) - 1 (the last bin ends at n); lo[k], hi[k] its first and last
** size, p[k] the sum of csd[s] over them (so the p[k] sum to the sum of
** csd[1..n]).  csd as afv_analysis.csd (index s = 1..n).  Returns the
** number of bins, floor(log2 n) + 1 <= AFV_CSD_MAX_BINS. */
#define AFV_CSD_MAX_BINS 32
int  afv_csd_log_bins(const double *csd, int n, int *lo, int *hi, double *p);

/* ---- drawing (svg.c) ---------------------------------------------------- */
/* Draws the configuration r (geometry g computed for it) like the paper's
** Fig. 1: red centres, blue contact edges, pink arcs (SVG arc commands),
** hollow purple triple junctions, cyan polarity arrows (theta may be NULL),
** the periodic box in black.  Elements carry class="centre", "edge", "arc",
** "junction", "polarity". */
int afv_svg_write(FILE *out, const afv_geom *g, int n, const double *r,
                  const double *theta, const afv_params *p, const afv_box *b);

/* What afv_svg_draw may change (zero-initialise, then set what you need;
** afv_svg_write draws with all of them zero). */
typedef struct afv_draw_opts {
  double width;          /* picture width in pixels; 0: the longer side of
                         ** the picture is 800 pixels */
  int    crop;           /* 1: draw only [x0, x1] x [y0, y1], model units;
                         ** in a periodic box within one box side of it */
  double x0, y0, x1, y1;
  int    color_by_cluster; /* 1: fill the cells by cluster, largest first */
  const double *value;   /* else, if not NULL: fill cell i by value[i] (a
                         ** colour per value when there are at most 7
                         ** values, a mixture of cell types; else a ramp) */
  const char *value_name;  /* name of the value, for the legend */
  int   *cluster_color;  /* with color_by_cluster, if not NULL (n ints, in
                         ** and out): each cell's palette colour in the
                         ** previous frame of a movie (-1: none), replaced
                         ** by its colour here.  A cluster keeps the colour
                         ** of a previous cluster of which it holds more
                         ** than half the cells; the others take free
                         ** colours, largest cluster first */
  const char *caption;   /* if not NULL: a line of text under the tissue
                         ** (e.g. "N 400  P0 4.8  v0 0.5  Lambda 0.2  t 100") */
  int    scale_bar;      /* 1: a bar of length l under the tissue */
} afv_draw_opts;
/* afv_svg_write with options: size, crop and filled cells with a legend
** (class="legend") right of the tissue; cells are class="cell".  Marks
** and lines are their size in l but at least a pixel or two, so they stay
** visible on a zoomed-out picture.  AFV_EINVAL on unusable options. */
int afv_svg_draw(FILE *out, const afv_geom *g, int n, const double *r,
                 const double *theta, const afv_params *p, const afv_box *b,
                 const afv_draw_opts *o);

/* ---- bindings (api.c) --------------------------------------------------- */
/* For callers that cannot include this header (Python's ctypes,
** python/afv.py): the structs that may grow between versions are handed
** out by pointer and read and written by field name, so a binding never
** mirrors their layout.  Names are the fields' names; a name the version
** does not know gives AFV_EINVAL. */
const char *afv_version(void);            /* AFV_VERSION of the library */
/* sizeof the struct "afv_params" or "afv_box" (0 for another name): a
** binding that mirrors these two checks its mirror against it. */
size_t afv_struct_size(const char *name);

/* A new afv_dyn with afv_dyn_default's values (NULL if out of memory). */
afv_dyn *afv_dyn_new(void);
void     afv_dyn_delete(afv_dyn *d);      /* NULL is allowed */
/* The scalar fields: "mu", "v0", "Dr", "dt", "seed" (an integer in
** [0, 2^64) as a double; others AFV_EINVAL). */
int afv_dyn_set(afv_dyn *d, const char *name, double value);
int afv_dyn_get(const afv_dyn *d, const char *name, double *value);
/* Points v0_i ("v0") or Dr_i ("Dr") at n values the caller keeps (NULL:
** the scalar again). */
int afv_dyn_set_cells(afv_dyn *d, const char *name, const double *values);

/* A zeroed report for afv_relax; its fields by name ("iterations", "time",
** "max_force", "energy0", "energy", "drift", "drop", "jumps",
** "converged", "at_kink", "refused"), integers as doubles. */
afv_relax_report *afv_relax_report_new(void);
void afv_relax_report_delete(afv_relax_report *rep);
int  afv_relax_report_get(const afv_relax_report *rep, const char *name,
                          double *value);

/* The order parameters of a configuration (afv_clusters_compute): into
** values[AFV_ORDER_COUNT], and each cell's cluster into label (n values;
** may be NULL).  g computed for r (afv_geometry or afv_compute). */
enum { AFV_ORDER_GIANT,      /* N_GC / N, the largest cluster's share */
       AFV_ORDER_OMEGA,      /* Omega, the confluency */
       AFV_ORDER_CLUSTERS,   /* number of clusters (isolated cells too) */
       AFV_ORDER_PAIRS,      /* contacting pairs */
       AFV_ORDER_JUNCTIONS,  /* triple junctions */
       AFV_ORDER_COUNT };
int afv_order_parameters(const afv_geom *g, const double *r, double l,
                         const afv_box *b, double *values, int *label);

/* afv_svg_draw (filled by cluster if color_by_cluster, else as
** afv_svg_write) into the file path, atomically. */
int afv_svg_save(const char *path, const afv_geom *g, int n, const double *r,
                 const double *theta, const afv_params *p, const afv_box *b,
                 int color_by_cluster);

/* Trajectories: a new, empty afv_traj (NULL if out of memory) to fill with
** afv_traj_read, or with afv_traj_set from a caller's arrays (copied:
** step and theta may be NULL for 0, 1, 2, ... and zeros; AFV_EINVAL for
** a negative count, AFV_ENOMEM); its fields through the accessors. */
afv_traj *afv_traj_new(void);
void      afv_traj_delete(afv_traj *tr);    /* NULL is allowed */
int       afv_traj_set(afv_traj *tr, int n, int nframes, const afv_box *b,
                       const long long *step, const double *t,
                       const double *r, const double *theta);
int              afv_traj_n(const afv_traj *tr);
int              afv_traj_nframes(const afv_traj *tr);
const afv_box   *afv_traj_box(const afv_traj *tr);
const long long *afv_traj_steps(const afv_traj *tr);
const double    *afv_traj_times(const afv_traj *tr);
const double    *afv_traj_positions(const afv_traj *tr);  /* 2n a frame */
const double    *afv_traj_angles(const afv_traj *tr);     /* n a frame */

/* An afv_msd for afv_msd_compute (NULL if out of memory), and its series
** "lag" (in time: afv_msd.dt), "msd", "msd_rel" (*count values; NULL and
** 0 for another name). */
afv_msd      *afv_msd_new(void);
void          afv_msd_delete(afv_msd *m);   /* NULL is allowed */
const double *afv_msd_series(const afv_msd *m, const char *name, int *count);

/* An afv_analysis for afv_analyze (NULL if out of memory); its numbers by
** the names of `afv analyze`'s summary.txt ("cells", "frames", "first",
** "ngc_frac_mean", "ngc_frac_sd", "n_clusters_mean", ..., "omega_sd",
** "t1_final", "D_s", "D_s_lag", "D_s_origins", "D_s_plain", "D_0",
** "D_eff", "tau_NGC", "tau_NGC_reliable", "t1_rate", "msd_beta"; else
** AFV_EINVAL) and its series by series.csv's and msd.csv's column names
** ("time", "ngc_frac", "n_clusters", "omega", "t1": one per frame; "lag",
** "msd", "msd_rel": one per lag; "csd": p(s) for s = 1..n; NULL and 0 for
** another name). */
afv_analysis *afv_analysis_new(void);
void          afv_analysis_delete(afv_analysis *a);  /* NULL is allowed */
int           afv_analysis_get(const afv_analysis *a, const char *name,
                               double *value);
const double *afv_analysis_series(const afv_analysis *a, const char *name,
                                  int *count);

/* An afv_protocol for afv_protocol_start (NULL if out of memory), with
** afv run's defaults: the authors' square start (side 0: set "side"),
** the flow relaxation to max |F| <= 1e-6 in at most 100000 steps.  Its
** numbers by name: "start" (AFV_START_*), "side", "spacing", "relax"
** (AFV_RELAX_*), "relax_tol", "relax_max_steps"; its arrays ("r",
** "theta": caller-owned, kept alive until afv_protocol_start) by
** afv_protocol_set_cells.  AFV_EINVAL for another name or a start,
** relax or step count out of range. */
afv_protocol *afv_protocol_new(void);
void          afv_protocol_delete(afv_protocol *pr);  /* NULL is allowed */
int           afv_protocol_set(afv_protocol *pr, const char *name,
                               double value);
int           afv_protocol_set_cells(afv_protocol *pr, const char *name,
                                     const double *values);

#endif /* AFV_H */
