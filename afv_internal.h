/*
** afv_internal.h -- what the library's own files share and no caller needs:
** the structs behind afv.h's opaque afv_geom and afv_sim, the steps of the
** geometry and of the simulation, the OpenMP macros.  Included by the
** library's .c files, the white-box tests and the parts of the program
** that need the internals; not installed (make install copies afv.h only).
** It includes afv_tool.h, the program's part of the library.
*/
#ifndef AFV_INTERNAL_H
#define AFV_INTERNAL_H

#include "afv.h"
#include "afv_tool.h"

#include <float.h>
#include <stddef.h>

/* ---- tolerances -------------------------------------------------------- */
/* Every tolerance of the library, here and nowhere else (a literal such as
** 1e-9 in a .c file is a bug); lengths are relative to l unless said.
** (The one a user reads, AFV_CONTACT_TOL, the shortest edge that counts as
** a contact, is public: afv.h.) */

/* geom.c, gap_angle: two kept parts of a cell's boundary that meet on the
** circle may have a computed gap a hair below zero, which wraps around to
** a full turn; a gap within AFV_ANGLE_TOL of 2 pi between two distinct
** edges is taken as zero (a true gap that large would need every contact
** edge of the cell shorter than about 1e-12 l). */
#define AFV_ANGLE_TOL 1e-12

/* geom.c, clip_pairs and sliver_kept: two bisectors with |t_a.u_b| below
** this are nearly parallel, and are clipped with care
** (clip_near_parallel). */
#define AFV_NEAR_PARALLEL 1e-6

/* geom.c, clip_near_parallel: two nearly parallel neighbours whose
** displacements differ by AFV_NEAR_PARALLEL_GAP |D_a| or more have lines
** that meet 1e6 l away or farther: the nearer line hides the other. */
#define AFV_NEAR_PARALLEL_GAP 1e-3

/* geom.c, keep_parts: a part bounded by two junctions whose length came
** out negative by at most this times |tau0| + |tau1| is a sliver of
** length zero lost to rounding, not an empty part. */
#define AFV_SLIVER_ROUNDING (8 * DBL_EPSILON)

/* geom.c, clip_pruned: a neighbour whose bisector lies farther than the
** cell's farthest vertex plus AFV_PRUNE_MARGIN l cannot cut the cell (the
** margin covers the rounding of the vertices, so pruning keeps the bits). */
#define AFV_PRUNE_MARGIN 1e-9

/* neighbours.c, window_around and security_radius: a reach (the bins
** around a point, the radius of security of a cut polygon) is widened by
** AFV_REACH_MARGIN l to cover the rounding of the positions it is
** computed from. */
#define AFV_REACH_MARGIN 1e-9

/* neighbours.c, NEAR: two centres closer than AFV_NEAR_IMAGE times the
** longer box side take their displacement from the unwrapped centres
** (wrapping rounds a centre to a multiple of eps L); the relative error
** is then below eps / AFV_NEAR_IMAGE = 2.3e-10.  2^-20, exact. */
#define AFV_NEAR_IMAGE 9.5367431640625e-07

/* The relative rounding of a sum of a few dozen rounded terms: a cell's
** area, perimeter or energy (afv.c, the finite-difference check's
** uncertainty; geom.c, the asserted bounds of a shape). */
#define AFV_SUM_ROUNDING (64 * DBL_EPSILON)

/* svg.c and phase.c: a plotted range narrower than AFV_PLOT_SPAN_TOL
** (times |lo| + 1 on a line plot's axis; absolute for a phase map's
** colour scale) holds one value, and is widened around it. */
#define AFV_PLOT_SPAN_TOL 1e-12

/* svg.c: a tick within AFV_PLOT_TICK_TOL of a step from zero is labelled
** 0, and the ticks run to the axis end plus that much of a step (the
** rounding of lo + k step). */
#define AFV_PLOT_TICK_TOL 1e-9

/* svg.c, draw_arc: an arc within AFV_FULL_CIRCLE_TOL (radians) of 2 pi
** is a full circle, drawn as two half arcs. */
#define AFV_FULL_CIRCLE_TOL 1e-9

