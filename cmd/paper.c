/*
** paper.c -- afv paper OUT: the paper's figures and the claims table from
** the two sweeps of `make paper` (tools/paper_sweeps.sh), after afv
** collect has tabled them:
**   OUT/grid  the (P0, v0) plane at N = 400: OUT/grid/table.csv (means and
**             standard errors over the seeds), and per run its
**             analysis/series.csv, msd.csv, csd.csv and final.svg;
**   OUT/fss   the finite-size study (N x P0 x v0): OUT/fss/table.csv.
** Writes the SVG files of OUT/figures/ (one file per panel, named after the paper's
** figure and panel), OUT/claims.csv (each number the paper states, afv's
** value, its error and whether they agree) and OUT/fss.csv.
**
** A separate command rather than more of afv collect: collect tables any
** sweep; this knows which state points the paper's panels show and what
** the paper says about them.  It only reads the sweeps.
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* The paper's thresholds (as afv collect): clustered if N_GC/N >= 0.99,
** epithelial if Omega >= 0.5, glassy if D_eff < 1e-8; and collect's own
** run-length-independent one, glassy if msd_beta < 0.5. */
#define CLUSTER_LEVEL 0.99
#define CONFLUENCY_LEVEL 0.5
#define DEFF_GLASS_LEVEL 1e-8
#define BETA_GLASS_LEVEL 0.5

#define MAX_VALUES 64        /* distinct P0 (or v0, N) values of a sweep */
#define CELL_MAX 64          /* longest field of a CSV file */
#define PATH_LEN (RUN_PATH_MAX + 128)

static const char *palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                "#bcbd22", "#17becf"};
#define N_COLORS ((int)(sizeof palette / sizeof palette[0]))

/* ---- CSV files ---------------------------------------------------------- */
typedef struct csv {
  int ncol, nrow;
  char (*name)[CELL_MAX];   /* ncol column names */
  char (*cell)[CELL_MAX];   /* nrow x ncol fields */
} csv;

