/*
** afv_tool.h -- what the afv program needs from the library beyond the
** model: reading lines, messages and atomic writes, checkpoints and the
** T1 reference of a run, analysis files, line plots.  (Phase diagrams and the paper's fits are the
** program's own: cmd/fits.h.)
** Not installed (make install copies afv.h alone): a user of the model
** needs afv.h only; these may change with the program.
**
** Contents
**   1. reading lines (afv_lines), messages, atomic writes     io.c
**   2. run files: checkpoints, the T1 reference, analysis files io.c,
**                                                         analysis.c
**   3. line plots and the plots of an analysis            svg.c
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

/* ---- 3. line plots and the plots of an analysis (svg.c) ---------------- */
/* A small line-plot helper for analysis figures. */
typedef struct afv_plot {
  const char *title, *xlabel, *ylabel;  /* texts (escaped on output) */
  int         logx, logy;  /* 1: log10 axis with decade ticks */
  double      ymin, ymax;  /* fixed y range if ymin < ymax, else fitted */
  const char *no_data;     /* why, when no series has a point to draw: the
                           ** plot then says "no data: " and this (NULL:
                           ** "no data" alone) */
} afv_plot;
/* afv_plot_series.points: how a series is drawn. */
enum { AFV_PLOT_LINE_MARKS,  /* a line, and a marker per point if at most
                             ** 60 points */
       AFV_PLOT_MARKS,       /* a marker per point and no line (scatter) */
       AFV_PLOT_LINE };      /* the line alone (an error bar) */
typedef struct afv_plot_series {
  const double *x, *y;  /* n points; non-positive values skipped on log axes */
  int           n;
  const char   *label;  /* legend text (NULL: none) */
  const char   *color;  /* SVG colour, e.g. "#1f77b4" */
  int           points; /* AFV_PLOT_LINE_MARKS (0), _MARKS (1) or _LINE */
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

#endif /* AFV_TOOL_H */
