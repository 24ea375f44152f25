/*
** run.c -- afv run: the simulation job (run directory, outputs, checkpoints, resume)
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"
/* afv.h alone: the job builds its start by afv_protocol_start and reads
** its afv_sim (opaque) through the accessors. */
#include "afv.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <fcntl.h>
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

#define RK(name, kind, field, def, unit, help) \
  {name, kind, offsetof(run_cfg, field), def, unit, help}
static const run_key run_keys[] = {
  RK("N", K_INT, N, "400", "cells", "number of cells (a cells file sets it); must be in 1 .. "
     "100000000"),
  RK("phi", K_REAL, phi, "0.5", "-", "packing fraction N pi l^2/L^2: sets "
     "the box side L (open: the side of the random start square); must be "
     "in (0, 1], and a periodic L must be >= 4 l"),
  RK("box", K_WORD, box, "periodic", "periodic|open", "boundary: periodic "
     "L x L box (minimum image) or open space"),
  RK("l", K_REAL, l, "1", "length", "maximal cell radius l (the unit of "
     "length); must be > 0"),
  RK("KA", K_REAL, KA, "1", "energy/l^4", "area modulus; must be >= 0"),
  RK("KP", K_REAL, KP, "1", "energy/l^2", "perimeter modulus; must be >= 0"),
  RK("A0", K_REAL, A0, "3.1415926535897931", "l^2", "preferred area (the "
     "default is pi, a disk of radius 1; it does not follow l); must be > 0 "
     "(where KA > 0; any number where KA = 0)"),
  RK("P0", K_REAL, P0, "4.8", "l", "preferred perimeter (main knob); "
     "must be > 0 (where KP > 0; any number where KP = 0)"),
  RK("Lambda", K_REAL, Lambda, "0.2", "energy/l", "extra tension of the "
     "free (arc) boundary; any finite number"),
  RK("cap", K_REAL, cap, "0", "l", "contact cap delta, defined as PyAFV's "
     "contact truncation: near detachment (4l^2-d^2 < delta^2) the "
     "arc-end velocities use sqrt(4l^2-d^2) >= delta in every term, so the "
     "force stays bounded but is NOT -grad E (the energy is unchanged; "
     "PyAFV's default is 0.45); 0 = exact -grad E; must be >= 0"),
  RK("mu", K_REAL, mu, "1", "l/(time force)", "mobility; must be > 0"),
  RK("v0", K_REAL, v0, "0.5", "l/time", "self-propulsion speed (main "
     "knob); any finite number (a run whose |v0| dt exceeds the box side L "
     "is refused)"),
  RK("Dr", K_REAL, Dr, "0.1", "1/time", "rotational diffusion of the "
     "polarity; must be >= 0"),
  RK("dt", K_REAL, dt, "0.01", "time", "time step (Euler-Maruyama); must be "
     "> 0"),
  RK("integrator", K_WORD, integrator, "euler", "euler", "how Eq. (4) "
     "is integrated, in the run and in its relaxation: euler = the paper's "
     "Euler step, every cell moves dt (mu F + v0 n) with the exact force "
     "however far (only a force or position that is not finite stops the "
     "run; steps that move a cell more than " AFV_STR(AFV_MAX_STEP_DISP)
     " l are counted in log.txt): near a breaking contact the force "
     "diverges and a finite step carries the pair over the barrier, so "
     "results depend on dt (doc/reproduction/convergence.md); integrator "
     "substeps and its max_move were removed in afv 0.3.0 (a run that "
     "uses them is finished with afv 0.2.0)"),
  RK("steps", K_INT, steps, "10000", "steps", "active steps of the whole "
     "run (main knob); must be >= 0"),
  RK("seed", K_SEED, seed, "1", "-", "random seed: noise, random start, "
     "initial angles; must be in 0 .. 18446744073709551615 (2^64-1)"),
  RK("init", K_WORD, init, "cluster", "cluster|lattice|random|file",
     "start: cluster = the authors' protocol, the N centres uniform at "
     "random (from seed) in a square of side 0.3 L centred in the box, "
     "then relaxed: a disordered tissue, as the paper's results are about; "
     "lattice = the N sites of a triangular lattice (spacing) nearest to "
     "the centre, which relaxes to a crystal that may never rearrange "
     "(for tests and comparisons); random = uniform over the whole box; "
     "file = the x y of the cells file"),
  RK("spacing", K_REAL, spacing, "1.8", "l", "lattice spacing of the "
     "lattice start; must be > 0"),
  RK("relax_tol", K_REAL, relax_tol, "1e-6", "force", "relaxation at v0 = "
     "0 (overdamped steps of dt) stops when max_i |F_i| <= relax_tol, or "
     "at a kink of E (every cell's mean force over 1000 steps <= 1e-3, "
     "mean energy change <= 1e-4 of sum |e_i|, max |F| <= 5); must be > 0"),
  RK("relax", K_WORD, relax, "flow", "flow|fire", "relaxation of the start: flow = the paper's overdamped steps at v0 = 0; fire = the FIRE 2.0 minimiser, to a true minimum of E, faster (not the paper's protocol)"),
  RK("relax_max_steps", K_INT, relax_max_steps, "100000", "steps",
     "relaxation step limit (0: no relaxation; reaching it is reported, "
     "and the run goes on); must be >= 0"),
  RK("sample_every", K_INT, sample_every, "100", "steps", "observables.csv "
     "row every so many steps (0: none); must be >= 0"),
  RK("frame_every", K_INT, frame_every, "1000", "steps", "trajectory frame "
     "every so many steps (0: none); must be >= 0"),
  RK("checkpoint_every", K_INT, checkpoint_every, "10000", "steps",
     "checkpoint every so many steps (and always at the start and end); "
     "must be >= 0"),
  RK("svg_every", K_INT, svg_every, "5000", "steps", "SVG snapshot every "
     "so many steps (0: only final.svg); must be >= 0"),
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

/* REMOVED KEYS.  integrator substeps and its key max_move (afv 0.1.0 and
** 0.2.0) were removed in afv 0.3.0 (doc/design.md, "Integrators"): a
** config, a --KEY or a params.txt that names them is refused with what to
** do, not as an unknown key or value.  1 (and the message in err) if KEY
** VALUE is one of them; value may be NULL. */
static int removed_key(const char *key, const char *value, char *err,
                       size_t errlen)
{
  if (strcmp(key, "max_move") == 0)
    afv_errorf(err, errlen, "max_move: the sub-step length of integrator "
               "substeps, removed in afv 0.3.0: a run that uses it must be "
               "finished with afv 0.2.0 (a run of integrator euler: drop "
               "the key)");
  else if (strcmp(key, "integrator") == 0 && value
           && strcmp(value, "substeps") == 0)
    afv_errorf(err, errlen, "integrator: substeps was removed in afv "
               "0.3.0 (euler is the one integrator): a run that uses it "
               "must be finished with afv 0.2.0");
  else
    return 0;
  return 1;
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
  const char *why = NULL;
  double x;
  errno = 0;
  switch (K->kind) {
  case K_REAL:
    if ((why = real_problem(text, (double *)p)) != NULL) break;
    return 1;
  case K_INT:
    if ((why = integral_problem(text, LLONG_MIN, LLONG_MAX,
                                (long long *)p)) != NULL) break;
    return 1;
  case K_SEED:   /* digits (the whole 0 .. 2^64-1), or an integral real */
    *(unsigned long long *)p = strtoull(text, &end, 10);
    if (end != text && !*end && errno != ERANGE && !strchr(text, '-'))
      return 1;
    if (!real_problem(text, &x) && x == floor(x) && x >= 0
        && x < 18446744073709551616.0) {
      *(unsigned long long *)p = (unsigned long long)x;
      return 1;
    }
    break;
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
  if (why) {
    afv_errorf(err, errlen, "%s: '%s' %s", K->name, text, why);
    return 0;
  }
  afv_errorf(err, errlen, "%s: '%s' is not %s", K->name, text,
             K->kind == K_SEED ? "an integer in 0 .. 2^64-1"
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
    if (removed_key(key, val, msg, sizeof msg)) {
      afv_errorf(err, errlen, "%s:%lld: %s", path, L.lineno, msg);
      ok = 0;
    } else if (!K) {
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

/* The value of key (column col of the cells file, if it has one, else
** the run's) for cell i, and its label for a message. */
static double cell_value(const afv_cells *cl, int col, double run_value,
                         int i, const char *key, char *label, size_t len)
{
  if (cl->has[col]) {
    snprintf(label, len, "%s (cells file, cell %d)", key, i);
    return cl->col[col][i];
  }
  snprintf(label, len, "%s", key);
  return run_value;
}

/* The targets the relaxation pulls to must be reachable: a cell's area
** and perimeter are positive, so A0 <= 0 (with KA > 0) or P0 <= 0 (with
** KP > 0) drives every cell to shrink without end, and the relaxation
** crawls through ever more crowded, ever slower steps for its whole
** relax_max_steps (afv run --N 50 --P0 0 sat silent for minutes). */
static int targets_positive(const run_cfg *c, const afv_cells *cl,
                            char *err, size_t errlen)
{
  static const struct { const char *target, *modulus; int tcol, mcol; }
    pairs[2] = {{"A0", "KA", AFV_COL_A0, AFV_COL_KA},
                {"P0", "KP", AFV_COL_P0, AFV_COL_KP}};
  int n = cl->n > 0 ? cl->n : 1, i, k;
  for (k = 0; k < 2; k++)
    for (i = 0; i < n; i++) {
      char tl[64], ml[64];
      double t = cell_value(cl, pairs[k].tcol, k ? c->P0 : c->A0, i,
                            pairs[k].target, tl, sizeof tl);
      double m = cell_value(cl, pairs[k].mcol, k ? c->KP : c->KA, i,
                            pairs[k].modulus, ml, sizeof ml);
      if (m > 0 && !(t > 0)) {
        afv_errorf(err, errlen, "%s: must be > 0 where %s > 0 (got %g): a "
                   "cell's %s is positive, and a target of %g would shrink "
                   "every cell without end", tl, ml, t, k ? "perimeter"
                   : "area", t);
        return 0;
      }
    }
  return 1;
}

/* Every active step moves a cell by v0 dt of self-propulsion alone: a
** self-propulsion that carries a cell across the whole box (side L) in
** one step makes the step meaningless, and is refused before anything is
** made. */
static int steps_meaningful(const run_cfg *c, const int *set,
                            const afv_cells *cl, char *err, size_t errlen)
{
  int n = cl->n > 0 ? cl->n : 1, i;
  int dt_named = set[find_key("dt") - run_keys] && !cl->has[AFV_COL_V0]
                 && !set[find_key("v0") - run_keys];
  double limit = box_side(c);
  if (c->steps == 0) return 1;   /* a run of no step moves nothing */
  for (i = 0; i < n; i++) {
    char label[64];
    double v0 = cell_value(cl, AFV_COL_V0, c->v0, i, "v0", label,
                           sizeof label);
    if (!(fabs(v0) * c->dt > limit)) continue;
    if (dt_named)   /* the key the user gave */
      afv_errorf(err, errlen, "dt: %g: a step's self-propulsion |v0| dt = "
                 "%g l (v0 = %g) exceeds %g l, the box side L: lower dt",
                 c->dt, fabs(v0) * c->dt / c->l, v0, limit / c->l);
    else
      afv_errorf(err, errlen, "%s: %g: a step's self-propulsion |v0| dt = "
                 "%g l (dt = %g) exceeds %g l, the box side L: lower v0 or "
                 "dt", label, v0, fabs(v0) * c->dt / c->l, c->dt,
                 limit / c->l);
    return 0;
  }
  return 1;
}

/* Range checks, one message naming the key.  Reads the cells file (cl). */
static int cfg_validate(run_cfg *c, const int *set, afv_cells *cl, char *err,
                        size_t errlen)
{
#define BAD(...) do { afv_errorf(err, errlen, __VA_ARGS__); return 0; } while (0)
  if (strcmp(c->cells, "none") != 0) {
    if (afv_cells_read(c->cells, cl, err, errlen) != AFV_OK) return 0;
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
  if (!(c->phi > 0 && c->phi <= 1))   /* %.17g: 1 + 2^-52 is not "1" */
    BAD("phi: must be in (0, 1] (got %.17g)", c->phi);
  if (c->l <= 0) BAD("l: must be > 0 (got %g)", c->l);
  if (c->KA < 0) BAD("KA: must be >= 0 (got %g)", c->KA);
  if (c->KP < 0) BAD("KP: must be >= 0 (got %g)", c->KP);
  if (c->cap < 0) BAD("cap: must be >= 0 (got %g)", c->cap);
  if (c->mu <= 0) BAD("mu: must be > 0 (got %g)", c->mu);
  if (c->Dr < 0) BAD("Dr: must be >= 0 (got %g)", c->Dr);
  if (c->dt <= 0) BAD("dt: must be > 0 (got %g)", c->dt);
  if (c->steps < 0) BAD("steps: must be >= 0 (got %lld)", c->steps);
  if (c->spacing <= 0) BAD("spacing: must be > 0 (got %g)", c->spacing);
  if (c->relax_tol <= 0) BAD("relax_tol: must be > 0 (got %g)", c->relax_tol);
  if (c->relax_max_steps < 0) BAD("relax_max_steps: must be >= 0");
  if (c->sample_every < 0) BAD("sample_every: must be >= 0");
  if (c->frame_every < 0) BAD("frame_every: must be >= 0");
  if (c->checkpoint_every < 0) BAD("checkpoint_every: must be >= 0");
  if (c->svg_every < 0) BAD("svg_every: must be >= 0");
  if (!(c->l * c->l >= DBL_MIN && isfinite(c->l * c->l)))
    BAD("l: %g: l^2 = %g %s the range of doubles; the geometry computes "
        "with l^2 (areas)", c->l, c->l * c->l, c->l < 1 ? "underflows" :
        "overflows");
  if (!isfinite(box_side(c)))
    BAD("phi: %g: the box side L = sqrt(N pi l^2/phi) overflows", c->phi);
  if (strcmp(c->box, "periodic") == 0 && box_side(c) < 4 * c->l)
    BAD("phi: the box side L = sqrt(N pi l^2/phi) = %.17g is smaller than "
        "4l = %.17g (minimum image); use more cells or a smaller phi",
        box_side(c), 4 * c->l);
  return targets_positive(c, cl, err, errlen)
         && steps_meaningful(c, set, cl, err, errlen);
#undef BAD
}

/* The value of key K in c as params.txt writes it (reals in %.17g). */
static void key_text(const run_cfg *c, const run_key *K, char *buf,
                     size_t len)
{
  const char *p = (const char *)c + K->off;
  switch (K->kind) {
  case K_REAL: snprintf(buf, len, "%.17g", *(const double *)p); break;
  case K_INT: snprintf(buf, len, "%lld", *(const long long *)p); break;
  case K_SEED: snprintf(buf, len, "%llu", *(const unsigned long long *)p);
    break;
  case K_BOOL: snprintf(buf, len, "%d", *(const int *)p); break;
  case K_WORD: case K_PATH: snprintf(buf, len, "%s", p); break;
  }
}

/* 1 for a key the run does not use, left out of params.txt: the lattice's
** spacing unless init lattice.  (Read back, a missing key takes its
** default; a params.txt of 0.4.0 that records it still resumes.) */
static int key_unused(const run_cfg *c, const run_key *K)
{
  return strcmp(K->name, "spacing") == 0 && strcmp(c->init, "lattice") != 0;
}

/* Writes every key the run uses to path as KEY VALUE (reals in %.17g: they
** read back exactly); cells is the value written for the cells key. */
static int write_params_to(const char *path, const run_cfg *c,
                           const char *cells)
{
  char tmp[RUN_PATH_MAX + 96];
  FILE *fp;
  int k;
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  fprintf(fp, "# afv run parameters, written by afv %s: afv run --config "
          "THIS_FILE --out DIR repeats the run\n", afv_build_version());
  for (k = 0; k < N_RUN_KEYS; k++) {
    const run_key *K = &run_keys[k];
    char value[RUN_PATH_MAX + 32];
    key_text(c, K, value, sizeof value);
    if (key_unused(c, K)) continue;
    fprintf(fp, "%-16s %s\n", K->name, K->kind == K_PATH ? cells : value);
  }
  if (strcmp(c->box, "periodic") == 0)
    fprintf(fp, "# box side L = %.17g\n", box_side(c));
  return afv_atomic_commit(fp, tmp, path);
}

static int write_params(const char *dir, const run_cfg *c, const char *cells)
{
  char path[RUN_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/params.txt", dir);
  return write_params_to(path, c, cells);
}

static int write_cells_copy(const char *dir, const afv_cells *cl)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 64];
  FILE *fp;
  snprintf(path, sizeof path, "%s/cells.txt", dir);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  afv_cells_write(fp, cl);
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
static int obs_t1_reference(obs_analysis *an, afv_sim *s,
                            const char *dir, int resume)
{
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 256];
  int st;
  snprintf(path, sizeof path, "%s/t1_reference.txt", dir);
  if (resume)
    return afv_t1_reference_read(path, afv_sim_n(s), &an->t1, err, sizeof err)
           == AFV_OK || !bad_input(err);
  if ((st = afv_clusters_compute(&an->c, afv_sim_geom(s),
                                 afv_sim_positions(s), afv_sim_params(s)->l,
                                 afv_sim_box(s))) == AFV_OK
      && (st = afv_t1_start(&an->t1, &an->c)) == AFV_OK)
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
  char io_path[RUN_PATH_MAX + 96];  /* the file whose writing failed */
  int io_errno;            /* and why (errno then) */
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

/* log.txt (only): the program that writes what follows, "afv 0.3.0
** (commit ...): a fresh run" or "...: resumed", so each part of a run can
** be traced to its code. */
static void log_build(run_state *R, const char *what)
{
  if (!R->log) return;
  fprintf(R->log, "afv %s: %s\n", afv_build_version(), what);
  fflush(R->log);
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

/* The paper's protocol as the run's keys ask for it (init, spacing, the
** cells file's x y theta; relax, relax_tol and, unless relax_steps is 0,
** relax_max_steps) into pr; r has room for the 2N positions of init file.
** The authors' start (init cluster) is the square of side
** AFV_AUTHORS_SQUARE L, L = sqrt(N pi l^2 / phi). */
static void cfg_protocol(const run_cfg *c, const afv_cells *cl,
                         long relax_steps, double *r, afv_protocol *pr)
{
  int i;
  memset(pr, 0, sizeof *pr);
  if (strcmp(c->init, "cluster") == 0) {
    pr->start = AFV_START_CLUSTER;
    pr->side = AFV_AUTHORS_SQUARE * box_side(c);
  } else if (strcmp(c->init, "lattice") == 0) {
    pr->start = AFV_START_LATTICE;
    pr->spacing = c->spacing * c->l;
  } else if (strcmp(c->init, "random") == 0) {
    pr->start = AFV_START_RANDOM;
    pr->side = box_side(c);
  } else {
    pr->start = AFV_START_GIVEN;
    for (i = 0; i < cl->n; i++) {
      r[2*i] = cl->col[AFV_COL_X][i];
      r[2*i+1] = cl->col[AFV_COL_Y][i];
    }
    pr->r = r;
  }
  pr->theta = cl->has[AFV_COL_THETA] ? cl->col[AFV_COL_THETA] : NULL;
  pr->relax = strcmp(c->relax, "fire") == 0 ? AFV_RELAX_FIRE : AFV_RELAX_FLOW;
  pr->relax_tol = c->relax_tol;
  pr->relax_max_steps = relax_steps;
}

/* R->sim through the protocol (afv_protocol_start): relax_steps 0 gives
** the start alone, as the run checks it before it writes anything;
** relax_steps = relax_max_steps builds that start again (the same
** numbers) and relaxes it, v0 on at the end (rep, mon as afv_relax). */
static int run_protocol(run_state *R, long relax_steps, afv_relax_report *rep,
                        afv_relax_monitor mon)
{
  const run_cfg *c = &R->cfg;
  int n = (int)c->N, st;
  double *r = malloc((size_t)(2 * n + 1) * sizeof(double));
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  if (!r) return AFV_ENOMEM;
  cfg_model(c, &R->cells, &p, &b, &d);
  cfg_protocol(c, &R->cells, relax_steps, r, &pr);
  st = afv_protocol_start(R->sim, n, &p, &b, &d, &pr, rep, mon, R);
  free(r);
  return st;
}

static int energy_computable(const afv_params *p, int n, char *err,
                             size_t errlen);

/* energy_computable for the configuration's model (the start refused its
** parameters: afv_params_check's energy bound is energy_computable's). */
static int start_energy_computable(const run_state *R, char *err,
                                   size_t errlen)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  cfg_model(&R->cfg, &R->cells, &p, &b, &d);
  return energy_computable(&p, (int)R->cfg.N, err, errlen);
}

/* The start (positions and angles) and the simulation at it, unrelaxed;
** for init lattice, the spacing it got (start_spacing). */
static int run_start(run_state *R, char *err, size_t errlen)
{
  int st = run_protocol(R, 0, NULL, NULL), i, j;
  if (st == AFV_ECOINCIDENT) {
    afv_geom_bad_pair(afv_sim_geom(R->sim), &i, &j);
    afv_errorf(err, errlen, "cells %d and %d of the start have the same "
               "centre", i, j);
  } else if (st == AFV_EINVAL && !start_energy_computable(R, err, errlen)) {
    ;                 /* afv_params_check's bound, the key named */
  } else if (st != AFV_OK)
    afv_errorf(err, errlen, "start: %s", afv_strerror(st));
  else if (strcmp(R->cfg.init, "lattice") == 0)
    R->start_spacing = R->cfg.N > 1 ? nearest_to_first((int)R->cfg.N,
      afv_sim_positions(R->sim), afv_sim_box(R->sim)) / R->cfg.l : 0;
  return st;
}

/* ---- what a run can compute --------------------------------------------- */
/* The run later multiplies the energy and the squared force norm checked
** here by modest factors (the relaxation's energy window): a value within
** COMPUTE_HEADROOM of the largest double is refused, so those products stay
** finite: |F|^2 summed over the cells above 1.8e302, or an energy bound
** above 1.8e302 (at the paper's values, KA = KP = 1 and N = 400, the
** bound is about 1e4). */
#define COMPUTE_HEADROOM 1e6

/* The three terms of a cell's energy (paper, Eq. energy), by modulus key. */
enum { TERM_AREA, TERM_PERIM, TERM_ARC, N_TERMS };
static const char *const term_key[N_TERMS] = {"KA", "KP", "Lambda"};
static const char *const term_name[N_TERMS] = {
  "area term KA (A - A0)^2", "perimeter term KP (P - P0)^2",
  "arc term Lambda L"};

/* The modulus of term k of cell i and the target it pulls to (A0, P0). */
static double term_modulus(const afv_params *p, int i, int k, double *target)
{
  *target = 0;
  if (k == TERM_AREA) {
    *target = p->A0_i ? p->A0_i[i] : p->A0;
    return p->KA_i ? p->KA_i[i] : p->KA;
  }
  if (k == TERM_PERIM) {
    *target = p->P0_i ? p->P0_i[i] : p->P0;
    return p->KP_i ? p->KP_i[i] : p->KP;
  }
  return p->Lambda;
}

/* The largest value term k of cell i takes over every shape the cell can
** have: 0 <= A <= pi l^2 and 0 <= P, L <= 2 pi l (the cell is a convex set
** inside its disk of radius l, so its perimeter is at most the circle's).
** *dev2: the largest squared deviation alone, (A - A0)^2 or (P - P0)^2. */
static double term_bound(const afv_params *p, int i, int k, double *dev2)
{
  const double pi = 3.14159265358979323846;
  double target, m = term_modulus(p, i, k, &target), top, dev;
  top = k == TERM_AREA ? pi * p->l * p->l : 2 * pi * p->l;
  if (k == TERM_ARC) {
    *dev2 = 0;
    return fabs(m) * top;
  }
  dev = fmax(fabs(target), fabs(top - target));
  *dev2 = dev * dev;
  return m * *dev2;
}

/* "KEY: VALUE", or "KEY (cells file, cell 12): VALUE" when the value is
** the cell's own (column, of the cells file, is not NULL). */
static void value_label(char *buf, size_t len, const char *key,
                        const double *column, int cell, double value)
{
  if (column)
    snprintf(buf, len, "%s (cells file, cell %d): %g", key, cell, value);
  else
    snprintf(buf, len, "%s: %g", key, value);
}

/* value_label of term k's modulus (or, target_key = 1, of its target). */
static void term_label(char *buf, size_t len, const afv_params *p, int k,
                       int cell, int target_key)
{
  static const char *const target_key_name[N_TERMS] = {"A0", "P0", ""};
  const double *own[N_TERMS][2] = {{p->KA_i, p->A0_i}, {p->KP_i, p->P0_i},
                                   {NULL, NULL}};
  double target, m = term_modulus(p, cell, k, &target);
  value_label(buf, len, target_key ? target_key_name[k] : term_key[k],
              own[k][target_key], cell, target_key ? target : m);
}

static int huge(double x)
{
  return !isfinite(x * COMPUTE_HEADROOM);
}

/* 1 if no state can overflow the energy: each term's bound, summed over
** the cells, and their total are within the headroom.  Else names the key
** (the target A0 or P0 when the deviation alone overflows). */
static int energy_computable(const afv_params *p, int n, char *err,
                             size_t errlen)
{
  double sum[N_TERMS] = {0, 0, 0};
  int i, k, worst_cell[N_TERMS] = {0, 0, 0}, worst_k = 0;
  for (k = 0; k < N_TERMS; k++) {
    double worst = -1;
    for (i = 0; i < n; i++) {
      double dev2, b = term_bound(p, i, k, &dev2);
      if (huge(dev2)) {   /* A0 or P0 far out, or the cell's size */
        char label[96];
        double target;
        term_modulus(p, i, k, &target);
        if (huge(target * target))
          term_label(label, sizeof label, p, k, i, 1);
        else
          snprintf(label, sizeof label, "l: %g", p->l);
        afv_errorf(err, errlen, "%s: the %s cannot be computed: its squared "
                   "deviation reaches %g", label, term_name[k], dev2);
        return 0;
      }
      if (!(b <= worst)) {
        worst = b;
        worst_cell[k] = i;
      }
      sum[k] += b;
    }
    if (!(sum[k] <= sum[worst_k])) worst_k = k;
  }
  if (!huge(sum[0] + sum[1] + sum[2])) return 1;
  for (k = 0; k < N_TERMS; k++)
    if (huge(sum[k])) break;
  if (k == N_TERMS) k = worst_k;
  {
    char label[96];
    term_label(label, sizeof label, p, k, worst_cell[k], 0);
    afv_errorf(err, errlen, "%s: the %s can reach %g summed over the %d "
               "cells, beyond %g (the largest double over a margin of %g "
               "for the sums the run forms)", label, term_name[k], sum[k],
               n, DBL_MAX / COMPUTE_HEADROOM, COMPUTE_HEADROOM);
  }
  return 0;
}

/* The term of the largest energy in the current state (its key names
** what makes the forces large). */
static int largest_term(afv_sim *s)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *A = afv_geom_area(g), *P = afv_geom_perim(g);
  const double *L = afv_geom_arc(g);
  double sum[N_TERMS] = {0, 0, 0};
  int i, k, best = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    double target, m;
    m = term_modulus(afv_sim_params(s), i, TERM_AREA, &target);
    sum[TERM_AREA] += fabs(m * (A[i] - target) * (A[i] - target));
    m = term_modulus(afv_sim_params(s), i, TERM_PERIM, &target);
    sum[TERM_PERIM] += fabs(m * (P[i] - target) * (P[i] - target));
    sum[TERM_ARC] += fabs(afv_sim_params(s)->Lambda * L[i]);
  }
  for (k = 1; k < N_TERMS; k++)
    if (sum[k] > sum[best]) best = k;
  return best;
}

/* 1 if the forces of the current state can be computed with: |F|^2 summed
** over the cells (what the relaxation forms) within the headroom. */
static int forces_computable(afv_sim *s, char *err, size_t errlen)
{
  char label[96];
  const double *f = afv_sim_forces(s);
  double f2 = 0, fmax = -1;
  int i, k, worst = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    double q = f[2*i] * f[2*i] + f[2*i+1] * f[2*i+1];
    if (!(q <= fmax)) {
      fmax = q;
      worst = i;
    }
    f2 += q;
  }
  if (!huge(f2)) return 1;
  k = largest_term(s);
  term_label(label, sizeof label, afv_sim_params(s), k, worst, 0);
  afv_errorf(err, errlen, "%s: the forces of the state overflow (|F|^2 "
             "summed over the cells is %g, beyond %g; largest at cell %d), "
             "and the %s dominates its energy", label, f2,
             DBL_MAX / COMPUTE_HEADROOM, worst, term_name[k]);
  return 0;
}

/* 1 if the clock, the step's factors and the angle noise stay finite for
** the whole run: t = step dt up to steps; mu dt and v0 dt (a step moves a
** cell by mu dt F + v0 dt n, so an overflow there would blame a finite
** force); sqrt(2 Dr dt) (as the step computes it;
** then |theta| grows by at most 8.57 sqrt(2 Dr dt) a step, which cannot
** reach the largest double within 2^63 steps). */
static int dynamics_computable(afv_sim *s, long long steps, char *err,
                               size_t errlen)
{
  const afv_dyn *d = afv_sim_dyn(s);
  int i;
  if (huge((double)steps * d->dt)) {
    afv_errorf(err, errlen, "dt: %g: the time of the last step, steps x dt "
               "= %lld x %g, overflows", d->dt, steps, d->dt);
    return 0;
  }
  if (huge(d->mu * d->dt)) {
    afv_errorf(err, errlen, "mu: %g: the step's factor mu dt overflows (dt "
               "= %g)", d->mu, d->dt);
    return 0;
  }
  for (i = 0; i < afv_sim_n(s); i++) {
    double v0 = d->v0_i ? d->v0_i[i] : d->v0;
    double Dr = d->Dr_i ? d->Dr_i[i] : d->Dr;
    char label[96];
    if (huge(v0 * d->dt)) {
      value_label(label, sizeof label, "v0", d->v0_i, i, v0);
      afv_errorf(err, errlen, "%s: the step's self-propulsion v0 dt "
                 "overflows (dt = %g)", label, d->dt);
      return 0;
    }
    if (!isfinite(sqrt(2 * Dr * d->dt))) {
      value_label(label, sizeof label, "Dr", d->Dr_i, i, Dr);
      afv_errorf(err, errlen, "%s: the angle noise sqrt(2 Dr dt) overflows "
                 "(dt = %g)", label, d->dt);
      return 0;
    }
  }
  return 1;
}

/* ---- a state the outputs can record ------------------------------------ */
/* What of cell i is not finite, with its value, into buf ("" if none). */
static void cell_nonfinite(afv_sim *s, int i, char *buf, size_t len)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *r = afv_sim_positions(s) + 2 * i;
  const double *f = afv_sim_forces(s) + 2 * i, th = afv_sim_angles(s)[i];
  const double A = afv_geom_area(g)[i], P = afv_geom_perim(g)[i];
  const double L = afv_geom_arc(g)[i];
  buf[0] = 0;
  if (!isfinite(r[0]) || !isfinite(r[1]))
    snprintf(buf, len, "position (%g, %g)", r[0], r[1]);
  else if (!isfinite(th))
    snprintf(buf, len, "polarity angle %g", th);
  else if (!isfinite(f[0]) || !isfinite(f[1]))
    snprintf(buf, len, "force (%g, %g)", f[0], f[1]);
  else if (!isfinite(A) || !isfinite(P) || !isfinite(L))
    snprintf(buf, len, "shape (area %g, perimeter %g, arc length %g)", A, P,
             L);
  else if (!isfinite(afv_cell_energy(afv_sim_params(s), i, A, P, L)))
    snprintf(buf, len, "energy");
}

/* 1 if everything the outputs record of the state is finite; else msg
** says what is not: the first three such cells and their values, or the
** total energy or the time. */
static int state_finite(afv_sim *s, char *msg, size_t len)
{
  char what[192];
  int i, named = 0;
  msg[0] = 0;
  for (i = 0; i < afv_sim_n(s); i++) {
    cell_nonfinite(s, i, what, sizeof what);
    if (!what[0]) continue;
    if (named < 3)
      afv_errorf(msg + strlen(msg), len - strlen(msg), "%scell %d's %s",
                 named ? ", " : "not finite: ", i, what);
    named++;
  }
  if (named > 3)
    afv_errorf(msg + strlen(msg), len - strlen(msg), " (and %d more cells)",
               named - 3);
  else if (!named && !isfinite(afv_geom_energy(afv_sim_geom(s))))
    afv_errorf(msg, len, "not finite: the total energy (%g), each cell's "
               "being finite", afv_geom_energy(afv_sim_geom(s)));
  else if (!named && !isfinite(afv_sim_time(s)))
    afv_errorf(msg, len, "not finite: the time t = %g", afv_sim_time(s));
  return msg[0] == 0;
}

/* Everything the run will compute from the state R->sim (the start, or a
** checkpoint: where names it): the state itself finite, no energy overflow
** in any state, the forces of this one, the clock and the angle noise.
** Else err names the key, or the cells and what of them is not finite. */
static int run_computable(const run_state *R, const char *where, char *err,
                          size_t errlen)
{
  char what[512];
  if (!energy_computable(afv_sim_params(R->sim), afv_sim_n(R->sim), err,
                         errlen)
      || !dynamics_computable(R->sim, R->cfg.steps, err, errlen))
    return 0;
  if (!state_finite(R->sim, what, sizeof what)) {
    afv_errorf(err, errlen, "%s: %s", where, what);
    return 0;
  }
  return forces_computable(R->sim, err, errlen);
}

/* ---- the keys seen from afv sweep (cli.h) -------------------------------- */
int run_key_check(const char *name, const char *text, char *err,
                  size_t errlen)
{
  run_cfg cfg;
  const run_key *K = find_key(name);
  if (removed_key(name, text, err, errlen)) return 0;
  if (!K) {
    afv_errorf(err, errlen, "unknown key '%s' (see afv run --help)", name);
    return 0;
  }
  cfg_defaults(&cfg);
  return set_key(&cfg, K, text, NULL, err, errlen);
}

/* The start of cfg (cells cl, borrowed) built and checked as afv run
** checks it before it creates anything (run_start, run_computable). */
static int start_computable(const run_cfg *cfg, const afv_cells *cl,
                            char *err, size_t errlen)
{
  run_state *R = calloc(1, sizeof *R);
  int ok;
  if (!R) {
    afv_errorf(err, errlen, "out of memory");
    return 0;
  }
  R->cfg = *cfg;
  R->cells = *cl;
  R->lock_fd = -1;
  ok = (R->sim = afv_sim_new()) != NULL && run_start(R, err, errlen) == AFV_OK
       && run_computable(R, "the start", err, errlen);
  if (!R->sim) afv_errorf(err, errlen, "out of memory");
  afv_sim_delete(R->sim);
  free(R);
  return ok;
}

int run_config_write(const char *path, int n, const char *const *names,
                     const char *const *values, char *err, size_t errlen)
{
  run_cfg cfg;
  afv_cells cl;
  int set[N_RUN_KEYS], k, ok = 1;
  memset(set, 0, sizeof set);
  memset(&cl, 0, sizeof cl);
  cfg_defaults(&cfg);
  for (k = 0; k < n && ok; k++) {
    const run_key *K = find_key(names[k]);
    ok = run_key_check(names[k], values[k], err, errlen)
         && set_key(&cfg, K, values[k], NULL, err, errlen);
    if (ok) set[K - run_keys] = -1;
  }
  ok = ok && cfg_validate(&cfg, set, &cl, err, errlen)
       && (path || start_computable(&cfg, &cl, err, errlen));
  if (ok && path && write_params_to(path, &cfg, cfg.cells) != AFV_OK) {
    afv_errorf(err, errlen, "%s: cannot write", path);
    ok = 0;
  }
  afv_cells_free(&cl);
  return ok;
}

/* ---- outputs ------------------------------------------------------------ */
/* Records that writing path failed and why (errno, read at once); returns
** AFV_EIO.  report_io prints it: the file and the system's reason. */
static int io_failed(run_state *R, const char *path)
{
  R->io_errno = errno;
  snprintf(R->io_path, sizeof R->io_path, "%s", path);
  return AFV_EIO;
}

static int report_io(const run_state *R)
{
  fprintf(stderr, "afv run: %s: cannot write: %s\n", R->io_path,
          R->io_errno ? strerror(R->io_errno) : "write error");
  return EXIT_BAD_INPUT;
}

/* observables.csv: one header, one row per sample.  To add a column, add
** its name to the header and its value to the row, at the same place. */
static void obs_write_header(FILE *fp)
{
  fputs("step,time,energy,mean_area,mean_perimeter,mean_arc_length,"
        "mean_contacts,max_force,ngc_frac,n_clusters,omega,t1\n", fp);
}

static int obs_write_row(FILE *fp, afv_sim *s, obs_analysis *an)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *area = afv_geom_area(g), *perim = afv_geom_perim(g);
  const double *arc = afv_geom_arc(g);
  const int *contacts = afv_geom_contacts(g);
  double A = 0, P = 0, L = 0, C = 0;
  int i, n = afv_sim_n(s);
  int st = afv_clusters_compute(&an->c, g, afv_sim_positions(s),
                                afv_sim_params(s)->l, afv_sim_box(s));
  if (st != AFV_OK) return st;   /* no row rather than a row of NaN */
  for (i = 0; i < n; i++) {
    A += area[i];
    P += perim[i];
    L += arc[i];
    C += contacts[i];
  }
  fprintf(fp, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,",
          afv_sim_steps(s), afv_sim_time(s), afv_geom_energy(g), A / n,
          P / n, L / n, C / n, afv_sim_max_force(s));
  fprintf(fp, "%.17g,%d,%.17g,%.17g\n", (double)an->c.giant / n,
          an->c.count, an->c.omega, afv_t1_count(&an->t1, &an->c));
  return AFV_OK;
}

/* Extended XYZ (OVITO): wrapped positions, z = 0, polarity as a column. */
static void xyz_write_frame(FILE *fp, afv_sim *s)
{
  const afv_box *b = afv_sim_box(s);
  const double *r = afv_sim_positions(s), *theta = afv_sim_angles(s);
  int i, n = afv_sim_n(s);
  fprintf(fp, "%d\n", n);
  if (b->periodic)
    fprintf(fp, "Lattice=\"%.17g 0 0 0 %.17g 0 0 0 1\" pbc=\"T T F\" ",
            b->Lx, b->Ly);
  fprintf(fp, "Properties=species:S:1:pos:R:3:theta:R:1 Time=%.17g "
          "Step=%lld\n", afv_sim_time(s), afv_sim_steps(s));
  for (i = 0; i < n; i++) {
    double x = r[2*i], y = r[2*i+1];
    afv_wrap(b, &x, &y);
    fprintf(fp, "C %.17g %.17g 0 %.17g\n", x, y, theta[i]);
  }
}

/* An SVG of the current state, written atomically to DIR/name. */
static int write_svg(run_state *R, const char *name)
{
  char path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 96];
  afv_sim *s = R->sim;
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp)))
    return io_failed(R, tmp);
  if (afv_svg_write(fp, afv_sim_geom(s), afv_sim_n(s), afv_sim_positions(s),
                    afv_sim_angles(s), afv_sim_params(s), afv_sim_box(s))
      != AFV_OK) {
    io_failed(R, tmp);
    fclose(fp);
    remove(tmp);
    return AFV_EIO;
  }
  if (afv_atomic_commit(fp, tmp, path) != AFV_OK) return io_failed(R, path);
  return AFV_OK;
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
      if (fflush(R->out[k]) != 0 || ferror(R->out[k])
          || (c.bytes[k] = (long long)ftell(R->out[k])) < 0) {
        snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
        return io_failed(R, path);
      }
    }
  c.n = afv_sim_n(R->sim);
  c.step = afv_sim_steps(R->sim);
  c.t = afv_sim_time(R->sim);
  c.seed = afv_sim_dyn(R->sim)->seed;
  c.r = afv_sim_positions(R->sim);
  c.theta = afv_sim_angles(R->sim);
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (afv_checkpoint_write(path, &c) != AFV_OK) return io_failed(R, path);
  R->ckpt_step = afv_sim_steps(R->sim);
  return AFV_OK;
}

