/*
** paper_data.c -- what afv paper reads: CSV files (afv collect's
** table.csv, a sweep's points.csv, a run's analysis files), the (P0, v0)
** plane of the grid's means, a run's analysis files and how the grid's
** runs were integrated.  It only reads.
*/
#define _POSIX_C_SOURCE 200809L  /* access */
#include "paper.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int paper_smoke;
char paper_partial[160];

/* ---- CSV files ---------------------------------------------------------- */
void csv_free(csv *t)
{
  free(t->name);
  free(t->cell);
  free(t->line);
  memset(t, 0, sizeof *t);
}

/* Splits line (modified) at commas into at most max fields of out. */
static int split_fields(char *line, char (*out)[CELL_MAX], int max)
{
  int n = 0;
  char *s = line, *e;
  line[strcspn(line, "\r\n")] = 0;
  for (;;) {
    e = strchr(s, ',');
    if (e) *e = 0;
    if (n < max) {
      size_t len = strlen(s);
      if (len >= CELL_MAX) len = CELL_MAX - 1;  /* longer fields cut */
      memcpy(out[n], s, len);
      out[n][len] = 0;
    }
    n++;
    if (!e) return n;
    s = e + 1;
  }
}

/* Reads a CSV file with a header line; 0 (message printed) on failure. */
int csv_read(const char *path, csv *t)
{
  char line[8192];
  FILE *fp = fopen(path, "r");
  int lineno = 1;
  memset(t, 0, sizeof *t);
  if (!fp) {
    fprintf(stderr, "afv paper: %s: %s\n", path, strerror(errno));
    return 0;
  }
  if (!fgets(line, sizeof line, fp)) goto bad;
  t->ncol = split_fields(line, NULL, 0);
  t->name = malloc((size_t)t->ncol * sizeof *t->name);
  if (!t->name) goto bad;
  fseek(fp, 0, SEEK_SET);
  if (!fgets(line, sizeof line, fp)) goto bad;
  split_fields(line, t->name, t->ncol);
  while (fgets(line, sizeof line, fp)) {
    void *grown;
    lineno++;
    if (line[0] == '#' || line[0] == '\n') continue;
    grown = realloc(t->line, (size_t)(t->nrow + 1) * sizeof *t->line);
    if (!grown) goto bad;
    t->line = grown;
    t->line[t->nrow] = lineno;
    grown = realloc(t->cell, (size_t)(t->nrow + 1) * t->ncol * sizeof *t->cell);
    if (!grown) goto bad;
    t->cell = grown;
    memset(t->cell + (size_t)t->nrow * t->ncol, 0,
           (size_t)t->ncol * sizeof *t->cell);
    if (split_fields(line, t->cell + (size_t)t->nrow * t->ncol, t->ncol)
        != t->ncol) {
      fprintf(stderr, "afv paper: %s: line %d has not %d fields\n", path,
              lineno, t->ncol);
      fclose(fp);
      csv_free(t);
      return 0;
    }
    t->nrow++;
  }
  fclose(fp);
  return 1;
bad:
  fprintf(stderr, "afv paper: %s: empty or unreadable\n", path);
  fclose(fp);
  csv_free(t);
  return 0;
}

/* A sweep's table.csv (afv collect) with one state point or more; else
** one line naming the file and what it lacks (a header only: no run of the
** sweep finished and verified). */
int table_read(const char *sweep_dir, csv *t)
{
  char path[PATH_LEN];
  snprintf(path, sizeof path, "%s/table.csv", sweep_dir);
  if (!csv_read(path, t)) return 0;
  if (t->nrow > 0) return 1;
  fprintf(stderr, "afv paper: %s: no state point, only a header (no run of "
          "%s finished and passed afv collect's checks: see %s/missing.txt)"
          "\n", path, sweep_dir, sweep_dir);
  csv_free(t);
  return 0;
}

int csv_col(const csv *t, const char *name)
{
  int k;
  for (k = 0; k < t->ncol; k++) if (strcmp(t->name[k], name) == 0) return k;
  return -1;
}

/* Number in row r, column c ("inf", "nan" as strtod reads them); NaN if
** the column is missing. */
double csv_num(const csv *t, int r, int c)
{
  return c < 0 ? NAN : strtod(t->cell[(size_t)r * t->ncol + c], NULL);
}

const char *csv_str(const csv *t, int r, int c)
{
  return c < 0 ? "" : t->cell[(size_t)r * t->ncol + c];
}

