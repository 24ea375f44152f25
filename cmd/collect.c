/*
** collect.c -- afv collect DIR: a sweep's (afv sweep) finished jobs into
** one table of state points, the list of missing jobs, the dispersal
** boundary fit and the phase-diagram figures.  It only reads: the order
** parameters come from each run's analysis/summary.txt (afv analyze).
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, open, fcntl, st_mtim */
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "collect.h"

const order_param collect_params[N_PARAMS] = {
  {"ngc_frac", "ngc_frac_mean", "N_GC/N", 0},
  {"n_clusters", "n_clusters_mean", "number of clusters", 1},
  {"omega", "omega_mean", "Omega", 0},
  {"D_eff", "D_eff", "D_eff", 1},
  {"tau_NGC", "tau_NGC", "tau_NGC (time)", 1},
  {"t1_rate", "t1_rate", "T1 rate (per cell per time)", 1},
  {"msd_beta", "msd_beta", "msd_beta (slope of log MSD_rel vs log lag, "
   "lags 1-10% of the window)", 0},
};


static const char *collect_usage =
  "usage: afv collect DIR\n"
  "\n"
  "Reads the sweep in DIR (afv sweep): points.csv and, for every job,\n"
  "runs/ID/analysis/summary.txt, and writes\n"
  "  DIR/table.csv    one row per state point with a verified job: the\n"
  "                   swept keys, n_seeds (its verified jobs), then\n"
  "                   NAME_mean and NAME_sem (standard error over the\n"
  "                   seeds where NAME is a number) for ngc_frac,\n"
  "                   n_clusters, omega, D_eff, tau_NGC, t1_rate, msd_beta,\n"
  "                   then the phase labels of the means:\n"
  "       cluster_phase      clustered if N_GC/N >= 0.99, else dispersed\n"
  "       confluency_phase   epithelial if Omega >= 0.5, else mesenchymal\n"
  "       dynamic_phase      glassy if msd_beta < 0.5, else fluid: the slope\n"
  "                          of log MSD_rel vs log lag at lags 1% .. 10% of\n"
  "                          the steady window is ~0 for caged cells and ~1\n"
  "                          for diffusing ones whatever the run's length\n"
  "                          (undefined where every seed's steady window\n"
  "                          was too short for msd_beta: afv analyze --help)\n"
  "       dynamic_phase_deff the paper's: glassy if D_eff < 1e-8; D_eff\n"
  "                          of a caged tissue falls like 1/lag, so this\n"
  "                          label depends on the run length and the lag\n"
  "                          (undefined at v0 = 0, where D_eff is nan)\n"
  "  DIR/missing.txt  every job not tabled, with the reason: missing (no\n"
  "                   summary: a run interrupted or stopped at step S of\n"
  "                   N, or the last line of its log, logs/ID.log) or\n"
  "                   damaged (see below); also listed on stderr\n"
  "  DIR/fits.txt     the dispersal boundary v_s(P0) = v0* - c P0^alpha,\n"
  "                   least squares over the v0 where N_GC/N falls below\n"
  "                   0.99 at each P0, with standard errors\n"
  "  DIR/figures/     NAME_vs_v0.svg (mean +- sem against v0, a curve per\n"
  "                   value of the other keys) if v0 is swept, else\n"
  "                   NAME_vs_P0.svg if P0 is swept; if P0 and\n"
  "                   v0 are the swept keys, map_ngc_frac.svg, map_omega.svg,\n"
  "                   map_D_eff.svg, map_msd_beta.svg (threshold contour in\n"
  "                   black, the fitted boundary dashed) and boundary.svg\n"
  "A job is tabled only when verified: its summary.txt is complete (every\n"
  "value above a number, once; N_GC/N and Omega in 0 .. 1, the cluster\n"
  "count >= 1, the T1 rate finite >= 0, D_eff finite >= 0, or nan where\n"
  "v0 = 0 or Dr = 0, tau_NGC not -inf, msd_beta finite or nan) and of\n"
  "this job's run (its run_id the job's id, its run_fingerprint that of\n"
  "the run's params.txt, its cell count N), its run's params.txt holds the\n"
  "values of its points.csv row and of jobs/ID.conf, the run finished\n"
  "(its checkpoint at its last step, final.svg written), the analysis saw\n"
  "every frame of it and is not older than DIR/analysis.txt (the sweep's\n"
  "analysis arguments).  Every other job is missing or damaged, with the\n"
  "reason.  points.csv must have distinct key columns, a job at least,\n"
  "distinct ids and distinct (state point, seed) rows, values that afv run\n"
  "accepts; DIR/analysis.txt must be there.\n"
  "Exit status: 0 every job verified, 1 some missing or damaged (the rest\n"
  "is still written), 2 bad input.\n";

/* ---- reading --------------------------------------------------------------- */
/* Opens path for reading if it is a regular file (a FIFO or a device would
** block or never end); NULL with errno set (EINVAL: not a regular file). */
static FILE *open_regular(const char *path)
{
  struct stat sb;
  FILE *fp;
  int fd = open(path, O_RDONLY | O_NONBLOCK);
  if (fd < 0) return NULL;
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)
      || fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0
      || !(fp = fdopen(fd, "r"))) {
    int e = S_ISREG(sb.st_mode) ? errno : EINVAL;
    close(fd);
    errno = e;
    return NULL;
  }
  return fp;
}

static const char *open_error(void)
{
  return errno == EINVAL ? "not a regular file" : strerror(errno);
}

