/*
** svg.c -- pictures: a tissue drawn like the paper's Fig. 1, and a small
** self-contained line-plot helper for the analysis figures.
**
** Tissue.  Coordinates are the model's (unit l), y up: the drawing sits in
** a group with transform matrix(1 0 0 -1 0 ymin+ymax), so every element is
** written in model coordinates and an arc running counter-clockwise in the
** model is an SVG arc with sweep-flag 1 (flags are read in the user space
** of the path, before the flip).  Every piece comes from afv_geom:
**   arc          pink path "M start A l l 0 large 1 end", one per arc piece
**                longer than AFV_CONTACT_TOL l (a shorter one is invisible);
**                a full circle (isolated cell) is one path of two half arcs;
**   edge         blue line, one per contacting pair: drawn by the cell of
**                lower index (or by the only cell that sees it).  An edge
**                shorter than AFV_CONTACT_TOL l is not a contact and is not
**                drawn: it is invisible anyway, and drawing it would make
**                the picture disagree with the contact count;
**   junction     hollow purple dot, one per triple junction as counted by
**                afv_clusters (a near-degenerate 4-fold vertex is one dot);
**   centre       red dot;  polarity  cyan arrow of length 0.6 l.
** Periodic box: each cell is drawn at its wrapped position and at every
** periodic image whose disk of radius l meets the box, and the whole
** drawing is clipped to the box (clipPath).  So a cell crossing the box
** edge appears in pieces on both sides, as in the paper.  A cell that does
** not reach the edge is drawn exactly once, so for such configurations the
** element counts equal the geometry's counts (tested).
*/
#include "afv.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

/* Drawing sizes in units of l, and the picture's width in pixels. */
#define CENTRE_R    0.07
#define JUNCTION_R  0.07
#define LINE_W      0.035
#define ARROW_LEN   0.6
#define PIXELS      800.0

/* ---- tissue ------------------------------------------------------------- */
typedef struct view {
  double xmin, ymin, w, h;   /* visible region, model units */
  double l;
  int periodic;
} view;

static void open_view(view *v, int n, const double *r, double l)
{
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int i;
  for (i = 0; i < n; i++) {
    if (i == 0 || r[2*i] < x0) x0 = r[2*i];
    if (i == 0 || r[2*i] > x1) x1 = r[2*i];
    if (i == 0 || r[2*i+1] < y0) y0 = r[2*i+1];
    if (i == 0 || r[2*i+1] > y1) y1 = r[2*i+1];
  }
  v->xmin = x0 - 1.5 * l;
  v->ymin = y0 - 1.5 * l;
  v->w = x1 - x0 + 3 * l;
  v->h = y1 - y0 + 3 * l;
}

static void svg_header(FILE *out, const view *v)
{
  double px = PIXELS / (v->w > v->h ? v->w : v->h);
  fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" "
          "height=\"%.0f\" viewBox=\"%.6g %.6g %.6g %.6g\">\n",
          v->w * px, v->h * px, v->xmin, v->ymin, v->w, v->h);
  fprintf(out, "<defs>\n"
          "<clipPath id=\"afv-box\"><rect x=\"%.6g\" y=\"%.6g\" "
          "width=\"%.6g\" height=\"%.6g\"/></clipPath>\n"
          "<marker id=\"afv-arrow\" viewBox=\"0 0 10 10\" refX=\"8\" "
          "refY=\"5\" markerWidth=\"4\" markerHeight=\"4\" orient=\"auto\">"
          "<path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#00bcd4\"/></marker>\n"
          "</defs>\n", v->xmin, v->ymin, v->w, v->h);
  fprintf(out, "<rect x=\"%.6g\" y=\"%.6g\" width=\"%.6g\" height=\"%.6g\" "
          "fill=\"white\"/>\n", v->xmin, v->ymin, v->w, v->h);
  fprintf(out, "<g transform=\"matrix(1 0 0 -1 0 %.6g)\"%s>\n",
          2 * v->ymin + v->h, v->periodic ? " clip-path=\"url(#afv-box)\"" : "");
}