static int due(long long step, long long every)
{
  return every > 0 && step % every == 0;
}

/* 1 if anything is written at the current step. */
static int outputs_due(const run_state *R)
{
  const run_cfg *c = &R->cfg;
  long long step = afv_sim_steps(R->sim);
  return due(step, c->sample_every) || due(step, c->frame_every)
         || due(step, c->svg_every) || due(step, c->checkpoint_every);
}

/* Everything that is written at the current step (also at step 0).  A
** state that is not finite is never written: AFV_ENONFINITE (state_finite
** says what), and the files end at the last good state. */
static int run_outputs(run_state *R)
{
  const run_cfg *c = &R->cfg;
  afv_sim *s = R->sim;
  char name[64], what[512];
  int st, k;
  if (!outputs_due(R)) return AFV_OK;
  if (!state_finite(s, what, sizeof what)) return AFV_ENONFINITE;
  if (due(afv_sim_steps(s), c->sample_every)
      && (st = obs_write_row(R->out[OUT_OBS], s, &R->an)) != AFV_OK)
    return st;
  if (due(afv_sim_steps(s), c->frame_every)) {
    afv_traj_write_frame(R->out[OUT_TRAJ], afv_sim_steps(s),
                         afv_sim_time(s), afv_sim_n(s),
                         afv_sim_positions(s), afv_sim_angles(s));
    if (R->out[OUT_XYZ]) xyz_write_frame(R->out[OUT_XYZ], s);
  }
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k] && ferror(R->out[k])) {
      char path[RUN_PATH_MAX + 32];
      snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
      return io_failed(R, path);
    }
  if (due(afv_sim_steps(s), c->svg_every)) {
    snprintf(name, sizeof name, "snap_%09lld.svg", afv_sim_steps(s));
    if (write_svg(R, name) != AFV_OK) return AFV_EIO;
  }
  if (due(afv_sim_steps(s), c->checkpoint_every)) return write_checkpoint(R);
  return AFV_OK;
}

