/*
** sweep.c -- afv sweep: a grid of afv run jobs and three runners for it
**
**   afv sweep --out DIR [--seeds K] [--KEY VALUES ...]
**
** VALUES is a:b:step (inclusive range), v1,v2,... (list) or one value
** (fixed).  Every job is one idempotent shell command (jobs.txt), run in
** DIR:
**   ./afv run --config jobs/ID.conf --out runs/ID --continue
**     && ./afv analyze runs/ID `cat analysis.txt`
** so the Makefile, GNU parallel and a SLURM array run the same lines, and
** any of them, stopped at any moment, finishes the sweep when run again.
** DIR/afv is a copy of the program that wrote the sweep: every path is
** relative to DIR, which may be moved.  Before anything is written the
** sweep's CPU time and disk are estimated and printed.
*/
#define _XOPEN_SOURCE 700  /* mkdir, realpath, readlink */
#include "cli.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "sweep.h"


static const char *sweep_usage =
  "usage: afv sweep --out DIR [--seeds K] [--KEY VALUES ...] [options]\n"
  "       afv sweep --reanalyze DIR [--steady-from T] [--lag L]\n"
  "\n"
  "Writes a grid of afv run jobs into DIR (which must not exist yet) and\n"
  "three runners for them; nothing runs until you start one:\n"
  "  make -C DIR -j N                     (nothing to install)\n"
  "  cd DIR && parallel -j N < jobs.txt   (GNU parallel)\n"
  "  sh DIR/slurm.sh [SBATCH OPTIONS]     (SLURM job arrays; see its header)\n"
  "Then afv collect DIR writes the table and the figures.  Every path in\n"
  "the runners is relative to DIR, so DIR may be moved or reached by\n"
  "another path (a cluster's shared file system).\n"
  "\n"
  "Any afv run key may be swept or fixed (afv run --help lists them):\n"
  "  --KEY a:b:step   inclusive range a, a+step, ..., b ((b-a)/step must be\n"
  "                   a whole number; values printed with %.10g)\n"
  "  --KEY v1,v2,...  list\n"
  "  --KEY v          fixed\n"
  "  --seeds K        K replicas per state point, seeds 1..K (default 1),\n"
  "                   unless --seed lists the seeds\n"
  "Two values of a key that are the same number (4, 4.0) or text, a\n"
  "value with a space or a control character, and a value longer than\n"
  AFV_STR(VALUE_LEN_MAX) " bytes (a cells file's absolute path included) are"
  " refused.\n"
  "Options:\n"
  "  --out DIR        the sweep's folder (created with its parents)\n"
  "  --steady-from T  --lag L   passed to afv analyze (steady window, lag\n"
  "                   of D_s in time units) after each run; checked against\n"
  "                   every job's run (steps, dt, frame_every) first\n"
  "  --afv PATH       the afv program copied into DIR/afv, which the\n"
  "                   runners call (default: this one)\n"
  "Cost: before writing anything, afv sweep prints the jobs' estimated CPU\n"
  "time (0.35 us per cell-step on one core, relaxation included) and disk\n"
  "(trajectory.dat: 16 + 20 N bytes a frame; an SVG snapshot: about 0.5 KB\n"
  "a cell).  To cut them: fewer --steps, --N or --seeds; a larger\n"
  "--frame_every (the analysis needs a few hundred frames, not more);\n"
  "--svg_every 0 (only final.svg).  Without --svg_every a job draws at\n"
  "most " AFV_STR(SWEEP_SNAPSHOTS) " snapshots and final.svg (every "
  "max(5000, steps/" AFV_STR(SWEEP_SNAPSHOTS) ") steps).\n"
  "SLURM (slurm.sh; each array task runs its jobs one after the other on\n"
  "one core):\n"
  "  --per-task K     jobs per array task (default 1)\n"
  "  --array-max K    tasks per job array at most (default 1000: SLURM's\n"
  "                   usual MaxArraySize is 1001); more tasks go into\n"
  "                   further arrays, each submitted by slurm.sh\n"
  "  --throttle K     at most K tasks of each array at once (%K of\n"
  "                   sbatch --array; sh slurm.sh --throttle K overrides)\n"
  "  --time T         time limit per task (default: estimated from the\n"
  "                   largest N and steps at 0.35 us per cell-step, x 3\n"
  "                   plus 10 min; printed)\n"
  "  --mem M          memory per task (default: estimated from the largest\n"
  "                   N, at least 256M; printed)\n"
  "  --account A  --partition P   written as #SBATCH lines (else the\n"
  "                   cluster's defaults)\n"
  "DIR gets points.csv (id, swept keys, seed), jobs/ID.conf (every key of\n"
  "a job: afv run --config jobs/ID.conf repeats it alone), jobs.txt (one\n"
  "command a line), analysis.txt (the analysis arguments), afv (a copy of\n"
  "the program: replace it to run the jobs with another build), Makefile,\n"
  "slurm.sh, and, as jobs run, runs/ID/ and logs/ID.log.  A job is\n"
  "idempotent: afv run --continue starts, resumes or leaves its run, then\n"
  "afv analyze writes runs/ID/analysis/.  Every job's keys are checked as\n"
  "afv run checks them, and the start of up to 256 jobs (every value of\n"
  "every key among them) is built, before DIR exists; DIR appears whole.\n"
  "\n"
  "--reanalyze DIR: a new analysis of a sweep's runs, none run again: the\n"
  "new --steady-from and --lag are checked against every job's run, then\n"
  "written to DIR/analysis.txt; run the runner again (make -C DIR -j N\n"
  "analyses every job again, since analysis.txt is newer than its\n"
  "summary), then afv collect DIR, which reports summaries older than\n"
  "analysis.txt.\n"
  "Exit status: 0 written, 2 bad option or value (DIR not created).\n";

/* ---- grid syntax ----------------------------------------------------------- */
/* Parses a whole string as a finite double. */
int whole_double(const char *text, double *v)
{
  char *end;
  errno = 0;
  *v = strtod(text, &end);
  return end != text && !*end && !errno && isfinite(*v);
}

