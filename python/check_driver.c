/*
** python/check_driver.c -- the C side of python/test_afv.py's bit-for-bit
** checks: the same scenario as the test's, through afv.h directly, every
** number printed in %.17g ("NAME INDEX VALUE" lines; %.17g reads back to
** the same double), and the pictures written with afv_svg_write.
**
**   check_driver OUTDIR     (writes OUTDIR/open.svg and OUTDIR/sim.svg)
**
** Scenario (python/test_afv.py mirrors it call for call):
**   open:  37 cells of afv_init_lattice (spacing 1.1), P0 per cell 4.5 or
**          5.5 (a mixture: even cells 4.5), Lambda 0.3: afv_compute's
**          shapes, energy, forces; the order parameters; a picture.
**   sim:   40 cells of afv_init_cluster (seed 7, side 3.6) in a periodic
**          12 x 12 box, angles afv_init_angles(seed 7), dyn defaults with
**          seed 11; afv_relax(tol 1e-4, 3000 steps); v0 = 0.5 for 30
**          steps; v0 per cell (0.2 + 0.05 i) for 20 steps; P0 = 5.5 and
**          afv_sim_refresh, 20 steps; dt = 0.005, 20 steps;
**          positions, angles, forces, energy, time, steps, order
**          parameters; a picture.
*/
#include <afv.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void print_array(const char *name, const double *v, int count)
{
  int k;
  for (k = 0; k < count; k++) printf("%s %d %.17g\n", name, k, v[k]);
}

static void print_order(const char *prefix, const afv_geom *g,
                        const double *r, double l, const afv_box *b, int n)
{
  double values[AFV_ORDER_COUNT];
  int *label = malloc((size_t)n * sizeof *label), k;
  char name[64];
  if (!label || afv_order_parameters(g, r, l, b, values, label) != AFV_OK)
    exit(1);
  snprintf(name, sizeof name, "%s.order", prefix);
  print_array(name, values, AFV_ORDER_COUNT);
  for (k = 0; k < n; k++) printf("%s.label %d %d\n", prefix, k, label[k]);
  free(label);
}

static void save(const char *dir, const char *file, const afv_geom *g, int n,
                 const double *r, const double *theta, const afv_params *p,
                 const afv_box *b)
{
  char path[4096];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", dir, file);
  if (!(fp = fopen(path, "w")) || afv_svg_write(fp, g, n, r, theta, p, b)
      || fclose(fp))
    exit(1);
}

static void open_space(const char *dir)
{
  enum { N = 37 };
  double r[2 * N], f[2 * N], P0_i[N];
  afv_params p;
  afv_box box = {0, 0, 0};
  afv_geom *g = afv_geom_new();
  const int *contacts;
  int i;
  afv_params_default(&p);
  p.Lambda = 0.3;
  for (i = 0; i < N; i++) P0_i[i] = i % 2 ? 5.5 : 4.5;
  p.P0_i = P0_i;
  if (!g || afv_init_lattice(N, 1.1, &box, r)
      || afv_compute(g, N, r, &p, &box, f))
    exit(1);
  print_array("open.area", afv_geom_area(g), N);
  print_array("open.perimeter", afv_geom_perim(g), N);
  print_array("open.arc", afv_geom_arc(g), N);
  contacts = afv_geom_contacts(g);
  for (i = 0; i < N; i++) printf("open.contacts %d %d\n", i, contacts[i]);
  print_array("open.forces", f, 2 * N);
  printf("open.energy 0 %.17g\n", afv_geom_energy(g));
  print_order("open", g, r, p.l, &box, N);
  save(dir, "open.svg", g, N, r, NULL, &p, &box);
  afv_geom_delete(g);
}

static void run(afv_sim *s, int steps)
{
  while (steps-- > 0)
    if (afv_sim_step(s)) exit(1);
}

static void simulation(const char *dir)
{
  enum { N = 40 };
  double r[2 * N], theta[N], v0_i[N];
  afv_params p;
  afv_box box = {1, 12, 12};
  afv_dyn d;
  afv_relax_report rep;
  afv_sim *s = afv_sim_new();
  int i;
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.seed = 11;
  afv_init_cluster(N, 7, &box, 3.6, r);
  afv_init_angles(N, 7, theta);
  if (!s || afv_sim_init(s, N, r, theta, &p, &box, &d)
      || afv_relax(s, 1e-4, 3000, &rep, NULL, NULL))
    exit(1);
  printf("sim.relax 0 %ld\nsim.relax 1 %.17g\n", rep.iterations, rep.energy);
  afv_sim_dyn(s)->v0 = 0.5;
  run(s, 30);
  for (i = 0; i < N; i++) v0_i[i] = 0.2 + 0.05 * i;
  afv_sim_dyn(s)->v0_i = v0_i;
  run(s, 20);
  afv_sim_params(s)->P0 = 5.5;
  if (afv_sim_refresh(s)) exit(1);
  run(s, 20);
  afv_sim_dyn(s)->dt = 0.005;
  run(s, 20);
  print_array("sim.positions", afv_sim_positions(s), 2 * N);
  print_array("sim.angles", afv_sim_angles(s), N);
  print_array("sim.forces", afv_sim_forces(s), 2 * N);
  printf("sim.energy 0 %.17g\n", afv_geom_energy(afv_sim_geom(s)));
  printf("sim.time 0 %.17g\nsim.steps 0 %lld\n", afv_sim_time(s),
         afv_sim_steps(s));
  print_order("sim", afv_sim_geom(s), afv_sim_positions(s), p.l, &box, N);
  save(dir, "sim.svg", afv_sim_geom(s), N, afv_sim_positions(s),
       afv_sim_angles(s), afv_sim_params(s), &box);
  afv_sim_delete(s);
}

int main(int argc, char **argv)
{
  if (argc != 2) return fprintf(stderr, "usage: check_driver OUTDIR\n"), 2;
  open_space(argv[1]);
  simulation(argv[1]);
  return 0;
}