/* One arc piece from (x0, y0) to (x1, y1), centre (cx, cy), angle phi. */
static void draw_arc(FILE *out, double cx, double cy, const afv_piece *a,
                     const afv_piece *next, double l)
{
  double phi = a->length / l;
  if (phi >= 2 * PI - 1e-9) {    /* full circle: two half arcs */
    fprintf(out, "<path class=\"arc\" d=\"M %.6g %.6g A %.6g %.6g 0 1 1 "
            "%.6g %.6g A %.6g %.6g 0 1 1 %.6g %.6g\"/>\n", cx + l, cy, l, l,
            cx - l, cy, l, l, cx + l, cy);
    return;
  }
  fprintf(out, "<path class=\"arc\" d=\"M %.6g %.6g A %.6g %.6g 0 %d 1 "
          "%.6g %.6g\"/>\n", cx + a->x, cy + a->y, l, l, phi > PI ? 1 : 0,
          cx + next->x, cy + next->y);
}

/* The pieces of cell i (centre cx, cy) that this cell draws. */
static void draw_cell_pieces(FILE *out, const afv_geom *g,
                             const afv_clusters *c, int i, double cx,
                             double cy, double l)
{
  int s = g->piece_start[i], m = g->n_pieces[i], k;
  for (k = 0; k < m; k++) {
    const afv_piece *pc = &g->pieces[s + k], *nx = &g->pieces[s + (k+1) % m];
    if (pc->nbr == AFV_ARC) {
      if (pc->length > AFV_CONTACT_TOL * l)
        draw_arc(out, cx, cy, pc, nx, l);
    } else if (c->contact[s + k] && (pc->nbr > i || c->partner[s + k] < 0)) {
      fprintf(out, "<line class=\"edge\" x1=\"%.6g\" y1=\"%.6g\" "
              "x2=\"%.6g\" y2=\"%.6g\"/>\n", cx + pc->x, cy + pc->y,
              cx + nx->x, cy + nx->y);
    }
  }
}

/* Image shifts of a disk of radius rad about (x, y) that meet the view:
** calls back with each shift; only (0, 0) in open space. */
static int image_shifts(const view *v, const afv_box *b, double x, double y,
                        double rad, double sh[9][2])
{
  int ix, iy, m = 0;
  if (!v->periodic) {
    sh[0][0] = sh[0][1] = 0;
    return 1;
  }
  for (iy = -1; iy <= 1; iy++)
    for (ix = -1; ix <= 1; ix++) {
      double X = x + ix * b->Lx, Y = y + iy * b->Ly;
      if (X + rad > 0 && X - rad < b->Lx && Y + rad > 0 && Y - rad < b->Ly) {
        sh[m][0] = ix * b->Lx;
        sh[m][1] = iy * b->Ly;
        m++;
      }
    }
  return m;
}

static void draw_tissue(FILE *out, const view *v, const afv_geom *g,
                        const afv_clusters *c, int n, const double *r,
                        const afv_box *b)
{
  double sh[9][2], l = v->l;
  int i, k, m;
  fprintf(out, "<g fill=\"none\" stroke-width=\"%.4g\" "
          "stroke-linecap=\"round\">\n", LINE_W * l);
  for (i = 0; i < n; i++) {
    double x = r[2*i], y = r[2*i+1];
    afv_wrap(b, &x, &y);
    m = image_shifts(v, b, x, y, l, sh);
    for (k = 0; k < m; k++)
      draw_cell_pieces(out, g, c, i, x + sh[k][0], y + sh[k][1], l);
  }
  fprintf(out, "</g>\n");
}

/* Colours come from the classes, so each element stays one short tag. */
static void svg_style(FILE *out)
{
  fprintf(out, "<style>.arc{stroke:#ff69b4}.edge{stroke:#1f4fd6}"
          ".junction{stroke:#800080;fill:none}.centre{fill:#e00000}"
          ".polarity{stroke:#00bcd4}.box{stroke:black;fill:none}</style>\n");
}

