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
** value, its error and whether they agree: claims.c) and OUT/fss.csv.
** afv paper --claims-from DIR writes the claims alone from a committed
** table (paper_data.c reads the tables).
**
** A separate command rather than more of afv collect: collect tables any
** sweep; this knows which state points the paper's panels show and what
** the paper says about them.  It only reads the sweeps.
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir */
#include "paper.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* ---- figures ------------------------------------------------------------ */
int figure_close(FILE *fp, const char *tmp, const char *path)
{
  /* a smoke figure, or one of a partial grid, gets a red line at its
  ** bottom left, before the "</svg>\n" that ends every SVG afv writes */
  if ((paper_smoke || paper_partial[0]) && fseek(fp, -7L, SEEK_END) == 0) {
    if (paper_smoke)
      fputs("<text x=\"4\" y=\"99%\" font-family=\"sans-serif\" "
            "font-size=\"10\" fill=\"#d62728\">SMOKE RUN (make paper "
            "SCALE=smoke): the numbers mean nothing</text>\n", fp);
    if (paper_partial[0])
      fprintf(fp, "<text x=\"4\" y=\"%s\" font-family=\"sans-serif\" "
              "font-size=\"10\" fill=\"#d62728\">%s</text>\n",
              paper_smoke ? "96%" : "99%", paper_partial);
    fputs("</svg>\n", fp);
  }
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}

/* paper_partial: the line that marks every figure of a grid whose runs are
** not all in (empty for a whole grid). */
static void read_partial(const plane *P)
{
  int all = runs_designed(P);
  paper_partial[0] = 0;
  if (runs_in(P) < all)
    snprintf(paper_partial, sizeof paper_partial, "PARTIAL GRID: %d of %d "
             "runs in (curves join the points that are in; grey: no run)",
             runs_in(P), all);
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
  paper_smoke = !strcmp(word, "smoke");
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
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
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
    s[ns].color = figure_color(c);
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
      s[ns].color = figure_color(c);
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
** optional dashed curve: m filled, nothing written. */
void map_of(const plane *P, int q, const char *title,
                   const char *zlabel, int logz, double level,
                   const double *cx, const double *cy, int cn, afv_map *m)
{
  memset(m, 0, sizeof *m);
  m->title = title;
  m->xlabel = "P0 (l)";
  m->ylabel = "v0 (l/time)";
  m->zlabel = zlabel;
  m->nx = P->np; m->ny = P->nv; m->x = P->p0; m->y = P->v0; m->z = P->mean[q];
  m->logz = logz;
  m->level = level;
  m->cx = cx; m->cy = cy; m->cn = cn;
}

static int plane_map(const char *out, const plane *P, int q, const char *name,
                     const char *title, const char *zlabel, int logz,
                     double level, const double *cx, const double *cy, int cn)
{
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
  afv_map m;
  FILE *fp;
  map_of(P, q, title, zlabel, logz, level, cx, cy, cn, &m);
  if (!(fp = figure_open(out, name, path, tmp))) return 0;
  afv_svg_map(fp, &m);
  return figure_close(fp, tmp, path);
}

/* Copies the final snapshot (final.svg, drawn by afv_svg_write at the end
** of the run) of seed 1 at the grid point nearest (p0, v0). */
static int snapshot(const char *out, const plane *P, double p0, double v0,
                    const char *name)
{
  char dir[PATH_LEN], src[PATH_LEN + 16];
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
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
    char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
    FILE *fp = figure_open(out, name, path, tmp);
    if (!fp) { free(csd); return 0; }
    afv_svg_plot(fp, &pl, s, fit->nbins >= 2 ? 2 : 1);
    ok = figure_close(fp, tmp, path);
  }
  free(csd);
  return ok;
}

/* ---- Fig. 2: clustering ----------------------------------------------------- */
/* N_GC/N of P0 column ip as a function of v0 (contiguous, NaN allowed). */
static void ngc_column(const plane *P, int ip, double *y)
{
  int iv;
  for (iv = 0; iv < P->nv; iv++) y[iv] = at(P, Q_NGC, ip, iv, 0);
}

