/*
** afv_internal.h -- what the library's own files share and no caller needs:
** the structs behind afv.h's opaque afv_geom and afv_sim, the steps of the
** geometry and of the simulation, the OpenMP macros.  Included by the
** library's .c files, the white-box tests and the parts of the program
** that need the internals; not installed (make install copies afv.h and
** afv_config.h only).  It does not include afv_tool.h, the part of the
** library that serves the program alone: a file that uses it says so.
*/
#ifndef AFV_INTERNAL_H
#define AFV_INTERNAL_H

#include "afv.h"

#include <float.h>
#include <stddef.h>
#include <stdint.h>

/* The tolerances of the library are in afv_config.h (through afv.h),
** each with its meaning and the test that pins it. */

/* ---- fast sin, cos, atan2, log, hypot (fastmath.c); random streams ---- */
/* The counter-clockwise angle from +x to the vector (x, y), in [0, 2 pi]
** (2 pi only by rounding, for y a hair below 0): atan2(y, x) + (2 pi if
** negative), within 8.9e-16 (measured), in plain arithmetic (fastmath.h);
** NaN if both components are infinite. */
double afv_angle(double y, double x);
/* sin x and cos x to within 2.22e-16 of the C library's (measured), in
** plain arithmetic without a branch (fastmath.h); |x| >= 1e6, inf and
** NaN are passed to sin and cos. */
void afv_sincos(double x, double *sin_x, double *cos_x);
/* log x within 1 ulp (fdlibm's e_log.c, fastmath.h), the same bits on
** every IEEE 754 machine: the Box-Muller radius uses it. */
double afv_log(double x);
/* sqrt(x^2 + y^2) without overflow or underflow, within about 1 ulp, in
** plain arithmetic (fastmath.h): inf if a component is infinite. */
double afv_hypot(double x, double y);

/* Philox4x32-10 (Salmon et al., SC'11; Random123): out = bijection of the
** 128-bit counter ctr under the 64-bit key. */
void afv_philox4x32(const uint32_t ctr[4], const uint32_t key[2],
                    uint32_t out[4]);
/* Streams: counter = (cell, step low 32 bits, step high 32 bits, purpose),
** key = seed.  One call yields 2 uniforms with 53 random bits each. */
enum { AFV_RNG_NOISE = 1, AFV_RNG_INIT_POS = 2, AFV_RNG_INIT_ANGLE = 3 };
/* Two uniforms in (0, 1] (multiples of 2^-53) for (seed, cell, step, purpose). */
void afv_rng_uniform2(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose, double u[2]);
/* Two independent standard normals (Box-Muller: cosine and sine branch)
** from the stream of counter `pair`. */
void afv_rng_normal2(unsigned long long seed, uint32_t pair,
                     unsigned long long step, unsigned purpose, double z[2]);
/* The normal of `cell`: z[cell % 2] of afv_rng_normal2 for pair cell / 2
** (the noise of cell i at step s in afv_sim_step). */
double afv_rng_normal(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose);

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
  int    *nbr;          /*   up to cand_lim[i] are unused (room kept)      */
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
  int    *cand;         /*   cand[cand_start[i] .. cand_end[i]-1], room  */
  int    *cand_end;     /*   up to cand_lim[i] (a re-anchored cell's     */
  int    *cand_lim;     /*   list may move past the rebuild's ones)      */
  int     cand_used, cand_top;  /* cand[] in use; reserved (spare room) */
  int     moved_lists;  /* lists moved into the spare room since the rebuild */
  double *cand_r0;      /* anchors: centres when each cell's candidates
                        ** were made (the rebuild, or a re-anchoring) */
  int    *anchor_node;  /* re-anchored cell: its node, else -1 (MOVERS) */
  int    *node_head, *node_next, *node_cell;  /* re-anchored cells by bin */
  double *node_xy;      /*   of the rebuild's grid, at their anchors */
  int     n_nodes, cap_nodes, cap_heads;
  double *rw;           /* centres as the lists see them (wrapped) */
  afv_box cand_box;     /* box and l the candidates were built for */
  double  cand_l;
  int     cand_n;       /* cells they were built for; 0 = none */
  int     cap_cand, n_rebuilds;  /* n_rebuilds: candidate rebuilds so far */
  afv_grid cand_grid;   /* the cell list of the last rebuild */
  unsigned char *is_mover; /* 1 for a cell moved beyond the skin */
  double  cand_checks;  /* re-anchoring work since the rebuild (MOVERS) */
  double  cand_moved;   /* largest distance of a cell from its anchor, as
                        ** of the last call (afv_cells_around widens by it) */
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
** the largest distance of a cell from its anchor, is at most 0.15 l:
** neighbours.c, MOVERS). */
int  afv_cells_around(const afv_geom *g, double x, double y, double R,
                      double moved, int *out);

/* Renumbers the n centres r in place in the order of afv_spatial_order,
** so that cells near in space are near in memory.  AFV_OK or AFV_ENOMEM. */
int  afv_spatial_renumber(int n, double *r, double l, const afv_box *b);

/* The cell a dense search has cut so far (geom.c, afv_reach_of): its
** vertices and arcs, in the cell's frame, for the test of the next
** centres (neighbours.c, DENSE). */
typedef struct afv_reach {
  int nv, na;           /* vertices; arcs (-1: no cut, the whole disk) */
  double l;
  double *v;            /* vertex k at (v[2k], v[2k+1]) */
  double *arc;          /* arc k from (arc[4k], arc[4k+1]) counter-clockwise
                        ** to (arc[4k+2], arc[4k+3]), on the circle */
} afv_reach;
/* The cell cut by k centres at displacements D, sorted by direction, with
** their edge cache edge (as afv_neighbours' lists): into R (room for
** 2k + 2 vertices, k + 1 arcs); work: afv_reach_work(k) bytes. */
void   afv_reach_of(const double *edge, const double *D, int k, double l,
                    void *work, afv_reach *R);
size_t afv_reach_work(int k);
/* 1 if a centre at (x, y) from the cell's centre cuts R's cell deeper than
** AFV_CUT_DEPTH l. */
int    afv_reach_cuts(const afv_reach *R, double x, double y);
/* 0 if no point of the rectangle q = {x0, x1, y0, y1} (cell frame) can
** cut R's cell (a superset test: 1 may also mean none can). */
int    afv_reach_meets_rect(const afv_reach *R, const double *q);

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
