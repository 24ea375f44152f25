/*
** afv.h -- the Active Finite Voronoi (AFV) model: public C99 API.
**
** A tissue is N cells, each given by its centre r_i.  Cell i is the disk of
** radius l about r_i, clipped by the perpendicular-bisector half-plane of
** every other centre closer than 2l.  Its boundary is a cyclic sequence of
** straight contact edges (shared with one neighbour) and circular arcs of
** radius l (free, non-contacting boundary).  The energy (paper, Eq. energy) is
**
**     E = sum_i KA_i (A_i - A0_i)^2 + KP_i (P_i - P0_i)^2 + Lambda L_i
**
** with A_i the area, P_i the perimeter and L_i the arc length of cell i.
** Forces are F_i = -dE/dr_i, exact and analytic (see afv.c).
**
** Conventions: positions are interleaved, r[2i] = x_i, r[2i+1] = y_i; so are
** forces.  The caller owns positions and forces; the library owns what is in
** an afv_geom.  Library functions never exit: they return a status code.
*/
#ifndef AFV_H
#define AFV_H

#include <stddef.h>
#include <stdio.h>

/* ---- status codes ------------------------------------------------------ */
#define AFV_OK           0  /* success */
#define AFV_ENOMEM       1  /* an allocation failed */
#define AFV_EINVAL       2  /* a parameter is out of range (l <= 0, NaN, ...) */
#define AFV_EBOX         3  /* periodic box side smaller than 4l */
#define AFV_ENONFINITE   4  /* a position is NaN or infinite */
#define AFV_ECOINCIDENT  5  /* two centres coincide (d = 0): see afv_geom.bad_i/j */
#define AFV_EIO          6  /* reading or writing a file failed */
#define AFV_EFORMAT      7  /* a file is not in the documented format */

const char *afv_strerror(int status);   /* one-line description of a status */

/* ---- tolerances (all relative to l; see geom.c for the reasoning) ------- */
/* A straight edge shorter than AFV_CONTACT_TOL * l is geometry, not a
** contact: it is kept in the boundary but not counted in afv_geom.contacts. */
#define AFV_CONTACT_TOL 1e-9

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
  int    slot;    /* for an edge: index of nbr in the neighbour list
                  ** (nbr_start[i] <= slot < nbr_start[i+1]); -1 for an arc */
  double x, y;    /* start vertex, relative to the cell centre */
  double length;  /* edge length or arc length (>= 0) */
} afv_piece;

/* Geometry of a whole tissue, filled by afv_compute (or afv_geometry).
** Zero-initialise (afv_geom g = {0};) before first use; free with
** afv_geom_free.  Buffers grow as needed and are reused between calls. */
typedef struct afv_geom {
  int     n;            /* number of cells */
  double *area;         /* A_i */
  double *perim;        /* P_i */
  double *arc;          /* L_i, length of the free boundary */
  int    *contacts;     /* number of edges longer than AFV_CONTACT_TOL l */
  int    *piece_start;  /* pieces of cell i: pieces[piece_start[i] ..     */
  int    *n_pieces;     /*   piece_start[i] + n_pieces[i] - 1]            */
  afv_piece *pieces;
  int    *nbr_start;    /* neighbours (centres closer than 2l) of cell i: */
  int    *nbr;          /*   nbr[nbr_start[i] .. nbr_start[i+1]-1]        */
  double *nbr_d;        /* their minimum-image displacements r_j - r_i,
                        ** interleaved, same indexing as nbr */
  int    *nbr_rev;      /* nbr_rev[s] = slot of i in the list of nbr[s] */
  double  energy;       /* total energy E */
  int     bad_i, bad_j; /* on AFV_ECOINCIDENT: the two coincident cells */
  /* private: capacities and work space */
  int     cap_cells, cap_nbr, cap_pieces, cap_bins, cap_work;
  int    *bin_start, *bin_cell;
  double *grad;         /* per neighbour slot s: dE_i/dr_nbr[s] */
  double *work;         /* per-cell clipping work space */
} afv_geom;

