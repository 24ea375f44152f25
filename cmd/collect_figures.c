/*
** collect_figures.c -- afv collect's figures: the (P0, v0) plane of a
** sweep's state points, the dispersal boundary v_s(P0) fitted to it
** (fits.txt) and the phase-diagram figures (figures/: maps with the
** paper's thresholds, each order parameter against v0 or P0).
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir */
#include "collect.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the (P0, v0) plane ------------------------------------------------------ */
int key_index(const sweep_table *T, const char *name)
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
    out[n++] = NUM(T, T->points[q].first, k);
  qsort(out, (size_t)n, sizeof *out, cmp_double);
  for (q = 0; q < n; q++)
    if (m == 0 || out[q] != out[m - 1]) out[m++] = out[q];
  return m;
}

/* The index of v in the sorted distinct values x[0 .. n-1] (it is one). */
static int value_index(const double *x, int n, double v)
{
  int lo = 0, hi = n - 1;
  while (lo < hi) {
    int mid = lo + (hi - lo) / 2;
    if (x[mid] < v) lo = mid + 1;
    else hi = mid;
  }
  return lo;
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
  /* a map is drawn over a grid: not over scattered points */
  if ((double)P->nx * P->ny > 4.0 * T->npoints + 16) return 0;
  for (q = 0; q < T->npoints; q++) {
    int i = value_index(P->x, P->nx, NUM(T, T->points[q].first, kp));
    int j = value_index(P->y, P->ny, NUM(T, T->points[q].first, kv));
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
    if (afv_curve_cross(P->ny, P->y, col, CLUSTER_LEVEL, &bv[nb]))
      bp[nb++] = P->x[i];
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
/* The curves of one figure: the points sharing all keys but v0, in order
** of v0; x = v0, y = mean, e = sem. */
typedef struct curves {
  int n;                  /* curves */
  int *start, *len;       /* curve c: order[start[c] .. start[c]+len[c]-1] */
  int *order;             /* point indices, curve by curve, v0 increasing */
  char (*label)[128];
} curves;

/* qsort has no context argument in C99: the table of the sort in progress
** and the key its curves run along. */
static const sweep_table *curve_table;
static int curve_key;

/* Points by every key but the curves' (curve_key), then it, then index. */
static int cmp_curve_point(const void *pa, const void *pb)
{
  int a = *(const int *)pa, b = *(const int *)pb, c;
  int ja = curve_table->points[a].first, jb = curve_table->points[b].first;
  if ((c = cmp_point(curve_table, ja, jb, curve_key)) != 0) return c;
  if ((c = cmp_value(curve_table, ja, jb, curve_key)) != 0) return c;
  return (a > b) - (a < b);
}

/* The points with a verified job, sorted by the other keys and v0: runs of
** equal other keys are the curves. */
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
  for (q = 0; q < T->npoints; q++)
    if (T->points[q].n > 0) C->order[m++] = q;
  curve_table = T;
  curve_key = kv;
  qsort(C->order, (size_t)m, sizeof(int), cmp_curve_point);
  for (q = 0; q < m; q++) {
    int first = T->points[C->order[q]].first;
    if (q && !cmp_point(T, T->points[C->order[q - 1]].first, first, kv)) {
      C->len[C->n - 1]++;
      continue;
    }
    C->start[C->n] = q;
    C->len[C->n] = 1;
    C->label[C->n][0] = 0;
    for (c = 0; c < T->nkeys; c++)
      if (c != kv) {
        size_t l = strlen(C->label[C->n]);
        snprintf(C->label[C->n] + l, 128 - l, "%s%s=%s", l ? ", " : "",
                 T->key[c], VAL(T, first, c));
      }
    C->n++;
  }
  return 1;
}

static void curves_free(curves *C)
{
  free(C->start); free(C->len); free(C->order); free(C->label);
}

/* Why a figure of order parameter k has no point: every mean is nan. */
static const char *no_data_reason(int k)
{
  if (k == P_BETA)
    return "msd_beta is nan at every state point: each steady window is too "
           "short for 3 lags between 1% and 10% of it (afv analyze --help)";
  if (k == P_DEFF)
    return "D_eff is nan at every state point (v0 = 0 or Dr = 0: D_0 is 0)";
  if (k == P_TAU)
    return "tau_NGC is nan or inf at every state point (N_GC/N constant)";
  return collect_params[k].logy ? "no finite value above 0 at any state point (a "
                          "log axis)" : "no finite value at any state point";
}

/* The axis of the figures against key kv: its label with the unit. */
static const char *axis_label(const char *key)
{
  return !strcmp(key, "v0") ? "v0 (l/time)" : !strcmp(key, "P0") ? "P0 (l)"
         : key;
}

/* Order parameter k against key kv (v0, or P0 when v0 is not swept): one
** labelled curve per curve of C, then each error bar (mean +- sem) as an
** unlabelled two-point line without markers. */
static int plot_against(const char *dir, const sweep_table *T, int kv,
                      const curves *C, int k)
{
  char name[64], path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
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
    s[ns].color = figure_color(c);
    ns++;
    for (i = 0; i < C->len[c]; i++) {
      const point *p = &T->points[o[i]];
      x[C->start[c] + i] = NUM(T, p->first, kv);
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
      s[ns].color = figure_color(c);
      s[ns].points = AFV_PLOT_LINE;
      ns++;
    }
  memset(&pl, 0, sizeof pl);
  pl.title = collect_params[k].label;
  pl.xlabel = axis_label(T->key[kv]);
  pl.ylabel = collect_params[k].label;
  pl.logy = collect_params[k].logy;
  pl.no_data = no_data_reason(k);
  snprintf(name, sizeof name, "%s_vs_%s.svg", collect_params[k].name, T->key[kv]);
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
  char name[64], path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
  char title[128];
  double *z = malloc((size_t)(P->nx * P->ny) * sizeof(double));
  afv_map m;
  FILE *fp;
  int ok = 0;
  if (!z) return 0;
  plane_values(T, P, k, z);
  memset(&m, 0, sizeof m);
  snprintf(title, sizeof title, "%s over (P0, v0); contour at %g%s",
           collect_params[k].label, level, level_side(z, P->nx * P->ny, level));
  m.title = title;
  m.xlabel = "P0 (l)";
  m.ylabel = "v0 (l/time)";
  m.zlabel = collect_params[k].label;
  m.nx = P->nx; m.ny = P->ny; m.x = P->x; m.y = P->y; m.z = z;
  m.logz = logz;
  m.level = level;
  m.cx = cx; m.cy = cy; m.cn = cn;
  snprintf(name, sizeof name, "map_%s.svg", collect_params[k].name);
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
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
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

/* The figures against v0 (a curve per value of the other keys); when v0
** is not swept, against P0 (a sweep over P0 alone: the EMT). */
int write_figures(const char *dir, const sweep_table *T)
{
  char path[RUN_PATH_MAX + 32];
  int kv = key_index(T, "v0"), k, ok = 1;
  curves C;
  snprintf(path, sizeof path, "%s/figures", dir);
  if (mkdir(path, 0777) != 0 && errno != EEXIST) return 0;
  if (kv < 0) kv = key_index(T, "P0");
  if (kv >= 0) {
    ok = curves_make(T, kv, &C);
    for (k = 0; ok && k < N_PARAMS; k++) ok = plot_against(dir, T, kv, &C, k);
    curves_free(&C);
  } else {
    printf("figures against v0 or P0: skipped (neither is swept)\n");
  }
  return ok && plane_figures(dir, T);
}

