/*
** test_pictures.c -- pictures: afv draw's options (size, crop, colours,
** frames), the digits of a drawn coordinate, the plots' legends, the
** log-binned cluster-size distribution, and analysis.c computing without
** drawing.  The program is run as a user runs it (./afv from the
** repository root, where `make test` starts the runner), its files in a
** temporary directory removed at the end of the suite.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[64];             /* the suite's directory */

#define shell test_sh   /* fixtures.c: a shell command's exit status */

/* tmpdir/name. */
static const char *in_tmp(char *buf, size_t len, const char *name)
{
  snprintf(buf, len, "%s/%s", tmpdir, name);
  return buf;
}

/* A whole file as a malloc'd string ("" if missing: caller frees). */
static char *read_all(const char *path)
{
  FILE *fp = fopen(path, "rb");
  char *buf;
  long size = 0;
  if (fp && fseek(fp, 0, SEEK_END) == 0) size = ftell(fp);
  if (size < 0) size = 0;
  buf = malloc((size_t)size + 1);
  if (!buf) {
    if (fp) fclose(fp);
    return NULL;
  }
  if (fp) rewind(fp);
  buf[fp ? fread(buf, 1, (size_t)size, fp) : 0] = 0;
  if (fp) fclose(fp);
  return buf;
}

static void write_text(const char *name, const char *text)
{
  char p[512];   /* tmpdir (64) and any name of this file (256) */
  FILE *fp = fopen(in_tmp(p, sizeof p, name), "w");
  CHECK(fp != NULL, "cannot create %s", p);
  if (!fp) return;
  fputs(text, fp);
  fclose(fp);
}

static int count_of(const char *s, const char *what)
{
  int m = 0;
  while ((s = strstr(s, what)) != NULL) {
    m++;
    s++;
  }
  return m;
}

/* Number in attribute name="..." of the tag that starts at or before at
** (searched up to the tag's end); NAN if absent. */
static double attr(const char *at, const char *name)
{
  char key[32];
  const char *end = strchr(at, '>'), *v;
  snprintf(key, sizeof key, " %s=\"", name);
  v = strstr(at, key);
  if (!v || (end && v > end)) return NAN;
  return strtod(v + strlen(key), NULL);
}

static int have_afv(void)
{
  if (access("./afv", X_OK) == 0) return 1;
  SKIP("./afv not built");
  return 0;
}

/* nx x ny cells of a square lattice, spacing 1.5, first at (x0, y0): a
** POINTS file. */
static void write_lattice(const char *name, int nx, int ny, double x0,
                          double y0)
{
  char p[128];
  FILE *fp = fopen(in_tmp(p, sizeof p, name), "w");
  int i, j;
  CHECK(fp != NULL, "cannot create %s", p);
  if (!fp) return;
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++)
      fprintf(fp, "%.17g %.17g\n", x0 + 1.5 * i, y0 + 1.5 * j);
  fclose(fp);
}

/* The centres drawn in svg (a write_lattice of nx columns from (x0,
** y0)): how many; *err the largest |dx| + |dy| of one from its cell, at
** centre *worst. */
static int centres_off(const char *svg, int nx, double x0, double y0,
                       double *err, int *worst)
{
  const char *at;
  int i = 0;
  *err = 0;
  *worst = -1;
  for (at = svg; at && (at = strstr(at, "class=\"centre\"")); at++, i++) {
    double e = fabs(attr(at, "cx") - (x0 + 1.5 * (i % nx)))
               + fabs(attr(at, "cy") - (y0 + 1.5 * (i / nx)));
    if (!(e <= *err)) {
      *err = e;
      *worst = i;
    }
  }
  return i;
}

/* ---- afv draw's options ------------------------------------------------- */
/* Every option accepted with a good value; each bad value refused with one
** line naming the option, exit status 2, and nothing written. */
static void draw_options_validated(void)
{
  static const char *bad[][2] = {
    {"--width 5", "--width"}, {"--width 2e5", "--width"},
    {"--width abc", "--width"}, {"--crop 1,2,3", "--crop"},
    {"--crop 3,0,1,5", "--crop"}, {"--crop 0,0,1,nan", "--crop"},
    {"--crop 0,0,1,1,", "--crop"}, {"--color-by speed", "--color-by"},
    {"--color-by", "--color-by"}, {"--color-by v0", "v0"},
    {"--frames", "--frames"}, {"--frames %s/never", "--frames"},
    {"--color-by P0 --cells %s/short.cells", "cells"}
  };
  char pts[128], so[128], se[128], never[128], opt[256], *o, *e;
  int k;
  if (!have_afv()) return;
  write_lattice("lat.xy", 4, 3, 0, 0);
  write_text("short.cells", "# P0\n4\n5\n");
  in_tmp(pts, sizeof pts, "lat.xy");
  in_tmp(so, sizeof so, "out.svg");
  in_tmp(se, sizeof se, "err.txt");
  CHECK(shell("./afv draw %s --width 300 --crop 0,0,3,3 --color-by cluster "
              ">%s 2>%s", pts, so, se) == 0, "good options refused");
  o = read_all(so);
  CHECK(o && strstr(o, "</svg>"), "good options: no picture");
  free(o);
  for (k = 0; k < (int)(sizeof bad / sizeof bad[0]); k++) {
    snprintf(opt, sizeof opt, bad[k][0], tmpdir);
    remove(so);
    CHECK(shell("./afv draw %s %s >%s 2>%s", pts, opt, so, se) == 2,
          "draw %s: exit status not 2", opt);
    o = read_all(so);
    e = read_all(se);
    CHECK(o && !o[0], "draw %s: wrote %s", opt, o);
    CHECK(e && count_of(e, "\n") == 1 && strstr(e, bad[k][1]),
          "draw %s: stderr not one line naming %s: %s", opt, bad[k][1], e);
    free(o);
    free(e);
  }
  CHECK(access(in_tmp(never, sizeof never, "never"), F_OK) != 0,
        "--frames on a POINTS file created the directory");
}