/* Resume: 1 if every append-only file the run writes holds at least the
** bytes the checkpoint records (checked for all before any is cut back);
** the library names the checkpoint's line of a size its file does not
** hold, this loop a file the run writes that is missing altogether. */
static int recorded_sizes_hold(const run_state *R, const afv_checkpoint *ck,
                               char *err, size_t errlen)
{
  char path[RUN_PATH_MAX + 32];
  int k;
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (afv_checkpoint_check_files(path, ck, err, errlen) != AFV_OK) return 0;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    if (k == OUT_XYZ && !R->cfg.xyz) continue;
    snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
    if (access(path, F_OK) != 0) {
      afv_errorf(err, errlen, "%s: %s (the checkpoint records %lld bytes)",
                 path, strerror(errno), (long long)ck->bytes[k]);
      return 0;
    }
  }
  return 1;
}

/* ---- a checkpoint agrees with the files it describes ------------------- */
/* A checkpoint is trusted only when it agrees with its files, checked
** before any byte changes: its time is step x dt (the run sets t so), and
** each append-only file, cut at the recorded size, ends with the record
** of the last output step at or before the checkpoint's step: the
** observables.csv row of that step and time (the header alone without
** samples), the whole trajectory.dat frame of that step and time (the
** header line alone without frames), and the trajectory.xyz frame of that
** step.  When the row is of the checkpoint's own step, its energy must
** equal the checkpointed state's, bit for bit (%.17g reads back exactly):
** a checksum of the state.  A checkpoint that fails any of this (edited,
** or of another run) would have cut the files to a wrong place or
** continued a different state. */

