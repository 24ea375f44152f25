/*
** run.h -- what the files of afv run share (cmd/run*.c; not part of the
** library, nor of the other commands, which see cli.h):
**
**   run.c          the job: its state, outputs, the loop, a fresh run, cmd_run
**   run_config.c   the keys: table, parsing, range checks, params.txt, the
**                  command line
**   run_compute.c  what a run can compute (checked before anything is made)
**   run_dir.c      the run directory: its lock, files afv did not write
**   run_resume.c   --resume and --continue
*/
#ifndef AFV_RUN_H
#define AFV_RUN_H

#include "cli.h"
#include "afv.h"

#include <stdio.h>

/* ---- afv run: the simulation job --------------------------------------- */
/* The job (paper, Sec. Model): the protocol (afv_protocol_start: build
** the start (init), relax it at v0 = 0 to max |F| <= relax_tol, a kink of
** E, or relax_max_steps, reported with its figures), then integrate the
** active dynamics for `steps` steps, writing samples, frames, snapshots
** and checkpoints.  Every parameter lives in one table (run_keys), which
** gives the defaults, the config-file and command-line parsing, --help
** and params.txt. */

typedef struct run_cfg {
  long long N;            /* cells */
  double phi;             /* packing fraction N pi l^2 / L^2 */
  char box[16];           /* "periodic" or "open" */
  double l, KA, KP, A0, P0, Lambda, cap;       /* model (afv_params) */
  char integrator[16];    /* "euler", the one integrator (REMOVED KEYS) */
  double mu, v0, Dr, dt;                       /* dynamics (afv_dyn) */
  long long steps;        /* active steps in the whole run */
  unsigned long long seed;/* noise and random starts */
  char init[16];          /* "cluster", "lattice", "random" or "file" */
  double spacing;         /* lattice start: lattice spacing, in l */
  double relax_tol;       /* relaxation force tolerance */
  char relax[16];         /* "flow" (afv_relax) or "fire" (afv_relax_fire) */
  long long relax_max_steps;   /* relaxation step limit (0: no relaxation) */
  long long sample_every, frame_every, checkpoint_every, svg_every;
  int xyz;                /* 1: also write trajectory.xyz */
  int quiet;              /* 1: no progress and no summary on stderr */
  char cells[RUN_PATH_MAX];    /* CELLS file, or "none" */
} run_cfg;

typedef enum { K_REAL, K_INT, K_SEED, K_BOOL, K_WORD, K_PATH } key_kind;

typedef struct run_key {
  const char *name;   /* KEY, as in the file and as --KEY */
  key_kind kind;      /* how the value is parsed */
  size_t off;         /* where it goes in run_cfg */
  const char *def;    /* default, parsed like a user's value */
  const char *unit;   /* unit, for --help */
  const char *help;   /* meaning, for --help */
} run_key;

/* The number of keys of afv run (run_config.c's table run_keys). */
#define N_RUN_KEYS 29

/* ---- analysis columns of observables.csv (analysis helper) -------------- */
/* ngc_frac, n_clusters, omega and t1 (analysis.c).  T1 counts the contact
** changes since step 0, so it needs C(0), the contacting pairs at step 0:
** kept in memory and in DIR/t1_reference.txt (a count line, then "i j"
** lines), which --resume reads back, so a resumed run writes the same rows
** as an unbroken one. */
typedef struct obs_analysis {
  afv_clusters c;   /* clusters of the state being sampled (work space) */
  afv_t1 t1;        /* C(0) */
} obs_analysis;

/* ---- the state of a run ------------------------------------------------- */
typedef struct run_state {
  run_cfg cfg;             /* parameters in force */
  afv_cells cells;         /* per-cell columns (n = 0 if none) */
  afv_sim *sim;            /* the simulation (afv_sim_new) */
  char dir[RUN_PATH_MAX];  /* output directory */
  FILE *out[AFV_CKPT_FILES];  /* append-only files (NULL if not written) */
  FILE *log;               /* log.txt */
  long long ckpt_step;     /* step of the last checkpoint */
  long long start_step;    /* step this invocation started from */
  double wall0;            /* wall clock at the start of the active run */
  double last_progress;    /* wall clock of the last progress line */
  int progress;            /* 1: progress lines on stderr */
  double start_spacing;    /* cluster start: the spacing used, in l (it is
                           ** reduced if the cluster would not fit the
                           ** box); 0 for other starts */
  obs_analysis an;         /* analysis columns of observables.csv */
  int lock_fd;             /* DIR/observables.csv while this process holds
                           ** the run directory's lock, else -1 */
  int made_dir;            /* 1 if this process created DIR */
  int dir_fd;              /* DIR while this process holds its flock, else
                           ** -1 (run_dir.c, one writer per directory) */
  char io_path[RUN_PATH_MAX + 96];  /* the file whose writing failed */
  int io_errno;            /* and why (errno then) */
  long long relax_jumps;   /* afv_sim_jumps at the end of the relaxation
                           ** (0: none in this process) */
  double relax_largest;    /* afv_sim_largest_move then, in l (0: none) */
} run_state;

enum { OUT_TRAJ, OUT_OBS, OUT_XYZ };   /* order of afv_checkpoint_files */

/* Command-line arguments of afv run. */
typedef struct run_args {
  const char *out, *resume, *config;
  const char *steps;      /* --steps with --resume */
  int quiet;              /* 0: not given; 1: --quiet or --quiet 1; -1: --quiet 0 */
  int quiet_kv;           /* 1 if given as --quiet VALUE */
  int n_keys;             /* --KEY VALUE pairs other than the above */
  int cont;               /* --continue: fresh, resumed or left alone */
} run_args;

