/*
** paper.h -- what the files of `afv paper` share:
**   paper_data.c  the sweeps' tables (CSV), the (P0, v0) plane of means,
**                 a run's analysis files, the runs' integration
**   claims.c      the claims table: each claim of the paper, its rule,
**                 afv's value, the judgement
**   paper.c       the figures, the finite-size table and the command
**   paper_compare.c  two records side by side (afv paper --compare)
** Not part of the library.
*/
#ifndef AFV_PAPER_H
#define AFV_PAPER_H

#include "cli.h"
#include "figure.h"  /* the paper's thresholds, the figures' colours */

#include <stdio.h>

#define MAX_VALUES 64        /* distinct P0 (or v0, N) values of a sweep */
#define CELL_MAX 64          /* longest field of a CSV file */
#define PATH_LEN FIGURE_PATH_LEN

/* The giant cluster is left out of the power-law fit: sizes <= N/4 (at
** v0* the giant cluster holds about 0.7 N). */
#define CSD_FIT_FRACTION 0.25

/* ---- CSV files (paper_data.c) ------------------------------------------- */
typedef struct csv {
  int ncol, nrow;
  char (*name)[CELL_MAX];   /* ncol column names */
  char (*cell)[CELL_MAX];   /* nrow x ncol fields */
  int *line;                /* nrow: each row's line in the file (from 1) */
} csv;

void csv_free(csv *t);
/* Reads a CSV file with a header line ('#' lines skipped); 0 (message
** printed) on failure. */
int csv_read(const char *path, csv *t);
/* The column named name, or -1. */
int csv_col(const csv *t, const char *name);
/* Number in row r, column c ("inf", "nan" as strtod reads them); NaN if
** c < 0. */
double csv_num(const csv *t, int r, int c);
const char *csv_str(const csv *t, int r, int c);

/* ---- the grid sweep: means on the (P0, v0) plane ------------------------- */
enum { Q_NGC, Q_NCL, Q_OMEGA, Q_DEFF, Q_TAU, Q_T1, Q_BETA, N_Q };

typedef struct plane {
  int np, nv;                  /* distinct P0, v0 values */
  double p0[MAX_VALUES], v0[MAX_VALUES];
  double *mean[N_Q], *sem[N_Q];  /* [iv np + ip]; NaN where no job ended */
  double *seeds;               /* [iv np + ip]: the table's n_seeds, the
                               ** runs in at the point (0 where none) */
  int design_seeds;            /* seeds per point by design: points.csv's
                               ** most at a point, or with a table alone
                               ** the table's largest n_seeds */
  csv points;                  /* points.csv: id, P0, v0, seed (no rows
                               ** when read from a table alone) */
  char dir[RUN_PATH_MAX];      /* the sweep's folder ("" without runs) */
} plane;

/* OUT/grid: the design from points.csv, the means from table.csv; 0 with
** a message on failure. */
int plane_read(const char *out, plane *P);
/* A table alone (afv collect's table.csv, e.g. a committed
** grid_table.csv): the design is the table's rows, no run is read. */
int plane_read_table(const char *path, plane *P);
/* The same on the design of both tables, path's and also's (two records
** of one grid compared: a point that one lacks stays NaN, not left out). */
int plane_read_table_over(const char *path, const char *also, plane *P);
void plane_free(plane *P);
/* A sweep's table.csv (afv collect) with one state point or more; else 0
** and one line naming the file and what it lacks. */
int table_read(const char *sweep_dir, csv *t);
/* Adds v to the sorted set vals (n values, at most MAX_VALUES) if it is
** not there yet. */
void add_value(double *vals, int *n, double v);
/* Runs in at (ip, iv), over the whole plane, and by design (np nv
** design_seeds): a point or a grid with fewer is partial. */
int seeds_at(const plane *P, int ip, int iv);
int runs_in(const plane *P);
int runs_designed(const plane *P);
/* Mean (sem = 0) or standard error (sem = 1) of quantity q at (ip, iv). */
double at(const plane *P, int q, int ip, int iv, int sem);
int index_of(const double *vals, int n, double v);
/* The value of vals nearest to v (the panels' state points on a coarser
** grid than the paper's). */
int nearest(const double *vals, int n, double v);