/* Reads bytes [from, to) of fd into buf (to - from <= cap - 1, NUL
** added).  1 if all were read. */
static int read_span(int fd, long long from, long long to, char *buf,
                     size_t cap)
{
  size_t want = (size_t)(to - from), got = 0;
  if (to < from || want >= cap) return 0;
  while (got < want) {
    ssize_t m = pread(fd, buf + got, want - got, (off_t)(from + (long long)got));
    if (m <= 0) return 0;
    got += (size_t)m;
  }
  buf[want] = 0;
  return 1;
}

/* The start of the k-th line (k >= 1) before end, which must follow a
** newline: -1 if the file does not end a line at end or has fewer lines.
** Reads backwards in blocks, so a frame costs its own size. */
static long long line_back(int fd, long long end, long long k)
{
  char buf[65536];
  long long pos = end - 1, seen = 0;
  if (end <= 0 || !read_span(fd, end - 1, end, buf, sizeof buf)
      || buf[0] != '\n')
    return -1;
  while (pos > 0) {
    long long from = pos - (long long)sizeof buf + 1 > 0
                     ? pos - (long long)sizeof buf + 1 : 0;
    long long j;
    if (!read_span(fd, from, pos, buf, sizeof buf)) return -1;
    for (j = pos - 1; j >= from; j--)
      if (buf[j - from] == '\n' && ++seen == k) return j + 1;
    pos = from;
  }
  return seen == k - 1 ? 0 : -1;
}

/* The line of fd starting at start (at most cap - 1 bytes, without its
** newline) into buf; 1 if read. */
static int line_at(int fd, long long start, long long end, char *buf,
                   size_t cap)
{
  long long to = end - start < (long long)cap - 1 ? end : start +
                 (long long)cap - 1;
  char *nl;
  if (!read_span(fd, start, to, buf, cap)) return 0;
  if ((nl = strchr(buf, '\n'))) *nl = 0;
  return 1;
}

/* The last output step at or before step for an interval (0: none). */
static long long last_due(long long step, long long every)
{
  return every > 0 ? step / every * every : -1;
}

typedef struct ckpt_trust {
  const run_state *R;
  const afv_checkpoint *ck;
  char *err;
  size_t errlen;
  double energy;       /* observables' energy at the checkpoint's step */
  int has_energy;      /* 1 if the last row is of the checkpoint's step */
} ckpt_trust;

/* "checkpoint.txt:LINE: bytes FILE B: the file there WHY: not ..." */
static int untrusted(ckpt_trust *T, int k, const char *why)
{
  afv_errorf(T->err, T->errlen, "%s/checkpoint.txt:%d: bytes %s %lld: %s "
             "there %s: the checkpoint does not describe these files (edited,"
             " or another run's); nothing was changed", T->R->dir,
             AFV_CKPT_BYTES_LINE + k, afv_checkpoint_files[k],
             T->ck->bytes[k], afv_checkpoint_files[k], why);
  return 0;
}

/* observables.csv (read through the lock's descriptor: closing another
** would drop the lock): its last line before the recorded size. */
static int obs_agrees(ckpt_trust *T)
{
  const run_state *R = T->R;
  long long end = T->ck->bytes[OUT_OBS], due_step = last_due(T->ck->step,
                  R->cfg.sample_every), start = line_back(R->lock_fd, end, 1);
  char line[4096], why[160];
  long long step;
  double t, e;
  if (start < 0 || !line_at(R->lock_fd, start, end, line, sizeof line))
    return untrusted(T, OUT_OBS, "does not end a line");
  if (due_step < 0)
    return start == 0 && strncmp(line, "step,", 5) == 0
           ? 1 : untrusted(T, OUT_OBS, "is not the header alone "
                           "(sample_every 0)");
  if (sscanf(line, "%lld,%lf,%lf,", &step, &t, &e) != 3 || step != due_step
      || t != (double)step * R->cfg.dt) {
    snprintf(why, sizeof why, "does not end with the row of step %lld "
             "(t = %.17g)", due_step, (double)due_step * R->cfg.dt);
    return untrusted(T, OUT_OBS, why);
  }
  T->has_energy = step == T->ck->step;
  T->energy = e;
  return 1;
}

/* trajectory.dat (format 2, io.c): its text header line, then frames of
** AFV_TRAJ_FRAME_HEAD + AFV_TRAJ_CELL_BYTES N bytes (step and time, which
** afv_traj_frame_head decodes, then the cells); the file must end, at the
** checkpoint's size, with the whole frame of the last frame step.  A
** format-1 (text) trajectory of afv < 0.3 is not appended to: its run is
** finished with the afv that began it. */
static int traj_agrees(ckpt_trust *T, int fd)
{
  const run_state *R = T->R;
  long long end = T->ck->bytes[OUT_TRAJ], frame = AFV_TRAJ_FRAME_HEAD
                + (long long)AFV_TRAJ_CELL_BYTES * R->cfg.N,
            due_step = last_due(T->ck->step, R->cfg.frame_every), head, step;
  char line[256], why[160];
  unsigned char rec[AFV_TRAJ_FRAME_HEAD + 1] = {0}; /* read_span ends what
                                                    ** it reads with 0 */
  double t = 0;
  if (!line_at(fd, 0, end, line, sizeof line)
      || strncmp(line, "# afv trajectory ", 17) != 0)
    return untrusted(T, OUT_TRAJ, "does not start with a trajectory header");
  if (strncmp(line, "# afv trajectory 2 ", 19) != 0)
    return untrusted(T, OUT_TRAJ, "is in format 1 (text, afv < 0.3), which "
                     "this afv does not append to: finish the run with the "
                     "afv that began it");
  head = (long long)strlen(line) + 1;
  if (due_step < 0)
    return end == head ? 1 : untrusted(T, OUT_TRAJ, "is not the header "
                                       "alone (frame_every 0)");
  if (end < head + frame || (end - head) % frame != 0
      || !read_span(fd, end - frame, end - frame + AFV_TRAJ_FRAME_HEAD,
                    (char *)rec, sizeof rec))
    step = -1;
  else
    afv_traj_frame_head(rec, &step, &t);
  if (step != due_step || t != (double)step * R->cfg.dt) {
    snprintf(why, sizeof why, "does not end with the whole frame of step "
             "%lld", due_step);
    return untrusted(T, OUT_TRAJ, why);
  }
  return 1;
}