static void draw_marks(FILE *out, const view *v, const afv_clusters *c, int n,
                       const double *r, const double *theta, const afv_box *b)
{
  double sh[9][2], l = v->l;
  int i, k, m;
  fprintf(out, "<g stroke-width=\"%.4g\">\n", 0.5 * LINE_W * l);
  for (i = 0; i < c->n_junctions; i++) {
    m = image_shifts(v, b, c->junction[2*i], c->junction[2*i+1],
                     JUNCTION_R * l, sh);
    for (k = 0; k < m; k++)
      fprintf(out, "<circle class=\"junction\" cx=\"%.6g\" cy=\"%.6g\" "
              "r=\"%.4g\"/>\n", c->junction[2*i] + sh[k][0],
              c->junction[2*i+1] + sh[k][1], JUNCTION_R * l);
  }
  fprintf(out, "</g>\n<g stroke-width=\"%.4g\">\n", LINE_W * l);
  for (i = 0; i < n; i++) {
    double x = r[2*i], y = r[2*i+1];
    afv_wrap(b, &x, &y);
    m = image_shifts(v, b, x, y, theta ? ARROW_LEN * l : CENTRE_R * l, sh);
    for (k = 0; k < m; k++) {
      double X = x + sh[k][0], Y = y + sh[k][1];
      fprintf(out, "<circle class=\"centre\" cx=\"%.6g\" cy=\"%.6g\" "
              "r=\"%.4g\"/>\n", X, Y, CENTRE_R * l);
      if (theta)
        fprintf(out, "<line class=\"polarity\" x1=\"%.6g\" y1=\"%.6g\" "
                "x2=\"%.6g\" y2=\"%.6g\" marker-end=\"url(#afv-arrow)\"/>\n",
                X, Y, X + ARROW_LEN * l * cos(theta[i]),
                Y + ARROW_LEN * l * sin(theta[i]));
    }
  }
  fprintf(out, "</g>\n");
}

int afv_svg_write(FILE *out, const afv_geom *g, int n, const double *r,
                  const double *theta, const afv_params *p, const afv_box *b)
{
  afv_clusters c;
  view v;
  int st;
  memset(&c, 0, sizeof c);
  if (g->n != n) return AFV_EINVAL;
  if ((st = afv_clusters_compute(&c, g, r, p->l, b)) != AFV_OK) return st;
  v.l = p->l;
  v.periodic = b && b->periodic;
  if (v.periodic) {
    v.xmin = v.ymin = 0;
    v.w = b->Lx;
    v.h = b->Ly;
  } else {
    open_view(&v, n, r, p->l);
  }
  svg_header(out, &v);
  svg_style(out);
  draw_tissue(out, &v, g, &c, n, r, b);
  draw_marks(out, &v, &c, n, r, theta, b);
  fprintf(out, "</g>\n");
  if (v.periodic)
    fprintf(out, "<rect class=\"box\" x=\"0\" y=\"0\" width=\"%.6g\" "
            "height=\"%.6g\" stroke-width=\"%.4g\"/>\n", b->Lx, b->Ly,
            2 * LINE_W * p->l);
  fprintf(out, "</svg>\n");
  afv_clusters_free(&c);
  return ferror(out) ? AFV_EIO : AFV_OK;
}

/* ---- line plots ---------------------------------------------------------- */
/* Canvas and plot area, pixels. */
#define PLOT_W   640.0
#define PLOT_H   420.0
#define PLOT_L   78.0
#define PLOT_R   20.0
#define PLOT_T   40.0
#define PLOT_B   52.0

typedef struct axis {
  int    log;        /* 1: values are plotted as log10(v) */
  double lo, hi;     /* range in plotted units */
  double step;       /* tick spacing in plotted units */
} axis;