/* --width sets the picture's width in pixels and keeps its aspect; --crop
** shows exactly the region asked for, and only the cells in it. */
static void draw_width_and_crop(void)
{
  char pts[128], so[128], *s, *tissue, *top;
  int inside = 0, i, j;
  if (!have_afv()) return;
  write_lattice("wc.xy", 10, 6, 0, 0);     /* x 0..13.5, y 0..7.5 */
  in_tmp(pts, sizeof pts, "wc.xy");
  in_tmp(so, sizeof so, "wc.svg");
  CHECK(shell("./afv draw %s --width 420 >%s 2>/dev/null", pts, so) == 0,
        "--width");
  s = read_all(so);
  top = s ? strstr(s, "<svg ") : NULL;
  CHECK(top != NULL, "no picture");
  if (top) {
    /* the open view is the cells' extent plus 1.5 l each side */
    CHECK_CLOSE(attr(top, "width"), 420, 0, 0, "width in pixels");
    CHECK_CLOSE(attr(top, "height"), 420 * 10.5 / 16.5, 1e-5, 0,
                "height keeps the aspect");
  }
  free(s);
  /* crop x 2.2..8.2, y 0.7..3.7: lattice lines at 1.5 i are >= 0.05 away
  ** from its sides, farther than a centre dot's radius is large */
  CHECK(shell("./afv draw %s --crop 2.2,0.7,8.2,3.7 --width 600 >%s "
              "2>/dev/null", pts,
              so) == 0, "--crop");
  s = read_all(so);
  tissue = s ? strstr(s, "class=\"tissue\"") : NULL;
  top = s ? strstr(s, "<svg ") : NULL;
  CHECK(tissue != NULL && top != NULL, "no tissue viewport");
  if (tissue && top) {
    CHECK(strstr(tissue, "viewBox=\"2.2 0.7 6 3\""), "viewBox is not the "
          "crop: %.80s", tissue);
    CHECK_CLOSE(attr(top, "height"), 300, 1e-9, 0, "crop's aspect");
  }
  for (j = 0; j < 6; j++)
    for (i = 0; i < 10; i++)
      inside += 1.5 * i > 2.2 && 1.5 * i < 8.2 && 1.5 * j > 0.7
                && 1.5 * j < 3.7;
  CHECK(s && count_of(s, "class=\"centre\"") == inside, "crop draws %d "
        "centres, %d cells are in it", s ? count_of(s, "class=\"centre\"")
        : -1, inside);
  free(s);
}

/* A mixture of two cell types (P0 from a CELLS file): two colours, one per
** type, every cell filled with its type's colour, and a legend of two. */
static void draw_color_by_two_types(void)
{
  char pts[128], cells[128], so[128], text[4096], col[2][8] = {"", ""};
  char *s, *at;
  int i, n = 12, bad = 0;
  if (!have_afv()) return;
  write_lattice("two.xy", 4, 3, 0, 0);
  strcpy(text, "# P0\n");
  for (i = 0; i < n; i++)
    strcat(text, (i * 7) % 3 ? "4.5\n" : "7.25\n");
  write_text("two.cells", text);
  in_tmp(pts, sizeof pts, "two.xy");
  in_tmp(cells, sizeof cells, "two.cells");
  in_tmp(so, sizeof so, "two.svg");
  CHECK(shell("./afv draw %s --color-by P0 --cells %s >%s 2>/dev/null", pts,
              cells, so)
        == 0, "--color-by P0 refused");
  s = read_all(so);
  if (!s) return;
  at = s;
  for (i = 0; i < n && (at = strstr(at, "class=\"cell\" fill=\"")); i++) {
    char *c = col[(i * 7) % 3 ? 0 : 1];
    at += strlen("class=\"cell\" fill=\"");
    if (!c[0]) snprintf(c, 8, "%.7s", at);
    bad += strncmp(c, at, 7) != 0;
  }
  CHECK(i == n, "%d cells filled, want %d", i, n);
  CHECK(bad == 0 && col[0][0] && strcmp(col[0], col[1]) != 0,
        "types not told apart: %d cells off their type's colour, colours "
        "%s and %s", bad, col[0], col[1]);
  at = strstr(s, "class=\"legend\"");
  CHECK(at && count_of(at, "class=\"swatch\"") == 2
        && strstr(at, "P0 = 4.5: 8 cells") && strstr(at, "P0 = 7.25: 4 cells"),
        "legend does not list the two types");
  CHECK(at && strstr(at, col[0]) && strstr(at, col[1]),
        "legend colours are not the cells' colours");
  free(s);
}