/* ---- the grid sweep: means on the (P0, v0) plane ------------------------- */
static const char *q_name[N_Q] = {"ngc_frac", "n_clusters", "omega", "D_eff",
                                  "tau_NGC", "t1_rate", "msd_beta"};

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Adds v to the sorted set vals (n values) if it is not there yet. */
void add_value(double *vals, int *n, double v)
{
  int k;
  for (k = 0; k < *n; k++) if (fabs(vals[k] - v) < 1e-9) return;
  if (*n < MAX_VALUES) vals[(*n)++] = v;
  qsort(vals, (size_t)*n, sizeof *vals, cmp_double);
}

int index_of(const double *vals, int n, double v)
{
  int k;
  for (k = 0; k < n; k++) if (fabs(vals[k] - v) < 1e-9) return k;
  return -1;
}

/* The value of vals nearest to v (the panels' state points on a coarser
** grid than the paper's). */
int nearest(const double *vals, int n, double v)
{
  int k, best = 0;
  for (k = 1; k < n; k++)
    if (fabs(vals[k] - v) < fabs(vals[best] - v)) best = k;
  return best;
}

void plane_free(plane *P)
{
  int q;
  for (q = 0; q < N_Q; q++) { free(P->mean[q]); free(P->sem[q]); }
  free(P->seeds);
  csv_free(&P->points);
}

/* Fills P's means and standard errors from table t (afv collect's
** table.csv, named path in messages) at the design's P0 and v0 values
** (P->p0, P->v0): a state point without a row stays NaN. */
static int plane_fill(plane *P, const csv *t, const char *path)
{
  int r, q, cq[N_Q], cs[N_Q];
  int cp = csv_col(t, "P0"), cv = csv_col(t, "v0"), cn = csv_col(t, "n_seeds");
  if (cp < 0 || cv < 0) {
    fprintf(stderr, "afv paper: %s: no P0 or v0 column\n", path);
    return 0;
  }
  if (!(P->seeds = calloc((size_t)(P->np * P->nv + 1), sizeof *P->seeds)))
    return 0;
  for (q = 0; q < N_Q; q++) {
    char name[CELL_MAX + 8];
    int k;
    P->mean[q] = malloc((size_t)(P->np * P->nv + 1) * sizeof(double));
    P->sem[q] = malloc((size_t)(P->np * P->nv + 1) * sizeof(double));
    if (!P->mean[q] || !P->sem[q]) return 0;
    for (k = 0; k < P->np * P->nv; k++) P->mean[q][k] = P->sem[q][k] = NAN;
    snprintf(name, sizeof name, "%s_mean", q_name[q]);
    cq[q] = csv_col(t, name);
    snprintf(name, sizeof name, "%s_sem", q_name[q]);
    cs[q] = csv_col(t, name);
  }
  for (r = 0; r < t->nrow; r++) {
    int ip = index_of(P->p0, P->np, csv_num(t, r, cp));
    int iv = index_of(P->v0, P->nv, csv_num(t, r, cv));
    if (ip < 0 || iv < 0) continue;
    for (q = 0; q < N_Q; q++) {
      P->mean[q][iv * P->np + ip] = csv_num(t, r, cq[q]);
      P->sem[q][iv * P->np + ip] = csv_num(t, r, cs[q]);
    }
    /* a table without n_seeds (an older one) counts one run per row */
    P->seeds[iv * P->np + ip] = cn < 0 ? 1 : csv_num(t, r, cn);
  }
  return P->np > 0 && P->nv > 0;
}

/* The most runs at one point: of points.csv's rows (the design), or of
** the table's n_seeds when the table is all there is. */
static int most_seeds(const plane *P, const csv *points)
{
  int ip, iv, r, most = 0;
  int cp = csv_col(points, "P0"), cv = csv_col(points, "v0");
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++) {
      int n = 0;
      for (r = 0; r < points->nrow; r++)
        n += fabs(csv_num(points, r, cp) - P->p0[ip]) < 1e-9
             && fabs(csv_num(points, r, cv) - P->v0[iv]) < 1e-9;
      if (points->nrow == 0) n = seeds_at(P, ip, iv);
      if (n > most) most = n;
    }
  return most;
}

int seeds_at(const plane *P, int ip, int iv)
{
  double n = P->seeds ? P->seeds[iv * P->np + ip] : 0;
  return isfinite(n) && n > 0 ? (int)n : 0;
}

int runs_in(const plane *P)
{
  int ip, iv, n = 0;
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++) n += seeds_at(P, ip, iv);
  return n;
}

int runs_designed(const plane *P)
{
  return P->np * P->nv * P->design_seeds;
}

/* The design's P0 and v0 values: every row of t. */
static void plane_design(plane *P, const csv *t)
{
  int r, cp = csv_col(t, "P0"), cv = csv_col(t, "v0");
  for (r = 0; r < t->nrow; r++) {
    add_value(P->p0, &P->np, csv_num(t, r, cp));
    add_value(P->v0, &P->nv, csv_num(t, r, cv));
  }
}