/* a:b:step -> n values a + k step (k = 0 .. n-1), n = round((b-a)/step)+1;
** (b-a)/step must be whole to 1e-6 (so rounding in a or step is harmless
** and the end point is b).  0 with a message in err if malformed. */
static int expand_range(sweep_axis *x, char *err, size_t errlen)
{
  char a_text[VALUE_MAX], b_text[VALUE_MAX], s_text[VALUE_MAX], extra;
  double a, b, step, span;
  long n, k;
  if (strlen(x->text) >= VALUE_MAX
      || sscanf(x->text, "%63[^:]:%63[^:]:%63[^:]%c", a_text, b_text, s_text,
                &extra) != 3
      || !whole_double(a_text, &a) || !whole_double(b_text, &b)
      || !whole_double(s_text, &step)) {
    afv_errorf(err, errlen, "--%s %s: a range is a:b:step with three "
               "numbers", x->key, x->text);
    return 0;
  }
  span = (b - a) / step;
  if (!(step > 0) || b < a || !isfinite(span)) {
    afv_errorf(err, errlen, "--%s %s: a range needs step > 0 and b >= a",
               x->key, x->text);
    return 0;
  }
  if (fabs(span - floor(span + 0.5)) > 1e-6 || span + 1 > SWEEP_MAX_JOBS) {
    afv_errorf(err, errlen, "--%s %s: (b - a)/step = %.10g is not a whole "
               "number of steps%s", x->key, x->text, span,
               span + 1 > SWEEP_MAX_JOBS ? " (or too many)" : "");
    return 0;
  }
  n = (long)floor(span + 0.5) + 1;
  if (!(x->value = malloc((size_t)n * sizeof *x->value))) return 0;
  for (k = 0; k < n; k++)
    snprintf(x->value[k], VALUE_MAX, "%.10g", a + (double)k * step);
  x->n = (int)n;
  return 1;
}

/* "is M bytes long, more than ..." for a value of key longer than a
** sweep's values may be, into buf; returns buf. */
static const char *too_long(const char *key, size_t m, char *buf, size_t len)
{
  snprintf(buf, len, "is %lu bytes long, more than the %d bytes a sweep's "
           "value may have%s", (unsigned long)m, VALUE_LEN_MAX,
           strcmp(key, "cells") ? "" : " (give the file by a shorter "
           "absolute path, such as a symbolic link's)");
  return buf;
}

/* v1,v2,... (or one value) -> the values as given. */
static int expand_list(sweep_axis *x, char *err, size_t errlen)
{
  const char *p = x->text;
  int n = 1, k = 0;
  for (; *p; p++) n += *p == ',';
  if (n > SWEEP_MAX_JOBS || !(x->value = malloc((size_t)n * sizeof *x->value)))
    return 0;
  for (p = x->text; k < n; k++) {
    size_t m = strcspn(p, ",");
    if (m == 0) {
      afv_errorf(err, errlen, "--%s %s: value %d of the list is empty",
                 x->key, x->text, k + 1);
      return 0;
    }
    if (m >= VALUE_MAX) {
      char why[160], which[40] = "the value";
      if (n > 1) snprintf(which, sizeof which, "value %d of the list", k + 1);
      afv_errorf(err, errlen, "--%s %s: %s %s", x->key, x->text, which,
                 too_long(x->key, m, why, sizeof why));
      return 0;
    }
    memcpy(x->value[k], p, m);
    x->value[k][m] = 0;
    p += m + (p[m] == ',');
  }
  x->n = n;
  return 1;
}

/* A value's text: printable characters, no space (a space, a tab or a
** newline would split jobs.txt, points.csv or a job file's line). */
static int plain_value(const char *v)
{
  for (; *v; v++)
    if ((unsigned char)*v <= ' ' || (unsigned char)*v >= 0x7f) return 0;
  return 1;
}

/* qsort has no context argument in C99: the axis of the sort in progress. */
static const sweep_axis *sort_axis;

/* Two values of an axis by index: as numbers when both are, else as text
** (so 4, 4.0 and 4.00 are one value). */
static int cmp_axis_value(const void *pa, const void *pb)
{
  const char *a = sort_axis->value[*(const int *)pa];
  const char *b = sort_axis->value[*(const int *)pb];
  double x, y;
  if (whole_double(a, &x) && whole_double(b, &y)) return (x > y) - (x < y);
  return strcmp(a, b);
}

/* 0 with a message if two values of x are the same state (equal numbers,
** or equal text): a repeated value would repeat its jobs. */
static int distinct_values(const sweep_axis *x, char *err, size_t errlen)
{
  int *order = malloc((size_t)x->n * sizeof *order), k, ok = 1;
  if (!order) {
    afv_errorf(err, errlen, "--%s: out of memory", x->key);
    return 0;
  }
  for (k = 0; k < x->n; k++) order[k] = k;
  sort_axis = x;
  qsort(order, (size_t)x->n, sizeof *order, cmp_axis_value);
  for (k = 1; k < x->n && ok; k++)
    if (cmp_axis_value(&order[k - 1], &order[k]) == 0) {
      int a = order[k - 1] < order[k] ? order[k - 1] : order[k];
      int b = order[k - 1] ^ order[k] ^ a;
      afv_errorf(err, errlen, "--%s %.80s: values %d and %d (%s, %s) are the "
                 "same%s", x->key, x->text, a + 1, b + 1, x->value[a],
                 x->value[b], strchr(x->text, ':') ? " at 10 digits (a step "
                 "too small for the range)" : ": each value once");
      ok = 0;
    }
  free(order);
  return ok;
}

/* Expands x->text into values and checks each as afv run would, and that
** no two are the same. */
static int sweep_axis_parse(sweep_axis *x, char *err, size_t errlen)
{
  char msg[RUN_PATH_MAX];
  int k;
  x->n = 0;
  x->value = NULL;
  if (!plain_value(x->text)) {
    afv_errorf(err, errlen, "--%s: the value holds a space, a tab, a newline "
               "or another control character", x->key);
    return 0;
  }
  if (!(strchr(x->text, ':') ? expand_range(x, err, errlen)
        : expand_list(x, err, errlen))) {
    if (!err[0]) afv_errorf(err, errlen, "--%s: out of memory", x->key);
    return 0;
  }
  for (k = 0; k < x->n; k++)
    if (!run_key_check(x->key, x->value[k], msg, sizeof msg)) {
      afv_errorf(err, errlen, "--%s %s: %s", x->key, x->text, msg);
      return 0;
    }
  return distinct_values(x, err, errlen);
}

