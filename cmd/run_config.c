/*
** run_config.c -- afv run's keys: the table (defaults, --help), parsing of
** a config file and of --KEY VALUE, range checks, params.txt written, read
** and compared (--continue), the command line; readers of params.txt for
** the other commands
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "run.h"

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

/* Without svg_every a run draws a snapshot every max(5000, steps /
** RUN_SNAPSHOTS) steps: at most RUN_SNAPSHOTS + 1 pictures of about 0.5 KB
** a cell however long the run (a 10^6-step run drew 201, 45 MB at N =
** 400). */
#define RUN_SNAPSHOTS 20

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
     "so many steps (0: only final.svg); must be >= 0; when not given, "
     "steps/" AFV_STR(RUN_SNAPSHOTS) " if that is larger, so that a long "
     "run draws at most " AFV_STR(RUN_SNAPSHOTS) " snapshots and final.svg"),
  RK("xyz", K_BOOL, xyz, "0", "0|1", "also write trajectory.xyz (extended "
     "XYZ, for OVITO)"),
  RK("quiet", K_BOOL, quiet, "0", "0|1", "no progress or summary on stderr "
     "(--quiet alone means 1)"),
  RK("cells", K_PATH, cells, "none", "file", "CELLS file with per-cell "
     "columns (x y theta v0 Dr KA KP A0 P0), or none"),
};
/* N_RUN_KEYS (run.h) counts the table: this array has a negative size,
** and the file does not compile, if a key is added without it. */
typedef char run_keys_counted[sizeof run_keys / sizeof run_keys[0]
                              == N_RUN_KEYS ? 1 : -1];

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

void cfg_defaults(run_cfg *cfg)
{
  int k;
  memset(cfg, 0, sizeof *cfg);
  for (k = 0; k < N_RUN_KEYS; k++)
    set_key(cfg, &run_keys[k], run_keys[k].def, NULL, NULL, 0);
}