/* One line of fp (without its end) into buf: 1, 0 at the end, -1 if it is
** longer than len - 1 bytes or holds a NUL byte. */
static int read_line(FILE *fp, char *buf, size_t len)
{
  size_t m = 0;
  int c;
  while ((c = getc(fp)) != EOF && c != '\n') {
    if (c == 0 || m + 1 >= len) return -1;
    buf[m++] = (char)c;
  }
  if (c == EOF && m == 0) return 0;
  if (m && buf[m - 1] == '\r') m--;
  buf[m] = 0;
  return 1;
}

/* Splits line at commas into at most max fields of FIELD_MAX; -1 if a field
** is too long or there are too many. */
static int split_csv(char *line, char (*f)[FIELD_MAX], int max)
{
  int n = 0;
  char *p = line;
  for (;;) {
    size_t m = strcspn(p, ",");
    if (n == max || m >= FIELD_MAX) return -1;
    memcpy(f[n], p, m);
    f[n++][m] = 0;
    if (!p[m]) return n;
    p += m + 1;
  }
}

/* A whole string as a number (NaN if it is not one). */
static double number_of(const char *text)
{
  char *end;
  double v = strtod(text, &end);
  return end != text && !*end ? v : NAN;
}

static int read_header(sweep_table *T, FILE *fp, const char *path)
{
  char line[LINE_MAX_POINTS], f[COLLECT_MAX_KEYS + 2][FIELD_MAX], err[512];
  int n = -1, k;
  if (read_line(fp, line, sizeof line) <= 0
      || (n = split_csv(line, f, COLLECT_MAX_KEYS + 2)) < 2
      || strcmp(f[0], "id") || strcmp(f[n - 1], "seed")) {
    fprintf(stderr, "afv collect: %s:1: expected the header id,KEY...,seed "
            "of afv sweep\n", path);
    return 0;
  }
  T->nkeys = n - 2;
  for (k = 0; k < T->nkeys; k++) {
    int m;
    for (m = 0; m <= k; m++)   /* f[0] is id; a key twice: which one? */
      if (!strcmp(f[m], f[k + 1])) {
        fprintf(stderr, "afv collect: %s:1: column '%s' repeats column %d\n",
                path, f[k + 1], m + 1);
        return 0;
      }
    snprintf(T->key[k], FIELD_MAX, "%s", f[k + 1]);
    if (!run_key_check(T->key[k], "1", err, sizeof err)
        && strstr(err, "unknown")) {
      fprintf(stderr, "afv collect: %s:1: '%s' is not a key of afv run\n",
              path, T->key[k]);
      return 0;
    }
  }
  return 1;
}

/* 1 if id can name a job (runs/ID): letters, digits, '_', '-', '.', and
** not "." or "..". */
static int plain_id(const char *id)
{
  return id[0] && strcmp(id, ".") && strcmp(id, "..")
         && strspn(id, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                   "0123456789_-.") == strlen(id);
}

/* Checks the fields f (n of them) of line lineno: the id, and every value
** as afv run would accept it for its key.  0 with a message printed. */
static int check_row(const sweep_table *T, char (*f)[FIELD_MAX], int n,
                     const char *path, int lineno)
{
  char err[512];
  int k;
  if (n != T->nkeys + 2) {
    fprintf(stderr, "afv collect: %s:%d: expected %d fields (id, keys, "
            "seed), found %d\n", path, lineno, T->nkeys + 2, n);
    return 0;
  }
  if (!plain_id(f[0])) {
    fprintf(stderr, "afv collect: %s:%d: id '%s' is not a job id of afv "
            "sweep\n", path, lineno, f[0]);
    return 0;
  }
  for (k = 0; k <= T->nkeys; k++) {
    const char *key = k < T->nkeys ? T->key[k] : "seed";
    if (!run_key_check(key, f[k + 1], err, sizeof err)) {
      fprintf(stderr, "afv collect: %s:%d: %s\n", path, lineno, err);
      return 0;
    }
  }
  return 1;
}

/* Room for one more job in T (arrays doubled as needed). */
static int grow(sweep_table *T, int *cap)
{
  size_t nk = (size_t)T->nkeys + 1;
  void *a, *b, *c;
  if (T->njobs < *cap) return 1;
  if (*cap > INT_MAX / 4) return 0;
  *cap = *cap ? 2 * *cap : 64;
  a = realloc(T->jobs, (size_t)*cap * sizeof *T->jobs);
  if (a) T->jobs = a;
  b = realloc(T->val, (size_t)*cap * nk * sizeof *T->val);
  if (b) T->val = b;
  c = realloc(T->num, (size_t)*cap * nk * sizeof *T->num);
  if (c) T->num = c;
  return a && b && c;
}