/* Each call's contract is at its definition; here, a line each.  Calls
** that return an exit status print their message; "0 with err" calls
** leave it in err. */

/* ---- run.c: the job ------------------------------------------------------ */
/* C(0) of the t1 column: made and written (resume 0), or read back. */
int obs_t1_reference(obs_analysis *an, afv_sim *s, const char *dir,
                     int resume);
/* A line in log.txt and, unless quiet, on stderr. */
void run_log(run_state *R, const char *fmt, ...);
/* log.txt: the afv (version, commit) that writes what follows. */
void log_build(run_state *R, const char *what);
/* The model and dynamics of a configuration (per-cell columns borrowed). */
void cfg_model(const run_cfg *c, const afv_cells *cl, afv_params *p,
               afv_box *b, afv_dyn *d);
/* The start, unrelaxed, in R->sim; an afv status, the reason in err. */
int run_start(run_state *R, char *err, size_t errlen);
/* The append-only files and log.txt, fresh (ck NULL) or cut back to ck. */
int open_outputs(run_state *R, const afv_checkpoint *ck);
/* Integrates to cfg.steps; an exit status. */
int run_loop(run_state *R);
/* "DIR/NAME: cannot write: REASON" (errno); EXIT_BAD_INPUT. */
int write_failed(run_state *R, const char *name);
/* afv run --out DIR; an exit status. */
int run_fresh(run_state *R, const run_args *a, int argc, char **argv);

/* ---- run_config.c: the keys ---------------------------------------------- */
void cfg_defaults(run_cfg *cfg);
/* A config or params.txt into cfg, set[k] the line of key k. */
int read_config(const char *path, run_cfg *cfg, int *set, char *err,
                size_t errlen);
/* L = sqrt(N pi l^2 / phi). */
double box_side(const run_cfg *c);
/* Prefixes "path:line: " to a message that starts with a key of set. */
void locate_error(char *err, size_t errlen, const int *set,
                  const char *path);
/* Range checks (reads the cells file into cl); 0 with err. */
int cfg_validate(run_cfg *c, const int *set, afv_cells *cl, char *err,
                 size_t errlen);
/* DIR/params.txt, every key and THE RECORD, atomically. */
int write_params(const char *dir, const run_cfg *c, const char *cells);
/* params.txt's keys against THE RECORD (a key edited since); 0 with err. */
int record_agrees(const char *path, const run_cfg *c, const int *set,
                  char *err, size_t errlen);
/* DIR/cells.txt, the run's copy of its cells file. */
int write_cells_copy(const char *dir, const afv_cells *cl);
/* The first pass over the command line: 1, 0 (bad), -1 (--help). */
int scan_args(int argc, char **argv, run_args *a);
/* Defaults, --config, --KEY VALUE, checked; 0 or an exit status. */
int requested_cfg(run_cfg *cfg, afv_cells *cl, const run_args *a,
                  int argc, char **argv, int *set);
/* 0, or an exit status for a params.txt of afv 0.1.0. */
int written_after_0_1_0(const char *params);
/* 1 afv's params.txt, 0 none, -1 a user's (or not a regular file). */
int params_written_by_afv(const char *path);
/* --continue: the keys asked are DIR's run's; 0 or an exit status. */
int same_run_asked(const run_args *a, int argc, char **argv);

/* ---- run_compute.c: what a run can compute ------------------------------- */
/* 1 if everything recorded of the state is finite, else msg says what. */
int state_finite(afv_sim *s, char *msg, size_t len);
/* The state of R->sim and the run's keys computable; 0 with err. */
/* 1 if no state of n cells of model p can overflow the energy; else err
** names the key (cmd/run_compute.c). */
int energy_computable(const afv_params *p, int n, char *err, size_t errlen);
int run_computable(const run_state *R, const char *where, char *err,
                   size_t errlen);
/* The start of cfg built and checked as afv run does; 0 with err. */
int start_computable(const run_cfg *cfg, const afv_cells *cl, char *err,
                     size_t errlen);

/* ---- run_dir.c: the run directory ---------------------------------------- */
/* "DIR is in use by process PID ..." (pid <= 0: another process). */
int report_in_use(const char *dir, long pid);
/* DIR's lock: flock on DIR, fcntl on observables.csv; 1 if held. */
int lock_run_dir(run_state *R, int create);
/* A write lock on fd's file; 1 if held, else 0 with a message. */
int run_file_lock(const char *dir, int fd, const char *path);
/* An append-only file: regular, never through a link, cut, locked. */
FILE *run_file_open(run_state *R, const char *name, long long size);
/* 1 if no link, FIFO or directory is at a run file's name. */
int run_files_regular(const char *dir);
void unlock_run_dir(run_state *R);
/* A fresh run's DIR: checked, created, locked, cleared; 1 or 0. */
int make_out_dir(run_state *R);
/* Removes what a fresh run made (an unstable relaxation). */
void discard_run(run_state *R);
/* Removes the temporaries of killed writers (NAME.PID.RAND.tmp, PID gone). */
void remove_stale_temporaries(const char *dir);

/* ---- run_resume.c: --resume and --continue ------------------------------- */
int run_resume(run_state *R, const run_args *a);
int run_continue(run_state *R, run_args *a, int argc, char **argv);

#endif
