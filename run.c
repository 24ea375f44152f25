/*
** run.c -- afv run: the simulation job (run directory, outputs, checkpoints, resume)
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* ---- afv run: the simulation job --------------------------------------- */
/* The job (paper, Sec. Model): build the start (cluster or random), relax it
** at v0 = 0 to max |F| <= relax_tol, then integrate the active dynamics for
** `steps` steps, writing samples, frames, snapshots and checkpoints.  Every
** parameter lives in one table (run_keys), which gives the defaults, the
** config-file and command-line parsing, --help and params.txt. */

typedef struct run_cfg {
  long long N;            /* cells */
  double phi;             /* packing fraction N pi l^2 / L^2 */
  char box[16];           /* "periodic" or "open" */
  double l, KA, KP, A0, P0, Lambda, cap;       /* model (afv_params) */
  double mu, v0, Dr, dt, max_move;             /* dynamics (afv_dyn) */
  long long steps;        /* active steps in the whole run */
  unsigned long long seed;/* noise and random starts */
  char init[16];          /* "cluster", "random" or "file" */
  double spacing;         /* cluster lattice spacing, in l */
  double relax_tol;       /* relaxation force tolerance */
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

#define RK(name, kind, field, def, unit, help) \
  {name, kind, offsetof(run_cfg, field), def, unit, help}
static const run_key run_keys[] = {
  RK("N", K_INT, N, "400", "cells", "number of cells (a cells file sets it)"),
  RK("phi", K_REAL, phi, "0.5", "-", "packing fraction N pi l^2/L^2: sets "
     "the box side L (open: the side of the random start square)"),
  RK("box", K_WORD, box, "periodic", "periodic|open", "boundary: periodic "
     "L x L box (minimum image) or open space"),
  RK("l", K_REAL, l, "1", "length", "maximal cell radius l (the unit of "
     "length)"),
  RK("KA", K_REAL, KA, "1", "energy/l^4", "area modulus"),
  RK("KP", K_REAL, KP, "1", "energy/l^2", "perimeter modulus"),
  RK("A0", K_REAL, A0, "3.1415926535897931", "l^2", "preferred area (pi)"),
  RK("P0", K_REAL, P0, "4.8", "l", "preferred perimeter (main knob)"),
  RK("Lambda", K_REAL, Lambda, "0.2", "energy/l", "extra tension of the "
     "free (arc) boundary"),
  RK("cap", K_REAL, cap, "0", "l", "contact cap delta: near detachment "
     "(4l^2-d^2 < delta^2) the force uses sqrt(4l^2-d^2) >= delta, so it "
     "stays bounded but is NOT -grad E (the peers' regularisation); 0 = "
     "exact -grad E"),
  RK("mu", K_REAL, mu, "1", "l/(time force)", "mobility"),
  RK("v0", K_REAL, v0, "0.5", "l/time", "self-propulsion speed (main "
     "knob)"),
  RK("Dr", K_REAL, Dr, "0.1", "1/time", "rotational diffusion of the "
     "polarity"),
  RK("dt", K_REAL, dt, "0.01", "time", "time step (Euler-Maruyama)"),
  RK("max_move", K_REAL, max_move, "0.05", "l", "sub-step threshold: a "
     "step in which the force would move some cell farther is integrated "
     "in halves (at most 20), which tames the exact force's divergence at "
     "contact breaking; 0 = plain Euler steps"),
  RK("steps", K_INT, steps, "10000", "steps", "active steps of the whole "
     "run (main knob)"),
  RK("seed", K_SEED, seed, "1", "-", "random seed (0 .. 2^64-1): noise, "
     "random start, initial angles"),
  RK("init", K_WORD, init, "cluster", "cluster|random|file", "start: "
     "compact cluster in the middle, uniform random, or the x y of the "
     "cells file"),
  RK("spacing", K_REAL, spacing, "1.8", "l", "lattice spacing of the "
     "cluster start"),
  RK("relax_tol", K_REAL, relax_tol, "1e-6", "force", "relaxation at v0 = "
     "0 stops when max_i |F_i| <= relax_tol"),
  RK("relax_max_steps", K_INT, relax_max_steps, "100000", "steps",
     "relaxation step limit (0: no relaxation)"),
  RK("sample_every", K_INT, sample_every, "100", "steps", "observables.csv "
     "row every so many steps (0: none)"),
  RK("frame_every", K_INT, frame_every, "1000", "steps", "trajectory frame "
     "every so many steps (0: none)"),
  RK("checkpoint_every", K_INT, checkpoint_every, "10000", "steps",
     "checkpoint every so many steps (and always at the start and end)"),
  RK("svg_every", K_INT, svg_every, "5000", "steps", "SVG snapshot every "
     "so many steps (0: only final.svg)"),
  RK("xyz", K_BOOL, xyz, "0", "0|1", "also write trajectory.xyz (extended "
     "XYZ, for OVITO)"),
  RK("quiet", K_BOOL, quiet, "0", "0|1", "no progress or summary on stderr "
     "(--quiet alone means 1)"),
  RK("cells", K_PATH, cells, "none", "file", "CELLS file with per-cell "
     "columns (x y theta v0 Dr KA KP A0 P0), or none"),
};
#define N_RUN_KEYS ((int)(sizeof run_keys / sizeof run_keys[0]))

static const run_key *find_key(const char *name)
{
  int k;
  for (k = 0; k < N_RUN_KEYS; k++)
    if (strcmp(run_keys[k].name, name) == 0) return &run_keys[k];
  return NULL;
}

/* Joins a relative path to the directory of the file that named it; 0 if
** the result would not fit RUN_PATH_MAX (out is then unchanged). */
static int resolve_path(const char *value, const char *base, char *out)
{
  const char *slash = base ? strrchr(base, '/') : NULL;
  char joined[RUN_PATH_MAX];
  int m;
  if (value[0] == '/' || !slash || strcmp(value, "none") == 0)
    m = snprintf(joined, sizeof joined, "%s", value);
  else
    m = snprintf(joined, sizeof joined, "%.*s/%s", (int)(slash - base), base,
                 value);
  if (m < 0 || m >= RUN_PATH_MAX) return 0;
  memcpy(out, joined, (size_t)m + 1);
  return 1;
}

/* 1 if text is one of the '|'-separated words of choices. */
static int word_in(const char *choices, const char *text)
{
  size_t m = strlen(text);
  const char *p = choices;
  while (m > 0 && m < 16) {
    if (strncmp(p, text, m) == 0 && (p[m] == '|' || p[m] == 0)) return 1;
    if (!(p = strchr(p, '|'))) return 0;
    p++;
  }
  return 0;
}

/* Parses text as the value of key K into cfg; base is the file the value
** came from (NULL: the command line).  On failure, err says why. */
static int set_key(run_cfg *cfg, const run_key *K, const char *text,
                   const char *base, char *err, size_t errlen)
{
  char *p = (char *)cfg + K->off, *end;
  errno = 0;
  switch (K->kind) {
  case K_REAL:
    *(double *)p = strtod(text, &end);
    if (end == text || *end || errno == ERANGE || !isfinite(*(double *)p))
      break;
    return 1;
  case K_INT:
    *(long long *)p = strtoll(text, &end, 10);
    if (end == text || *end || errno == ERANGE) break;
    return 1;
  case K_SEED:
    *(unsigned long long *)p = strtoull(text, &end, 10);
    if (end == text || *end || errno == ERANGE || strchr(text, '-')) break;
    return 1;
  case K_BOOL:
    if (strcmp(text, "0") && strcmp(text, "1")) break;
    *(int *)p = text[0] == '1';
    return 1;
  case K_WORD:
    if (!word_in(K->unit, text)) break;
    snprintf(p, 16, "%s", text);
    return 1;
  case K_PATH:
    if (resolve_path(text, base, p)) return 1;
    afv_errorf(err, errlen, "%s: path longer than %d bytes", K->name,
               RUN_PATH_MAX - 1);
    return 0;
  }
  afv_errorf(err, errlen, "%s: '%s' is not %s", K->name, text,
             K->kind == K_REAL ? "a finite number"
             : K->kind == K_INT ? "an integer"
             : K->kind == K_SEED ? "an integer in 0 .. 2^64-1"
             : K->kind == K_BOOL ? "0 or 1" : "one of the choices");
  if (K->kind == K_WORD && err) {
    size_t m = strlen(err);
    afv_errorf(err + m, errlen - m, " %s", K->unit);
  }
  return 0;
}

static void cfg_defaults(run_cfg *cfg)
{
  int k;
  memset(cfg, 0, sizeof *cfg);
  for (k = 0; k < N_RUN_KEYS; k++)
    set_key(cfg, &run_keys[k], run_keys[k].def, NULL, NULL, 0);
}

/* Reads KEY VALUE lines ('#' starts a comment).  set[k] records the line
** of key k.  Returns 1, or 0 with "FILE:LINE: ..." in err. */
static int read_config(const char *path, run_cfg *cfg, int *set, char *err,
                       size_t errlen)
{
  afv_lines L;
  char msg[RUN_PATH_MAX];
  int ok = 1, got = 0;
  if (afv_lines_open(&L, path, err, errlen) != AFV_OK) return 0;
  while (ok && (got = afv_lines_next(&L, err, errlen)) > 0) {
    char *key, *val, *extra, *hash = strchr(L.line, '#');
    const run_key *K;
    if (hash) *hash = 0;
    key = strtok(L.line, " \t\r");
    if (!key) continue;
    val = strtok(NULL, " \t\r");
    extra = val ? strtok(NULL, " \t\r") : NULL;
    K = find_key(key);
    if (!K) {
      afv_errorf(err, errlen, "%s:%lld: unknown key '%.32s' (see afv run "
                 "--help)", path, L.lineno, key);
      ok = 0;
    } else if (!val || extra) {
      afv_errorf(err, errlen, "%s:%lld: %s: expected one value ('KEY "
                 "VALUE')", path, L.lineno, key);
      ok = 0;
    } else if (!set_key(cfg, K, val, path, msg, sizeof msg)) {
      afv_errorf(err, errlen, "%s:%lld: %s", path, L.lineno, msg);
      ok = 0;
    } else {
      set[K - run_keys] = L.lineno < INT_MAX ? (int)L.lineno : INT_MAX;
    }
  }
  afv_lines_close(&L);
  return ok && got == 0;
}

/* The box side of N cells at packing fraction phi: N pi l^2 = phi L^2. */
static double box_side(const run_cfg *c)
{
  return sqrt((double)c->N * 3.14159265358979323846 * c->l * c->l / c->phi);
}

static int cells_nonneg(const afv_cells *cl, int col, const char *what,
                        char *err, size_t errlen)
{
  int i;
  if (!cl->has[col]) return 1;
  for (i = 0; i < cl->n; i++)
    if (cl->col[col][i] < 0) {
      afv_errorf(err, errlen, "cells: cell %d (data line %d) has %s < 0", i,
                 i + 1, what);
      return 0;
    }
  return 1;
}

/* If the message err starts with "KEY:" and KEY came from line set[KEY] of
** the file path, prefixes "path:line: " (so the user finds the line). */
static void locate_error(char *err, size_t errlen, const int *set,
                         const char *path)
{
  char key[32], copy[2 * RUN_PATH_MAX];
  const run_key *K;
  size_t m = strcspn(err, ":");
  if (!path || m >= sizeof key) return;
  memcpy(key, err, m);
  key[m] = 0;
  K = find_key(key);
  if (!K || set[K - run_keys] <= 0) return;
  snprintf(copy, sizeof copy, "%s", err);
  afv_errorf(err, errlen, "%s:%d: %s", path, set[K - run_keys], copy);
}

/* Range checks, one message naming the key.  Reads the cells file (cl). */
static int cfg_validate(run_cfg *c, const int *set, afv_cells *cl, char *err,
                        size_t errlen)
{
#define BAD(...) do { afv_errorf(err, errlen, __VA_ARGS__); return 0; } while (0)
  if (strcmp(c->cells, "none") != 0) {
    if (afv_read_cells(c->cells, cl, err, errlen) != AFV_OK) return 0;
    if (set[find_key("N") - run_keys] && c->N != cl->n)
      BAD("N: %lld, but the cells file %s has %d cells", c->N, c->cells,
          cl->n);
    c->N = cl->n;
    if (cl->has[AFV_COL_X] && strcmp(c->init, "file") != 0) {
      if (set[find_key("init") - run_keys])
        BAD("init: '%s', but the cells file gives positions (x y): use init "
            "file, or drop those columns", c->init);
      snprintf(c->init, sizeof c->init, "file");
    }
    if (!cells_nonneg(cl, AFV_COL_DR, "Dr", err, errlen)
        || !cells_nonneg(cl, AFV_COL_KA, "KA", err, errlen)
        || !cells_nonneg(cl, AFV_COL_KP, "KP", err, errlen))
      return 0;
  }
  if (strcmp(c->init, "file") == 0 && !cl->has[AFV_COL_X])
    BAD("init: 'file' needs a cells file with x and y columns");
  if (c->N < 1) BAD("N: must be >= 1 (got %lld)", c->N);
  if (c->N > 100000000) BAD("N: at most 100000000 (got %lld)", c->N);
  if (!(c->phi > 0 && c->phi <= 1)) BAD("phi: must be in (0, 1] (got %g)",
                                        c->phi);
  if (c->l <= 0) BAD("l: must be > 0 (got %g)", c->l);
  if (c->KA < 0) BAD("KA: must be >= 0 (got %g)", c->KA);
  if (c->KP < 0) BAD("KP: must be >= 0 (got %g)", c->KP);
  if (c->cap < 0) BAD("cap: must be >= 0 (got %g)", c->cap);
  if (c->mu <= 0) BAD("mu: must be > 0 (got %g)", c->mu);
  if (c->Dr < 0) BAD("Dr: must be >= 0 (got %g)", c->Dr);
  if (c->dt <= 0) BAD("dt: must be > 0 (got %g)", c->dt);
  if (c->max_move < 0) BAD("max_move: must be >= 0 (got %g)", c->max_move);
  if (c->steps < 0) BAD("steps: must be >= 0 (got %lld)", c->steps);
  if (c->spacing <= 0) BAD("spacing: must be > 0 (got %g)", c->spacing);
  if (c->relax_tol <= 0) BAD("relax_tol: must be > 0 (got %g)", c->relax_tol);
  if (c->relax_max_steps < 0) BAD("relax_max_steps: must be >= 0");
  if (c->sample_every < 0) BAD("sample_every: must be >= 0");
  if (c->frame_every < 0) BAD("frame_every: must be >= 0");
  if (c->checkpoint_every < 0) BAD("checkpoint_every: must be >= 0");
  if (c->svg_every < 0) BAD("svg_every: must be >= 0");
  if (strcmp(c->box, "periodic") == 0 && box_side(c) < 4 * c->l)
    BAD("phi: the box side L = sqrt(N pi l^2/phi) = %g is smaller than 4l = "
        "%g (minimum image); use more cells or a smaller phi", box_side(c),
        4 * c->l);
  return 1;
#undef BAD
}

/* Writes every key as KEY VALUE (reals in %.17g: they read back exactly). */
static int write_params(const char *dir, const run_cfg *c, const char *cells)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 64];
  FILE *fp;
  int k;
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  fprintf(fp, "# afv run parameters: afv run --config THIS_FILE --out DIR "
          "repeats the run\n");
  for (k = 0; k < N_RUN_KEYS; k++) {
    const run_key *K = &run_keys[k];
    const char *p = (const char *)c + K->off;
    fprintf(fp, "%-16s ", K->name);
    switch (K->kind) {
    case K_REAL: fprintf(fp, "%.17g\n", *(const double *)p); break;
    case K_INT: fprintf(fp, "%lld\n", *(const long long *)p); break;
    case K_SEED: fprintf(fp, "%llu\n", *(const unsigned long long *)p); break;
    case K_BOOL: fprintf(fp, "%d\n", *(const int *)p); break;
    case K_WORD: fprintf(fp, "%s\n", p); break;
    case K_PATH: fprintf(fp, "%s\n", cells); break;
    }
  }
  if (strcmp(c->box, "periodic") == 0)
    fprintf(fp, "# box side L = %.17g\n", box_side(c));
  return afv_atomic_commit(fp, tmp, path);
}