/* points.csv into T->jobs, T->val and T->num. */
static int read_points(sweep_table *T)
{
  char path[RUN_PATH_MAX + 32], line[LINE_MAX_POINTS];
  char f[COLLECT_MAX_KEYS + 2][FIELD_MAX];
  int cap = 0, lineno = 1, st;
  FILE *fp;
  snprintf(path, sizeof path, "%s/points.csv", T->dir);
  if (!(fp = open_regular(path))) {
    fprintf(stderr, "afv collect: %s: cannot open: %s (is %s a sweep of afv "
            "sweep?)\n", path, open_error(), T->dir);
    return 0;
  }
  if (!read_header(T, fp, path)) return fclose(fp), 0;
  while ((st = read_line(fp, line, sizeof line)) != 0) {
    int n = st < 0 ? -1 : split_csv(line, f, COLLECT_MAX_KEYS + 2), k;
    job *J;
    lineno++;
    if (st < 0) {
      fprintf(stderr, "afv collect: %s:%d: a NUL byte or a line over %d "
              "bytes\n", path, lineno, LINE_MAX_POINTS - 2);
      return fclose(fp), 0;
    }
    if (!check_row(T, f, n, path, lineno)) return fclose(fp), 0;
    if (!grow(T, &cap))
      return fclose(fp), !bad_input("collect: out of memory");
    J = &T->jobs[T->njobs];
    memset(J, 0, sizeof *J);
    J->line = lineno;
    snprintf(J->id, FIELD_MAX, "%s", f[0]);
    snprintf(J->seed, FIELD_MAX, "%s", f[n - 1]);
    for (k = 0; k < T->nkeys; k++) {
      snprintf(VAL(T, T->njobs, k), FIELD_MAX, "%s", f[k + 1]);
      NUM(T, T->njobs, k) = number_of(f[k + 1]);
    }
    T->njobs++;
  }
  fclose(fp);
  if (T->njobs == 0) {
    fprintf(stderr, "afv collect: %s: no job (the header alone): not a "
            "sweep of afv sweep\n", path);
    return 0;
  }
  return 1;
}

/* ---- state points ---------------------------------------------------------- */
/* Order of two values of a key: as numbers when both are, else as text. */
int cmp_value(const sweep_table *T, int a, int b, int k)
{
  double x = NUM(T, a, k), y = NUM(T, b, k);
  if (!isnan(x) && !isnan(y)) return x < y ? -1 : x > y;
  return strcmp(VAL(T, a, k), VAL(T, b, k));
}

/* Order of jobs a and b by state point (key by key), skipping key skip. */
int cmp_point(const sweep_table *T, int a, int b, int skip)
{
  int k, c;
  for (k = 0; k < T->nkeys; k++)
    if (k != skip && (c = cmp_value(T, a, b, k)) != 0) return c;
  return 0;
}

/* qsort has no context argument in C99: the table of the sort in progress. */
static const sweep_table *sort_table;

/* Jobs by state point, then seed (as numbers), then line. */
static int cmp_job_point(const void *pa, const void *pb)
{
  int a = *(const int *)pa, b = *(const int *)pb, c;
  double sa, sb;
  if ((c = cmp_point(sort_table, a, b, -1)) != 0) return c;
  sa = number_of(sort_table->jobs[a].seed);
  sb = number_of(sort_table->jobs[b].seed);
  if (sa != sb) return sa < sb ? -1 : 1;
  return (a > b) - (a < b);
}

static int cmp_job_id(const void *pa, const void *pb)
{
  int a = *(const int *)pa, b = *(const int *)pb;
  int c = strcmp(sort_table->jobs[a].id, sort_table->jobs[b].id);
  return c ? c : (a > b) - (a < b);
}

/* Groups the jobs into state points (numbered in order of their first
** job); refuses a repeated id or a repeated (state point, seed). */
static int group_points(sweep_table *T, int *order)
{
  int j, q;
  sort_table = T;
  for (j = 0; j < T->njobs; j++) order[j] = j;
  qsort(order, (size_t)T->njobs, sizeof *order, cmp_job_id);
  for (j = 1; j < T->njobs; j++)
    if (!strcmp(T->jobs[order[j]].id, T->jobs[order[j - 1]].id))
      return fprintf(stderr, "afv collect: %s/points.csv:%d: id %s repeats "
                     "line %d\n", T->dir, T->jobs[order[j]].line,
                     T->jobs[order[j]].id, T->jobs[order[j - 1]].line), 0;
  qsort(order, (size_t)T->njobs, sizeof *order, cmp_job_point);
  for (j = 0; j < T->njobs; j = q) {
    int a = order[j], least = a, m;
    for (q = j + 1; q < T->njobs && !cmp_point(T, a, order[q], -1); q++) {
      int b = order[q], c = order[q - 1];
      if (number_of(T->jobs[b].seed) == number_of(T->jobs[c].seed))
        return fprintf(stderr, "afv collect: %s/points.csv:%d: state point "
                       "and seed %s repeat line %d\n", T->dir,
                       T->jobs[b].line, T->jobs[b].seed, T->jobs[c].line), 0;
      if (b < least) least = b;
    }
    /* the point of jobs j .. q-1 (sorted) is named by its first job */
    for (m = j; m < q; m++) T->jobs[order[m]].point = -1 - least;
  }
  /* number the points in order of their first job */
  for (j = 0, q = 0; j < T->njobs; j++) {
    int p = T->jobs[j].point;
    if (p < 0 && -1 - p == j) {
      T->points[q].first = j;
      T->jobs[j].point = q++;
    } else if (p < 0) {
      T->jobs[j].point = T->jobs[-1 - p].point;
    }
  }
  T->npoints = q;
  return 1;
}

