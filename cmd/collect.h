/*
** collect.h -- what afv collect's two files share: the sweep's table of
** jobs and state points (collect.c reads and verifies it, writes table.csv
** and missing.txt) and its figures (collect_figures.c: the (P0, v0) plane,
** the dispersal boundary fit, the phase-diagram figures).
*/
#ifndef AFV_COLLECT_H
#define AFV_COLLECT_H

#include "cli.h"
#include "figure.h"  /* the paper's thresholds, the figures' colours */

#include <sys/stat.h>

#define COLLECT_MAX_KEYS 32   /* swept keys in points.csv */
#define FIELD_MAX 64          /* longest value in points.csv */
#define LINE_MAX_POINTS 4096  /* longest line of points.csv */

/* Order parameters of the table: column name and summary.txt key. */
typedef struct order_param {
  const char *name, *key, *label;
  int logy;               /* 1: plotted on a log axis */
} order_param;
/* The table's order parameters (collect.c), N_PARAMS of them, in the
** order of the enum below. */
#define N_PARAMS 7
extern const order_param collect_params[N_PARAMS];
enum { P_NGC, P_NCL, P_OMEGA, P_DEFF, P_TAU, P_T1, P_BETA };

/* What afv collect found for a job. */
enum { JOB_MISSING, JOB_DONE, JOB_DAMAGED };

typedef struct job {
  char id[FIELD_MAX];
  char seed[FIELD_MAX];
  int line;               /* its line in points.csv */
  int point;              /* state point it belongs to */
  int state;              /* JOB_MISSING, JOB_DONE or JOB_DAMAGED */
  char *why;              /* missing or damaged: the reason (allocated) */
  double v[N_PARAMS];     /* its order parameters */
} job;

typedef struct point {
  int first;              /* first job of the point (its key values) */
  int n;                  /* verified jobs */
  int lack_beta;          /* verified jobs without msd_beta */
  double mean[N_PARAMS], sem[N_PARAMS];
} point;

typedef struct sweep_table {
  const char *dir;
  int nkeys;
  char key[COLLECT_MAX_KEYS][FIELD_MAX];
  int njobs, npoints;
  job *jobs;
  char (*val)[FIELD_MAX]; /* VAL(T, j, k): key k of job j */
  double *num;            /* NUM(T, j, k): the same as a number (or NaN) */
  point *points;
  struct stat analysis_args;  /* DIR/analysis.txt, if has_args */
  int has_args;
} sweep_table;
#define VAL(T, j, k) ((T)->val[(size_t)(j) * (size_t)(T)->nkeys + (size_t)(k)])
#define NUM(T, j, k) ((T)->num[(size_t)(j) * (size_t)(T)->nkeys + (size_t)(k)])

/* Order of two values of key k of jobs a and b (as numbers when both are,
** else as text), and of jobs a and b by state point, key by key, skipping
** key skip (-1: none): <0, 0, >0 (collect.c). */
int cmp_value(const sweep_table *T, int a, int b, int k);
int cmp_point(const sweep_table *T, int a, int b, int skip);
/* The index of swept key name in T's keys, or -1 (collect_figures.c). */
int key_index(const sweep_table *T, const char *name);
/* fits.txt and the figures of T into dir/figures/ (collect_figures.c);
** 0 on a write error, which it reports. */
int write_figures(const char *dir, const sweep_table *T);

#endif