/* trajectory.dat (above); trajectory.xyz: the count line, a comment with
** Step=S and N rows. */
static int frames_agree(ckpt_trust *T)
{
  const run_state *R = T->R;
  char path[RUN_PATH_MAX + 32];
  int ok, fd;
  long long n = R->cfg.N;
  snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[OUT_TRAJ]);
  if ((fd = open(path, O_RDONLY)) < 0)
    return untrusted(T, OUT_TRAJ, "cannot be read");
  ok = traj_agrees(T, fd);
  close(fd);
  if (!ok || !R->cfg.xyz) return ok;
  snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[OUT_XYZ]);
  if ((fd = open(path, O_RDONLY)) < 0)
    return untrusted(T, OUT_XYZ, "cannot be read");
  {   /* the comment line: "... Properties=... Time=T Step=S" */
    long long start = line_back(fd, T->ck->bytes[OUT_XYZ], n + 1);
    char line[4096], *at;
    long long step = -1, due_step = last_due(T->ck->step, R->cfg.frame_every);
    if (due_step < 0)
      ok = T->ck->bytes[OUT_XYZ] == 0
           || untrusted(T, OUT_XYZ, "holds frames (frame_every 0)");
    else if (start < 0 || !line_at(fd, start, T->ck->bytes[OUT_XYZ], line,
                                   sizeof line)
             || !(at = strstr(line, "Step=")) || sscanf(at, "Step=%lld",
                                                        &step) != 1
             || step != due_step) {
      char why[96];
      snprintf(why, sizeof why, "does not end with the whole frame of step "
               "%lld", due_step);
      ok = untrusted(T, OUT_XYZ, why);
    }
  }
  close(fd);
  return ok;
}

/* The checkpoint's clock and each file's last record (above).  1, or 0
** with the reason in err. */
static int checkpoint_agrees(const run_state *R, const afv_checkpoint *ck,
                             ckpt_trust *T, char *err, size_t errlen)
{
  memset(T, 0, sizeof *T);
  T->R = R;
  T->ck = ck;
  T->err = err;
  T->errlen = errlen;
  if (ck->t != (double)ck->step * R->cfg.dt) {
    afv_errorf(err, errlen, "%s/checkpoint.txt:4: time %.17g, but step %lld "
               "x dt %g is %.17g: the checkpoint does not describe this run "
               "(edited, or another run's); nothing was changed", R->dir,
               ck->t, ck->step, R->cfg.dt, (double)ck->step * R->cfg.dt);
    return 0;
  }
  return obs_agrees(T) && frames_agree(T);
}

