/*
** phase.c -- phase diagrams from a grid of state points: where an order
** parameter crosses a threshold, the dispersal boundary fit, and the SVG
** map of an order parameter over a (P0, v0) grid with its threshold
** contour.  Used by afv collect; no state, no files of its own.
*/
#include "fits.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- crossings -------------------------------------------------------------- */
int afv_curve_cross(int n, const double *x, const double *y, double level,
                    double *xc)
{
  int i, prev = -1;
  for (i = 0; i < n; i++) {
    if (!isfinite(x[i]) || !isfinite(y[i])) continue;
    if (prev >= 0 && y[prev] >= level && y[i] < level) {
      *xc = x[prev] + (x[i] - x[prev]) * (y[prev] - level)
                      / (y[prev] - y[i]);
      return 1;
    }
    prev = i;
  }
  return 0;
}

/* ---- the dispersal boundary v_s(P0) = v0* - c P0^alpha ------------------------ */
/* Range of alpha searched: the boundary's curvature, from nearly flat to
** steep; outside it P0^alpha over P0 in [4, 8.8] spans so many decades that
** the linear solve for (v0*, c) loses its digits. */
#define ALPHA_MIN 0.05
#define ALPHA_MAX 12.0
#define ALPHA_SCAN 600     /* log-spaced alphas scanned before refining */

/* For fixed alpha the model is linear in (v0*, c): least squares of
** vs = v0* - c u with u = P0^alpha.  Returns the residual sum of squares
** (HUGE_VAL if u does not vary). */
static double linear_fit(int n, const double *p0, const double *vs,
                         double alpha, double *v0star, double *c)
{
  double su = 0, sv = 0, suu = 0, suv = 0, det, rss = 0;
  int i;
  for (i = 0; i < n; i++) {
    double u = pow(p0[i], alpha);
    su += u; sv += vs[i]; suu += u * u; suv += u * vs[i];
  }
  det = n * suu - su * su;
  if (!(fabs(det) > AFV_FIT_SINGULAR * (suu + 1)) || !isfinite(det)) return HUGE_VAL;
  *c = -(n * suv - su * sv) / det;
  *v0star = (sv + *c * su) / n;
  for (i = 0; i < n; i++) {
    double r = vs[i] - (*v0star - *c * pow(p0[i], alpha));
    rss += r * r;
  }
  return rss;
}

static double rss_at(int n, const double *p0, const double *vs, double la)
{
  double a, c;
  return linear_fit(n, p0, vs, exp(la), &a, &c);
}

/* Standard errors from the Jacobian of the full model at the optimum:
** covariance = s^2 (J^T J)^-1, s^2 = RSS / (n - 3). */
static void boundary_errors(int n, const double *p0, afv_boundary *b)
{
  double M[3][3] = {{0}}, inv[3][3], det, s2;
  int i, r, q;
  b->se_v0star = b->se_c = b->se_alpha = NAN;
  if (n <= 3) return;
  for (i = 0; i < n; i++) {
    double u = pow(p0[i], b->alpha);
    double J[3];
    J[0] = 1;                          /* d v_s / d v0* */
    J[1] = -u;                         /* d v_s / d c */
    J[2] = -b->c * u * log(p0[i]);     /* d v_s / d alpha */
    for (r = 0; r < 3; r++)
      for (q = 0; q < 3; q++) M[r][q] += J[r] * J[q];
  }
  for (r = 0; r < 3; r++)
    for (q = 0; q < 3; q++) {
      int r1 = (r + 1) % 3, r2 = (r + 2) % 3, q1 = (q + 1) % 3,
          q2 = (q + 2) % 3;
      inv[q][r] = M[r1][q1] * M[r2][q2] - M[r1][q2] * M[r2][q1];
    }
  det = M[0][0] * inv[0][0] + M[0][1] * inv[1][0] + M[0][2] * inv[2][0];
  if (!(fabs(det) > 0)) return;
  s2 = b->rss / (n - 3);
  b->se_v0star = sqrt(s2 * inv[0][0] / det);
  b->se_c = sqrt(s2 * inv[1][1] / det);
  b->se_alpha = sqrt(s2 * inv[2][2] / det);
}

