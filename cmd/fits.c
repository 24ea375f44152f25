/*
** fits.c -- the numbers `afv paper` compares with the paper: a power law
** fitted to a log-binned cluster-size distribution, the point where two
** order-parameter curves cross, and the scaling collapse
** N_GC/N = G((v0 - v0*) / P0^alpha) (paper, clustering section).
** Each works on plain arrays, so test/test_paper.c can feed it curves whose
** answer is known.
*/
#include "fits.h"

#include <math.h>
#include <stdlib.h>

/* Slope and its standard error of the least-squares line y = a + b x. */
static void line_fit(int m, const double *x, const double *y, double *slope,
                     double *se)
{
  double mx = 0, my = 0, sxx = 0, sxy = 0, rss = 0;
  int k;
  for (k = 0; k < m; k++) { mx += x[k]; my += y[k]; }
  mx /= m; my /= m;
  for (k = 0; k < m; k++) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxy += (x[k] - mx) * (y[k] - my);
  }
  *slope = sxy / sxx;
  for (k = 0; k < m; k++) {
    double r = y[k] - my - *slope * (x[k] - mx);
    rss += r * r;
  }
  /* s^2 = rss / (m - 2); var(slope) = s^2 / Sxx.  No error from 2 points. */
  *se = m > 2 ? sqrt(rss / (m - 2) / sxx) : NAN;
}

int afv_powerlaw_fit(const double *csd, int n, int nmax, afv_powerlaw *fit)
{
  int lo[AFV_CSD_MAX_BINS], hi[AFV_CSD_MAX_BINS], nb, k, peak = -1, m = 0;
  double p[AFV_CSD_MAX_BINS], dens[AFV_CSD_MAX_BINS];
  double x[AFV_CSD_MAX_BINS], y[AFV_CSD_MAX_BINS];
  fit->exponent = fit->se = NAN;
  fit->nbins = 0;
  fit->lo = fit->hi = 0;
  if (!csd || n < 1 || nmax < 1) return AFV_EINVAL;
  nb = afv_csd_log_bins(csd, n, lo, hi, p);
  /* Density per size in each bin (sum of p over its sizes / their number),
  ** at the bin's geometric centre: a power law keeps its exponent. */
  for (k = 0; k < nb; k++) {
    dens[k] = p[k] / (hi[k] - lo[k] + 1);
    if (hi[k] <= nmax && dens[k] > 0 && (peak < 0 || dens[k] > dens[peak]))
      peak = k;
  }
  /* The decay: from the bin after the densest one (which may straddle a
  ** rise and the fall) through the last bin below nmax. */
  for (k = peak < 0 ? nb : peak + 1; k < nb && hi[k] <= nmax; k++) {
    if (!(dens[k] > 0)) continue;
    x[m] = log10(sqrt((double)lo[k] * hi[k]));
    y[m] = log10(dens[k]);
    if (m == 0) fit->lo = lo[k];
    fit->hi = hi[k];
    m++;
  }
  fit->nbins = m;
  if (m < 2) return AFV_EINVAL;
  line_fit(m, x, y, &fit->exponent, &fit->se);
  return AFV_OK;
}

/* ya - yb at point k, or NaN where either is not finite. */
static double gap(const double *ya, const double *yb, int k)
{
  return isfinite(ya[k]) && isfinite(yb[k]) ? ya[k] - yb[k] : NAN;
}

int afv_curves_cross(int n, const double *x, const double *ya,
                     const double *yb, double *xc)
{
  int k, prev = -1;
  double dprev = 0;
  for (k = 0; k < n; k++) {
    double d = gap(ya, yb, k);
    if (!isfinite(d) || d == 0) continue;  /* equal (both 1): no side yet */
    if (prev >= 0 && dprev > 0 && d < 0) {
      /* Linear interpolation of the gap between the two points. */
      *xc = x[prev] + (x[k] - x[prev]) * dprev / (dprev - d);
      return 1;
    }
    prev = k;
    dprev = d;
  }
  return 0;
}

/* Mean over the pairs a < b of the curves whose flag is set. */
static int pair_crossings(int nc, int n, const double *x, const double *y,
                          const int *use, double *mean)
{
  int a, b, m = 0;
  double s = 0, xc;
  for (a = 0; a < nc; a++)
    for (b = a + 1; b < nc; b++)
      if (use[a] && use[b]
          && afv_curves_cross(n, x, y + (size_t)a * n, y + (size_t)b * n,
                              &xc)) {
        s += xc;
        m++;
      }
  *mean = m ? s / m : NAN;
  return m;
}

/* Jackknife standard error of an estimate from nc leave-one-out values
** (NaN entries skipped): sqrt((m-1)/m sum (t_i - mean)^2). */
static double jackknife_se(int nc, const double *t)
{
  double mean = 0, s = 0;
  int i, m = 0;
  for (i = 0; i < nc; i++) if (isfinite(t[i])) { mean += t[i]; m++; }
  if (m < 2) return NAN;
  mean /= m;
  for (i = 0; i < nc; i++)
    if (isfinite(t[i])) s += (t[i] - mean) * (t[i] - mean);
  return sqrt((m - 1.0) / m * s);
}

int afv_curves_cross_common(int nc, int n, const double *x, const double *y,
                            afv_crossing_fit *out)
{
  int *use, i;
  double *loo;
  out->x = out->se = NAN;
  out->pairs = 0;
  if (nc < 2 || n < 2) return AFV_EINVAL;
  use = malloc((size_t)nc * sizeof(int));
  loo = malloc((size_t)nc * sizeof(double));
  if (!use || !loo) { free(use); free(loo); return AFV_ENOMEM; }
  for (i = 0; i < nc; i++) use[i] = 1;
  out->pairs = pair_crossings(nc, n, x, y, use, &out->x);
  for (i = 0; i < nc; i++) {
    use[i] = 0;
    pair_crossings(nc, n, x, y, use, &loo[i]);
    use[i] = 1;
  }
  out->se = jackknife_se(nc, loo);
  free(use);
  free(loo);
  return out->pairs ? AFV_OK : AFV_EINVAL;
}

