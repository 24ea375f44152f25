/*
** afv_tool.h -- what the afv program needs from the library beyond the
** model: reading lines, messages and atomic writes, checkpoints and the
** T1 reference of a run, analysis files, the noise streams and fast sin,
** cos and atan2, line plots, phase diagrams and the paper's fits.
** Not installed (make install copies afv.h alone): a user of the model
** needs afv.h only; these may change with the program.
**
** Contents
**   1. reading lines (afv_lines), messages, atomic writes     io.c
**   2. run files: checkpoints, the T1 reference, analysis files io.c,
**                                                         analysis.c
**   3. fast sin, cos and atan2; the random streams        fastmath.c, rng.c
**   4. line plots and the plots of an analysis            svg.c
**   5. phase diagrams                                     phase.c
**   6. the paper's fits                                   fits.c
*/
#ifndef AFV_TOOL_H
#define AFV_TOOL_H

#include "afv.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* ---- 1. reading lines, messages, atomic writes (io.c) ------------------ */
/* Reading text files.  Every reader of afv reads through afv_lines: the
** path must name a regular file (a directory, pipe or device is refused),
** each line is handed out whole (a line longer than AFV_LINE_MAX bytes is
** refused, never split), and a NUL byte is refused where it is; every
** message starts "FILE:LINE: ".  Usage:
**   if (afv_lines_open(&L, path, err, errlen) != AFV_OK) return ...;
**   while ((got = afv_lines_next(&L, err, errlen)) > 0) use L.line;
**   if (got < 0) the status is L.status;  afv_lines_close(&L); */
#ifndef AFV_LINE_MAX
#define AFV_LINE_MAX (1 << 20)
#endif
#ifndef AFV_LINES_BLOCK
#define AFV_LINES_BLOCK 8192   /* bytes read at a time */
#endif
/* Most cells (rows) a reader accepts: 2n + 1 still fits an int. */
#define AFV_CELLS_MAX 1073741823
typedef struct afv_lines {
  const char *path;    /* as given (not copied), for messages */
  FILE       *fp;
  long long   size;    /* the file's size in bytes, when opened */
  char       *line;    /* the current line, without its '\n' (NUL-ended) */
  size_t      len;     /* its length in bytes */
  long long   lineno;  /* its number, from 1 */
  int         newline; /* 1 if it ended with '\n' (0: the last line of a
                       ** file that does not end with one) */
  int         status;  /* after afv_lines_next returned -1: the error */
  size_t      cap, pos, fill;  /* line capacity; unread part of buf */
  char        buf[AFV_LINES_BLOCK];
} afv_lines;
int  afv_lines_open(afv_lines *L, const char *path, char *err, size_t errlen);
/* 1: the next line is in L->line; 0: end of file; -1: an error (message in
** err, status in L->status). */
int  afv_lines_next(afv_lines *L, char *err, size_t errlen);
void afv_lines_close(afv_lines *L);

/* snprintf into err (if err != NULL): the library's way to explain a status. */
void afv_errorf(char *err, size_t errlen, const char *fmt, ...);

/* Atomic output: write to the FILE from afv_atomic_open (a new file
** PATH.PID.RAND.tmp created exclusively, never through a link; its name in
** tmp, which needs room for PATH and 32 bytes), then afv_atomic_commit
** flushes, closes and renames it over PATH.  An interrupted writer leaves
** PATH as it was.  On error the temporary (afv's own) is removed. */
FILE *afv_atomic_open(const char *path, char *tmp, size_t tmplen);
/* The PID of those names: 0 unless the program sets it (afv's main sets
** its process id, so a killed writer's temporaries can be told apart). */
extern long afv_atomic_pid;
int   afv_atomic_commit(FILE *fp, const char *tmp, const char *path);

/* ---- 2. run files: checkpoints, T1 reference, analysis (io.c, ...) ----- */
/* The append-only outputs whose sizes a checkpoint records: on resume they
** are cut back to these sizes, so they match the checkpointed state. */
#define AFV_CKPT_FILES 3
extern const char *const afv_checkpoint_files[AFV_CKPT_FILES];

/* Everything needed to continue a run beside its parameters (exact). */
typedef struct afv_checkpoint {
  int        n;      /* cells */
  long long  step;   /* steps taken */
  double     t;      /* simulated time */
  unsigned long long seed;         /* generator key (also in params.txt) */
  long long  bytes[AFV_CKPT_FILES]; /* sizes of afv_checkpoint_files[k] */
  double    *r;      /* 2n unwrapped centres */
  double    *theta;  /* n angles */
} afv_checkpoint;

