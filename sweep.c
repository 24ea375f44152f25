/*
** sweep.c -- afv sweep: a grid of afv run jobs and three runners for it
**
**   afv sweep --out DIR [--seeds K] [--KEY VALUES ...]
**
** VALUES is a:b:step (inclusive range), v1,v2,... (list) or one value
** (fixed).  Every job is one idempotent shell command (jobs.txt):
**   AFV run --config DIR/jobs/ID.conf --out DIR/runs/ID --continue
**     && AFV analyze DIR/runs/ID [--steady-from T] [--lag L]
** so the Makefile, GNU parallel and a SLURM array run the same lines, and
** any of them, stopped at any moment, finishes the sweep when run again.
*/
#define _XOPEN_SOURCE 700  /* mkdir, realpath, readlink */
#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* At most this many jobs in one sweep (a guard against a typo in a step). */
#define SWEEP_MAX_JOBS 100000
/* At most this many --KEY options. */
#define SWEEP_MAX_KEYS 64
/* Longest value text of one grid point. */
#define VALUE_MAX 64

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
  long seeds;             /* --seeds K (0: not given) */
  long per_task;          /* jobs per SLURM array task */
  int nax;                /* --KEY options */
  sweep_axis ax[SWEEP_MAX_KEYS];
  int seed_axis;          /* index of --seed in ax, or -1 */
} sweep_opts;

static const char *sweep_usage =
  "usage: afv sweep --out DIR [--seeds K] [--KEY VALUES ...] [options]\n"
  "\n"
  "Writes a grid of afv run jobs into DIR (which must not exist yet) and\n"
  "three runners for them; nothing runs until you start one:\n"
  "  make -C DIR -j N            (nothing to install)\n"
  "  parallel -j N < DIR/jobs.txt   (GNU parallel)\n"
  "  sbatch DIR/slurm.sh         (SLURM job array; see its header)\n"
  "Then afv collect DIR writes the table and the figures.\n"
  "\n"
  "Any afv run key may be swept or fixed (afv run --help lists them):\n"
  "  --KEY a:b:step   inclusive range a, a+step, ..., b ((b-a)/step must be\n"
  "                   a whole number; values printed with %.10g)\n"
  "  --KEY v1,v2,...  list\n"
  "  --KEY v          fixed\n"
  "  --seeds K        K replicas per state point, seeds 1..K (default 1),\n"
  "                   unless --seed lists the seeds\n"
  "Options:\n"
  "  --out DIR        the sweep's folder (created with its parents)\n"
  "  --steady-from T  --lag L   passed to afv analyze (steady window, lag\n"
  "                   of D_s in time units) after each run\n"
  "  --per-task K     SLURM: K jobs per array task, run one after the\n"
  "                   other (default 1)\n"
  "  --afv PATH       the afv program the runners call (default: this one)\n"
  "DIR gets points.csv (id, swept keys, seed), jobs/ID.conf (every key of\n"
  "a job: afv run --config jobs/ID.conf repeats it alone), jobs.txt (one\n"
  "command a line), Makefile, slurm.sh, and, as jobs run, runs/ID/ and\n"
  "logs/ID.log.  A job is idempotent: afv run --continue starts, resumes\n"
  "or leaves its run, then afv analyze writes runs/ID/analysis/.  Every\n"
  "value is checked as afv run checks it before anything is written.\n"
  "Exit status: 0 written, 2 bad option or value (DIR not created).\n";

/* ---- grid syntax ----------------------------------------------------------- */
/* Parses a whole string as a finite double. */
static int whole_double(const char *text, double *v)
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
    if (m == 0 || m >= VALUE_MAX) {
      afv_errorf(err, errlen, "--%s %s: value %d of the list is %s", x->key,
                 x->text, k + 1, m ? "too long" : "empty");
      return 0;
    }
    memcpy(x->value[k], p, m);
    x->value[k][m] = 0;
    p += m + (p[m] == ',');
  }
  x->n = n;
  return 1;
}