/* ---- verifying a job ---------------------------------------------------------- */
/* The reason a job is not tabled, into J->why (allocated); returns 0. */
static int job_fails(job *J, int state, const char *fmt, ...)
{
  char text[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  J->state = state;
  free(J->why);
  J->why = malloc(strlen(text) + 1);
  if (J->why) strcpy(J->why, text);
  return 0;
}

/* A KEY VALUE file (summary.txt, params.txt, ID.conf): its keys and their
** values, in order; lines starting with '#' are comments. */
#define KV_MAX 64
typedef struct kv_file {
  int n;
  char key[KV_MAX][64], val[KV_MAX][FIELD_MAX + 192];
} kv_file;

/* Reads path into F; 1, or 0 with the reason in why (-1: no such file). */
static int kv_read(const char *path, kv_file *F, char *why, size_t len)
{
  char line[512];
  FILE *fp = open_regular(path);
  int st, lineno = 0, k;
  F->n = 0;
  if (!fp) {
    snprintf(why, len, "%s", open_error());
    return errno == ENOENT ? -1 : 0;
  }
  while ((st = read_line(fp, line, sizeof line)) != 0) {
    char extra[2];
    lineno++;
    if (st > 0 && (line[0] == '#' || !line[0])) continue;
    if (st < 0 || F->n == KV_MAX
        || sscanf(line, "%63s %255s %1s", F->key[F->n], F->val[F->n],
                  extra) != 2) {
      snprintf(why, len, "line %d is not KEY VALUE", lineno);
      return fclose(fp), 0;
    }
    for (k = 0; k < F->n; k++)   /* last-wins would hide one */
      if (!strcmp(F->key[k], F->key[F->n])) {
        snprintf(why, len, "line %d: %s given twice", lineno, F->key[k]);
        return fclose(fp), 0;
      }
    F->n++;
  }
  fclose(fp);
  return 1;
}

/* The value of key in F, or NULL. */
static const char *kv_get(const kv_file *F, const char *key)
{
  int k;
  for (k = F->n - 1; k >= 0; k--)
    if (!strcmp(F->key[k], key)) return F->val[k];
  return NULL;
}

/* 1 if a run's value (params.txt) and a sweep's value of key agree:
** equal numbers, or equal text; a run given a cells file records its own
** copy, cells.txt. */
static int same_value(const char *key, const char *run, const char *sweep)
{
  double x = number_of(run), y = number_of(sweep);
  if (!strcmp(key, "cells") && !strcmp(run, "cells.txt"))
    return strcmp(sweep, "none") != 0;
  return !isnan(x) && !isnan(y) ? x == y : !strcmp(run, sweep);
}

/* Order parameters collect requires finite (the others may be nan: D_eff
** at v0 = 0, msd_beta of a short window, tau_NGC of a flat N_GC). */
static int must_be_finite(int k)
{
  return k == P_NGC || k == P_NCL || k == P_OMEGA || k == P_T1;
}

/* The range of each order parameter (in the order of collect_params[]), which a
** summary.txt of afv analyze never leaves (ngc_frac_mean 7, omega_mean -3,
** D_eff -5 or inf, msd_beta inf were "verified" before).  nan passes
** here where must_be_finite allows it (D_eff at v0 = 0: tied_ok). */
static const char *const range_text[N_PARAMS] = {
  "0 .. 1", ">= 1", "0 .. 1", ">= 0, finite, or nan", "finite, inf or nan",
  ">= 0", "finite or nan"};

static int in_range(int k, double x)
{
  if (isnan(x)) return !must_be_finite(k);
  switch (k) {
  case P_NGC: case P_OMEGA: return x >= 0 && x <= 1;
  case P_NCL: return x >= 1;
  case P_DEFF: return x >= 0 && isfinite(x);
  case P_TAU: return !isinf(x) || x > 0;   /* -1e-17: a rounded 0 */
  case P_T1: return x >= 0;
  default: return isfinite(x);   /* P_BETA */
  }
}

/* summary.txt of J, complete (read into S): its order parameters into
** J->v, each in its range, its frame count into *frames. */
static int summary_ok(const sweep_table *T, job *J, kv_file *S,
                      long *frames, struct stat *when)
{
  char path[RUN_PATH_MAX + 96], why[256];
  const kv_file *F = S;
  const char *f;
  int k, st;
  double fr;
  snprintf(path, sizeof path, "%s/runs/%s/analysis/summary.txt", T->dir, J->id);
  if ((st = kv_read(path, S, why, sizeof why)) <= 0)
    return st < 0 ? job_fails(J, JOB_MISSING, "")
                  : job_fails(J, JOB_DAMAGED, "summary.txt: %s", why);
  if (stat(path, when) != 0) return job_fails(J, JOB_DAMAGED, "summary.txt: "
                                              "%s", strerror(errno));
  for (k = 0; k < N_PARAMS; k++) {
    const char *v = kv_get(F, collect_params[k].key);
    if (!v) return job_fails(J, JOB_DAMAGED, "summary.txt lacks %s (an "
                             "incomplete analysis)", collect_params[k].key);
    J->v[k] = number_of(v);
    if (isnan(J->v[k]) && strcmp(v, "nan") && strcmp(v, "-nan"))
      return job_fails(J, JOB_DAMAGED, "summary.txt: %s '%s' is not a "
                       "number", collect_params[k].key, v);
    if (must_be_finite(k) && !isfinite(J->v[k]))
      return job_fails(J, JOB_DAMAGED, "summary.txt: %s %s is not finite",
                       collect_params[k].key, v);
    if (!in_range(k, J->v[k]))
      return job_fails(J, JOB_DAMAGED, "summary.txt: %s %s is out of its "
                       "range (%s)", collect_params[k].key, v, range_text[k]);
  }
  f = kv_get(F, "frames");
  if (!f) return job_fails(J, JOB_DAMAGED, "summary.txt lacks frames (an "
                           "incomplete analysis)");
  /* a frame count, checked before the cast: 1e27 would overflow a long */
  fr = number_of(f);
  if (!(fr >= 1 && fr <= 1e15 && fr == floor(fr)))
    return job_fails(J, JOB_DAMAGED, "summary.txt: frames '%s' is not a "
                     "frame count", f);
  *frames = (long)fr;
  return 1;
}

/* The run's params.txt holds the values of J's row of points.csv and of
** jobs/ID.conf (if there is one: afv sweep writes it); its steps and
** frame_every into *steps, *every. */
static int params_ok(const sweep_table *T, job *J, int j, kv_file *Pf,
                     double *steps, double *every)
{
  static kv_file C;  /* big: not on the stack */
  kv_file *const P = Pf;
  char path[RUN_PATH_MAX + 96], why[256];
  const char *v;
  int k, st;
  snprintf(path, sizeof path, "%s/runs/%s/params.txt", T->dir, J->id);
  if ((st = kv_read(path, P, why, sizeof why)) <= 0)
    return job_fails(J, JOB_DAMAGED, "params.txt: %s", why);
  for (k = 0; k <= T->nkeys; k++) {
    const char *key = k < T->nkeys ? T->key[k] : "seed";
    const char *want = k < T->nkeys ? VAL(T, j, k) : J->seed;
    if (!(v = kv_get(P, key)) || !same_value(key, v, want))
      return job_fails(J, JOB_DAMAGED, "params.txt has %s %s, points.csv %s "
                       "(not this job's run)", key, v ? v : "(none)", want);
  }
  snprintf(path, sizeof path, "%s/jobs/%s.conf", T->dir, J->id);
  if ((st = kv_read(path, &C, why, sizeof why)) <= 0)
    return job_fails(J, JOB_DAMAGED, "jobs/%s.conf: %s", J->id, why);
  for (k = 0; st > 0 && k < C.n; k++)
    if (strcmp(C.key[k], "version") && strcmp(C.key[k], "commit")
        && (!(v = kv_get(P, C.key[k])) || !same_value(C.key[k], v, C.val[k])))
      return job_fails(J, JOB_DAMAGED, "params.txt has %s %s, jobs/%s.conf "
                       "%s (not this job's run)", C.key[k], v ? v : "(none)",
                       J->id, C.val[k]);
  v = kv_get(P, "steps");
  *steps = v ? number_of(v) : NAN;
  v = kv_get(P, "frame_every");
  *every = v ? number_of(v) : NAN;
  if (!(*steps >= 0) || !(*every >= 0))
    return job_fails(J, JOB_DAMAGED, "params.txt lacks steps or "
                     "frame_every");
  return 1;
}

/* The run reached its steps (checkpoint) and wrote final.svg, its last
** output; its analysis saw every frame and is not older than the sweep's
** analysis arguments. */
static int finished_ok(const sweep_table *T, job *J, double steps,
                       double every, long frames, const struct stat *when)
{
  char path[RUN_PATH_MAX + 96], err[512];
  afv_checkpoint ck;
  struct stat sb;
  long long at;
  long want = every > 0 ? (long)floor(steps / every) + 1 : 0;
  snprintf(path, sizeof path, "%s/runs/%s/checkpoint.txt", T->dir, J->id);
  if (stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
    return job_fails(J, JOB_DAMAGED, "checkpoint.txt: %s (the run did not "
                     "finish)", stat(path, &sb) ? strerror(errno)
                     : "not a regular file");
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK)
    return job_fails(J, JOB_DAMAGED, "%s", err);
  at = ck.step;
  afv_checkpoint_free(&ck);
  snprintf(path, sizeof path, "%s/runs/%s/final.svg", T->dir, J->id);
  if (at < (long long)steps || stat(path, &sb) != 0)
    return job_fails(J, JOB_DAMAGED, "the run is at step %lld of %.0f%s "
                     "(unfinished, yet analysed: remove runs/%s/analysis "
                     "and run the runner again)", at, steps,
                     at < (long long)steps ? "" : ", without final.svg",
                     J->id);
  if (frames != want)
    return job_fails(J, JOB_DAMAGED, "analysed %ld frames of the finished "
                     "run's %ld (analysed before it finished: remove "
                     "runs/%s/analysis and run the runner again)", frames,
                     want, J->id);
  if (T->has_args && (when->st_mtim.tv_sec < T->analysis_args.st_mtim.tv_sec
      || (when->st_mtim.tv_sec == T->analysis_args.st_mtim.tv_sec
          && when->st_mtim.tv_nsec < T->analysis_args.st_mtim.tv_nsec)))
    return job_fails(J, JOB_DAMAGED, "analysed before analysis.txt last "
                     "changed (a new analysis of the sweep): run the runner again");
  return 1;
}

/* summary.txt (S) is of J's run (params.txt, P): its run_id is J's id and
** its run_fingerprint that of params.txt with that id (run_fingerprint; a
** summary copied from another sweep, seed or job, or a run edited since,
** has another), it counted N cells, and D_eff is a number where D_0 is
** (v0 != 0, Dr > 0). */
static int tied_ok(const sweep_table *T, job *J, const kv_file *S,
                   const kv_file *P)
{
  char path[RUN_PATH_MAX + 96], print[32], err[2 * RUN_PATH_MAX];
  const char *id = kv_get(S, "run_id"), *fp = kv_get(S, "run_fingerprint");
  const char *cells = kv_get(S, "cells"), *N = kv_get(P, "N");
  const char *v0 = kv_get(P, "v0"), *Dr = kv_get(P, "Dr");
  if (!id || !fp)
    return job_fails(J, JOB_DAMAGED, "summary.txt lacks run_id or "
                     "run_fingerprint (written by an older afv analyze, or "
                     "not by afv): remove runs/%s/analysis and run the "
                     "runner again", J->id);
  snprintf(path, sizeof path, "%s/runs/%s/params.txt", T->dir, J->id);
  if (run_fingerprint(path, J->id, print, sizeof print, err, sizeof err) <= 0)
    return job_fails(J, JOB_DAMAGED, "params.txt: %s", err);
  if (strcmp(id, J->id) || strcmp(fp, print))
    return job_fails(J, JOB_DAMAGED, "summary.txt is of run %s with "
                     "fingerprint %s, but job %s's run has %s (copied from "
                     "another run, or the run changed since its analysis)",
                     id, fp, J->id, print);
  if (!cells || !N || number_of(cells) != number_of(N))
    return job_fails(J, JOB_DAMAGED, "summary.txt counts %s cells, params.txt "
                     "has N %s", cells ? cells : "no", N ? N : "(none)");
  if (isnan(J->v[P_DEFF]) && v0 && Dr && number_of(v0) != 0
      && number_of(Dr) > 0)
    return job_fails(J, JOB_DAMAGED, "summary.txt: D_eff nan, but v0 %s and "
                     "Dr %s make D_0 a number", v0, Dr);
  return 1;
}

/* Reads and verifies job j: JOB_DONE with its order parameters, else
** JOB_MISSING or JOB_DAMAGED with the reason. */
static void verify_job(const sweep_table *T, int j)
{
  static kv_file S, P;   /* summary.txt, params.txt (big: not on the stack) */
  job *J = &T->jobs[j];
  double steps = 0, every = 0;
  long frames = 0;
  struct stat when;
  if (summary_ok(T, J, &S, &frames, &when)
      && params_ok(T, J, j, &P, &steps, &every)
      && finished_ok(T, J, steps, every, frames, &when)
      && tied_ok(T, J, &S, &P))
    J->state = JOB_DONE;
}

/* Mean and standard error of the mean (sd with n - 1, over sqrt n) of the
** values of x that are not NaN; NaN if there are none, the standard error
** NaN for one. */
static void mean_sem(const double *x, int n, double *mean, double *sem)
{
  double s = 0, v = 0;
  int k, m = 0;
  for (k = 0; k < n; k++)
    if (!isnan(x[k])) s += x[k], m++;
  if (m) s /= m;
  for (k = 0; k < n; k++)
    if (!isnan(x[k])) v += (x[k] - s) * (x[k] - s);
  *mean = m ? s : NAN;
  *sem = m > 1 ? sqrt(v / (m - 1) / m) : NAN;
}

/* Groups the jobs into state points, verifies every job and averages the
** verified seeds of each point. */
static int make_points(sweep_table *T)
{
  double *x = malloc((size_t)(T->njobs + 1) * sizeof(double));
  int *order = malloc((size_t)(T->njobs + 1) * sizeof(int));
  int *start = calloc((size_t)T->njobs + 2, sizeof(int));
  int j, q, k, ok = 0;
  char path[RUN_PATH_MAX + 32];
  T->points = calloc((size_t)T->njobs + 1, sizeof *T->points);
  if (!x || !order || !start || !T->points) {
    bad_input("collect: out of memory");
    goto done;
  }
  if (!group_points(T, order)) goto done;
  snprintf(path, sizeof path, "%s/analysis.txt", T->dir);
  T->has_args = stat(path, &T->analysis_args) == 0;   /* else refused */
  for (j = 0; j < T->njobs; j++) {
    verify_job(T, j);
    if (T->jobs[j].state != JOB_DONE) continue;
    T->points[T->jobs[j].point].n++;
    T->points[T->jobs[j].point].lack_beta += isnan(T->jobs[j].v[P_BETA]);
  }
  /* the verified jobs of point q: order[start[q] .. start[q+1]-1] */
  for (q = 0; q < T->npoints; q++) start[q + 1] = start[q] + T->points[q].n;
  for (q = 0; q < T->npoints; q++) T->points[q].n = 0;
  for (j = 0; j < T->njobs; j++)
    if (T->jobs[j].state == JOB_DONE) {
      point *p = &T->points[T->jobs[j].point];
      order[start[T->jobs[j].point] + p->n++] = j;
    }
  for (q = 0; q < T->npoints; q++)
    for (k = 0; k < N_PARAMS; k++) {
      int m;
      for (m = 0; m < T->points[q].n; m++)
        x[m] = T->jobs[order[start[q] + m]].v[k];
      if (m) mean_sem(x, m, &T->points[q].mean[k], &T->points[q].sem[k]);
    }
  ok = 1;
done:
  free(x);
  free(order);
  free(start);
  return ok;
}

/* ---- table.csv and missing.txt --------------------------------------------- */
static void put_number(FILE *fp, double v)
{
  if (isnan(v)) fputs(",nan", fp);
  else if (isinf(v)) fputs(v > 0 ? ",inf" : ",-inf", fp);
  else fprintf(fp, ",%.6g", v);
}

static const char *cluster_phase(const point *p)
{
  return p->mean[P_NGC] >= CLUSTER_LEVEL ? "clustered" : "dispersed";
}

static const char *confluency_phase(const point *p)
{
  return p->mean[P_OMEGA] >= CONFLUENCY_LEVEL ? "epithelial" : "mesenchymal";
}

static const char *dynamic_phase(const point *p)
{
  double b = p->mean[P_BETA];
  return isnan(b) ? "undefined" : b < BETA_GLASS_LEVEL ? "glassy" : "fluid";
}

static const char *dynamic_phase_deff(const point *p)
{
  double d = p->mean[P_DEFF];
  return isnan(d) ? "undefined" : d < DEFF_GLASS_LEVEL ? "glassy" : "fluid";
}

static void write_table(FILE *fp, const sweep_table *T)
{
  int k, q;
  for (k = 0; k < T->nkeys; k++) fprintf(fp, "%s,", T->key[k]);
  fputs("n_seeds", fp);
  for (k = 0; k < N_PARAMS; k++)
    fprintf(fp, ",%s_mean,%s_sem", collect_params[k].name, collect_params[k].name);
  fputs(",cluster_phase,confluency_phase,dynamic_phase,dynamic_phase_deff\n",
        fp);
  for (q = 0; q < T->npoints; q++) {
    const point *p = &T->points[q];
    if (p->n == 0) continue;
    for (k = 0; k < T->nkeys; k++) fprintf(fp, "%s,", VAL(T, p->first, k));
    fprintf(fp, "%d", p->n);
    for (k = 0; k < N_PARAMS; k++) {
      put_number(fp, p->mean[k]);
      put_number(fp, p->sem[k]);
    }
    fprintf(fp, ",%s,%s,%s,%s\n", cluster_phase(p), confluency_phase(p),
            dynamic_phase(p), dynamic_phase_deff(p));
  }
}

/* 1 if a line of afv run's log is its own news (progress, the
** relaxation's end), not an error: a log that ends on one was cut short. */
static int run_news(const char *line)
{
  return !strncmp(line, "afv run: relaxation", 19)
         || (!strncmp(line, "afv run: step ", 14) && strstr(line, "elapsed"));
}

/* A run of J begun but short of its steps: "interrupted at step S of N"
** when nobody writes it and its log ends on afv run's own news (a kill, a
** time limit: the runner run again resumes it), "running" when an afv
** run holds it, else "stopped at step S of N: " and the log's last line.
** 0 (out untouched) if the run finished or has no checkpoint. */
static int run_stopped(const sweep_table *T, const job *J, const char *last,
                       char *out, size_t len)
{
  char dir[RUN_PATH_MAX + 96], path[RUN_PATH_MAX + 128], err[256];
  afv_checkpoint ck;
  double steps;
  long long at;
  long pid;
  snprintf(dir, sizeof dir, "%s/runs/%s", T->dir, J->id);
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (run_param(path, "steps", &steps) != 1) return 0;
  snprintf(path, sizeof path, "%s/checkpoint.txt", dir);
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK) return 0;
  at = ck.step;
  afv_checkpoint_free(&ck);
  if (at >= (long long)steps) return 0;
  if ((pid = run_lock_holder(dir)) > 0)
    snprintf(out, len, "running (process %ld), at step %lld of %.0f", pid,
             at, steps);
  else if (!last[0] || run_news(last))
    snprintf(out, len, "interrupted at step %lld of %.0f (killed or out of "
             "time: run the runner again to resume it)", at, steps);
  else
    snprintf(out, len, "stopped at step %lld of %.0f: %.600s", at, steps,
             last);
  return 1;
}