/* ---- options -------------------------------------------------------------- */
static void free_opts(sweep_opts *o)
{
  int k;
  for (k = 0; k < o->nax; k++) free(o->ax[k].value);
}

/* A positive integer option value. */
static int count_value(const char *opt, const char *text, long *out)
{
  char *end;
  errno = 0;
  *out = strtol(text, &end, 10);
  if (end == text || *end || errno || *out < 1 || *out > SWEEP_MAX_JOBS) {
    fprintf(stderr, "afv sweep: %s '%s': expected an integer in 1 .. %d\n",
            opt, text, SWEEP_MAX_JOBS);
    return 0;
  }
  return 1;
}

/* A SLURM resource value: characters of kind ("word": letters, digits,
** _.-; "mem": digits then one of KMGT; "time": digits, ':' and '-'). */
static int slurm_value(const char *opt, const char *val, const char *kind,
                       const char **out)
{
  const char *word = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                     "0123456789_.-";
  size_t m = strlen(val);
  int ok = m > 0 && m < VALUE_MAX;
  if (!strcmp(kind, "word")) ok = ok && strspn(val, word) == m;
  else if (!strcmp(kind, "mem"))
    ok = ok && strspn(val, "0123456789") >= m - (strchr("KMGT", val[m - 1])
                                                 && m > 1);
  else ok = ok && strspn(val, "0123456789:-") == m && isdigit((unsigned char)val[0]);
  if (!ok)
    return !fprintf(stderr, "afv sweep: %s '%s': expected %s\n", opt, val,
                    !strcmp(kind, "word") ? "letters, digits and _.- only"
                    : !strcmp(kind, "mem") ? "a size such as 2000M or 4G"
                    : "a SLURM time such as 90, 2:30:00 or 1-12:00:00");
  *out = val;
  return 1;
}

/* --steady-from, --lag: numbers >= 0 (> 0 for --lag). */
static int analysis_value(sweep_opts *o, const char *opt, const char *val)
{
  double d;
  int lag = !strcmp(opt, "--lag");
  if (!whole_double(val, &d) || d < 0 || (lag && d == 0))
    return !fprintf(stderr, "afv sweep: %s '%s': expected a number %s 0\n",
                    opt, val, lag ? ">" : ">=");
  if (lag) o->lag = val;
  else o->steady_from = val;
  return 1;
}

/* One option with its value; 0 on a bad one (message printed). */
static int sweep_option(sweep_opts *o, const char *opt, const char *val)
{
  char err[2 * RUN_PATH_MAX] = "";
  int k;
  if (!strcmp(opt, "--out")) o->out = val;
  else if (!strcmp(opt, "--reanalyze")) o->reanalyze = val;
  else if (!strcmp(opt, "--afv")) o->afv = val;
  else if (!strcmp(opt, "--seeds")) return count_value(opt, val, &o->seeds);
  else if (!strcmp(opt, "--per-task"))
    return count_value(opt, val, &o->per_task);
  else if (!strcmp(opt, "--array-max"))
    return count_value(opt, val, &o->array_max);
  else if (!strcmp(opt, "--throttle"))
    return count_value(opt, val, &o->throttle);
  else if (!strcmp(opt, "--account"))
    return slurm_value(opt, val, "word", &o->account);
  else if (!strcmp(opt, "--partition"))
    return slurm_value(opt, val, "word", &o->partition);
  else if (!strcmp(opt, "--mem")) return slurm_value(opt, val, "mem", &o->mem);
  else if (!strcmp(opt, "--time"))
    return slurm_value(opt, val, "time", &o->time);
  else if (!strcmp(opt, "--steady-from") || !strcmp(opt, "--lag"))
    return analysis_value(o, opt, val);
  else {
    sweep_axis *x = &o->ax[o->nax];
    for (k = 0; k < o->nax; k++)
      if (!strcmp(o->ax[k].key, opt + 2))
        return !fprintf(stderr, "afv sweep: %s given twice\n", opt);
    if (o->nax == SWEEP_MAX_KEYS)
      return !fprintf(stderr, "afv sweep: more than %d keys\n",
                      SWEEP_MAX_KEYS);
    x->key = opt + 2;
    x->text = val;
    o->nax++;
    if (!run_key_check(x->key, "0", err, sizeof err) && strstr(err, "unknown"))
      return !unknown_option(opt, sweep_usage, run_option_names());
    err[0] = 0;
    if (!sweep_axis_parse(x, err, sizeof err))
      return !fprintf(stderr, "afv sweep: %s\n", err);
    if (!strcmp(x->key, "seed")) o->seed_axis = o->nax - 1;
  }
  return 1;
}

/* Parses argv; -1 after --help, 0 on bad input (message printed). */
static int sweep_parse(int argc, char **argv, sweep_opts *o)
{
  int k;
  memset(o, 0, sizeof *o);
  o->seed_axis = -1;
  o->per_task = 1;
  o->array_max = SLURM_ARRAY_MAX;
  for (k = 1; k < argc; k += 2) {
    if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
      fputs(sweep_usage, stdout);
      return -1;
    }
    if (strncmp(argv[k], "--", 2) != 0 || !argv[k][2])
      return !fprintf(stderr, "afv sweep: unexpected '%s' (options are "
                      "--KEY VALUE; see afv sweep --help)\n", argv[k]);
    if (k + 1 >= argc)
      return !fprintf(stderr, "afv sweep: %s needs a value\n", argv[k]);
    if (!sweep_option(o, argv[k], argv[k + 1])) return 0;
  }
  if (o->reanalyze)
    return o->out || o->nax || o->seeds || o->afv
           ? !bad_input("sweep: --reanalyze DIR takes --steady-from and --lag "
                        "only (the runs stay as they are)") : 1;
  if (!o->out) return !bad_input("sweep: --out DIR is required");
  if (o->seeds && o->seed_axis >= 0)
    return !bad_input("sweep: give --seeds K or --seed LIST, not both");
  return 1;
}