/* Cells far from the origin are drawn where they are: every printed
** coordinate within 1e-4 l (with %.6g, 100000.75 was printed 100001). */
static void draw_coordinates_at_1e5(void)
{
  char pts[128], so[128], *s;
  int i, worst;
  double err;
  if (!have_afv()) return;
  write_lattice("far.xy", 3, 3, 100000.125, -99999.875);
  in_tmp(pts, sizeof pts, "far.xy");
  in_tmp(so, sizeof so, "far.svg");
  CHECK(shell("./afv draw %s >%s", pts, so) == 0, "draw far cells");
  s = read_all(so);
  i = centres_off(s, 3, 100000.125, -99999.875, &err, &worst);
  CHECK(i == 9, "%d centres drawn, want 9", i);
  CHECK(err <= 1e-4, "centre %d drawn %g l from its place", worst, err);
  free(s);
}

/* At the default size a 400-cell box (800 pixels for 32 l) shows its
** junctions and edges: a junction at least 2.5 pixels in radius, lines at
** least a pixel wide (they were 1.75 and 0.875 pixels). */
static void draw_marks_visible_at_default_size(void)
{
  double r[2 * 400];
  char pts[128], so[128], box[64], *s, *at;
  afv_box b;
  int i;
  FILE *fp;
  double px, jr, lw;
  if (!have_afv()) return;
  b = test_tri_lattice(20, 20, 1.6, 0.3, 0.2, r);
  fp = fopen(in_tmp(pts, sizeof pts, "box.xy"), "w");
  if (!fp) return;
  for (i = 0; i < 400; i++) fprintf(fp, "%.17g %.17g\n", r[2*i], r[2*i+1]);
  fclose(fp);
  snprintf(box, sizeof box, "%.17g,%.17g", b.Lx, b.Ly);
  in_tmp(so, sizeof so, "box.svg");
  CHECK(shell("./afv draw %s --box %s >%s", pts, box, so) == 0, "draw box");
  s = read_all(so);
  at = s ? strstr(s, "class=\"junction\"") : NULL;
  CHECK(at != NULL, "no junction drawn");
  if (!at) {
    free(s);
    return;
  }
  px = 800 / (b.Lx > b.Ly ? b.Lx : b.Ly);
  jr = attr(at, "r") * px;
  at = strstr(s, "<g fill=\"none\"");
  lw = at ? attr(at, "stroke-width") * px : 0;
  CHECK(jr >= 2.5, "junction radius %.3g pixels", jr);
  CHECK(lw >= 1, "edge width %.3g pixels", lw);
  free(s);
}

/* On a picture of many cells at a small size, a centre is still printed
** to 1e-4 l (AFV_SVG_RESOLUTION: a pixel there is 0.16 l, and the
** resolution of a hundredth of a pixel alone would print 3 digits). */
static void draw_coordinates_of_a_small_picture(void)
{
  char pts[128], so[128], *s;
  int i, worst;
  double err;
  if (!have_afv()) return;
  write_lattice("small.xy", 10, 10, 0.123456789, 0.987654321);
  in_tmp(pts, sizeof pts, "small.xy");
  in_tmp(so, sizeof so, "small.svg");
  CHECK(shell("./afv draw %s --width 100 >%s", pts, so) == 0, "draw");
  s = read_all(so);
  i = centres_off(s, 10, 0.123456789, 0.987654321, &err, &worst);
  CHECK(i == 100, "%d centres drawn, want 100", i);
  CHECK(err <= 1e-4, "centre %d drawn %g l from its place", worst, err);
  free(s);
}

/* The arcs of SVG path d (after "d=\""): how many; 0 if one of them ends
** where it starts (SVG draws no such arc: SVG 1.1, F.6.2) or d is not
** "M x y" followed by "A rx ry 0 large sweep x y" commands. */
static int arcs_drawn(const char *d)
{
  double x, y, nx, ny, rx, ry, rot;
  int large, sweep, used, n = 0;
  if (sscanf(d, "M %lf %lf%n", &x, &y, &used) != 2) return 0;
  for (d += used; sscanf(d, " A %lf %lf %lf %d %d %lf %lf%n", &rx, &ry, &rot,
                         &large, &sweep, &nx, &ny, &used) == 7; d += used) {
    if (nx == x && ny == y) return 0;
    x = nx;
    y = ny;
    n++;
  }
  return *d == '"' ? n : 0;
}