int afv_boundary_fit(int n, const double *p0, const double *vs,
                     afv_boundary *b)
{
  double lo = log(ALPHA_MIN), hi = log(ALPHA_MAX), best = HUGE_VAL, la = lo;
  double g = (sqrt(5.0) - 1) / 2, a, d, x1, x2, f1, f2;
  int i, k;
  memset(b, 0, sizeof *b);
  b->n = n;
  for (i = 0; i < n; i++)
    if (!(p0[i] > 0) || !isfinite(vs[i])) return AFV_EINVAL;
  if (n < 3) return AFV_EINVAL;
  /* scan, then golden-section search between the scan's neighbours */
  for (k = 0; k <= ALPHA_SCAN; k++) {
    double x = lo + (hi - lo) * k / ALPHA_SCAN, f = rss_at(n, p0, vs, x);
    if (f < best) { best = f; la = x; }
  }
  if (!(best < HUGE_VAL)) return AFV_EINVAL;
  a = la - (hi - lo) / ALPHA_SCAN;
  d = la + (hi - lo) / ALPHA_SCAN;
  x1 = d - g * (d - a);
  x2 = a + g * (d - a);
  f1 = rss_at(n, p0, vs, x1);
  f2 = rss_at(n, p0, vs, x2);
  for (k = 0; k < 200 && d - a > AFV_FIT_ALPHA_TOL; k++) {
    if (f1 < f2) { d = x2; x2 = x1; f2 = f1; x1 = d - g * (d - a);
                   f1 = rss_at(n, p0, vs, x1); }
    else         { a = x1; x1 = x2; f1 = f2; x2 = a + g * (d - a);
                   f2 = rss_at(n, p0, vs, x2); }
  }
  la = f1 < best || f2 < best ? (f1 < f2 ? x1 : x2) : la;
  b->alpha = exp(la);
  b->rss = linear_fit(n, p0, vs, b->alpha, &b->v0star, &b->c);
  boundary_errors(n, p0, b);
  return AFV_OK;
}

/* ---- SVG map over a grid ----------------------------------------------------- */
#define MAP_W 700.0
#define MAP_H 520.0
#define MAP_L 70.0     /* margins of the plot area */
#define MAP_R 140.0
#define MAP_T 40.0
#define MAP_B 55.0

/* Colour of t in [0, 1]: a viridis-like ramp through five anchors. */
static void ramp(double t, char *rgb)
{
  static const double c[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140},
                                 {94, 201, 98}, {253, 231, 37}};
  int k;
  double f;
  if (!(t >= 0)) t = 0;
  if (t > 1) t = 1;
  k = t >= 1 ? 3 : (int)(t * 4);
  f = t * 4 - k;
  sprintf(rgb, "#%02x%02x%02x", (int)(c[k][0] + f * (c[k+1][0] - c[k][0])),
          (int)(c[k][1] + f * (c[k+1][1] - c[k][1])),
          (int)(c[k][2] + f * (c[k+1][2] - c[k][2])));
}

/* The value as coloured: log10 on a log map (non-positive: NaN). */
static double shown(const afv_map *m, double z)
{
  return !m->logz ? z : z > 0 ? log10(z) : NAN;
}

/* Edges of grid cell i along coordinates v (n values, increasing): halfway
** to the neighbours, the outer ones as far out as the inner. */
static double cell_edge(const double *v, int n, int i, int upper)
{
  if (n == 1) return v[0] + (upper ? 0.5 : -0.5);
  if (upper) return i < n - 1 ? (v[i] + v[i+1]) / 2 : v[i] + (v[i] - v[i-1]) / 2;
  return i > 0 ? (v[i-1] + v[i]) / 2 : v[i] - (v[i+1] - v[i]) / 2;
}

typedef struct map_frame {
  double x0, x1, y0, y1;      /* data range of the plot area */
  double zlo, zhi;            /* colour range (as shown) */
} map_frame;

static double px(const map_frame *f, double x)
{
  return MAP_L + (x - f->x0) / (f->x1 - f->x0) * (MAP_W - MAP_L - MAP_R);
}

static double py(const map_frame *f, double y)
{
  return MAP_H - MAP_B - (y - f->y0) / (f->y1 - f->y0)
                         * (MAP_H - MAP_T - MAP_B);
}

static void put_escaped(FILE *out, const char *s)
{
  for (; s && *s; s++)
    if (*s == '<') fputs("&lt;", out);
    else if (*s == '>') fputs("&gt;", out);
    else if (*s == '&') fputs("&amp;", out);
    else fputc(*s, out);
}