/* ---- the grid -------------------------------------------------------------- */

static int grid_make(sweep_grid *g, const sweep_opts *o)
{
  int k;
  memset(g, 0, sizeof *g);
  for (k = 0; k < o->nax; k++)
    if (k != o->seed_axis) g->ax[g->nax++] = &o->ax[k];
  if (o->seed_axis >= 0) g->ax[g->nax++] = &o->ax[o->seed_axis];
  else {
    long s, n = o->seeds ? o->seeds : 1;
    g->seeds.key = "seed";
    g->seeds.text = "--seeds";
    if (!(g->seeds.value = malloc((size_t)n * sizeof *g->seeds.value)))
      return !bad_input("sweep: out of memory");
    for (s = 0; s < n; s++) snprintf(g->seeds.value[s], VALUE_MAX, "%ld", s + 1);
    g->seeds.n = (int)n;
    g->ax[g->nax++] = &g->seeds;
  }
  g->njobs = 1;
  for (k = 0; k < g->nax; k++) {
    g->njobs *= g->ax[k]->n;
    if (g->njobs > SWEEP_MAX_JOBS) {
      fprintf(stderr, "afv sweep: more than %d jobs\n", SWEEP_MAX_JOBS);
      return 0;
    }
  }
  return 1;
}

/* Values of job j (0-based), one per axis of g, into names/values. */
void job_values(const sweep_grid *g, long j, const char **names,
                       const char **values)
{
  int k;
  for (k = g->nax - 1; k >= 0; k--) {
    names[k] = g->ax[k]->key;
    values[k] = g->ax[k]->value[j % g->ax[k]->n];
    j /= g->ax[k]->n;
  }
}

/* 1 if axis k of g is swept (seed: never a swept key of points.csv). */
int swept(const sweep_grid *g, int k)
{
  return g->ax[k]->n > 1 && strcmp(g->ax[k]->key, "seed") != 0;
}

/* ---- runners ---------------------------------------------------------------- */
/* The runners hold paths unquoted, so paths are kept to characters no
** shell or make treats specially. */
static int plain_path(const char *what, const char *p)
{
  const char *ok = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                   "0123456789._-/+@,=~";
  if (strspn(p, ok) == strlen(p)) return 1;
  fprintf(stderr, "afv sweep: %s '%s': the runners need a path of letters, "
          "digits and ._-/+@,=~ only\n", what, p);
  return 0;
}

/* argv[0] as a path: itself if it names a folder, else the first
** executable of that name along PATH.  0 if none. */
static int program_path(const char *argv0, char *out)
{
  char buf[PATH_MAX];
  const char *dirs = getenv("PATH");
  if (strchr(argv0, '/')) return realpath(argv0, out) != NULL;
  while (dirs && *dirs) {
    size_t m = strcspn(dirs, ":");
    if (m == 0) snprintf(buf, sizeof buf, "./%s", argv0);  /* "::": cwd */
    else snprintf(buf, sizeof buf, "%.*s/%s", (int)m, dirs, argv0);
    if (access(buf, X_OK) == 0 && realpath(buf, out)) return 1;
    dirs += m + (dirs[m] == ':');
  }
  return 0;
}

/* The absolute path of this afv program (or of --afv), into out: the
** runners call it.  Linux names the running program in /proc/self/exe;
** elsewhere argv[0] is resolved. */
static int afv_program(const char *given, char *out)
{
  char buf[PATH_MAX];
  ssize_t m;
  if (given) {
    if (!realpath(given, out) || access(out, X_OK) != 0) {
      fprintf(stderr, "afv sweep: --afv %s: not an executable file\n", given);
      return 0;
    }
    return 1;
  }
  m = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (m > 0) {
    buf[m] = 0;
    snprintf(out, PATH_MAX, "%s", buf);
    return 1;
  }
  if (program_path(program_name, out)) return 1;
  fprintf(stderr, "afv sweep: cannot find the afv program's path: give "
          "--afv PATH\n");
  return 0;
}

/* Job id's command line (no newline), run in the sweep's folder: paths,
** the program's too (SWEEP_PROGRAM), are relative to it, and the analysis
** arguments are read from analysis.txt when the job runs (afv sweep
** --reanalyze changes them). */
static void job_command(char *cmd, size_t len, const char *id)
{
  snprintf(cmd, len, "%s run --config jobs/%s.conf --out runs/%s --continue "
           "2>>logs/%s.log && %s analyze runs/%s `cat analysis.txt` "
           ">logs/%s.out 2>>logs/%s.log", SWEEP_PROGRAM, id, id, id,
           SWEEP_PROGRAM, id, id, id);
}

/* Copies the program at path into dir/afv (mode 0755): the runners call
** it by a path relative to the sweep.  0 on failure (message printed). */
static int copy_program(const char *path, const char *dir)
{
  char to[PATH_MAX + 64], tmp[PATH_MAX + 128], buf[1 << 16];
  FILE *in = fopen(path, "rb"), *out = NULL;
  size_t m;
  int ok = in != NULL;
  snprintf(to, sizeof to, "%s/afv", dir);
  if (ok) ok = (out = afv_atomic_open(to, tmp, sizeof tmp)) != NULL;
  while (ok && (m = fread(buf, 1, sizeof buf, in)) > 0)
    ok = fwrite(buf, 1, m, out) == m;
  ok = ok && !ferror(in) && chmod(tmp, 0755) == 0;
  if (in) fclose(in);
  if (out && (!ok || afv_atomic_commit(out, tmp, to) != AFV_OK)) {
    if (!ok) fclose(out);
    remove(tmp);
    ok = 0;
  }
  if (!ok) fprintf(stderr, "afv sweep: cannot copy %s to %s: %s\n", path, to,
                   strerror(errno));
  return ok;
}

