/*
** svg.c -- pictures: a tissue drawn like the paper's Fig. 1, a small
** self-contained line-plot helper, and the plots of an analysis.  Nothing
** here computes an order parameter: analysis.c gives the numbers, the
** commands (cmd/report.c) write the files.
**
** Tissue.  The picture is a canvas in pixels holding the tissue's own
** viewport in model coordinates (unit l), y up: the drawing sits in a
** group with transform matrix(1 0 0 -1 0 ymin+ymax), so every element is
** written in model coordinates and an arc running counter-clockwise in the
** model is an SVG arc with sweep-flag 1 (flags are read in the user space
** of the path, before the flip).  A legend, when cells are coloured, sits
** right of the viewport, outside it; the optional caption and scale bar
** (a bar of length l) in a footer strip under it.  Every piece comes from
** afv_geom:
**   cell         filled path (only when coloured: afv_draw_opts), its
**                edges as lines and its arcs as arcs, under the outlines;
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
** Lines and dots are their size in l but at least a pixel or two (see the
** sizes below), and coordinates are printed to 1e-4 l wherever the cells
** are.  Periodic box: each cell is drawn at its wrapped position and at
** every periodic image whose disk of radius l meets the view (the box, or
** the crop), and the whole drawing is clipped to the view (clipPath).  So
** a cell crossing the box edge appears in pieces on both sides, as in the
** paper.  A cell that does not reach the edge is drawn exactly once, so
** for such configurations the element counts equal the geometry's counts
** (tested).
*/
#include "afv_internal.h"
#include "afv_tool.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Mark sizes: each is its size in units of l, but never thinner than MIN_PX
** pixels on the picture (at the default size of a 400-cell box, 16 px per
** l, a line of 0.035 l is half a pixel and a junction of 0.07 l one pixel:
** invisible) and never more than CAP l (a far zoomed-out picture would be
** all marks). */
#define LINE_W          0.035
#define LINE_MIN_PX     1.2
#define LINE_CAP        0.12
#define JUNCTION_R      0.07
#define JUNCTION_MIN_PX 2.8
#define JUNCTION_CAP    0.25
#define CENTRE_R        0.07
#define CENTRE_MIN_PX   1.8
#define CENTRE_CAP      0.18
#define ARROW_LEN   0.6      /* polarity arrow, l */
#define PIXELS      800.0    /* default: the longer side of the picture */
#define MAX_SHIFT   2        /* periodic images drawn: -2..2 boxes */
#define MAX_IMAGES  25       /* (2 MAX_SHIFT + 1)^2 */
#define COORD_LEN   40       /* longest printed coordinate, with its 0 */
/* below this magnitude a coordinate with 17 decimals fits COORD_LEN (16
** digits, the point, 17 decimals, the 0); at or above, %.17g */
#define COORD_FIXED_MAX 1e15

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

/* ---- tissue ------------------------------------------------------------- */
typedef struct view {
  double xmin, ymin, w, h;   /* visible region, model units */
  double l;
  double px;                 /* pixels per model unit */
  int    periodic;           /* cells have images (periodic box) */
  int    clip;               /* drawing clipped to the view */
  int    dec;                /* decimals of a printed coordinate */
  double line_w, junction_r, centre_r;  /* mark sizes, model units */
} view;

/* x with v->dec decimals, trailing zeros dropped.  Decimals, not
** significant digits: a cell at x = 1e5 needs as many decimals as one near
** 0 (with %.6g it was drawn at 100000 whatever its fraction). */
static const char *coord(char buf[COORD_LEN], const view *v, double x)
{
  size_t k;
  if (!(fabs(x) < COORD_FIXED_MAX)) {
    snprintf(buf, COORD_LEN, "%.17g", x);
    return buf;
  }
  snprintf(buf, COORD_LEN, "%.*f", v->dec, x);
  k = strlen(buf);
  if (strchr(buf, '.')) {
    while (buf[k - 1] == '0') buf[--k] = 0;
    if (buf[k - 1] == '.') buf[--k] = 0;
  }
  if (strcmp(buf, "-0") == 0) strcpy(buf, "0");
  return buf;
}
#define C(k, x) coord(cb[k], v, (x))   /* needs char cb[..][COORD_LEN] */

/* Size of a mark: base l, at least min_px pixels, at most cap l. */
static double mark_size(const view *v, double base, double min_px, double cap)
{
  double s = base * v->l;
  if (s * v->px < min_px) s = min_px / v->px;
  return s < cap * v->l ? s : cap * v->l;
}

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

/* AFV_EINVAL unless the options are usable for box b. */
static int draw_opts_check(const afv_draw_opts *o, int n, const afv_box *b)
{
  int i;
  if (!o) return AFV_OK;
  if (!(o->width >= 0) || !isfinite(o->width)) return AFV_EINVAL;
  for (i = 0; o->value && i < n; i++)
    if (!isfinite(o->value[i])) return AFV_EINVAL;
  if (!o->crop) return AFV_OK;
  if (!isfinite(o->x0) || !isfinite(o->y0) || !isfinite(o->x1)
      || !isfinite(o->y1) || !(o->x0 < o->x1) || !(o->y0 < o->y1))
    return AFV_EINVAL;
  if (b && b->periodic && (o->x0 < -b->Lx || o->x1 > 2 * b->Lx
                           || o->y0 < -b->Ly || o->y1 > 2 * b->Ly))
    return AFV_EINVAL;
  return AFV_OK;
}

