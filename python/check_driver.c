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
**   protocol: afv_protocol_start as afv run --N 40 --seed 5
**          --relax_max_steps 2000 (the authors' square of side 0.3 L in
**          the periodic box L = sqrt(40 pi / 0.5), relaxed, v0 0.5 on);
**          200 steps, a frame every 20 into OUTDIR/traj.dat (format 2)
**          and OUTDIR/traj1.txt (format 1, text); both read back
**          (afv_traj_read): frames; afv_analyze (l 1, v0 0.5, Dr 0.1,
**          steady from t 0.5, lag 1) of traj.dat; afv_msd_compute from
**          frame 2.
*/
#include <afv.h>
#include <math.h>
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

static FILE *open_in(const char *dir, const char *file)
{
  char path[4096];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", dir, file);
  if (!(fp = fopen(path, "w"))) exit(1);
  return fp;
}

/* A frame in format 1 (io.c, TRAJECTORY): "# step S time T", N lines
** "x y theta" in %.17g, two blank lines. */
static void text_frame(FILE *fp, afv_sim *s)
{
  const double *r = afv_sim_positions(s), *th = afv_sim_angles(s);
  int i;
  fprintf(fp, "# step %lld time %.17g\n", afv_sim_steps(s), afv_sim_time(s));
  for (i = 0; i < afv_sim_n(s); i++)
    fprintf(fp, "%.17g %.17g %.17g\n", r[2*i], r[2*i+1], th[i]);
  fprintf(fp, "\n\n");
}

static void print_traj(const char *dir, const char *file, const char *name)
{
  char path[4096], err[512], key[64];
  afv_traj tr = {0};
  double *steps;
  int k;
  snprintf(path, sizeof path, "%s/%s", dir, file);
  if (afv_traj_read(path, &tr, err, sizeof err)) exit(1);
  if (!(steps = malloc((size_t)tr.nframes * sizeof *steps))) exit(1);
  for (k = 0; k < tr.nframes; k++) steps[k] = (double)tr.step[k];
  snprintf(key, sizeof key, "%s.steps", name);
  print_array(key, steps, tr.nframes);
  snprintf(key, sizeof key, "%s.times", name);
  print_array(key, tr.t, tr.nframes);
  snprintf(key, sizeof key, "%s.positions", name);
  print_array(key, tr.r, 2 * tr.n * tr.nframes);
  snprintf(key, sizeof key, "%s.angles", name);
  print_array(key, tr.theta, tr.n * tr.nframes);
  free(steps);
  afv_traj_free(&tr);
}

static void print_analysis(const char *dir)
{
  static const char *numbers[] = {"cells", "frames", "first",
    "ngc_frac_mean", "ngc_frac_sd", "n_clusters_mean", "n_clusters_sd",
    "omega_mean", "omega_sd", "t1_final", "D_s", "D_s_lag", "D_s_origins",
    "D_s_plain", "D_0", "D_eff", "tau_NGC", "tau_NGC_reliable", "t1_rate",
    "msd_beta"};
  static const char *series[] = {"time", "ngc_frac", "n_clusters", "omega",
                                 "t1", "lag", "msd", "msd_rel", "csd"};
  char path[4096], err[512], key[64];
  afv_traj tr = {0};
  afv_analysis *a = afv_analysis_new();
  afv_msd *m = afv_msd_new();
  double v;
  size_t k;
  int count;
  snprintf(path, sizeof path, "%s/traj.dat", dir);
  if (!a || !m || afv_traj_read(path, &tr, err, sizeof err)
      || afv_analyze(a, &tr, 1, 0.5, 0.1, 0.5, 1))
    exit(1);
  for (k = 0; k < sizeof numbers / sizeof *numbers; k++) {
    if (afv_analysis_get(a, numbers[k], &v)) exit(1);
    snprintf(key, sizeof key, "analysis.%s", numbers[k]);
    print_array(key, &v, 1);
  }
  for (k = 0; k < sizeof series / sizeof *series; k++) {
    const double *values = afv_analysis_series(a, series[k], &count);
    snprintf(key, sizeof key, "analysis.%s", series[k]);
    print_array(key, values, count);
  }
  if (afv_msd_compute(m, &tr, 2, 1)) exit(1);
  for (k = 5; k < 8; k++) {
    const double *values = afv_msd_series(m, series[k], &count);
    snprintf(key, sizeof key, "msd.%s", series[k]);
    print_array(key, values, count);
  }
  afv_msd_delete(m);
  afv_analysis_delete(a);
  afv_traj_free(&tr);
}

static void protocol(const char *dir)
{
  enum { N = 40 };
  double L = sqrt(N * 3.14159265358979323846 * 1 * 1 / 0.5);
  afv_params p;
  afv_box box;
  afv_dyn d;
  afv_relax_report rep;
  afv_protocol *pr = afv_protocol_new();
  afv_sim *s = afv_sim_new();
  FILE *bin = open_in(dir, "traj.dat"), *text = open_in(dir, "traj1.txt");
  int k;
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.v0 = 0.5;
  d.seed = 5;
  box.periodic = 1;
  box.Lx = box.Ly = L;
  if (!pr || !s || afv_protocol_set(pr, "side", AFV_AUTHORS_SQUARE * L)
      || afv_protocol_set(pr, "relax_max_steps", 2000)
      || afv_protocol_start(s, N, &p, &box, &d, pr, &rep, NULL, NULL))
    exit(1);
  printf("protocol.relax 0 %ld\nprotocol.relax 1 %.17g\n", rep.iterations,
         rep.energy);
  afv_traj_write_header(bin, N, &box);
  fprintf(text, "# afv trajectory cells %d box periodic %.17g %.17g\n", N,
          L, L);
  for (k = 0; k <= 200; k++) {
    if (k % 20 == 0) {
      afv_traj_write_frame(bin, afv_sim_steps(s), afv_sim_time(s), N,
                           afv_sim_positions(s), afv_sim_angles(s));
      text_frame(text, s);
    }
    if (k < 200) run(s, 1);
  }
  if (fclose(bin) || fclose(text)) exit(1);
  print_array("protocol.positions", afv_sim_positions(s), 2 * N);
  print_array("protocol.angles", afv_sim_angles(s), N);
  afv_sim_delete(s);
  afv_protocol_delete(pr);
  print_traj(dir, "traj.dat", "traj2");
  print_traj(dir, "traj1.txt", "traj1");
  print_analysis(dir);
}

int main(int argc, char **argv)
{
  if (argc != 2) return fprintf(stderr, "usage: check_driver OUTDIR\n"), 2;
  open_space(argv[1]);
  simulation(argv[1]);
  protocol(argv[1]);
  return 0;
}
