/*
** tools/convergence_plot.c -- the figures of the detachment convergence
** study (tools/convergence.sh, doc/reproduction/convergence.md).
**
**   tools/convergence_plot CONVERGENCE.CSV DIR
**
** Reads convergence.csv (scheme,setting,P0,v0,n_seeds, then mean and seed
** standard error of ngc_frac, n_clusters and omega) and writes into DIR one
** SVG per scheme that has rows and per observable: the observable against
** the setting (dt for euler and euler_cap0.45, max_move for the substeps
** of afv 0.2.0, in the committed study; log axis), one line per state
** point (P0, v0), the seed standard error drawn as the two dotted lines
** mean +- sem.  Exit status 2 on a malformed file.
*/
#include "afv.h"
#include "afv_tool.h"   /* afv_svg_plot */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROWS 512
#define N_OBS 3

typedef struct row {
  char scheme[32];
  double setting, P0, v0, mean[N_OBS], sem[N_OBS];
} row;

static const char *obs_name[N_OBS] = {"ngc_frac", "n_clusters", "omega"};
static const char *obs_label[N_OBS] = {"N_GC/N", "number of clusters",
                                       "Omega"};
static const char *colors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                               "#9467bd", "#8c564b"};

static int read_rows(const char *path, row *rows, int *n)
{
  char line[1024];
  FILE *fp = fopen(path, "r");
  int lineno = 0;
  if (!fp) {
    fprintf(stderr, "convergence_plot: %s: cannot open\n", path);
    return 0;
  }
  *n = 0;
  while (fgets(line, sizeof line, fp)) {
    row *r = &rows[*n];
    int seeds, k;
    if (++lineno == 1) continue;                  /* the header */
    k = sscanf(line, "%31[^,],%lf,%lf,%lf,%d,%lf,%lf,%lf,%lf,%lf,%lf",
               r->scheme, &r->setting, &r->P0, &r->v0, &seeds, &r->mean[0],
               &r->sem[0], &r->mean[1], &r->sem[1], &r->mean[2], &r->sem[2]);
    if (k != 11 || *n + 1 >= MAX_ROWS) {
      fprintf(stderr, "convergence_plot: %s:%d: not a row of 11 fields\n",
              path, lineno);
      fclose(fp);
      return 0;
    }
    (*n)++;
  }
  fclose(fp);
  return 1;
}

/* 1 if some row is of scheme. */
static int has_scheme(const row *rows, int n, const char *scheme)
{
  int k;
  for (k = 0; k < n; k++)
    if (strcmp(rows[k].scheme, scheme) == 0) return 1;
  return 0;
}

static int by_setting(const void *a, const void *b)
{
  const row *x = a, *y = b;
  return (x->setting > y->setting) - (x->setting < y->setting);
}

/* One figure: observable o of scheme against its setting. */
static int plot_one(const row *rows, int n, const char *scheme, int o,
                    const char *dir)
{
  static const double P0s[2] = {4, 8}, v0s[3] = {1, 1.85, 2.6};
  afv_plot_series s[18];
  double x[6][8], y[6][8], lo[6][8], hi[6][8];
  char label[6][64], path[1024], title[160];
  int ns = 0, p, v, k, m;
  afv_plot pl;
  FILE *fp;
  for (p = 0; p < 2; p++)
    for (v = 0; v < 3; v++) {
      int c = 3 * p + v;
      row pick[8];
      for (m = 0, k = 0; k < n && m < 8; k++)
        if (strcmp(rows[k].scheme, scheme) == 0 && rows[k].P0 == P0s[p]
            && rows[k].v0 == v0s[v])
          pick[m++] = rows[k];
      qsort(pick, (size_t)m, sizeof *pick, by_setting);
      for (k = 0; k < m; k++) {
        x[c][k] = pick[k].setting;
        y[c][k] = pick[k].mean[o];
        lo[c][k] = pick[k].mean[o] - pick[k].sem[o];
        hi[c][k] = pick[k].mean[o] + pick[k].sem[o];
      }
      snprintf(label[c], sizeof label[c], "P0 %g, v0 %g", P0s[p], v0s[v]);
      memset(&s[ns], 0, 3 * sizeof s[0]);
      s[ns].x = x[c]; s[ns].y = y[c]; s[ns].n = m;
      s[ns].label = label[c]; s[ns].color = colors[c];
      s[ns + 1].x = x[c]; s[ns + 1].y = lo[c]; s[ns + 1].n = m;
      s[ns + 1].color = colors[c]; s[ns + 1].points = 1;
      s[ns + 2].x = x[c]; s[ns + 2].y = hi[c]; s[ns + 2].n = m;
      s[ns + 2].color = colors[c]; s[ns + 2].points = 1;
      if (m > 0) ns += 3;
    }
  if (ns == 0) return 1;            /* a scheme not in the file: no figure */
  memset(&pl, 0, sizeof pl);
  snprintf(title, sizeof title, "%s, %s (N = 400; markers: mean +- sem)",
           obs_label[o], scheme);
  pl.title = title;
  pl.xlabel = strcmp(scheme, "substeps") == 0 ? "max_move (l), dt = 0.01"
                                              : "dt";
  pl.ylabel = obs_label[o];
  pl.logx = 1;
  pl.logy = o == 1;
  snprintf(path, sizeof path, "%s/%s_%s.svg", dir, scheme, obs_name[o]);
  if (!(fp = fopen(path, "w"))) {
    fprintf(stderr, "convergence_plot: %s: cannot write\n", path);
    return 0;
  }
  afv_svg_plot(fp, &pl, s, ns);
  return fclose(fp) == 0;
}

int main(int argc, char **argv)
{
  static row rows[MAX_ROWS];
  static const char *schemes[3] = {"euler", "euler_cap0.45", "substeps"};
  int n, k, o;
  if (argc != 3) {
    fprintf(stderr, "usage: tools/convergence_plot CONVERGENCE.CSV DIR\n");
    return 2;
  }
  if (!read_rows(argv[1], rows, &n)) return 2;
  for (k = 0; k < 3; k++)
    for (o = 0; o < N_OBS && has_scheme(rows, n, schemes[k]); o++)
      if (!plot_one(rows, n, schemes[k], o, argv[2])) return 2;
  return 0;
}