static int usable(const axis *a, double v)
{
  return isfinite(v) && (!a->log || v > 0);
}

static double plotted(const axis *a, double v)
{
  return a->log ? log10(v) : v;
}

/* 1, 2 or 5 times a power of ten, near span / 5. */
static double nice_step(double span)
{
  double raw = span / 5, p = pow(10.0, floor(log10(raw))), f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

/* Range of every usable value of one coordinate, then round it outward:
** to whole decades (log) or to multiples of a nice step (linear). */
static void fit_axis(axis *a, const afv_plot_series *s, int ns, int use_y)
{
  int k, i, any = 0;
  a->lo = a->hi = 0;
  for (k = 0; k < ns; k++)
    for (i = 0; i < s[k].n; i++) {
      double v = use_y ? s[k].y[i] : s[k].x[i];
      if (!usable(a, v) || !usable(a, use_y ? s[k].x[i] : s[k].y[i])) continue;
      v = plotted(a, v);
      if (!any || v < a->lo) a->lo = v;
      if (!any || v > a->hi) a->hi = v;
      any = 1;
    }
  if (a->hi - a->lo < 1e-12 * (fabs(a->lo) + 1)) {  /* one value: widen */
    a->lo -= a->log ? 1 : 0.5 * (fabs(a->lo) + 1);
    a->hi += a->log ? 1 : 0.5 * (fabs(a->hi) + 1);
  }
  if (a->log) {
    a->lo = floor(a->lo);
    a->hi = ceil(a->hi);
    a->step = a->hi - a->lo > 8 ? ceil((a->hi - a->lo) / 8) : 1;
  } else {
    a->step = nice_step(a->hi - a->lo);
    a->lo = a->step * floor(a->lo / a->step);
    a->hi = a->step * ceil(a->hi / a->step);
  }
}

static double to_px(const axis *a, double v, double p0, double p1)
{
  return p0 + (plotted(a, v) - a->lo) / (a->hi - a->lo) * (p1 - p0);
}

/* Writes text with &, <, > escaped. */
static void put_text(FILE *out, const char *s)
{
  for (; s && *s; s++) {
    if (*s == '&') fputs("&amp;", out);
    else if (*s == '<') fputs("&lt;", out);
    else if (*s == '>') fputs("&gt;", out);
    else fputc(*s, out);
  }
}

/* Tick label: 10^k on a log axis, %g otherwise. */
static void tick_label(FILE *out, const axis *a, double t)
{
  if (a->log)
    fprintf(out, "10<tspan dy=\"-6\" font-size=\"9\">%.0f</tspan>", t);
  else
    fprintf(out, "%g", fabs(t) < 1e-9 * a->step ? 0.0 : t);
}

static void draw_axes(FILE *out, const axis *ax, const axis *ay)
{
  double x0 = PLOT_L, x1 = PLOT_W - PLOT_R, y0 = PLOT_H - PLOT_B, y1 = PLOT_T;
  double t;
  fprintf(out, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" "
          "fill=\"none\" stroke=\"black\"/>\n", x0, y1, x1 - x0, y0 - y1);
  for (t = ax->lo; t <= ax->hi + 1e-9 * ax->step; t += ax->step) {
    double px = x0 + (t - ax->lo) / (ax->hi - ax->lo) * (x1 - x0);
    fprintf(out, "<line x1=\"%.2f\" y1=\"%g\" x2=\"%.2f\" y2=\"%g\" "
            "stroke=\"black\"/>\n<text x=\"%.2f\" y=\"%g\" "
            "text-anchor=\"middle\">", px, y0, px, y0 + 5, px, y0 + 19);
    tick_label(out, ax, t);
    fprintf(out, "</text>\n");
  }
  for (t = ay->lo; t <= ay->hi + 1e-9 * ay->step; t += ay->step) {
    double py = y0 + (t - ay->lo) / (ay->hi - ay->lo) * (y1 - y0);
    fprintf(out, "<line x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" "
            "stroke=\"black\"/>\n<text x=\"%g\" y=\"%.2f\" "
            "text-anchor=\"end\">", x0 - 5, py, x0, py, x0 - 8, py + 4);
    tick_label(out, ay, t);
    fprintf(out, "</text>\n");
  }
}

/* A polyline through the usable points (unless s->points), and a marker on
** each point when there are few of them or when asked to (scatter). */
static void draw_series(FILE *out, const axis *ax, const axis *ay,
                        const afv_plot_series *s)
{
  double x0 = PLOT_L, x1 = PLOT_W - PLOT_R, y0 = PLOT_H - PLOT_B, y1 = PLOT_T;
  int i, used = 0;
  if (!s->points) {
    fprintf(out, "<polyline class=\"series\" fill=\"none\" stroke=\"%s\" "
            "stroke-width=\"1.5\" points=\"", s->color);
    for (i = 0; i < s->n; i++)
      if (usable(ax, s->x[i]) && usable(ay, s->y[i]))
        fprintf(out, "%s%.2f,%.2f", used++ ? " " : "",
                to_px(ax, s->x[i], x0, x1), to_px(ay, s->y[i], y0, y1));
    fprintf(out, "\"/>\n");
    if (s->n > 60) return;
  }
  for (i = 0; i < s->n; i++)
    if (usable(ax, s->x[i]) && usable(ay, s->y[i]))
      fprintf(out, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.5\" fill=\"%s\"/>\n",
              to_px(ax, s->x[i], x0, x1), to_px(ay, s->y[i], y0, y1),
              s->color);
}

int afv_svg_plot(FILE *out, const afv_plot *pl, const afv_plot_series *s,
                 int ns)
{
  axis ax, ay;
  int k;
  ax.log = pl->logx;
  ay.log = pl->logy;
  fit_axis(&ax, s, ns, 0);
  fit_axis(&ay, s, ns, 1);
  if (pl->ymin < pl->ymax && (!ay.log || pl->ymin > 0)) {
    ay.lo = plotted(&ay, pl->ymin);
    ay.hi = plotted(&ay, pl->ymax);
    ay.step = ay.log ? 1 : nice_step(ay.hi - ay.lo);
  }
  fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" "
          "height=\"%g\" font-family=\"sans-serif\" font-size=\"12\">\n"
          "<rect width=\"%g\" height=\"%g\" fill=\"white\"/>\n",
          PLOT_W, PLOT_H, PLOT_W, PLOT_H);
  fprintf(out, "<text x=\"%g\" y=\"24\" text-anchor=\"middle\" "
          "font-size=\"15\">", PLOT_W / 2);
  put_text(out, pl->title);
  fprintf(out, "</text>\n<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">",
          (PLOT_L + PLOT_W - PLOT_R) / 2, PLOT_H - 12);
  put_text(out, pl->xlabel);
  fprintf(out, "</text>\n<text transform=\"translate(18 %g) rotate(-90)\" "
          "text-anchor=\"middle\">", (PLOT_T + PLOT_H - PLOT_B) / 2);
  put_text(out, pl->ylabel);
  fprintf(out, "</text>\n");
  draw_axes(out, &ax, &ay);
  for (k = 0; k < ns; k++) {
    draw_series(out, &ax, &ay, &s[k]);
    if (!s[k].label) continue;
    fprintf(out, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" "
            "stroke-width=\"2\"/>\n<text x=\"%g\" y=\"%g\">",
            PLOT_W - PLOT_R - 130, PLOT_T + 16 + 16 * k, PLOT_W - PLOT_R - 108,
            PLOT_T + 16 + 16 * k, s[k].color, PLOT_W - PLOT_R - 102,
            PLOT_T + 20 + 16 * k);
    put_text(out, s[k].label);
    fprintf(out, "</text>\n");
  }
  fprintf(out, "</svg>\n");
  return ferror(out) ? AFV_EIO : AFV_OK;
}
