/*
** cli.h -- what the commands of the afv program share (not part of the
** library: libafv.a and afv.h know nothing of it).
**
**   main.c     the dispatcher: afv COMMAND ... -> cmd_COMMAND
**   cli.c      option parsing and messages shared by the commands
**   inspect.c  eval, check, draw, meanfield: one configuration
**   run*.c     run: the simulation job (run directory, outputs, resume;
**              cmd/run.h lists its files)
**   report.c   analyze: a run's order parameters and plots
**   sweep.c    sweep: a grid of runs and its runners (make, parallel, SLURM)
**   collect.c  collect: a sweep's table, missing jobs, fits and figures
**   paper.c    paper: the paper's figures and claims table (make paper);
**              paper_data.c its tables, claims.c its claim rules,
**              paper_compare.c two records side by side (paper.h)
**   figure.c   what collect's and paper's figures share (figure.h)
**   phase.c,   phase diagrams and the paper's fits (fits.h): afv collect's
**   fits.c     and afv paper's, not the library's
**
** Exit status of every command: 0 success, 1 a check failed (or jobs are
** missing, or the run analysed is unfinished), 2 bad input or options, 3 a
** run stopped on an unstable step.  Only these files decide
** to exit; the library returns status codes.
*/
#ifndef AFV_CLI_H
#define AFV_CLI_H

#include "afv.h"
#include "afv_tool.h"
#include "fits.h"

#define EXIT_CHECK_FAILED 1
#define EXIT_BAD_INPUT    2
#define EXIT_UNSTABLE     3
#define EXIT_CHECK_UNSURE 4   /* afv check: finite differences cannot decide */
#define EXIT_RUN_UNFINISHED 1 /* afv analyze: the run has not finished and
                              ** --partial was not given */

/* The text of a macro's value: AFV_STR(AFV_MAX_STEP_DISP) is "0.5".  Help
** texts quote the code's constants through it, so they cannot drift. */
#define AFV_STR_(x) #x
#define AFV_STR(x)  AFV_STR_(x)

/* Longest run directory or file path the commands accept. */
#define RUN_PATH_MAX 1024