int plane_read(const char *out, plane *P)
{
  char path[PATH_LEN];
  csv t;
  int ok;
  memset(P, 0, sizeof *P);
  snprintf(P->dir, sizeof P->dir, "%s/grid", out);
  if (!table_read(P->dir, &t)) return 0;
  snprintf(path, sizeof path, "%s/points.csv", P->dir);
  if (!csv_read(path, &P->points)) { csv_free(&t); return 0; }
  /* The grid is the sweep's design (points.csv), not the table's rows: a
  ** state point whose runs have not finished stays NaN ("not measured"),
  ** so no claim is ever taken from a neighbouring point instead. */
  plane_design(P, &P->points);
  snprintf(path, sizeof path, "%s/table.csv", P->dir);
  ok = plane_fill(P, &t, path);
  if (ok) P->design_seeds = most_seeds(P, &P->points);
  csv_free(&t);
  return ok;
}

int plane_read_table(const char *path, plane *P)
{
  return plane_read_table_over(path, NULL, P);
}

int plane_read_table_over(const char *path, const char *also, plane *P)
{
  csv t, d;
  int ok;
  memset(P, 0, sizeof *P);
  if (!csv_read(path, &t)) return 0;
  if (also && !csv_read(also, &d)) { csv_free(&t); return 0; }
  plane_design(P, &t);
  if (also) plane_design(P, &d);
  ok = t.nrow > 0 && plane_fill(P, &t, path);
  if (ok) P->design_seeds = most_seeds(P, &P->points);
  if (t.nrow == 0)
    fprintf(stderr, "afv paper: %s: no state point, only a header\n", path);
  csv_free(&t);
  if (also) csv_free(&d);
  return ok;
}

double at(const plane *P, int q, int ip, int iv, int sem)
{
  return (sem ? P->sem[q] : P->mean[q])[iv * P->np + ip];
}

/* The run folder (SWEEP/runs/ID) of the k-th job in points (points.csv of
** the sweep in dir) whose keys[j] equal vals[j], j < nk; 0 if none. */
int find_run(const csv *points, const char *dir, int nk,
                    const char *const *keys, const double *vals, int k,
                    char *path)
{
  int r, j, ci = csv_col(points, "id");
  for (r = 0; r < points->nrow; r++) {
    for (j = 0; j < nk; j++)
      if (!(fabs(csv_num(points, r, csv_col(points, keys[j])) - vals[j])
            < 1e-9)) break;
    if (j == nk && k-- == 0) {
      snprintf(path, PATH_LEN, "%s/runs/%s", dir, csv_str(points, r, ci));
      return 1;
    }
  }
  return 0;
}

/* The run folder of the job at (P0, v0) of the grid with its k-th seed. */
int run_dir(const plane *P, double p0, double v0, int k, char *path)
{
  static const char *const keys[2] = {"P0", "v0"};
  double vals[2];
  vals[0] = p0;
  vals[1] = v0;
  return find_run(&P->points, P->dir, 2, keys, vals, k, path);
}

/* A number from a run's analysis/summary.txt (KEY VALUE lines); NaN if
** the key or the file is missing. */
double summary_value(const char *dir, const char *key)
{
  char path[PATH_LEN + 32], line[256], k[128];
  double v, out = NAN;
  FILE *fp;
  snprintf(path, sizeof path, "%s/analysis/summary.txt", dir);
  if (!(fp = fopen(path, "r"))) return NAN;
  while (fgets(line, sizeof line, fp))
    if (sscanf(line, "%127s %lf", k, &v) == 2 && strcmp(k, key) == 0) out = v;
  fclose(fp);
  return out;
}

/* Column `name` of the CSV file DIR/analysis/FILE as a malloc'd array. */
double *run_column(const char *dir, const char *file, const char *name,
                          int *n)
{
  char path[PATH_LEN + 64];
  csv t;
  double *x;
  int r, c;
  *n = 0;
  snprintf(path, sizeof path, "%s/analysis/%s", dir, file);
  /* a run not analysed yet is one of collect's missing.txt: no message */
  if (access(path, F_OK) != 0 && errno == ENOENT) return NULL;
  if (!csv_read(path, &t)) return NULL;
  c = csv_col(&t, name);
  x = malloc((size_t)(t.nrow + 1) * sizeof *x);
  if (x && c >= 0) {
    for (r = 0; r < t.nrow; r++) x[r] = csv_num(&t, r, c);
    *n = t.nrow;
  }
  csv_free(&t);
  return x;
}

/* The afv version of the grid's runs and how they were integrated, from
** the first job's keys (OUT/grid/jobs/0001.conf: integrator, dt, cap,
** max_move), e.g. "afv 0.3.0, integrator euler, dt 0.01, exact force";
** every claim's note ends with it, since N_GC/N and what depends on it
** move with dt (doc/reproduction/convergence.md). */
char paper_integration[320] = "integration not recorded";