/* The run folder (SWEEP/runs/ID) of the k-th job in points (points.csv of
** the sweep in dir) whose keys[j] equal vals[j], j < nk; 0 if none. */
int find_run(const csv *points, const char *dir, int nk,
             const char *const *keys, const double *vals, int k, char *path);
/* The run folder of the job at (P0, v0) of the grid with its k-th seed. */
int run_dir(const plane *P, double p0, double v0, int k, char *path);
/* A number from a run's analysis/summary.txt; NaN if missing. */
double summary_value(const char *dir, const char *key);
/* Column `name` of the CSV file DIR/analysis/FILE as a malloc'd array. */
double *run_column(const char *dir, const char *file, const char *name,
                   int *n);
/* p(n) of the runs at (ip, iv) pooled over the seeds (the mean of their
** csd.csv), index 1..ncell; *ncell from the sizes seen (0 if none). */
double *pooled_csd(const plane *P, int ip, int iv, int *ncell);

/* "afv 0.2.0, integrator euler, dt 0.01, exact force": how the grid's runs
** were made (read_integration); every claim's note ends with it. */
extern char paper_integration[320];
void read_integration(const plane *P);

/* 1 when OUT's sweeps are make paper's smoke scale: every figure and claim
** is marked so. */
extern int paper_smoke;
/* Non-empty when the grid's runs are not all in: the line every figure of
** afv paper OUT then carries ("PARTIAL GRID: 20 of 144 runs in ..."). */
extern char paper_partial[160];

/* ---- the dt study (dt_study.c) ------------------------------------------ */
/* tools/model_table.sh's dt_table.csv: one row per state point (P0, v0)
** and dt, n_seeds, each observable's NAME_mean and NAME_sem.  The rule
** that reads it is dt_study.c's header. */
#define DT_STEPS 3           /* the dt of the study, coarsest first */
#define DT_KEYS 5            /* P0, v0, dt, cap, n_seeds */
#define DT_OBS_MAX 16        /* observables (NAME_mean, NAME_sem) */
#define DT_MAX_POINTS 256    /* distinct (P0, v0) written to dt_verdicts */
extern const double dt_steps[DT_STEPS];      /* 0.01, 0.005, 0.0025 */

typedef struct dt_table {
  csv t;
  char path[PATH_LEN];         /* for the messages */
  int key[DT_KEYS];            /* columns of P0, v0, dt, cap, n_seeds */
  int obs[2 * DT_OBS_MAX];     /* columns of each NAME_mean, NAME_sem */
  double cap;                  /* every row's (the table holds one model) */
} dt_table;

/* One observable at one state point, at each dt of dt_steps. */
typedef struct dt_series {
  double p0, v0;
  double mean[DT_STEPS], sem[DT_STEPS];  /* NaN where absent */
  int seeds[DT_STEPS];                   /* 0: no row at that dt */
} dt_series;

typedef enum {
  DT_MODEL, DT_OF_DT, DT_NOT_CONVERGED, DT_MISSING, DT_NOT_MEASURED, DT_NONE
} dt_verdict;
/* "property of the model", "property of dt = 0.01", "not converged",
** "missing", "not measured", "none" */
const char *dt_verdict_name(dt_verdict v);

/* Reads and checks PATH: every column, every field a number, one cap, one
** row per (P0, v0, dt); else 0 and one line naming the file, the line and
** the key. */
int dt_table_read(const char *path, dt_table *T);
void dt_table_free(dt_table *T);
/* Observable NAME (e.g. "msd_beta") at (p0, v0); 0 if no row is there. */
int dt_series_at(const dt_table *T, double p0, double v0, const char *name,
                 dt_series *s);