/* An isolated cell's outline is a whole circle, drawn as two half arcs (a
** single arc from a point to itself draws nothing); two cells 1.99 l
** apart are each outlined by one arc of 2 pi - 0.2 (AFV_FULL_CIRCLE_TOL:
** only an arc within rounding of a full turn is a whole circle). */
static void draw_whole_and_nearly_whole_circles(void)
{
  char pts[128], so[128], *s, *at;
  int paths = 0, whole = 0, single = 0, k;
  if (!have_afv()) return;
  write_text("arcs.xy", "0 0\n1.99 0\n20 0\n");
  in_tmp(pts, sizeof pts, "arcs.xy");
  in_tmp(so, sizeof so, "arcs.svg");
  CHECK(shell("./afv draw %s >%s", pts, so) == 0, "draw");
  s = read_all(so);
  for (at = s; at && (at = strstr(at, "class=\"arc\" d=\"")); at++, paths++) {
    k = arcs_drawn(at + strlen("class=\"arc\" d=\""));
    whole += k == 2;
    single += k == 1;
  }
  CHECK(paths == 3 && whole == 1 && single == 2, "%d arc paths: %d whole "
        "circles (want 1), %d single arcs (want 2), the rest not drawn",
        paths, whole, single);
  free(s);
}

/* --frames writes every frame of a trajectory, named frame_NNNNN.svg. */
static void draw_frames_of_a_trajectory(void)
{
  char run[128], frames[128], name[192], *log;
  afv_traj tr;
  char err[256];
  int f, have = 0;
  if (!have_afv()) return;
  in_tmp(run, sizeof run, "run");
  in_tmp(frames, sizeof frames, "frames");
  CHECK(shell("./afv run --out %s --N 30 --steps 300 --frame_every 50 "
              "--svg_every 0 --quiet >/dev/null 2>&1", run) == 0, "afv run");
  snprintf(name, sizeof name, "%s/trajectory.dat", run);
  if (afv_traj_read(name, &tr, err, sizeof err) != AFV_OK) {
    CHECK(0, "%s", err);
    return;
  }
  CHECK(shell("./afv draw %s --frames %s --color-by v0 2>%s/frames.log",
              name, frames, tmpdir) == 0, "--frames refused");
  for (f = 0; f < tr.nframes + 1; f++) {
    snprintf(name, sizeof name, "%s/frame_%05d.svg", frames, f);
    have += access(name, R_OK) == 0;
  }
  CHECK(tr.nframes == 7 && have == tr.nframes, "%d of %d frames written",
        have, tr.nframes);
  snprintf(name, sizeof name, "%s/frames.log", tmpdir);
  log = read_all(name);
  CHECK(log && strstr(log, "7 frames written"), "no report: %s", log);
  free(log);
  afv_traj_free(&tr);
}

/* ---- plots ------------------------------------------------------------- */
/* The legend lies right of every data point (it covered msd.svg's
** curves: the old legend sat inside the plot area's top right corner). */
static void plot_legend_beside_data(void)
{
  double x[50], y[50], most = 0, v;
  afv_plot pl = {"t", "x", "y", 1, 1, 0, 0, NULL};
  afv_plot_series s[2];
  FILE *fp = tmpfile();
  char *svg, *at;
  long size;
  int k;
  if (!fp) return;
  for (k = 0; k < 50; k++) {
    x[k] = pow(10, k / 10.0);
    y[k] = x[k] * x[k];
  }
  s[0].x = s[1].x = x;
  s[0].y = s[1].y = y;
  s[0].n = s[1].n = 50;
  s[0].label = "first label";
  s[1].label = "second";
  s[0].color = "#ff0000";
  s[1].color = "#0000ff";
  s[0].points = 0;
  s[1].points = 1;
  CHECK(afv_svg_plot(fp, &pl, s, 2) == AFV_OK, "plot");
  size = ftell(fp);
  rewind(fp);
  svg = size > 0 ? malloc((size_t)size + 1) : NULL;
  if (svg) svg[fread(svg, 1, (size_t)size, fp)] = 0;
  fclose(fp);
  if (!svg) return;
  for (at = svg; (at = strstr(at, "<circle")) != NULL; at++)
    if ((v = attr(at, "cx")) > most) most = v;
  at = strstr(svg, ">first label<");
  while (at && at > svg && strncmp(at, "<text", 5)) at--;
  CHECK(at && attr(at, "x") > most + 5, "legend text at x %g, data up to %g",
        at ? attr(at, "x") : NAN, most);
  at = strstr(svg, ">second<");
  while (at && at > svg && strncmp(at, "<text", 5)) at--;
  CHECK(at && attr(at, "x") > most + 5, "second legend entry over the data");
  free(svg);
}