static void csv_free(csv *t)
{
  free(t->name);
  free(t->cell);
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
static int csv_read(const char *path, csv *t)
{
  char line[8192];
  FILE *fp = fopen(path, "r");
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
    if (line[0] == '#' || line[0] == '\n') continue;
    grown = realloc(t->cell, (size_t)(t->nrow + 1) * t->ncol * sizeof *t->cell);
    if (!grown) goto bad;
    t->cell = grown;
    memset(t->cell + (size_t)t->nrow * t->ncol, 0,
           (size_t)t->ncol * sizeof *t->cell);
    if (split_fields(line, t->cell + (size_t)t->nrow * t->ncol, t->ncol)
        != t->ncol) {
      fprintf(stderr, "afv paper: %s: line %d has not %d fields\n", path,
              t->nrow + 2, t->ncol);
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
static int table_read(const char *sweep_dir, csv *t)
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

static int csv_col(const csv *t, const char *name)
{
  int k;
  for (k = 0; k < t->ncol; k++) if (strcmp(t->name[k], name) == 0) return k;
  return -1;
}

/* Number in row r, column c ("inf", "nan" as strtod reads them); NaN if
** the column is missing. */
static double csv_num(const csv *t, int r, int c)
{
  return c < 0 ? NAN : strtod(t->cell[(size_t)r * t->ncol + c], NULL);
}

static const char *csv_str(const csv *t, int r, int c)
{
  return c < 0 ? "" : t->cell[(size_t)r * t->ncol + c];
}

/* ---- the grid sweep: means on the (P0, v0) plane ------------------------- */
enum { Q_NGC, Q_NCL, Q_OMEGA, Q_DEFF, Q_TAU, Q_T1, Q_BETA, N_Q };
static const char *q_name[N_Q] = {"ngc_frac", "n_clusters", "omega", "D_eff",
                                  "tau_NGC", "t1_rate", "msd_beta"};

typedef struct plane {
  int np, nv;                  /* distinct P0, v0 values */
  double p0[MAX_VALUES], v0[MAX_VALUES];
  double *mean[N_Q], *sem[N_Q];  /* [iv np + ip]; NaN where no job ended */
  csv points;                  /* points.csv: id, P0, v0, seed */
  char dir[RUN_PATH_MAX];
} plane;

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Adds v to the sorted set vals (n values) if it is not there yet. */
static void add_value(double *vals, int *n, double v)
{
  int k;
  for (k = 0; k < *n; k++) if (fabs(vals[k] - v) < 1e-9) return;
  if (*n < MAX_VALUES) vals[(*n)++] = v;
  qsort(vals, (size_t)*n, sizeof *vals, cmp_double);
}

static int index_of(const double *vals, int n, double v)
{
  int k;
  for (k = 0; k < n; k++) if (fabs(vals[k] - v) < 1e-9) return k;
  return -1;
}

/* The value of vals nearest to v (the panels' state points on a coarser
** grid than the paper's). */
static int nearest(const double *vals, int n, double v)
{
  int k, best = 0;
  for (k = 1; k < n; k++)
    if (fabs(vals[k] - v) < fabs(vals[best] - v)) best = k;
  return best;
}

static void plane_free(plane *P)
{
  int q;
  for (q = 0; q < N_Q; q++) { free(P->mean[q]); free(P->sem[q]); }
  csv_free(&P->points);
}

static int plane_read(const char *out, plane *P)
{
  char path[PATH_LEN];
  csv t;
  int r, q, cp, cv, cq[N_Q], cs[N_Q];
  memset(P, 0, sizeof *P);
  snprintf(P->dir, sizeof P->dir, "%s/grid", out);
  if (!table_read(P->dir, &t)) return 0;
  snprintf(path, sizeof path, "%s/points.csv", P->dir);
  if (!csv_read(path, &P->points)) { csv_free(&t); return 0; }
  cp = csv_col(&t, "P0");
  cv = csv_col(&t, "v0");
  if (cp < 0 || cv < 0) {
    fprintf(stderr, "afv paper: %s/table.csv: no P0 or v0 column\n", P->dir);
    csv_free(&t);
    return 0;
  }
  /* The grid is the sweep's design (points.csv), not the table's rows: a
  ** state point whose runs have not finished stays NaN ("not measured"),
  ** so no claim is ever taken from a neighbouring point instead. */
  for (r = 0; r < P->points.nrow; r++) {
    add_value(P->p0, &P->np, csv_num(&P->points, r, csv_col(&P->points, "P0")));
    add_value(P->v0, &P->nv, csv_num(&P->points, r, csv_col(&P->points, "v0")));
  }
  for (q = 0; q < N_Q; q++) {
    char name[CELL_MAX + 8];
    int k;
    P->mean[q] = malloc((size_t)(P->np * P->nv + 1) * sizeof(double));
    P->sem[q] = malloc((size_t)(P->np * P->nv + 1) * sizeof(double));
    if (!P->mean[q] || !P->sem[q]) { csv_free(&t); return 0; }
    for (k = 0; k < P->np * P->nv; k++) P->mean[q][k] = P->sem[q][k] = NAN;
    snprintf(name, sizeof name, "%s_mean", q_name[q]);
    cq[q] = csv_col(&t, name);
    snprintf(name, sizeof name, "%s_sem", q_name[q]);
    cs[q] = csv_col(&t, name);
  }
  for (r = 0; r < t.nrow; r++) {
    int ip = index_of(P->p0, P->np, csv_num(&t, r, cp));
    int iv = index_of(P->v0, P->nv, csv_num(&t, r, cv));
    for (q = 0; q < N_Q && ip >= 0 && iv >= 0; q++) {
      P->mean[q][iv * P->np + ip] = csv_num(&t, r, cq[q]);
      P->sem[q][iv * P->np + ip] = csv_num(&t, r, cs[q]);
    }
  }
  csv_free(&t);
  return P->np > 0 && P->nv > 0;
}

static double at(const plane *P, int q, int ip, int iv, int sem)
{
  return (sem ? P->sem[q] : P->mean[q])[iv * P->np + ip];
}

/* The run folder (SWEEP/runs/ID) of the k-th job in points (points.csv of
** the sweep in dir) whose keys[j] equal vals[j], j < nk; 0 if none. */
static int find_run(const csv *points, const char *dir, int nk,
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
static int run_dir(const plane *P, double p0, double v0, int k, char *path)
{
  static const char *const keys[2] = {"P0", "v0"};
  double vals[2];
  vals[0] = p0;
  vals[1] = v0;
  return find_run(&P->points, P->dir, 2, keys, vals, k, path);
}

/* A number from a run's analysis/summary.txt (KEY VALUE lines); NaN if
** the key or the file is missing. */
static double summary_value(const char *dir, const char *key)
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
static double *run_column(const char *dir, const char *file, const char *name,
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

/* ---- figures ------------------------------------------------------------ */
static FILE *figure_open(const char *out, const char *name, char *path,
                         char *tmp)
{
  snprintf(path, PATH_LEN, "%s/figures/%s", out, name);
  return afv_atomic_open(path, tmp, PATH_LEN + 16);
}

/* 1 when OUT's sweeps are make paper's smoke scale (OUT/grid/scale, as
** tools/paper_sweeps.sh writes it, says smoke): every figure and claim is
** marked so. */
static int smoke;

static int figure_close(FILE *fp, const char *tmp, const char *path)
{
  /* a smoke figure gets a red line at its bottom left, before the "</svg>\n" that
  ** ends every SVG afv writes */
  if (smoke && fseek(fp, -7L, SEEK_END) == 0)
    fputs("<text x=\"4\" y=\"99%\" font-family=\"sans-serif\" "
          "font-size=\"10\" fill=\"#d62728\">SMOKE RUN (make paper "
          "SCALE=smoke): the numbers mean nothing</text>\n</svg>\n", fp);
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* Reads OUT/grid/scale into smoke. */
static void read_scale(const char *out)
{
  char path[PATH_LEN], word[16] = "";
  FILE *fp;
  snprintf(path, sizeof path, "%s/grid/scale", out);
  if ((fp = fopen(path, "r"))) {
    if (fscanf(fp, "%15s", word) != 1) word[0] = 0;
    fclose(fp);
  }
  smoke = !strcmp(word, "smoke");
}

/* The afv version of the grid's runs and how they were integrated, from
** the first job's keys (OUT/grid/jobs/0001.conf: integrator, dt, cap,
** max_move), e.g. "afv 0.3.0, integrator euler, dt 0.01, exact force";
** every claim's note ends with it, since N_GC/N and what depends on it
** move with dt (doc/reproduction/convergence.md). */
static char integration[320] = "integration not recorded";

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

/* integration: the integrator of the grid's runs, from the first job's
** configuration (every job of a sweep shares it), and their afv version
** (read_version). */
static void read_integration(const plane *P)
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
  if (!strcmp(integ, "substeps"))
    snprintf(how, sizeof how, "integrator substeps, dt %.20s, max_move %.20s",
             dt, mm);
  else
    snprintf(how, sizeof how, "integrator %.20s, dt %.20s, %s%.20s", integ,
             dt, strtod(cap, NULL) > 0 ? "cap " : "exact force",
             strtod(cap, NULL) > 0 ? cap : "");
  read_version(P, version, sizeof version);
  snprintf(integration, sizeof integration, "%s, %s", version, how);
}

/* How a claim's value moves with dt, from the committed convergence study
** (doc/reproduction/convergence.md: N = 400, t = 1500, exact Euler at
** Lambda = 0.2), for runs integrated that way; "" for the others and for
** claims the study does not touch (the mean field) or did not measure. */
static const char *dt_dependence(const char *claim)
{
  static const char *const ngc[] = {"v0_star", "ngc_at_v0_star", "vs_",
    "collapse_", "csd_exponent", "tau_ngc", "state_P0_4_v0_0.1_cluster",
    "state_P0_8.8_v0_0.1_cluster", "state_P0_4.4_v0_2.6_cluster",
    "state_P0_8.8_v0_2.6_cluster"};
  size_t k;
  if (!strstr(integration, "integrator euler, dt 0.01, exact force"))
    return "";
  for (k = 0; k < sizeof ngc / sizeof ngc[0]; k++)
    if (strncmp(claim, ngc[k], strlen(ngc[k])) == 0)
      return " Depends on dt: built on N_GC/N, which does not converge in dt "
             "(convergence.md: 0.41, 0.61, 0.77, 1.00 at P0 4, v0 1.85 for dt "
             "0.02, 0.01, 0.005, 0.0025).";
  if (strstr(claim, "omega") || strstr(claim, "confluency"))
    return " Omega moves little with dt (convergence.md: at most 0.034, "
           "dt 0.005 -> 0.0025, at P0 4, v0 2.6).";
  if (strncmp(claim, "msd_beta", 8) == 0 || strncmp(claim, "glassy", 6) == 0)
    return " Its dependence on dt was not measured.";
  return "";
}

/* nc curves y[c n + k] against x[k] (or x[c n + k] if xper), labelled,
** with error bars y +- err (err may be NULL) as unlabelled two-point
** series of the curve's colour; extra series (e.g. a threshold line)
** appended.  NaN points are left out of the curve. */
typedef struct curveset {
  int nc, n, xper;
  const double *x, *y, *err;
  char (*label)[64];
} curveset;

static int plot_curves(const char *out, const char *name, const afv_plot *pl,
                       const curveset *cs, const afv_plot_series *extra,
                       int nextra)
{
  char path[PATH_LEN], tmp[PATH_LEN + 16];
  int total = cs->nc * cs->n, c, k, ns = 0, m, ok = 0;
  afv_plot_series *s = calloc((size_t)(cs->nc + total + nextra + 1),
                              sizeof *s);
  double *px = malloc((size_t)(total + 1) * 6 * sizeof(double));
  double *py = px ? px + total : NULL, *bar = px ? px + 2 * total : NULL;
  FILE *fp;
  if (!s || !px) goto done;
  for (c = 0; c < cs->nc; c++) {
    for (k = 0, m = 0; k < cs->n; k++) {
      double x = cs->x[cs->xper ? c * cs->n + k : k], y = cs->y[c * cs->n + k];
      if (!isfinite(y) || !isfinite(x)) continue;
      px[c * cs->n + m] = x;
      py[c * cs->n + m] = y;
      m++;
    }
    s[ns].x = px + c * cs->n;
    s[ns].y = py + c * cs->n;
    s[ns].n = m;
    s[ns].label = cs->label ? cs->label[c] : NULL;
    s[ns].color = palette[c % N_COLORS];
    s[ns].points = m == 1;
    ns++;
  }
  for (c = 0; cs->err && c < cs->nc; c++)
    for (k = 0; k < cs->n; k++) {
      double x = cs->x[cs->xper ? c * cs->n + k : k], y = cs->y[c * cs->n + k];
      double e = cs->err[c * cs->n + k], *b = bar + 4 * (c * cs->n + k);
      if (!isfinite(y) || !isfinite(e) || !(e > 0)) continue;
      if (pl->logy && !(y - e > 0)) continue;
      b[0] = b[1] = x;
      b[2] = y - e;
      b[3] = y + e;
      s[ns].x = b;
      s[ns].y = b + 2;
      s[ns].n = 2;
      s[ns].color = palette[c % N_COLORS];
      ns++;
    }
  for (k = 0; k < nextra; k++) s[ns++] = extra[k];
  if (!(fp = figure_open(out, name, path, tmp))) goto done;
  afv_svg_plot(fp, pl, s, ns);
  ok = figure_close(fp, tmp, path);
done:
  free(s);
  free(px);
  return ok;
}

/* One of the plane's quantities against v0, a curve per P0. */
static int plot_vs_v0(const char *out, const plane *P, int q,
                      const char *name, const char *title, const char *ylabel,
                      int logy, const afv_plot_series *extra, int nextra)
{
  double *y = malloc((size_t)P->np * P->nv * 2 * sizeof(double));
  char (*label)[64] = malloc((size_t)P->np * sizeof *label);
  curveset cs;
  afv_plot pl;
  int ip, iv, ok = 0;
  if (y && label) {
    for (ip = 0; ip < P->np; ip++) {
      snprintf(label[ip], 64, "P0 = %g", P->p0[ip]);
      for (iv = 0; iv < P->nv; iv++) {
        y[ip * P->nv + iv] = at(P, q, ip, iv, 0);
        y[P->np * P->nv + ip * P->nv + iv] = at(P, q, ip, iv, 1);
      }
    }
    memset(&pl, 0, sizeof pl);
    pl.title = title;
    pl.xlabel = "v0 (l/time)";
    pl.ylabel = ylabel;
    pl.logy = logy;
    cs.nc = P->np; cs.n = P->nv; cs.xper = 0; cs.x = P->v0; cs.y = y;
    cs.err = y + P->np * P->nv; cs.label = label;
    ok = plot_curves(out, name, &pl, &cs, extra, nextra);
  }
  free(y);
  free(label);
  return ok;
}

/* A map of quantity q over the plane with its contour at level and an
** optional dashed curve. */
static int plane_map(const char *out, const plane *P, int q, const char *name,
                     const char *title, const char *zlabel, int logz,
                     double level, const double *cx, const double *cy, int cn)
{
  char path[PATH_LEN], tmp[PATH_LEN + 16];
  afv_map m;
  FILE *fp;
  memset(&m, 0, sizeof m);
  m.title = title;
  m.xlabel = "P0 (l)";
  m.ylabel = "v0 (l/time)";
  m.zlabel = zlabel;
  m.nx = P->np; m.ny = P->nv; m.x = P->p0; m.y = P->v0; m.z = P->mean[q];
  m.logz = logz;
  m.level = level;
  m.cx = cx; m.cy = cy; m.cn = cn;
  if (!(fp = figure_open(out, name, path, tmp))) return 0;
  afv_svg_map(fp, &m);
  return figure_close(fp, tmp, path);
}

/* Copies the final snapshot (final.svg, drawn by afv_svg_write at the end
** of the run) of seed 1 at the grid point nearest (p0, v0). */
static int snapshot(const char *out, const plane *P, double p0, double v0,
                    const char *name)
{
  char dir[PATH_LEN], src[PATH_LEN + 16], path[PATH_LEN], tmp[PATH_LEN + 16];
  char buf[65536];
  size_t got;
  FILE *in, *fp;
  int ip = nearest(P->p0, P->np, p0), iv = nearest(P->v0, P->nv, v0);
  if (!run_dir(P, P->p0[ip], P->v0[iv], 0, dir)) return 1;
  snprintf(src, sizeof src, "%s/final.svg", dir);
  if (!(in = fopen(src, "rb"))) {
    fprintf(stderr, "afv paper: %s: %s (figure %s left out)\n", src,
            strerror(errno), name);
    return 1;
  }
  if (!(fp = figure_open(out, name, path, tmp))) { fclose(in); return 0; }
  while ((got = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, got, fp);
  fclose(in);
  printf("%s: P0 = %g, v0 = %g (asked %g, %g)\n", name, P->p0[ip], P->v0[iv],
         p0, v0);
  return figure_close(fp, tmp, path);
}

/* Time series (column col of series.csv, seed 1) of the runs at the grid
** points nearest (p0s[c], v0s[c]), c < nc, one curve each. */
static int plot_traces(const char *out, const plane *P, int nc,
                       const double *p0s, const double *v0s, const char *file,
                       const char *xcol, const char *ycol, const char *name,
                       const afv_plot *pl, const afv_plot_series *extra,
                       int nextra)
{
  double *xs[MAX_VALUES], *ys[MAX_VALUES];
  int len[MAX_VALUES], c, k, ok = 0, n = 0;
  double *x = NULL, *y = NULL;
  char (*label)[64] = malloc((size_t)(nc + 1) * sizeof *label);
  curveset cs;
  for (c = 0; c < nc; c++) {
    char dir[PATH_LEN];
    int ip = nearest(P->p0, P->np, p0s[c]), iv = nearest(P->v0, P->nv, v0s[c]);
    xs[c] = ys[c] = NULL;
    len[c] = 0;
    if (label) snprintf(label[c], 64, "P0 = %g, v0 = %g", P->p0[ip], P->v0[iv]);
    if (!run_dir(P, P->p0[ip], P->v0[iv], 0, dir)) continue;
    xs[c] = run_column(dir, file, xcol, &len[c]);
    ys[c] = run_column(dir, file, ycol, &k);
    if (k < len[c]) len[c] = k;
    if (len[c] > n) n = len[c];
  }
  x = malloc((size_t)(nc * n + 1) * sizeof *x);
  y = malloc((size_t)(nc * n + 1) * sizeof *y);
  if (x && y && label) {
    for (c = 0; c < nc; c++)
      for (k = 0; k < n; k++) {
        x[c * n + k] = k < len[c] ? xs[c][k] : NAN;
        y[c * n + k] = k < len[c] ? ys[c][k] : NAN;
      }
    cs.nc = nc; cs.n = n; cs.xper = 1; cs.x = x; cs.y = y; cs.err = NULL;
    cs.label = label;
    ok = plot_curves(out, name, pl, &cs, extra, nextra);
  }
  for (c = 0; c < nc; c++) { free(xs[c]); free(ys[c]); }
  free(x); free(y); free(label);
  return ok;
}

/* ---- the cluster-size distribution --------------------------------------- */
/* p(n) of the runs at (p0, v0) pooled over the seeds (the mean of their
** csd.csv), index 1..ncell; *ncell from the sizes seen (0 if none). */
static double *pooled_csd(const plane *P, int ip, int iv, int *ncell)
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

/* The giant cluster is left out of the power-law fit: sizes <= N/4 (at
** v0* the giant cluster holds about 0.7 N). */
#define CSD_FIT_FRACTION 0.25

static int plot_csd(const char *out, const plane *P, double p0, double v0,
                    const char *name, int ncells, afv_powerlaw *fit)
{
  int ip = nearest(P->p0, P->np, p0), iv = nearest(P->v0, P->nv, v0), n, k;
  int lo[AFV_CSD_MAX_BINS], hi[AFV_CSD_MAX_BINS], nb, m = 0, ok;
  double p[AFV_CSD_MAX_BINS], bx[AFV_CSD_MAX_BINS], by[AFV_CSD_MAX_BINS];
  double fx[2], fy[2];
  double *csd = pooled_csd(P, ip, iv, &n);
  char title[128], lab[96];
  afv_plot pl;
  afv_plot_series s[2];
  fit->exponent = fit->se = NAN;
  fit->nbins = 0;
  if (!csd || n < 1) { free(csd); return 1; }
  if (ncells < n) ncells = n;
  afv_powerlaw_fit(csd, n, (int)(CSD_FIT_FRACTION * ncells), fit);
  nb = afv_csd_log_bins(csd, n, lo, hi, p);
  for (k = 0; k < nb; k++) {
    double d = p[k] / (hi[k] - lo[k] + 1);
    if (!(d > 0)) continue;
    bx[m] = sqrt((double)lo[k] * hi[k]);
    by[m] = d;
    m++;
  }
  memset(s, 0, sizeof s);
  s[0].x = bx; s[0].y = by; s[0].n = m; s[0].points = 1;
  s[0].label = "p(n), log-binned (mean over seeds)";
  s[0].color = "#1f77b4";
  if (fit->nbins >= 2) {
    /* The fitted line through the fitted bins' mean log density. */
    double sx = 0, sy = 0;
    int j = 0;
    for (k = 0; k < m; k++)
      if (bx[k] >= fit->lo && bx[k] <= fit->hi) {
        sx += log10(bx[k]); sy += log10(by[k]); j++;
      }
    fx[0] = fit->lo; fx[1] = fit->hi;
    fy[0] = pow(10, sy / j + fit->exponent * (log10(fx[0]) - sx / j));
    fy[1] = pow(10, sy / j + fit->exponent * (log10(fx[1]) - sx / j));
    snprintf(lab, sizeof lab, "fit n^(%.2f +- %.2f), n = %d..%d",
             fit->exponent, fit->se, fit->lo, fit->hi);
    s[1].x = fx; s[1].y = fy; s[1].n = 2; s[1].label = lab;
    s[1].color = "#d62728";
  }
  snprintf(title, sizeof title, "Cluster sizes at P0 = %g, v0 = %g",
           P->p0[ip], P->v0[iv]);
  memset(&pl, 0, sizeof pl);
  pl.title = title;
  pl.xlabel = "cluster size n";
  pl.ylabel = "p(n)";
  pl.logx = pl.logy = 1;
  {
    char path[PATH_LEN], tmp[PATH_LEN + 16];
    FILE *fp = figure_open(out, name, path, tmp);
    if (!fp) { free(csd); return 0; }
    afv_svg_plot(fp, &pl, s, fit->nbins >= 2 ? 2 : 1);
    ok = figure_close(fp, tmp, path);
  }
  free(csd);
  return ok;
}

/* ---- the claims table ----------------------------------------------------- */
/* One row of claims.csv.  Numeric claims agree when |afv - paper| <= 2
** sqrt(afv_err^2 + paper_err^2) (paper_err: the paper's stated error, 0
** where it states none); label claims by their own test (agrees set). */
typedef struct claim {
  char name[64];
  char paper[48];        /* the paper's value (a number, or a label) */
  double paper_err;
  double afv, afv_err;
  int agrees;            /* 1 yes, 0 no, -1 not measured; -2: by the rule */
  char note[640];
} claim;

#define MAX_CLAIMS 40
typedef struct claims {
  int n;
  claim c[MAX_CLAIMS];
} claims;

static claim *claim_add(claims *C, const char *name, double paper,
                        double paper_err, double afv, double afv_err)
{
  claim *c = &C->c[C->n < MAX_CLAIMS ? C->n++ : MAX_CLAIMS - 1];
  memset(c, 0, sizeof *c);
  snprintf(c->name, sizeof c->name, "%s", name);
  snprintf(c->paper, sizeof c->paper, "%g", paper);
  c->paper_err = paper_err;
  c->afv = afv;
  c->afv_err = afv_err;
  c->agrees = -2;
  return c;
}

static const char *agree_text(const claim *c)
{
  int a = c->agrees;
  if (a == -2) {
    double p = strtod(c->paper, NULL);
    double e = isfinite(c->afv_err) ? c->afv_err : 0;
    if (!isfinite(c->afv)) a = -1;
    else a = fabs(c->afv - p) <= 2 * sqrt(e * e + c->paper_err * c->paper_err);
  }
  if (smoke) return "not established (smoke run)";
  return a == 1 ? "yes" : a == 0 ? "no" : "not measured";
}

/* A CSV field: quoted if it holds a comma or a quote. */
static void put_field(FILE *fp, const char *s)
{
  if (!strpbrk(s, ",\"\n")) { fputs(s, fp); return; }
  fputc('"', fp);
  for (; *s; s++) { if (*s == '"') fputc('"', fp); fputc(*s, fp); }
  fputc('"', fp);
}

static int claims_write(const char *out, const claims *C)
{
  char path[PATH_LEN], tmp[PATH_LEN + 16];
  FILE *fp;
  int k;
  snprintf(path, sizeof path, "%s/claims.csv", out);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return 0;
  fprintf(fp, "claim,paper,afv,afv_err,agrees,note\n");
  for (k = 0; k < C->n; k++) {
    const claim *c = &C->c[k];
    put_field(fp, c->name);
    fputc(',', fp);
    put_field(fp, c->paper);
    char note[sizeof c->note + sizeof integration + 256];
    fprintf(fp, ",%.6g,%.6g,%s,", c->afv, c->afv_err, agree_text(c));
    snprintf(note, sizeof note, "%s [%s]%s", c->note, integration,
             dt_dependence(c->name));
    put_field(fp, note);
    fputc('\n', fp);
  }
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* ---- Fig. 2: clustering ----------------------------------------------------- */
/* N_GC/N of P0 column ip as a function of v0 (contiguous, NaN allowed). */
static void ngc_column(const plane *P, int ip, double *y)
{
  int iv;
  for (iv = 0; iv < P->nv; iv++) y[iv] = at(P, Q_NGC, ip, iv, 0);
}

/* The dispersal points v_s(P0) (N_GC/N falls below 0.99) and their fit. */
static int dispersal_boundary(const plane *P, double *bp, double *bv,
                              afv_boundary *fit, int *fitted)
{
  double y[MAX_VALUES];
  int ip, nb = 0;
  for (ip = 0; ip < P->np; ip++) {
    ngc_column(P, ip, y);
    if (afv_curve_cross(P->nv, P->v0, y, CLUSTER_LEVEL, &bv[nb])) {
      bp[nb] = P->p0[ip];
      nb++;
    }
  }
  *fitted = nb >= 3 && afv_boundary_fit(nb, bp, bv, fit) == AFV_OK;
  return nb;
}

/* Curve of the fitted boundary over the P0 range. */
#define CURVE_POINTS 60
static int boundary_curve(const plane *P, const afv_boundary *fit,
                          double *cx, double *cy)
{
  int k;
  for (k = 0; k < CURVE_POINTS; k++) {
    cx[k] = P->p0[0] + (P->p0[P->np - 1] - P->p0[0]) * k / (CURVE_POINTS - 1);
    cy[k] = fit->v0star - fit->c * pow(cx[k], fit->alpha);
  }
  return CURVE_POINTS;
}

static int collapse_figure(const char *out, const plane *P,
                           const afv_collapse *cf)
{
  int n = P->np * P->nv, ip, iv, ok = 0;
  double *x = malloc((size_t)(3 * n + 1) * sizeof *x), *y = x + n, *e = x + 2 * n;
  char (*label)[64] = malloc((size_t)P->np * sizeof *label);
  char title[160];
  curveset cs;
  afv_plot pl;
  if (x && label && isfinite(cf->vstar)) {
    for (ip = 0; ip < P->np; ip++) {
      snprintf(label[ip], 64, "P0 = %g", P->p0[ip]);
      for (iv = 0; iv < P->nv; iv++) {
        x[ip * P->nv + iv] = (P->v0[iv] - cf->vstar) / pow(P->p0[ip], cf->alpha);
        y[ip * P->nv + iv] = at(P, Q_NGC, ip, iv, 0);
        e[ip * P->nv + iv] = at(P, Q_NGC, ip, iv, 1);
      }
    }
    snprintf(title, sizeof title, "Collapse: v0* = %.3f, alpha = %.2f "
             "(paper 1.85, 1.50)", cf->vstar, cf->alpha);
    memset(&pl, 0, sizeof pl);
    pl.title = title;
    pl.xlabel = "(v0 - v0*) / P0^alpha";
    pl.ylabel = "N_GC/N";
    cs.nc = P->np; cs.n = P->nv; cs.xper = 1; cs.x = x; cs.y = y; cs.err = e;
    cs.label = label;
    ok = plot_curves(out, "fig2a_inset_collapse.svg", &pl, &cs, NULL, 0);
  } else {
    ok = 1;
  }
  free(x);
  free(label);
  return ok;
}

static int cluster_figures(const char *out, const plane *P, claims *C)
{
  double bp[MAX_VALUES], bv[MAX_VALUES], cx[CURVE_POINTS], cy[CURVE_POINTS];
  double *y = malloc((size_t)P->np * P->nv * sizeof *y), v, s = 0, s2 = 0;
  afv_boundary fit;
  afv_crossing_fit cr;
  afv_collapse cf;
  afv_powerlaw pl4, pl8;
  int nb, fitted, cn = 0, ip, iv, m = 0, ok;
  claim *c;
  if (!y) return 0;
  for (ip = 0; ip < P->np; ip++) ngc_column(P, ip, y + ip * P->nv);
  afv_curves_cross_common(P->np, P->nv, P->v0, y, &cr);
  afv_collapse_fit(P->np, P->nv, P->v0, y, P->p0, &cf);
  c = claim_add(C, "v0_star", 1.85, 0.06, cr.x, cr.se);
  snprintf(c->note, sizeof c->note, "paper (clustering section): all N_GC/N "
           "curves cross at v0* = 1.85 +- 0.06; afv: mean crossing of %d of "
           "%d pairs of P0 curves (grid means), error by jackknife over the "
           "P0 curves", cr.pairs, P->np * (P->np - 1) / 2);
  /* N_GC/N at afv's v0*, interpolated on each P0 curve. */
  for (ip = 0; ip < P->np && isfinite(cr.x); ip++)
    for (iv = 0; iv + 1 < P->nv; iv++)
      if (P->v0[iv] <= cr.x && cr.x <= P->v0[iv + 1]) {
        double t = (cr.x - P->v0[iv]) / (P->v0[iv + 1] - P->v0[iv]);
        v = (1 - t) * y[ip * P->nv + iv] + t * y[ip * P->nv + iv + 1];
        if (isfinite(v)) { s += v; s2 += v * v; m++; }
        break;
      }
  c = claim_add(C, "ngc_at_v0_star", 0.7, 0, m ? s / m : NAN,
                m > 1 ? sqrt(fmax(0, (s2 - s * s / m) / (m - 1))) : NAN);
  snprintf(c->note, sizeof c->note, "paper: N_GC/N ~ 0.7 at v0* whatever "
           "P0; afv: mean over %d P0 curves at afv's v0*, error = their "
           "standard deviation", m);
  nb = dispersal_boundary(P, bp, bv, &fit, &fitted);
  if (fitted) cn = boundary_curve(P, &fit, cx, cy);
  c = claim_add(C, "vs_alpha", 1.50, 0.12, fitted ? fit.alpha : NAN,
                fitted ? fit.se_alpha : NAN);
  snprintf(c->note, sizeof c->note, "paper: v_s(P0) = v0* - c P0^alpha, "
           "alpha = 1.50 +- 0.12 (collapse), c fitted where N_GC/N drops "
           "below 0.99; afv: least squares to the %d P0 where the mean N_GC/N "
           "crosses 0.99 (afv_boundary_fit)", nb);
  c = claim_add(C, "vs_c", 0.06, 0.005, fitted ? fit.c : NAN,
                fitted ? fit.se_c : NAN);
  snprintf(c->note, sizeof c->note, "paper: c = 0.06 +- 0.005; afv: same fit "
           "as vs_alpha");
  c = claim_add(C, "vs_v0_star", 1.85, 0.06, fitted ? fit.v0star : NAN,
                fitted ? fit.se_v0star : NAN);
  snprintf(c->note, sizeof c->note, "v0* of the boundary fit (paper: the "
           "same v0* = 1.85 +- 0.06 as the crossing)");
  c = claim_add(C, "collapse_v0_star", 1.85, 0.06, cf.vstar, cf.se_vstar);
  snprintf(c->note, sizeof c->note, "paper: collapse N_GC/N = G((v0 - v0*)/"
           "P0^alpha) with v0* = 1.85 +- 0.06; afv: afv_collapse_fit on the "
           "grid means, jackknife error over the P0 curves");
  c = claim_add(C, "collapse_alpha", 1.50, 0.12, cf.alpha, cf.se_alpha);
  snprintf(c->note, sizeof c->note, "paper: alpha = 1.50 +- 0.12 from the "
           "collapse; afv: same fit as collapse_v0_star (alpha in [0, 4])");
  ok = plot_vs_v0(out, P, Q_NGC, "fig2a_ngc_vs_v0.svg",
                  "Giant cluster N_GC/N against v0 (mean +- sem over seeds)",
                  "N_GC/N", 0, NULL, 0)
       && collapse_figure(out, P, &cf)
       && plot_vs_v0(out, P, Q_NCL, "fig2a_inset_nclusters_vs_v0.svg",
                     "Number of clusters against v0", "number of clusters",
                     1, NULL, 0)
       && plane_map(out, P, Q_NGC, "fig2b_cluster_phase.svg",
                    "Clustering: N_GC/N, contour 0.99, dashed: v_s fit",
                    "N_GC/N", 0, CLUSTER_LEVEL, cx, cy, cn)
       && snapshot(out, P, 4.2, 0.1, "fig2b_snapshot_clustered.svg")
       && snapshot(out, P, 4.2, 2.1, "fig2b_snapshot_dispersed.svg")
       && plot_csd(out, P, 4, 1.85, "fig2c_csd_P0_4.svg", 0, &pl4)
       && plot_csd(out, P, 8, 1.85, "fig2c_csd_P0_8.svg", 0, &pl8);
  c = claim_add(C, "csd_exponent_P0_4", -1.25, 0, pl4.exponent, pl4.se);
  snprintf(c->note, sizeof c->note, "paper Fig. 2(c): decay n^-1.25 at P0 = "
           "4, v0 = v0* (a visual aid, no error given); afv: grid point "
           "nearest (4, 1.85), seeds pooled, log bins, fit over sizes %d..%d "
           "(the bins after the densest, sizes <= N/4)", pl4.lo, pl4.hi);
  c = claim_add(C, "csd_exponent_P0_8", -1.75, 0, pl8.exponent, pl8.se);
  snprintf(c->note, sizeof c->note, "paper Fig. 2(c): decay n^-1.75 at P0 = "
           "8; afv as csd_exponent_P0_4, sizes %d..%d", pl8.lo, pl8.hi);
  free(y);
  return ok;
}

/* ---- Fig. 3: fluctuations of the giant cluster ------------------------------ */
/* Mean of the runs' summary value `key` over the seeds at (ip, iv). */
static double seeds_mean(const plane *P, int ip, int iv, const char *key)
{
  char dir[PATH_LEN];
  double s = 0, v;
  int k, m = 0;
  for (k = 0; run_dir(P, P->p0[ip], P->v0[iv], k, dir); k++)
    if (isfinite(v = summary_value(dir, key))) { s += v; m++; }
  return m ? s / m : NAN;
}

static int ngc_mean_vs_p0(const char *out, const plane *P)
{
  /* Two curves (v0 = 0.1, 1) and their bands mean +- sd (the temporal
  ** standard deviation of N_GC/N, averaged over the seeds). */
  double y[2 * MAX_VALUES], e[2 * MAX_VALUES], band[4][MAX_VALUES];
  static const double vs[2] = {0.1, 1};
  char label[2][64], blab[2][64];
  afv_plot_series ex[4];
  afv_plot pl;
  curveset cs;
  int c, ip;
  memset(ex, 0, sizeof ex);
  for (c = 0; c < 2; c++) {
    int iv = nearest(P->v0, P->nv, vs[c]);
    snprintf(label[c], 64, "v0 = %g", P->v0[iv]);
    snprintf(blab[c], 64, "v0 = %g: mean +- sd in time", P->v0[iv]);
    for (ip = 0; ip < P->np; ip++) {
      double sd = seeds_mean(P, ip, iv, "ngc_frac_sd");
      y[c * P->np + ip] = at(P, Q_NGC, ip, iv, 0);
      e[c * P->np + ip] = at(P, Q_NGC, ip, iv, 1);
      band[2 * c][ip] = y[c * P->np + ip] - sd;
      band[2 * c + 1][ip] = y[c * P->np + ip] + sd;
    }
    ex[2 * c].x = ex[2 * c + 1].x = P->p0;
    ex[2 * c].y = band[2 * c];
    ex[2 * c + 1].y = band[2 * c + 1];
    ex[2 * c].n = ex[2 * c + 1].n = P->np;
    ex[2 * c].color = ex[2 * c + 1].color = c ? "#aec7e8" : "#ffbb78";
    ex[2 * c].label = blab[c];
  }
  memset(&pl, 0, sizeof pl);
  pl.title = "Mean N_GC/N against P0 (thin: mean +- sd in time)";
  pl.xlabel = "P0 (l)";
  pl.ylabel = "N_GC/N";
  cs.nc = 2; cs.n = P->np; cs.xper = 0; cs.x = P->p0; cs.y = y; cs.err = e;
  cs.label = label;
  return plot_curves(out, "fig3b_ngc_mean_vs_P0.svg", &pl, &cs, ex, 4);
}

static int fluctuation_figures(const char *out, const plane *P, claims *C)
{
  static const double p0s[2] = {4, 8}, v0s[2] = {1, 1};
  double y[MAX_VALUES], e[MAX_VALUES], mx[2], my[2];
  int iv = nearest(P->v0, P->nv, 1), ip8 = nearest(P->p0, P->np, 8), ip;
  int last_inf = -1, first_fin = -1, order_ok = 1;
  char label[1][64];
  afv_plot pl;
  afv_plot_series ex;
  curveset cs;
  claim *c;
  memset(&pl, 0, sizeof pl);
  memset(&ex, 0, sizeof ex);
  /* The mean of P0 = 8 as a horizontal line (the paper's dashed cyan). */
  mx[0] = 0;
  mx[1] = 1e9;
  my[0] = my[1] = at(P, Q_NGC, ip8, iv, 0);
  {
    char dir[PATH_LEN];
    int n = 0;
    double *t = run_dir(P, P->p0[ip8], P->v0[iv], 0, dir)
                ? run_column(dir, "series.csv", "time", &n) : NULL;
    if (t && n > 0) mx[1] = t[n - 1];
    else mx[1] = mx[0];
    free(t);
  }
  ex.x = mx; ex.y = my; ex.n = 2; ex.color = "#17becf";
  ex.label = "mean, P0 = 8";
  pl.title = "N_GC/N traces at v0 = 1 (seed 1)";
  pl.xlabel = "time";
  pl.ylabel = "N_GC/N";
  if (!plot_traces(out, P, 2, p0s, v0s, "series.csv", "time", "ngc_frac",
                   "fig3a_ngc_traces_v0_1.svg", &pl, &ex, 1))
    return 0;
  if (!ngc_mean_vs_p0(out, P)) return 0;
  /* tau_NGC at v0 = 1: infinite (a constant series) points are not drawn. */
  for (ip = 0; ip < P->np; ip++) {
    y[ip] = at(P, Q_TAU, ip, iv, 0);
    e[ip] = at(P, Q_TAU, ip, iv, 1);
    if (isinf(y[ip])) {
      last_inf = ip;
      if (first_fin >= 0) order_ok = 0;
    } else if (isfinite(y[ip]) && first_fin < 0) {
      first_fin = ip;
    }
  }
  snprintf(label[0], 64, "v0 = %g", P->v0[iv]);
  memset(&pl, 0, sizeof pl);
  pl.title = "tau_NGC at v0 = 1 (infinite values not drawn)";
  pl.xlabel = "P0 (l)";
  pl.ylabel = "tau_NGC (time)";
  pl.logy = 1;
  cs.nc = 1; cs.n = P->np; cs.xper = 0; cs.x = P->p0; cs.y = y; cs.err = e;
  cs.label = label;
  if (!plot_curves(out, "fig3c_tau_ngc_vs_P0.svg", &pl, &cs, NULL, 0))
    return 0;
  /* Where tau_NGC turns finite: between the last infinite and the first
  ** finite P0; the paper: infinite for P0 < 5, finite above. */
  c = claim_add(C, "tau_ngc_infinite_below_P0", 5, 0, NAN, NAN);
  if (last_inf >= 0 && first_fin >= 0 && order_ok) {
    c->afv = 0.5 * (P->p0[last_inf] + P->p0[first_fin]);
    c->afv_err = 0.5 * (P->p0[first_fin] - P->p0[last_inf]);
  }
  c->agrees = isfinite(c->afv) ? fabs(c->afv - 5) <= c->afv_err : -1;
  snprintf(c->note, sizeof c->note, "paper Fig. 3(c): at v0 = 1 tau_NGC is "
           "infinite for P0 < 5 and finite above; afv: midpoint (and half gap)"
           " between the largest grid P0 with an infinite mean tau_NGC (some "
           "seed's N_GC constant) and the smallest with a finite one%s",
           order_ok ? "" : "; NOT ordered: an infinite value above a finite "
           "one");
  return 1;
}

/* ---- Fig. 4: confluency ----------------------------------------------------- */
static int confluency_figures(const char *out, const plane *P, claims *C)
{
  double pstar = afv_meanfield_p0(0.2, acos(-1.0), 1), cx[2], cy[2], row[MAX_VALUES];
  double xc, sem_at = NAN;
  int ip, ok;
  claim *c;
  afv_plot_series none;
  memset(&none, 0, sizeof none);
  cx[0] = cx[1] = pstar;
  cy[0] = P->v0[0];
  cy[1] = P->v0[P->nv - 1];
  ok = plot_vs_v0(out, P, Q_OMEGA, "fig4a_omega_vs_v0.svg",
                  "Confluency Omega against v0", "Omega", 0, NULL, 0)
       && plane_map(out, P, Q_OMEGA, "fig4b_omega_map.svg",
                    "Omega, contour 0.5; dashed: mean-field P0* = 5.73",
                    "Omega", 0, CONFLUENCY_LEVEL, cx, cy, 2);
  c = claim_add(C, "meanfield_P0_star", 5.73, 0.005, pstar, 0);
  snprintf(c->note, sizeof c->note, "paper (EMT section, hexagonal mean "
           "field): P0* = 5.73 for Lambda = 0.2, A0 = pi, kP = 1; afv: "
           "afv_meanfield_p0 (the paper's error: the rounding of 5.73)");
  /* Omega against P0 at the lowest v0: where it falls below 0.5. */
  for (ip = 0; ip < P->np; ip++) row[ip] = at(P, Q_OMEGA, ip, 0, 0);
  c = claim_add(C, "P0_omega_half_low_v0", 5.73, 0, NAN, NAN);
  if (afv_curve_cross(P->np, P->p0, row, CONFLUENCY_LEVEL, &xc)) {
    /* Error: the standard errors of the two bracketing means, carried
    ** through the linear interpolation to P0. */
    for (ip = 0; ip + 1 < P->np; ip++)
      if (P->p0[ip] <= xc && xc <= P->p0[ip + 1]) {
        double t = (xc - P->p0[ip]) / (P->p0[ip + 1] - P->p0[ip]);
        double sa = at(P, Q_OMEGA, ip, 0, 1), sb = at(P, Q_OMEGA, ip + 1, 0, 1);
        double slope = (row[ip + 1] - row[ip]) / (P->p0[ip + 1] - P->p0[ip]);
        sem_at = sqrt((1 - t) * (1 - t) * sa * sa + t * t * sb * sb)
                 / fabs(slope);
        break;
      }
    c->afv = xc;
    c->afv_err = sem_at;
  }
  snprintf(c->note, sizeof c->note, "paper: the mean-field P0* = 5.73 'provides "
           "a reasonable approximation for the phase boundary' Omega = 0.5 as "
           "v0 -> 0 (no measured value printed); afv: P0 where the mean Omega "
           "falls below 0.5 at v0 = %g (the grid's lowest), error from the "
           "seeds' sem", P->v0[0]);
  return ok;
}

/* ---- Fig. 5, 6: dynamics ----------------------------------------------------- */
/* The P0 of the grid within [lo, hi] (the paper's MSD and T1 panels show
** P0 from 4 to 8). */
static int p0_between(const plane *P, double lo, double hi, double *out)
{
  int ip, m = 0;
  for (ip = 0; ip < P->np; ip++)
    if (P->p0[ip] >= lo - 1e-9 && P->p0[ip] <= hi + 1e-9) out[m++] = P->p0[ip];
  return m;
}

/* The slope of log MSD_rel between the lag nearest L/8 and the longest lag
** L of the run at (p0, v0), seed 1 (NaN if unreadable); *msd_last: MSD_rel
** at L, *lag_last: L. */
static double late_slope(const plane *P, double p0, double v0,
                         double *msd_last, double *lag_last)
{
  char dir[PATH_LEN];
  int nl = 0, nm = 0, k, a = 0;
  double *lag = NULL, *msd = NULL, slope = NAN;
  *msd_last = *lag_last = NAN;
  if (run_dir(P, p0, v0, 0, dir)) {
    lag = run_column(dir, "msd.csv", "lag", &nl);
    msd = run_column(dir, "msd.csv", "msd_rel", &nm);
  }
  if (lag && msd && nl == nm && nl >= 2) {
    for (k = 0; k < nl; k++)
      if (fabs(lag[k] - lag[nl - 1] / 8) < fabs(lag[a] - lag[nl - 1] / 8))
        a = k;
    if (a < nl - 1 && msd[a] > 0 && msd[nl - 1] > 0)
      slope = log(msd[nl - 1] / msd[a]) / log(lag[nl - 1] / lag[a]);
    *msd_last = msd[nl - 1];
    *lag_last = lag[nl - 1];
  }
  free(lag);
  free(msd);
  return slope;
}

static claim *beta_claim(claims *C, const plane *P, const char *name,
                         double p0, double paper)
{
  int ip = nearest(P->p0, P->np, p0), iv = nearest(P->v0, P->nv, 0.4);
  double m_last, l_last, late;
  claim *c = claim_add(C, name, paper, 0, at(P, Q_BETA, ip, iv, 0),
                       at(P, Q_BETA, ip, iv, 1));
  c->agrees = !isfinite(c->afv) ? -1
              : paper < 0.5 ? c->afv < BETA_GLASS_LEVEL
              : c->afv >= BETA_GLASS_LEVEL;
  late = late_slope(P, P->p0[ip], P->v0[iv], &m_last, &l_last);
  snprintf(c->note, sizeof c->note, "paper (glassy dynamics section): MSD ~ "
           "lag^beta with beta ~ %g for P0 %s at v0 = 0.4; afv: msd_beta (slope "
           "of log MSD_rel, lags 1%%..10%% of the steady window) at P0 = %g, "
           "v0 = %g; agrees = on the same side of 0.5 (afv collect's label).  "
           "Measured (seed 1): slope %.2f between lags %.3g/8 and %.3g, where "
           "MSD_rel = %.3g l^2", paper, paper < 0.5 ? "<= 4" : ">= 7",
           P->p0[ip], P->v0[iv], late, l_last, l_last, m_last);
  return c;
}

static int dynamics_figures(const char *out, const plane *P, claims *C)
{
  double p0s[MAX_VALUES], v0s[MAX_VALUES], lx[2], ly[2];
  int np = p0_between(P, 4, 8, p0s), k, nv = 0, ip, iv;
  afv_plot pl;
  afv_plot_series line;
  claim *c;
  memset(&pl, 0, sizeof pl);
  pl.xlabel = "lag (time)";
  pl.ylabel = "relative MSD (l^2)";
  pl.logx = pl.logy = 1;
  for (k = 0; k < np; k++) v0s[k] = 0.4;
  pl.title = "Relative MSD at v0 = 0.4 (seed 1)";
  if (!plot_traces(out, P, np, p0s, v0s, "msd.csv", "lag", "msd_rel",
                   "fig5a_msd_v0_0.4.svg", &pl, NULL, 0))
    return 0;
  for (iv = 0; iv < P->nv; iv++)
    if (P->v0[iv] > 0) { v0s[nv] = P->v0[iv]; p0s[nv] = 5.6; nv++; }
  pl.title = "Relative MSD at P0 = 5.6 (seed 1)";
  if (!plot_traces(out, P, nv, p0s, v0s, "msd.csv", "lag", "msd_rel",
                   "fig5b_msd_P0_5.6.svg", &pl, NULL, 0))
    return 0;
  lx[0] = P->v0[0];
  lx[1] = P->v0[P->nv - 1];
  ly[0] = ly[1] = DEFF_GLASS_LEVEL;
  memset(&line, 0, sizeof line);
  line.x = lx; line.y = ly; line.n = 2; line.color = "#000000";
  line.label = "D_eff = 1e-8";
  if (!plot_vs_v0(out, P, Q_DEFF, "fig5c_deff_vs_v0.svg",
                  "D_eff = D_s / D_0 against v0", "D_eff", 1, &line, 1)
      || !plane_map(out, P, Q_DEFF, "fig5d_dynamic_phase.svg",
                    "D_eff, contour 1e-8 (the paper's glass line)", "D_eff",
                    1, DEFF_GLASS_LEVEL, NULL, NULL, 0)
      || !plane_map(out, P, Q_BETA, "fig5d_dynamic_phase_msd_beta.svg",
                    "msd_beta, contour 0.5 (afv collect's glass line)",
                    "msd_beta", 0, BETA_GLASS_LEVEL, NULL, NULL, 0))
    return 0;
  np = p0_between(P, 4, 8, p0s);
  for (k = 0; k < np; k++) v0s[k] = 0.4;
  memset(&pl, 0, sizeof pl);
  pl.title = "Cumulative T1 count at v0 = 0.4 (seed 1)";
  pl.xlabel = "time";
  pl.ylabel = "T1";
  if (!plot_traces(out, P, np, p0s, v0s, "series.csv", "time", "t1",
                   "fig6_t1_traces_v0_0.4.svg", &pl, NULL, 0))
    return 0;
  beta_claim(C, P, "msd_beta_P0_4_v0_0.4", 4, 0);
  for (ip = 0; ip < P->np; ip++)
    if (P->p0[ip] >= 7 - 1e-9) {
      char name[64];
      snprintf(name, sizeof name, "msd_beta_P0_%g_v0_0.4", P->p0[ip]);
      beta_claim(C, P, name, P->p0[ip], 1);
    }
  ip = nearest(P->p0, P->np, 4);
  iv = nearest(P->v0, P->nv, 0.4);
  c = claim_add(C, "glassy_P0_4_v0_0.4_D_eff", 1e-8, 0,
                at(P, Q_DEFF, ip, iv, 0), at(P, Q_DEFF, ip, iv, 1));
  snprintf(c->paper, sizeof c->paper, "<1e-8");
  c->agrees = isfinite(c->afv) ? c->afv < DEFF_GLASS_LEVEL : -1;
  {
    /* A caged relative MSD stays at its plateau: D_eff at the paper's lag
    ** 5000 would be plateau / (4 5000 D_0), D_0 = v0^2 / (2 Dr), Dr = 0.1. */
    char dir[PATH_LEN];
    int nl = 0, nm = 0;
    double *lag = NULL, *msd = NULL, at5000 = NAN, d0 = P->v0[iv] * P->v0[iv]
                                                       / (2 * 0.1);
    if (run_dir(P, P->p0[ip], P->v0[iv], 0, dir)) {
      lag = run_column(dir, "msd.csv", "lag", &nl);
      msd = run_column(dir, "msd.csv", "msd_rel", &nm);
    }
    if (lag && msd && nl == nm && nl > 0)
      at5000 = msd[nl - 1] / (4 * 5000 * d0);
    snprintf(c->note, sizeof c->note, "paper Fig. 5(d)/6: (P0, v0) = (4, 0.4) "
             "is glassy, D_eff < 1e-8 (D_s at lag 5000 of a 1e4 run); afv: "
             "D_eff at P0 = %g, v0 = %g at the sweep's lag (a caged D_eff "
             "falls like 1/lag; msd_beta_P0_4_v0_0.4 is the length-"
             "independent test).  Measured: MSD_rel = %.3g at the longest lag "
             "%.3g (seed 1); held there, D_eff at lag 5000 = %.3g",
             P->p0[ip], P->v0[iv], nl ? msd[nl - 1] : NAN,
             nl ? lag[nl - 1] : NAN, at5000);
    free(lag);
    free(msd);
  }
  return 1;
}

/* ---- Fig. 7: summary ---------------------------------------------------------- */
/* Boundary points of quantity q on the plane: for each P0 the v0 where it
** crosses level (rising if sign = -1, with log10 if logq), or for each v0
** the P0 where it falls (along_p0). */
static int boundary_points(const plane *P, int q, double level, int sign,
                           int logq, int along_p0, double *bx, double *by)
{
  double line[MAX_VALUES], xc;
  int i, j, n = along_p0 ? P->nv : P->np, m = along_p0 ? P->np : P->nv, nb = 0;
  for (i = 0; i < n; i++) {
    for (j = 0; j < m; j++) {
      double v = along_p0 ? at(P, q, j, i, 0) : at(P, q, i, j, 0);
      if (logq) v = v > 0 ? log10(v) : NAN;
      line[j] = sign * v;
    }
    if (afv_curve_cross(m, along_p0 ? P->p0 : P->v0, line,
                     sign * (logq ? log10(level) : level), &xc)) {
      bx[nb] = along_p0 ? xc : P->p0[i];
      by[nb] = along_p0 ? P->v0[i] : xc;
      nb++;
    }
  }
  return nb;
}

/* One label of a summary state: afv's mean of q at the grid point nearest
** (p0, v0) against the level; the paper's label is `yes` (at or above the
** level) or `no`. */
static void label_claim(claims *C, const plane *P, const char *name, int q,
                        double level, double p0, double v0, int above,
                        const char *yes, const char *no, const char *what)
{
  int ip = nearest(P->p0, P->np, p0), iv = nearest(P->v0, P->nv, v0);
  claim *c = claim_add(C, name, level, 0, at(P, q, ip, iv, 0),
                       at(P, q, ip, iv, 1));
  snprintf(c->paper, sizeof c->paper, "%s", above ? yes : no);
  c->agrees = !isfinite(c->afv) ? -1 : (c->afv >= level) == above;
  snprintf(c->note, sizeof c->note, "paper Fig. 7(b): (P0, v0) = (%g, %g) "
           "is %s; afv: mean %s at (%g, %g), %s if >= %g", p0, v0, above ? yes : no,
           what, P->p0[ip], P->v0[iv], yes, level);
}

static void state_claims(claims *C, const plane *P, double p0, double v0,
                         int clustered, int epithelial)
{
  char name[64];
  snprintf(name, sizeof name, "state_P0_%g_v0_%g_cluster", p0, v0);
  label_claim(C, P, name, Q_NGC, CLUSTER_LEVEL, p0, v0, clustered,
              "clustered", "dispersed", "N_GC/N");
  snprintf(name, sizeof name, "state_P0_%g_v0_%g_confluency", p0, v0);
  label_claim(C, P, name, Q_OMEGA, CONFLUENCY_LEVEL, p0, v0, epithelial,
              "epithelial", "mesenchymal", "Omega");
}

static int summary_figures(const char *out, const plane *P, claims *C)
{
  double bx[4][MAX_VALUES], by[4][MAX_VALUES], cx[CURVE_POINTS],
         cy[CURVE_POINTS];
  afv_boundary fit;
  afv_plot pl;
  afv_plot_series s[5];
  int nb[4], fitted, ns = 0, k, ok;
  char path[PATH_LEN], tmp[PATH_LEN + 16];
  FILE *fp;
  static const char *lab[4] = {"dispersal: N_GC/N = 0.99",
                               "confluency: Omega = 0.5",
                               "glass: D_eff = 1e-8",
                               "glass: msd_beta = 0.5"};
  static const char *col[4] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"};
  nb[0] = dispersal_boundary(P, bx[0], by[0], &fit, &fitted);
  nb[1] = boundary_points(P, Q_OMEGA, CONFLUENCY_LEVEL, 1, 0, 1, bx[1], by[1]);
  nb[2] = boundary_points(P, Q_DEFF, DEFF_GLASS_LEVEL, -1, 1, 0, bx[2], by[2]);
  nb[3] = boundary_points(P, Q_BETA, BETA_GLASS_LEVEL, -1, 0, 0, bx[3], by[3]);
  memset(s, 0, sizeof s);
  for (k = 0; k < 4; k++) {
    s[ns].x = bx[k]; s[ns].y = by[k]; s[ns].n = nb[k];
    s[ns].label = lab[k]; s[ns].color = col[k]; s[ns].points = nb[k] < 2;
    ns++;
  }
  if (fitted) {
    s[ns].n = boundary_curve(P, &fit, cx, cy);
    s[ns].x = cx; s[ns].y = cy; s[ns].color = "#000000";
    s[ns].label = "v_s fit";
    ns++;
  }
  memset(&pl, 0, sizeof pl);
  pl.title = "Summary: the three boundaries on the (P0, v0) plane";
  pl.xlabel = "P0 (l)";
  pl.ylabel = "v0 (l/time)";
  pl.ymin = P->v0[0];
  pl.ymax = P->v0[P->nv - 1];
  if (!(fp = figure_open(out, "fig7a_summary_phase.svg", path, tmp))) return 0;
  afv_svg_plot(fp, &pl, s, ns);
  ok = figure_close(fp, tmp, path)
       && snapshot(out, P, 4, 0.1, "fig7b_clustered_epithelial.svg")
       && snapshot(out, P, 8.8, 0.1, "fig7b_clustered_mesenchymal.svg")
       && snapshot(out, P, 4.4, 2.6, "fig7b_dispersed_epithelial.svg")
       && snapshot(out, P, 8.8, 2.6, "fig7b_dispersed_mesenchymal.svg")
       && snapshot(out, P, 5.6, 0.4, "fig1_snapshot.svg");
  state_claims(C, P, 4, 0.1, 1, 1);
  state_claims(C, P, 8.8, 0.1, 1, 0);
  state_claims(C, P, 4.4, 2.6, 0, 1);
  state_claims(C, P, 8.8, 2.6, 0, 0);
  return ok;
}

/* ---- the finite-size study --------------------------------------------------- */
typedef struct fss {
  int nn, np, nv;
  double N[MAX_VALUES], p0[MAX_VALUES], v0[MAX_VALUES];
  double *mean, *sem;          /* [(in np + ip) nv + iv] */
  double *half[2];             /* N_GC/N over the first, second half of the
                               ** steady window (seed 1): a drift test */
} fss;

#define FSS_AT(F, in, ip, iv) ((((in) * (F)->np + (ip)) * (F)->nv) + (iv))

/* Mean N_GC/N of series.csv over the two halves of the steady window. */
static void halves(const char *dir, double *h)
{
  int n = 0, m = 0, k, cnt[2] = {0, 0};
  double *t = run_column(dir, "series.csv", "time", &n);
  double *y = run_column(dir, "series.csv", "ngc_frac", &m);
  double from = summary_value(dir, "steady_from"), s[2] = {0, 0};
  h[0] = h[1] = NAN;
  if (t && y && n == m && isfinite(from)) {
    int first = 0;
    while (first < n && t[first] < from) first++;
    for (k = first; k < n; k++) {
      int j = 2 * (k - first) >= n - first;
      s[j] += y[k];
      cnt[j]++;
    }
    for (k = 0; k < 2; k++) if (cnt[k]) h[k] = s[k] / cnt[k];
  }
  free(t);
  free(y);
}

static int fss_read(const char *out, fss *F)
{
  char path[PATH_LEN], dir[RUN_PATH_MAX];
  csv t, pts;
  int r, cn, cp, cv, cm, cs, k, total;
  static const char *const keys[3] = {"N", "P0", "v0"};
  memset(F, 0, sizeof *F);
  snprintf(dir, sizeof dir, "%s/fss", out);
  if (!table_read(dir, &t)) return 0;
  snprintf(path, sizeof path, "%s/points.csv", dir);
  if (!csv_read(path, &pts)) { csv_free(&t); return 0; }
  cn = csv_col(&t, "N"); cp = csv_col(&t, "P0"); cv = csv_col(&t, "v0");
  cm = csv_col(&t, "ngc_frac_mean"); cs = csv_col(&t, "ngc_frac_sem");
  for (r = 0; r < t.nrow; r++) {
    add_value(F->N, &F->nn, csv_num(&t, r, cn));
    add_value(F->p0, &F->np, csv_num(&t, r, cp));
    add_value(F->v0, &F->nv, csv_num(&t, r, cv));
  }
  total = F->nn * F->np * F->nv;
  F->mean = malloc((size_t)(4 * total + 1) * sizeof(double));
  if (!F->mean) { csv_free(&t); csv_free(&pts); return 0; }
  F->sem = F->mean + total;
  F->half[0] = F->mean + 2 * total;
  F->half[1] = F->mean + 3 * total;
  for (k = 0; k < 4 * total; k++) F->mean[k] = NAN;
  for (r = 0; r < t.nrow; r++) {
    double vals[3];
    int in = index_of(F->N, F->nn, vals[0] = csv_num(&t, r, cn));
    int ip = index_of(F->p0, F->np, vals[1] = csv_num(&t, r, cp));
    int iv = index_of(F->v0, F->nv, vals[2] = csv_num(&t, r, cv));
    double h[2] = {NAN, NAN};
    if (in < 0 || ip < 0 || iv < 0) continue;
    k = FSS_AT(F, in, ip, iv);
    F->mean[k] = csv_num(&t, r, cm);
    F->sem[k] = csv_num(&t, r, cs);
    if (find_run(&pts, dir, 3, keys, vals, 0, path)) halves(path, h);
    F->half[0][k] = h[0];
    F->half[1][k] = h[1];
  }
  csv_free(&t);
  csv_free(&pts);
  return 1;
}

/* Largest |d(N_GC/N)/d v0| between consecutive v0 of one curve. */
static double max_slope(const fss *F, int in, int ip)
{
  double best = NAN;
  int iv;
  for (iv = 0; iv + 1 < F->nv; iv++) {
    double a = F->mean[FSS_AT(F, in, ip, iv)];
    double b = F->mean[FSS_AT(F, in, ip, iv + 1)];
    double s = fabs(b - a) / (F->v0[iv + 1] - F->v0[iv]);
    if (isfinite(s) && !(s <= best)) best = s;
  }
  return best;
}

/* The grid's N_GC/N against v0 at P0 = p0 (N = 400, the sweep's start)
** as extra series of the finite-size figure: the curve, then its error
** bars; returns the number of series written into s. */
static int grid_curve(const plane *P, double p0, const char *label,
                      const char *color, double *buf, afv_plot_series *s)
{
  int ip = index_of(P->p0, P->np, p0), iv, m = 0, ns = 1;
  double *x = buf, *y = buf + P->nv, *bar = buf + 2 * P->nv;
  if (ip < 0) return 0;
  for (iv = 0; iv < P->nv; iv++) {
    double e = at(P, Q_NGC, ip, iv, 1), v = at(P, Q_NGC, ip, iv, 0);
    if (!isfinite(v)) continue;
    x[m] = P->v0[iv];
    y[m] = v;
    if (isfinite(e) && e > 0) {
      double *b = bar + 4 * m;
      b[0] = b[1] = P->v0[iv];
      b[2] = v - e;
      b[3] = v + e;
      memset(&s[ns], 0, sizeof s[ns]);
      s[ns].x = b; s[ns].y = b + 2; s[ns].n = 2; s[ns].color = color;
      ns++;
    }
    m++;
  }
  memset(&s[0], 0, sizeof s[0]);
  s[0].x = x; s[0].y = y; s[0].n = m; s[0].label = label; s[0].color = color;
  return ns;
}

static int fss_outputs(const char *out, const fss *F, const plane *P)
{
  char path[PATH_LEN], tmp[PATH_LEN + 16], (*label)[64], glab[2][64];
  int nc = F->nn * F->np, in, ip, iv, ok, ne = 0, g;
  static const char *gcol[2] = {"#000000", "#7f7f7f"};
  double *buf = malloc((size_t)(2 * 6 * P->nv + 1) * sizeof *buf);
  afv_plot_series *ex = calloc((size_t)(2 * (P->nv + 1)), sizeof *ex);
  afv_plot pl;
  curveset cs;
  FILE *fp;
  label = malloc((size_t)(nc + 1) * sizeof *label);
  if (!label || !buf || !ex) { free(label); free(buf); free(ex); return 0; }
  for (in = 0; in < F->nn; in++)
    for (ip = 0; ip < F->np; ip++)
      snprintf(label[in * F->np + ip], 64, "N = %g, P0 = %g", F->N[in],
               F->p0[ip]);
  /* The lowest and highest P0 of the study as the grid has them. */
  for (g = 0; g < 2 && F->np > 0; g++) {
    double p0 = F->p0[g ? F->np - 1 : 0];
    snprintf(glab[g], 64, "grid N = 400 (cluster start), P0 = %g", p0);
    ne += grid_curve(P, p0, glab[g], gcol[g], buf + g * 6 * P->nv, ex + ne);
  }
  memset(&pl, 0, sizeof pl);
  pl.title = "Finite size: N_GC/N against v0 (fss sweep; black/grey: grid)";
  pl.xlabel = "v0 (l/time)";
  pl.ylabel = "N_GC/N";
  cs.nc = nc; cs.n = F->nv; cs.xper = 0; cs.x = F->v0; cs.y = F->mean;
  cs.err = F->sem; cs.label = label;
  ok = plot_curves(out, "fss_ngc_vs_v0.svg", &pl, &cs, ex, ne);
  free(label);
  free(buf);
  free(ex);
  if (!ok) return 0;
  /* fss.csv: every state point, then per N the crossing of the lowest and
  ** highest P0 curves and the steepest slope of each. */
  snprintf(path, sizeof path, "%s/fss.csv", out);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return 0;
  fprintf(fp, "N,P0,v0,ngc_mean,ngc_sem,ngc_first_half,ngc_second_half\n");
  for (in = 0; in < F->nn; in++)
    for (ip = 0; ip < F->np; ip++)
      for (iv = 0; iv < F->nv; iv++) {
        int k = FSS_AT(F, in, ip, iv);
        fprintf(fp, "%g,%g,%g,%.6g,%.6g,%.6g,%.6g\n", F->N[in], F->p0[ip],
                F->v0[iv], F->mean[k], F->sem[k], F->half[0][k],
                F->half[1][k]);
      }
  fprintf(fp, "\nN,v0_cross_P0_%g_P0_%g,max_slope_P0_%g,max_slope_P0_%g\n",
          F->p0[0], F->p0[F->np - 1], F->p0[0], F->p0[F->np - 1]);
  for (in = 0; in < F->nn; in++) {
    double xc = NAN;
    if (F->np >= 2
        && !afv_curves_cross(F->nv, F->v0, F->mean + FSS_AT(F, in, 0, 0),
                             F->mean + FSS_AT(F, in, F->np - 1, 0), &xc))
      xc = NAN;
    fprintf(fp, "%g,%.6g,%.6g,%.6g\n", F->N[in], xc, max_slope(F, in, 0),
            max_slope(F, in, F->np - 1));
  }
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* ---- run length: the grid's steady window in two halves ------------------ */
/* OUT/halves.csv: N_GC/N at every grid point over the first and the second
** half of the steady window (mean over the seeds), then the common crossing
** v0* and the dispersal fit from each half alone.  A quantity that moves
** between the halves has not settled within the run. */
static int halves_table(const char *out, const plane *P)
{
  char path[PATH_LEN], tmp[PATH_LEN + 16], dir[PATH_LEN];
  int n = P->np * P->nv, ip, iv, k, h;
  double *y = malloc((size_t)(2 * n + 1) * sizeof *y);
  afv_crossing_fit cr;
  FILE *fp;
  if (!y) return 0;
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++) {
      double s[2] = {0, 0}, hv[2];
      int m[2] = {0, 0};
      for (k = 0; run_dir(P, P->p0[ip], P->v0[iv], k, dir); k++) {
        halves(dir, hv);
        for (h = 0; h < 2; h++)
          if (isfinite(hv[h])) { s[h] += hv[h]; m[h]++; }
      }
      for (h = 0; h < 2; h++)
        y[h * n + ip * P->nv + iv] = m[h] ? s[h] / m[h] : NAN;
    }
  snprintf(path, sizeof path, "%s/halves.csv", out);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) { free(y); return 0; }
  fprintf(fp, "P0,v0,ngc_first_half,ngc_second_half\n");
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++)
      fprintf(fp, "%g,%g,%.6g,%.6g\n", P->p0[ip], P->v0[iv],
              y[ip * P->nv + iv], y[n + ip * P->nv + iv]);
  for (h = 0; h < 2; h++) {
    afv_curves_cross_common(P->np, P->nv, P->v0, y + h * n, &cr);
    fprintf(fp, "# v0_star_%s_half %.6g se %.6g pairs %d\n",
            h ? "second" : "first", cr.x, cr.se, cr.pairs);
  }
  free(y);
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* ---- the command ------------------------------------------------------------ */
static const char *paper_usage =
"usage: afv paper OUT\n"
"\n"
"The paper's figures and claims from the sweeps of make paper\n"
"(tools/paper_sweeps.sh) after afv collect: OUT/grid (P0 x v0 at N = 400)\n"
"and OUT/fss (N x P0 x v0).  Writes\n"
"  OUT/figures/figN*_*.svg  one file per panel of the paper's figures\n"
"                           (state points: the grid's nearest)\n"
"  OUT/figures/fss_ngc_vs_v0.svg  N_GC/N against v0 for each N and P0\n"
"  OUT/claims.csv           claim,paper,afv,afv_err,agrees,note: each\n"
"                           number the paper states and afv's; numeric\n"
"                           claims agree when |afv - paper| <= 2 sqrt(\n"
"                           afv_err^2 + paper_err^2); each note ends\n"
"                           with the runs' afv version and integration\n"
"When OUT/grid/scale says smoke (make paper SCALE=smoke), every agrees\n"
"is 'not established (smoke run)' and every figure says SMOKE RUN.\n"
"  OUT/fss.csv              the finite-size table\n"
"  OUT/halves.csv           the grid's N_GC/N over each half of the steady\n"
"                           window, and v0* from each (a run-length test)\n"
"Exit status: 0 written, 2 a sweep's table is missing, unreadable or\n"
"a header only (no run finished).\n";

int cmd_paper(int argc, char **argv)
{
  char path[PATH_LEN];
  const char *out;
  plane P;
  fss F;
  claims *C;
  int ok;
  if (argc == 2 && (strcmp(argv[1], "--help") == 0
                    || strcmp(argv[1], "-h") == 0)) {
    fputs(paper_usage, stdout);
    return 0;
  }
  if (argc != 2) {
    fputs(paper_usage, stderr);
    return EXIT_BAD_INPUT;
  }
  out = argv[1];
  if (strlen(out) > RUN_PATH_MAX - 64) return bad_input("paper: OUT too long");
  read_scale(out);
  if (!plane_read(out, &P)) { plane_free(&P); return EXIT_BAD_INPUT; }
  read_integration(&P);
  if (!fss_read(out, &F)) { plane_free(&P); return EXIT_BAD_INPUT; }
  snprintf(path, sizeof path, "%s/figures", out);
  if (mkdir(path, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv paper: %s: %s\n", path, strerror(errno));
    plane_free(&P);
    free(F.mean);
    return EXIT_BAD_INPUT;
  }
  C = calloc(1, sizeof *C);
  ok = C && cluster_figures(out, &P, C) && fluctuation_figures(out, &P, C)
       && confluency_figures(out, &P, C) && dynamics_figures(out, &P, C)
       && summary_figures(out, &P, C) && fss_outputs(out, &F, &P)
       && halves_table(out, &P)
       && claims_write(out, C);
  if (ok) printf("afv paper: %s/figures, %s/claims.csv (%d claims), "
                 "%s/fss.csv%s\n", out, out, C->n, out, smoke ? " (smoke "
                 "run: figures and claims marked, the numbers mean nothing)"
                 : "");
  else fprintf(stderr, "afv paper: could not write into %s\n", out);
  free(C);
  plane_free(&P);
  free(F.mean);
  return ok ? 0 : EXIT_BAD_INPUT;
}