static int write_cells_copy(const char *dir, const afv_cells *cl)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 64];
  FILE *fp;
  snprintf(path, sizeof path, "%s/cells.txt", dir);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  afv_write_cells(fp, cl);
  return afv_atomic_commit(fp, tmp, path);
}

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

/* Fresh run (resume = 0): C(0) from the current state, written to the
** file; resume = 1: read back.  Prints a message and returns 0 on failure. */
static int obs_t1_reference(obs_analysis *an, const afv_sim *s,
                            const char *dir, int resume)
{
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 256];
  int st;
  snprintf(path, sizeof path, "%s/t1_reference.txt", dir);
  if (resume)
    return afv_t1_reference_read(path, s->n, &an->t1, err, sizeof err)
           == AFV_OK || !bad_input(err);
  if ((st = afv_clusters_compute(&an->c, &s->geom, s->r, s->par.l, &s->box))
      == AFV_OK && (st = afv_t1_start(&an->t1, &an->c)) == AFV_OK)
    st = afv_t1_reference_write(path, &an->t1);
  if (st != AFV_OK)   /* an I/O error says the system's reason */
    fprintf(stderr, "afv run: %s: cannot write (C(0) of the t1 column): "
            "%s\n", path, st == AFV_EIO && errno ? strerror(errno)
            : afv_strerror(st));
  return st == AFV_OK;
}

