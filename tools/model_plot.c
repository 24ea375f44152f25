/*
** tools/model_plot.c -- the figures of the model study
** (tools/model_sweeps.sh, doc/reproduction/model/README.md).
**
**   tools/model_plot TABLE.CSV XCOL OBS FILTER OUT.SVG TITLE
**
** TABLE.CSV is tools/model_table.sh's dt_table.csv or cap_table.csv: a
** header naming the columns, among them P0, v0, XCOL, OBS_mean and OBS_sem.
** One curve per state point (P0, v0) that FILTER keeps: OBS's seed mean
** against XCOL (log axis), with the seed standard error drawn as small
** markers at mean - sem and mean + sem (D_eff and t1_rate on a log
** axis).  FILTER is "v0=X" (rows with
** v0 == X), "v0!=X" or "all".  Exit status 2 on a malformed file or
** when no row is kept.
*/
#include "afv.h"
#include "afv_tool.h"   /* afv_svg_plot */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROWS   512
#define MAX_COLS   64
#define MAX_CURVES 12

typedef struct row { double P0, v0, x, mean, sem; } row;

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

static int keep(const char *filter, double v0)
{
  if (strcmp(filter, "all") == 0) return 1;
  if (strncmp(filter, "v0!=", 4) == 0) return v0 != atof(filter + 4);
  if (strncmp(filter, "v0=", 3) == 0) return v0 == atof(filter + 3);
  return -1;
}

static int read_rows(const char *path, const char *xcol, const char *obs,
                     const char *filter, row *rows, int *n)
{
  char line[4096], header[4096], name[128], *f[MAX_COLS], *h[MAX_COLS];
  int nh, c[5], k, lineno = 1;
  FILE *fp = fopen(path, "r");
  if (!fp || !fgets(header, sizeof header, fp)) {
    fprintf(stderr, "model_plot: %s: cannot read\n", path);
    if (fp) fclose(fp);
    return 0;
  }
  nh = split_csv(header, h, MAX_COLS);
  c[0] = column(h, nh, "P0");
  c[1] = column(h, nh, "v0");
  c[2] = column(h, nh, xcol);
  snprintf(name, sizeof name, "%s_mean", obs);
  c[3] = column(h, nh, name);
  snprintf(name, sizeof name, "%s_sem", obs);
  c[4] = column(h, nh, name);
  for (k = 0; k < 5; k++)
    if (c[k] < 0) {
      fprintf(stderr, "model_plot: %s: no column for %s\n", path,
              k == 2 ? xcol : k < 2 ? (k ? "v0" : "P0") : obs);
      fclose(fp);
      return 0;
    }
  *n = 0;
  while (fgets(line, sizeof line, fp)) {
    row r;
    lineno++;
    if (split_csv(line, f, MAX_COLS) != nh || *n >= MAX_ROWS) {
      fprintf(stderr, "model_plot: %s:%d: not a row of %d fields\n", path,
              lineno, nh);
      fclose(fp);
      return 0;
    }
    r.P0 = atof(f[c[0]]); r.v0 = atof(f[c[1]]); r.x = atof(f[c[2]]);
    r.mean = atof(f[c[3]]);
    r.sem = f[c[4]][0] ? atof(f[c[4]]) : 0;   /* one seed: no error */
    if (keep(filter, r.v0) == 1) rows[(*n)++] = r;
  }
  fclose(fp);
  return 1;
}

static int by_x(const void *a, const void *b)
{
  const row *p = a, *q = b;
  return (p->x > q->x) - (p->x < q->x);
}

int main(int argc, char **argv)
{
  static row rows[MAX_ROWS];
  static double x[MAX_CURVES][MAX_ROWS], y[3][MAX_CURVES][MAX_ROWS];
  afv_plot_series s[3 * MAX_CURVES];
  char label[MAX_CURVES][64];
  double P0s[MAX_CURVES], v0s[MAX_CURVES];
  int n, nc = 0, ns = 0, k, j;
  afv_plot pl;
  FILE *fp;
  if (argc != 7 || keep(argv[4], 0) < 0) {
    fprintf(stderr, "usage: tools/model_plot TABLE.CSV XCOL OBS FILTER "
                    "OUT.SVG TITLE  (FILTER: all, v0=X or v0!=X)\n");
    return 2;
  }
  if (!read_rows(argv[1], argv[2], argv[3], argv[4], rows, &n)) return 2;
  if (n == 0) {
    fprintf(stderr, "model_plot: %s: no row kept by %s\n", argv[1], argv[4]);
    return 2;
  }
  qsort(rows, (size_t)n, sizeof *rows, by_x);
  for (k = 0; k < n; k++) {           /* the curves, in order of appearance */
    for (j = 0; j < nc; j++)
      if (P0s[j] == rows[k].P0 && v0s[j] == rows[k].v0) break;
    if (j == nc && nc < MAX_CURVES) { P0s[nc] = rows[k].P0; v0s[nc++] = rows[k].v0; }
  }
  for (j = 0; j < nc; j++) {
    int m = 0;
    for (k = 0; k < n; k++)
      if (rows[k].P0 == P0s[j] && rows[k].v0 == v0s[j]) {
        x[j][m] = rows[k].x;
        y[0][j][m] = rows[k].mean;
        y[1][j][m] = rows[k].mean - rows[k].sem;
        y[2][j][m++] = rows[k].mean + rows[k].sem;
      }
    snprintf(label[j], sizeof label[j], "P0 %g, v0 %g", P0s[j], v0s[j]);
    for (k = 0; k < 3; k++) {
      memset(&s[ns], 0, sizeof s[ns]);
      s[ns].x = x[j]; s[ns].y = y[k][j]; s[ns].n = m;
      s[ns].color = colors[j]; s[ns].points = k > 0;
      s[ns++].label = k == 0 ? label[j] : NULL;
    }
  }
  memset(&pl, 0, sizeof pl);
  pl.title = argv[6];
  pl.xlabel = argv[2];
  pl.ylabel = argv[3];
  pl.logx = 1;
  /* rates and diffusivities span decades between the phases */
  pl.logy = strcmp(argv[3], "D_eff") == 0 || strcmp(argv[3], "t1_rate") == 0;
  if (!(fp = fopen(argv[5], "w"))) {
    fprintf(stderr, "model_plot: %s: cannot write\n", argv[5]);
    return 2;
  }
  afv_svg_plot(fp, &pl, s, ns);
  return fclose(fp) == 0 ? 0 : 2;
}