/* Writes (atomically) / reads a checkpoint file (format in io.c). */
int  afv_checkpoint_write(const char *path, const afv_checkpoint *c);
int  afv_checkpoint_read(const char *path, afv_checkpoint *c, char *err,
                         size_t errlen);
/* Line of "bytes afv_checkpoint_files[k] SIZE" in a checkpoint: this + k. */
#define AFV_CKPT_BYTES_LINE 6
/* Checks each recorded size (bytes > 0) against its file beside the
** checkpoint at path: the file must exist and hold at least that many
** bytes.  AFV_OK, or AFV_EFORMAT with "path:LINE: bytes FILE: ..." in err. */
int  afv_checkpoint_check_files(const char *path, const afv_checkpoint *c,
                                char *err, size_t errlen);
void afv_checkpoint_free(afv_checkpoint *c);

/* A format-2 trajectory frame starts with AFV_TRAJ_FRAME_HEAD bytes: its
** step (int64) and time (float64), little-endian (io.c).  Decodes them;
** the step is -1 if it is not in 0 .. 2^63-1. */
#define AFV_TRAJ_FRAME_HEAD 16
#define AFV_TRAJ_CELL_BYTES 20  /* then per cell x, y (float64), theta (float32) */
void afv_traj_frame_head(const unsigned char *b, long long *step, double *t);

/* C(0) in a file (T1 REFERENCE format, io.c): written atomically by afv run,
** read back on --resume; n is the number of cells (pairs i < j < n). */
int    afv_t1_reference_write(const char *path, const afv_t1 *t);
int    afv_t1_reference_read(const char *path, int n, afv_t1 *t, char *err,
                             size_t errlen);

/* Writes summary.txt, msd.csv, csd.csv, csd_binned.csv and series.csv into
** the existing directory dir, each atomically.  Numbers only: the plots of
** an analysis are drawn by afv_svg_msd, afv_svg_series and afv_svg_csd. */
int  afv_analysis_write(const afv_analysis *a, const char *dir, char *err,
                        size_t errlen);

/* ---- 3. fast sin, cos and atan2 (fastmath.c); random streams (rng.c) --- */
/* The counter-clockwise angle from +x to the vector (x, y), in [0, 2 pi]
** (2 pi only by rounding, for y a hair below 0): atan2(y, x) + (2 pi if
** negative), within 8.9e-16 (measured), in plain arithmetic (fastmath.h);
** NaN if both components are infinite. */
double afv_angle(double y, double x);
/* sin x and cos x to within 2.22e-16 of the C library's (measured), in
** plain arithmetic without a branch (fastmath.h); |x| >= 1e6, inf and
** NaN are passed to sin and cos. */
void afv_sincos(double x, double *sin_x, double *cos_x);

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

/* ---- 4. line plots and the plots of an analysis (svg.c) ---------------- */
/* A small line-plot helper for analysis figures. */
typedef struct afv_plot {
  const char *title, *xlabel, *ylabel;  /* texts (escaped on output) */
  int         logx, logy;  /* 1: log10 axis with decade ticks */
  double      ymin, ymax;  /* fixed y range if ymin < ymax, else fitted */
} afv_plot;
typedef struct afv_plot_series {
  const double *x, *y;  /* n points; non-positive values skipped on log axes */
  int           n;
  const char   *label;  /* legend text (NULL: none) */
  const char   *color;  /* SVG colour, e.g. "#1f77b4" */
  int           points; /* 1: a marker per point and no line (scatter) */
} afv_plot_series;
/* The legend (class="legend") is right of the plot area, never on it. */
int afv_svg_plot(FILE *out, const afv_plot *pl, const afv_plot_series *s,
                 int ns);

/* The plots of an analysis, as afv analyze writes them: msd.svg (plain and
** relative MSD against lag, log-log), series.svg (N_GC/N and Omega against
** time), csd.svg (the cluster-size distribution, each size and its log
** bins, afv_csd_log_bins). */
int afv_svg_msd(FILE *out, const afv_analysis *a);
int afv_svg_series(FILE *out, const afv_analysis *a);
int afv_svg_csd(FILE *out, const afv_analysis *a);