static void map_cells(FILE *out, const afv_map *m, const map_frame *f)
{
  char rgb[8];
  int i, j;
  for (j = 0; j < m->ny; j++)
    for (i = 0; i < m->nx; i++) {
      double z = shown(m, m->z[j * m->nx + i]);
      double xa = px(f, cell_edge(m->x, m->nx, i, 0));
      double xb = px(f, cell_edge(m->x, m->nx, i, 1));
      double ya = py(f, cell_edge(m->y, m->ny, j, 1));
      double yb = py(f, cell_edge(m->y, m->ny, j, 0));
      if (isfinite(z)) ramp((z - f->zlo) / (f->zhi - f->zlo), rgb);
      fprintf(out, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\""
              " fill=\"%s\" shape-rendering=\"crispEdges\"/>\n", xa, ya,
              xb - xa, yb - ya,
              isfinite(z) ? rgb : "#dddddd");
      if (m->nx * m->ny <= 150)
        fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\" "
                "font-size=\"10\" fill=\"%s\">%.3g</text>\n", (xa + xb) / 2,
                (ya + yb) / 2 + 4, isfinite(z) && (z - f->zlo)
                / (f->zhi - f->zlo) > 0.6 ? "black" : "white",
                m->z[j * m->nx + i]);
    }
}

/* Where the contour crosses the grid edge from node a to node b. */
static int edge_cross(double za, double zb, double level, double *t)
{
  if (!isfinite(za) || !isfinite(zb) || (za >= level) == (zb >= level))
    return 0;
  *t = (level - za) / (zb - za);
  return 1;
}

/* Marching squares over the grid of state points: in each square of four
** known values, the contour joins the edges it crosses (two, or four at a
** saddle, paired by the square's mean). */
static void map_contour(FILE *out, const afv_map *m, const map_frame *f)
{
  double level = shown(m, m->level);
  int i, j, k;
  if (!isfinite(level)) return;
  fputs("<g stroke=\"black\" stroke-width=\"2.5\" fill=\"none\">\n", out);
  for (j = 0; j + 1 < m->ny; j++)
    for (i = 0; i + 1 < m->nx; i++) {
      /* corners counter-clockwise from (i, j); edge k joins k and k+1 */
      int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1}, nc = 0;
      double cx[4], cy[4], t, z[4];
      for (k = 0; k < 4; k++) z[k] = shown(m, m->z[cj[k] * m->nx + ci[k]]);
      for (k = 0; k < 4; k++) {
        int a = k, b = (k + 1) % 4;
        if (!edge_cross(z[a], z[b], level, &t)) continue;
        cx[nc] = m->x[ci[a]] + t * (m->x[ci[b]] - m->x[ci[a]]);
        cy[nc] = m->y[cj[a]] + t * (m->y[cj[b]] - m->y[cj[a]]);
        nc++;
      }
      if (nc == 4 && (z[0] + z[1] + z[2] + z[3]) / 4 >= level
          && z[0] < level) {  /* saddle: keep the high middle connected */
        double sx = cx[0], sy = cy[0];
        memmove(cx, cx + 1, 3 * sizeof(double));
        memmove(cy, cy + 1, 3 * sizeof(double));
        cx[3] = sx; cy[3] = sy;
      }
      for (k = 0; k + 1 < nc; k += 2)
        fprintf(out, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>"
                "\n", px(f, cx[k]), py(f, cy[k]), px(f, cx[k+1]),
                py(f, cy[k+1]));
    }
  fputs("</g>\n", out);
}

static void map_curve(FILE *out, const afv_map *m, const map_frame *f)
{
  int k;
  if (m->cn < 2) return;
  fputs("<polyline fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\" "
        "stroke-dasharray=\"6 4\" points=\"", out);
  for (k = 0; k < m->cn; k++)
    if (m->cy[k] >= f->y0 && m->cy[k] <= f->y1)
      fprintf(out, "%.2f,%.2f ", px(f, m->cx[k]), py(f, m->cy[k]));
  fputs("\"/>\n", out);
}

/* Tick labels at the grid values (at most about 12 of them). */
static void map_axes(FILE *out, const afv_map *m, const map_frame *f)
{
  int i, sx = m->nx / 12 + 1, sy = m->ny / 12 + 1;
  for (i = 0; i < m->nx; i += sx)
    fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%g"
            "</text>\n", px(f, m->x[i]), MAP_H - MAP_B + 16, m->x[i]);
  for (i = 0; i < m->ny; i += sy)
    fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">%g</text>\n",
            MAP_L - 6, py(f, m->y[i]) + 4, m->y[i]);
  fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">",
          (MAP_L + MAP_W - MAP_R) / 2, MAP_H - 14);
  put_escaped(out, m->xlabel);
  fprintf(out, "</text>\n<text transform=\"translate(20 %.2f) rotate(-90)\" "
          "text-anchor=\"middle\">", (MAP_T + MAP_H - MAP_B) / 2);
  put_escaped(out, m->ylabel);
  fprintf(out, "</text>\n<text x=\"%.2f\" y=\"24\" text-anchor=\"middle\" "
          "font-size=\"15\">", MAP_W / 2);
  put_escaped(out, m->title);
  fputs("</text>\n", out);
}