/* Why job J is not tabled: damaged, and why; or missing: its run stopped
** short (run_stopped), or the last non-empty line of logs/ID.log that is
** not a warning (else its last line), or the state of its run folder. */
static void missing_reason(const sweep_table *T, const job *J, char *out,
                           size_t len)
{
  char path[RUN_PATH_MAX + 96], line[1024];
  FILE *fp;
  struct stat sb;
  out[0] = 0;
  if (J->state == JOB_DAMAGED) {
    snprintf(out, len, "damaged: %s", J->why ? J->why : "out of memory");
    return;
  }
  snprintf(path, sizeof path, "%s/logs/%s.log", T->dir, J->id);
  if ((fp = open_regular(path))) {
    int warned = 0, st;
    while ((st = read_line(fp, line, sizeof line)) != 0) {
      if (st < 0) continue;
      if (!line[0] || (strstr(line, "warning:") && out[0] && !warned))
        continue;
      warned = strstr(line, "warning:") != NULL;
      snprintf(out, len, "%s", line);
    }
    fclose(fp);
  }
  snprintf(line, sizeof line, "%s", out);
  if (run_stopped(T, J, line, out, len) || out[0]) return;
  snprintf(path, sizeof path, "%s/runs/%s", T->dir, J->id);
  snprintf(out, len, "%s", stat(path, &sb) == 0
           ? "unfinished (no error logged: running, or stopped by a kill)"
           : "not started");
}