/* Job j's id: 0001 .. 9999, or six digits for bigger sweeps (at most
** SWEEP_MAX_JOBS), so that ids sort as the jobs. */
static void job_id(char *id, long j, long njobs)
{
  snprintf(id, 16, njobs < 10000 ? "%04ld" : "%06ld", (j + 1) % 1000000);
}

/* Writes one file atomically through fn; 0 on failure (message printed). */
typedef void (*sweep_writer)(FILE *fp, const sweep_grid *g,
                             const sweep_opts *o, const char *afv);
static int write_file(const char *dir, const char *name, sweep_writer fn,
                      const sweep_grid *g, const sweep_opts *o,
                      const char *afv)
{
  char path[PATH_MAX + 64], tmp[PATH_MAX + 128];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))
      || (fn(fp, g, o, afv), afv_atomic_commit(fp, tmp, path)) != AFV_OK) {
    fprintf(stderr, "afv sweep: %s: cannot write\n", path);
    return 0;
  }
  return 1;
}

static void write_points(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                         const char *afv)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char id[16];
  long j;
  int k;
  (void)o; (void)afv;
  fputs("id", fp);
  for (k = 0; k < g->nax; k++)
    if (swept(g, k)) fprintf(fp, ",%s", g->ax[k]->key);
  fputs(",seed\n", fp);
  for (j = 0; j < g->njobs; j++) {
    job_values(g, j, names, values);
    job_id(id, j, g->njobs);
    fputs(id, fp);
    for (k = 0; k < g->nax; k++)
      if (swept(g, k)) fprintf(fp, ",%s", values[k]);
    fprintf(fp, ",%s\n", values[g->nax - 1]);
  }
}

static void write_jobs(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                       const char *afv)
{
  char id[16], cmd[4 * PATH_MAX];
  long j;
  (void)o; (void)afv;
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    job_command(cmd, sizeof cmd, id);
    fprintf(fp, "%s\n", cmd);
  }
}

/* The analysis arguments of every job: --steady-from and --lag as given
** (afv analyze's defaults where not). */
static void write_analysis(FILE *fp, const sweep_grid *g,
                           const sweep_opts *o, const char *afv)
{
  (void)g; (void)afv;
  if (o->steady_from) fprintf(fp, "--steady-from %s ", o->steady_from);
  if (o->lag) fprintf(fp, "--lag %s", o->lag);
  fputs("\n", fp);
}

static void write_makefile(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                           const char *afv)
{
  char id[16], cmd[4 * PATH_MAX];
  long j;
  (void)o; (void)afv;
  fprintf(fp, "# afv sweep: %ld jobs.  make -C DIR -j N runs them, N at a "
          "time.\n# A job is done when runs/ID/analysis/summary.txt exists "
          "and is newer\n# than analysis.txt (afv sweep --reanalyze "
          "rewrites it); make run again\n# (after a crash, a kill, or a "
          "change of machine) does what is missing.\n# --keep-going: a "
          "failed job (see logs/ID.log) does not stop the others;\n# afv "
          "collect lists it in missing.txt.\nMAKEFLAGS += --keep-going\n\n"
          ".PHONY: all\nall:", g->njobs);
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    fprintf(fp, " \\\n  runs/%s/analysis/summary.txt", id);
  }
  fputs("\n", fp);
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    job_command(cmd, sizeof cmd, id);
    fprintf(fp, "\nruns/%s/analysis/summary.txt: analysis.txt\n\t%s\n", id,
            cmd);
  }
}

/* ---- checks before anything is created ------------------------------------- */
/* At most this many jobs have their start built and its forces checked
** (the relaxation's first step, as afv run does): every value of every
** key among them when there are fewer values. */
#define START_CHECKS 256

/* Checks the start of a spread of jobs that holds every value of every
** axis (or START_CHECKS of them, evenly spread); 0 on the first bad one
** (the message names its values).  Every job's keys together are checked
** when its file is written. */
static int check_starts(const sweep_grid *g)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char err[2 * RUN_PATH_MAX];
  long most = 1, c, n;
  int k;
  for (k = 0; k < g->nax; k++)
    if (g->ax[k]->n > most) most = g->ax[k]->n;
  n = most < START_CHECKS ? most : START_CHECKS;
  for (c = 0; c < n; c++) {
    long v = c * most / n, j = 0;
    /* job with value v mod n_k on every axis k (first axis slowest) */
    for (k = 0; k < g->nax; k++) j = j * g->ax[k]->n + v % g->ax[k]->n;
    job_values(g, j, names, values);
    if (!run_config_write(NULL, g->nax, names, values, err, sizeof err)) {
      fprintf(stderr, "afv sweep: job");
      for (k = 0; k < g->nax; k++)
        fprintf(stderr, " %s=%s", names[k], values[k]);
      fprintf(stderr, ": %s\n", err);
      return 0;
    }
  }
  return 1;
}

/* The analysis (--steady-from from, --lag lag if lag_given) fits a run of
** steps steps of dt with a frame every `every` steps (frames at steps 0,
** every, 2 every, ... <= steps, at t = step dt, as afv analyze reads
** them): the steady window holds 2 frames, the lag lies within it and is
** no shorter than a frame interval.  0 with the reason in err. */
static int analysis_fits(double steps, double dt, double every, double from,
                         double lag, int lag_given, char *err, size_t errlen)
{
  double last, first;
  if (!(every > 0)) {
    afv_errorf(err, errlen, "frame_every %g: the run writes no trajectory to "
               "analyze", every);
    return 0;
  }
  last = floor(steps / every) * every * dt;
  /* the first frame at t >= from: step k every, k from its estimate up */
  first = fmax(0, floor(from / (every * dt)) - 1);
  while (first * every * dt < from) first++;
  first *= every * dt;
  if (!(first < last)) {
    afv_errorf(err, errlen, "--steady-from %g: the run ends at t = %g (steps "
               "%.0f, dt %g, a frame every %.0f steps): the steady window "
               "needs 2 frames or more", from, last, steps, dt, every);
    return 0;
  }
  if (lag_given && (lag > (last - first) * (1 + 1e-9)
                    || lag < 0.5 * every * dt)) {
    afv_errorf(err, errlen, "--lag %g: the steady window t = %g .. %g (steps "
               "%.0f, dt %g, a frame every %.0f steps) holds lags %g .. %g "
               "only", lag, first, last, steps, dt, every, every * dt,
               last - first);
    return 0;
  }
  return 1;
}

