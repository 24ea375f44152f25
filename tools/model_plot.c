/*
** tools/model_plot.c -- the figures of the model study
** (tools/model_sweeps.sh, doc/reproduction/model/README.md).
**
**   tools/model_plot TABLE.CSV XCOL OBS FILTER OUT.SVG TITLE [GROUP]
**   tools/model_plot --crossing TABLE.CSV OBS CURVE LO HI
**
** TABLE.CSV is one of tools/model_table.sh's tables (dt_table.csv,
** cap_seq_table.csv, fss_table.csv, ...): a header naming the columns,
** among them XCOL, the GROUP columns and OBS_mean (or OBS itself), OBS_sem
** if there is one.  The first form draws one curve per value of GROUP (a
** comma list of columns, default P0,v0) among the rows FILTER keeps: OBS's
** seed mean against XCOL, with the seed standard error drawn as small
** markers at mean - sem and mean + sem.  XCOL dt and N are drawn on a log
** axis, any other linearly; D_eff and t1_rate on a log axis.  FILTER is
** "all", "KEY=X" (rows whose column KEY is the number X) or "KEY!=X".  A
** row whose x or mean is not a number (a state point without a finished
** run) is left out; the title should say so.
**
** The second form prints, for each value of the column N, runs in or not
** (a row per N, "N,v0_cross,points"), where the curve of OBS against v0 at CURVE = LO
** (e.g. P0 4) falls below the one at CURVE = HI (afv_curves_cross, as afv
** paper's finite-size table), over the v0 where both are in: "none" when
** they do not cross there, "missing" with fewer than two such v0.
**
** Exit status 2 on a malformed file, or (first form) when no row is kept.
*/
#include "afv.h"
#include "afv_tool.h"   /* afv_svg_plot */
#include "cmd/fits.h"   /* afv_curves_cross */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROWS   512
#define MAX_COLS   64
#define MAX_GROUP  4
#define MAX_CURVES 12
#define LINE_LEN   4096

typedef struct row {
  double key[MAX_GROUP];  /* the GROUP columns' values: the curve */
  double x, mean, sem;    /* sem 0 where none (one seed) */
} row;

typedef struct table {
  int nrow, ngroup;
  char group[MAX_GROUP][64];
  row rows[MAX_ROWS];
} table;

static const char *colors[MAX_CURVES] = {
  "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
  "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939"};

/* The index of column name in the header's fields, or -1. */
static int column(char **names, int n, const char *name)
{
  int k;
  for (k = 0; k < n; k++)
    if (strcmp(names[k], name) == 0) return k;
  return -1;
}

/* Splits line at commas in place (empty fields kept); returns the count. */
static int split_csv(char *line, char **field, int max)
{
  int n = 0;
  char *p = line;
  line[strcspn(line, "\r\n")] = '\0';
  while (n < max) {
    field[n++] = p;
    p = strchr(p, ',');
    if (!p) break;
    *p++ = '\0';
  }
  return n;
}

/* A field as a number: NaN if empty or not a number ("missing"). */
static double number(const char *s)
{
  char *end;
  double v = strtod(s, &end);
  return end == s ? NAN : v;
}

/* The filter "all", "KEY=X" or "KEY!=X": its column in *col (-1: all),
** its value, *negate; 0 if malformed or KEY is not a column. */
static int parse_filter(const char *filter, char **h, int nh, int *col,
                        double *value, int *negate)
{
  char key[64];
  const char *eq = strchr(filter, '=');
  size_t len;
  *col = -1;
  if (strcmp(filter, "all") == 0) return 1;
  if (!eq || eq == filter) return 0;
  *negate = eq[-1] == '!';
  len = (size_t)(eq - filter) - (size_t)*negate;
  if (len == 0 || len >= sizeof key) return 0;
  memcpy(key, filter, len);
  key[len] = '\0';
  *value = number(eq + 1);
  return (*col = column(h, nh, key)) >= 0;
}

/* The columns of x, OBS's mean and sem (or -1), and GROUP's. */
static int find_columns(char **h, int nh, const char *xcol, const char *obs,
                        table *t, int *c)
{
  char name[128];
  int k;
  snprintf(name, sizeof name, "%s_mean", obs);
  c[0] = column(h, nh, xcol);
  c[1] = column(h, nh, name) >= 0 ? column(h, nh, name) : column(h, nh, obs);
  snprintf(name, sizeof name, "%s_sem", obs);
  c[2] = column(h, nh, name);
  if (c[0] < 0 || c[1] < 0) {
    fprintf(stderr, "model_plot: no column %s\n", c[0] < 0 ? xcol : obs);
    return 0;
  }
  for (k = 0; k < t->ngroup; k++)
    if ((c[3 + k] = column(h, nh, t->group[k])) < 0) {
      fprintf(stderr, "model_plot: no column %s\n", t->group[k]);
      return 0;
    }
  return 1;
}

