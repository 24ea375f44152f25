/*
** paper_compare.c -- afv paper --compare DIR_A DIR_B OUT: two records of
** the (P0, v0) grid (e.g. the exact model's, doc/reproduction/paper, and
** the capped model's, doc/reproduction/model/cap) drawn side by side on
** one colour scale, with afv paper's maps (paper.c: map_of) and their
** contours and dashed curves.  It only reads the records.
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir */
#include "paper.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

/* ---- two records side by side (afv paper --compare) ---------------------- */
/* The maps afv paper draws of the plane (Fig. 2(b), 4(b), 5(d)): the
** quantity, its contour, the file. */
typedef struct compared_map {
  const char *file, *what, *zlabel;
  int q, logz;
  double level;
} compared_map;

static const compared_map compared[] = {
  {"compare_fig2b_cluster_phase.svg", "N_GC/N, contour 0.99, dashed: v_s fit",
   "N_GC/N", Q_NGC, 0, CLUSTER_LEVEL},
  {"compare_fig4b_omega_map.svg", "Omega, contour 0.5, dashed: P0* 5.73",
   "Omega", Q_OMEGA, 0, CONFLUENCY_LEVEL},
  {"compare_fig5d_dynamic_phase.svg", "D_eff, contour 1e-8", "D_eff", Q_DEFF,
   1, DEFF_GLASS_LEVEL},
  {"compare_fig5d_dynamic_phase_msd_beta.svg", "msd_beta, contour 0.5",
   "msd_beta", Q_BETA, 0, BETA_GLASS_LEVEL},
};
#define N_COMPARED ((int)(sizeof compared / sizeof compared[0]))

/* A record to compare: its plane (DIR/grid_table.csv on the design of
** both records' tables, so that a grid still running shows the points not
** in), its name (the integration that ends DIR/claims.csv's first note
** from "dt" on, e.g. "dt 0.01, cap 0.45"; else DIR), the dashed curves of
** its maps. */
typedef struct record {
  plane P;
  char name[320];
  double cx[CURVE_POINTS], cy[CURVE_POINTS];   /* the v_s fit */
  int cn;
  double mx[2], my[2];                         /* the mean field's P0* */
} record;

static int record_read(const char *dir, const char *other, record *R)
{
  char path[PATH_LEN], also[PATH_LEN], how[320];
  double bp[MAX_VALUES], bv[MAX_VALUES];
  const char *dt;
  afv_boundary fit;
  int fitted;
  snprintf(path, sizeof path, "%s/grid_table.csv", dir);
  snprintf(also, sizeof also, "%s/grid_table.csv", other);
  if (!plane_read_table_over(path, also, &R->P)) return 0;
  snprintf(path, sizeof path, "%s/claims.csv", dir);
  if (!claims_integration(path, how, sizeof how)) snprintf(how, sizeof how,
                                                           "%s", dir);
  snprintf(R->name, sizeof R->name, "%s", (dt = strstr(how, "dt ")) ? dt : how);
  dispersal_boundary(&R->P, bp, bv, &fit, &fitted);
  R->cn = fitted ? boundary_curve(&R->P, &fit, R->cx, R->cy) : 0;
  R->mx[0] = R->mx[1] = afv_meanfield_p0(0.2, acos(-1.0), 1);
  R->my[0] = R->P.v0[0];
  R->my[1] = R->P.v0[R->P.nv - 1];
  return 1;
}

/* The state points of P with a run. */
static int points_in(const plane *P)
{
  int ip, iv, in = 0;
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++) in += seeds_at(P, ip, iv) > 0;
  return in;
}