/* phase.c, linear_fit: a least-squares determinant below AFV_FIT_SINGULAR
** times sum u^2 + 1 is singular (u does not vary). */
#define AFV_FIT_SINGULAR 1e-300

/* phase.c, the dispersal boundary's exponent alpha: the golden-section
** search stops when its bracket is narrower than AFV_FIT_ALPHA_TOL. */
#define AFV_FIT_ALPHA_TOL 1e-13

/* fits.c, collapse_grid: a grid of v0* and alpha runs to its end plus
** AFV_GRID_END_TOL, so that rounding of lo + k step keeps the last point. */
#define AFV_GRID_END_TOL 1e-12

/* ---- OpenMP build (make OPENMP=1) ----------------------------------- */
/* A per-cell loop over fewer than AFV_PARALLEL_MIN cells runs on the
** calling thread alone (see below): starting and joining a team
** costs more than such a loop.  The bits do not depend on it. */
#define AFV_PARALLEL_MIN 256

/* The library's per-cell loops are marked with these (the comment below says
** why any thread count gives the same bits); `size` is the loop's length in cells
** (in bins for the cell list's bin loop).  Empty without OpenMP. */
#ifdef _OPENMP
#define AFV_PRAGMA(text) _Pragma(#text)
#define AFV_PARALLEL_FOR(size) \
  AFV_PRAGMA(omp parallel for schedule(static) if ((size) >= AFV_PARALLEL_MIN))
#define AFV_PARALLEL_REDUCE(size, clauses) \
  AFV_PRAGMA(omp parallel for schedule(static) \
             if ((size) >= AFV_PARALLEL_MIN) clauses)
#else
#define AFV_PARALLEL_FOR(size)
#define AFV_PARALLEL_REDUCE(size, clauses)
#endif

/* Private: the grid of a cell list (neighbours.c). */
typedef struct afv_grid {
  int nbx, nby;     /* bins along x and y (>= 1) */
  int periodic;     /* 1: the bins tile the periodic box */
  double x0, y0;    /* lower-left corner of bin (0, 0) */
  double wx, wy;    /* bin sides */
  double Lx, Ly;    /* periodic box sides (0 in open space) */
} afv_grid;

/* The geometry (afv.h, afv_geom): the library, the tests and the program
** may hold one by value.  Zero-initialise (afv_geom g = {0};) before first
** use; release its buffers with afv_geom_free (the struct stays, empty and
** reusable).  Buffers grow as needed and are reused between calls. */
struct afv_geom {
  int     n;            /* number of cells */
  double *area;         /* A_i */
  double *perim;        /* P_i */
  double *arc;          /* L_i, length of the free boundary */
  int    *contacts;     /* number of edges longer than AFV_CONTACT_TOL l */
  int    *piece_start;  /* pieces of cell i: pieces[piece_start[i] ..     */
  int    *n_pieces;     /*   piece_start[i] + n_pieces[i] - 1]            */
  afv_piece *pieces;
  int    *nbr_start;    /* neighbours (centres closer than 2l; in dense  */
                        /* input only those that can cut: neighbours.c) */
  int    *nbr_end;      /*   nbr[nbr_start[i] .. nbr_end[i]-1]; the slots  */
  int    *nbr;          /*   up to nbr_start[i+1] are unused (room kept)   */
  double *nbr_d;        /* their minimum-image displacements r_j - r_i,
                        ** interleaved, same indexing as nbr */
  int    *nbr_rev;      /* nbr_rev[s] = slot of i in the list of nbr[s] */
  double  energy;       /* total energy E */
  int     bad_i, bad_j; /* on AFV_ECOINCIDENT: the two coincident cells */
  /* private: capacities and work space */
  int     cap_cells, cap_nbr, cap_pieces, cap_bins, cap_work;
  int    *bin_start, *bin_cell;
  double *bin_xy;       /* centres in bin order (wrapped if periodic) */
  int    *cand_start;   /* Verlet candidates of cell i (neighbours.c):     */
  int    *cand;         /*   cand[cand_start[i] .. cand_start[i+1]-1]    */
  double *cand_r0;      /* centres when the candidates were built */
  double *rw;           /* centres as the lists see them (wrapped) */
  afv_box cand_box;     /* box and l the candidates were built for */
  double  cand_l;
  int     cand_n;       /* cells they were built for; 0 = none */
  int     cap_cand, n_rebuilds;  /* n_rebuilds: candidate rebuilds so far */
  afv_grid cand_grid;   /* the cell list of the last rebuild */
  unsigned char *is_mover; /* 1 for a cell moved beyond the skin */
  double  cand_checks;  /* mover pair tests since the rebuild */
  double  cand_moved;   /* largest move of a cell since the rebuild, as of
                        ** the last call (afv_cells_around widens by it) */
  int     max_cand;     /* most candidates of a cell (sizes the work) */
  int     cand_dense;   /* 1: the candidates are the dense search's (a
                        ** function of these very positions): rebuilt at
                        ** every call (neighbours.c, DENSE) */
  double *edge;         /* per slot s: u = D/d (2), d/2, half-chord
                        ** sqrt(l^2 - d^2/4), set by afv_neighbours */
  double *grad;         /* per neighbour slot s: dE_i/dr_nbr[s] as
                        ** (a, b), see afv_cell_shape_gradient (zeroed
                        ** by afv_neighbours, summed by afv_compute) */
  double *work;         /* clipping work space, one block per thread */
  int     work_stride;  /* doubles per thread block of work */
};