static void write_missing(FILE *fp, const sweep_table *T)
{
  char why[1024];
  int j, k;
  fprintf(fp, "# afv collect: jobs not tabled: without runs/ID/analysis/"
          "summary.txt (with the last line of logs/ID.log), or damaged (with "
          "the reason)\n");
  for (j = 0; j < T->njobs; j++) {
    const job *J = &T->jobs[j];
    if (J->state == JOB_DONE) continue;
    missing_reason(T, J, why, sizeof why);
    fprintf(fp, "%s", J->id);
    for (k = 0; k < T->nkeys; k++) fprintf(fp, " %s=%s", T->key[k], VAL(T, j, k));
    fprintf(fp, " seed=%s: %s\n", J->seed, why);
  }
}

/* ---- afv collect ---------------------------------------------------------------- */
typedef void (*table_writer)(FILE *fp, const sweep_table *T);

static int write_one(const char *dir, const char *name, table_writer fn,
                     const sweep_table *T)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 96];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))
      || (fn(fp, T), afv_atomic_commit(fp, tmp, path)) != AFV_OK) {
    fprintf(stderr, "afv collect: %s: cannot write: %s\n", path,
            strerror(errno));   /* ENOSPC: "No space left on device" */
    return 0;
  }
  return 1;
}

/* A sweep whose jobs run with different cap values (PyAFV's contact cap
** makes another model: doc/reproduction/convergence.md) is not one table
** unless cap is a column of points.csv: 1, and one line naming the two
** jobs' files, if their jobs/ID.conf disagree on cap (no key: cap 0).
** A job without its conf file is left to the checks of each job. */
static int mixes_cap(const sweep_table *T)
{
  char path[RUN_PATH_MAX + 64], why[128], first[FIELD_MAX + 192] = "";
  const char *first_id = NULL, *cap;
  kv_file F;
  int j;
  if (key_index(T, "cap") >= 0) return 0;
  for (j = 0; j < T->njobs; j++) {
    snprintf(path, sizeof path, "%s/jobs/%s.conf", T->dir, T->jobs[j].id);
    if (kv_read(path, &F, why, sizeof why) != 1) continue;
    if (!(cap = kv_get(&F, "cap"))) cap = "0";
    if (!first_id) {
      first_id = T->jobs[j].id;
      snprintf(first, sizeof first, "%s", cap);
    } else if (!same_value("cap", cap, first)) {
      fprintf(stderr, "afv collect: %s: cap %s, but %s/jobs/%s.conf has cap "
              "%s: a sweep mixing cap values is not one table (sweep cap as "
              "a column of points.csv)\n", path, cap, T->dir, first_id, first);
      return 1;
    }
  }
  return 0;
}

