/*
** collect.c -- afv collect DIR: a sweep's (afv sweep) finished jobs into
** one table of state points, the list of missing jobs, the dispersal
** boundary fit and the phase-diagram figures.  It only reads: the order
** parameters come from each run's analysis/summary.txt (afv analyze).
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

#define COLLECT_MAX_KEYS 32   /* swept keys in points.csv */
#define FIELD_MAX 64          /* longest value in points.csv */
#define LINE_MAX_POINTS 4096  /* longest line of points.csv */

/* The paper's thresholds (Sec. Results): clustered if N_GC/N >= 0.99,
** epithelial if Omega >= 0.5, glassy if D_eff < 1e-8. */
#define CLUSTER_LEVEL 0.99
#define CONFLUENCY_LEVEL 0.5
#define DEFF_GLASS_LEVEL 1e-8
/* Glassy if msd_beta < 0.5: halfway between a caged relative MSD (slope 0)
** and a diffusive one (slope 1), at lags set as fractions of the window. */
#define BETA_GLASS_LEVEL 0.5

/* Order parameters of the table: column name and summary.txt key. */
typedef struct order_param {
  const char *name, *key, *label;
  int logy;               /* 1: plotted on a log axis */
} order_param;
static const order_param params[] = {
  {"ngc_frac", "ngc_frac_mean", "N_GC/N", 0},
  {"n_clusters", "n_clusters_mean", "number of clusters", 1},
  {"omega", "omega_mean", "Omega", 0},
  {"D_eff", "D_eff", "D_eff", 1},
  {"tau_NGC", "tau_NGC", "tau_NGC (time)", 1},
  {"t1_rate", "t1_rate", "T1 rate (per cell per time)", 1},
  {"msd_beta", "msd_beta", "msd_beta (long-time MSD_rel slope)", 0},
};
#define N_PARAMS ((int)(sizeof params / sizeof params[0]))
enum { P_NGC, P_NCL, P_OMEGA, P_DEFF, P_TAU, P_T1, P_BETA };

typedef struct job {
  char id[FIELD_MAX];
  char seed[FIELD_MAX];
  int point;              /* state point it belongs to */
  int done;               /* 1: summary.txt read */
  double v[N_PARAMS];     /* its order parameters */
} job;

typedef struct point {
  int first;              /* first job of the point (its key values) */
  int n;                  /* finished jobs */
  double mean[N_PARAMS], sem[N_PARAMS];
} point;

typedef struct sweep_table {
  const char *dir;
  int nkeys;
  char key[COLLECT_MAX_KEYS][FIELD_MAX];
  int njobs, npoints;
  job *jobs;
  char (*val)[COLLECT_MAX_KEYS][FIELD_MAX];  /* val[j][k]: key k of job j */
  point *points;
} sweep_table;

static const char *collect_usage =
  "usage: afv collect DIR\n"
  "\n"
  "Reads the sweep in DIR (afv sweep): points.csv and, for every job,\n"
  "runs/ID/analysis/summary.txt, and writes\n"
  "  DIR/table.csv    one row per state point with a finished job: the\n"
  "                   swept keys, n_seeds, then NAME_mean and NAME_sem\n"
  "                   (standard error over the seeds) for ngc_frac,\n"
  "                   n_clusters, omega, D_eff, tau_NGC, t1_rate, msd_beta,\n"
  "                   then the phase labels of the means:\n"
  "       cluster_phase      clustered if N_GC/N >= 0.99, else dispersed\n"
  "       confluency_phase   epithelial if Omega >= 0.5, else mesenchymal\n"
  "       dynamic_phase      glassy if msd_beta < 0.5, else fluid: the slope\n"
  "                          of log MSD_rel vs log lag at lags 1% .. 10% of\n"
  "                          the steady window is ~0 for caged cells and ~1\n"
  "                          for diffusing ones whatever the run's length\n"
  "       dynamic_phase_deff the paper's: glassy if D_eff < 1e-8; D_eff\n"
  "                          of a caged tissue falls like 1/lag, so this\n"
  "                          label depends on the run length and the lag\n"
  "                          (undefined at v0 = 0, where D_eff is nan)\n"
  "  DIR/missing.txt  every job without a summary, with the last line of\n"
  "                   its log (logs/ID.log); also listed on stderr\n"
  "  DIR/fits.txt     the dispersal boundary v_s(P0) = v0* - c P0^alpha,\n"
  "                   least squares over the v0 where N_GC/N falls below\n"
  "                   0.99 at each P0, with standard errors\n"
  "  DIR/figures/     NAME_vs_v0.svg (mean +- sem against v0, a curve per\n"
  "                   value of the other keys) if v0 is swept; if P0 and\n"
  "                   v0 are the swept keys, map_ngc_frac.svg, map_omega.svg,\n"
  "                   map_D_eff.svg, map_msd_beta.svg (threshold contour in\n"
  "                   black, the fitted boundary dashed) and boundary.svg\n"
  "Exit status: 0 every job finished, 1 some missing (the rest is still\n"
  "written), 2 bad input.\n";