/* ---- the state of a run ------------------------------------------------- */
typedef struct run_state {
  run_cfg cfg;             /* parameters in force */
  afv_cells cells;         /* per-cell columns (n = 0 if none) */
  afv_sim sim;             /* the simulation */
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
} run_state;

enum { OUT_TRAJ, OUT_OBS, OUT_XYZ };   /* order of afv_checkpoint_files */

static double wall_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void run_log(run_state *R, const char *fmt, ...)
{
  va_list ap;
  if (R->log) {
    va_start(ap, fmt);
    vfprintf(R->log, fmt, ap);
    va_end(ap);
    fflush(R->log);
  }
  if (!R->cfg.quiet) {
    fputs("afv run: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
  }
}

/* Model and dynamics parameters of the configuration, per-cell arrays
** pointing into the cells file's columns. */
static void cfg_model(const run_cfg *c, const afv_cells *cl, afv_params *p,
                      afv_box *b, afv_dyn *d)
{
  afv_params_default(p);
  p->l = c->l; p->KA = c->KA; p->KP = c->KP; p->A0 = c->A0; p->P0 = c->P0;
  p->Lambda = c->Lambda; p->cap = c->cap;
  p->KA_i = cl->col[AFV_COL_KA]; p->KP_i = cl->col[AFV_COL_KP];
  p->A0_i = cl->col[AFV_COL_A0]; p->P0_i = cl->col[AFV_COL_P0];
  b->periodic = strcmp(c->box, "periodic") == 0;
  b->Lx = b->Ly = box_side(c);
  afv_dyn_default(d);
  d->mu = c->mu; d->v0 = c->v0; d->Dr = c->Dr; d->dt = c->dt;
  d->max_move = c->max_move;
  d->seed = c->seed;
  d->v0_i = cl->col[AFV_COL_V0];
  d->Dr_i = cl->col[AFV_COL_DR];
}

/* Distance from cell 0 to its nearest neighbour (minimum image): the
** lattice spacing of a cluster start. */
static double nearest_to_first(int n, const double *r, const afv_box *b)
{
  double best = HUGE_VAL;
  int i;
  for (i = 1; i < n; i++) {
    double dx = r[2*i] - r[0], dy = r[2*i+1] - r[1];
    afv_min_image(b, &dx, &dy);
    if (hypot(dx, dy) < best) best = hypot(dx, dy);
  }
  return best;
}

/* Builds the start (positions and angles) and the simulation at it. */
static int run_start(run_state *R, char *err, size_t errlen)
{
  const run_cfg *c = &R->cfg;
  int n = (int)c->N, st = AFV_OK, i;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *th = malloc((size_t)n * sizeof(double));
  afv_params p;
  afv_box b;
  afv_dyn d;
  cfg_model(c, &R->cells, &p, &b, &d);
  if (!r || !th) st = AFV_ENOMEM;
  else if (strcmp(c->init, "cluster") == 0) {
    st = afv_init_cluster(n, c->spacing * c->l, &b, r);
    R->start_spacing = n > 1 ? nearest_to_first(n, r, &b) / c->l : 0;
  }
  else if (strcmp(c->init, "random") == 0)
    afv_init_random(n, c->seed, &b, box_side(c), r);
  else
    for (i = 0; i < n; i++) {
      r[2*i] = R->cells.col[AFV_COL_X][i];
      r[2*i+1] = R->cells.col[AFV_COL_Y][i];
    }
  if (st == AFV_OK && R->cells.has[AFV_COL_THETA])
    memcpy(th, R->cells.col[AFV_COL_THETA], (size_t)n * sizeof(double));
  else if (st == AFV_OK)
    afv_init_angles(n, c->seed, th);
  if (st == AFV_OK) st = afv_sim_init(&R->sim, n, r, th, &p, &b, &d);
  if (st == AFV_ECOINCIDENT)
    afv_errorf(err, errlen, "cells %d and %d of the start have the same "
               "centre", R->sim.geom.bad_i, R->sim.geom.bad_j);
  else if (st != AFV_OK)
    afv_errorf(err, errlen, "start: %s", afv_strerror(st));
  free(r);
  free(th);
  return st;
}

/* ---- outputs ------------------------------------------------------------ */
/* observables.csv: one header, one row per sample.  To add a column, add
** its name to the header and its value to the row, at the same place. */
static void obs_write_header(FILE *fp)
{
  fputs("step,time,energy,mean_area,mean_perimeter,mean_arc_length,"
        "mean_contacts,max_force,ngc_frac,n_clusters,omega,t1\n", fp);
}

static void obs_write_row(FILE *fp, const afv_sim *s, obs_analysis *an)
{
  const afv_geom *g = &s->geom;
  double A = 0, P = 0, L = 0, C = 0;
  int i, n = s->n;
  int ok = afv_clusters_compute(&an->c, g, s->r, s->par.l, &s->box) == AFV_OK;
  for (i = 0; i < n; i++) {
    A += g->area[i];
    P += g->perim[i];
    L += g->arc[i];
    C += g->contacts[i];
  }
  fprintf(fp, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,", s->step,
          s->t, g->energy, A / n, P / n, L / n, C / n, afv_sim_max_force(s));
  if (ok)
    fprintf(fp, "%.17g,%d,%.17g,%.17g\n", (double)an->c.giant / n,
            an->c.count, an->c.omega, afv_t1_count(&an->t1, &an->c));
  else
    fputs("nan,nan,nan,nan\n", fp);   /* out of memory: no analysis */
}

/* Extended XYZ (OVITO): wrapped positions, z = 0, polarity as a column. */
static void xyz_write_frame(FILE *fp, const afv_sim *s)
{
  int i;
  fprintf(fp, "%d\n", s->n);
  if (s->box.periodic)
    fprintf(fp, "Lattice=\"%.17g 0 0 0 %.17g 0 0 0 1\" pbc=\"T T F\" ",
            s->box.Lx, s->box.Ly);
  fprintf(fp, "Properties=species:S:1:pos:R:3:theta:R:1 Time=%.17g "
          "Step=%lld\n", s->t, s->step);
  for (i = 0; i < s->n; i++) {
    double x = s->r[2*i], y = s->r[2*i+1];
    afv_wrap(&s->box, &x, &y);
    fprintf(fp, "C %.17g %.17g 0 %.17g\n", x, y, s->theta[i]);
  }
}

/* An SVG of the current state, written atomically to DIR/name. */
static int write_svg(run_state *R, const char *name)
{
  char path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 96];
  afv_sim *s = &R->sim;
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  if (afv_svg_write(fp, &s->geom, s->n, s->r, s->theta, &s->par, &s->box)
      != AFV_OK) {
    fclose(fp);
    remove(tmp);
    return AFV_EIO;
  }
  return afv_atomic_commit(fp, tmp, path);
}