/* The rows of path that filter keeps into t; a row whose x or mean is not
** a number is left out, unless keep_missing (its mean then NaN). */
static int read_rows(const char *path, const char *xcol, const char *obs,
                     const char *filter, int keep_missing, table *t)
{
  char line[LINE_LEN], header[LINE_LEN], *f[MAX_COLS], *h[MAX_COLS];
  int nh, c[3 + MAX_GROUP], k, lineno = 1, fcol, negate = 0, ok = 1;
  double fval = 0;
  FILE *fp = fopen(path, "r");
  if (!fp || !fgets(header, sizeof header, fp)) {
    fprintf(stderr, "model_plot: %s: cannot read\n", path);
    if (fp) fclose(fp);
    return 0;
  }
  nh = split_csv(header, h, MAX_COLS);
  if (!find_columns(h, nh, xcol, obs, t, c)
      || !parse_filter(filter, h, nh, &fcol, &fval, &negate)) {
    fprintf(stderr, "model_plot: %s: columns or filter '%s' not found\n",
            path, filter);
    fclose(fp);
    return 0;
  }
  t->nrow = 0;
  while (ok && fgets(line, sizeof line, fp)) {
    row *r = &t->rows[t->nrow];
    lineno++;
    if (line[0] == '\n') break;          /* a second table follows */
    if (split_csv(line, f, MAX_COLS) != nh || t->nrow >= MAX_ROWS) {
      fprintf(stderr, "model_plot: %s:%d: not a row of %d fields\n", path,
              lineno, nh);
      ok = 0;
      break;
    }
    if (fcol >= 0 && (number(f[fcol]) == fval) == negate) continue;
    r->x = number(f[c[0]]);
    r->mean = number(f[c[1]]);
    r->sem = c[2] >= 0 && isfinite(number(f[c[2]])) ? number(f[c[2]]) : 0;
    for (k = 0; k < t->ngroup; k++) r->key[k] = number(f[c[3 + k]]);
    if (isfinite(r->x) && (keep_missing || isfinite(r->mean))) t->nrow++;
  }
  fclose(fp);
  return ok;
}

static int by_x(const void *a, const void *b)
{
  const row *p = a, *q = b;
  return (p->x > q->x) - (p->x < q->x);
}

static int by_value(const void *a, const void *b)
{
  double p = *(const double *)a, q = *(const double *)b;
  return (p > q) - (p < q);
}

static int same_key(const table *t, const row *a, const double *key)
{
  int k;
  for (k = 0; k < t->ngroup; k++)
    if (!(a->key[k] == key[k])) return 0;
  return 1;
}

/* GROUP "P0,v0" into t->group; 0 if too many or empty. */
static int parse_group(const char *group, table *t)
{
  char buf[256], *f[MAX_GROUP + 1];
  int k;
  snprintf(buf, sizeof buf, "%s", group);
  t->ngroup = split_csv(buf, f, MAX_GROUP + 1);
  if (t->ngroup > MAX_GROUP) return 0;
  for (k = 0; k < t->ngroup; k++) {
    if (!f[k][0]) return 0;
    snprintf(t->group[k], sizeof t->group[k], "%s", f[k]);
  }
  return 1;
}

/* The curves' series: one line per GROUP value and two marker series
** (mean - sem, mean + sem); returns the number of series. */
static int make_series(const table *t, afv_plot_series *s,
                       double (*x)[MAX_ROWS], double (*y)[MAX_CURVES][MAX_ROWS],
                       char (*label)[96])
{
  double keys[MAX_CURVES][MAX_GROUP];
  int nc = 0, ns = 0, j, k, m, used;
  for (k = 0; k < t->nrow; k++) {       /* the curves, in order of appearance */
    for (j = 0; j < nc && !same_key(t, &t->rows[k], keys[j]); j++) {}
    if (j == nc && nc < MAX_CURVES)
      memcpy(keys[nc++], t->rows[k].key, sizeof keys[0]);
  }
  for (j = 0; j < nc; j++) {
    for (k = 0, m = 0; k < t->nrow; k++)
      if (same_key(t, &t->rows[k], keys[j])) {
        x[j][m] = t->rows[k].x;
        y[0][j][m] = t->rows[k].mean;
        y[1][j][m] = t->rows[k].mean - t->rows[k].sem;
        y[2][j][m++] = t->rows[k].mean + t->rows[k].sem;
      }
    for (k = 0, used = 0; k < t->ngroup; k++)
      used += snprintf(label[j] + used, (size_t)(96 - used), "%s%s %g",
                       k ? ", " : "", t->group[k], keys[j][k]);
    for (k = 0; k < 3; k++) {
      memset(&s[ns], 0, sizeof s[ns]);
      s[ns].x = x[j]; s[ns].y = y[k][j]; s[ns].n = m;
      s[ns].color = colors[j]; s[ns].points = k > 0;
      s[ns++].label = k == 0 ? label[j] : NULL;
    }
  }
  return ns;
}