/* ---- reading --------------------------------------------------------------- */
/* Splits line at commas into at most max fields of FIELD_MAX; -1 if a field
** is too long or there are too many. */
static int split_csv(char *line, char (*f)[FIELD_MAX], int max)
{
  int n = 0;
  char *p = line;
  line[strcspn(line, "\r\n")] = 0;
  for (;;) {
    size_t m = strcspn(p, ",");
    if (n == max || m >= FIELD_MAX) return -1;
    memcpy(f[n], p, m);
    f[n++][m] = 0;
    if (!p[m]) return n;
    p += m + 1;
  }
}

static int read_header(sweep_table *T, FILE *fp, const char *path)
{
  char line[LINE_MAX_POINTS], f[COLLECT_MAX_KEYS + 2][FIELD_MAX];
  int n, k;
  if (!fgets(line, sizeof line, fp)
      || (n = split_csv(line, f, COLLECT_MAX_KEYS + 2)) < 2
      || strcmp(f[0], "id") || strcmp(f[n - 1], "seed")) {
    fprintf(stderr, "afv collect: %s:1: expected the header id,KEY...,seed "
            "of afv sweep\n", path);
    return 0;
  }
  T->nkeys = n - 2;
  for (k = 0; k < T->nkeys; k++) snprintf(T->key[k], FIELD_MAX, "%s", f[k + 1]);
  return 1;
}

/* points.csv into T->jobs and T->val. */
static int read_points(sweep_table *T)
{
  char path[RUN_PATH_MAX + 32], line[LINE_MAX_POINTS];
  char f[COLLECT_MAX_KEYS + 2][FIELD_MAX];
  int cap = 0, lineno = 1;
  FILE *fp;
  snprintf(path, sizeof path, "%s/points.csv", T->dir);
  if (!(fp = fopen(path, "r"))) {
    fprintf(stderr, "afv collect: %s: cannot open: %s (is %s a sweep of afv "
            "sweep?)\n", path, strerror(errno), T->dir);
    return 0;
  }
  if (!read_header(T, fp, path)) return fclose(fp), 0;
  while (fgets(line, sizeof line, fp)) {
    int n = split_csv(line, f, COLLECT_MAX_KEYS + 2), k;
    lineno++;
    if (n != T->nkeys + 2 || !f[0][0] || strchr(f[0], '/')) {
      fprintf(stderr, "afv collect: %s:%d: expected %d fields (id, keys, "
              "seed)\n", path, lineno, T->nkeys + 2);
      return fclose(fp), 0;
    }
    if (T->njobs == cap) {
      void *a, *b;
      cap = cap ? 2 * cap : 64;
      a = realloc(T->jobs, (size_t)cap * sizeof *T->jobs);
      if (a) T->jobs = a;
      b = realloc(T->val, (size_t)cap * sizeof *T->val);
      if (b) T->val = b;
      if (!a || !b) return fclose(fp), !bad_input("collect: out of memory");
    }
    memset(&T->jobs[T->njobs], 0, sizeof *T->jobs);
    snprintf(T->jobs[T->njobs].id, FIELD_MAX, "%s", f[0]);
    snprintf(T->jobs[T->njobs].seed, FIELD_MAX, "%s", f[n - 1]);
    for (k = 0; k < T->nkeys; k++)
      snprintf(T->val[T->njobs][k], FIELD_MAX, "%s", f[k + 1]);
    T->njobs++;
  }
  fclose(fp);
  return 1;
}