/* afv_svg_plot of one series of n points (markers only), as a string
** (NULL if it could not be written: the caller frees). */
static char *plot_string(const double *x, const double *y, int n)
{
  afv_plot pl = {"t", "x", "y", 0, 0, 0, 0, NULL};
  afv_plot_series sr;
  FILE *fp = tmpfile();
  char *svg = NULL;
  long size;
  if (!fp) return NULL;
  memset(&sr, 0, sizeof sr);
  sr.x = x;
  sr.y = y;
  sr.n = n;
  sr.color = "#000000";
  sr.points = AFV_PLOT_MARKS;
  CHECK(afv_svg_plot(fp, &pl, &sr, 1) == AFV_OK, "plot");
  size = ftell(fp);
  rewind(fp);
  svg = size > 0 ? malloc((size_t)size + 1) : NULL;
  if (svg) svg[fread(svg, 1, (size_t)size, fp)] = 0;
  fclose(fp);
  return svg;
}

/* The y axis's tick labels of a plot, bottom to top, into lab (at most
** max); how many. */
static int y_tick_labels(const char *svg, char lab[][32], int max)
{
  const char *at = svg, *key = "text-anchor=\"end\">";
  int n = 0;
  while (n < max && (at = strstr(at, key)) != NULL) {
    at += strlen(key);
    sscanf(at, "%31[^<]", lab[n++]);
  }
  return n;
}

/* A plotted range that holds one value is widened around it
** (AFV_PLOT_SPAN_TOL): the points sit inside the frame, and the y axis
** has at least two ticks, labelled apart.  (A range of rounding, 0.1 + 0.2
** and 0.3, is one value too: with the tolerance 0 its ticks, 1e-17
** apart, never reached the axis end, and the plot never ended.) */
static void plot_of_one_value(void)
{
  static const double x[3] = {1, 2, 3}, y[3] = {0.5, 0.5, 0.5};
  char lab[64][32], *svg = plot_string(x, y, 3), *c;
  const char *frame = svg ? strstr(svg, "<rect x=") : NULL;
  int bad = 0, count = 0, n, k;
  CHECK(frame != NULL, "no plot frame");
  if (!frame) {
    free(svg);
    return;
  }
  for (c = strstr(svg, "<circle"); c; c = strstr(c + 1, "<circle")) {
    double cy = attr(c, "cy");
    count++;
    bad += !(cy > attr(frame, "y") + 5
             && cy < attr(frame, "y") + attr(frame, "height") - 5);
  }
  CHECK(count == 3 && bad == 0, "%d of %d points off the frame", bad, count);
  n = y_tick_labels(svg, lab, 64);
  CHECK(n >= 2, "%d y ticks", n);
  for (k = 1; k < n; k++)
    CHECK(strcmp(lab[k - 1], lab[k]) != 0, "two ticks labelled %s", lab[k]);
  free(svg);
}

/* The ticks of a range symmetric about 0 (data -0.3 .. 0.3: ticks every
** 0.1 from -0.4 to 0.4, summed as lo + step + step ...) are symmetric: the
** middle one labelled 0, not the rounding of the sum (AFV_PLOT_TICK_TOL),
** the last at the axis end although the sum overshoots it by rounding. */
static void plot_ticks_symmetric(void)
{
  static const double x[3] = {1, 2, 3}, y[3] = {-0.3, 0.1, 0.3};
  char lab[64][32], *svg = plot_string(x, y, 3);
  int n = svg ? y_tick_labels(svg, lab, 64) : 0, k;
  CHECK(n == 9, "%d y ticks, want 9 (-0.4 .. 0.4)", n);
  for (k = 0; k < n; k++) {
    const char *a = lab[k], *b = lab[n - 1 - k];
    if (k == n / 2) CHECK(!strcmp(a, "0"), "middle tick labelled %s", a);
    else CHECK(a[0] == '-' ? !strcmp(a + 1, b) : !strcmp(a, b + 1),
               "ticks %d and %d labelled %s and %s", k, n - 1 - k, a, b);
  }
  free(svg);
}

/* Log bins: sizes 2^k .. 2^(k+1) - 1, each size in exactly one bin, and
** the bins' p sum to the distribution's. */
static void csd_log_bins_sum(void)
{
  enum { N = 300 };
  double csd[N + 1], p[AFV_CSD_MAX_BINS], total = 0, binned = 0;
  int lo[AFV_CSD_MAX_BINS], hi[AFV_CSD_MAX_BINS], m, k, s;
  test_rng_seed(23);
  csd[0] = 0;
  for (s = 1; s <= N; s++) total += csd[s] = test_rng_uniform() / s;
  m = afv_csd_log_bins(csd, N, lo, hi, p);
  CHECK(m == 9, "%d bins for n <= 300, want 9 (1, 2, 4, .., 256)", m);
  for (k = 0; k < m; k++) {
    double want = 0;
    CHECK(lo[k] == 1 << k && hi[k] == (k == m - 1 ? N : 2 * lo[k] - 1),
          "bin %d is %d..%d", k, lo[k], hi[k]);
    for (s = lo[k]; s <= hi[k]; s++) want += csd[s];
    CHECK_CLOSE(p[k], want, 1e-15, 0, "p of a bin");
    binned += p[k];
  }
  CHECK_CLOSE(binned, total, 1e-14, 0, "bins sum to the distribution");
  CHECK(afv_csd_log_bins(csd, 1, lo, hi, p) == 1 && lo[0] == 1 && hi[0] == 1,
        "one cell: one bin");
}