void afv_geom_free(afv_geom *g);

/* ---- the geometric steps (geom.c, neighbours.c) ------------------------ */
/* Checks the positions, fills the neighbour lists and reserves the piece
** and work space: what afv_cell_shape needs.  (afv_geometry = this, then
** afv_cell_shape for every cell.) */
int  afv_geometry_prepare(afv_geom *g, int n, const double *r, double l,
                          const afv_box *b);
/* Fills g's neighbour lists: every centre closer than 2l, sorted by
** direction (counter-clockwise from +x), filtered from candidates that a
** cell list refreshes only when cells have moved (neighbours.c, Verlet skin);
** (the plain path to read is reference/afv_plain.c). */
int  afv_neighbours(afv_geom *g, int n, const double *r, double l,
                    const afv_box *b);
/* The cells that may now lie within R of the point (x, y), from the cell
** list of g's last candidate rebuild (a superset: the caller tests the
** distance), written to out[] (room for g->n), each once; returns how
** many.  g must come from afv_neighbours (or afv_compute) at positions
** from which no cell has since moved more than `moved`.  Cost: the cells
** in the bins within about R + cand_moved + moved, not O(N) (cand_moved,
** the largest move since the rebuild, is at most 0.15 l unless some
** cells have moved farther: neighbours.c, MOVERS). */
int  afv_cells_around(const afv_geom *g, double x, double y, double R,
                      double moved, int *out);

/* Renumbers the n centres r in place in the order of afv_spatial_order,
** so that cells near in space are near in memory.  AFV_OK or AFV_ENOMEM. */
int  afv_spatial_renumber(int n, double *r, double l, const afv_box *b);

/* 1 if cell i's list is sorted by direction, as afv_neighbours leaves it
** (the clipping relies on it; for assert). */
int  afv_slots_sorted(const afv_geom *g, int i);

/* Shape of cell i from its neighbour list: pieces, area, perimeter, arc.
** Different cells may be shaped at once by OpenMP threads (at most
** omp_get_max_threads() as of afv_geometry_prepare: one work block each). */
void afv_cell_shape(afv_geom *g, int i, double l);
/* Adds to grad[2s], grad[2s+1] (for every neighbour slot s of cell i)
** the vector  G = wA dA_i/dr_j + wP dP_i/dr_j + wL dL_i/dr_j  (j = nbr[s])
** as (a, b) with  G = a u + (b / d) t,  u = D/d (D = nbr_d of s), t = u
** turned by +90 degrees: a = dG/dd, b the derivative for r_j turning
** about r_i (see afv.c: both stay bounded as d -> 0, where G does not),
** for the shape computed by afv_cell_shape.  cap as in afv_params. */
void afv_cell_shape_gradient(const afv_geom *g, int i, double l, double cap,
                             double wA, double wP, double wL, double *grad);