/* runs/ID/analysis/summary.txt of job J: its order parameters (NaN for a
** key it lacks).  0 if there is none. */
static int read_summary(const sweep_table *T, job *J)
{
  char path[RUN_PATH_MAX + 96], line[256], key[64];
  FILE *fp;
  int k;
  snprintf(path, sizeof path, "%s/runs/%s/analysis/summary.txt", T->dir, J->id);
  if (!(fp = fopen(path, "r"))) return 0;
  for (k = 0; k < N_PARAMS; k++) J->v[k] = NAN;
  while (fgets(line, sizeof line, fp)) {
    char val[64], *end;
    if (line[0] == '#' || sscanf(line, "%63s %63s", key, val) != 2) continue;
    for (k = 0; k < N_PARAMS; k++)
      if (!strcmp(key, params[k].key)) {
        double v = strtod(val, &end);
        J->v[k] = *end ? NAN : v;
      }
  }
  fclose(fp);
  return 1;
}

/* ---- state points ---------------------------------------------------------- */
static int same_point(const sweep_table *T, int a, int b)
{
  int k;
  for (k = 0; k < T->nkeys; k++)
    if (strcmp(T->val[a][k], T->val[b][k])) return 0;
  return 1;
}

/* Mean and standard error of the mean (sd with n - 1, over sqrt n); the
** standard error is NaN for one seed. */
static void mean_sem(const double *x, int n, double *mean, double *sem)
{
  double s = 0, v = 0;
  int k;
  for (k = 0; k < n; k++) s += x[k];
  s /= n;
  for (k = 0; k < n; k++) v += (x[k] - s) * (x[k] - s);
  *mean = s;
  *sem = n > 1 ? sqrt(v / (n - 1) / n) : NAN;
}

/* Groups the jobs into state points and averages their finished seeds. */
static int make_points(sweep_table *T)
{
  double *x = malloc((size_t)(T->njobs + 1) * sizeof(double));
  int j, q, k;
  T->points = calloc((size_t)T->njobs + 1, sizeof *T->points);
  if (!x || !T->points) return free(x), !bad_input("collect: out of memory");
  for (j = 0; j < T->njobs; j++) {
    /* afv sweep lists the seeds of a point together: try the last first */
    q = T->npoints - 1;
    if (q < 0 || !same_point(T, T->points[q].first, j))
      for (q = 0; q < T->npoints && !same_point(T, T->points[q].first, j);
           q++) {}
    if (q == T->npoints) T->points[T->npoints++].first = j;
    T->jobs[j].point = q;
    T->jobs[j].done = read_summary(T, &T->jobs[j]);
    T->points[q].n += T->jobs[j].done;
  }
  for (q = 0; q < T->npoints; q++)
    for (k = 0; k < N_PARAMS; k++) {
      int m = 0;
      for (j = 0; j < T->njobs; j++)
        if (T->jobs[j].point == q && T->jobs[j].done) x[m++] = T->jobs[j].v[k];
      if (m) mean_sem(x, m, &T->points[q].mean[k], &T->points[q].sem[k]);
    }
  free(x);
  return 1;
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
    fprintf(fp, ",%s_mean,%s_sem", params[k].name, params[k].name);
  fputs(",cluster_phase,confluency_phase,dynamic_phase,dynamic_phase_deff\n",
        fp);
  for (q = 0; q < T->npoints; q++) {
    const point *p = &T->points[q];
    if (p->n == 0) continue;
    for (k = 0; k < T->nkeys; k++) fprintf(fp, "%s,", T->val[p->first][k]);
    fprintf(fp, "%d", p->n);
    for (k = 0; k < N_PARAMS; k++) {
      put_number(fp, p->mean[k]);
      put_number(fp, p->sem[k]);
    }
    fprintf(fp, ",%s,%s,%s,%s\n", cluster_phase(p), confluency_phase(p),
            dynamic_phase(p), dynamic_phase_deff(p));
  }
}