/* Opens the append-only files: fresh (with headers) or cut back to the
** sizes of the checkpoint (recorded_sizes_hold checked them) and appended
** to. */
static int open_outputs(run_state *R, const afv_checkpoint *ck, char *err,
                        size_t errlen)
{
  char path[RUN_PATH_MAX + 32];
  int k;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    if (k == OUT_XYZ && !R->cfg.xyz) continue;
    snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
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
    afv_traj_write_header(R->out[OUT_TRAJ], afv_sim_n(R->sim),
                          afv_sim_box(R->sim));
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

/* Seconds between progress lines when stderr is not a terminal (a log
** file, a SLURM job's output). */
#define PROGRESS_LOG_SECONDS 30.0

/* Not on a terminal (and not quiet): a whole line every
** PROGRESS_LOG_SECONDS with the step, the percentage, the elapsed time
** and the estimated time left. */
static void log_progress(run_state *R, double now)
{
  long long step = afv_sim_steps(R->sim);
  double done = (double)(step - R->start_step), rate;
  if (R->cfg.quiet || now - R->last_progress < PROGRESS_LOG_SECONDS) return;
  R->last_progress = now;
  rate = done / (now - R->wall0 > 1e-9 ? now - R->wall0 : 1e-9);
  fprintf(stderr, "afv run: step %lld of %lld (%.1f%%), %.0f s elapsed, "
          "about %.0f s left\n", step, R->cfg.steps,
          100.0 * (double)step / (double)R->cfg.steps, now - R->wall0,
          rate > 0 ? (double)(R->cfg.steps - step) / rate : 0);
  fflush(stderr);
}

static void show_progress(run_state *R, int final)
{
  double now = wall_seconds(), done, rate, left;
  if (!R->progress && !final) log_progress(R, now);
  if (!R->progress || (!final && now - R->last_progress < 0.5)) return;
  R->last_progress = now;
  done = (double)(afv_sim_steps(R->sim) - R->start_step);
  rate = done / (now - R->wall0 > 1e-9 ? now - R->wall0 : 1e-9);
  left = rate > 0 ? (double)(R->cfg.steps - afv_sim_steps(R->sim)) / rate : 0;
  fprintf(stderr, "\rstep %lld/%lld  t %.6g  %.0f steps/s  %.0f s left   %s",
          afv_sim_steps(R->sim), R->cfg.steps, afv_sim_time(R->sim), rate,
          left, final ? "\n" : "");
  fflush(stderr);
}

/* ---- the run ------------------------------------------------------------ */
static void monitor_relax(void *ctx, long iter, double E, double fmax)
{
  run_state *R = ctx;
  double now = wall_seconds();
  if (!R->progress) {   /* a log, a SLURM output: a line every 30 s, and
                        ** in log.txt, so a slow relaxation is never mute */
    if (now - R->last_progress < PROGRESS_LOG_SECONDS) return;
    R->last_progress = now;
    if (R->log) {
      fprintf(R->log, "relaxing: step %ld of at most %lld, E %.10g, max |F| "
              "%.3e\n", iter, R->cfg.relax_max_steps, E, fmax);
      fflush(R->log);
    }
    if (!R->cfg.quiet)
      fprintf(stderr, "afv run: relaxing: step %ld of at most %lld, E %.10g, "
              "max |F| %.3e\n", iter, R->cfg.relax_max_steps, E, fmax);
    return;
  }
  if (now - R->last_progress < 0.5) return;
  R->last_progress = now;
  fprintf(stderr, "\rrelaxing: step %ld  E %.10g  max|F| %.3e   ", iter, E,
          fmax);
  fflush(stderr);
}

/* Where the relaxation stopped and why, with its figures (the kink
** criterion: afv.h, afv_relax). */
static void log_relax(run_state *R, const afv_relax_report *rep)
{
  if (strcmp(R->cfg.relax, "fire") == 0) {      /* relax_fire.c, STOPS */
    run_log(R, "relaxation by FIRE 2.0 (relax fire; a cell moves at most "
            "0.1 l a step): %ld steps (FIRE time %.6g), energy %.10g -> "
            "%.10g, max |F| %.3e: %s\n", rep->iterations, rep->time,
            rep->energy0, rep->energy, rep->max_force, rep->converged
            ? "converged" : rep->at_kink ? "stopped at a kink of E (the "
            "lowest energy stopped falling, max |F| <= 5 there); the "
            "lowest-energy state kept" : rep->refused ? "FIRE cannot step "
            "down from here (2000 uphill restarts in a row, or the lowest "
            "energy stopped falling at max |F| > 5); the lowest-energy state "
            "kept, relax_tol NOT reached, the run goes on" : "NOT reached "
            "within relax_max_steps; the lowest-energy state kept, the run "
            "goes on");
    return;
  }
  run_log(R, "relaxation at v0 = 0 (Euler steps of dt = %g): %ld steps "
          "(t = %.6g; %lld moved a cell more than %g l), energy %.10g -> "
          "%.10g, max |F| %.3e\n", afv_sim_dyn(R->sim)->dt, rep->iterations,
          rep->time, rep->jumps, AFV_MAX_STEP_DISP, rep->energy0,
          rep->energy, rep->max_force);
  if (R->cfg.cap > 0)
    run_log(R, "relaxation: with cap %g the force is regularised near "
            "detachment (PyAFV's contact truncation), so it is not -grad E: "
            "the relaxation follows that force, and E may rise in a step\n",
            R->cfg.cap);
  if (rep->converged)
    run_log(R, "relaxation: converged, max |F| %.3e <= relax_tol %g\n",
            rep->max_force, R->cfg.relax_tol);
  else if (rep->at_kink)
    run_log(R, "relaxation: stopped at a kink of E (a triple junction on a "
            "cell's circle, where the force jumps and does not vanish): "
            "over the last %d steps every cell's mean force <= %.2e (bound "
            "%g), mean energy change %.2e of sum |e_i| (bound %g), max |F| "
            "%.3g (bound %g); relax_tol %g not reached\n", AFV_RELAX_WINDOW,
            rep->drift, AFV_RELAX_KINK_DRIFT, rep->drop, AFV_RELAX_KINK_DROP,
            rep->max_force, AFV_RELAX_KINK_FORCE, R->cfg.relax_tol);
  else if (rep->refused)
    run_log(R, "relaxation: stopped at step %ld, which it cannot take: cell "
            "%d would move %g l (> %g l, a runaway) in one step (forces far "
            "too large for mu = %g, dt = %g: check mu, KA, KP, Lambda); "
            "relax_tol %g NOT reached, the run goes on from here\n",
            rep->iterations + 1, afv_sim_bad_cell(R->sim),
            afv_sim_bad_disp(R->sim), AFV_RUNAWAY_MOVE, R->cfg.mu, R->cfg.dt,
            R->cfg.relax_tol);
  else
    run_log(R, "relaxation: NOT reached within relax_max_steps %lld: max "
            "|F| %.3e > relax_tol %g, no kink shown (last window: mean "
            "force %.2e, bound %g; energy change %.2e, bound %g); the run "
            "goes on from here\n", R->cfg.relax_max_steps, rep->max_force,
            R->cfg.relax_tol, rep->drift, AFV_RELAX_KINK_DRIFT, rep->drop,
            AFV_RELAX_KINK_DROP);
}

static int relax_start(run_state *R)
{
  afv_relax_report rep;
  int st;
  if (R->cfg.relax_max_steps == 0) {
    run_log(R, "relaxation skipped (relax_max_steps 0); max |F| %.6e\n",
            afv_sim_max_force(R->sim));
    return AFV_OK;
  }
  R->last_progress = wall_seconds();
  st = run_protocol(R, (long)R->cfg.relax_max_steps, &rep, monitor_relax);
  if (R->progress) fprintf(stderr, "\r%70s\r", "");
  if (st != AFV_OK) return st;
  log_relax(R, &rep);
  return AFV_OK;
}

/* The end of a stop message: where the run can go on from.  A run whose
** last checkpoint is at step 0 (or that has none yet) would stop the same
** way from it (a run depends on its seed and parameters only), so that
** checkpoint is removed: DIR then holds a run that stopped before its
** first checkpoint, which a fresh run, with other parameters, replaces
** (before, such a directory was dead: a retry was refused as "already
** holds a run" and a resume stopped again). */
static const char *resume_point(const run_state *R, char *buf, size_t len)
{
  char path[RUN_PATH_MAX + 32];
  if (R->ckpt_step > 0) {
    snprintf(buf, len, "last good checkpoint: %s/checkpoint.txt (step %lld)",
             R->dir, R->ckpt_step);
    return buf;
  }
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  remove(path);
  snprintf(buf, len, "no checkpoint kept (from its start the run would stop "
           "the same way): afv run --out %s with other parameters replaces "
           "this run", R->dir);
  return buf;
}

/* The state became non-finite (a step failed on it, or it was about to be
** written): names the cells and what of them; nothing of it is written.
** Exit status 3, like an unstable step: the last checkpoint resumes. */
static int report_nonfinite(run_state *R)
{
  afv_sim *s = R->sim;
  char what[512];
  if (state_finite(s, what, sizeof what))
    snprintf(what, sizeof what, "a step made a position NaN or infinite "
             "(and was undone)");
  char where[RUN_PATH_MAX + 256];
  fprintf(stderr, "%safv run: step %lld (t = %g): %s; not written, the run "
          "stops; %s\n", R->progress ? "\n" : "", afv_sim_steps(s),
          afv_sim_time(s), what, resume_point(R, where, sizeof where));
  if (R->log)
    fprintf(R->log, "stopped at step %lld: %s\n", afv_sim_steps(s), what);
  return EXIT_UNSTABLE;
}

/* What a refused step means (afv_sim_step, AFV_EUNSTABLE). */
static const char *unstable_reason(afv_sim *s)
{
  if (!isfinite(afv_sim_bad_disp(s)))
    return "its force or position is not finite";
  return "a runaway: the forces are far too large for the time step "
         "(check mu, then KA, KP, Lambda)";
}

/* Integrates to cfg.steps.  Returns an exit status. */
static int run_loop(run_state *R)
{
  afv_sim *s = R->sim;
  char what[512], where[RUN_PATH_MAX + 256];
  int st = AFV_OK;
  R->start_step = afv_sim_steps(s);
  R->wall0 = R->last_progress = wall_seconds();
  while (afv_sim_steps(s) < R->cfg.steps) {
    if ((st = afv_sim_step(s)) != AFV_OK) break;
    if ((st = run_outputs(R)) != AFV_OK) break;
    show_progress(R, 0);
  }
  if (st == AFV_EUNSTABLE) {
    int i = afv_sim_bad_cell(s);
    fprintf(stderr, "%safv run: step %lld (t = %g): cell %d would move %g l "
            "(> %g l) in a time %g: %s; %s\n",
            R->progress ? "\n" : "", afv_sim_steps(s) + 1, afv_sim_time(s),
            i, afv_sim_bad_disp(s), AFV_RUNAWAY_MOVE, afv_sim_dyn(s)->dt,
            unstable_reason(s), resume_point(R, where, sizeof where));
    if (R->log) fprintf(R->log, "stopped: unstable step %lld, cell %d\n",
                        afv_sim_steps(s) + 1, i);
    return EXIT_UNSTABLE;
  }
  if (st == AFV_OK && R->ckpt_step != afv_sim_steps(s)
      && !state_finite(s, what, sizeof what))
    st = AFV_ENONFINITE;   /* the final checkpoint would record it */
  if (st == AFV_ECOINCIDENT) {   /* after a step */
    int i, j;
    afv_geom_bad_pair(afv_sim_geom(s), &i, &j);
    fprintf(stderr, "%safv run: step %lld: %s (cells %d and %d): the time "
            "step dt = %g is probably too large; %s\n",
            R->progress ? "\n" : "", afv_sim_steps(s), afv_strerror(st),
            i, j, afv_sim_dyn(s)->dt, resume_point(R, where, sizeof where));
    return EXIT_UNSTABLE;
  }
  if (st == AFV_ENONFINITE) return report_nonfinite(R);
  if (st == AFV_EIO) return report_io(R);
  if (st != AFV_OK) {
    fprintf(stderr, "afv run: step %lld: %s\n", afv_sim_steps(s),
            afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if ((R->ckpt_step != afv_sim_steps(s) && write_checkpoint(R) != AFV_OK)
      || write_svg(R, "final.svg") != AFV_OK)
    return report_io(R);
  show_progress(R, 1);
  {
    double w = wall_seconds() - R->wall0;
    long long k = afv_sim_steps(s) - R->start_step;
    run_log(R, "%d cells, steps %lld..%lld (t = %.6g) in %.3g s (%.0f "
            "steps/s; Euler steps that moved a cell more than %g l: "
            "%lld, since this process started, relaxation included; "
            "largest move of a cell in one step %.3g l); outputs in %s/: "
            "observables.csv, trajectory.dat, snapshots snap_*.svg and "
            "final.svg\n", afv_sim_n(s), R->start_step, afv_sim_steps(s),
            afv_sim_time(s), w, w > 0 ? (double)k / w : 0.0, AFV_MAX_STEP_DISP, afv_sim_jumps(s),
            afv_sim_largest_move(s), R->dir);
  }
  return 0;
}

static const char *run_usage =
  "usage: afv run [--config FILE] [--KEY VALUE ...] --out DIR\n"
  "       afv run [--config FILE] [--KEY VALUE ...] --out DIR --continue\n"
  "       afv run --resume DIR [--steps MORE] [--quiet]\n"
  "\n"
  "Simulates the active finite Voronoi model (paper protocol): the start\n"
  "(init; default: the authors' random cluster) relaxed at v0 = 0 until\n"
  "max |F| <= relax_tol or a kink of E, then dr/dt = mu F + v0 n,\n"
  "dth = sqrt(2 Dr dt) xi (Euler-Maruyama, the paper's steps of dt with\n"
  "the exact force, never refused for their size).\n"
  "FILE holds 'KEY VALUE' lines ('#' comments); --KEY VALUE overrides it.\n"
  "Relative paths in FILE are relative to FILE's directory.  DIR gets\n"
  "params.txt (every key; --config DIR/params.txt repeats the run),\n"
  "observables.csv, trajectory.dat, checkpoint.txt, snap_*.svg, final.svg,\n"
  "log.txt, t1_reference.txt (C(0) for the t1 column) (and cells.txt,\n"
  "trajectory.xyz).  --resume continues from the\n"
  "last checkpoint, to the run's steps or MORE steps past the checkpoint;\n"
  "it checks every file first and changes none if one does not match\n"
  "(the checkpoint must agree with the files: time = step x dt, each file\n"
  "ending with the row or frame of the last output step, that row's\n"
  "energy the state's).\n"
  "One process at a time writes in DIR (a lock on DIR/observables.csv,\n"
  "the run's data, which ends with the process); another is refused,\n"
  "naming it.  DIR may exist, but\n"
  "a fresh run refuses one with a checkpoint.txt (a run that stopped\n"
  "before its first checkpoint is replaced) and one holding files of a\n"
  "run's names without afv's params.txt (a user's own log.txt, say).  A\n"
  "run that stops (exit 3) from its step-0 checkpoint keeps none: from it\n"
  "the run would stop the same way, and a fresh run may use DIR.  --continue makes the command\n"
  "idempotent (the jobs of afv sweep): a new run if DIR holds none (or one\n"
  "that stopped before its first checkpoint), a resumed one if DIR holds\n"
  "an unfinished run, nothing if it is finished; parameters other than\n"
  "the run's in DIR (any key but quiet and checkpoint_every) are refused,\n"
  "naming the key.  Missing parent folders\n"
  "of DIR are created.\n"
  "Exit status: 0 done, 2 bad input or an I/O error, 3 unstable step (a\n"
  "force or position not finite, or a runaway move beyond 1e8 l) or a\n"
  "state that is not finite (never written).\n"
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

/* "--out --resume ... --N --phi ...": every option of afv run, for the
** nearest one to an unknown option. */
const char *run_option_names(void)
{
  static char names[2048];
  size_t m;
  int k;
  if (names[0]) return names;
  snprintf(names, sizeof names, "--out --resume --config --continue "
           "--quiet --help");
  for (k = 0; k < N_RUN_KEYS; k++) {
    m = strlen(names);
    snprintf(names + m, sizeof names - m, " --%s", run_keys[k].name);
  }
  return names;
}

/* Command-line arguments of afv run. */
typedef struct run_args {
  const char *out, *resume, *config;
  const char *steps;      /* --steps with --resume */
  int quiet;              /* 0: not given; 1: --quiet or --quiet 1; -1: --quiet 0 */
  int quiet_kv;           /* 1 if given as --quiet VALUE */
  int n_keys;             /* --KEY VALUE pairs other than the above */
  int cont;               /* --continue: fresh, resumed or left alone */
} run_args;

/* First pass: --help, --config, --out, --resume, --quiet; checks that
** every other option is --KEY VALUE with a known KEY. */
static int scan_args(int argc, char **argv, run_args *a)
{
  char msg[512];
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
    if (strcmp(o, "--continue") == 0) {
      a->cont = 1;
      continue;
    }
    if (strncmp(o, "--", 2) == 0
        && removed_key(o + 2, k + 1 < argc ? argv[k + 1] : NULL, msg,
                       sizeof msg))
      return !bad_input(msg);
    if (strncmp(o, "--", 2) != 0
        || (!find_key(o + 2) && strcmp(o, "--out") && strcmp(o, "--resume")
            && strcmp(o, "--config"))) {
      unknown_option(o, run_option_names(), NULL);
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
    if (strcmp(argv[k], "--continue") == 0) continue;
    K = find_key(argv[k] + 2);
    if (!set_key(cfg, K, argv[k + 1], NULL, err, sizeof err))
      return !bad_input(err);
    set[K - run_keys] = -1;
    k++;
  }
  return 1;
}

/* Creates the missing parent folders of dir (mkdir -p of its dirname), so
** that many jobs can write to runs/ID of a folder nobody made yet. */
static int make_parents(const char *dir)
{
  char path[RUN_PATH_MAX];
  size_t k;
  snprintf(path, sizeof path, "%s", dir);
  for (k = 1; path[k]; k++) {
    if (path[k] != '/' || path[k - 1] == '/') continue;
    path[k] = 0;
    if (mkdir(path, 0777) != 0 && errno != EEXIST) {
      fprintf(stderr, "afv run: cannot create %s: %s\n", path,
              strerror(errno));
      return 0;
    }
    path[k] = '/';
  }
  return 1;
}

/* ---- one writer per run directory -------------------------------------- */
/* A run holds a POSIX record lock (fcntl, a write lock on the whole file)
** on DIR/observables.csv, the run's own data file, from before its first
** check of DIR's files to its end, so a second `afv run` on DIR (fresh or
** --resume) is refused at once, naming the holder's process id (F_GETLK).
** The kernel drops the lock when the process ends, however it ends
** (SIGKILL included): no stale lock is ever left to clean up.  The lock is
** on a file a user has no reason to delete or replace while the run
** lives (deleting it deletes the results), not on an empty file of its
** own that invites cleaning (a deleted lock file let a second writer in).
** observables.csv keeps its inode for the whole run: a fresh run opens it
** with O_TRUNC, a resume cuts it back with truncate(2), and nothing else
** replaces it.  fcntl locks belong to the process and the file: closing
** any descriptor of observables.csv before the end would drop the lock,
** so within a run the file is read only through R->lock_fd. */
#define LOCK_FILE "observables.csv"

static int report_in_use(const char *dir, long pid)
{
  fprintf(stderr, "afv run: %s is in use by process %ld (it holds the lock "
          "on %s/" LOCK_FILE "): a run directory has one writer at a time; "
          "wait for that run to end, or stop it\n", dir, pid, dir);
  return EXIT_BAD_INPUT;
}

/* The process holding DIR's lock, or 0 (none, or no lock file: nothing is
** created).  Only for a process that does not hold the lock itself:
** closing any descriptor of the file drops the caller's own locks on it.
** (afv analyze asks it too: a run still being written is unfinished.) */
long run_lock_holder(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  struct flock fl;
  int fd;
  snprintf(path, sizeof path, "%s/" LOCK_FILE, dir);
  if ((fd = open(path, O_RDWR | O_NOFOLLOW)) < 0) return 0;
  memset(&fl, 0, sizeof fl);
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  if (fcntl(fd, F_GETLK, &fl) != 0) fl.l_type = F_UNLCK;
  close(fd);
  return fl.l_type == F_UNLCK ? 0 : (long)fl.l_pid;
}

/* Opens DIR's lock file: created if missing only for a fresh run (create
** = 1; a resume changes nothing before its checks pass), never through a
** symbolic link (a dangling one would make afv create its target), and
** only a regular file.  The descriptor, or -1 with a message. */
static int open_lock_file(const char *path, int create)
{
  struct stat sb;
  int fd = open(path, O_RDWR | O_NOFOLLOW | (create ? O_CREAT : 0), 0666);
  if (fd < 0) {
    fprintf(stderr, "afv run: %s: cannot open%s: %s\n", path,
            create ? "" : " (a run directory has it from its start)",
            errno == ELOOP ? "a symbolic link (afv writes only its own "
            "files)" : strerror(errno));
    return -1;
  }
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    fprintf(stderr, "afv run: %s: not a regular file\n", path);
    close(fd);
    return -1;
  }
  return fd;
}

/* Takes DIR's lock (create: see open_lock_file).  1 if this process now
** holds it (R->lock_fd), else 0 with a message. */
static int lock_run_dir(run_state *R, int create)
{
  char path[RUN_PATH_MAX + 32];
  struct flock fl;
  int fd, tries;
  snprintf(path, sizeof path, "%s/" LOCK_FILE, R->dir);
  if ((fd = open_lock_file(path, create)) < 0) return 0;
  for (tries = 0; tries < 100; tries++) {
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;   /* l_start = l_len = 0: the whole file */
    if (fcntl(fd, F_SETLK, &fl) == 0) {
      R->lock_fd = fd;
      return 1;
    }
    if (errno != EACCES && errno != EAGAIN) break;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(fd, F_GETLK, &fl) != 0) break;
    if (fl.l_type != F_UNLCK) {   /* else the holder just ended: try again */
      report_in_use(R->dir, (long)fl.l_pid);
      close(fd);
      return 0;
    }
  }
  fprintf(stderr, "afv run: %s: cannot lock: %s\n", path,
          tries < 100 ? strerror(errno) : "the lock keeps changing hands");
  close(fd);
  return 0;
}

/* Ends this process's hold on the run directory (closing the file drops
** the lock). */
static void unlock_run_dir(run_state *R)
{
  if (R->lock_fd >= 0) close(R->lock_fd);
  R->lock_fd = -1;
}

/* 1 (with a message) if R->dir holds a run: it has a checkpoint (a run
** that stopped before its first checkpoint has nothing to resume, and a
** fresh run replaces it).  A run still being written is named by its
** writer's process id. */
static int holds_run(const run_state *R)
{
  char path[RUN_PATH_MAX + 32];
  long pid;
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (access(path, F_OK) != 0) return 0;
  if (R->lock_fd < 0 && (pid = run_lock_holder(R->dir)) > 0)
    report_in_use(R->dir, pid);
  else
    fprintf(stderr, "afv run: %s already holds a run (checkpoint.txt): "
            "continue it with --resume %s, or choose another --out\n",
            R->dir, R->dir);
  return 1;
}

/* 1 if name is a snapshot's, snap_DIGITS.svg. */
static int is_snapshot(const char *name)
{
  size_t m = strlen(name);
  return strncmp(name, "snap_", 5) == 0 && m > 9
         && strcmp(name + m - 4, ".svg") == 0
         && strspn(name + 5, "0123456789") == m - 9;
}

/* Files a run that stopped before its first checkpoint may have left and
** a fresh run does not always rewrite (the others it rewrites). */
static void clear_unfinished_run(const char *dir)
{
  static const char *const left[] = {"log.txt", "cells.txt",
                                      "trajectory.xyz", "final.svg"};
  char path[RUN_PATH_MAX + 300];
  size_t k;
  DIR *d;
  struct dirent *e;
  for (k = 0; k < sizeof left / sizeof left[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, left[k]);
    remove(path);
  }
  if (!(d = opendir(dir))) return;
  while ((e = readdir(d)) != NULL)   /* its snapshots, of any step */
    if (is_snapshot(e->d_name)) {
      snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
      remove(path);
    }
  closedir(d);
}

/* The files afv run writes in DIR (besides snap_*.svg). */
static const char *const run_files[] = {
  "params.txt", "checkpoint.txt", "trajectory.dat", LOCK_FILE,
  "trajectory.xyz", "log.txt", "t1_reference.txt", "cells.txt", "final.svg"};

/* DIR's params.txt: 1 if afv wrote it, 0 if there is none, -1 if it is
** a user's file (it does not start with afv's first line). */
static int params_written_by_afv(const char *dir)
{
  char path[RUN_PATH_MAX + 32], line[64] = "";
  struct stat sb;
  FILE *fp;
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (lstat(path, &sb) != 0) return 0;
  if ((fp = fopen(path, "r"))) {
    if (!fgets(line, sizeof line, fp)) line[0] = 0;
    fclose(fp);
  }
  return strncmp(line, "# afv run parameters", 20) == 0 ? 1 : -1;
}

/* 1 (with a message) if DIR holds files of a run's names that afv did not
** write: a params.txt that is not afv's, or any of run_files, or a
** snapshot, without a params.txt.  A fresh run would overwrite them
** (before, a user's own log.txt and trajectory.dat were, without a
** word).  An empty observables.csv is the lock of a run being started
** (it writes params.txt next), not a user's file.  This look comes before
** the lock, so a run started at the same moment may write its files
** during it: they are that run's when DIR is locked, or when afv's
** params.txt has appeared meanwhile (before, such a run's params.txt was
** reported as a foreign file, "holds params.txt but no params.txt"). */
static int foreign_files(const char *dir)
{
  char path[RUN_PATH_MAX + 300];
  struct stat sb;
  size_t k;
  long holder;
  DIR *d;
  struct dirent *e;
  const char *found = NULL;
  int params = params_written_by_afv(dir);
  if (params > 0) return 0;
  if (params < 0) found = "params.txt";
  /* run_files[0] is params.txt, looked at above */
  for (k = 1; !found && k < sizeof run_files / sizeof run_files[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, run_files[k]);
    if (lstat(path, &sb) == 0 && !(strcmp(run_files[k], LOCK_FILE) == 0
                                   && S_ISREG(sb.st_mode) && sb.st_size == 0))
      found = run_files[k];
  }
  if (!found && (d = opendir(dir))) {
    while (!found && (e = readdir(d)) != NULL)
      if (is_snapshot(e->d_name)) found = "a snapshot snap_*.svg";
    closedir(d);
  }
  if (!found) return 0;
  if ((holder = run_lock_holder(dir)) > 0) {
    report_in_use(dir, holder);
    return 1;
  }
  if (params == 0 && params_written_by_afv(dir) > 0)
    return 0;   /* a run's, started meanwhile: the lock or holds_run says */
  if (params < 0)
    fprintf(stderr, "afv run: %s/params.txt is not afv's (it does not start "
            "with '# afv run parameters'): afv run writes only into a new or "
            "empty directory or a run directory of its own; choose another "
            "--out\n", dir);
  else
    fprintf(stderr, "afv run: %s holds %s but no params.txt: not a run "
            "directory of afv, and a run would overwrite it; choose another "
            "--out, or move that file away\n", dir, found);
  return 1;
}

/* Creates DIR for a fresh run and takes its lock.  DIR may exist, but must
** not hold a run (holds_run).  Two fresh runs to the same DIR: mkdir lets
** both in, the lock lets one on, and the other is refused (in use, or,
** once the first has checkpointed, holding a run). */
static int make_out_dir(run_state *R)
{
  const char *dir = R->dir;
  if (holds_run(R) || foreign_files(dir))
    return 0;                       /* refused before anything changes */
  if (!make_parents(dir)) return 0;
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv run: cannot create %s: %s\n", dir, strerror(errno));
    return 0;
  }
  if (!lock_run_dir(R, 1) || holds_run(R)) return 0;
  clear_unfinished_run(dir);
  return 1;
}