static int draw(int argc, char **argv)
{
  static table t;
  static double x[MAX_CURVES][MAX_ROWS], y[3][MAX_CURVES][MAX_ROWS];
  afv_plot_series s[3 * MAX_CURVES];
  char label[MAX_CURVES][96];
  const char *xcol = argv[2], *obs = argv[3];
  afv_plot pl;
  FILE *fp;
  int ns;
  if (!parse_group(argc == 8 ? argv[7] : "P0,v0", &t)) {
    fprintf(stderr, "model_plot: GROUP '%s': 1 to %d columns\n", argv[7],
            MAX_GROUP);
    return 2;
  }
  if (!read_rows(argv[1], xcol, obs, argv[4], 0, &t)) return 2;
  if (t.nrow == 0) {
    fprintf(stderr, "model_plot: %s: no row kept by %s\n", argv[1], argv[4]);
    return 2;
  }
  qsort(t.rows, (size_t)t.nrow, sizeof *t.rows, by_x);
  ns = make_series(&t, s, x, y, label);
  memset(&pl, 0, sizeof pl);
  pl.title = argv[6];
  pl.xlabel = xcol;
  pl.ylabel = obs;
  pl.logx = strcmp(xcol, "dt") == 0 || strcmp(xcol, "N") == 0;
  /* rates and diffusivities span decades between the phases */
  pl.logy = strcmp(obs, "D_eff") == 0 || strcmp(obs, "t1_rate") == 0;
  if (!(fp = fopen(argv[5], "w"))) {
    fprintf(stderr, "model_plot: %s: cannot write\n", argv[5]);
    return 2;
  }
  afv_svg_plot(fp, &pl, s, ns);
  return fclose(fp) == 0 ? 0 : 2;
}

/* --crossing: per N, the two curves on the v0 where both are in:
** `missing` with fewer than two such v0 while the design has two (runs
** not in), `not measured` when the design itself has fewer. */
static int crossing(char **argv)
{
  static table t;
  double lo = number(argv[4]), hi = number(argv[5]), ns[MAX_CURVES];
  int nn = 0, j, k;
  char group[160];
  snprintf(group, sizeof group, "N,%s", argv[3]);
  if (!parse_group(group, &t)
      || !read_rows(argv[1], "v0", argv[2], "all", 1, &t))
    return 2;
  qsort(t.rows, (size_t)t.nrow, sizeof *t.rows, by_x);
  for (k = 0; k < t.nrow; k++) {
    for (j = 0; j < nn && ns[j] != t.rows[k].key[0]; j++) {}
    if (j == nn && nn < MAX_CURVES) ns[nn++] = t.rows[k].key[0];
  }
  qsort(ns, (size_t)nn, sizeof *ns, by_value);
  printf("N,v0_cross,points\n");
  for (j = 0; j < nn; j++) {
    double v[MAX_ROWS], a[MAX_ROWS], b[MAX_ROWS], xc;
    int m = 0, designed = 0, i;
    for (k = 0; k < t.nrow; k++)       /* rows with curve LO, then HI's */
      if (t.rows[k].key[0] == ns[j] && t.rows[k].key[1] == lo)
        for (i = 0; i < t.nrow; i++)
          if (t.rows[i].key[0] == ns[j] && t.rows[i].key[1] == hi
              && t.rows[i].x == t.rows[k].x) {
            designed++;
            if (isfinite(t.rows[k].mean) && isfinite(t.rows[i].mean)) {
              v[m] = t.rows[k].x; a[m] = t.rows[k].mean; b[m++] = t.rows[i].mean;
            }
            break;
          }
    if (designed < 2) printf("%g,not measured,%d\n", ns[j], m);
    else if (m < 2) printf("%g,missing,%d\n", ns[j], m);
    else if (afv_curves_cross(m, v, a, b, &xc)) printf("%g,%.4g,%d\n", ns[j], xc, m);
    else printf("%g,none,%d\n", ns[j], m);
  }
  return 0;
}

int main(int argc, char **argv)
{
  if (argc == 7 && strcmp(argv[1], "--crossing") == 0) return crossing(argv + 1);
  if (argc != 7 && argc != 8) {
    fprintf(stderr, "usage: tools/model_plot TABLE.CSV XCOL OBS FILTER "
                    "OUT.SVG TITLE [GROUP]  (FILTER: all, KEY=X or KEY!=X;\n"
                    "GROUP: the columns naming a curve, default P0,v0)\n"
                    "       tools/model_plot --crossing TABLE.CSV OBS CURVE "
                    "LO HI\n");
    return 2;
  }
  return draw(argc, argv);
}