/* Why job J has no summary: the last non-empty line of logs/ID.log that is
** not a warning (else its last line), or the state of its run folder. */
static void missing_reason(const sweep_table *T, const job *J, char *out,
                           size_t len)
{
  char path[RUN_PATH_MAX + 96], line[1024];
  FILE *fp;
  struct stat sb;
  out[0] = 0;
  snprintf(path, sizeof path, "%s/logs/%s.log", T->dir, J->id);
  if ((fp = fopen(path, "r"))) {
    int warned = 0;
    while (fgets(line, sizeof line, fp)) {
      line[strcspn(line, "\r\n")] = 0;
      if (!line[0] || (strstr(line, "warning:") && out[0] && !warned))
        continue;
      warned = strstr(line, "warning:") != NULL;
      snprintf(out, len, "%s", line);
    }
    fclose(fp);
  }
  if (out[0]) return;
  snprintf(path, sizeof path, "%s/runs/%s", T->dir, J->id);
  snprintf(out, len, "%s", stat(path, &sb) == 0
           ? "unfinished (no error logged: running, or stopped by a kill)"
           : "not started");
}

static void write_missing(FILE *fp, const sweep_table *T)
{
  char why[1024];
  int j, k;
  fprintf(fp, "# afv collect: jobs without runs/ID/analysis/summary.txt, "
          "with the last line of logs/ID.log\n");
  for (j = 0; j < T->njobs; j++) {
    const job *J = &T->jobs[j];
    if (J->done) continue;
    missing_reason(T, J, why, sizeof why);
    fprintf(fp, "%s", J->id);
    for (k = 0; k < T->nkeys; k++) fprintf(fp, " %s=%s", T->key[k], T->val[j][k]);
    fprintf(fp, " seed=%s: %s\n", J->seed, why);
  }
}

