/*
** sweep.h -- what afv sweep's two files share: its options, the grid of
** jobs they make (sweep.c: options, grid, runners, the sweep's folder) and
** the jobs' cost and SLURM runner (sweep_slurm.c).
*/
#ifndef AFV_SWEEP_H
#define AFV_SWEEP_H

#include "cli.h"

#include <stdio.h>

/* At most this many jobs in one sweep (a guard against a typo in a step). */
#define SWEEP_MAX_JOBS 100000
/* At most this many --KEY options. */
#define SWEEP_MAX_KEYS 64
/* Longest value text of one grid point (bytes), and its buffer size. */
#define VALUE_LEN_MAX 63
#define VALUE_MAX (VALUE_LEN_MAX + 1)
/* Tasks of one SLURM job array at most, by default (SLURM's default
** MaxArraySize is 1001: indices 0 .. 1000). */
#define SLURM_ARRAY_MAX 1000
/* The program the runners call, copied into DIR (a path relative to DIR,
** where every job runs). */
#define SWEEP_PROGRAM "./afv"
/* Without --svg_every a job draws a snapshot every max(afv run's default,
** steps / SWEEP_SNAPSHOTS) steps: at most SWEEP_SNAPSHOTS + 1 pictures of
** about 0.5 KB a cell however long the run (a 10^6-step job of 400 cells
** drew 201, 45 MB, at afv run's default of 5000). */
#define SWEEP_SNAPSHOTS 20

/* One --KEY VALUES option: its expanded values. */
typedef struct sweep_axis {
  const char *key;        /* run key */
  const char *text;       /* VALUES as given */
  int n;                  /* number of values (1: fixed) */
  char (*value)[VALUE_MAX];  /* n value texts */
} sweep_axis;

/* The options of afv sweep. */
typedef struct sweep_opts {
  const char *out, *afv, *steady_from, *lag;
  const char *reanalyze;  /* --reanalyze DIR: a new analysis of DIR */
  const char *account, *partition, *mem, *time;  /* SLURM resources */
  long throttle;          /* tasks of an array at once (0: no limit) */
  long seeds;             /* --seeds K (0: not given) */
  long per_task;          /* jobs per SLURM array task */
  long array_max;         /* tasks per SLURM array at most */
  int nax;                /* --KEY options */
  sweep_axis ax[SWEEP_MAX_KEYS];
  int seed_axis;          /* index of --seed in ax, or -1 */
} sweep_opts;

/* The jobs: every combination of the non-seed axes (first given =
** slowest), times the seeds.  A job's values: idx[axis]. */
typedef struct sweep_grid {
  long njobs, nseeds;
  int nax;                 /* axes, the seed axis last if any */
  const sweep_axis *ax[SWEEP_MAX_KEYS + 1];
  sweep_axis seeds;        /* --seeds K expanded (if no --seed) */
  double max_cells, max_steps;  /* the largest N and steps of a job */
} sweep_grid;

/* Values of job j (0-based), one per axis of g, into names/values. */
void job_values(const sweep_grid *g, long j, const char **names,
                const char **values);
/* 1 if axis k of g is swept (seed: never a swept key of points.csv). */
int swept(const sweep_grid *g, int k);
/* The value of key for job j: its axis value if the key is swept or
** fixed, else def. */
double job_number(const sweep_grid *g, long j, const char *key, double def);
/* Parses a whole string as a finite double; 0 if it is not one. */
int whole_double(const char *text, double *v);

/* ---- sweep_slurm.c: cost and SLURM ------------------------------------------ */
/* What the jobs of a sweep cost, estimated before anything is written. */
typedef struct sweep_cost {
  double cpu;            /* CPU seconds of every job, on one core */
  double cpu_max;        /* CPU seconds of the longest job */
  double trajectory;     /* bytes of the trajectory.dat files */
  double pictures;       /* bytes of the SVG pictures */
  double rest;           /* bytes of everything else */
  double npictures;      /* SVG pictures (snapshots and final.svg) */
} sweep_cost;

/* The cost of every job of g (a cells file's N counts as --N's). */
void sweep_cost_of(const sweep_grid *g, sweep_cost *c);
/* Prints the cost of njobs jobs and how to cut it (stdout). */
void print_cost(const sweep_cost *c, long njobs);
/* Without --svg_every: every job's snapshots bounded (SWEEP_SNAPSHOTS), as
** an axis of o; 0 if out of memory. */
int bound_snapshots(sweep_opts *o);
/* The time limit of an array task (--time, else estimated) as SLURM's
** text; the estimate in seconds. */
double estimate_time(const sweep_grid *g, const sweep_opts *o, char *text,
                     size_t len);
/* The memory of one job in MB, estimated (twice its measured peak). */
long estimate_mem_mb(const sweep_grid *g);
/* slurm.sh: the job arrays that run the sweep's jobs (jobs.txt). */
void write_slurm(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                 const char *afv);

#endif