/* Reads KEY VALUE lines ('#' starts a comment).  set[k] records the line
** of key k (set must hold no line numbers: a key on two lines is refused,
** naming both).  A REMOVED KEY is refused, or skipped if removed_ok (a
** reader of an old run's params.txt).  Returns 1, or 0 with "FILE:LINE:
** ..." in err. */
static int read_keys(const char *path, run_cfg *cfg, int *set,
                     int removed_ok, char *err, size_t errlen)
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
      if (removed_ok) continue;
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
    } else if (set[K - run_keys] > 0) {   /* last-wins would hide one */
      afv_errorf(err, errlen, "%s:%lld: %s: given twice (line %d has it "
                 "too): a key has one value", path, L.lineno, key,
                 set[K - run_keys]);
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

int read_config(const char *path, run_cfg *cfg, int *set, char *err,
                size_t errlen)
{
  return read_keys(path, cfg, set, 0, err, errlen);
}

/* The box side of N cells at packing fraction phi: N pi l^2 = phi L^2. */
double box_side(const run_cfg *c)
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
void locate_error(char *err, size_t errlen, const int *set,
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

/* svg_every not given: at least steps / RUN_SNAPSHOTS (RUN_SNAPSHOTS). */
static void bound_snapshots(run_cfg *c, const int *set)
{
  /* the ceiling of steps / RUN_SNAPSHOTS, without steps + RUN_SNAPSHOTS - 1,
  ** which overflows for steps near LLONG_MAX */
  long long every = c->steps / RUN_SNAPSHOTS + (c->steps % RUN_SNAPSHOTS != 0);
  if (!set[find_key("svg_every") - run_keys] && c->svg_every > 0
      && every > c->svg_every)
    c->svg_every = every;
}

/* Range checks, one message naming the key.  Reads the cells file (cl). */
int cfg_validate(run_cfg *c, const int *set, afv_cells *cl, char *err,
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
  bound_snapshots(c, set);
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

/* THE RECORD.  params.txt ends with the keys as afv wrote them, in
** comment lines "# as written: KEY=VALUE ..." (at most RECORD_WIDTH
** characters; the cells key, a path, is not in it), so that --resume finds
** a key edited since (record_agrees): the checkpoint and the files do not
** show every key (an edited v0, Dr, mu, cap, phi, frame_every, init or
** relax_tol let the run go on under other parameters in the same files).
** A params.txt of an earlier afv has no record and is not checked. */
#define RECORD_PREFIX "# as written:"
#define RECORD_WIDTH 72

/* 1 for a key the run does not use, left out of params.txt: the lattice's
** spacing unless init lattice.  (Read back, a missing key takes its
** default, so a params.txt that records it still resumes.) */
static int key_unused(const run_cfg *c, const run_key *K)
{
  return strcmp(K->name, "spacing") == 0 && strcmp(c->init, "lattice") != 0;
}

/* The keys a resume may see changed: steps (--steps MORE rewrites it, and
** a run may be made longer by hand), quiet and checkpoint_every (neither
** changes what the run computes or records), cells (not recorded). */
static int resume_may_change(const run_key *K)
{
  return K->kind == K_PATH || strcmp(K->name, "steps") == 0
         || strcmp(K->name, "quiet") == 0
         || strcmp(K->name, "checkpoint_every") == 0;
}

static void write_record(FILE *fp, const run_cfg *c)
{
  size_t used = 0;
  int k;
  for (k = 0; k < N_RUN_KEYS; k++) {
    char value[RUN_PATH_MAX + 32];
    size_t m;
    if (run_keys[k].kind == K_PATH || key_unused(c, &run_keys[k])) continue;
    key_text(c, &run_keys[k], value, sizeof value);
    m = strlen(run_keys[k].name) + strlen(value) + 2;
    if (used == 0 || used + m > RECORD_WIDTH) {
      fprintf(fp, "%s" RECORD_PREFIX, used ? "\n" : "");
      used = strlen(RECORD_PREFIX);
    }
    fprintf(fp, " %s=%s", run_keys[k].name, value);
    used += m;
  }
  fputc('\n', fp);
}

/* A real key's value text (%.17g) in the fewest digits that read back
** as it, in place (it never grows: %.17g is the longest form). */
static void shortest_real(const run_key *K, char *text, size_t len)
{
  char buf[64];
  double x;
  if (K->kind != K_REAL || real_problem(text, &x)) return;
  exact_text(x, buf, sizeof buf);
  if (strlen(buf) < len) memcpy(text, buf, strlen(buf) + 1);
}

/* The KEY=VALUE words of a record line: each key that the resume may not
** change must have the value in c.  1, or 0 with the message in err. */
static int record_line_agrees(char *line, const run_cfg *c, const int *set,
                              const char *path, char *err, size_t errlen)
{
  char *word;
  for (word = strtok(line + strlen(RECORD_PREFIX), " \t\r"); word;
       word = strtok(NULL, " \t\r")) {
    char *eq = strchr(word, '='), now[RUN_PATH_MAX + 32];
    const run_key *K;
    if (!eq) continue;
    *eq = 0;
    if (!(K = find_key(word)) || resume_may_change(K) || key_unused(c, K))
      continue;
    key_text(c, K, now, sizeof now);
    if (strcmp(now, eq + 1) == 0) continue;
    shortest_real(K, now, sizeof now);   /* 0.7, not 0.69999999999999996 */
    shortest_real(K, eq + 1, strlen(eq + 1) + 1);
    afv_errorf(err, errlen, "%s:%d: %s %s, but afv wrote %s %s (its record "
               "at the end of the file): a key edited since the run began "
               "changes the run its files hold; restore it, or start a new "
               "run (afv run --config %s --out NEWDIR)", path,
               set[K - run_keys], K->name, now, K->name, eq + 1, path);
    return 0;
  }
  return 1;
}

/* params.txt at path (read into c, set[k] the line of key k) against its
** record: 1 if every key a resume may not change has the value afv wrote
** (or there is no record), else 0 naming the key in err. */
int record_agrees(const char *path, const run_cfg *c, const int *set,
                  char *err, size_t errlen)
{
  afv_lines L;
  int ok = 1;
  if (afv_lines_open(&L, path, err, errlen) != AFV_OK) return 0;
  while (ok && afv_lines_next(&L, NULL, 0) > 0)
    if (strncmp(L.line, RECORD_PREFIX, strlen(RECORD_PREFIX)) == 0)
      ok = record_line_agrees(L.line, c, set, path, err, errlen);
  afv_lines_close(&L);
  return ok;
}

/* A value text of key K for a message: a real in the fewest digits that
** read back as it (4.8, not params.txt's 4.7999999999999998); in place. */
static const char *as_written(const run_key *K, char *text)
{
  char buf[64];
  if (K->kind == K_REAL) {
    exact_text(strtod(text, NULL), buf, sizeof buf);
    strcpy(text, buf);
  }
  return text;
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
  write_record(fp, c);
  return afv_atomic_commit(fp, tmp, path);
}

int write_params(const char *dir, const run_cfg *c, const char *cells)
{
  char path[RUN_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/params.txt", dir);
  return write_params_to(path, c, cells);
}

int write_cells_copy(const char *dir, const afv_cells *cl)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 64];
  FILE *fp;
  snprintf(path, sizeof path, "%s/cells.txt", dir);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  afv_cells_write(fp, cl);
  return afv_atomic_commit(fp, tmp, path);
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

const char *run_key_default(const char *name)
{
  const run_key *K = find_key(name);
  return K ? K->def : NULL;
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

/* 1 if the option argv[k] ("--NAME") is among argv[1 .. k-1]: no value
** starts with "--" (scan_args refuses one), so an equal word there is the
** same option given before. */
static int given_before(char **argv, int k)
{
  int j;
  if (strncmp(argv[k], "--", 2) != 0) return 0;
  for (j = 1; j < k; j++)
    if (strcmp(argv[j], argv[k]) == 0) return 1;
  return 0;
}

/* First pass: --help, --config, --out, --resume, --quiet; checks that
** every other option is --KEY VALUE with a known KEY. */
int scan_args(int argc, char **argv, run_args *a)
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
    if (given_before(argv, k)) {
      fprintf(stderr, "afv run: %s: given twice: an option has one value "
              "(the last one would silently win)\n", o);
      return 0;
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

/* The parameters the command line asks for: the defaults, --config FILE,
** the --KEY VALUE overrides, checked (cfg_validate; the cells file read
** into cl); set[k] records where key k came from.  0, or an exit status
** with the message printed. */
int requested_cfg(run_cfg *cfg, afv_cells *cl, const run_args *a,
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
int written_after_0_1_0(const char *params)
{
  if (has_key(params, "integrator") != 0) return 0;
  fprintf(stderr, "afv run: %s: no integrator key: a run of afv 0.1.0, "
          "whose sub-steps (integrator substeps) were removed in afv 0.3.0; "
          "finish it with afv 0.1.0\n", params);
  return EXIT_BAD_INPUT;
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
int same_run_asked(const run_args *a, int argc, char **argv)
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
                 K->name, as_written(K, want), path, as_written(K, have),
                 a->out,
                 strcmp(K->name, "steps") == 0 ? " (to run it longer: afv "
                 "run --resume DIR --steps MORE)" : "");
    st = EXIT_BAD_INPUT;
  }
done:
  afv_cells_free(&asked_cells);
  afv_cells_free(&run_cells);
  return st;
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

/* The params.txt at path: 1 if afv wrote it (it starts with afv's first
** line), 0 if there is none, -1 if it is a user's file (or not a regular
** file: a FIFO is not opened for reading, which would block). */
int params_written_by_afv(const char *path)
{
  char line[32] = "";
  struct stat sb;
  ssize_t got = 0;
  int fd;
  if (lstat(path, &sb) != 0) return 0;
  if (!S_ISREG(sb.st_mode)) return -1;
  if ((fd = open(path, O_RDONLY | O_NONBLOCK | O_NOFOLLOW)) >= 0) {
    got = read(fd, line, 20);
    close(fd);
  }
  return got == 20 && strncmp(line, "# afv run parameters", 20) == 0 ? 1
         : -1;
}

/* params.txt of a run read whole, as afv run reads it (read_config: every
** line a known key with a value it accepts, no key twice), for afv
** analyze (the keys of afv 0.1 and 0.2 that were removed are skipped),
** which must not fill in defaults for what it cannot read (an
** empty, garbled or cut params.txt gave v0 = 0.5 silently, and D_eff 25
** times off): l, v0 and Dr, which it must hold, and steps, which afv's
** own params.txt must hold (one written by hand, for a trajectory from
** elsewhere, need not: *steps = -1).  1 if read, 0 if there is no file at
** path, -1 with the reason in err. */
int run_params_read(const char *path, run_params_info *p, char *err,
                    size_t errlen)
{
  static const char *const needed[] = {"l", "v0", "Dr", "steps"};
  int set[N_RUN_KEYS], afv_own = params_written_by_afv(path) > 0;
  run_cfg c;
  size_t k;
  if (access(path, F_OK) != 0 && errno == ENOENT) return 0;
  memset(set, 0, sizeof set);
  cfg_defaults(&c);
  if (!read_keys(path, &c, set, 1, err, errlen)) return -1;
  for (k = 0; k < sizeof needed / sizeof needed[0]; k++)
    if (set[find_key(needed[k]) - run_keys] == 0 && (k < 3 || afv_own)) {
      afv_errorf(err, errlen, "%s: no %s (afv run writes every key): not "
                 "the whole params.txt of a run", path, needed[k]);
      return -1;
    }
  memset(p, 0, sizeof *p);
  p->afv_run = afv_own;
  p->l = c.l;
  p->v0 = c.v0;
  p->Dr = c.Dr;
  p->dt = c.dt;
  p->steps = set[find_key("steps") - run_keys] ? c.steps : -1;
  p->N = c.N;
  p->frame_every = c.frame_every;
  p->periodic = strcmp(c.box, "periodic") == 0;
  p->L = box_side(&c);
  p->cells = strcmp(c.cells, "none") != 0;
  return 1;
}

/* THE FINGERPRINT of a run, which afv analyze writes into its summary.txt
** and afv collect checks against the run (cli.h): FNV-1a 64 over "id=ID\n"
** and "KEY=VALUE\n" for every key of params.txt as afv run writes it
** (key_text; not the keys the run does not use, key_unused), but quiet and
** checkpoint_every, which change nothing the
** run computes, and cells, a path read relative to where params.txt is
** read from (a run's own copy is always cells.txt).  A summary copied
** from another job (another id, seed or point) or from a run edited since
** has another fingerprint. */
static unsigned long long fnv1a(unsigned long long h, const char *text)
{
  for (; *text; text++) {
    h ^= (unsigned char)*text;
    h *= 0x100000001b3ull;
  }
  return h;
}

int run_fingerprint(const char *path, const char *id, char *out, size_t len,
                    char *err, size_t errlen)
{
  unsigned long long h = fnv1a(0xcbf29ce484222325ull, "id=");
  int set[N_RUN_KEYS], k;
  run_cfg c;
  if (access(path, F_OK) != 0 && errno == ENOENT) return 0;
  memset(set, 0, sizeof set);
  cfg_defaults(&c);
  if (!read_keys(path, &c, set, 1, err, errlen)) return -1;
  h = fnv1a(fnv1a(h, id), "\n");
  for (k = 0; k < N_RUN_KEYS; k++) {
    char value[RUN_PATH_MAX + 32];
    if (!strcmp(run_keys[k].name, "quiet")
        || !strcmp(run_keys[k].name, "checkpoint_every")
        || run_keys[k].kind == K_PATH || key_unused(&c, &run_keys[k]))
      continue;
    key_text(&c, &run_keys[k], value, sizeof value);
    h = fnv1a(fnv1a(fnv1a(fnv1a(h, run_keys[k].name), "="), value), "\n");
  }
  snprintf(out, len, "%016llx", h);
  return 1;
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