/* ---- the (P0, v0) plane ------------------------------------------------------ */
static int key_index(const sweep_table *T, const char *name)
{
  int k;
  for (k = 0; k < T->nkeys; k++)
    if (!strcmp(T->key[k], name)) return k;
  return -1;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Sorted distinct numeric values of key k over the points; count. */
static int distinct_values(const sweep_table *T, int k, double *out)
{
  int q, n = 0, m = 0;
  for (q = 0; q < T->npoints; q++)
    out[n++] = atof(T->val[T->points[q].first][k]);
  qsort(out, (size_t)n, sizeof *out, cmp_double);
  for (q = 0; q < n; q++)
    if (m == 0 || out[q] != out[m - 1]) out[m++] = out[q];
  return m;
}

/* The (P0, v0) grid: a map's x (P0), y (v0) and, per point q, its cell. */
typedef struct plane {
  int nx, ny;
  double *x, *y;
  int *cell;              /* cell[q] = j nx + i of point q, or -1 */
} plane;

static int plane_make(const sweep_table *T, plane *P)
{
  int kp = key_index(T, "P0"), kv = key_index(T, "v0"), q;
  memset(P, 0, sizeof *P);
  if (kp < 0 || kv < 0 || T->nkeys != 2) return 0;
  P->x = malloc((size_t)T->npoints * sizeof(double));
  P->y = malloc((size_t)T->npoints * sizeof(double));
  P->cell = malloc((size_t)T->npoints * sizeof(int));
  if (!P->x || !P->y || !P->cell) return 0;
  P->nx = distinct_values(T, kp, P->x);
  P->ny = distinct_values(T, kv, P->y);
  for (q = 0; q < T->npoints; q++) {
    double p0 = atof(T->val[T->points[q].first][kp]);
    double v0 = atof(T->val[T->points[q].first][kv]);
    int i = 0, j = 0;
    while (P->x[i] != p0) i++;
    while (P->y[j] != v0) j++;
    P->cell[q] = j * P->nx + i;
  }
  return 1;
}

static void plane_free(plane *P)
{
  free(P->x); free(P->y); free(P->cell);
}

/* Mean of order parameter k over the grid (NaN where no seed finished). */
static void plane_values(const sweep_table *T, const plane *P, int k,
                         double *z)
{
  int q;
  for (q = 0; q < P->nx * P->ny; q++) z[q] = NAN;
  for (q = 0; q < T->npoints; q++)
    if (T->points[q].n > 0) z[P->cell[q]] = T->points[q].mean[k];
}

/* ---- the dispersal boundary -------------------------------------------------- */
/* At each P0, the v0 where N_GC/N falls below CLUSTER_LEVEL; the fit. */
static int boundary(const sweep_table *T, const plane *P, double *bp,
                    double *bv, afv_boundary *fit, int *fitted)
{
  double *z = malloc((size_t)(P->nx * P->ny) * sizeof(double));
  double *col = malloc((size_t)P->ny * sizeof(double));
  int i, j, nb = 0;
  *fitted = 0;
  if (!z || !col) return free(z), free(col), 0;
  plane_values(T, P, P_NGC, z);
  for (i = 0; i < P->nx; i++) {
    for (j = 0; j < P->ny; j++) col[j] = z[j * P->nx + i];
    if (afv_crossing(P->ny, P->y, col, CLUSTER_LEVEL, &bv[nb])) bp[nb++] = P->x[i];
  }
  if (nb >= 3) *fitted = afv_boundary_fit(nb, bp, bv, fit) == AFV_OK;
  free(z);
  free(col);
  return nb;
}

static int write_fits(const char *dir, int nb, const double *bp,
                      const double *bv, const afv_boundary *f, int fitted)
{
  char path[RUN_PATH_MAX + 32], tmp[RUN_PATH_MAX + 96];
  FILE *fp;
  int k;
  snprintf(path, sizeof path, "%s/fits.txt", dir);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return 0;
  fprintf(fp, "# afv collect: dispersal boundary v_s(P0) = v0* - c P0^alpha"
          "\n# points: at each P0, the v0 where the mean N_GC/N falls below "
          "%g\n# (linear interpolation between state points); least squares,"
          "\n# standard errors from s^2 (J^T J)^-1 (nan with 3 points)\n",
          CLUSTER_LEVEL);
  for (k = 0; k < nb; k++) fprintf(fp, "# P0 %.10g v_s %.10g\n", bp[k], bv[k]);
  fprintf(fp, "points %d\n", nb);
  if (fitted)
    fprintf(fp, "v0_star %.6g\nv0_star_se %.6g\nc %.6g\nc_se %.6g\n"
            "alpha %.6g\nalpha_se %.6g\nrss %.6g\n", f->v0star, f->se_v0star,
            f->c, f->se_c, f->alpha, f->se_alpha, f->rss);
  else
    fprintf(fp, "# no fit: %d crossing point(s), 3 needed\n", nb);
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* ---- figures ------------------------------------------------------------------ */
static const char *palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                "#bcbd22", "#17becf"};
#define N_COLORS ((int)(sizeof palette / sizeof palette[0]))

/* Opens DIR/figures/NAME for an atomic write. */
static FILE *figure_open(const char *dir, const char *name, char *path,
                         char *tmp)
{
  snprintf(path, RUN_PATH_MAX + 64, "%s/figures/%s", dir, name);
  return afv_atomic_open(path, tmp, RUN_PATH_MAX + 128);
}

/* The curves of one figure: the points sharing all keys but v0, in order
** of v0; x = v0, y = mean, e = sem. */
typedef struct curves {
  int n;                  /* curves */
  int *start, *len;       /* curve c: order[start[c] .. start[c]+len[c]-1] */
  int *order;             /* point indices, curve by curve, v0 increasing */
  char (*label)[128];
} curves;

/* qsort has no context argument in C99: the table and the v0 column of the
** sort in progress. */
static const sweep_table *sort_table;
static int sort_kv;
static int cmp_v0(const void *a, const void *b)
{
  double x = atof(sort_table->val[sort_table->points[*(const int *)a].first][sort_kv]);
  double y = atof(sort_table->val[sort_table->points[*(const int *)b].first][sort_kv]);
  return x < y ? -1 : x > y;
}

/* 1 if points a and b agree on every key but kv. */
static int same_curve(const sweep_table *T, int a, int b, int kv)
{
  int k;
  for (k = 0; k < T->nkeys; k++)
    if (k != kv && strcmp(T->val[T->points[a].first][k],
                          T->val[T->points[b].first][k]))
      return 0;
  return 1;
}

static int curves_make(const sweep_table *T, int kv, curves *C)
{
  int q, c, m = 0;
  size_t np = (size_t)T->npoints + 1;
  C->start = malloc(np * sizeof(int));
  C->len = calloc(np, sizeof(int));
  C->order = malloc(np * sizeof(int));
  C->label = malloc(np * sizeof *C->label);
  C->n = 0;
  if (!C->start || !C->len || !C->order || !C->label) return 0;
  for (q = 0; q < T->npoints; q++) {
    int done = 0;
    for (c = 0; c < q && !done; c++) done = same_curve(T, c, q, kv);
    if (done || T->points[q].n == 0) continue;
    C->start[C->n] = m;
    for (c = q; c < T->npoints; c++)
      if (T->points[c].n > 0 && same_curve(T, q, c, kv)) C->order[m++] = c;
    C->len[C->n] = m - C->start[C->n];
    C->label[C->n][0] = 0;
    for (c = 0; c < T->nkeys; c++)
      if (c != kv) {
        size_t l = strlen(C->label[C->n]);
        snprintf(C->label[C->n] + l, 128 - l, "%s%s=%s", l ? ", " : "",
                 T->key[c], T->val[T->points[q].first][c]);
      }
    sort_table = T;
    sort_kv = kv;
    qsort(C->order + C->start[C->n], (size_t)C->len[C->n], sizeof(int), cmp_v0);
    C->n++;
  }
  return 1;
}

static void curves_free(curves *C)
{
  free(C->start); free(C->len); free(C->order); free(C->label);
}

/* Order parameter k against v0: one labelled curve per curve of C, then
** each error bar (mean +- sem) as an unlabelled two-point series. */
static int plot_vs_v0(const char *dir, const sweep_table *T, int kv,
                      const curves *C, int k)
{
  char name[64], path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 128];
  int n = T->npoints, c, i, ns = 0;
  double *x = malloc((size_t)n * 3 * sizeof(double)), *y = x ? x + n : NULL;
  double *bar = malloc((size_t)n * 4 * sizeof(double));
  afv_plot_series *s = malloc((size_t)(C->n + n) * sizeof *s);
  afv_plot pl;
  FILE *fp;
  int ok = 0;
  if (!x || !bar || !s) goto done;
  for (c = 0; c < C->n; c++) {
    const int *o = C->order + C->start[c];
    memset(&s[ns], 0, sizeof s[ns]);
    s[ns].x = x + C->start[c];
    s[ns].y = y + C->start[c];
    s[ns].n = C->len[c];
    s[ns].label = C->label[c];
    s[ns].color = palette[c % N_COLORS];
    ns++;
    for (i = 0; i < C->len[c]; i++) {
      const point *p = &T->points[o[i]];
      x[C->start[c] + i] = atof(T->val[p->first][kv]);
      y[C->start[c] + i] = p->mean[k];
    }
  }
  for (c = 0; c < C->n; c++)
    for (i = 0; i < C->len[c]; i++) {
      const point *p = &T->points[C->order[C->start[c] + i]];
      double *b = bar + 4 * (C->start[c] + i);
      if (!isfinite(p->sem[k]) || !(p->sem[k] > 0)) continue;
      b[0] = b[1] = x[C->start[c] + i];
      b[2] = p->mean[k] - p->sem[k];
      b[3] = p->mean[k] + p->sem[k];
      memset(&s[ns], 0, sizeof s[ns]);
      s[ns].x = b;
      s[ns].y = b + 2;
      s[ns].n = 2;
      s[ns].color = palette[c % N_COLORS];
      ns++;
    }
  memset(&pl, 0, sizeof pl);
  pl.title = params[k].label;
  pl.xlabel = "v0 (l/time)";
  pl.ylabel = params[k].label;
  pl.logy = params[k].logy;
  snprintf(name, sizeof name, "%s_vs_v0.svg", params[k].name);
  if (!(fp = figure_open(dir, name, path, tmp))) goto done;
  afv_svg_plot(fp, &pl, s, ns);
  ok = afv_atomic_commit(fp, tmp, path) == AFV_OK;
done:
  free(x); free(bar); free(s);
  return ok;
}