/* The value of key for job j: its axis value if the key is swept or
** fixed, else def. */
double job_number(const sweep_grid *g, long j, const char *key,
                  double def)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  double v;
  int k;
  job_values(g, j, names, values);
  for (k = 0; k < g->nax; k++)
    if (!strcmp(names[k], key)) return whole_double(values[k], &v) ? v : def;
  return def;
}

/* Reads steps, dt, frame_every and N of a job file into v[0..3]. */
static int job_file_numbers(const char *path, double *v)
{
  static const char *key[] = {"steps", "dt", "frame_every", "N"};
  int k;
  for (k = 0; k < 4; k++)
    if (run_param(path, key[k], &v[k]) != 1) return 0;
  return 1;
}

/* Every job's analysis fits its run (analysis_fits); the largest N and
** steps into g (for the SLURM time).  dir/jobs/ID.conf of the first job
** gives the keys not given. */
static int check_analysis(sweep_grid *g, const sweep_opts *o, const char *dir)
{
  char path[PATH_MAX + 64], id[16], err[1024];
  double d[4], from = 0, lag = 0;
  long j;
  job_id(id, 0, g->njobs);
  snprintf(path, sizeof path, "%s/jobs/%s.conf", dir, id);
  if (!job_file_numbers(path, d))
    return !fprintf(stderr, "afv sweep: %s: cannot read steps, dt, "
                    "frame_every, N\n", path);
  if (o->steady_from) whole_double(o->steady_from, &from);
  if (o->lag) whole_double(o->lag, &lag);
  for (j = 0; j < g->njobs; j++) {
    double steps = job_number(g, j, "steps", d[0]);
    double n = job_number(g, j, "N", d[3]);
    if (steps > g->max_steps) g->max_steps = steps;
    if (n > g->max_cells) g->max_cells = n;
    if (!analysis_fits(steps, job_number(g, j, "dt", d[1]),
                       job_number(g, j, "frame_every", d[2]), from, lag,
                       o->lag != NULL, err, sizeof err)) {
      job_id(id, j, g->njobs);
      return !fprintf(stderr, "afv sweep: %s (job %s)\n", err, id);
    }
  }
  return 1;
}

/* ---- the sweep's folder ------------------------------------------------------ */
/* The absolute path out will have, without creating anything: the real
** path of its deepest existing ancestor and the rest; 0 (message printed)
** if out exists, its ancestor is not a folder, or the rest holds "." or
** "..". */
static int future_path(const char *out, char *abs)
{
  char head[PATH_MAX], real[PATH_MAX];
  const char *rest;
  struct stat sb;
  size_t m = strlen(out);
  if (m == 0 || m >= PATH_MAX - 64) return !bad_input("sweep: --out: empty "
                                                      "or too long");
  if (stat(out, &sb) == 0)
    return !fprintf(stderr, "afv sweep: %s exists: choose a new --out (to "
                    "finish a sweep, run its runner again)\n", out);
  snprintf(head, sizeof head, "%s", out);
  while (m > 1 && head[m - 1] == '/') head[--m] = 0;
  for (;;) {
    char *slash = strrchr(head, '/');
    if (!slash) { snprintf(head, sizeof head, "."); break; }
    if (slash == head) { head[1] = 0; break; }
    *slash = 0;
    if (stat(head, &sb) == 0) break;
  }
  if (stat(head, &sb) != 0 || !S_ISDIR(sb.st_mode) || !realpath(head, real))
    return !fprintf(stderr, "afv sweep: --out %s: %s is not a folder\n", out,
                    head);
  rest = !strcmp(head, ".") && out[0] != '.' ? out : out + strlen(head);
  while (*rest == '/') rest++;
  if (!strcmp(head, ".") && !strncmp(out, "./", 2)) rest = out + 2;
  {
    char r[PATH_MAX], *c;
    snprintf(r, sizeof r, "/%s/", rest);
    for (c = r; (c = strstr(c, "/.")) != NULL; c++)
      if (c[2] == '/' || (c[2] == '.' && c[3] == '/'))
        return !fprintf(stderr, "afv sweep: --out %s: '.' or '..' in the "
                        "part of the path that does not exist yet\n", out);
  }
  if (strlen(real) + strlen(rest) + 2 > RUN_PATH_MAX - 64)
    return !bad_input("sweep: --out: path too long");
  strcpy(abs, real);
  if (strcmp(real, "/")) strcat(abs, "/");
  strcat(abs, rest);
  m = strlen(abs);
  while (m > 1 && abs[m - 1] == '/') abs[--m] = 0;
  return 1;
}

/* mkdir -p path: the folders it created into made (at most max; the
** count into *nmade, outermost first). */
static int make_dirs(const char *path, char (*made)[PATH_MAX], int max,
                     int *nmade)
{
  char p[PATH_MAX];
  size_t k;
  snprintf(p, sizeof p, "%s", path);
  for (k = 1; ; k++) {
    if (p[k] && (p[k] != '/' || p[k - 1] == '/')) continue;
    {
      char c = p[k];
      p[k] = 0;
      if (mkdir(p, 0777) == 0 && *nmade < max)
        snprintf(made[(*nmade)++], PATH_MAX, "%s", p);
      else if (errno != EEXIST) {
        fprintf(stderr, "afv sweep: cannot create %s: %s\n", p,
                strerror(errno));
        return 0;
      }
      if (!(p[k] = c)) return 1;
    }
  }
}

/* The files and folders a sweep holds when written (removed again if the
** sweep cannot be written whole). */
static const char *sweep_files[] = {"points.csv", "jobs.txt", "analysis.txt",
                                    "Makefile", "slurm.sh", "afv"};
static const char *sweep_dirs[] = {"jobs", "runs", "logs"};
#define N_OF(a) ((int)(sizeof a / sizeof a[0]))

/* 1 if name is NAME or its temporary NAME.PID.RAND.tmp (afv_atomic_open),
** name and NAME differing from byte m on. */
static int is_or_temporary_of(const char *name, size_t m)
{
  return name[m] == 0 || (name[m] == '.' && strstr(name + m, ".tmp") != NULL);
}