/* ---- the simulation (dynamics.c) ---------------------------------------- */
/* The simulation (afv.h, afv_sim; what a caller may change between steps
** is listed there).  Zero-initialise, then afv_sim_init; release its
** buffers with afv_sim_free.  Invariant between calls: f and geom hold the
** forces and the geometry at r, and geom.energy the energy there.  The
** fields marked private are the step's work space. */
struct afv_sim {
  int        n;        /* number of cells */
  long long  step;     /* steps taken since the start of the active run */
  double     t;        /* simulated time, step * dt after a step */
  double    *r;        /* 2n centres, UNWRAPPED (minimum image inside) */
  double    *theta;    /* n polarity angles (radians, not reduced) */
  double    *f;        /* 2n forces -dE/dr at r */
  afv_params par;      /* model; per-cell arrays point into own[] */
  afv_box    box;      /* boundary */
  afv_dyn    dyn;      /* dynamics; per-cell arrays point into own[] */
  afv_geom   geom;     /* geometry at r (energy, areas, contacts, ...) */
  long long  jumps;    /* steps in which some cell moved more than
                       ** AFV_MAX_STEP_DISP l (dynamics.c, euler_step) */
  double     largest_move; /* the largest move of a cell in one step so
                       ** far, in l */
  int        bad_cell; /* on AFV_EUNSTABLE: the offending cell, else -1 */
  double     bad_disp; /* on AFV_EUNSTABLE: its step length / l (NaN or
                       ** inf if the force was not finite) */
  double    *r_start;  /* private: r at the start of the step (2n) */
  double    *move_len; /* private: per-cell squared move lengths (n) */
  double    *pol;      /* private: v0_i n_i during a step (2n) */
  double    *own;      /* private: one block holding r, theta, f and the
                       ** copies of the per-cell parameter arrays */
};
void afv_sim_free(afv_sim *s);

/* A function for a rare case, kept out of line so that the compiler does
** not hoist its work into the common path that calls it (gcc did, with
** exact_near: its pass cost every cell instructions, though never taken).
** An extension of gcc and clang; other compilers inline as they like. */
#if defined(__GNUC__)
#define COLD __attribute__((noinline, cold))
#else
#define COLD
#endif

/* Makes room for `need` elements of `elem` bytes in *ptr, whose capacity
** *cap grows by doubling (neighbours.c; geom.c uses it too).
** AFV_OK or AFV_ENOMEM (then *ptr and *cap are unchanged). */
int afv_grow(void **ptr, int *cap, int need, size_t elem);

#define PI     3.14159265358979323846
#define TWO_PI 6.28318530717958647692

/* OpenMP (make OPENMP=1; the macros are above): the per-cell loops
** marked AFV_PARALLEL_FOR write only their own cell's entries, so any
** thread count gives the same bits.  Static schedule: each thread gets
** one contiguous, spatially coherent block.  AFV_PARALLEL_REDUCE adds
** reduction clauses, used only for reductions whose result does not
** depend on the order (max, min, | and sums of integers), so again any
** thread count gives the same bits.
** `size` is the loop's length in cells (in bins for the bin loop): below
** AFV_PARALLEL_MIN the loop runs on the calling thread: for a small
** tissue, starting a team of threads costs more than the loop.  Without
** OpenMP the macros are empty and the files are plain C99. */

/* 0 for a direction in [0, pi) counter-clockwise from +x, 1 in [pi, 2 pi). */
static inline int lower_half(double dx, double dy)
{
  return dy < 0 || (dy == 0 && dx < 0);
}

/* afv analyze's memory for frames held (analysis.c, STREAMING). */
#define AFV_ANALYSIS_RING_BYTES (16L << 20)
/* afv_analyze (tr) or afv_analyze_file (f) holding at most ring_bytes of
** frames (tests hold fewer, to reach the second pass). */
int afv_analyze_ring(afv_analysis *a, const afv_traj *tr, afv_traj_file *f,
                     double l, double v0, double Dr, double steady_from,
                     double lag, long ring_bytes, char *err, size_t errlen);

#endif /* AFV_INTERNAL_H */