/* "" if the level lies within the finite values of z, else which side
** they all are on (the map then has no contour, and says why). */
static const char *level_side(const double *z, int n, double level)
{
  int k, above = 0, below = 0;
  for (k = 0; k < n; k++) {
    above += z[k] >= level;
    below += z[k] < level;
  }
  return above && below ? "" : above ? " (none: every point above)"
         : below ? " (none: every point below)" : "";
}

static int draw_map(const char *dir, const sweep_table *T, const plane *P,
                    int k, int logz, double level, const double *cx,
                    const double *cy, int cn)
{
  char name[64], path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 128];
  char title[128];
  double *z = malloc((size_t)(P->nx * P->ny) * sizeof(double));
  afv_map m;
  FILE *fp;
  int ok = 0;
  if (!z) return 0;
  plane_values(T, P, k, z);
  memset(&m, 0, sizeof m);
  snprintf(title, sizeof title, "%s over (P0, v0); contour at %g%s",
           params[k].label, level, level_side(z, P->nx * P->ny, level));
  m.title = title;
  m.xlabel = "P0 (l)";
  m.ylabel = "v0 (l/time)";
  m.zlabel = params[k].label;
  m.nx = P->nx; m.ny = P->ny; m.x = P->x; m.y = P->y; m.z = z;
  m.logz = logz;
  m.level = level;
  m.cx = cx; m.cy = cy; m.cn = cn;
  snprintf(name, sizeof name, "map_%s.svg", params[k].name);
  if ((fp = figure_open(dir, name, path, tmp))) {
    afv_svg_map(fp, &m);
    ok = afv_atomic_commit(fp, tmp, path) == AFV_OK;
  }
  free(z);
  return ok;
}