/* Flushes the append-only files and records their sizes with the state. */
static int write_checkpoint(run_state *R)
{
  char path[RUN_PATH_MAX + 32];
  afv_checkpoint c;
  int k;
  memset(&c, 0, sizeof c);
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k]) {
      if (fflush(R->out[k]) != 0) return AFV_EIO;
      c.bytes[k] = (long long)ftell(R->out[k]);
    }
  c.n = R->sim.n;
  c.step = R->sim.step;
  c.t = R->sim.t;
  c.seed = R->sim.dyn.seed;
  c.r = R->sim.r;
  c.theta = R->sim.theta;
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  R->ckpt_step = R->sim.step;
  return afv_checkpoint_write(path, &c);
}

static int due(long long step, long long every)
{
  return every > 0 && step % every == 0;
}

/* Everything that is written at the current step (also at step 0). */
static int run_outputs(run_state *R)
{
  const run_cfg *c = &R->cfg;
  afv_sim *s = &R->sim;
  char name[64];
  if (due(s->step, c->sample_every)) obs_write_row(R->out[OUT_OBS], s, &R->an);
  if (due(s->step, c->frame_every)) {
    afv_traj_write_frame(R->out[OUT_TRAJ], s->step, s->t, s->n, s->r,
                         s->theta);
    if (R->out[OUT_XYZ]) xyz_write_frame(R->out[OUT_XYZ], s);
  }
  if (due(s->step, c->svg_every)) {
    snprintf(name, sizeof name, "snap_%09lld.svg", s->step);
    if (write_svg(R, name) != AFV_OK) return AFV_EIO;
  }
  if (due(s->step, c->checkpoint_every)) return write_checkpoint(R);
  return AFV_OK;
}