/* Lists the jobs not tabled on stderr (the first 20; all in missing.txt);
** their count. */
static int report_missing(const sweep_table *T)
{
  char why[1024];
  int j, m = 0, damaged = 0;
  for (j = 0; j < T->njobs; j++) {
    const job *J = &T->jobs[j];
    if (J->state == JOB_DONE) continue;
    damaged += J->state == JOB_DAMAGED;
    if (++m <= 20) {
      missing_reason(T, J, why, sizeof why);
      fprintf(stderr, "afv collect: %s job %s: %s\n", J->state == JOB_DAMAGED
              ? "damaged" : "missing", J->id,
              why + (J->state == JOB_DAMAGED ? strlen("damaged: ") : 0));
    }
  }
  if (m)
    fprintf(stderr, "afv collect: %d of %d jobs not tabled: %d missing, %d "
            "damaged (all in %s/missing.txt)\n", m, T->njobs, m - damaged,
            damaged, T->dir);
  return m;
}

/* Says how many tabled state points have no msd_beta (every seed's steady
** window too short for it) or lack it in some seeds. */
static void report_beta(const sweep_table *T)
{
  int q, none = 0, some = 0, tabled = 0;
  for (q = 0; q < T->npoints; q++) {
    const point *p = &T->points[q];
    if (p->n == 0) continue;
    tabled++;
    none += p->lack_beta == p->n;
    some += p->lack_beta > 0 && p->lack_beta < p->n;
  }
  if (none)
    printf("msd_beta: nan at %d of %d state points (dynamic_phase "
           "undefined there): their steady window is too short for it (see "
           "afv analyze --help)\n", none, tabled);
  if (some)
    printf("msd_beta: nan from some seeds at %d of %d state points (their "
           "means are over the other seeds)\n", some, tabled);
}