/* Boundary points and the fitted curve against P0. */
static int plot_boundary(const char *dir, int nb, const double *bp,
                         const double *bv, const double *cx, const double *cy,
                         int cn)
{
  char path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 128];
  afv_plot pl;
  afv_plot_series s[2];
  FILE *fp;
  memset(&pl, 0, sizeof pl);
  memset(s, 0, sizeof s);
  pl.title = "Dispersal boundary v_s(P0) = v0* - c P0^alpha";
  pl.xlabel = "P0 (l)";
  pl.ylabel = "v_s (l/time)";
  s[0].x = bp; s[0].y = bv; s[0].n = nb; s[0].points = 1;
  s[0].label = "N_GC/N crosses 0.99";
  s[0].color = "#1f77b4";
  s[1].x = cx; s[1].y = cy; s[1].n = cn;
  s[1].label = "fit";
  s[1].color = "#d62728";
  if (!(fp = figure_open(dir, "boundary.svg", path, tmp))) return 0;
  afv_svg_plot(fp, &pl, s, cn > 1 ? 2 : 1);
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

#define CURVE_POINTS 100

/* The maps, the boundary and fits.txt, when P0 and v0 are the swept keys. */
static int plane_figures(const char *dir, const sweep_table *T)
{
  plane P;
  afv_boundary fit;
  double *bp = NULL, *bv = NULL, cx[CURVE_POINTS], cy[CURVE_POINTS];
  int nb, fitted = 0, cn = 0, k, ok;
  if (!plane_make(T, &P)) {
    plane_free(&P);
    printf("maps and boundary fit: skipped (they need exactly the keys P0 "
           "and v0 swept)\n");
    return 1;
  }
  bp = malloc((size_t)P.nx * sizeof(double));
  bv = malloc((size_t)P.nx * sizeof(double));
  ok = bp && bv;
  nb = ok ? boundary(T, &P, bp, bv, &fit, &fitted) : 0;
  for (k = 0; fitted && k < CURVE_POINTS; k++) {
    cx[k] = P.x[0] + (P.x[P.nx - 1] - P.x[0]) * k / (CURVE_POINTS - 1);
    cy[k] = fit.v0star - fit.c * pow(cx[k], fit.alpha);
    cn++;
  }
  ok = ok && write_fits(dir, nb, bp, bv, &fit, fitted)
       && draw_map(dir, T, &P, P_NGC, 0, CLUSTER_LEVEL, cx, cy, cn)
       && draw_map(dir, T, &P, P_OMEGA, 0, CONFLUENCY_LEVEL, NULL, NULL, 0)
       && draw_map(dir, T, &P, P_DEFF, 1, DEFF_GLASS_LEVEL, NULL, NULL, 0)
       && draw_map(dir, T, &P, P_BETA, 0, BETA_GLASS_LEVEL, NULL, NULL, 0)
       && plot_boundary(dir, nb, bp, bv, cx, cy, cn);
  if (fitted)
    printf("boundary: v0* = %.4g +- %.2g, c = %.4g +- %.2g, alpha = %.4g +- "
           "%.2g (%d points)\n", fit.v0star, fit.se_v0star, fit.c, fit.se_c,
           fit.alpha, fit.se_alpha, nb);
  else
    printf("boundary: %d crossing point(s), no fit (3 needed)\n", nb);
  free(bp);
  free(bv);
  plane_free(&P);
  return ok;
}