/* 1 if the file at path exists and holds at least `bytes` bytes (cutting
** back a shorter one would pad it with zeros). */
static int file_at_least(const char *path, long long bytes)
{
  struct stat st;
  return stat(path, &st) == 0 && (long long)st.st_size >= bytes;
}

/* Opens the append-only files: fresh (with headers) or cut back to the
** sizes of the checkpoint and appended to. */
static int open_outputs(run_state *R, const afv_checkpoint *ck, char *err,
                        size_t errlen)
{
  char path[RUN_PATH_MAX + 32];
  int k;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    if (k == OUT_XYZ && !R->cfg.xyz) continue;
    snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
    if (ck && !file_at_least(path, ck->bytes[k])) {
      afv_errorf(err, errlen, "%s: shorter than the checkpoint records (%lld "
                 "bytes): not the file this checkpoint was written with",
                 path, (long long)ck->bytes[k]);
      return 0;
    }
    if (ck && truncate(path, (off_t)ck->bytes[k]) != 0) {
      afv_errorf(err, errlen, "%s: cannot cut back to the checkpoint: %s",
                 path, strerror(errno));
      return 0;
    }
    if (!(R->out[k] = fopen(path, ck ? "a" : "w"))) {
      afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
      return 0;
    }
  }
  if (!ck) {
    afv_traj_write_header(R->out[OUT_TRAJ], R->sim.n, &R->sim.box);
    obs_write_header(R->out[OUT_OBS]);
  }
  snprintf(path, sizeof path, "%s/log.txt", R->dir);
  R->log = fopen(path, "a");
  return 1;
}

static void close_outputs(run_state *R)
{
  int k;
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k]) fclose(R->out[k]);
  if (R->log) fclose(R->log);
  memset(R->out, 0, sizeof R->out);
  R->log = NULL;
}

static void show_progress(run_state *R, int final)
{
  double now = wall_seconds(), done, rate, left;
  if (!R->progress || (!final && now - R->last_progress < 0.5)) return;
  R->last_progress = now;
  done = (double)(R->sim.step - R->start_step);
  rate = done / (now - R->wall0 > 1e-9 ? now - R->wall0 : 1e-9);
  left = rate > 0 ? (double)(R->cfg.steps - R->sim.step) / rate : 0;
  fprintf(stderr, "\rstep %lld/%lld  t %.6g  %.0f steps/s  %.0f s left   %s",
          R->sim.step, R->cfg.steps, R->sim.t, rate, left, final ? "\n" : "");
  fflush(stderr);
}