void afv_geom_free(afv_geom *g);

/* Geometry only: neighbour lists and every cell's shape (no energy, no force). */
int afv_geometry(afv_geom *g, int n, const double *r, const afv_params *p,
                 const afv_box *b);

/* Geometry, total energy (g->energy) and, if f != NULL, the forces
** f[2i], f[2i+1] = -dE/dr_i.  O(N) time and memory. */
int afv_compute(afv_geom *g, int n, const double *r, const afv_params *p,
                const afv_box *b, double *f);

/* Energy of one cell from its shape: KA (A-A0)^2 + KP (P-P0)^2 + Lambda L. */
double afv_cell_energy(const afv_params *p, int i, double A, double P, double L);

/* ---- the geometric steps, for readers and advanced callers ------------- */
/* Checks the positions, fills the neighbour lists and reserves the piece
** and work space: what afv_cell_shape needs.  (afv_geometry = this, then
** afv_cell_shape for every cell.) */
int  afv_geometry_prepare(afv_geom *g, int n, const double *r, double l,
                          const afv_box *b);
/* Fills g's neighbour lists (cell list with bins of side >= 2l). */
int  afv_neighbours(afv_geom *g, int n, const double *r, double l,
                    const afv_box *b);
/* Shape of cell i from its neighbour list: pieces, area, perimeter, arc. */
void afv_cell_shape(afv_geom *g, int i, double l);
/* Adds to grad[s] (for every neighbour slot s of cell i) the vector
**   wA dA_i/dr_j + wP dP_i/dr_j + wL dL_i/dr_j,   j = nbr[s],
** for the shape computed by afv_cell_shape.  cap as in afv_params. */
void afv_cell_shape_gradient(const afv_geom *g, int i, double l, double cap,
                             double wA, double wP, double wL, double *grad);

/* ---- finite-difference gradient check --------------------------------- */
typedef struct afv_check_report {
  double max_abs;     /* max |F_analytic - F_fd| over all components */
  double force_scale; /* max |F_analytic| over all components */
  double max_rel;     /* max_abs / force_scale (max_abs if the scale is 0) */
  int    worst_cell;  /* where max_abs occurs */
  int    worst_comp;  /* 0 = x, 1 = y */
} afv_check_report;

/* Central differences of the total energy with step h (in units of l):
** compares -dE/dr from E(r +- h) with afv_compute's forces. */
int afv_gradient_check(int n, const double *r, const afv_params *p,
                       const afv_box *b, double h, afv_check_report *rep);

/* ---- files (io.c) ----------------------------------------------------- */
/* Reads a POINTS file: one cell "x y" per line, separated by spaces, tabs
** or commas, '#' lines and blank lines ignored.  On success *r is a malloc'd
** array of 2 *n coordinates (caller frees).  On failure, err holds a
** one-line message naming the file and line. */
int  afv_read_points(const char *path, int *n, double **r, char *err,
                     size_t errlen);
/* snprintf into err (if err != NULL): the library's way to explain a status. */
void afv_errorf(char *err, size_t errlen, const char *fmt, ...);

/* Atomic output: write to the FILE from afv_atomic_open (PATH.tmp, name in
** tmp), then afv_atomic_commit flushes, closes and renames it over PATH.
** An interrupted writer leaves PATH as it was.  On error the .tmp is removed. */
FILE *afv_atomic_open(const char *path, char *tmp, size_t tmplen);
int   afv_atomic_commit(FILE *fp, const char *tmp, const char *path);

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

int  afv_traj_write_header(FILE *fp, int n, const afv_box *b);
int  afv_traj_write_frame(FILE *fp, long long step, double t, int n,
                          const double *r, const double *theta);
/* Reads every complete frame (a truncated last frame is dropped). */
int  afv_traj_read(const char *path, afv_traj *tr, char *err, size_t errlen);
void afv_traj_free(afv_traj *tr);

#endif /* AFV_H */