/* The two records' maps of one quantity side by side, on one colour scale;
** each title counts the state points with a value (grey: none). */
static int compare_figure(const char *out, const record *R,
                          const compared_map *c)
{
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN], title[2][480];
  afv_map m[2];
  FILE *fp;
  int k;
  for (k = 0; k < 2; k++) {
    const plane *P = &R[k].P;
    int ngc = c->q == Q_NGC, omega = c->q == Q_OMEGA;
    snprintf(title[k], sizeof title[k], "%s: %s (%d of %d points)",
             R[k].name, c->what, points_in(P), P->np * P->nv);
    map_of(P, c->q, title[k], c->zlabel, c->logz, c->level,
           ngc ? R[k].cx : omega ? R[k].mx : NULL,
           ngc ? R[k].cy : omega ? R[k].my : NULL,
           ngc ? R[k].cn : omega ? 2 : 0, &m[k]);
  }
  if (!(fp = figure_open(out, c->file, path, tmp))) return 0;
  afv_svg_maps(fp, m, 2);
  return figure_close(fp, tmp, path);
}

/* Fig. 7(a) of both records in one plot: each boundary of the first
** (solid colours) and of the second (their light tints), the second's
** points marked; a boundary with one point is a marker. */
static int compare_summary(const char *out, const record *R)
{
  static const char *col[2][N_BOUNDARIES] = {
    {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"},
    {"#ff9896", "#aec7e8", "#98df8a", "#c5b0d5"}};
  static boundaries B[2];
  char path[FIGURE_PATH_LEN], tmp[FIGURE_TMP_LEN], lab[2][N_BOUNDARIES][400];
  char title[160];
  afv_plot_series s[2 * N_BOUNDARIES];
  afv_plot pl;
  FILE *fp;
  int k, j, ns = 0;
  memset(s, 0, sizeof s);
  for (k = 0; k < 2; k++) {
    phase_boundaries(&R[k].P, &B[k]);
    for (j = 0; j < N_BOUNDARIES; j++) {
      snprintf(lab[k][j], sizeof lab[k][j], "%s: %s", R[k].name,
               boundary_label[j]);
      s[ns].x = B[k].bx[j]; s[ns].y = B[k].by[j]; s[ns].n = B[k].nb[j];
      s[ns].label = lab[k][j]; s[ns].color = col[k][j];
      s[ns].points = B[k].nb[j] < 2 ? AFV_PLOT_MARKS : AFV_PLOT_LINE_MARKS;
      ns++;
    }
  }
  snprintf(title, sizeof title, "Fig. 7(a)'s boundaries: %d of %d points "
           "(solid), %d of %d (light)", points_in(&R[0].P),
           R[0].P.np * R[0].P.nv, points_in(&R[1].P), R[1].P.np * R[1].P.nv);
  memset(&pl, 0, sizeof pl);
  pl.title = title;
  pl.xlabel = "P0 (l)";
  pl.ylabel = "v0 (l/time)";
  pl.ymin = R[0].P.v0[0];
  pl.ymax = R[0].P.v0[R[0].P.nv - 1];
  if (!(fp = figure_open(out, "compare_fig7a_summary_phase.svg", path, tmp)))
    return 0;
  afv_svg_plot(fp, &pl, s, ns);
  return figure_close(fp, tmp, path);
}

/* afv paper --compare DIR_A DIR_B OUT. */
int paper_compare(const char *a, const char *b, const char *out)
{
  static record R[2];
  char path[PATH_LEN];
  int k, ok = 1;
  memset(R, 0, sizeof R);
  ok = record_read(a, b, &R[0]) && record_read(b, a, &R[1]);
  snprintf(path, sizeof path, "%s/figures", out);
  if (ok && (mkdir(out, 0777) != 0 && errno != EEXIST)) path[strlen(out)] = 0;
  if (ok && mkdir(path, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv paper: %s: %s\n", path, strerror(errno));
    ok = 0;
  }
  for (k = 0; ok && k < N_COMPARED; k++) ok = compare_figure(out, R, &compared[k]);
  ok = ok && compare_summary(out, R);
  if (ok) printf("afv paper: %s/figures/compare_*.svg (%s beside %s)\n", out,
                 R[0].name, R[1].name);
  plane_free(&R[0].P);
  plane_free(&R[1].P);
  return ok ? 0 : EXIT_BAD_INPUT;
}