/* Expands x->text into values and checks each as afv run would. */
static int sweep_axis_parse(sweep_axis *x, char *err, size_t errlen)
{
  char msg[RUN_PATH_MAX];
  int k;
  x->n = 0;
  x->value = NULL;
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
  return 1;
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

/* One option with its value; 0 on a bad one (message printed). */
static int sweep_option(sweep_opts *o, const char *opt, const char *val)
{
  char err[2 * RUN_PATH_MAX] = "";
  double d;
  int k;
  if (!strcmp(opt, "--out")) o->out = val;
  else if (!strcmp(opt, "--afv")) o->afv = val;
  else if (!strcmp(opt, "--seeds")) return count_value(opt, val, &o->seeds);
  else if (!strcmp(opt, "--per-task"))
    return count_value(opt, val, &o->per_task);
  else if (!strcmp(opt, "--steady-from")) {
    if (!whole_double(val, &d) || d < 0)
      return !fprintf(stderr, "afv sweep: %s '%s': expected a number >= 0\n",
                      opt, val);
    o->steady_from = val;
  } else if (!strcmp(opt, "--lag")) {
    if (!whole_double(val, &d) || d <= 0)
      return !fprintf(stderr, "afv sweep: %s '%s': expected a number > 0\n",
                      opt, val);
    o->lag = val;
  } else {
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
  if (!o->out) return !bad_input("sweep: --out DIR is required");
  if (o->seeds && o->seed_axis >= 0)
    return !bad_input("sweep: give --seeds K or --seed LIST, not both");
  return 1;
}

/* ---- the grid -------------------------------------------------------------- */
/* The jobs: every combination of the non-seed axes (first given =
** slowest), times the seeds.  A job's values: idx[axis]. */
typedef struct sweep_grid {
  long njobs, nseeds;
  int nax;                 /* axes, the seed axis last if any */
  const sweep_axis *ax[SWEEP_MAX_KEYS + 1];
  sweep_axis seeds;        /* --seeds K expanded (if no --seed) */
} sweep_grid;

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
static void job_values(const sweep_grid *g, long j, const char **names,
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
static int swept(const sweep_grid *g, int k)
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

/* Job j's command line (no newline). */
static void job_command(char *cmd, size_t len, const sweep_opts *o,
                        const char *afv, const char *dir, const char *id)
{
  int m = snprintf(cmd, len, "%s run --config %s/jobs/%s.conf --out %s/runs/%s"
                   " --continue 2>>%s/logs/%s.log && %s analyze %s/runs/%s",
                   afv, dir, id, dir, id, dir, id, afv, dir, id);
  if (o->steady_from)
    m += snprintf(cmd + m, len - m, " --steady-from %s", o->steady_from);
  if (o->lag) m += snprintf(cmd + m, len - m, " --lag %s", o->lag);
  snprintf(cmd + m, len - m, " >%s/logs/%s.out 2>>%s/logs/%s.log", dir, id,
           dir, id);
}

/* Job j's id: 0001 .. 9999, or six digits for bigger sweeps (at most
** SWEEP_MAX_JOBS), so that ids sort as the jobs. */
static void job_id(char *id, long j, long njobs)
{
  snprintf(id, 16, njobs < 10000 ? "%04ld" : "%06ld", (j + 1) % 1000000);
}

/* Writes one file atomically through fn; 0 on failure (message printed). */
typedef void (*sweep_writer)(FILE *fp, const sweep_grid *g,
                             const sweep_opts *o, const char *afv,
                             const char *dir);
static int write_file(const char *dir, const char *name, sweep_writer fn,
                      const sweep_grid *g, const sweep_opts *o,
                      const char *afv)
{
  char path[PATH_MAX + 64], tmp[PATH_MAX + 128];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))
      || (fn(fp, g, o, afv, dir), afv_atomic_commit(fp, tmp, path)) != AFV_OK) {
    fprintf(stderr, "afv sweep: %s: cannot write\n", path);
    return 0;
  }
  return 1;
}

static void write_points(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                         const char *afv, const char *dir)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char id[16];
  long j;
  int k;
  (void)o; (void)afv; (void)dir;
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
                       const char *afv, const char *dir)
{
  char id[16], cmd[4 * PATH_MAX];
  long j;
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    job_command(cmd, sizeof cmd, o, afv, dir, id);
    fprintf(fp, "%s\n", cmd);
  }
}