/* 1 if name is one afv sweep writes in jobs/: DIGITS.conf or its temporary. */
static int sweep_job_file(const char *name)
{
  size_t m = strspn(name, "0123456789");
  return m > 0 && strncmp(name + m, ".conf", 5) == 0
         && is_or_temporary_of(name, m + 5);
}

/* 1 if name is one afv sweep writes at the top of a sweep folder (a
** sweep_files name) or its temporary. */
static int sweep_top_file(const char *name)
{
  int k;
  for (k = 0; k < N_OF(sweep_files); k++) {
    size_t m = strlen(sweep_files[k]);
    if (strncmp(name, sweep_files[k], m) == 0 && is_or_temporary_of(name, m))
      return 1;
  }
  return 0;
}

/* Removes what a sweep being written in dir holds (afv sweep's file names
** in dir and dir/jobs, and their temporaries), then its empty folders and
** dir: a folder holding anything else (a user's file) stays. */
static void remove_writing_folder(const char *dir)
{
  char sub[PATH_MAX + 320];
  int k;
  snprintf(sub, sizeof sub, "%s/jobs", dir);
  remove_named(sub, sweep_job_file);
  remove_named(dir, sweep_top_file);
  for (k = 0; k < N_OF(sweep_dirs); k++) {
    snprintf(sub, sizeof sub, "%s/%s", dir, sweep_dirs[k]);
    rmdir(sub);
  }
  rmdir(dir);
}

/* A killed afv sweep (SIGKILL cannot be caught) leaves its DIR.writing-PID
** folder (46 MB for a large grid).  The next sweep to DIR removes every
** such folder whose process is gone (kill(PID, 0): ESRCH), as a sweep
** that cannot be written whole removes its own (remove_writing_folder). */
static void remove_stale_writing(const char *dir)
{
  char parent[PATH_MAX], path[PATH_MAX + 300];
  const char *slash = strrchr(dir, '/'), *base = slash ? slash + 1 : dir;
  size_t m = strlen(base);
  DIR *d;
  struct dirent *e;
  snprintf(parent, sizeof parent, "%.*s", slash ? (int)(slash - dir) + 1
           : 1, slash ? dir : ".");
  if (!(d = opendir(parent))) return;
  while ((e = readdir(d)) != NULL) {
    const char *pid = e->d_name + m + 9;   /* after "BASE.writing-" */
    if (strncmp(e->d_name, base, m) != 0
        || strncmp(e->d_name + m, ".writing-", 9) != 0 || !*pid
        || strspn(pid, "0123456789") != strlen(pid) || strlen(pid) > 9
        || kill((pid_t)atol(pid), 0) == 0 || errno != ESRCH)
      continue;
    snprintf(path, sizeof path, "%s/%s", parent, e->d_name);
    remove_writing_folder(path);
  }
  closedir(d);
}

static int write_job_configs(const sweep_grid *g, const char *dir)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char path[PATH_MAX + 64], id[16], err[2 * RUN_PATH_MAX];
  long j;
  int k;
  for (j = 0; j < g->njobs; j++) {
    job_values(g, j, names, values);
    job_id(id, j, g->njobs);
    snprintf(path, sizeof path, "%s/jobs/%s.conf", dir, id);
    if (!run_config_write(path, g->nax, names, values, err, sizeof err)) {
      fprintf(stderr, "afv sweep: job %s (", id);
      for (k = 0; k < g->nax; k++)
        fprintf(stderr, "%s%s=%s", k ? " " : "", names[k], values[k]);
      fprintf(stderr, "): %s\n", err);
      return 0;
    }
  }
  return 1;
}

/* Writes the sweep into tmp (a new folder beside dir), checks every job's
** keys and analysis on the way, then renames tmp to dir: a sweep is there
** whole or not at all. */
static int write_sweep(sweep_grid *g, const sweep_opts *o, const char *afv,
                       const char *dir)
{
  char tmp[RUN_PATH_MAX], p[RUN_PATH_MAX + 16];
  int k, ok;
  snprintf(tmp, sizeof tmp, "%.*s.writing-%ld", RUN_PATH_MAX - 64, dir,
           (long)getpid());
  remove_stale_writing(dir);
  if (mkdir(tmp, 0777) != 0)
    return !fprintf(stderr, "afv sweep: cannot create %s: %s\n", tmp,
                    strerror(errno));
  for (k = 0, ok = 1; ok && k < N_OF(sweep_dirs); k++) {
    snprintf(p, sizeof p, "%s/%s", tmp, sweep_dirs[k]);
    if (mkdir(p, 0777) != 0)
      ok = !fprintf(stderr, "afv sweep: cannot create %s: %s\n", p,
                    strerror(errno));
  }
  ok = ok && copy_program(afv, tmp) && write_job_configs(g, tmp)
       && check_analysis(g, o, tmp)
       && write_file(tmp, "points.csv", write_points, g, o, afv)
       && write_file(tmp, "jobs.txt", write_jobs, g, o, afv)
       && write_file(tmp, "analysis.txt", write_analysis, g, o, afv)
       && write_file(tmp, "Makefile", write_makefile, g, o, afv)
       && write_file(tmp, "slurm.sh", write_slurm, g, o, afv);
  if (ok && rename(tmp, dir) != 0)
    ok = !fprintf(stderr, "afv sweep: cannot rename %s to %s: %s\n", tmp, dir,
                  strerror(errno));
  if (!ok) remove_writing_folder(tmp);
  return ok;
}

/* Relative cells paths become absolute (the job files live elsewhere). */
static int absolute_cells(sweep_opts *o, char *buf)
{
  int k, v;
  for (k = 0; k < o->nax; k++) {
    sweep_axis *x = &o->ax[k];
    for (v = 0; !strcmp(x->key, "cells") && v < x->n; v++) {
      if (x->value[v][0] == '/' || !strcmp(x->value[v], "none")) continue;
      if (!realpath(x->value[v], buf)) {
        fprintf(stderr, "afv sweep: --cells %s: %s\n", x->value[v],
                strerror(errno));
        return 0;
      }
      if (strlen(buf) >= VALUE_MAX) {   /* the jobs name it by this path */
        char why[160];
        fprintf(stderr, "afv sweep: --cells %s: its absolute path %s %s\n",
                x->value[v], buf, too_long("cells", strlen(buf), why,
                                           sizeof why));
        return 0;
      }
      snprintf(x->value[v], VALUE_MAX, "%s", buf);
    }
  }
  return 1;
}

