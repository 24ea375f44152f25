/*
** tools/lambda_plot.c -- one figure of the Lambda study (tools/lambda.sh,
** doc/reproduction/lambda.md): the three boundaries of the phase diagram
** on the (P0, v0) plane, from a table of afv collect.
**
**   tools/lambda_plot TABLE.CSV LAMBDA FIGURE.SVG
**
** TABLE.CSV is afv collect's table.csv of a sweep over P0 and v0.  The
** boundaries are drawn as afv paper draws its Fig. 7(a), by linear
** interpolation of the seed means between state points (afv_curve_cross) at
** afv collect's levels:
**   clustering  at each P0, the v0 where N_GC/N falls below 0.99
**   confluency  at each v0, the P0 where Omega falls below 0.5
**   dynamics    at each P0, the v0 where msd_beta rises above 0.5
** and the state points that afv collect labels clustered or glassy are
** marked (a clustered region need not end at a crossing along v0: at
** Lambda = 0 the tissue comes apart at v0 = 0 for large P0).  The
** dynamics leave out v0 = 0: there no cell moves after the relaxation
** (MSD_rel ~ 1e-19 l^2 at Lambda 0), msd_beta is the slope of round-off
** and its label means nothing (afv collect's D_eff label is undefined
** there for the same reason).  The
** boundary points are also printed on stdout as CSV (boundary,P0,v0).
** The figure is written atomically.  Exit status 2 on a malformed table.
*/
#include "afv.h"
#include "afv_tool.h"   /* afv_svg_plot */
#include "cmd/fits.h"   /* afv_curve_cross */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_VALUES 64          /* distinct P0 or v0 values */
#define MAX_FIELDS 64
#define LINE_LEN 4096

/* afv collect's levels (collect.c): clustered if N_GC/N >= 0.99,
** epithelial if Omega >= 0.5, glassy if msd_beta < 0.5. */
#define CLUSTER_LEVEL 0.99
#define CONFLUENCY_LEVEL 0.5
#define BETA_GLASS_LEVEL 0.5

enum { Q_NGC, Q_OMEGA, Q_BETA, N_Q };
static const char *q_column[N_Q] = {"ngc_frac_mean", "omega_mean",
                                    "msd_beta_mean"};

typedef struct plane {
  int np, nv;
  double p0[MAX_VALUES], v0[MAX_VALUES];
  double q[N_Q][MAX_VALUES][MAX_VALUES];  /* [q][ip][iv]; NAN: no row */
  int glassy[MAX_VALUES][MAX_VALUES];     /* afv collect's dynamic_phase */
  int clustered[MAX_VALUES][MAX_VALUES];  /* afv collect's cluster_phase */
} plane;

/* Splits line at commas in place (empty fields kept); the field count. */
static int split(char *line, char **field)
{
  int n = 0;
  char *p = line;
  line[strcspn(line, "\r\n")] = '\0';
  for (;;) {
    if (n == MAX_FIELDS) return -1;
    field[n++] = p;
    p = strchr(p, ',');
    if (!p) return n;
    *p++ = '\0';
  }
}

/* The index of value x in the sorted list vals (added if new). */
static int value_index(double *vals, int *n, double x)
{
  int i, k;
  for (i = 0; i < *n && vals[i] < x; i++) continue;
  if (i < *n && vals[i] == x) return i;
  if (*n == MAX_VALUES) return -1;
  for (k = *n; k > i; k--) vals[k] = vals[k - 1];
  vals[i] = x;
  (*n)++;
  return i;
}

static int column(char **field, int n, const char *name)
{
  int k;
  for (k = 0; k < n; k++)
    if (strcmp(field[k], name) == 0) return k;
  return -1;
}

static int number(const char *s, double *x)
{
  char *end;
  *x = strtod(s, &end);
  return end != s && *end == '\0';
}

