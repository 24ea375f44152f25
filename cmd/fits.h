/*
** fits.h -- what the afv program computes from many runs: phase diagrams
** (phase.c: where a curve crosses a level, the dispersal boundary's fit,
** the map of an order parameter) and the paper's fits (fits.c: power
** laws, crossings of curves, the scaling collapse).  The program's, not
** the model's: they are not in libafv.a, and the library never includes
** this header.  Used by afv collect and afv paper (cmd/collect.c,
** cmd/paper.c), tools/lambda_plot.c and the tests.
*/
#ifndef AFV_FITS_H
#define AFV_FITS_H

#include "afv.h"
#include "afv_tool.h"

#include <stdio.h>

/* ---- tolerances of the fits ---------------------------------------------- */
/* phase.c, linear_fit: a least-squares determinant below AFV_FIT_SINGULAR
** times sum u^2 + 1 is singular (u does not vary).  Exercised (not
** mutated) by test_sweep.c's boundary fit of 3 points. */
#define AFV_FIT_SINGULAR 1e-300

/* phase.c, the dispersal boundary's exponent alpha: the golden-section
** search stops when its bracket is narrower than AFV_FIT_ALPHA_TOL.
** Exercised (not mutated) by test_sweep.c's boundary fit. */
#define AFV_FIT_ALPHA_TOL 1e-13

/* fits.c, collapse_grid: a grid of v0* and alpha runs to its end plus
** AFV_GRID_END_TOL, so that rounding of lo + k step keeps the last point.
** Exercised (not mutated) by test_paper.c collapse_recovers. */
#define AFV_GRID_END_TOL 1e-12

/* ---- 1. phase diagrams (phase.c) ---------------------------------------- */
/* The first x where y falls from >= level to < level as x grows (linear
** interpolation between consecutive finite points); 1 if found into *xc. */
int afv_curve_cross(int n, const double *x, const double *y, double level,
                    double *xc);

/* Least-squares fit of the dispersal boundary v_s(P0) = v0* - c P0^alpha
** (the paper's form) to n >= 3 points (P0 > 0): linear in (v0*, c) at each
** alpha, alpha in [0.05, 12] by a scan and a golden-section search.
** Standard errors from s^2 (J^T J)^-1 with s^2 = rss / (n - 3): NaN when
** n = 3.  AFV_EINVAL if n < 3 or a point is not finite. */
typedef struct afv_boundary {
  int    n;                  /* points fitted */
  double v0star, c, alpha;   /* the fit */
  double se_v0star, se_c, se_alpha;  /* their standard errors */
  double rss;                /* residual sum of squares */
} afv_boundary;
int afv_boundary_fit(int n, const double *p0, const double *vs,
                     afv_boundary *b);

/* A map of z over an nx x ny grid (x, y increasing), one coloured rectangle
** per point (grey: NaN), the contour z = level (marching squares; NaN
** level: none), an optional dashed curve (cx, cy; cn points), a colour bar. */
typedef struct afv_map {
  const char   *title, *xlabel, *ylabel, *zlabel;
  int           nx, ny;
  const double *x, *y;       /* grid coordinates */
  const double *z;           /* z[j nx + i] at (x[i], y[j]) */
  int           logz;        /* 1: colour by log10 z */
  double        level;       /* contour level */
  const double *cx, *cy;     /* curve (may be NULL with cn = 0) */
  int           cn;
} afv_map;
int afv_svg_map(FILE *out, const afv_map *m);
/* n <= AFV_MAPS_MAX maps side by side in one figure on one colour scale
** (the range of all their values), e.g. two models' diagrams: afv_svg_map's
** panel each.  AFV_EINVAL for n out of range or an empty map. */
#define AFV_MAPS_MAX 4
int afv_svg_maps(FILE *out, const afv_map *m, int n);

/* ---- 2. the paper's fits (fits.c) --------------------------------------- */
/* Power law p(n) ~ n^exponent fitted to the decay of a cluster-size
** distribution (csd as afv_analysis.csd, index 1..n): log-binned
** (afv_csd_log_bins), density per size in each bin at the bin's geometric
** centre, least squares of log10 density on log10 size over the bins after
** the densest one through the last one whose sizes are all <= nmax (sizes
** above nmax, the giant cluster, are left out); empty bins skipped.
** se = the slope's standard error (NaN from 2 bins).  AFV_EINVAL if fewer
** than 2 bins are left. */
typedef struct afv_powerlaw {
  double exponent, se;   /* slope of log p against log n, its error */
  int    nbins;          /* bins fitted */
  int    lo, hi;         /* sizes they cover */
} afv_powerlaw;
int afv_powerlaw_fit(const double *csd, int n, int nmax, afv_powerlaw *fit);

/* Where curve a falls below curve b (n points on a common increasing x):
** the first sign change of ya - yb from > 0 to < 0 among the points where
** both are finite and differ (points where they are equal, e.g. both 1,
** take no side), by linear interpolation; 1 if found into *xc. */
int afv_curves_cross(int n, const double *x, const double *ya,
                     const double *yb, double *xc);

/* The common crossing of nc curves y[c n + k] (c in increasing P0) on x:
** x = mean over the pairs a < b that cross (afv_curves_cross: curve a, the
** lower P0, falls below b); se = jackknife over the curves (leave one out,
** recompute the mean); pairs = how many crossed.  AFV_EINVAL if none. */
typedef struct afv_crossing_fit {
  double x, se;
  int    pairs;
} afv_crossing_fit;
int afv_curves_cross_common(int nc, int n, const double *x, const double *y,
                            afv_crossing_fit *out);

/* Scaling collapse (paper, clustering section): the v0* and alpha in
** [0, 4] that put the curves y[c n + k] (at x[k], P0 = p0[c]) on one curve
** of s = (x - v0*) / P0^alpha, by minimising the mean squared distance of
** each point from every other curve interpolated at its s (grid search,
** coarse then fine: v0* to 0.002, alpha to 0.005); se by jackknife over
** the curves (nc >= 3, else NaN).  AFV_EINVAL for nc < 2, n < 2, x not
** increasing or P0 <= 0. */
typedef struct afv_collapse {
  double vstar, alpha, se_vstar, se_alpha;
  double cost;           /* the minimum mean squared distance */
} afv_collapse;
int afv_collapse_fit(int nc, int n, const double *x, const double *y,
                     const double *p0, afv_collapse *out);

#endif /* AFV_FITS_H */