/* ---- the run ------------------------------------------------------------ */
static void monitor_relax(void *ctx, long iter, double E, double fmax)
{
  run_state *R = ctx;
  double now;
  if (!R->progress || (now = wall_seconds()) - R->last_progress < 0.5) return;
  R->last_progress = now;
  fprintf(stderr, "\rrelaxing: step %ld  E %.10g  max|F| %.3e   ", iter, E,
          fmax);
  fflush(stderr);
}

static int relax_start(run_state *R)
{
  afv_relax_report rep;
  int st;
  if (R->cfg.relax_max_steps == 0) {
    run_log(R, "relaxation skipped (relax_max_steps 0); max |F| %.6e\n",
            afv_sim_max_force(&R->sim));
    return AFV_OK;
  }
  R->last_progress = wall_seconds();
  st = afv_relax(&R->sim, R->cfg.relax_tol, (long)R->cfg.relax_max_steps,
                 &rep, monitor_relax, R);
  if (R->progress) fprintf(stderr, "\r%70s\r", "");
  if (st != AFV_OK) return st;
  run_log(R, "relaxation at v0 = 0: %ld steps (%ld undone), energy %.10g -> "
          "%.10g, max |F| %.6e (tolerance %g)%s\n", rep.iterations,
          rep.rejected, rep.energy0, rep.energy, rep.max_force,
          R->cfg.relax_tol, rep.converged ? ""
          : rep.stalled ? "; stopped: the energy no longer decreases (a "
            "minimum on a kink of E, e.g. a triple junction on a cell's "
            "circle, as above P0* ~ 5.7)" : "; NOT REACHED");
  return AFV_OK;
}