/* Two passes: the P0 and v0 values (sorted), then the means. */
static int read_table(const char *path, plane *P)
{
  char line[LINE_LEN], *field[MAX_FIELDS];
  int col[N_Q] = {-1, -1, -1}, cp = -1, cv = -1, cd = -1, cc = -1, nf = 0,
      pass, lineno, k;
  FILE *fp = fopen(path, "r");
  if (!fp) {
    fprintf(stderr, "lambda_plot: %s: cannot open\n", path);
    return 0;
  }
  memset(P, 0, sizeof *P);
  for (pass = 0; pass < 2; pass++) {
    rewind(fp);
    lineno = 0;
    while (fgets(line, sizeof line, fp)) {
      double p0, v0, x;
      int n = split(line, field), ip, iv;
      if (++lineno == 1) {
        nf = n;
        cp = column(field, n, "P0");
        cv = column(field, n, "v0");
        cd = column(field, n, "dynamic_phase");
        cc = column(field, n, "cluster_phase");
        for (k = 0; k < N_Q; k++) col[k] = column(field, n, q_column[k]);
        if (cp < 0 || cv < 0 || cd < 0 || cc < 0 || col[0] < 0 || col[1] < 0
            || col[2] < 0) {
          fprintf(stderr, "lambda_plot: %s:1: not afv collect's table of "
                  "a (P0, v0) sweep\n", path);
          fclose(fp);
          return 0;
        }
        continue;
      }
      if (n != nf || !number(field[cp], &p0) || !number(field[cv], &v0)) {
        fprintf(stderr, "lambda_plot: %s:%d: not a row of %d fields with "
                "numbers P0 and v0\n", path, lineno, nf);
        fclose(fp);
        return 0;
      }
      ip = value_index(P->p0, &P->np, p0);
      iv = value_index(P->v0, &P->nv, v0);
      if (ip < 0 || iv < 0) {
        fprintf(stderr, "lambda_plot: %s:%d: more than %d values of P0 or "
                "v0\n", path, lineno, MAX_VALUES);
        fclose(fp);
        return 0;
      }
      if (pass == 0) continue;
      for (k = 0; k < N_Q; k++) {
        if (!number(field[col[k]], &x)) {
          fprintf(stderr, "lambda_plot: %s:%d: %s is not a number\n", path,
                  lineno, q_column[k]);
          fclose(fp);
          return 0;
        }
        P->q[k][ip][iv] = x;
      }
      P->glassy[ip][iv] = strcmp(field[cd], "glassy") == 0;
      P->clustered[ip][iv] = strcmp(field[cc], "clustered") == 0;
    }
    if (pass == 0) {       /* every state point NAN until its row is read */
      int i, j;
      for (k = 0; k < N_Q; k++)
        for (i = 0; i < MAX_VALUES; i++)
          for (j = 0; j < MAX_VALUES; j++) P->q[k][i][j] = NAN;
    }
  }
  fclose(fp);
  return 1;
}

/* Where quantity q crosses level: along v0 at each P0 (along_p0 = 0) or
** along P0 at each v0; sign -1 for a quantity that rises through the
** level.  Returns the number of points (bx = P0, by = v0). */
static int boundary(const plane *P, int q, double level, int sign,
                    int along_p0, double *bx, double *by)
{
  double line[MAX_VALUES], xc;
  int i, j, n = along_p0 ? P->nv : P->np, m = along_p0 ? P->np : P->nv,
      nb = 0;
  for (i = 0; i < n; i++) {
    for (j = 0; j < m; j++)
      line[j] = sign * (along_p0 ? P->q[q][j][i] : P->q[q][i][j]);
    if (q == Q_BETA && !along_p0 && P->v0[0] == 0)
      line[0] = NAN;                     /* v0 = 0: nothing moves */
    if (afv_curve_cross(m, along_p0 ? P->p0 : P->v0, line, sign * level,
                     &xc)) {
      bx[nb] = along_p0 ? xc : P->p0[i];
      by[nb] = along_p0 ? P->v0[i] : xc;
      nb++;
    }
  }
  return nb;
}