/* afv analyze writes the plots (drawn by report.c, svg.c) and the log bins
** (csd_binned.csv, summing to csd.csv). */
static void analyze_writes_binned_csd_and_plots(void)
{
  static const char *plots[] = {"msd.svg", "series.svg", "csd.svg"};
  char run[128], path[192], *csv, *line;
  double sum_csd = 0, sum_bins = 0;
  int k;
  if (!have_afv()) return;
  in_tmp(run, sizeof run, "run");
  if (access(run, F_OK) != 0)
    CHECK(shell("./afv run --out %s --N 30 --steps 300 --frame_every 50 "
                "--svg_every 0 --quiet >/dev/null 2>&1", run) == 0, "run");
  CHECK(shell("./afv analyze %s --lag 1 >/dev/null 2>&1", run) == 0,
        "afv analyze");
  for (k = 0; k < 3; k++) {
    char *svg;
    snprintf(path, sizeof path, "%s/analysis/%s", run, plots[k]);
    svg = read_all(path);
    CHECK(svg && strstr(svg, "</svg>") && strstr(svg, "class=\"legend\""),
          "%s missing or without its legend", plots[k]);
    free(svg);
  }
  snprintf(path, sizeof path, "%s/analysis/csd.csv", run);
  csv = read_all(path);
  for (line = csv ? strchr(csv, '\n') : NULL; line && line[1];
       line = strchr(line + 1, '\n'))
    sum_csd += strtod(strchr(line, ',') + 1, NULL);
  free(csv);
  snprintf(path, sizeof path, "%s/analysis/csd_binned.csv", run);
  csv = read_all(path);
  CHECK(csv && !strncmp(csv, "n_lo,n_hi,p_bin,p_per_n\n", 24),
        "csd_binned.csv missing or without its header");
  for (line = csv ? strchr(csv, '\n') : NULL; line && line[1];
       line = strchr(line + 1, '\n')) {
    char *c = strchr(strchr(line + 1, ',') + 1, ',');
    sum_bins += strtod(c + 1, NULL);
  }
  free(csv);
  CHECK(sum_csd > 0.999, "csd.csv sums to %g", sum_csd);
  CHECK_CLOSE(sum_bins, sum_csd, 1e-8, 0, "csd_binned.csv sums to csd.csv");
}

/* Computing an order parameter never draws: analysis.o uses no afv_svg_
** function (nm), and analysis.c names none. */
static void analysis_does_not_draw(void)
{
  char line[512];
  char *src = read_all("analysis.c");
  FILE *nm;
  int uses = 0, lines = 0;
  CHECK(src && src[0], "analysis.c not found (run from the repository root)");
  CHECK(src && !strstr(src, "afv_svg_"), "analysis.c names afv_svg_*");
  free(src);
  if (access("analysis.o", R_OK) != 0) {
    SKIP("analysis.o not built");
    return;
  }
  nm = popen("nm analysis.o 2>/dev/null", "r");
  if (!nm) return;
  while (fgets(line, sizeof line, nm)) {
    lines++;
    uses += strstr(line, "afv_svg_") != NULL;
  }
  pclose(nm);
  if (lines == 0) {
    SKIP("nm printed nothing");
    return;
  }
  CHECK(uses == 0, "analysis.o refers to %d afv_svg_ symbol(s)", uses);
}

/* ---- messages ---------------------------------------------------------- */
/* afv draw on an empty POINTS file and afv analyze on a mistyped DIR:
** exit 2 and one line naming the file and the reason (before: draw said
** only "parameter out of range"; analyze first said "params.txt not
** found: using l = 1 ..." and then "cannot open"). */
static void draw_and_analyze_name_what_is_wrong(void)
{
  char pts[128], se[128], typo[128], *e;
  if (!have_afv()) return;
  write_text("empty.xy", "# no cells\n");
  in_tmp(pts, sizeof pts, "empty.xy");
  in_tmp(se, sizeof se, "err.txt");
  in_tmp(typo, sizeof typo, "runs/typo");
  CHECK(shell("./afv draw %s >/dev/null 2>%s", pts, se) == 2, "draw empty");
  e = read_all(se);
  CHECK(e && count_of(e, "\n") == 1 && strstr(e, "empty.xy")
        && strstr(e, "no cells"), "afv draw on an empty file: %s", e);
  free(e);
  CHECK(shell("./afv analyze %s >/dev/null 2>%s", typo, se) == 2,
        "analyze typo");
  e = read_all(se);
  CHECK(e && count_of(e, "\n") == 1 && strstr(e, "runs/typo")
        && !strstr(e, "params.txt"), "afv analyze on a missing DIR: %s", e);
  free(e);
}