/* "afv VERSION" of the program that wrote the grid's first started run
** (its params.txt's first line, "... written by afv 0.3.0 (commit ...)":
** the version without the commit), or "afv version not recorded".  The
** runs are taken in points.csv's order; a partial grid may lack some. */
static void read_version(const plane *P, char *buf, size_t len)
{
  char path[PATH_LEN + 16], line[512], version[64];
  const char *at;
  FILE *fp = NULL;
  int r, ci = csv_col(&P->points, "id");
  snprintf(buf, len, "afv version not recorded");
  for (r = 0; ci >= 0 && r < P->points.nrow && !fp; r++) {
    snprintf(path, sizeof path, "%s/runs/%s/params.txt", P->dir,
             csv_str(&P->points, r, ci));
    fp = fopen(path, "r");
  }
  if (!fp) return;
  if (fgets(line, sizeof line, fp) && (at = strstr(line, "written by afv "))
      && sscanf(at + 15, "%63[^ (:\n]", version) == 1)
    snprintf(buf, len, "afv %s", version);
  fclose(fp);
}

/* A number of a job file as the sweep was asked for it: afv 0.4.0's job
** files print every digit (cap 0.45000000000000001), so %g; not a number:
** left as it is. */
static void as_asked(char *v, size_t len)
{
  char *end;
  double x = strtod(v, &end);
  if (end != v) snprintf(v, len, "%g", x);
}

/* integration: the integrator of the grid's runs, from the first job's
** configuration (every job of a sweep shares it), and their afv version
** (read_version). */
void read_integration(const plane *P)
{
  char path[PATH_LEN + 32], line[256], key[64], val[64], version[96], how[160];
  char integ[64] = "substeps", dt[64] = "?", cap[64] = "0", mm[64] = "?";
  FILE *fp;
  int ci = csv_col(&P->points, "id");
  if (ci < 0 || P->points.nrow < 1) return;
  snprintf(path, sizeof path, "%s/jobs/%s.conf", P->dir,
           csv_str(&P->points, 0, ci));
  if (!(fp = fopen(path, "r"))) return;
  while (fgets(line, sizeof line, fp))
    if (sscanf(line, "%63s %63s", key, val) == 2) {
      if (!strcmp(key, "integrator")) snprintf(integ, sizeof integ, "%s", val);
      else if (!strcmp(key, "dt")) snprintf(dt, sizeof dt, "%s", val);
      else if (!strcmp(key, "cap")) snprintf(cap, sizeof cap, "%s", val);
      else if (!strcmp(key, "max_move")) snprintf(mm, sizeof mm, "%s", val);
    }
  fclose(fp);
  as_asked(dt, sizeof dt);
  as_asked(cap, sizeof cap);
  if (!strcmp(integ, "substeps"))
    snprintf(how, sizeof how, "integrator substeps, dt %.20s, max_move %.20s",
             dt, mm);
  else
    snprintf(how, sizeof how, "integrator %.20s, dt %.20s, %s%.20s", integ,
             dt, strtod(cap, NULL) > 0 ? "cap " : "exact force",
             strtod(cap, NULL) > 0 ? cap : "");
  read_version(P, version, sizeof version);
  snprintf(paper_integration, sizeof paper_integration, "%s, %s", version, how);
}

/* ---- the cluster-size distribution --------------------------------------- */
/* p(n) of the runs at (p0, v0) pooled over the seeds (the mean of their
** csd.csv), index 1..ncell; *ncell from the sizes seen (0 if none). */
double *pooled_csd(const plane *P, int ip, int iv, int *ncell)
{
  double *csd = NULL;
  int k, seeds = 0, cap = 0;
  char dir[PATH_LEN];
  *ncell = 0;
  for (k = 0; run_dir(P, P->p0[ip], P->v0[iv], k, dir); k++) {
    int m, m2, j;
    double *n = run_column(dir, "csd.csv", "n", &m);
    double *p = run_column(dir, "csd.csv", "p", &m2);
    if (n && p && m == m2) {
      for (j = 0; j < m; j++) {
        int s = (int)n[j];
        if (s >= cap) {
          void *g = realloc(csd, (size_t)(s + 1) * sizeof *csd);
          if (!g) { free(n); free(p); free(csd); return NULL; }
          csd = g;
          while (cap <= s) csd[cap++] = 0;
        }
        if (s > 0) csd[s] += p[j];
        if (s > *ncell) *ncell = s;
      }
      seeds++;
    }
    free(n);
    free(p);
  }
  for (k = 1; k <= *ncell; k++) csd[k] /= seeds;
  return csd;
}