/* The region drawn, its scale, the mark sizes and the printed digits. */
static void set_view(view *v, int n, const double *r, const afv_params *p,
                     const afv_box *b, const afv_draw_opts *o)
{
  double width, res;
  v->l = p->l;
  v->periodic = b && b->periodic;
  if (o && o->crop) {
    v->xmin = o->x0;
    v->ymin = o->y0;
    v->w = o->x1 - o->x0;
    v->h = o->y1 - o->y0;
  } else if (v->periodic) {
    v->xmin = v->ymin = 0;
    v->w = b->Lx;
    v->h = b->Ly;
  } else {
    open_view(v, n, r, p->l);
  }
  v->clip = v->periodic || (o && o->crop);
  width = o && o->width > 0 ? o->width
          : v->w >= v->h ? PIXELS : PIXELS * v->w / v->h;
  v->px = width / v->w;
  v->line_w = mark_size(v, LINE_W, LINE_MIN_PX, LINE_CAP);
  v->junction_r = mark_size(v, JUNCTION_R, JUNCTION_MIN_PX, JUNCTION_CAP);
  v->centre_r = mark_size(v, CENTRE_R, CENTRE_MIN_PX, CENTRE_CAP);
  /* a coordinate to AFV_SVG_RESOLUTION l (1e-4 l), and to
  ** AFV_SVG_RESOLUTION_PX (1/100) pixel on a magnified picture */
  res = fmin(AFV_SVG_RESOLUTION * v->l, AFV_SVG_RESOLUTION_PX / v->px);
  v->dec = (int)ceil(-log10(res));
  if (v->dec < 0) v->dec = 0;
  if (v->dec > 17) v->dec = 17;
}

/* ---- colours of the cells (--color-by) ---------------------------------- */
#define N_COLORS 7           /* categories with a colour of their own */
static const char *const palette[N_COLORS] = {
  "#4477aa", "#ee6677", "#228833", "#ccbb44", "#66ccee", "#aa3377",
  "#997700"
};
#define OTHER_COLOR "#bbbbbb"
#define LEGEND_ROWS (N_COLORS + 1)

typedef struct legend {
  char title[64];
  int  rows;                       /* swatches (0 with a ramp) */
  char text[LEGEND_ROWS][64];
  char color[LEGEND_ROWS][8];
  int  ramp;                       /* 1: a colour bar from lo to hi */
  double lo, hi;
  int  min_chars, min_rows;        /* room kept whatever the entries: the
                                   ** frames of a movie keep one size */
} legend;