/* ---- pictures along a movie --------------------------------------------- */
/* The fill of each cell of an SVG (class="cell", in cell order: open
** space draws each cell once), into fill[n][8]; returns how many. */
static int cell_fills(const char *svg, char fill[][8], int n)
{
  const char *p = svg;
  int k = 0;
  while (k < n && (p = strstr(p, "class=\"cell\" fill=\"")) != NULL) {
    p += strlen("class=\"cell\" fill=\"");
    snprintf(fill[k], 8, "%.7s", p);
    k++;
  }
  return k;
}

/* Draws the 16 cells r (open space) coloured by cluster with the colour
** memory color, into a string (malloc'd; NULL on failure). */
static char *draw_clusters(const double *r, int *color)
{
  char path[128], *svg;
  afv_geom g = {0};
  afv_params p;
  afv_box b = test_open_box();
  afv_draw_opts o;
  FILE *fp = fopen(in_tmp(path, sizeof path, "clusters.svg"), "w");
  int st;
  afv_params_default(&p);
  memset(&o, 0, sizeof o);
  o.color_by_cluster = 1;
  o.cluster_color = color;
  if (!fp) return NULL;
  st = afv_geometry(&g, 16, r, &p, &b);
  if (st == AFV_OK) st = afv_svg_draw(fp, &g, 16, r, NULL, &p, &b, &o);
  fclose(fp);
  afv_geom_free(&g);
  CHECK(st == AFV_OK, "afv_svg_draw: %d", st);
  svg = read_all(path);
  return svg;
}

/* Along a movie a cluster keeps its colour while it keeps more than half
** of its cells: A (8 cells) splits into 5 + 3, B (5) merges with C (3)
** and becomes the largest; B+C keeps B's colour and A's 5 keep A's
** (before: colours were ranked by size in each frame, so B+C took A's). */
static void cluster_colours_stable(void)
{
  double r[32];
  int color[16], i;
  char f1[16][8], f2[16][8];
  char *s1, *s2;
  for (i = 0; i < 8; i++) { r[2*i] = 1.5 * i; r[2*i+1] = 0; }            /* A */
  for (i = 8; i < 13; i++) { r[2*i] = 1.5 * (i - 8); r[2*i+1] = 10; }    /* B */
  for (i = 13; i < 16; i++) { r[2*i] = 20 + 1.5 * (i - 13); r[2*i+1] = 10; }
  for (i = 0; i < 16; i++) color[i] = -1;
  s1 = draw_clusters(r, color);
  for (i = 5; i < 8; i++) r[2*i+1] = -10;           /* A splits */
  for (i = 13; i < 16; i++) r[2*i] = 7.5 + 1.5 * (i - 13);   /* C joins B */
  s2 = draw_clusters(r, color);
  CHECK(s1 && s2 && cell_fills(s1, f1, 16) == 16
        && cell_fills(s2, f2, 16) == 16, "16 filled cells expected");
  if (s1 && s2) {
    CHECK(strcmp(f1[0], f2[0]) == 0, "A's larger part changed colour: %s "
          "-> %s", f1[0], f2[0]);
    CHECK(strcmp(f1[8], f2[8]) == 0 && strcmp(f2[8], f2[13]) == 0, "B+C "
          "did not keep B's colour: B %s -> %s, C's cells %s", f1[8], f2[8],
          f2[13]);
    CHECK(strcmp(f2[5], f2[0]) != 0 && strcmp(f2[5], f2[8]) != 0, "A's "
          "smaller part shares a colour: %s", f2[5]);
  }
  free(s1);
  free(s2);
}

/* --frames replaces its own older frames (none left past the new last
** one) and refuses a directory holding anything else, changing nothing
** (before: 3 stale frames stayed; the foreign file's directory was used). */
static void frames_dir_replaced_or_refused(void)
{
  char run[128], dir[128], name[256], *s;
  int f, have = 0;
  if (!have_afv()) return;
  in_tmp(run, sizeof run, "run/trajectory.dat");
  in_tmp(dir, sizeof dir, "oldframes");
  if (access(run, R_OK) != 0) {
    CHECK(0, "%s missing (draw_frames_of_a_trajectory makes it)", run);
    return;
  }
  mkdir(dir, 0700);
  for (f = 0; f < 10; f++) {
    snprintf(name, sizeof name, "oldframes/frame_%05d.svg", f);
    write_text(name, "old\n");
  }
  CHECK(shell("./afv draw %s --frames %s 2>/dev/null", run, dir) == 0,
        "--frames over older frames refused");
  for (f = 0; f < 10; f++) {
    snprintf(name, sizeof name, "%s/frame_%05d.svg", dir, f);
    have += access(name, F_OK) == 0;
  }
  CHECK(have == 7, "%d frames in DIR after redrawing 7 over 10", have);
  write_text("oldframes/notes.txt", "mine\n");
  CHECK(shell("./afv draw %s --frames %s 2>/dev/null", run, dir) == 2,
        "--frames into a directory holding notes.txt: not refused");
  s = read_all(in_tmp(name, sizeof name, "oldframes/notes.txt"));
  CHECK(s && strcmp(s, "mine\n") == 0, "notes.txt changed: %s", s);
  free(s);
}

