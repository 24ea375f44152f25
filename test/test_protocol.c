/*
** test_protocol.c -- the paper's protocol (issue 19): the authors' start,
** a relaxation that relaxes and reports honestly where it stopped, and no
** refused steps in the paper's range.
**
** test_protocol_reduced is the reduced version of `make protocol-check`
** (test/protocol_check.c): N = 100, P0 in {4, 6, 8}, seeds 1 and 2, 2000
** steps at v0 in {0, 1, 2.7}.  With the FIRE relaxation and its global
** energy guard (before this change) it fails: the relaxation stopped as
** "stalled at a kink" with max |F| far above any kink's, the mean area far
** from the lattice start's, and steps were refused.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* The paper's model at P0 in the periodic box of packing fraction 0.5. */
static void paper_model(int n, double P0, afv_params *p, afv_box *b,
                        afv_dyn *d)
{
  afv_params_default(p);
  p->P0 = P0;
  afv_dyn_default(d);
  b->periodic = 1;
  b->Lx = b->Ly = sqrt(n * PI / 0.5);
}

/* The start (lattice: spacing 1.8 l; else the authors' square of side
** 0.3 L from seed) relaxed as afv run does; 0 if something failed. */
static int relaxed_start(int n, double P0, int lattice,
                         unsigned long long seed, afv_sim *s,
                         afv_relax_report *rep)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  int ok;
  paper_model(n, P0, &p, &b, &d);
  d.seed = seed;
  if (lattice) afv_init_cluster(n, 1.8, &b, r);
  else afv_init_square(n, seed, &b, 0.3 * b.Lx, r);
  memset(s, 0, sizeof *s);
  ok = afv_sim_init(s, n, r, NULL, &p, &b, &d) == AFV_OK
       && afv_relax(s, 1e-6, 100000, rep, NULL, NULL) == AFV_OK;
  free(r);
  return ok;
}

static double mean_area(const afv_sim *s)
{
  double A = 0;
  int i;
  for (i = 0; i < s->n; i++) A += s->geom.area[i];
  return A / s->n;
}

/* The report says where the relaxation stopped, and the state agrees. */
static void check_report(const afv_sim *s, const afv_relax_report *rep,
                         double P0, int seed)
{
  double f = afv_sim_max_force(s);
  CHECK(rep->max_force == f, "P0 %g seed %d: reported max|F| %g, state %g",
        P0, seed, rep->max_force, f);
  CHECK(rep->converged || rep->at_kink, "P0 %g seed %d: neither converged "
        "nor at a kink after %ld steps (max|F| %g)", P0, seed,
        rep->iterations, rep->max_force);
  CHECK(!rep->converged || rep->max_force <= 1e-6, "P0 %g seed %d: "
        "converged with max|F| %g", P0, seed, rep->max_force);
  CHECK(!rep->at_kink || (rep->max_force <= AFV_RELAX_KINK_FORCE
                          && rep->drift <= AFV_RELAX_KINK_DRIFT
                          && fabs(rep->drop) <= AFV_RELAX_KINK_DROP),
        "P0 %g seed %d: kink claimed with max|F| %g, mean force %g, energy "
        "change %g", P0, seed, rep->max_force, rep->drift, rep->drop);
}

static void test_protocol_reduced(void)
{
  static const double P0s[3] = {4, 6, 8}, v0s[3] = {0, 1, 2.7};
  enum { N = 100, STEPS = 2000 };
  int k, seed, q;
  for (k = 0; k < 3; k++) {
    afv_sim lat, s, run;
    afv_relax_report rep;
    double A_lat;
    CHECK(relaxed_start(N, P0s[k], 1, 1, &lat, &rep), "lattice start");
    A_lat = mean_area(&lat);
    afv_sim_free(&lat);
    for (seed = 1; seed <= 2; seed++) {
      double A;
      CHECK(relaxed_start(N, P0s[k], 0, (unsigned long long)seed, &s, &rep),
            "P0 %g seed %d: start or relaxation failed", P0s[k], seed);
      A = mean_area(&s);
      printf("  P0 %g seed %d: %ld steps, %s, max|F| %.2e, mean area %.3f "
             "(lattice %.3f)\n", P0s[k], seed, rep.iterations,
             rep.converged ? "converged" : rep.at_kink ? "kink" : "NOT "
             "reached", rep.max_force, A, A_lat);
      check_report(&s, &rep, P0s[k], seed);
      CHECK(fabs(A / A_lat - 1) <= 0.1, "P0 %g seed %d: mean area %g, "
            "lattice start %g", P0s[k], seed, A, A_lat);
      for (q = 0; q < 3; q++) {
        int i, st = AFV_OK;
        memset(&run, 0, sizeof run);
        CHECK(afv_sim_init(&run, N, s.r, s.theta, &s.par, &s.box, &s.dyn)
              == AFV_OK, "init");
        run.dyn.v0 = v0s[q];
        for (i = 0; i < STEPS && st == AFV_OK; i++) st = afv_sim_step(&run);
        CHECK(st == AFV_OK, "P0 %g seed %d v0 %g: step %d refused: %s, "
              "cell %d, move %g l", P0s[k], seed, v0s[q], i,
              afv_strerror(st), run.bad_cell, run.bad_disp);
        afv_sim_free(&run);
      }
      afv_sim_free(&s);
    }
  }
}

/* ---- afv run: the starts and the relaxation's report ------------------- */
static char tmp[64];