/* Colour at u in [0, 1] of a blue-green-yellow ramp (viridis' ends). */
static void ramp_color(double u, char out[8])
{
  static const double stop[5][3] = {
    {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}
  };
  double s = (u < 0 ? 0 : u > 1 ? 1 : u) * 4;
  int k = s >= 4 ? 3 : (int)s, c;
  unsigned rgb[3];
  for (c = 0; c < 3; c++)
    rgb[c] = (unsigned)(stop[k][c] + (s - k) * (stop[k+1][c] - stop[k][c])
                        + 0.5);
  snprintf(out, 8, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Cells coloured by value[i]: a colour per distinct value when there are
** at most N_COLORS of them (a mixture of cell types), else a ramp. */
static int color_by_value(char (*fill)[8], legend *lg, int n,
                          const double *value, const char *name)
{
  double *s = malloc((size_t)n * sizeof(double) + 1);
  int i, k, m = 0;
  if (!s) return AFV_ENOMEM;
  memcpy(s, value, (size_t)n * sizeof(double));
  qsort(s, (size_t)n, sizeof(double), cmp_double);
  for (i = 0; i < n; i++)
    if (i == 0 || s[i] != s[m - 1]) {
      if (m == N_COLORS) break;
      s[m++] = s[i];
    }
  snprintf(lg->title, sizeof lg->title, "colour: %s", name ? name : "value");
  lg->ramp = i < n;
  lg->lo = s[0];
  lg->hi = value[0];
  for (i = 0; i < n; i++) {
    if (value[i] < lg->lo) lg->lo = value[i];
    if (value[i] > lg->hi) lg->hi = value[i];
  }
  for (i = 0; i < n; i++) {
    if (lg->ramp) {
      ramp_color(lg->hi > lg->lo ? (value[i] - lg->lo) / (lg->hi - lg->lo)
                 : 0.5, fill[i]);
      continue;
    }
    for (k = 0; s[k] != value[i]; k++) {}
    snprintf(fill[i], 8, "%s", palette[k]);
  }
  for (k = 0; !lg->ramp && k < m; k++) {
    int count = 0;
    for (i = 0; i < n; i++) count += value[i] == s[k];
    snprintf(lg->text[k], sizeof lg->text[k], "%s = %.6g: %d cell%s",
             name ? name : "value", s[k], count, count == 1 ? "" : "s");
    snprintf(lg->color[k], 8, "%s", palette[k]);
  }
  lg->rows = lg->ramp ? 0 : m;
  free(s);
  return AFV_OK;
}

typedef struct ranked { int size, index; } ranked;

/* Larger clusters first; equal sizes by index (a stable order). */
static int cmp_ranked(const void *a, const void *b)
{
  const ranked *x = a, *y = b;
  if (x->size != y->size) return x->size < y->size ? 1 : -1;
  return (x->index > y->index) - (x->index < y->index);
}

/* The palette colour of each shown cluster (rank k < shown, by order):
** without a previous frame (prev NULL) colour k; with one, the colour of
** which the cluster holds more than half of the cells that had it (at
** most one cluster can: it keeps it), else the first colour free, larger
** clusters choosing first.  col[k] for rank k. */
static void cluster_palette(const afv_clusters *c, const ranked *order,
                            int shown, const int *prev, int n, int *col)
{
  int had[N_COLORS] = {0}, kept[N_COLORS][N_COLORS], used[N_COLORS] = {0};
  int *rank_of = NULL, i, k, q;
  for (k = 0; k < shown; k++) col[k] = prev ? -1 : k;
  if (!prev || !(rank_of = malloc((size_t)c->count * sizeof(int) + 1)))
    return;
  memset(kept, 0, sizeof kept);
  for (k = 0; k < c->count; k++) rank_of[order[k].index] = k;
  for (i = 0; i < n; i++) {
    if (prev[i] < 0 || prev[i] >= N_COLORS) continue;
    had[prev[i]]++;
    k = rank_of[c->label[i]];
    if (k < shown) kept[k][prev[i]]++;
  }
  for (k = 0; k < shown; k++)          /* a cluster keeps its colour */
    for (q = 0; q < N_COLORS; q++)
      if (2 * kept[k][q] > had[q] && !used[q]) {
        col[k] = q;
        used[q] = 1;
        break;
      }
  for (k = 0; k < shown; k++)          /* the others: the first free */
    for (q = 0; col[k] < 0 && q < N_COLORS; q++)
      if (!used[q]) {
        col[k] = q;
        used[q] = 1;
      }
  free(rank_of);
}

/* Cells coloured by cluster: the N_COLORS - 1 largest clusters a colour
** each (largest first, or kept along a movie: cluster_palette), every
** other cluster grey.  color (n ints, or NULL): in, the previous frame's
** colour of each cell; out, this one's (-1: grey). */
static int color_by_cluster(char (*fill)[8], legend *lg, int n,
                            const afv_clusters *c, int *color)
{
  ranked *order = malloc((size_t)c->count * sizeof(ranked) + 1);
  int *rank = malloc((size_t)c->count * sizeof(int) + 1), col[N_COLORS];
  int k, i, shown = c->count <= N_COLORS ? c->count : N_COLORS - 1;
  if (!order || !rank) {
    free(order);
    free(rank);
    return AFV_ENOMEM;
  }
  for (k = 0; k < c->count; k++) {
    order[k].size = c->size[k];
    order[k].index = k;
  }
  qsort(order, (size_t)c->count, sizeof(ranked), cmp_ranked);
  for (k = 0; k < c->count; k++) rank[order[k].index] = k;
  cluster_palette(c, order, shown, color, n, col);
  for (i = 0; i < n; i++) {
    k = rank[c->label[i]];
    snprintf(fill[i], 8, "%s", k < shown ? palette[col[k]] : OTHER_COLOR);
    if (color) color[i] = k < shown ? col[k] : -1;
  }
  snprintf(lg->title, sizeof lg->title, "colour: cluster (%d)", c->count);
  for (k = 0; k < shown; k++) {
    int s = order[k].size;
    snprintf(lg->text[k], sizeof lg->text[k], "cluster of %d cell%s", s,
             s == 1 ? "" : "s");
    snprintf(lg->color[k], 8, "%s", palette[col[k]]);
  }
  lg->rows = shown;
  if (shown < c->count) {
    snprintf(lg->text[k], sizeof lg->text[k], "%d more (%d cell%s or fewer)",
             c->count - shown, order[shown].size,
             order[shown].size == 1 ? "" : "s");
    snprintf(lg->color[k], 8, "%s", OTHER_COLOR);
    lg->rows++;
  }
  lg->ramp = 0;
  /* the longest entry any frame of n cells can have, every row */
  snprintf(lg->text[LEGEND_ROWS - 1], sizeof lg->text[0], "%d more (%d cells "
           "or fewer)", n, n);
  lg->min_chars = (int)strlen(lg->text[LEGEND_ROWS - 1]);
  lg->min_rows = LEGEND_ROWS;
  free(order);
  free(rank);
  return AFV_OK;
}

/* Legend box size in pixels (0 x 0 without colours). */
#define LEGEND_FONT  13.0
#define LEGEND_ROW   20.0
#define LEGEND_CHAR  7.5     /* mean advance of a character at 13 px */
static void legend_size(const legend *lg, int on, double *w, double *h)
{
  size_t most = strlen(lg->title);
  int k;
  *w = *h = 0;
  if (!on) return;
  for (k = 0; k < lg->rows; k++)
    if (strlen(lg->text[k]) > most) most = strlen(lg->text[k]);
  if (lg->ramp && most < 16) most = 16;
  if ((int)most < lg->min_chars) most = (size_t)lg->min_chars;
  *w = 24 + 28 + most * LEGEND_CHAR + 12;
  *h = 16 + LEGEND_ROW * (1 + (lg->ramp ? 6 : lg->rows > lg->min_rows
                                ? lg->rows : lg->min_rows)) + 12;
}

/* The legend, in pixels, its top-left corner at (x, y). */
static void draw_legend(FILE *out, const legend *lg, double x, double y)
{
  int k;
  fprintf(out, "<g class=\"legend\" font-family=\"sans-serif\" "
          "font-size=\"%g\">\n<text x=\"%g\" y=\"%g\">", LEGEND_FONT,
          x + 12, y + 16 + LEGEND_FONT);
  put_text(out, lg->title);
  fprintf(out, "</text>\n");
  y += 16 + LEGEND_ROW;
  for (k = 0; k < lg->rows; k++, y += LEGEND_ROW) {
    fprintf(out, "<rect class=\"swatch\" x=\"%g\" y=\"%g\" width=\"20\" "
            "height=\"14\" fill=\"%s\" fill-opacity=\"0.6\" stroke=\"#444\" "
            "stroke-width=\"0.5\"/><text x=\"%g\" y=\"%g\">", x + 12,
            y + 2, lg->color[k], x + 40, y + 14);
    put_text(out, lg->text[k]);
    fprintf(out, "</text>\n");
  }
  if (lg->ramp) {   /* a vertical bar, hi at the top */
    fprintf(out, "<defs><linearGradient id=\"afv-ramp\" x1=\"0\" y1=\"1\" "
            "x2=\"0\" y2=\"0\">");
    for (k = 0; k <= 8; k++) {
      char c[8];
      ramp_color(k / 8.0, c);
      fprintf(out, "<stop offset=\"%g\" stop-color=\"%s\"/>", k / 8.0, c);
    }
    fprintf(out, "</linearGradient></defs>\n<rect class=\"swatch\" x=\"%g\" "
            "y=\"%g\" width=\"20\" height=\"%g\" fill=\"url(#afv-ramp)\" "
            "fill-opacity=\"0.6\" stroke=\"#444\" stroke-width=\"0.5\"/>\n"
            "<text x=\"%g\" y=\"%g\">%.6g</text>\n<text x=\"%g\" y=\"%g\">"
            "%.6g</text>\n", x + 12, y, 5 * LEGEND_ROW, x + 40, y + 10,
            lg->hi, x + 40, y + 5 * LEGEND_ROW, lg->lo);
  }
  fprintf(out, "</g>\n");
}

/* ---- the drawing -------------------------------------------------------- */
/* Opens the picture: an outer canvas in pixels (the tissue, then the
** legend to its right), and in it the tissue's own viewport in model
** units, y up (the group's matrix flips y). */
static void svg_header(FILE *out, const view *v, double legend_w,
                       double legend_h, double footer_h)
{
  char cb[5][COORD_LEN];
  double W = v->w * v->px, H = v->h * v->px;
  double TH = (H + footer_h > legend_h ? H + footer_h : legend_h);
  fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.6g\" "
          "height=\"%.6g\" viewBox=\"0 0 %.6g %.6g\">\n"
          "<rect width=\"%.6g\" height=\"%.6g\" fill=\"white\"/>\n",
          W + legend_w, TH, W + legend_w, TH, W + legend_w, TH);
  fprintf(out, "<svg class=\"tissue\" x=\"0\" y=\"0\" width=\"%.6g\" "
          "height=\"%.6g\" viewBox=\"%s %s %s %s\">\n", W, H, C(0, v->xmin),
          C(1, v->ymin), C(2, v->w), C(3, v->h));
  fprintf(out, "<defs>\n"
          "<clipPath id=\"afv-box\"><rect x=\"%s\" y=\"%s\" "
          "width=\"%s\" height=\"%s\"/></clipPath>\n"
          "<marker id=\"afv-arrow\" viewBox=\"0 0 10 10\" refX=\"8\" "
          "refY=\"5\" markerWidth=\"4\" markerHeight=\"4\" orient=\"auto\">"
          "<path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#00bcd4\"/></marker>\n"
          "</defs>\n", C(0, v->xmin), C(1, v->ymin), C(2, v->w), C(3, v->h));
  fprintf(out, "<g transform=\"matrix(1 0 0 -1 0 %s)\"%s>\n",
          C(4, 2 * v->ymin + v->h),
          v->clip ? " clip-path=\"url(#afv-box)\"" : "");
}

/* Colours come from the classes, so each element stays one short tag. */
static void svg_style(FILE *out)
{
  fprintf(out, "<style>.arc{stroke:#ff69b4}.edge{stroke:#1f4fd6}"
          ".junction{stroke:#800080;fill:none}.centre{fill:#e00000}"
          ".polarity{stroke:#00bcd4}.box{stroke:black;fill:none}"
          ".cell{stroke:none;fill-opacity:0.6}</style>\n");
}

/* Image shifts of a disk of radius rad about (x, y) that meet the view:
** up to MAX_SHIFT boxes each way in a periodic box (a crop reaches at
** most one box beyond it), only (0, 0) in open space; none if the disk
** misses the view. */
static int image_shifts(const view *v, const afv_box *b, double x, double y,
                        double rad, double sh[MAX_IMAGES][2])
{
  int ix, iy, m = 0, K = v->periodic ? MAX_SHIFT : 0;
  for (iy = -K; iy <= K; iy++)
    for (ix = -K; ix <= K; ix++) {
      double X = x + (K ? ix * b->Lx : 0), Y = y + (K ? iy * b->Ly : 0);
      if (X + rad > v->xmin && X - rad < v->xmin + v->w
          && Y + rad > v->ymin && Y - rad < v->ymin + v->h) {
        sh[m][0] = X - x;
        sh[m][1] = Y - y;
        m++;
      }
    }
  return m;
}

/* One arc piece from (x0, y0) to (x1, y1), centre (cx, cy), angle phi. */
static void draw_arc(FILE *out, const view *v, double cx, double cy,
                     const afv_piece *a, const afv_piece *next)
{
  char cb[4][COORD_LEN];
  double phi = a->length / v->l, l = v->l;
  if (phi >= 2 * PI - AFV_FULL_CIRCLE_TOL) {    /* full circle: two half arcs */
    fprintf(out, "<path class=\"arc\" d=\"M %s %s A %.6g %.6g 0 1 1 "
            "%s %s A %.6g %.6g 0 1 1 %s %s\"/>\n", C(0, cx + l), C(1, cy),
            l, l, C(2, cx - l), C(3, cy), l, l, C(0, cx + l), C(1, cy));
    return;
  }
  fprintf(out, "<path class=\"arc\" d=\"M %s %s A %.6g %.6g 0 %d 1 "
          "%s %s\"/>\n", C(0, cx + a->x), C(1, cy + a->y), l, l,
          phi > PI ? 1 : 0, C(2, cx + next->x), C(3, cy + next->y));
}

/* Cell i's shape, centre (cx, cy), filled with colour fill: its edges as
** lines and its arcs as arcs, closed. */
static void draw_cell_fill(FILE *out, const view *v, const afv_geom *g,
                           int i, double cx, double cy, const char *fill)
{
  char cb[2][COORD_LEN];
  int s = g->piece_start[i], m = g->n_pieces[i], k;
  const afv_piece *pc = &g->pieces[s];
  if (m == 1 && pc->nbr == AFV_ARC) {   /* a whole disk */
    fprintf(out, "<circle class=\"cell\" fill=\"%s\" cx=\"%s\" cy=\"%s\" "
            "r=\"%.6g\"/>\n", fill, C(0, cx), C(1, cy), v->l);
    return;
  }
  fprintf(out, "<path class=\"cell\" fill=\"%s\" d=\"M %s %s", fill,
          C(0, cx + pc->x), C(1, cy + pc->y));
  for (k = 0; k < m; k++) {
    const afv_piece *nx = &g->pieces[s + (k + 1) % m];
    pc = &g->pieces[s + k];
    if (pc->nbr == AFV_ARC)
      fprintf(out, " A %.6g %.6g 0 %d 1 %s %s", v->l, v->l,
              pc->length > PI * v->l ? 1 : 0, C(0, cx + nx->x),
              C(1, cy + nx->y));
    else
      fprintf(out, " L %s %s", C(0, cx + nx->x), C(1, cy + nx->y));
  }
  fprintf(out, " Z\"/>\n");
}

/* The pieces of cell i (centre cx, cy) that this cell draws. */
static void draw_cell_pieces(FILE *out, const view *v, const afv_geom *g,
                             const afv_clusters *c, int i, double cx,
                             double cy)
{
  char cb[4][COORD_LEN];
  int s = g->piece_start[i], m = g->n_pieces[i], k;
  for (k = 0; k < m; k++) {
    const afv_piece *pc = &g->pieces[s + k], *nx = &g->pieces[s + (k+1) % m];
    if (pc->nbr == AFV_ARC) {
      if (pc->length > AFV_CONTACT_TOL * v->l)
        draw_arc(out, v, cx, cy, pc, nx);
    } else if (c->contact[s + k] && (pc->nbr > i || c->partner[s + k] < 0)) {
      fprintf(out, "<line class=\"edge\" x1=\"%s\" y1=\"%s\" "
              "x2=\"%s\" y2=\"%s\"/>\n", C(0, cx + pc->x), C(1, cy + pc->y),
              C(2, cx + nx->x), C(3, cy + nx->y));
    }
  }
}

/* Every cell's fill (when coloured), then its edges and arcs. */
static void draw_tissue(FILE *out, const view *v, const afv_geom *g,
                        const afv_clusters *c, int n, const double *r,
                        const afv_box *b, char (*fill)[8])
{
  double sh[MAX_IMAGES][2];
  int i, k, m, pass;
  for (pass = fill ? 0 : 1; pass < 2; pass++) {
    if (pass == 1)
      fprintf(out, "<g fill=\"none\" stroke-width=\"%.4g\" "
              "stroke-linecap=\"round\">\n", v->line_w);
    for (i = 0; i < n; i++) {
      double x = r[2*i], y = r[2*i+1];
      afv_wrap(b, &x, &y);
      m = image_shifts(v, b, x, y, v->l, sh);
      for (k = 0; k < m; k++) {
        if (pass == 0)
          draw_cell_fill(out, v, g, i, x + sh[k][0], y + sh[k][1], fill[i]);
        else
          draw_cell_pieces(out, v, g, c, i, x + sh[k][0], y + sh[k][1]);
      }
    }
    if (pass == 1) fprintf(out, "</g>\n");
  }
}

static void draw_marks(FILE *out, const view *v, const afv_clusters *c, int n,
                       const double *r, const double *theta, const afv_box *b)
{
  char cb[4][COORD_LEN];
  double sh[MAX_IMAGES][2], arrow = ARROW_LEN * v->l;
  int i, k, m;
  fprintf(out, "<g stroke-width=\"%.4g\">\n", 0.7 * v->line_w);
  for (i = 0; i < c->n_junctions; i++) {
    m = image_shifts(v, b, c->junction[2*i], c->junction[2*i+1],
                     v->junction_r, sh);
    for (k = 0; k < m; k++)
      fprintf(out, "<circle class=\"junction\" cx=\"%s\" cy=\"%s\" "
              "r=\"%.4g\"/>\n", C(0, c->junction[2*i] + sh[k][0]),
              C(1, c->junction[2*i+1] + sh[k][1]), v->junction_r);
  }
  fprintf(out, "</g>\n<g stroke-width=\"%.4g\">\n", v->line_w);
  for (i = 0; i < n; i++) {
    double x = r[2*i], y = r[2*i+1];
    afv_wrap(b, &x, &y);
    m = image_shifts(v, b, x, y, theta ? arrow : v->centre_r, sh);
    for (k = 0; k < m; k++) {
      double X = x + sh[k][0], Y = y + sh[k][1];
      fprintf(out, "<circle class=\"centre\" cx=\"%s\" cy=\"%s\" "
              "r=\"%.4g\"/>\n", C(0, X), C(1, Y), v->centre_r);
      if (theta)
        fprintf(out, "<line class=\"polarity\" x1=\"%s\" y1=\"%s\" "
                "x2=\"%s\" y2=\"%s\" marker-end=\"url(#afv-arrow)\"/>\n",
                C(0, X), C(1, Y), C(2, X + arrow * cos(theta[i])),
                C(3, Y + arrow * sin(theta[i])));
    }
  }
  fprintf(out, "</g>\n");
}

/* Per-cell fill colours and the legend, as the options ask; *fill NULL
** when the cells are not coloured. */
static int cell_colors(const afv_draw_opts *o, const afv_clusters *c, int n,
                       char (**fill)[8], legend *lg)
{
  int st;
  *fill = NULL;
  memset(lg, 0, sizeof *lg);
  if (!o || (!o->color_by_cluster && !o->value)) return AFV_OK;
  if (!(*fill = malloc((size_t)n * sizeof **fill + 1))) return AFV_ENOMEM;
  st = o->color_by_cluster ? color_by_cluster(*fill, lg, n, c,
                                              o->cluster_color)
       : color_by_value(*fill, lg, n, o->value, o->value_name);
  if (st != AFV_OK) {
    free(*fill);
    *fill = NULL;
  }
  return st;
}

/* The footer under the tissue: the scale bar (a black bar of length l,
** labelled) at the left, then the caption; FOOTER_H pixels high. */
#define FOOTER_H 30.0
static double footer_height(const afv_draw_opts *o)
{
  return o && (o->caption || o->scale_bar) ? FOOTER_H : 0;
}

static void draw_footer(FILE *out, const view *v, const afv_draw_opts *o)
{
  double y = v->h * v->px + FOOTER_H / 2, x = 10, bar = v->l * v->px;
  fprintf(out, "<g class=\"footer\" font-family=\"sans-serif\" "
          "font-size=\"13\">\n");
  if (o->scale_bar) {
    fprintf(out, "<rect class=\"scale-bar\" x=\"%g\" y=\"%g\" width=\"%.6g\" "
            "height=\"4\" fill=\"black\"/>\n<text x=\"%.6g\" y=\"%g\">1 l"
            "</text>\n", x, y - 2, bar, x + bar + 6, y + 5);
    x += bar + 40;
  }
  if (o->caption) {
    fprintf(out, "<text class=\"caption\" x=\"%.6g\" y=\"%g\">", x, y + 5);
    put_text(out, o->caption);
    fprintf(out, "</text>\n");
  }
  fprintf(out, "</g>\n");
}

int afv_svg_draw(FILE *out, const afv_geom *g, int n, const double *r,
                 const double *theta, const afv_params *p, const afv_box *b,
                 const afv_draw_opts *o)
{
  assert(out != NULL && g != NULL && p != NULL && (r != NULL || n <= 0));
  char cb[4][COORD_LEN], (*fill)[8] = NULL;
  afv_clusters c;
  legend lg;
  view view_, *v = &view_;
  double lw, lh;
  int st;
  memset(&c, 0, sizeof c);
  if (g->n != n || n < 1) return AFV_EINVAL;
  if ((st = draw_opts_check(o, n, b)) != AFV_OK) return st;
  if ((st = afv_clusters_compute(&c, g, r, p->l, b)) != AFV_OK) return st;
  if ((st = cell_colors(o, &c, n, &fill, &lg)) != AFV_OK) {
    afv_clusters_free(&c);
    return st;
  }
  set_view(v, n, r, p, b, o);
  legend_size(&lg, fill != NULL, &lw, &lh);
  svg_header(out, v, lw, lh, footer_height(o));
  svg_style(out);
  draw_tissue(out, v, g, &c, n, r, b, fill);
  draw_marks(out, v, &c, n, r, theta, b);
  if (v->periodic)
    fprintf(out, "<rect class=\"box\" x=\"0\" y=\"0\" width=\"%s\" "
            "height=\"%s\" stroke-width=\"%.4g\"/>\n", C(0, b->Lx),
            C(1, b->Ly), 2 * v->line_w);
  fprintf(out, "</g>\n</svg>\n");
  if (fill) draw_legend(out, &lg, v->w * v->px, 0);
  if (footer_height(o) > 0) draw_footer(out, v, o);
  fprintf(out, "</svg>\n");
  afv_clusters_free(&c);
  free(fill);
  return ferror(out) ? AFV_EIO : AFV_OK;
}

int afv_svg_write(FILE *out, const afv_geom *g, int n, const double *r,
                  const double *theta, const afv_params *p, const afv_box *b)
{
  assert(out != NULL && g != NULL && p != NULL && (r != NULL || n <= 0));
  return afv_svg_draw(out, g, n, r, theta, p, b, NULL);
}

/* ---- line plots ---------------------------------------------------------- */
/* Canvas and plot area, pixels. */
#define PLOT_W   640.0
#define PLOT_H   420.0
#define PLOT_L   78.0
#define PLOT_R   20.0
#define PLOT_T   40.0
#define PLOT_B   52.0

/* Every point lies at least this fraction of the data's span inside the
** plot's frame (before the range is rounded out to ticks). */
#define PLOT_MARGIN 0.04

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
  if (a->hi - a->lo < AFV_PLOT_SPAN_TOL * (fabs(a->lo) + 1)) {  /* one value: widen */
    a->lo -= a->log ? 1 : 0.5 * (fabs(a->lo) + 1);
    a->hi += a->log ? 1 : 0.5 * (fabs(a->hi) + 1);
  } else {              /* a margin, so that no point sits on the frame */
    double pad = PLOT_MARGIN * (a->hi - a->lo);
    a->lo -= pad;
    a->hi += pad;
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

/* Tick label: 10^k on a log axis, %g otherwise. */
static void tick_label(FILE *out, const axis *a, double t)
{
  if (a->log)
    fprintf(out, "10<tspan dy=\"-6\" font-size=\"9\">%.0f</tspan>", t);
  else
    fprintf(out, "%g", fabs(t) < AFV_PLOT_TICK_TOL * a->step ? 0.0 : t);
}

static void draw_axes(FILE *out, const axis *ax, const axis *ay)
{
  double x0 = PLOT_L, x1 = PLOT_W - PLOT_R, y0 = PLOT_H - PLOT_B, y1 = PLOT_T;
  double t;
  fprintf(out, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" "
          "fill=\"none\" stroke=\"black\"/>\n", x0, y1, x1 - x0, y0 - y1);
  for (t = ax->lo; t <= ax->hi + AFV_PLOT_TICK_TOL * ax->step; t += ax->step) {
    double px = x0 + (t - ax->lo) / (ax->hi - ax->lo) * (x1 - x0);
    fprintf(out, "<line x1=\"%.2f\" y1=\"%g\" x2=\"%.2f\" y2=\"%g\" "
            "stroke=\"black\"/>\n<text x=\"%.2f\" y=\"%g\" "
            "text-anchor=\"middle\">", px, y0, px, y0 + 5, px, y0 + 19);
    tick_label(out, ax, t);
    fprintf(out, "</text>\n");
  }
  for (t = ay->lo; t <= ay->hi + AFV_PLOT_TICK_TOL * ay->step; t += ay->step) {
    double py = y0 + (t - ay->lo) / (ay->hi - ay->lo) * (y1 - y0);
    fprintf(out, "<line x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" "
            "stroke=\"black\"/>\n<text x=\"%g\" y=\"%.2f\" "
            "text-anchor=\"end\">", x0 - 5, py, x0, py, x0 - 8, py + 4);
    tick_label(out, ay, t);
    fprintf(out, "</text>\n");
  }
}

/* A polyline through the usable points (unless a scatter), and a marker
** on each point when there are few of them (not on an error bar) or when
** asked to (scatter): s->points, AFV_PLOT_*. */
static void draw_series(FILE *out, const axis *ax, const axis *ay,
                        const afv_plot_series *s)
{
  double x0 = PLOT_L, x1 = PLOT_W - PLOT_R, y0 = PLOT_H - PLOT_B, y1 = PLOT_T;
  int i, used = 0;
  if (s->points != AFV_PLOT_MARKS) {
    fprintf(out, "<polyline class=\"series\" fill=\"none\" stroke=\"%s\" "
            "stroke-width=\"1.5\" points=\"", s->color);
    for (i = 0; i < s->n; i++)
      if (usable(ax, s->x[i]) && usable(ay, s->y[i]))
        fprintf(out, "%s%.2f,%.2f", used++ ? " " : "",
                to_px(ax, s->x[i], x0, x1), to_px(ay, s->y[i], y0, y1));
    fprintf(out, "\"/>\n");
    if (s->n > 60 || s->points == AFV_PLOT_LINE) return;
  }
  for (i = 0; i < s->n; i++)
    if (usable(ax, s->x[i]) && usable(ay, s->y[i]))
      fprintf(out, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.5\" fill=\"%s\"/>\n",
              to_px(ax, s->x[i], x0, x1), to_px(ay, s->y[i], y0, y1),
              s->color);
}

/* The legend sits right of the plot area, outside it, so it never covers
** the data: one entry a row, LEGEND_RUN rows a column, as many columns as
** needed.  Returns its width in pixels (0: no labels). */
#define LEGEND_RUN   ((int)((PLOT_H - PLOT_T - PLOT_B) / 16))
#define PLOT_CHAR    7.0     /* mean advance of a character at 12 px */
static double plot_legend_width(const afv_plot_series *s, int ns,
                                double *col_w)
{
  size_t most = 0;
  int k, labels = 0;
  for (k = 0; k < ns; k++)
    if (s[k].label) {
      labels++;
      if (strlen(s[k].label) > most) most = strlen(s[k].label);
    }
  *col_w = 34 + most * PLOT_CHAR + 10;
  return labels ? *col_w * ((labels + LEGEND_RUN - 1) / LEGEND_RUN) + 6 : 0;
}

static void plot_legend(FILE *out, const afv_plot_series *s, int ns,
                        double col_w)
{
  int k, j = 0;
  fprintf(out, "<g class=\"legend\">\n");
  for (k = 0; k < ns; k++) {
    double x = PLOT_W - PLOT_R + 12 + col_w * (j / LEGEND_RUN);
    double y = PLOT_T + 8 + 16 * (j % LEGEND_RUN);
    if (!s[k].label) continue;
    j++;
    if (s[k].points)
      fprintf(out, "<circle cx=\"%g\" cy=\"%g\" r=\"2.5\" fill=\"%s\"/>\n",
              x + 11, y, s[k].color);
    else
      fprintf(out, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" "
              "stroke=\"%s\" stroke-width=\"2\"/>\n", x, y, x + 22, y,
              s[k].color);
    fprintf(out, "<text x=\"%g\" y=\"%g\">", x + 28, y + 4);
    put_text(out, s[k].label);
    fprintf(out, "</text>\n");
  }
  fprintf(out, "</g>\n");
}

/* 1 if some series of s has a point that the axes ax, ay can draw. */
static int plot_has_data(const axis *ax, const axis *ay,
                         const afv_plot_series *s, int ns)
{
  int k, i;
  for (k = 0; k < ns; k++)
    for (i = 0; i < s[k].n; i++)
      if (usable(ax, s[k].x[i]) && usable(ay, s[k].y[i])) return 1;
  return 0;
}

/* "no data" (and why, if given) across the middle of an empty plot, so
** that its axes are not read as a result. */
static void plot_no_data(FILE *out, const afv_plot *pl)
{
  fprintf(out, "<text class=\"no-data\" x=\"%g\" y=\"%g\" "
          "text-anchor=\"middle\" font-size=\"14\">no data%s",
          (PLOT_L + PLOT_W - PLOT_R) / 2, (PLOT_T + PLOT_H - PLOT_B) / 2,
          pl->no_data ? ": " : "");
  if (pl->no_data) put_text(out, pl->no_data);
  fprintf(out, "</text>\n");
}

int afv_svg_plot(FILE *out, const afv_plot *pl, const afv_plot_series *s,
                 int ns)
{
  axis ax, ay;
  double col_w, W = PLOT_W + plot_legend_width(s, ns, &col_w);
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
          "<rect width=\"%g\" height=\"%g\" fill=\"white\"/>\n"
          "<defs><clipPath id=\"afv-plot-area\"><rect x=\"%g\" y=\"%g\" "
          "width=\"%g\" height=\"%g\"/></clipPath></defs>\n", W, PLOT_H, W,
          PLOT_H, PLOT_L, PLOT_T, PLOT_W - PLOT_R - PLOT_L,
          PLOT_H - PLOT_B - PLOT_T);
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
  /* the data stay inside the plot area (a fixed y range may cut them) */
  fprintf(out, "<g class=\"data\" clip-path=\"url(#afv-plot-area)\">\n");
  for (k = 0; k < ns; k++) draw_series(out, &ax, &ay, &s[k]);
  fprintf(out, "</g>\n");
  if (!plot_has_data(&ax, &ay, s, ns)) plot_no_data(out, pl);
  plot_legend(out, s, ns, col_w);
  fprintf(out, "</svg>\n");
  return ferror(out) ? AFV_EIO : AFV_OK;
}

/* ---- the plots of an analysis (afv analyze) ------------------------------ */
int afv_svg_msd(FILE *out, const afv_analysis *a)
{
  afv_plot pl = {"Mean-squared displacement", "lag (time)", "MSD (l^2)", 1,
                 1, 0, 0, NULL};
  afv_plot_series s[2];
  s[0].x = s[1].x = a->msd.dt;
  s[0].n = s[1].n = a->msd.nlags;
  s[0].y = a->msd.msd_rel;
  s[0].label = "relative MSD";
  s[0].color = "#d62728";
  s[1].y = a->msd.msd;
  s[1].label = "MSD";
  s[1].color = "#1f77b4";
  s[0].points = s[1].points = 0;
  return afv_svg_plot(out, &pl, s, 2);
}

int afv_svg_series(FILE *out, const afv_analysis *a)
{
  afv_plot pl = {"Giant cluster and confluency", "time", "N_GC/N, Omega", 0,
                 0, 0, 1.2, NULL};
  afv_plot_series s[2];
  s[0].x = s[1].x = a->t;
  s[0].n = s[1].n = a->nframes;
  s[0].y = a->ngc_frac;
  s[0].label = "N_GC/N";
  s[0].color = "#1f77b4";
  s[1].y = a->omega;
  s[1].label = "Omega";
  s[1].color = "#9467bd";
  s[0].points = s[1].points = 0;
  return afv_svg_plot(out, &pl, s, 2);
}

/* Each size's p(n) as a grey dot, and the log bins (afv_csd_log_bins) as
** a line through p per size of each bin at the bin's geometric middle. */
int afv_svg_csd(FILE *out, const afv_analysis *a)
{
  afv_plot pl = {"Cluster size distribution",
                 "cluster size n (cells); bin k: n = 2^k .. 2^(k+1) - 1",
                 "p(n)", 1, 1, 0, 0, NULL};
  afv_plot_series s[2];
  int lo[AFV_CSD_MAX_BINS], hi[AFV_CSD_MAX_BINS], k, m, st;
  double p[AFV_CSD_MAX_BINS], bx[AFV_CSD_MAX_BINS];
  double *x = malloc((size_t)(a->n + 1) * sizeof(double));
  if (!x) return AFV_ENOMEM;
  for (k = 0; k <= a->n; k++) x[k] = k;
  m = afv_csd_log_bins(a->csd, a->n, lo, hi, p);
  for (k = 0; k < m; k++) {
    bx[k] = sqrt((double)lo[k] * hi[k]);
    p[k] /= hi[k] - lo[k] + 1;
  }
  s[0].x = x + 1;
  s[0].y = a->csd + 1;
  s[0].n = a->n;
  s[0].label = "p(n), each size";
  s[0].color = "#aaaaaa";
  s[0].points = 1;
  s[1].x = bx;
  s[1].y = p;
  s[1].n = m;
  s[1].label = "mean p(n) over a log bin";
  s[1].color = "#2ca02c";
  s[1].points = 0;
  st = afv_svg_plot(out, &pl, s, 2);
  free(x);
  return st;
}