/* --caption and --scale-bar: a line with N, P0, v0, Lambda and t, and a
** bar of exactly 1 l (a 4 x 3 lattice of spacing 1.5 is drawn 7.5 l
** wide in 800 px: 106.67 px a unit).  Without them, neither. */
static void caption_and_scale_bar(void)
{
  char run[128], so[128], pts[128], *s, *bar;
  if (!have_afv()) return;
  in_tmp(run, sizeof run, "run/trajectory.dat");
  in_tmp(so, sizeof so, "caption.svg");
  CHECK(shell("./afv draw %s --caption > %s", run, so) == 0,
        "--caption refused");
  s = read_all(so);
  CHECK(s && strstr(s, "class=\"caption\"") && strstr(s, "N = 30, P0 = ")
        && strstr(s, "v0 = ") && strstr(s, "Lambda = ") && strstr(s, "t = "),
        "caption missing or incomplete");
  CHECK(s && !strstr(s, "scale-bar"), "a scale bar nobody asked for");
  free(s);
  write_lattice("bar.xy", 4, 3, 0, 0);
  in_tmp(pts, sizeof pts, "bar.xy");
  CHECK(shell("./afv draw %s --scale-bar > %s", pts, so) == 0,
        "--scale-bar refused");
  s = read_all(so);
  bar = s ? strstr(s, "class=\"scale-bar\"") : NULL;
  CHECK(bar && fabs(attr(bar, "width") - 800 / 7.5) < 1e-3, "scale bar: "
        "%g px, want %g", bar ? attr(bar, "width") : -1, 800 / 7.5);
  CHECK(s && !strstr(s, "class=\"caption\""), "a caption nobody asked for");
  free(s);
}

/* ---- plot ranges -------------------------------------------------------- */
/* Every point of a plot lies inside its frame with a margin, also a point
** exactly at a decade or a tick (before: csd.svg's p = 1 sat on the top
** edge, boundary.svg clipped a point at a corner). */
static void plot_points_inside_frame(void)
{
  static double x1[3] = {1, 10, 100}, y1[3] = {1, 0.1, 0.01};
  static double x2[4] = {4, 4.4, 4.8, 5.2}, y2[4] = {2, 1.5, 1, 0.5};
  afv_plot pl = {"t", "x", "y", 1, 1, 0, 0, NULL};
  afv_plot_series s;
  char path[128], *svg, *c;
  int round, bad = 0, count = 0;
  for (round = 0; round < 2; round++) {
    FILE *fp = fopen(in_tmp(path, sizeof path, "plot.svg"), "w");
    double fx0, fy0, fw, fh;
    const char *frame;
    memset(&s, 0, sizeof s);
    s.x = round ? x2 : x1;
    s.y = round ? y2 : y1;
    s.n = round ? 4 : 3;
    s.color = "#000000";
    s.points = 1;
    pl.logx = pl.logy = !round;
    if (!fp) return;
    afv_svg_plot(fp, &pl, &s, 1);
    fclose(fp);
    svg = read_all(path);
    if (!svg) return;
    frame = strstr(svg, "<rect x=");
    fx0 = attr(frame, "x"); fy0 = attr(frame, "y");
    fw = attr(frame, "width"); fh = attr(frame, "height");
    for (c = strstr(svg, "<circle"); c; c = strstr(c + 1, "<circle")) {
      double cx = attr(c, "cx"), cy = attr(c, "cy");
      count++;
      if (!(cx > fx0 + 5 && cx < fx0 + fw - 5 && cy > fy0 + 5
            && cy < fy0 + fh - 5))
        bad++;
    }
    free(svg);
  }
  CHECK(count == 7 && bad == 0, "%d of %d points within 5 px of the frame",
        bad, count);
}

void suite_pictures(void)
{
  char cmd[128];
  snprintf(tmpdir, sizeof tmpdir, "/tmp/afv_pictures_XXXXXX");
  if (!mkdtemp(tmpdir)) {
    printf("FAIL suite_pictures: cannot create a temporary directory\n");
    return;
  }
  RUN(draw_options_validated);
  RUN(draw_width_and_crop);
  RUN(draw_color_by_two_types);
  RUN(draw_coordinates_at_1e5);
  RUN(draw_marks_visible_at_default_size);
  RUN(draw_coordinates_of_a_small_picture);
  RUN(draw_whole_and_nearly_whole_circles);
  RUN(draw_frames_of_a_trajectory);
  RUN(frames_dir_replaced_or_refused);
  RUN(caption_and_scale_bar);
  RUN(cluster_colours_stable);
  RUN(plot_points_inside_frame);
  RUN(plot_legend_beside_data);
  RUN(plot_of_one_value);
  RUN(plot_ticks_symmetric);
  RUN(csd_log_bins_sum);
  RUN(analyze_writes_binned_csd_and_plots);
  RUN(analysis_does_not_draw);
  RUN(draw_and_analyze_name_what_is_wrong);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd) != 0) printf("  (could not remove %s)\n", tmpdir);
}