/* The dispersal points v_s(P0) (N_GC/N falls below 0.99) and their fit. */
int dispersal_boundary(const plane *P, double *bp, double *bv,
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
int boundary_curve(const plane *P, const afv_boundary *fit,
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

static int cluster_figures(const char *out, const plane *P)
{
  double bp[MAX_VALUES], bv[MAX_VALUES], cx[CURVE_POINTS], cy[CURVE_POINTS];
  double *y = malloc((size_t)P->np * P->nv * sizeof *y);
  afv_boundary fit;
  afv_collapse cf;
  afv_powerlaw pl4, pl8;
  int fitted, cn = 0, ip, ok;
  if (!y) return 0;
  for (ip = 0; ip < P->np; ip++) ngc_column(P, ip, y + ip * P->nv);
  afv_collapse_fit(P->np, P->nv, P->v0, y, P->p0, &cf);
  dispersal_boundary(P, bp, bv, &fit, &fitted);
  if (fitted) cn = boundary_curve(P, &fit, cx, cy);
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

static int fluctuation_figures(const char *out, const plane *P)
{
  static const double p0s[2] = {4, 8}, v0s[2] = {1, 1};
  double y[MAX_VALUES], e[MAX_VALUES], mx[2], my[2];
  int iv = nearest(P->v0, P->nv, 1), ip8 = nearest(P->p0, P->np, 8), ip;
  char label[1][64];
  afv_plot pl;
  afv_plot_series ex;
  curveset cs;
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
  }
  snprintf(label[0], 64, "v0 = %g", P->v0[iv]);
  memset(&pl, 0, sizeof pl);
  pl.title = "tau_NGC at v0 = 1 (infinite values not drawn)";
  pl.xlabel = "P0 (l)";
  pl.ylabel = "tau_NGC (time)";
  pl.logy = 1;
  cs.nc = 1; cs.n = P->np; cs.xper = 0; cs.x = P->p0; cs.y = y; cs.err = e;
  cs.label = label;
  return plot_curves(out, "fig3c_tau_ngc_vs_P0.svg", &pl, &cs, NULL, 0);
}

/* ---- Fig. 4: confluency ----------------------------------------------------- */
static int confluency_figures(const char *out, const plane *P)
{
  double pstar = afv_meanfield_p0(0.2, acos(-1.0), 1), cx[2], cy[2];
  cx[0] = cx[1] = pstar;
  cy[0] = P->v0[0];
  cy[1] = P->v0[P->nv - 1];
  return plot_vs_v0(out, P, Q_OMEGA, "fig4a_omega_vs_v0.svg",
                    "Confluency Omega against v0", "Omega", 0, NULL, 0)
         && plane_map(out, P, Q_OMEGA, "fig4b_omega_map.svg",
                      "Omega, contour 0.5; dashed: mean-field P0* = 5.73",
                      "Omega", 0, CONFLUENCY_LEVEL, cx, cy, 2);
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

static int dynamics_figures(const char *out, const plane *P)
{
  double p0s[MAX_VALUES], v0s[MAX_VALUES], lx[2], ly[2];
  int np = p0_between(P, 4, 8, p0s), k, nv = 0, iv;
  afv_plot pl;
  afv_plot_series line;
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
  return plot_traces(out, P, np, p0s, v0s, "series.csv", "time", "t1",
                     "fig6_t1_traces_v0_0.4.svg", &pl, NULL, 0);
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

const char *const boundary_label[N_BOUNDARIES] = {
  "dispersal: N_GC/N = 0.99", "confluency: Omega = 0.5",
  "glass: D_eff = 1e-8", "glass: msd_beta = 0.5"};

void phase_boundaries(const plane *P, boundaries *B)
{
  B->nb[0] = dispersal_boundary(P, B->bx[0], B->by[0], &B->fit, &B->fitted);
  B->nb[1] = boundary_points(P, Q_OMEGA, CONFLUENCY_LEVEL, 1, 0, 1, B->bx[1],
                             B->by[1]);
  B->nb[2] = boundary_points(P, Q_DEFF, DEFF_GLASS_LEVEL, -1, 1, 0, B->bx[2],
                             B->by[2]);
  B->nb[3] = boundary_points(P, Q_BETA, BETA_GLASS_LEVEL, -1, 0, 0, B->bx[3],
                             B->by[3]);
}

static int summary_figures(const char *out, const plane *P)
{
  double cx[CURVE_POINTS], cy[CURVE_POINTS];
  boundaries B;
  afv_plot pl;
  afv_plot_series s[5];
  int ns = 0, k, ok;
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN];
  FILE *fp;
  static const char *col[4] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"};
  phase_boundaries(P, &B);
  memset(s, 0, sizeof s);
  for (k = 0; k < N_BOUNDARIES; k++) {
    s[ns].x = B.bx[k]; s[ns].y = B.by[k]; s[ns].n = B.nb[k];
    s[ns].label = boundary_label[k]; s[ns].color = col[k];
    s[ns].points = B.nb[k] < 2;
    ns++;
  }
  if (B.fitted) {
    s[ns].n = boundary_curve(P, &B.fit, cx, cy);
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
"usage: afv paper OUT [--dt-table FILE]\n"
"       afv paper --grid-only OUT [--dt-table FILE]\n"
"       afv paper --claims-from DIR [--dt-table FILE]\n"
"       afv paper --dt-verdicts FILE OUTFILE\n"
"       afv paper --compare DIR_A DIR_B OUT\n"
"\n"
"The paper's figures and claims from the sweeps of make paper\n"
"(tools/paper_sweeps.sh) after afv collect: OUT/grid (P0 x v0 at N = 400)\n"
"and OUT/fss (N x P0 x v0).  Writes\n"
"  OUT/figures/figN*_*.svg  one file per panel of the paper's figures\n"
"                           (state points: the grid's nearest)\n"
"  OUT/figures/fss_ngc_vs_v0.svg  N_GC/N against v0 for each N and P0\n"
"  OUT/claims.csv           claim,paper,afv,afv_err,agrees,dt_verdict,note:\n"
"                           each number the paper states and afv's, judged\n"
"                           by the rules of doc/reproduction/README.md\n"
"                           (agrees: yes, no, undetermined, not measured);\n"
"                           each note ends with the runs' afv version and\n"
"                           integration, then the claim's dependence on dt\n"
"When OUT/grid/scale says smoke (make paper SCALE=smoke), every agrees\n"
"is 'not established (smoke run)' and every figure says SMOKE RUN.\n"
"  OUT/fss.csv              the finite-size table\n"
"  OUT/halves.csv           the grid's N_GC/N over each half of the steady\n"
"                           window, and v0* from each (a run-length test)\n"
"\n"
"--claims-from DIR: the claims alone, from a record whose runs are gone\n"
"(e.g. doc/reproduction/paper): DIR/grid_table.csv (afv collect's table)\n"
"and DIR/claims.csv, the earlier claims, for the two a table cannot give\n"
"(the cluster-size exponents, fitted to the runs' csd.csv) and the runs'\n"
"integration; rewrites DIR/claims.csv.\n"
"A claim whose runs are not all in (its point short of the design's\n"
"seeds, or for a claim drawn from the whole grid any point) says\n"
"'missing' (its value given, no verdict), and every figure of such a grid\n"
"a red line 'PARTIAL GRID: k of n runs in'.\n"
"--dt-table FILE: the dt study (tools/model_table.sh's dt_table.csv, e.g.\n"
"doc/reproduction/model/dt_table.csv): each claim's dt_verdict is then\n"
"property of the model, property of dt = 0.01, not converged, missing or\n"
"not measured by the rule of doc/reproduction/model/README.md (none: the\n"
"mean field); without it every dt_verdict is not measured.\n"
"--dt-verdicts FILE OUTFILE: that rule applied to every state point and\n"
"observable of the dt table FILE, written to OUTFILE (dt_verdicts.csv).\n"
"--grid-only OUT: as afv paper OUT for a study without OUT/fss (e.g. the\n"
"regularised model's grid): no fss.csv, no finite-size figure.\n"
"--compare DIR_A DIR_B OUT: two records (DIR/grid_table.csv, and\n"
"DIR/claims.csv for the runs' integration) side by side on one colour\n"
"scale: OUT/figures/compare_fig2b_cluster_phase.svg (N_GC/N),\n"
"compare_fig4b_omega_map.svg (Omega), compare_fig5d_dynamic_phase.svg\n"
"(D_eff), compare_fig5d_dynamic_phase_msd_beta.svg (grey: no run;\n"
"both on the design of both tables), and compare_fig7a_summary_phase.svg\n"
"(both records' boundaries in one plot).\n"
"Exit status: 0 written, 2 a sweep's table is missing, unreadable or\n"
"a header only (no run finished), or the dt table is malformed (a\n"
"missing column, a field not a number, two cap values): nothing written.\n";

/* afv paper --claims-from DIR. */
static int claims_from(const char *dir, const dt_table *dt)
{
  char path[PATH_LEN], summary[256];
  plane P;
  claim_source S;
  int ok;
  snprintf(path, sizeof path, "%s/grid_table.csv", dir);
  if (!plane_read_table(path, &P)) { plane_free(&P); return EXIT_BAD_INPUT; }
  snprintf(path, sizeof path, "%s/claims.csv", dir);
  S.P = &P;
  S.have_runs = 0;
  S.previous = path;
  S.dt = dt;
  ok = claims_table(&S, path, summary, sizeof summary);
  if (ok) printf("afv paper: %s (%s)\n", path, summary);
  else fprintf(stderr, "afv paper: could not write %s\n", path);
  plane_free(&P);
  return ok ? 0 : EXIT_BAD_INPUT;
}

/* afv paper OUT: figures, claims and tables from the sweeps in OUT
** (without OUT/fss's outputs unless with_fss). */
static int paper_from_sweeps(const char *out, const dt_table *dt,
                             int with_fss)
{
  char path[PATH_LEN], summary[256];
  plane P;
  fss F;
  claim_source S;
  int ok;
  read_scale(out);
  if (!plane_read(out, &P)) { plane_free(&P); return EXIT_BAD_INPUT; }
  read_integration(&P);
  read_partial(&P);
  memset(&F, 0, sizeof F);
  if (with_fss && !fss_read(out, &F)) {
    plane_free(&P);
    return EXIT_BAD_INPUT;
  }
  snprintf(path, sizeof path, "%s/figures", out);
  if (mkdir(path, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv paper: %s: %s\n", path, strerror(errno));
    plane_free(&P);
    free(F.mean);
    return EXIT_BAD_INPUT;
  }
  S.P = &P;
  S.have_runs = 1;
  S.previous = NULL;
  S.dt = dt;
  snprintf(path, sizeof path, "%s/claims.csv", out);
  ok = cluster_figures(out, &P) && fluctuation_figures(out, &P)
       && confluency_figures(out, &P) && dynamics_figures(out, &P)
       && summary_figures(out, &P) && (!with_fss || fss_outputs(out, &F, &P))
       && halves_table(out, &P)
       && claims_table(&S, path, summary, sizeof summary);
  if (ok) printf("afv paper: %s/figures, %s (%s)%s%s%s%s\n", out, path,
                 summary, with_fss ? ", " : "", with_fss ? out : "",
                 with_fss ? "/fss.csv" : "", paper_smoke ? " (smoke run: "
                 "figures and claims marked, the numbers mean nothing)" : "");
  else fprintf(stderr, "afv paper: could not write into %s\n", out);
  plane_free(&P);
  free(F.mean);
  return ok ? 0 : EXIT_BAD_INPUT;
}

/* afv paper --dt-verdicts FILE OUTFILE. */
static int dt_verdicts(const char *table, const char *out)
{
  dt_table T;
  int ok;
  if (!dt_table_read(table, &T)) return EXIT_BAD_INPUT;
  ok = dt_verdicts_write(&T, out);
  if (ok) printf("afv paper: %s\n", out);
  else fprintf(stderr, "afv paper: could not write %s\n", out);
  dt_table_free(&T);
  return ok ? 0 : EXIT_BAD_INPUT;
}

/* The arguments: OUT or --claims-from DIR, then --dt-table FILE or not;
** with_fss 0 for --grid-only OUT. */
static int paper_run(const char *claims_dir, const char *out,
                     const char *dt_path, int with_fss)
{
  dt_table T;
  int st;
  const char *dir = claims_dir ? claims_dir : out;
  if (strlen(dir) > RUN_PATH_MAX - 64)
    return bad_input(claims_dir ? "paper: --claims-from DIR too long"
                                : "paper: OUT too long");
  if (dt_path && strlen(dt_path) >= PATH_LEN)
    return bad_input("paper: --dt-table FILE too long");
  if (dt_path && !dt_table_read(dt_path, &T)) return EXIT_BAD_INPUT;
  st = claims_dir ? claims_from(claims_dir, dt_path ? &T : NULL)
                  : paper_from_sweeps(out, dt_path ? &T : NULL, with_fss);
  if (dt_path) dt_table_free(&T);
  return st;
}

int cmd_paper(int argc, char **argv)
{
  const char *dt_path = NULL;
  if (argc == 2 && (strcmp(argv[1], "--help") == 0
                    || strcmp(argv[1], "-h") == 0)) {
    fputs(paper_usage, stdout);
    return 0;
  }
  if (argc == 4 && strcmp(argv[1], "--dt-verdicts") == 0) {
    if (strlen(argv[2]) >= PATH_LEN || strlen(argv[3]) > RUN_PATH_MAX)
      return bad_input("paper: --dt-verdicts FILE OUTFILE too long");
    return dt_verdicts(argv[2], argv[3]);
  }
  if (argc == 5 && strcmp(argv[1], "--compare") == 0) {
    int k;
    for (k = 2; k < 5; k++)
      if (strlen(argv[k]) > RUN_PATH_MAX - 64)
        return bad_input("paper: --compare: a path too long");
    return paper_compare(argv[2], argv[3], argv[4]);
  }
  if (argc >= 4 && strcmp(argv[argc - 2], "--dt-table") == 0) {
    dt_path = argv[argc - 1];
    argc -= 2;
  }
  if (argc == 3 && strcmp(argv[1], "--claims-from") == 0)
    return paper_run(argv[2], NULL, dt_path, 1);
  if (argc == 3 && strcmp(argv[1], "--grid-only") == 0)
    return paper_run(NULL, argv[2], dt_path, 0);
  if (argc != 2 || argv[1][0] == '-') {
    fputs(paper_usage, stderr);
    return EXIT_BAD_INPUT;
  }
  return paper_run(NULL, argv[1], dt_path, 1);
}