static int write_figures(const char *dir, const sweep_table *T)
{
  char path[RUN_PATH_MAX + 32];
  int kv = key_index(T, "v0"), k, ok = 1;
  curves C;
  snprintf(path, sizeof path, "%s/figures", dir);
  if (mkdir(path, 0777) != 0 && errno != EEXIST) return 0;
  if (kv >= 0) {
    ok = curves_make(T, kv, &C);
    for (k = 0; ok && k < N_PARAMS; k++) ok = plot_vs_v0(dir, T, kv, &C, k);
    curves_free(&C);
  } else {
    printf("figures against v0: skipped (v0 is not swept)\n");
  }
  return ok && plane_figures(dir, T);
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
    fprintf(stderr, "afv collect: %s: cannot write\n", path);
    return 0;
  }
  return 1;
}

/* Lists the missing jobs on stderr (the first 20; all in missing.txt). */
static int report_missing(const sweep_table *T)
{
  char why[1024];
  int j, m = 0;
  for (j = 0; j < T->njobs; j++) {
    if (T->jobs[j].done) continue;
    if (++m <= 20) {
      missing_reason(T, &T->jobs[j], why, sizeof why);
      fprintf(stderr, "afv collect: missing job %s: %s\n", T->jobs[j].id, why);
    }
  }
  if (m)
    fprintf(stderr, "afv collect: %d of %d jobs missing (all in %s/"
            "missing.txt)\n", m, T->njobs, T->dir);
  return m;
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
  ok = read_points(&T) && make_points(&T);
  if (ok) {
    missing = report_missing(&T);
    ok = write_one(T.dir, "table.csv", write_table, &T)
         && write_one(T.dir, "missing.txt", write_missing, &T);
    if (ok && !write_figures(T.dir, &T)) {
      fprintf(stderr, "afv collect: %s/figures: cannot write\n", T.dir);
      ok = 0;
    }
  }
  if (ok)
    printf("%d state points (%d of %d jobs finished): %s/table.csv\n",
           T.npoints, T.njobs - missing, T.njobs, T.dir);
  free(T.jobs);
  free(T.val);
  free(T.points);
  return !ok ? EXIT_BAD_INPUT : missing ? EXIT_CHECK_FAILED : 0;
}