/* Integrates to cfg.steps.  Returns an exit status. */
static int run_loop(run_state *R)
{
  afv_sim *s = &R->sim;
  int st = AFV_OK;
  R->start_step = s->step;
  R->wall0 = R->last_progress = wall_seconds();
  while (s->step < R->cfg.steps) {
    if ((st = afv_sim_step(s)) != AFV_OK) break;
    if ((st = run_outputs(R)) != AFV_OK) break;
    show_progress(R, 0);
  }
  if (st == AFV_EUNSTABLE) {
    int i = s->bad_cell;
    fprintf(stderr, "%safv run: step %lld (t = %g): cell %d would move %g l "
            "(> %g l)%s: the time step dt = %g is too large%s; last good "
            "checkpoint: %s/checkpoint.txt (step %lld)\n",
            R->progress ? "\n" : "", s->step + 1, s->t, i, s->bad_disp,
            AFV_MAX_STEP_DISP,
            isfinite(s->bad_disp) ? "" : " (its force is not finite)",
            s->dyn.dt, R->cfg.max_move > 0 ? "" : " (or two cells are "
            "losing contact, where the exact force diverges: try max_move "
            "0.05 or cap 0.1)",
            R->dir, R->ckpt_step);
    if (R->log) fprintf(R->log, "stopped: unstable step %lld, cell %d\n",
                        s->step + 1, i);
    return EXIT_UNSTABLE;
  }
  if (st == AFV_ECOINCIDENT || st == AFV_ENONFINITE) {   /* after a step */
    fprintf(stderr, "afv run: step %lld: %s (cells %d and %d): the time "
            "step dt = %g is probably too large; last good checkpoint: "
            "%s/checkpoint.txt (step %lld)\n", s->step, afv_strerror(st),
            s->geom.bad_i, s->geom.bad_j, s->dyn.dt, R->dir, R->ckpt_step);
    return EXIT_UNSTABLE;
  }
  if (st != AFV_OK) {
    fprintf(stderr, "afv run: step %lld: %s\n", s->step, afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if (R->ckpt_step != s->step && write_checkpoint(R) != AFV_OK) {
    fprintf(stderr, "afv run: %s/checkpoint.txt: cannot write\n", R->dir);
    return EXIT_BAD_INPUT;
  }
  if (write_svg(R, "final.svg") != AFV_OK) {
    fprintf(stderr, "afv run: %s/final.svg: cannot write\n", R->dir);
    return EXIT_BAD_INPUT;
  }
  show_progress(R, 1);
  {
    double w = wall_seconds() - R->wall0;
    long long k = s->step - R->start_step;
    run_log(R, "%d cells, steps %lld..%lld (t = %.6g) in %.3g s (%.0f "
            "steps/s, %lld extra sub-steps); outputs in %s/: "
            "observables.csv, trajectory.dat, snapshots snap_*.svg and "
            "final.svg\n", s->n, R->start_step, s->step, s->t, w,
            w > 0 ? (double)k / w : 0.0, s->substeps, R->dir);
  }
  return 0;
}

static const char *run_usage =
  "usage: afv run [--config FILE] [--KEY VALUE ...] --out DIR\n"
  "       afv run --resume DIR [--steps MORE] [--quiet]\n"
  "\n"
  "Simulates the active finite Voronoi model (paper protocol): a compact\n"
  "cluster (or random start) relaxed at v0 = 0 until max |F| <= relax_tol,\n"
  "then dr/dt = mu F + v0 n, dth = sqrt(2 Dr dt) xi (Euler-Maruyama).\n"
  "FILE holds 'KEY VALUE' lines ('#' comments); --KEY VALUE overrides it.\n"
  "Relative paths in FILE are relative to FILE's directory.  DIR gets\n"
  "params.txt (every key; --config DIR/params.txt repeats the run),\n"
  "observables.csv, trajectory.dat, checkpoint.txt, snap_*.svg, final.svg,\n"
  "log.txt, t1_reference.txt (C(0) for the t1 column) (and cells.txt,\n"
  "trajectory.xyz).  --resume continues from the\n"
  "last checkpoint, to the run's steps or MORE steps past the checkpoint.\n"
  "Exit status: 0 done, 2 bad input, 3 unstable step (dt too large).\n"
  "\n"
  "keys (default, unit, meaning):\n";

static void run_help(void)
{
  int k;
  fputs(run_usage, stdout);
  for (k = 0; k < N_RUN_KEYS; k++) {
    printf("  %-16s %-18s [%s]\n", run_keys[k].name, run_keys[k].def,
           run_keys[k].unit);
    print_wrapped(run_keys[k].help);
  }
}

/* Command-line arguments of afv run. */
typedef struct run_args {
  const char *out, *resume, *config;
  const char *steps;      /* --steps with --resume */
  int quiet;              /* 0: not given; 1: --quiet or --quiet 1; -1: --quiet 0 */
  int quiet_kv;           /* 1 if given as --quiet VALUE */
  int n_keys;             /* --KEY VALUE pairs other than the above */
} run_args;

/* First pass: --help, --config, --out, --resume, --quiet; checks that
** every other option is --KEY VALUE with a known KEY. */
static int scan_args(int argc, char **argv, run_args *a)
{
  int k;
  memset(a, 0, sizeof *a);
  for (k = 1; k < argc; k++) {
    const char *o = argv[k];
    if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
      run_help();
      return -1;
    }
    if (strcmp(o, "--quiet") == 0
        && (k + 1 >= argc || strncmp(argv[k + 1], "--", 2) == 0)) {
      a->quiet = 1;
      continue;
    }
    if (strncmp(o, "--", 2) != 0
        || (!find_key(o + 2) && strcmp(o, "--out") && strcmp(o, "--resume")
            && strcmp(o, "--config"))) {
      fprintf(stderr, "afv run: unknown option '%s' (see afv run --help)\n",
              o);
      return 0;
    }
    if (k + 1 >= argc || strncmp(argv[k + 1], "--", 2) == 0) {
      fprintf(stderr, "afv run: %s needs a value\n", o);
      return 0;
    }
    k++;
    if (strcmp(o, "--out") == 0) a->out = argv[k];
    else if (strcmp(o, "--resume") == 0) a->resume = argv[k];
    else if (strcmp(o, "--config") == 0) a->config = argv[k];
    else if (strcmp(o, "--steps") == 0) {
      a->steps = argv[k];
      a->n_keys++;
    }
    else if (strcmp(o, "--quiet") == 0) {
      a->quiet = strcmp(argv[k], "1") == 0 ? 1 : -1;
      a->quiet_kv = 1;
      a->n_keys++;
    }
    else a->n_keys++;
  }
  return 1;
}

/* Second pass: the --KEY VALUE overrides, in order. */
static int apply_args(int argc, char **argv, run_cfg *cfg, int *set)
{
  char err[RUN_PATH_MAX];
  int k;
  for (k = 1; k < argc; k++) {
    const run_key *K;
    if (strcmp(argv[k], "--quiet") == 0
        && (k + 1 >= argc || strncmp(argv[k + 1], "--", 2) == 0)) {
      cfg->quiet = 1;
      continue;
    }
    if (!strcmp(argv[k], "--out") || !strcmp(argv[k], "--resume")
        || !strcmp(argv[k], "--config")) {
      k++;
      continue;
    }
    K = find_key(argv[k] + 2);
    if (!set_key(cfg, K, argv[k + 1], NULL, err, sizeof err))
      return !bad_input(err);
    set[K - run_keys] = -1;
    k++;
  }
  return 1;
}

/* Creates DIR (it may exist, but must not hold a run). */
static int make_out_dir(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  struct stat sb;
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (stat(path, &sb) == 0) {
    fprintf(stderr, "afv run: %s already holds a run (params.txt): continue "
            "it with --resume %s, or choose another --out\n", dir, dir);
    return 0;
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv run: cannot create %s: %s\n", dir, strerror(errno));
    return 0;
  }
  return 1;
}

static int run_fresh(run_state *R, const run_args *a, int argc, char **argv)
{
  char err[2 * RUN_PATH_MAX] = "";
  int set[N_RUN_KEYS], st;
  memset(set, 0, sizeof set);
  if (strlen(a->out) > RUN_PATH_MAX - 64) return bad_input("--out: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->out);
  if (a->config && !read_config(a->config, &R->cfg, set, err, sizeof err))
    return bad_input(err);
  if (!apply_args(argc, argv, &R->cfg, set)) return EXIT_BAD_INPUT;
  if (!cfg_validate(&R->cfg, set, &R->cells, err, sizeof err)) {
    locate_error(err, sizeof err, set, a->config);
    return bad_input(err);
  }
  if (run_start(R, err, sizeof err) != AFV_OK) return bad_input(err);
  /* everything is checked: only now is anything created */
  if (!make_out_dir(R->dir)) return EXIT_BAD_INPUT;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  if ((R->cells.n && write_cells_copy(R->dir, &R->cells) != AFV_OK)
      || write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
         != AFV_OK
      || !open_outputs(R, NULL, err, sizeof err)) {
    fprintf(stderr, "afv run: %s: cannot write the outputs%s%s\n", R->dir,
            err[0] ? ": " : "", err);
    return EXIT_BAD_INPUT;
  }
  if (R->start_spacing > 0
      && R->start_spacing < R->cfg.spacing * (1 - 1e-9))
    run_log(R, "cluster start: spacing %.6g l instead of %.6g l, so that "
            "the cluster fits the box\n", R->start_spacing, R->cfg.spacing);
  if ((st = relax_start(R)) != AFV_OK) {
    fprintf(stderr, "afv run: relaxation: %s\n", afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if (!obs_t1_reference(&R->an, &R->sim, R->dir, 0)) return EXIT_BAD_INPUT;
  if (run_outputs(R) != AFV_OK
      || (!due(0, R->cfg.checkpoint_every) && write_checkpoint(R) != AFV_OK)) {
    fprintf(stderr, "afv run: %s: cannot write the outputs\n", R->dir);
    return EXIT_BAD_INPUT;
  }
  return run_loop(R);
}

static int run_resume(run_state *R, const run_args *a)
{
  char err[2 * RUN_PATH_MAX], path[RUN_PATH_MAX + 32];
  int set[N_RUN_KEYS];
  afv_checkpoint ck;
  long long more = -1;
  memset(set, 0, sizeof set);
  if (a->n_keys > (a->steps != NULL) + a->quiet_kv || a->config || a->out)
    return bad_input("run: with --resume only --steps MORE and --quiet are "
                     "allowed (the parameters are DIR/params.txt)");
  if (a->steps) {
    char *end;
    errno = 0;
    more = strtoll(a->steps, &end, 10);
    if (end == a->steps || *end || errno || more < 0)
      return bad_input("steps: MORE must be an integer >= 0");
  }
  if (strlen(a->resume) > RUN_PATH_MAX - 64)
    return bad_input("--resume: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->resume);
  snprintf(path, sizeof path, "%s/params.txt", R->dir);
  if (!read_config(path, &R->cfg, set, err, sizeof err)) return bad_input(err);
  if (a->quiet) R->cfg.quiet = a->quiet > 0;
  if (!cfg_validate(&R->cfg, set, &R->cells, err, sizeof err)) {
    locate_error(err, sizeof err, set, path);
    return bad_input(err);
  }
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (access(path, F_OK) != 0) {
    fprintf(stderr, "afv run: %s has no checkpoint.txt: the run stopped "
            "before its first checkpoint (during the relaxation); remove "
            "the directory and start again\n", R->dir);
    return EXIT_BAD_INPUT;
  }
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK)
    return bad_input(err);
  if (ck.n != R->cfg.N || ck.seed != R->cfg.seed) {
    afv_checkpoint_free(&ck);
    return bad_input("resume: checkpoint.txt does not match params.txt "
                     "(cells or seed)");
  }
  if (more >= 0 && R->cfg.steps != ck.step + more) {
    R->cfg.steps = ck.step + more;
    if (write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
        != AFV_OK) {
      afv_checkpoint_free(&ck);
      return bad_input("resume: cannot rewrite params.txt");
    }
  }
  {
    afv_params p;
    afv_box b;
    afv_dyn d;
    int st;
    cfg_model(&R->cfg, &R->cells, &p, &b, &d);
    st = afv_sim_init(&R->sim, ck.n, ck.r, ck.theta, &p, &b, &d);
    R->sim.step = ck.step;
    R->sim.t = ck.t;
    R->ckpt_step = ck.step;
    if (st != AFV_OK || !open_outputs(R, &ck, err, sizeof err)) {
      afv_checkpoint_free(&ck);
      return bad_input(st != AFV_OK ? afv_strerror(st) : err);
    }
  }
  afv_checkpoint_free(&ck);
  if (!obs_t1_reference(&R->an, &R->sim, R->dir, 1)) return EXIT_BAD_INPUT;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  run_log(R, "resuming at step %lld (t = %.6g), to step %lld\n", R->sim.step,
          R->sim.t, R->cfg.steps);
  return run_loop(R);
}

int cmd_run(int argc, char **argv)
{
  run_state R;
  run_args a;
  int m = scan_args(argc, argv, &a), status;
  if (m < 0) return 0;
  if (m == 0) return EXIT_BAD_INPUT;
  if (!a.out == !a.resume)
    return bad_input("run: give either --out DIR (a new run) or --resume "
                     "DIR (see afv run --help)");
  memset(&R, 0, sizeof R);
  cfg_defaults(&R.cfg);
  status = a.resume ? run_resume(&R, &a) : run_fresh(&R, &a, argc, argv);
  close_outputs(&R);
  afv_sim_free(&R.sim);
  afv_cells_free(&R.cells);
  afv_clusters_free(&R.an.c);
  afv_t1_free(&R.an.t1);
  return status;
}


int run_param(const char *path, const char *key, double *v)
{
  afv_lines L;
  int found = 0;
  if (afv_lines_open(&L, path, NULL, 0) != AFV_OK) return -1;
  while (afv_lines_next(&L, NULL, 0) > 0) {
    char *k = strtok(L.line, " \t\r"), *val = strtok(NULL, " \t\r"), *end;
    double x;
    if (!k || !val || k[0] == '#' || strcmp(k, key) != 0) continue;
    x = strtod(val, &end);
    if (end != val && *end == 0 && isfinite(x)) {
      *v = x;
      found = 1;
    }
  }
  afv_lines_close(&L);
  return found;
}

/* params.txt of a run: picks l, v0 and Dr (a tolerant reader: the run
** owns the format).  0 if unreadable. */
int read_run_params(const char *path, double *l, double *v0,
                           double *Dr)
{
  if (run_param(path, "l", l) < 0) return 0;
  run_param(path, "v0", v0);
  run_param(path, "Dr", Dr);
  return 1;
}

/* l of the run whose trajectory is at path: from params.txt in the same
** directory, if there is one (else *l is left as it is). */
void run_l_beside(const char *path, double *l)
{
  char dir[RUN_PATH_MAX + 32];
  const char *slash = strrchr(path, '/');
  double v0 = 0, Dr = 0;
  size_t len = slash ? (size_t)(slash - path) : 0;
  if (len > RUN_PATH_MAX) return;
  if (slash) snprintf(dir, sizeof dir, "%.*s/params.txt", (int)len, path);
  else snprintf(dir, sizeof dir, "params.txt");
  read_run_params(dir, l, &v0, &Dr);
}