static void write_makefile(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                           const char *afv, const char *dir)
{
  char id[16], cmd[4 * PATH_MAX];
  long j;
  fprintf(fp, "# afv sweep: %ld jobs.  make -C %s -j N runs them, N at a "
          "time.\n# A job is done when runs/ID/analysis/summary.txt exists; "
          "make run again\n# (after a crash, a kill, or a change of "
          "machine) does what is missing.\n# --keep-going: a failed job "
          "(see logs/ID.log) does not stop the others;\n# afv collect lists "
          "it in missing.txt.\nMAKEFLAGS += --keep-going\n\n.PHONY: all\n"
          "all:", g->njobs, dir);
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    fprintf(fp, " \\\n  runs/%s/analysis/summary.txt", id);
  }
  fputs("\n", fp);
  for (j = 0; j < g->njobs; j++) {
    job_id(id, j, g->njobs);
    job_command(cmd, sizeof cmd, o, afv, dir, id);
    fprintf(fp, "\nruns/%s/analysis/summary.txt:\n\t%s\n", id, cmd);
  }
}

static void write_slurm(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                        const char *afv, const char *dir)
{
  long tasks = (g->njobs + o->per_task - 1) / o->per_task;
  (void)afv;
  fprintf(fp, "#!/bin/sh\n"
          "# afv sweep as a SLURM job array: %ld jobs of %s/jobs.txt, %ld per "
          "task\n# (afv sweep --per-task K), %ld array tasks.  Submit with\n"
          "#   sbatch %s/slurm.sh\n"
          "# Task T runs lines T*%ld+1 .. T*%ld+%ld of jobs.txt, one after "
          "the other.\n# Every job is idempotent: submit again (or use make "
          "or parallel) to finish\n# what a crash, a time limit or a "
          "scancel left.\n#\n"
          "# Resources, per array task (one job at a time, one core): edit "
          "the lines\n# below or override them on the command line, where "
          "sbatch options win,\n# e.g.  sbatch --time=2:00:00 "
          "--partition=short --array=0-9%%4 %s/slurm.sh\n"
          "# (%%4: at most 4 tasks at once).  --time must cover %ld job(s); "
          "afv runs\n# about 5000 steps/s of 400 cells on one core.\n"
          "#SBATCH --job-name=afv-sweep\n"
          "#SBATCH --array=0-%ld\n"
          "#SBATCH --ntasks=1\n"
          "#SBATCH --cpus-per-task=1\n"
          "#SBATCH --time=24:00:00\n"
          "#SBATCH --output=%s/logs/slurm-%%A_%%a.out\n"
          "set -u\n"
          "per_task=%ld\n"
          "jobs=%s/jobs.txt\n"
          "task=${SLURM_ARRAY_TASK_ID:?submit with sbatch: this is a job "
          "array}\n"
          "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}\n"
          "status=0\n"
          "line=$((task * per_task + 1))\n"
          "last=$((line + per_task - 1))\n"
          "while [ \"$line\" -le \"$last\" ]; do\n"
          "  job=$(sed -n \"${line}p\" \"$jobs\")\n"
          "  if [ -n \"$job\" ]; then sh -c \"$job\" || status=1; fi\n"
          "  line=$((line + 1))\n"
          "done\n"
          "exit $status\n",
          g->njobs, dir, o->per_task, tasks, dir, o->per_task, o->per_task,
          o->per_task, dir, o->per_task, tasks - 1, dir, o->per_task, dir);
}