/* Colour bar at the right, labelled at its ends, middle and the level. */
static void map_colorbar(FILE *out, const afv_map *m, const map_frame *f)
{
  double x = MAP_W - MAP_R + 30, top = MAP_T, h = MAP_H - MAP_T - MAP_B;
  double level = shown(m, m->level);
  char rgb[8];
  int k;
  for (k = 0; k < 50; k++) {
    ramp((k + 0.5) / 50, rgb);
    fprintf(out, "<rect x=\"%.2f\" y=\"%.2f\" width=\"18\" height=\"%.2f\" "
            "fill=\"%s\"/>\n", x, top + h * (49 - k) / 50, h / 50 + 0.5, rgb);
  }
  for (k = 0; k <= 2; k++) {
    double v = f->zlo + (f->zhi - f->zlo) * k / 2;
    fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"11\">%.3g</text>\n",
            x + 22, top + h * (1 - k / 2.0) + 4, m->logz ? pow(10, v) : v);
  }
  if (isfinite(level) && level >= f->zlo && level <= f->zhi) {
    double y = top + h * (1 - (level - f->zlo) / (f->zhi - f->zlo));
    fprintf(out, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "stroke=\"black\" stroke-width=\"2.5\"/>\n", x - 4, y, x + 22, y);
  }
  fprintf(out, "<text transform=\"translate(%.2f %.2f) rotate(-90)\" "
          "text-anchor=\"middle\">", x + 92, top + h / 2);
  put_escaped(out, m->zlabel);
  fputs("</text>\n", out);
}

/* The frame of map m: its grid's extent; 0 if m has no point. */
static int map_extent(const afv_map *m, map_frame *f)
{
  if (m->nx < 1 || m->ny < 1) return 0;
  f->x0 = cell_edge(m->x, m->nx, 0, 0);
  f->x1 = cell_edge(m->x, m->nx, m->nx - 1, 1);
  f->y0 = cell_edge(m->y, m->ny, 0, 0);
  f->y1 = cell_edge(m->y, m->ny, m->ny - 1, 1);
  return 1;
}

/* The colour range over the finite values of the n maps m (one scale for
** maps drawn side by side) into f. */
static void map_range(const afv_map *m, int n, map_frame *f)
{
  int k, j, any = 0;
  f->zlo = HUGE_VAL;
  f->zhi = -HUGE_VAL;
  for (j = 0; j < n; j++)
    for (k = 0; k < m[j].nx * m[j].ny; k++) {
      double z = shown(&m[j], m[j].z[k]);
      if (!isfinite(z)) continue;
      any = 1;
      if (z < f->zlo) f->zlo = z;
      if (z > f->zhi) f->zhi = z;
    }
  if (!any) f->zlo = 0, f->zhi = 1;
  if (f->zhi - f->zlo < AFV_PLOT_SPAN_TOL) { f->zlo -= 0.5; f->zhi += 0.5; }
}

static void map_panel(FILE *out, const afv_map *m, const map_frame *f)
{
  map_cells(out, m, f);
  map_contour(out, m, f);
  map_curve(out, m, f);
  fprintf(out, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" "
          "fill=\"none\" stroke=\"black\"/>\n", MAP_L, MAP_T,
          MAP_W - MAP_L - MAP_R, MAP_H - MAP_T - MAP_B);
  map_axes(out, m, f);
  map_colorbar(out, m, f);
}

int afv_svg_map(FILE *out, const afv_map *m)
{
  return afv_svg_maps(out, m, 1);
}

int afv_svg_maps(FILE *out, const afv_map *m, int n)
{
  map_frame f[AFV_MAPS_MAX], range;
  int k;
  if (n < 1 || n > AFV_MAPS_MAX) return AFV_EINVAL;
  for (k = 0; k < n; k++)
    if (!map_extent(&m[k], &f[k])) return AFV_EINVAL;
  map_range(m, n, &range);
  for (k = 0; k < n; k++) { f[k].zlo = range.zlo; f[k].zhi = range.zhi; }
  fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\""
          "http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
          "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"%g\" "
          "height=\"%g\" fill=\"white\"/>\n", n * MAP_W, MAP_H, n * MAP_W,
          MAP_H);
  for (k = 0; k < n; k++) {
    if (n > 1) fprintf(out, "<g transform=\"translate(%g 0)\">\n", k * MAP_W);
    map_panel(out, &m[k], &f[k]);
    if (n > 1) fputs("</g>\n", out);
  }
  fputs("</svg>\n", out);
  return ferror(out) ? AFV_EIO : AFV_OK;
}