/* Prints "afv run: DIR/NAME: cannot write: REASON" (errno at the call);
** EXIT_BAD_INPUT. */
static int write_failed(run_state *R, const char *name)
{
  char path[RUN_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  io_failed(R, path);
  return report_io(R);
}

/* The parameters the command line asks for: the defaults, --config FILE,
** the --KEY VALUE overrides, checked (cfg_validate; the cells file read
** into cl); set[k] records where key k came from.  0, or an exit status
** with the message printed. */
static int requested_cfg(run_cfg *cfg, afv_cells *cl, const run_args *a,
                         int argc, char **argv, int *set)
{
  char err[2 * RUN_PATH_MAX] = "";
  if (a->config && !read_config(a->config, cfg, set, err, sizeof err))
    return bad_input(err);
  if (!apply_args(argc, argv, cfg, set)) return EXIT_BAD_INPUT;
  if (!cfg_validate(cfg, set, cl, err, sizeof err)) {
    locate_error(err, sizeof err, set, a->config);
    return bad_input(err);
  }
  return 0;
}

static int run_fresh(run_state *R, const run_args *a, int argc, char **argv)
{
  char err[2 * RUN_PATH_MAX] = "";
  int set[N_RUN_KEYS], st;
  memset(set, 0, sizeof set);
  long holder;
  if (strlen(a->out) > RUN_PATH_MAX - 64) return bad_input("--out: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->out);
  if ((holder = run_lock_holder(R->dir)) > 0)   /* at once, before the start */
    return report_in_use(R->dir, holder);
  if ((st = requested_cfg(&R->cfg, &R->cells, a, argc, argv, set)) != 0)
    return st;
  if (run_start(R, err, sizeof err) != AFV_OK) return bad_input(err);
  if (!run_computable(R, "the start", err, sizeof err)) {
    locate_error(err, sizeof err, set, a->config);
    return bad_input(err);
  }
  /* everything is checked: only now is anything created */
  if (!make_out_dir(R)) return EXIT_BAD_INPUT;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  /* params.txt first: a directory with it is afv's (foreign_files) */
  if (write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
      != AFV_OK)
    return write_failed(R, "params.txt");
  if (R->cells.n && write_cells_copy(R->dir, &R->cells) != AFV_OK)
    return write_failed(R, "cells.txt");
  if (!open_outputs(R, NULL, err, sizeof err)) {
    fprintf(stderr, "afv run: %s\n", err);
    return EXIT_BAD_INPUT;
  }
  log_build(R, "a fresh run");
  if (R->start_spacing > 0
      && R->start_spacing < R->cfg.spacing * (1 - 1e-9))
    run_log(R, "cluster start: spacing %.6g l instead of %.6g l, so that "
            "the cluster fits the box\n", R->start_spacing, R->cfg.spacing);
  if ((st = relax_start(R)) == AFV_ENONFINITE) return report_nonfinite(R);
  if (st != AFV_OK) {
    fprintf(stderr, "afv run: relaxation: %s\n", afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if (!obs_t1_reference(&R->an, R->sim, R->dir, 0)) return EXIT_BAD_INPUT;
  st = run_outputs(R);
  if (st == AFV_OK && !due(0, R->cfg.checkpoint_every))
    st = write_checkpoint(R);
  if (st == AFV_ENONFINITE) return report_nonfinite(R);
  if (st != AFV_OK) return report_io(R);
  return run_loop(R);
}

/* --steps MORE of a resume: a count of steps, 0 .. 2^63 - 1. */
static int parse_more_steps(const char *text, long long *more)
{
  const char *why = integral_problem(text, 0, LLONG_MAX, more);
  if (!why) return 1;
  cli_errorf("--steps: '%s' %s: not a count of steps (an integer from 0 to "
             "%lld)", text, why, LLONG_MAX);
  return 0;
}

/* 1 if the KEY VALUE file at path has a line for key, 0 if not, -1 if it
** cannot be read. */
static int has_key(const char *path, const char *key)
{
  afv_lines L;
  int found = 0;
  if (afv_lines_open(&L, path, NULL, 0) != AFV_OK) return -1;
  while (!found && afv_lines_next(&L, NULL, 0) > 0) {
    char *k = strtok(L.line, " \t\r");
    found = k && strcmp(k, key) == 0;
  }
  afv_lines_close(&L);
  return found;
}

/* The params.txt of a run to go on with (--resume, --continue): one
** without the integrator key was written by afv 0.1.0, whose runs used the
** sub-steps (REMOVED KEYS), and is refused, naming the version that goes
** on with it.  0 if it has the key (or cannot be read: read_config then
** says why), else an exit status with the message printed. */
static int written_after_0_1_0(const char *params)
{
  if (has_key(params, "integrator") != 0) return 0;
  fprintf(stderr, "afv run: %s: no integrator key: a run of afv 0.1.0, "
          "whose sub-steps (integrator substeps) were removed in afv 0.3.0; "
          "finish it with afv 0.1.0\n", params);
  return EXIT_BAD_INPUT;
}

/* Resume: params.txt (and the cells file it names) into R->cfg; set[k]
** records the line of key k.  0, or an exit status with the message
** printed. */
static int resume_params(run_state *R, const run_args *a, int *set,
                         const char *params)
{
  char err[2 * RUN_PATH_MAX];
  int st;
  if ((st = written_after_0_1_0(params)) != 0) return st;
  if (!read_config(params, &R->cfg, set, err, sizeof err))
    return bad_input(err);
  if (a->quiet) R->cfg.quiet = a->quiet > 0;
  if (!cfg_validate(&R->cfg, set, &R->cells, err, sizeof err)) {
    locate_error(err, sizeof err, set, params);
    return bad_input(err);
  }
  return 0;
}

/* Resume: the checkpoint at ckpt against params.txt (cells, seed), its
** step plus --steps MORE (no overflow) and the recorded sizes against
** their files.  *new_steps = 1 if MORE changes the run's steps (R->cfg
** then has the new count).  0, or an exit status with the message
** printed. */
static int resume_checkpoint(run_state *R, long long more, const char *ckpt,
                             afv_checkpoint *ck, int *new_steps,
                             ckpt_trust *T)
{
  char err[2 * RUN_PATH_MAX];
  if (access(ckpt, F_OK) != 0) {
    fprintf(stderr, "afv run: %s has no checkpoint.txt: its run stopped "
            "before its first checkpoint; start it again with afv run "
            "--config %s/params.txt --out %s (a fresh run replaces a run "
            "without a checkpoint)\n", R->dir, R->dir, R->dir);
    return EXIT_BAD_INPUT;
  }
  if (afv_checkpoint_read(ckpt, ck, err, sizeof err) != AFV_OK)
    return bad_input(err);
  if (ck->n != R->cfg.N || ck->seed != R->cfg.seed) {
    fprintf(stderr, "afv run: %s: %d cells and seed %llu, but params.txt "
            "has N %lld and seed %llu: not this run's checkpoint\n", ckpt,
            ck->n, ck->seed, R->cfg.N, R->cfg.seed);
    return EXIT_BAD_INPUT;
  }
  if (ck->step < 0) {
    fprintf(stderr, "afv run: %s: step %lld is negative\n", ckpt, ck->step);
    return EXIT_BAD_INPUT;
  }
  if (more >= 0 && more > LLONG_MAX - ck->step) {
    cli_errorf("--steps: %lld more steps past the checkpoint's step %lld "
               "exceed the largest step count (%lld)", more, ck->step,
               LLONG_MAX);
    return EXIT_BAD_INPUT;
  }
  *new_steps = more >= 0 && R->cfg.steps != ck->step + more;
  if (more >= 0) R->cfg.steps = ck->step + more;
  if (!recorded_sizes_hold(R, ck, err, sizeof err)
      || !checkpoint_agrees(R, ck, T, err, sizeof err))
    return bad_input(err);
  return 0;
}

/* Resume: the simulation at the checkpoint's state, which must be one the
** run can compute with (run_computable), and the T1 reference.  0, or an
** exit status with the message printed. */
static int resume_state(run_state *R, const afv_checkpoint *ck,
                        const char *ckpt, const int *set, const char *params,
                        const ckpt_trust *T)
{
  char err[2 * RUN_PATH_MAX];
  afv_params p;
  afv_box b;
  afv_dyn d;
  int st, i, j;
  cfg_model(&R->cfg, &R->cells, &p, &b, &d);
  st = afv_sim_init(R->sim, ck->n, ck->r, ck->theta, &p, &b, &d);
  afv_geom_bad_pair(afv_sim_geom(R->sim), &i, &j);
  if (st == AFV_ECOINCIDENT)
    afv_errorf(err, sizeof err, "%s: cells %d and %d have the same centre",
               ckpt, i, j);
  else if (st != AFV_OK)
    afv_errorf(err, sizeof err, "%s: %s", ckpt, afv_strerror(st));
  if (st != AFV_OK) return bad_input(err);
  afv_sim_set_steps(R->sim, ck->step);   /* t = step dt: ck->t, checked */
  R->ckpt_step = ck->step;
  if (!run_computable(R, ckpt, err, sizeof err)) {
    locate_error(err, sizeof err, set, params);  /* a key: its line */
    return bad_input(err);
  }
  if (T->has_energy && T->energy != afv_geom_energy(afv_sim_geom(R->sim))) {
    fprintf(stderr, "afv run: %s: its state has the energy %.17g under "
            "params.txt, but observables.csv's row of step %lld has %.17g: "
            "the checkpoint and params.txt do not describe these files "
            "(edited, or another run's); nothing was changed\n", ckpt,
            afv_geom_energy(afv_sim_geom(R->sim)), ck->step, T->energy);
    return EXIT_BAD_INPUT;
  }
  if (!obs_t1_reference(&R->an, R->sim, R->dir, 1)) return EXIT_BAD_INPUT;
  return 0;
}

/* Every check of a resume, before any byte of any file changes: params.txt
** (and the cells file), the checkpoint (against params.txt, --steps MORE,
** every recorded size against its file, the state computable) and the T1
** reference.  Fills R (cfg, sim, an) and *ck.  0, or an exit status with
** the message printed. */
static int resume_checks(run_state *R, const run_args *a, long long more,
                         afv_checkpoint *ck, int *new_steps)
{
  char params[RUN_PATH_MAX + 32], ckpt[RUN_PATH_MAX + 32];
  int set[N_RUN_KEYS], st;
  ckpt_trust T;
  memset(set, 0, sizeof set);
  memset(&T, 0, sizeof T);
  snprintf(params, sizeof params, "%s/params.txt", R->dir);
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", R->dir);
  if ((st = resume_params(R, a, set, params)) != 0
      || (st = resume_checkpoint(R, more, ckpt, ck, new_steps, &T)) != 0)
    return st;
  return resume_state(R, ck, ckpt, set, params, &T);
}

static int run_resume(run_state *R, const run_args *a)
{
  char err[2 * RUN_PATH_MAX], path[RUN_PATH_MAX + 32];
  afv_checkpoint ck;
  long long more = -1;
  int st, new_steps = 0;
  if (a->n_keys > (a->steps != NULL) + a->quiet_kv || a->config || a->out)
    return bad_input("run: with --resume only --steps MORE and --quiet are "
                     "allowed (the parameters are DIR/params.txt)");
  if (a->steps && !parse_more_steps(a->steps, &more)) return EXIT_BAD_INPUT;
  if (strlen(a->resume) > RUN_PATH_MAX - 64)
    return bad_input("--resume: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->resume);
  snprintf(path, sizeof path, "%s/params.txt", R->dir);
  if (access(path, F_OK) != 0) {   /* not a run: refused before the lock */
    fprintf(stderr, "afv run: %s: cannot open: %s (--resume needs a run "
            "directory)\n", path, strerror(errno));
    return EXIT_BAD_INPUT;
  }
  if (!lock_run_dir(R, 0)) return EXIT_BAD_INPUT;
  memset(&ck, 0, sizeof ck);
  st = resume_checks(R, a, more, &ck, &new_steps);
  /* all checked: from here on files change (params.txt atomically) */
  if (st == 0 && new_steps
      && write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
         != AFV_OK)
    st = write_failed(R, "params.txt");
  if (st == 0 && !open_outputs(R, &ck, err, sizeof err)) {
    fprintf(stderr, "afv run: %s\n", err);
    st = EXIT_BAD_INPUT;
  }
  afv_checkpoint_free(&ck);
  if (st != 0) return st;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  log_build(R, "resumed");
  run_log(R, "resuming at step %lld (t = %.6g), to step %lld\n",
          afv_sim_steps(R->sim), afv_sim_time(R->sim), R->cfg.steps);
  return run_loop(R);
}

/* 1 if the run in dir has reached its steps (its checkpoint is at the end)
** and written final.svg, its last output (a run killed between the two is
** resumed, at no step, to write it); -1 if params.txt or the checkpoint
** cannot be read (message printed). */
static int run_finished(const char *dir)
{
  char path[RUN_PATH_MAX + 32], err[2 * RUN_PATH_MAX];
  int set[N_RUN_KEYS], done;
  run_cfg cfg;
  afv_checkpoint ck;
  memset(set, 0, sizeof set);
  cfg_defaults(&cfg);
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (!read_config(path, &cfg, set, err, sizeof err)) return -bad_input(err);
  snprintf(path, sizeof path, "%s/checkpoint.txt", dir);
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK)
    return -bad_input(err);
  snprintf(path, sizeof path, "%s/final.svg", dir);
  done = ck.step >= cfg.steps && access(path, F_OK) == 0;
  afv_checkpoint_free(&ck);
  return done;
}

/* 1 if the cells files a and b hold the same columns and values. */
static int same_cells(const afv_cells *a, const afv_cells *b)
{
  int k;
  if (a->n != b->n) return 0;
  for (k = 0; k < AFV_NCOLS; k++)
    if (a->has[k] != b->has[k] || (a->has[k] && memcmp(a->col[k], b->col[k],
                                   (size_t)a->n * sizeof(double)) != 0))
      return 0;
  return 1;
}

/* --continue on DIR with a run: the parameters asked for must be the
** run's (DIR/params.txt, and its cells.txt against the cells file
** given), every key but quiet and checkpoint_every; else refused, naming the first key that
** differs (before, they were ignored: --P0 5 on a finished P0 4 run said
** "finished already", and an unfinished one resumed with the old N, P0,
** v0).  0 if they agree, else an exit status with the message printed. */
static int same_run_asked(const run_args *a, int argc, char **argv)
{
  char path[RUN_PATH_MAX + 32], err[2 * RUN_PATH_MAX];
  char want[RUN_PATH_MAX + 32], have[RUN_PATH_MAX + 32];
  run_cfg asked, run;
  afv_cells asked_cells, run_cells;
  int set_asked[N_RUN_KEYS], set_run[N_RUN_KEYS], k, st = 0;
  memset(set_asked, 0, sizeof set_asked);
  memset(set_run, 0, sizeof set_run);
  memset(&asked_cells, 0, sizeof asked_cells);
  memset(&run_cells, 0, sizeof run_cells);
  cfg_defaults(&asked);
  cfg_defaults(&run);
  snprintf(path, sizeof path, "%s/params.txt", a->out);
  if ((st = requested_cfg(&asked, &asked_cells, a, argc, argv, set_asked))
      || (st = written_after_0_1_0(path)))
    goto done;
  if (!read_config(path, &run, set_run, err, sizeof err)) {
    st = bad_input(err);
    goto done;
  }
  if (!cfg_validate(&run, set_run, &run_cells, err, sizeof err)) {
    locate_error(err, sizeof err, set_run, path);
    st = bad_input(err);
    goto done;
  }
  for (k = 0; k < N_RUN_KEYS && !st; k++) {
    const run_key *K = &run_keys[k];
    if (strcmp(K->name, "quiet") == 0
        || strcmp(K->name, "checkpoint_every") == 0)
      continue;   /* neither changes what the run computes or records */
    key_text(&asked, K, want, sizeof want);
    key_text(&run, K, have, sizeof have);
    if (K->kind == K_PATH ? same_cells(&asked_cells, &run_cells)
        : strcmp(want, have) == 0)
      continue;
    if (K->kind == K_PATH)
      cli_errorf("--continue: cells: the cells file %s differs from the "
                 "run's (%s/cells.txt): %s holds another run; choose another "
                 "--out", want, a->out, a->out);
    else
      cli_errorf("--continue: %s: %s asked, but %s has %s: %s holds another "
                 "run; choose another --out, or ask for its parameters%s",
                 K->name, want, path, have, a->out,
                 strcmp(K->name, "steps") == 0 ? " (to run it longer: afv "
                 "run --resume DIR --steps MORE)" : "");
    st = EXIT_BAD_INPUT;
  }
done:
  afv_cells_free(&asked_cells);
  afv_cells_free(&run_cells);
  return st;
}

/* --continue --out DIR: the idempotent job of afv sweep.  No checkpoint in
** DIR (no run, or one that stopped before its first checkpoint, which a
** fresh run replaces): a fresh run.  A checkpointed run short of its
** steps: resumed.  A finished run: left alone.  The fresh run and the
** resume take DIR's lock as always, so a run still being written by
** another process is refused, not touched. */
static int run_continue(run_state *R, run_args *a, int argc, char **argv)
{
  char ckpt[RUN_PATH_MAX + 32];
  run_args resume;
  int done;
  if (strlen(a->out) > RUN_PATH_MAX - 64) return bad_input("--out: path too long");
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", a->out);
  if (access(ckpt, F_OK) != 0) return run_fresh(R, a, argc, argv);
  if ((done = same_run_asked(a, argc, argv)) != 0) return done;
  if ((done = run_finished(a->out)) != 0) {
    if (done > 0 && !a->quiet)
      fprintf(stderr, "afv run: %s: finished already\n", a->out);
    return done > 0 ? 0 : EXIT_BAD_INPUT;
  }
  memset(&resume, 0, sizeof resume);
  resume.resume = a->out;
  resume.quiet = a->quiet;
  return run_resume(R, &resume);
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
  if (a.cont && !a.out)
    return bad_input("run: --continue goes with --out DIR (see afv run "
                     "--help)");
  memset(&R, 0, sizeof R);
  R.lock_fd = -1;
  cfg_defaults(&R.cfg);
  if (!(R.sim = afv_sim_new())) return bad_input("run: out of memory");
  status = a.resume ? run_resume(&R, &a)
           : a.cont ? run_continue(&R, &a, argc, argv)
           : run_fresh(&R, &a, argc, argv);
  close_outputs(&R);
  unlock_run_dir(&R);
  afv_sim_delete(R.sim);
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