/* ---- 5. phase diagrams (phase.c) ---------------------------------------- */
/* The first x where y falls from >= level to < level as x grows (linear
** interpolation between consecutive finite points); 1 if found into *xc. */
int afv_curve_cross(int n, const double *x, const double *y, double level,
                    double *xc);

/* Least-squares fit of the dispersal boundary v_s(P0) = v0* - c P0^alpha
** (the paper's form) to n >= 3 points (P0 > 0): linear in (v0*, c) at each
** alpha, alpha in [0.05, 12] by a scan and a golden-section search.
** Standard errors from s^2 (J^T J)^-1 with s^2 = rss / (n - 3): NaN when
** n = 3.  AFV_EINVAL if n < 3 or a point is not finite. */
typedef struct afv_boundary {
  int    n;                  /* points fitted */
  double v0star, c, alpha;   /* the fit */
  double se_v0star, se_c, se_alpha;  /* their standard errors */
  double rss;                /* residual sum of squares */
} afv_boundary;
int afv_boundary_fit(int n, const double *p0, const double *vs,
                     afv_boundary *b);

/* A map of z over an nx x ny grid (x, y increasing), one coloured rectangle
** per point (grey: NaN), the contour z = level (marching squares; NaN
** level: none), an optional dashed curve (cx, cy; cn points), a colour bar. */
typedef struct afv_map {
  const char   *title, *xlabel, *ylabel, *zlabel;
  int           nx, ny;
  const double *x, *y;       /* grid coordinates */
  const double *z;           /* z[j nx + i] at (x[i], y[j]) */
  int           logz;        /* 1: colour by log10 z */
  double        level;       /* contour level */
  const double *cx, *cy;     /* curve (may be NULL with cn = 0) */
  int           cn;
} afv_map;
int afv_svg_map(FILE *out, const afv_map *m);

/* ---- 6. the paper's fits (fits.c) --------------------------------------- */
/* Power law p(n) ~ n^exponent fitted to the decay of a cluster-size
** distribution (csd as afv_analysis.csd, index 1..n): log-binned
** (afv_csd_log_bins), density per size in each bin at the bin's geometric
** centre, least squares of log10 density on log10 size over the bins after
** the densest one through the last one whose sizes are all <= nmax (sizes
** above nmax, the giant cluster, are left out); empty bins skipped.
** se = the slope's standard error (NaN from 2 bins).  AFV_EINVAL if fewer
** than 2 bins are left. */
typedef struct afv_powerlaw {
  double exponent, se;   /* slope of log p against log n, its error */
  int    nbins;          /* bins fitted */
  int    lo, hi;         /* sizes they cover */
} afv_powerlaw;
int afv_powerlaw_fit(const double *csd, int n, int nmax, afv_powerlaw *fit);

/* Where curve a falls below curve b (n points on a common increasing x):
** the first sign change of ya - yb from > 0 to < 0 among the points where
** both are finite and differ (points where they are equal, e.g. both 1,
** take no side), by linear interpolation; 1 if found into *xc. */
int afv_curves_cross(int n, const double *x, const double *ya,
                     const double *yb, double *xc);

/* The common crossing of nc curves y[c n + k] (c in increasing P0) on x:
** x = mean over the pairs a < b that cross (afv_curves_cross: curve a, the
** lower P0, falls below b); se = jackknife over the curves (leave one out,
** recompute the mean); pairs = how many crossed.  AFV_EINVAL if none. */
typedef struct afv_crossing_fit {
  double x, se;
  int    pairs;
} afv_crossing_fit;
int afv_curves_cross_common(int nc, int n, const double *x, const double *y,
                            afv_crossing_fit *out);

/* Scaling collapse (paper, clustering section): the v0* and alpha in
** [0, 4] that put the curves y[c n + k] (at x[k], P0 = p0[c]) on one curve
** of s = (x - v0*) / P0^alpha, by minimising the mean squared distance of
** each point from every other curve interpolated at its s (grid search,
** coarse then fine: v0* to 0.002, alpha to 0.005); se by jackknife over
** the curves (nc >= 3, else NaN).  AFV_EINVAL for nc < 2, n < 2, x not
** increasing or P0 <= 0. */
typedef struct afv_collapse {
  double vstar, alpha, se_vstar, se_alpha;
  double cost;           /* the minimum mean squared distance */
} afv_collapse;
int afv_collapse_fit(int nc, int n, const double *x, const double *y,
                     const double *p0, afv_collapse *out);

#endif /* AFV_TOOL_H */