/* Runs ./afv run ARGS --out tmp/NAME (stderr to tmp/NAME.err); exit status. */
static int afv_run(const char *name, const char *args)
{
  char cmd[1024];
  int st;
  snprintf(cmd, sizeof cmd, "./afv run %s --out %s/%s 2> %s/%s.err", args,
           tmp, name, tmp, name);
  st = system(cmd);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* The text of tmp/name (malloc'd, "" if missing). */
static char *text_of(const char *name)
{
  char path[128];
  FILE *fp;
  char *buf = calloc(1, 65536);
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  if (buf && (fp = fopen(path, "r"))) {
    size_t k = fread(buf, 1, 65535, fp);
    buf[k] = 0;
    fclose(fp);
  }
  return buf;
}

/* Frame 0 of tmp/name/trajectory.dat (the start when relax_max_steps 0). */
static int first_frame(const char *name, afv_traj *tr)
{
  char path[128], err[256];
  snprintf(path, sizeof path, "%s/%s/trajectory.dat", tmp, name);
  memset(tr, 0, sizeof *tr);
  return afv_traj_read(path, tr, err, sizeof err) == AFV_OK
         && tr->nframes > 0;
}

static void test_run_starts(void)
{
  afv_traj tr;
  double L = sqrt(100 * PI / 0.5), far = 0, near = 1e9;
  int i, j;
  const char *common = "--N 100 --steps 0 --relax_max_steps 0 --quiet";
  char args[256];
  CHECK(afv_run("square", common) == 0, "default start");
  if (first_frame("square", &tr)) {
    for (i = 0; i < tr.n; i++)
      far = fmax(far, fmax(fabs(tr.r[2*i] - L / 2),
                           fabs(tr.r[2*i+1] - L / 2)));
    CHECK(far <= 0.15 * L && far > 0.13 * L, "default start: centres up to "
          "%g from the box centre, want the square of half side 0.15 L = %g",
          far, 0.15 * L);
    afv_traj_free(&tr);
  } else CHECK(0, "no trajectory of the default start");
  snprintf(args, sizeof args, "%s --init lattice --spacing 1.7", common);
  CHECK(afv_run("lattice", args) == 0, "lattice start");
  if (first_frame("lattice", &tr)) {
    for (i = 0; i < tr.n; i++)
      for (j = 0; j < i; j++)
        near = fmin(near, hypot(tr.r[2*i] - tr.r[2*j],
                                tr.r[2*i+1] - tr.r[2*j+1]));
    CHECK_CLOSE(near, 1.7, 1e-9, 0, "lattice start spacing");
    afv_traj_free(&tr);
  } else CHECK(0, "no trajectory of the lattice start");
  CHECK(afv_run("bad", "--N 100 --init crystal --quiet") == 2,
        "init crystal accepted");
  {
    char *e = text_of("bad.err");
    CHECK(strstr(e, "init") && strstr(e, "lattice"), "message: %s", e);
    CHECK(access("bad", F_OK) != 0, "a directory was made for bad input");
    free(e);
  }
  CHECK(system("./afv run --help | grep -q 'init.*cluster|lattice|random"
               "|file'") == 0, "afv run --help does not list the starts");
}

/* The log says why the relaxation stopped, with figures: at a kink (P0 6),
** converged (P0 4), not reached (a limit of 50 steps) and at a step it
** cannot take (KA 1e100); in the last two the run goes on. */
static void test_run_relaxation_reports(void)
{
  char *log, *e;
  CHECK(afv_run("kink", "--N 100 --P0 6 --steps 10 --quiet") == 0, "P0 6");
  log = text_of("kink/log.txt");
  CHECK(strstr(log, "stopped at a kink") && strstr(log, "mean force")
        && strstr(log, "(bound 5)"), "P0 6 log: %s", log);
  free(log);
  CHECK(afv_run("conv", "--N 100 --P0 4 --steps 10 --quiet") == 0, "P0 4");
  log = text_of("conv/log.txt");
  CHECK(strstr(log, "converged, max |F|"), "P0 4 log: %s", log);
  free(log);
  CHECK(afv_run("short", "--N 100 --P0 6 --steps 10 --relax_max_steps 50")
        == 0, "relaxation limit: exit status");
  log = text_of("short/log.txt");
  e = text_of("short.err");
  CHECK(strstr(log, "NOT reached within relax_max_steps 50")
        && strstr(log, "the run goes on"), "log: %s", log);
  CHECK(strstr(e, "NOT reached within relax_max_steps 50"), "stderr: %s", e);
  free(log);
  free(e);
  /* forces no step of dt can follow: the relaxation stops and says so,
  ** the run goes on (0 steps: exit 0) */
  CHECK(afv_run("stiff", "--N 30 --KA 1e100 --steps 0 --quiet") == 0,
        "KA 1e100, 0 steps: exit status");
  log = text_of("stiff/log.txt");
  CHECK(strstr(log, "which it cannot take") && strstr(log, "the run goes "
        "on"), "log: %s", log);
  free(log);
}

void suite_protocol(void)
{
  char cmd[128];
  RUN(test_protocol_reduced);
  snprintf(tmp, sizeof tmp, "/tmp/afv_test_protocol.XXXXXX");
  if (!mkdtemp(tmp)) {
    printf("  cannot make a temporary directory\n");
    return;
  }
  RUN(test_run_starts);
  RUN(test_run_relaxation_reports);
  snprintf(cmd, sizeof cmd, "rm -rf %s", tmp);
  if (system(cmd) != 0) printf("  could not remove %s\n", tmp);
}
