/*
** examples/analysis.c -- a custom analysis of an afv run in C, against the
** installed library: for every frame of a trajectory, the cluster's radius
** of gyration, the mean shape index q = P / sqrt(A) of the cells and the
** largest cluster's share N_GC / N, as CSV on standard output.
**
**   cc -std=c99 analysis.c $(pkg-config --cflags --libs afv) -o analysis
**   ./analysis RUN/trajectory.dat [P0] > spreading.csv
**
** P0 (default afv's 4.8) only enters the energy, not these shapes; give
** the run's other parameters the same way if you add energies.
*/
#include <afv.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Radius of gyration of the n centres r (interleaved). */
static double gyration_radius(int n, const double *r)
{
  double cx = 0, cy = 0, s = 0;
  int i;
  for (i = 0; i < n; i++) cx += r[2*i], cy += r[2*i+1];
  cx /= n, cy /= n;
  for (i = 0; i < n; i++)
    s += (r[2*i] - cx) * (r[2*i] - cx) + (r[2*i+1] - cy) * (r[2*i+1] - cy);
  return sqrt(s / n);
}

/* Mean of P_i / sqrt(A_i) over the cells of the geometry g. */
static double mean_shape_index(const afv_geom *g)
{
  const double *area = afv_geom_area(g), *perim = afv_geom_perim(g);
  double s = 0;
  int i, n = afv_geom_n(g);
  for (i = 0; i < n; i++) s += perim[i] / sqrt(area[i]);
  return s / n;
}

int main(int argc, char **argv)
{
  afv_traj tr = {0};
  afv_params p;
  afv_geom *g = afv_geom_new();
  double order[AFV_ORDER_COUNT];
  char err[512];
  int k, st;
  if (argc < 2 || argc > 3) {
    fprintf(stderr, "usage: analysis TRAJECTORY [P0]\n");
    return 2;
  }
  afv_params_default(&p);
  if (argc == 3) p.P0 = atof(argv[2]);
  if (!g) return 1;
  if ((st = afv_traj_read(argv[1], &tr, err, sizeof err)) != AFV_OK) {
    fprintf(stderr, "analysis: %s\n", err);
    return 2;
  }
  printf("time,gyration_radius,shape_index,ngc_frac\n");
  for (k = 0; k < tr.nframes; k++) {
    const double *r = tr.r + (size_t)k * 2 * tr.n;
    if ((st = afv_geometry(g, tr.n, r, &p, &tr.box)) != AFV_OK ||
        (st = afv_order_parameters(g, r, p.l, &tr.box, order, NULL))) {
      fprintf(stderr, "analysis: frame %d: %s\n", k, afv_strerror(st));
      return 1;
    }
    printf("%g,%.6f,%.6f,%.6f\n", tr.t[k], gyration_radius(tr.n, r),
           mean_shape_index(g), order[AFV_ORDER_GIANT]);
  }
  afv_traj_free(&tr);
  afv_geom_delete(g);
  return 0;
}