/* ---- afv sweep ------------------------------------------------------------- */
/* Checks every job's whole configuration (as afv run does) before any file
** is written; 0 on the first bad one (message names its values). */
static int check_jobs(const sweep_grid *g, const sweep_opts *o)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char err[2 * RUN_PATH_MAX];
  long j;
  int k;
  (void)o;
  for (j = 0; j < g->njobs; j++) {
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

/* mkdir -p path. */
static int make_dirs(const char *path)
{
  char p[PATH_MAX];
  size_t k;
  snprintf(p, sizeof p, "%s", path);
  for (k = 1; ; k++) {
    if (p[k] && (p[k] != '/' || p[k - 1] == '/')) continue;
    {
      char c = p[k];
      p[k] = 0;
      if (mkdir(p, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "afv sweep: cannot create %s: %s\n", p,
                strerror(errno));
        return 0;
      }
      if (!(p[k] = c)) return 1;
    }
  }
}

/* Creates DIR, DIR/jobs, DIR/runs, DIR/logs; the absolute DIR into abs. */
static int make_sweep_dir(const char *out, char *abs)
{
  static const char *sub[] = {"jobs", "runs", "logs"};
  char p[PATH_MAX + 16];
  struct stat sb;
  int k;
  if (stat(out, &sb) == 0) {
    fprintf(stderr, "afv sweep: %s exists: choose a new --out (to finish a "
            "sweep, run its runner again)\n", out);
    return 0;
  }
  if (!make_dirs(out) || !realpath(out, abs)) {
    fprintf(stderr, "afv sweep: cannot create %s\n", out);
    return 0;
  }
  for (k = 0; k < 3; k++) {
    snprintf(p, sizeof p, "%s/%s", abs, sub[k]);
    if (mkdir(p, 0777) != 0) {
      fprintf(stderr, "afv sweep: cannot create %s: %s\n", p, strerror(errno));
      return 0;
    }
  }
  return 1;
}

static int write_job_configs(const sweep_grid *g, const char *dir)
{
  const char *names[SWEEP_MAX_KEYS + 1], *values[SWEEP_MAX_KEYS + 1];
  char path[PATH_MAX + 64], id[16], err[2 * RUN_PATH_MAX];
  long j;
  for (j = 0; j < g->njobs; j++) {
    job_values(g, j, names, values);
    job_id(id, j, g->njobs);
    snprintf(path, sizeof path, "%s/jobs/%s.conf", dir, id);
    if (!run_config_write(path, g->nax, names, values, err, sizeof err)) {
      fprintf(stderr, "afv sweep: %s\n", err);
      return 0;
    }
  }
  return 1;
}

/* Relative cells paths become absolute (the job files live elsewhere). */
static int absolute_cells(sweep_opts *o, char *buf)
{
  int k, v;
  for (k = 0; k < o->nax; k++) {
    sweep_axis *x = &o->ax[k];
    for (v = 0; !strcmp(x->key, "cells") && v < x->n; v++) {
      if (x->value[v][0] == '/' || !strcmp(x->value[v], "none")) continue;
      errno = 0;
      if (!realpath(x->value[v], buf) || strlen(buf) >= VALUE_MAX) {
        fprintf(stderr, "afv sweep: --cells %s: %s\n", x->value[v],
                errno ? strerror(errno) : "absolute path too long");
        return 0;
      }
      snprintf(x->value[v], VALUE_MAX, "%s", buf);
    }
  }
  return 1;
}

int cmd_sweep(int argc, char **argv)
{
  sweep_opts o;
  sweep_grid g;
  char afv[PATH_MAX], dir[PATH_MAX];
  int m = sweep_parse(argc, argv, &o), ok;
  if (m <= 0) {
    free_opts(&o);
    return m < 0 ? 0 : EXIT_BAD_INPUT;
  }
  ok = grid_make(&g, &o) && absolute_cells(&o, dir) && check_jobs(&g, &o)
       && afv_program(o.afv, afv) && plain_path("--afv", afv)
       && plain_path("--out", o.out)
       && (strlen(o.out) < RUN_PATH_MAX - 64 || !bad_input("--out: path too long"));
  /* everything is checked: only now is anything created */
  if (ok) ok = make_sweep_dir(o.out, dir) && plain_path("--out", dir);
  if (ok) ok = write_job_configs(&g, dir)
               && write_file(dir, "points.csv", write_points, &g, &o, afv)
               && write_file(dir, "jobs.txt", write_jobs, &g, &o, afv)
               && write_file(dir, "Makefile", write_makefile, &g, &o, afv)
               && write_file(dir, "slurm.sh", write_slurm, &g, &o, afv);
  if (ok)
    printf("%ld jobs in %s; run them with one of\n  make -C %s -j 2\n  "
           "parallel -j 2 < %s/jobs.txt\n  sbatch %s/slurm.sh\nthen: afv "
           "collect %s\n", g.njobs, dir, dir, dir, dir, dir);
  free(g.seeds.value);
  free_opts(&o);
  return ok ? 0 : EXIT_BAD_INPUT;
}