/* ---- afv sweep --reanalyze DIR ------------------------------------------------ */
/* Checks the new analysis against every job of the sweep in dir (its
** jobs/ID.conf, by the ids of points.csv), then rewrites dir/analysis.txt;
** the runners then analyse every run again (make: summary.txt older than
** analysis.txt), and rerun none. */
static int reanalyze(const sweep_opts *o)
{
  char path[PATH_MAX + 64], line[4096], err[1024];
  double d[4], from = 0, lag = 0;
  long n = 0, lineno = 1;
  FILE *fp;
  struct stat sb;
  snprintf(path, sizeof path, "%s/analysis.txt", o->reanalyze);
  if (strlen(o->reanalyze) > PATH_MAX - 128 || stat(path, &sb) != 0)
    return fprintf(stderr, "afv sweep: --reanalyze %s: no analysis.txt: not "
                   "a sweep (or one written by an older afv sweep)\n",
                   o->reanalyze), EXIT_BAD_INPUT;
  if (o->steady_from) whole_double(o->steady_from, &from);
  if (o->lag) whole_double(o->lag, &lag);
  snprintf(path, sizeof path, "%s/points.csv", o->reanalyze);
  if (stat(path, &sb) != 0 || !S_ISREG(sb.st_mode) || !(fp = fopen(path, "r")))
    return fprintf(stderr, "afv sweep: %s: cannot read\n", path),
           EXIT_BAD_INPUT;
  fgets(line, sizeof line, fp);
  while (fgets(line, sizeof line, fp)) {
    char conf[PATH_MAX + 96];
    size_t m = strcspn(line, ",\r\n");
    lineno++;
    line[m] = 0;
    snprintf(conf, sizeof conf, "%s/jobs/%s.conf", o->reanalyze, line);
    if (!m || strchr(line, '/') || !job_file_numbers(conf, d)) {
      fclose(fp);
      return fprintf(stderr, "afv sweep: %s:%ld: no job file %s with steps, "
                     "dt, frame_every\n", path, lineno, conf), EXIT_BAD_INPUT;
    }
    if (!analysis_fits(d[0], d[1], d[2], from, lag, o->lag != NULL, err,
                       sizeof err)) {
      fclose(fp);
      return fprintf(stderr, "afv sweep: %s (job %s)\n", err, line),
             EXIT_BAD_INPUT;
    }
    n++;
  }
  fclose(fp);
  if (!write_file(o->reanalyze, "analysis.txt", write_analysis, NULL, o, ""))
    return EXIT_BAD_INPUT;
  printf("%ld jobs of %s will be analysed with '%s%s%s%s' when their "
         "runner runs again:\n  make -C %s -j 2   (or cd %s && parallel -j 2 "
         "< jobs.txt, or sh %s/slurm.sh)\nthen: afv collect %s\n", n,
         o->reanalyze, o->steady_from ? "--steady-from " : "",
         o->steady_from ? o->steady_from : "", o->lag ? " --lag " : "",
         o->lag ? o->lag : "", o->reanalyze, o->reanalyze, o->reanalyze,
         o->reanalyze);
  return 0;
}

int cmd_sweep(int argc, char **argv)
{
  sweep_opts o;
  sweep_grid g;
  char afv[PATH_MAX], dir[PATH_MAX], made[16][PATH_MAX], est[32];
  sweep_cost cost;
  int m = sweep_parse(argc, argv, &o), ok, nmade = 0;
  if (m <= 0) {
    free_opts(&o);
    return m < 0 ? 0 : EXIT_BAD_INPUT;
  }
  if (o.reanalyze) return reanalyze(&o);
  ok = bound_snapshots(&o) && grid_make(&g, &o) && absolute_cells(&o, dir)
       && future_path(o.out, dir) && plain_path("--out", dir)
       && (strlen(dir) < RUN_PATH_MAX - 64 || !bad_input("sweep: --out: path "
                                                          "too long"))
       && afv_program(o.afv, afv) && plain_path("--afv", afv)
       && check_starts(&g);
  if (ok) {
    sweep_cost_of(&g, &cost);
    print_cost(&cost, g.njobs);
  }
  /* only now is anything created: the parents, then the sweep whole */
  if (ok) {
    char parent[PATH_MAX];
    snprintf(parent, sizeof parent, "%s", dir);
    *strrchr(parent, '/') = 0;
    ok = make_dirs(parent[0] ? parent : "/", made, 16, &nmade)
         && write_sweep(&g, &o, afv, dir);
    while (!ok && nmade > 0) rmdir(made[--nmade]);
  }
  if (ok) {
    double sec = estimate_time(&g, &o, est, sizeof est);
    char mem[32];
    snprintf(mem, sizeof mem, "%ldM", estimate_mem_mb(&g));
    printf("%ld jobs in %s; run them with one of\n  make -C %s -j 2\n  "
           "cd %s && parallel -j 2 < jobs.txt\n  sh %s/slurm.sh   (SLURM: "
           "%ld job array(s), --time %s%s, --mem %s%s per task%s)\nthen: "
           "afv collect %s\n", g.njobs, dir, dir, dir, dir,
           ((g.njobs + o.per_task - 1) / o.per_task + o.array_max - 1)
           / o.array_max, o.time ? o.time : est, o.time ? " as given"
           : sec > 0 ? " estimated" : "", o.mem ? o.mem : mem,
           o.mem ? " as given" : " estimated",
           o.account && o.partition ? "" : "; no --account/--partition: "
           "the cluster's defaults", dir);
  }
  free(g.seeds.value);
  free_opts(&o);
  return ok ? 0 : EXIT_BAD_INPUT;
}