/* DIR/analysis.txt, the analysis every summary must be of (afv sweep
** writes it): 1, or 0 with a message if it is not there (a deleted one
** let every summary, of any analysis, pass). */
static int analysis_args_there(const sweep_table *T)
{
  if (T->has_args) return 1;
  fprintf(stderr, "afv collect: %s/analysis.txt: %s (afv sweep writes it: "
          "the analysis every job's summary must be of)\n", T->dir,
          strerror(ENOENT));
  return 0;
}

int cmd_collect(int argc, char **argv)
{
  sweep_table T;
  int k, ok, missing = 0;
  memset(&T, 0, sizeof T);
  for (k = 1; k < argc; k++) {
    if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
      fputs(collect_usage, stdout);
      return 0;
    }
    if (argv[k][0] == '-')
      return unknown_option(argv[k], collect_usage, NULL);
    if (T.dir) return bad_input("collect: more than one DIR given");
    T.dir = argv[k];
  }
  if (!T.dir) return bad_input("collect: missing DIR (see afv collect --help)");
  if (strlen(T.dir) > RUN_PATH_MAX - 128) return bad_input("collect: DIR too long");
  ok = read_points(&T) && make_points(&T) && !mixes_cap(&T)
       && analysis_args_there(&T);
  if (ok) {
    missing = report_missing(&T);
    ok = write_one(T.dir, "table.csv", write_table, &T)
         && write_one(T.dir, "missing.txt", write_missing, &T);
    if (ok && !write_figures(T.dir, &T)) {
      fprintf(stderr, "afv collect: %s/figures: cannot write: %s\n", T.dir,
              strerror(errno));
      ok = 0;
    }
  }
  if (ok) {
    report_beta(&T);
    printf("%d state points (%d of %d jobs verified): %s/table.csv\n",
           T.npoints, T.njobs - missing, T.njobs, T.dir);
  }
  for (k = 0; k < T.njobs; k++) free(T.jobs[k].why);
  free(T.jobs);
  free(T.val);
  free(T.num);
  free(T.points);
  return !ok ? EXIT_BAD_INPUT : missing ? EXIT_CHECK_FAILED : 0;
}