/* Whether the conclusion at dt 0.01 is the one at 0.0025: 1 yes, 0 no, -1
** a number it needs is missing.  how: what the conclusion is. */
typedef int (*dt_same_fn)(const dt_series *s, const void *how);
int dt_same_side(const dt_series *s, const void *level);  /* a double */
int dt_same_value(const dt_series *s, const void *unused);
/* The seed means at dt index a and b agree within 2 sqrt(sem^2 + sem^2). */
int dt_agree(const dt_series *s, int a, int b);
/* The rule (dt_study.c's header); never DT_NOT_MEASURED or DT_NONE. */
dt_verdict dt_rule(const dt_series *s, dt_same_fn same, const void *how);
/* The worse of two state points' verdicts for one claim. */
dt_verdict dt_worse(dt_verdict a, dt_verdict b);
/* The distinct (P0, v0) of the table (at most max), sorted by P0 then
** v0; their number. */
int dt_state_points(const dt_table *T, double (*pt)[2], int max);
/* "m +- e | m +- e | m (1 seed)" at dt 0.01 | 0.005 | 0.0025. */
void dt_series_text(const dt_series *s, char *buf, size_t len);
/* dt_verdicts.csv: per observable and state point, the finest two dt
** compared, dt 0.01 against 0.0025, and dt_rule's verdict on the value
** and on the side of the observable's threshold (where it has one). */
int dt_verdicts_write(const dt_table *T, const char *path);

/* ---- figures (paper.c), shared with paper_compare.c ----------------------- */
/* Commits a figure opened by figure_open (figure.h): a smoke run's, or a
** partial grid's, marked so. */
int figure_close(FILE *fp, const char *tmp, const char *path);
/* The map of quantity q over the plane, its contour at level and an
** optional dashed curve (cx, cy; cn points): m filled, nothing written. */
void map_of(const plane *P, int q, const char *title, const char *zlabel,
            int logz, double level, const double *cx, const double *cy,
            int cn, afv_map *m);
/* The dispersal points v_s(P0) (N_GC/N falls below 0.99 along v0) into
** bp, bv (their number returned) and their fit (*fitted 1 if made). */
int dispersal_boundary(const plane *P, double *bp, double *bv,
                       afv_boundary *fit, int *fitted);
/* The fitted boundary over the plane's P0 range: CURVE_POINTS points. */
#define CURVE_POINTS 60
int boundary_curve(const plane *P, const afv_boundary *fit, double *cx,
                   double *cy);
/* The boundaries of Fig. 7(a) on the plane (afv paper's summary): the
** dispersal points and fit, the Omega = 0.5 line (along P0), the D_eff =
** 1e-8 and msd_beta = 0.5 lines (along v0); boundary_label names them. */
#define N_BOUNDARIES 4
typedef struct boundaries {
  double bx[N_BOUNDARIES][MAX_VALUES], by[N_BOUNDARIES][MAX_VALUES];
  int nb[N_BOUNDARIES];        /* points of each */
  afv_boundary fit;            /* the dispersal points' fit, */
  int fitted;                  /* if made */
} boundaries;
extern const char *const boundary_label[N_BOUNDARIES];
void phase_boundaries(const plane *P, boundaries *B);
/* afv paper --compare DIR_A DIR_B OUT (paper_compare.c): 0, or
** EXIT_BAD_INPUT with a message. */
int paper_compare(const char *a, const char *b, const char *out);

/* ---- the claims table (claims.c) ---------------------------------------- */
/* Where the claims' numbers come from: the plane, and where the runs are
** gone (afv paper --claims-from) the earlier claims.csv for the claims a
** table cannot give (the cluster-size exponents, from the runs' csd.csv). */
typedef struct claim_source {
  const plane *P;
  int have_runs;               /* 1: P->dir's runs are read */
  const char *previous;        /* an earlier claims.csv's path, or NULL */
  const dt_table *dt;          /* the dt study (--dt-table), or NULL */
} claim_source;

/* Judges every claim of the paper (the rule table of claims.c) and writes
** PATH atomically; prints "N claims, Y agree, U undetermined" into
** summary.  0 on a write error. */
int claims_table(const claim_source *S, const char *path, char *summary,
                 size_t len);
/* The runs' integration ("afv 0.2.0, integrator euler, dt 0.01, exact
** force") that ends the first note of the claims.csv at path, into buf;
** 0 if there is none. */
int claims_integration(const char *path, char *buf, size_t len);

#endif /* AFV_PAPER_H */