/* ---- the commands (argv[0] is the command's name) ----------------------- */
int cmd_eval(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_draw(int argc, char **argv);
int cmd_analyze(int argc, char **argv);
int cmd_meanfield(int argc, char **argv);
int cmd_sweep(int argc, char **argv);
int cmd_collect(int argc, char **argv);
int cmd_paper(int argc, char **argv);

/* argv[0] of the program as started (main.c); afv sweep finds itself by it
** where /proc/self/exe is not there. */
extern const char *program_name;

/* ---- cli.c -------------------------------------------------------------- */
/* afv's version and, when built from a git checkout, its commit:
** "0.3.0 (commit 0123456789ab)", or "0.2.0". */
const char *afv_build_version(void);
/* The running command ("run", "sweep", ...; main.c sets it): every message
** starts "afv COMMAND: ". */
extern const char *command_name;
/* Prints "afv COMMAND: MSG" on stderr and returns EXIT_BAD_INPUT. */
int bad_input(const char *msg);
/* Prints "afv COMMAND: " and the formatted message, then a newline. */
void cli_errorf(const char *fmt, ...);
/* NULL if text is a whole finite normal double (or 0), stored in *out;
** else why not ("is not a number", ...), to follow "KEY: 'TEXT' ". */
const char *real_problem(const char *text, double *out);
/* NULL if text is an integer in lo .. hi, written as one (12) or as a
** real with no fractional part (1e5, 2.0); else why not. */
const char *integral_problem(const char *text, long long lo, long long hi,
                             long long *out);
/* The option of help_text ("--NAME" words) nearest to opt by edit
** distance (at most 2, and less than opt's length), or NULL. */
const char *nearest_option(const char *opt, const char *help_text);
/* "afv CMD: unknown option 'OPT' (did you mean --NEAR? see afv CMD
** --help)", NEAR the nearest option of help_text and more_text (which
** may be NULL); returns EXIT_BAD_INPUT. */
int unknown_option(const char *opt, const char *help_text,
                   const char *more_text);
/* x in the fewest digits that read back as x (20.0000001, not "20"),
** into buf; returns buf. */
const char *exact_text(double x, char *buf, size_t len);
/* Every option of afv run ("--out ... --N --phi ..."), for afv sweep. */
const char *run_option_names(void);
/* Parses a whole string as a finite double; message names the option. */
int parse_double(const char *opt, const char *text, double *out);
/* --help text of the model options shared by eval, check and draw. */
extern const char *model_help;
/* If argv[*k] is a model option, consumes it (and its value) and returns 1;
** returns 0 if it is not one, -1 on a bad value (message printed). */
int model_option(int argc, char **argv, int *k, afv_params *p, afv_box *b);
/* Range checks of the model options, with messages naming the option. */
int model_valid(const afv_params *p, const afv_box *b);
/* Loads POINTS and wraps them into a periodic box. */
int load_points(const char *path, const afv_box *b, int *n, double **r);
/* Prints the library's error st (naming cells where it can); EXIT_BAD_INPUT. */
int library_error(int st, const afv_geom *g);
/* Prints text in lines of at most 72 characters, each indented by 6. */
void print_wrapped(const char *text);
/* Option NAME with a finite double value; returns 1 if consumed. */
int double_option(int argc, char **argv, int *k, const char *name,
                  double *out, int *bad);

/* ---- run_config.c: the keys of afv run, for afv sweep ------------------ */
/* 1 if NAME is a key of afv run and TEXT a value it accepts; else 0 and
** err says why ("KEY: 'TEXT' is not ...", or "unknown key"). */
int run_key_check(const char *name, const char *text, char *err,
                  size_t errlen);
/* Applies the n KEY VALUE pairs to the defaults, checks the whole set as
** afv run does (ranges, cells file) and, if path is not NULL, writes every
** key to path in params.txt form.  1, or 0 with the reason in err. */
int run_config_write(const char *path, int n, const char *const *names,
                     const char *const *values, char *err, size_t errlen);
/* The default value text of afv run's key NAME (NULL: no such key). */
const char *run_key_default(const char *name);

/* ---- run_config.c, run_dir.c: readers of a run directory --------------- */
/* The value of key in the params.txt at path, if it is a whole finite
** number (the last one, if the key repeats): 1 if found, 0 if not, -1 if
** the file cannot be read.  Lines are read whole (afv_lines). */
int run_param(const char *path, const char *key, double *v);
/* params.txt of a run: picks l, v0 and Dr.  0 if unreadable. */
int read_run_params(const char *path, double *l, double *v0, double *Dr);
/* A run's params.txt as afv analyze reads it (run_params_read). */
typedef struct run_params_info {
  int afv_run;             /* 1: written by afv run (every key is there) */
  double l, v0, Dr, dt;    /* the model's and the dynamics' */
  long long steps;         /* -1 if a hand-written one has none */
  long long N, frame_every;
  int periodic;            /* 1: box periodic, of side L */
  double L;                /* sqrt(N pi l^2 / phi) */
  int cells;               /* 1: per-cell values from a cells file */
} run_params_info;
/* params.txt of a run read whole, as afv run reads it: l, v0, Dr, which
** it must hold, and steps (-1 if a hand-written one has none; afv's own
** must).  1, 0 if there is no file at path, -1 with the reason in err
** (afv analyze refuses it: no silent defaults). */
int run_params_read(const char *path, run_params_info *p, char *err,
                    size_t errlen);
/* The fingerprint of the run with the params.txt at path and the id id
** (its directory's name, a sweep's job id): 16 hex digits into out, of
** every key that changes what the run computes (but cells, a path), and
** the id.  1, 0 if
** there is no file at path, -1 with the reason in err. */
int run_fingerprint(const char *path, const char *id, char *out, size_t len,
                    char *err, size_t errlen);
/* Unlinks every file of directory dir whose name named() accepts; nothing
** else (cmd/run_dir.c).  A cleanup: a file it cannot remove stays. */
void remove_named(const char *dir, int (*named)(const char *name));
/* l of the run whose trajectory is at path, from params.txt beside it. */
void run_l_beside(const char *path, double *l);
/* The process id of the afv run writing in DIR (it holds the lock on
** DIR/observables.csv), or 0 if none does. */
long run_lock_holder(const char *dir);

#endif