int main(int argc, char **argv)
{
  static plane P;
  static const char *name[3] = {"clustering", "confluency", "dynamics"};
  static const char *lab[3] = {"clustering: N_GC/N = 0.99",
                               "confluency: Omega = 0.5",
                               "dynamics: msd_beta = 0.5 (v0 > 0)"};
  static const char *col[3] = {"#d62728", "#1f77b4", "#9467bd"};
  double bx[3][MAX_VALUES], by[3][MAX_VALUES];
  double gx[MAX_VALUES * MAX_VALUES], gy[MAX_VALUES * MAX_VALUES];
  double cx[MAX_VALUES * MAX_VALUES], cy[MAX_VALUES * MAX_VALUES];
  char title[160], tmp[4096];
  char label[3][96];
  afv_plot pl;
  afv_plot_series s[6];
  double ex[2], ey[2];
  int nb[3], ng = 0, nc = 0, i, j, k;
  FILE *fp;
  if (argc != 4) {
    fprintf(stderr, "usage: tools/lambda_plot TABLE.CSV LAMBDA FIGURE.SVG\n");
    return 2;
  }
  if (!read_table(argv[1], &P)) return 2;
  nb[0] = boundary(&P, Q_NGC, CLUSTER_LEVEL, 1, 0, bx[0], by[0]);
  nb[1] = boundary(&P, Q_OMEGA, CONFLUENCY_LEVEL, 1, 1, bx[1], by[1]);
  nb[2] = boundary(&P, Q_BETA, BETA_GLASS_LEVEL, -1, 0, bx[2], by[2]);
  for (i = 0; i < P.np; i++)
    for (j = 0; j < P.nv; j++)
      if (P.glassy[i][j] && P.v0[j] > 0) {
        gx[ng] = P.p0[i];
        gy[ng] = P.v0[j];
        ng++;
      }
  for (i = 0; i < P.np; i++)
    for (j = 0; j < P.nv; j++)
      if (P.clustered[i][j]) {
        cx[nc] = P.p0[i];
        cy[nc] = P.v0[j];
        nc++;
      }

  printf("boundary,P0,v0\n");
  for (k = 0; k < 3; k++)
    for (i = 0; i < nb[k]; i++)
      printf("%s,%.6g,%.6g\n", name[k], bx[k][i], by[k][i]);

  memset(s, 0, sizeof s);
  for (k = 0; k < 3; k++) {
    s[k].x = bx[k]; s[k].y = by[k]; s[k].n = nb[k];
    snprintf(label[k], sizeof label[k], "%s%s", lab[k],
             nb[k] ? "" : ": no crossing");
    s[k].label = label[k]; s[k].color = col[k]; s[k].points = nb[k] < 2;
  }
  s[3].x = gx; s[3].y = gy; s[3].n = ng; s[3].points = 1;
  s[3].label = "glassy (v0 > 0)"; s[3].color = "#9467bd";
  s[4].x = cx; s[4].y = cy; s[4].n = nc; s[4].points = 1;
  s[4].label = "clustered"; s[4].color = "#f4a6a6";
  /* the grid's corners, not drawn: the axes span the whole grid */
  ex[0] = P.np ? P.p0[0] : 0; ex[1] = P.np ? P.p0[P.np - 1] : 1;
  ey[0] = ey[1] = P.nv ? P.v0[0] : 0;
  s[5].x = ex; s[5].y = ey; s[5].n = 2; s[5].points = 1;
  s[5].color = "none";
  memset(&pl, 0, sizeof pl);
  snprintf(title, sizeof title, "Lambda = %s: the three boundaries "
           "(N = 400, t = 300, Euler dt = 0.01)", argv[2]);
  pl.title = title;
  pl.xlabel = "P0 (l)";
  pl.ylabel = "v0 (l/time)";
  pl.ymin = P.nv ? P.v0[0] : 0;
  pl.ymax = P.nv ? P.v0[P.nv - 1] : 1;
  snprintf(tmp, sizeof tmp, "%s.tmp", argv[3]);
  if (!(fp = fopen(tmp, "w"))) {
    fprintf(stderr, "lambda_plot: %s: cannot write\n", tmp);
    return 2;
  }
  k = afv_svg_plot(fp, &pl, s, 6);
  if (fclose(fp) != 0 || k != AFV_OK || rename(tmp, argv[3]) != 0) {
    fprintf(stderr, "lambda_plot: %s: cannot write\n", argv[3]);
    remove(tmp);
    return 2;
  }
  return 0;
}