/* y of curve j (n points, x increasing in s) at s0 by linear interpolation;
** 0 if s0 is outside the curve's finite points. */
static int interp_at(int n, const double *s, const double *y, double s0,
                     double *out)
{
  int k;
  for (k = 0; k + 1 < n; k++) {
    if (!isfinite(y[k]) || !isfinite(y[k + 1])) continue;
    if (s0 >= s[k] && s0 <= s[k + 1]) {
      double t = s[k + 1] > s[k] ? (s0 - s[k]) / (s[k + 1] - s[k]) : 0;
      *out = y[k] + t * (y[k + 1] - y[k]);
      return 1;
    }
  }
  return 0;
}

/* Collapse cost: the mean squared distance of every point of a curve from
** every other curve interpolated at the same scaled abscissa; HUGE_VAL if
** fewer than 2 nc such comparisons (curves that no longer overlap). */
static double collapse_cost(int nc, int n, const double *x, const double *y,
                            const double *p, const int *use, double vstar,
                            double alpha, double *s)
{
  int a, b, k, m = 0;
  double sum = 0, yb;
  for (a = 0; a < nc; a++)
    for (k = 0; k < n; k++)
      s[(size_t)a * n + k] = (x[k] - vstar) / pow(p[a], alpha);
  for (a = 0; a < nc; a++)
    for (b = 0; b < nc; b++) {
      if (a == b || !use[a] || !use[b]) continue;
      for (k = 0; k < n; k++) {
        double ya = y[(size_t)a * n + k];
        if (!isfinite(ya)) continue;
        if (interp_at(n, s + (size_t)b * n, y + (size_t)b * n,
                      s[(size_t)a * n + k], &yb)) {
          sum += (ya - yb) * (ya - yb);
          m++;
        }
      }
    }
  return m >= 2 * nc ? sum / m : HUGE_VAL;
}

/* Grid search of the collapse: a coarse grid over v0* (the x range) and
** alpha ([0, COLLAPSE_AMAX]), then a fine grid around the coarse best. */
#define COLLAPSE_AMAX 4.0

static void collapse_grid(int nc, int n, const double *x, const double *y,
                          const double *p, const int *use, double *s,
                          double v_lo, double v_hi, double dv, double a_lo,
                          double a_hi, double da, double *best)
{
  double v, a, c;
  for (v = v_lo; v <= v_hi + AFV_GRID_END_TOL; v += dv)
    for (a = a_lo; a <= a_hi + AFV_GRID_END_TOL; a += da) {
      c = collapse_cost(nc, n, x, y, p, use, v, a, s);
      if (c < best[2]) { best[0] = v; best[1] = a; best[2] = c; }
    }
}

static void collapse_search(int nc, int n, const double *x, const double *y,
                            const double *p, const int *use, double *s,
                            double *vstar, double *alpha, double *cost)
{
  double best[3] = {NAN, NAN, HUGE_VAL}, v, a;
  collapse_grid(nc, n, x, y, p, use, s, x[0], x[n - 1], 0.05, 0,
                COLLAPSE_AMAX, 0.1, best);
  v = best[0];
  a = best[1];
  if (isfinite(best[2]))
    collapse_grid(nc, n, x, y, p, use, s, fmax(v - 0.05, x[0]),
                  fmin(v + 0.05, x[n - 1]), 0.002, a > 0.1 ? a - 0.1 : 0,
                  fmin(a + 0.1, COLLAPSE_AMAX), 0.005, best);
  *vstar = best[0];
  *alpha = best[1];
  *cost = best[2];
}

int afv_collapse_fit(int nc, int n, const double *x, const double *y,
                     const double *p0, afv_collapse *out)
{
  double *s, *lv, *la, cost;
  int *use, i;
  out->vstar = out->alpha = out->se_vstar = out->se_alpha = out->cost = NAN;
  if (nc < 2 || n < 2) return AFV_EINVAL;
  for (i = 0; i < nc; i++) if (!(p0[i] > 0)) return AFV_EINVAL;
  for (i = 0; i + 1 < n; i++) if (!(x[i + 1] > x[i])) return AFV_EINVAL;
  s = malloc((size_t)nc * n * sizeof(double));
  lv = malloc((size_t)nc * 2 * sizeof(double));
  use = malloc((size_t)nc * sizeof(int));
  if (!s || !lv || !use) { free(s); free(lv); free(use); return AFV_ENOMEM; }
  la = lv + nc;
  for (i = 0; i < nc; i++) use[i] = 1;
  collapse_search(nc, n, x, y, p0, use, s, &out->vstar, &out->alpha,
                  &out->cost);
  /* Leave-one-curve-out fits for the jackknife errors (needs 3 curves). */
  for (i = 0; nc >= 3 && i < nc; i++) {
    use[i] = 0;
    collapse_search(nc, n, x, y, p0, use, s, &lv[i], &la[i], &cost);
    use[i] = 1;
  }
  if (nc >= 3) {
    out->se_vstar = jackknife_se(nc, lv);
    out->se_alpha = jackknife_se(nc, la);
  }
  free(s); free(lv); free(use);
  return isfinite(out->cost) ? AFV_OK : AFV_EINVAL;
}
