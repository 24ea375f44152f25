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
  if (lattice) afv_init_lattice(n, 1.8, &b, r);
  else afv_init_cluster(n, seed, &b, 0.3 * b.Lx, r);
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

/* ---- afv_protocol_start: the protocol in one call ---------------------- */
/* The start of pr built, initialised and relaxed by the library's calls
** one by one (afv_init_*, afv_spatial_renumber, afv_init_angles,
** afv_sim_init, afv_relax or afv_relax_fire): what afv_protocol_start
** must give.  AFV_OK or a status. */
static int protocol_by_hand(afv_sim *s, int n, const afv_params *p,
                            const afv_box *b, const afv_dyn *d,
                            const afv_protocol *pr, afv_relax_report *rep)
{
  double *r = malloc((size_t)(2 * n) * sizeof(double));
  double *th = malloc((size_t)n * sizeof(double));
  int st = AFV_OK;
  if (pr->start == AFV_START_CLUSTER)
    afv_init_cluster(n, d->seed, b, pr->side, r);
  else if (pr->start == AFV_START_LATTICE)
    st = afv_init_lattice(n, pr->spacing, b, r);
  else if (pr->start == AFV_START_RANDOM)
    afv_init_random(n, d->seed, b, pr->side, r);
  else memcpy(r, pr->r, (size_t)(2 * n) * sizeof(double));
  if (st == AFV_OK && pr->start != AFV_START_GIVEN)   /* cell list order */
    st = afv_spatial_renumber(n, r, p->l, b);
  if (pr->theta) memcpy(th, pr->theta, (size_t)n * sizeof(double));
  else afv_init_angles(n, d->seed, th);
  if (st == AFV_OK) st = afv_sim_init(s, n, r, th, p, b, d);
  if (st == AFV_OK && pr->relax_max_steps > 0)
    st = (pr->relax == AFV_RELAX_FIRE ? afv_relax_fire : afv_relax)
         (s, pr->relax_tol, pr->relax_max_steps, rep, NULL, NULL);
  free(r);
  free(th);
  return st;
}

/* afv_protocol_start is the paper's protocol in one call, the one afv run
** makes: every start (the authors' square, a lattice, uniform, given
** positions and angles), unrelaxed, relaxed by the flow at v0 = 0 or by
** FIRE, gives the bits of the calls made one by one (a generated start
** numbered in afv_spatial_order), and ends at step 0 with v0 on again;
** unrelaxed, its report holds the start's energy and force. */
static void test_protocol_start_is_the_papers_order(void)
{
  enum { N = 60 };
  static const int starts[4] = {AFV_START_CLUSTER, AFV_START_LATTICE,
                                AFV_START_RANDOM, AFV_START_GIVEN};
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  afv_relax_report rep, want;
  double given[2 * N], th_given[N];
  afv_sim *s = afv_sim_new(), *hand = afv_sim_new();
  int k, relax;
  CHECK(s && hand, "out of memory");
  if (!s || !hand) goto done;
  paper_model(N, 4.6, &p, &b, &d);
  d.v0 = 0.7;
  d.seed = 9;
  afv_init_random(N, 77, &b, 0, given);
  afv_init_angles(N, 78, th_given);
  for (k = 0; k < 4; k++)
    for (relax = 0; relax < 3; relax++) {     /* none, flow, FIRE */
      size_t two = 2 * N * sizeof(double);
      memset(&pr, 0, sizeof pr);
      pr.start = starts[k];
      pr.side = AFV_AUTHORS_SQUARE * b.Lx;
      pr.spacing = 1.8;
      pr.r = given;
      pr.theta = starts[k] == AFV_START_GIVEN ? th_given : NULL;
      pr.relax = relax == 2 ? AFV_RELAX_FIRE : AFV_RELAX_FLOW;
      pr.relax_tol = 1e-6;
      pr.relax_max_steps = relax ? 300 : 0;
      memset(&want, 0, sizeof want);
      CHECK(afv_protocol_start(s, N, &p, &b, &d, &pr, &rep, NULL, NULL)
            == AFV_OK, "start %d, relax %d: refused", k, relax);
      CHECK(protocol_by_hand(hand, N, &p, &b, &d, &pr, &want) == AFV_OK,
            "start %d, relax %d: by hand", k, relax);
      CHECK(memcmp(afv_sim_positions(s), afv_sim_positions(hand), two) == 0
            && memcmp(afv_sim_angles(s), afv_sim_angles(hand), two / 2) == 0
            && memcmp(afv_sim_forces(s), afv_sim_forces(hand), two) == 0,
            "start %d, relax %d: not the state of the calls one by one", k,
            relax);
      CHECK(afv_sim_dyn(s)->v0 == d.v0 && afv_sim_steps(s) == 0
            && afv_sim_time(s) == 0, "start %d, relax %d: v0 %g, step "
            "%lld after the protocol", k, relax, afv_sim_dyn(s)->v0,
            afv_sim_steps(s));
      if (relax)
        CHECK(rep.iterations == want.iterations && rep.iterations > 0
              && rep.energy == want.energy && rep.energy0 == want.energy0,
              "start %d, relax %d: report %ld steps E %.17g, by hand %ld "
              "E %.17g", k, relax, rep.iterations, rep.energy,
              want.iterations, want.energy);
      else
        CHECK(rep.iterations == 0 && rep.energy0 == rep.energy
              && rep.energy == afv_geom_energy(afv_sim_geom(s))
              && rep.max_force == afv_sim_max_force(s),
              "start %d: the unrelaxed report is not the start's", k);
    }
  pr.start = 99;
  CHECK(afv_protocol_start(s, N, &p, &b, &d, &pr, &rep, NULL, NULL)
        == AFV_EINVAL, "an unknown start was accepted");
done:
  afv_sim_delete(s);
  afv_sim_delete(hand);
}

/* A generated start is numbered in space: cells i and i + 1 lie a few l
** apart on average, where the order drawn puts them a third of the square
** apart (about 17 l here), and the centres are the start's own (the same
** set, only renumbered).  Memory locality: doc/performance.md. */
static void test_generated_start_numbered_in_space(void)
{
  enum { N = 2000 };
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  afv_sim *s = afv_sim_new();
  static double drawn[2 * N];
  double gap = 0, sum_s[2] = {0, 0}, sum_d[2] = {0, 0};
  int i;
  CHECK(s != NULL, "out of memory");
  if (!s) return;
  paper_model(N, 4, &p, &b, &d);
  memset(&pr, 0, sizeof pr);
  pr.start = AFV_START_CLUSTER;
  pr.side = AFV_AUTHORS_SQUARE * b.Lx;
  CHECK(afv_protocol_start(s, N, &p, &b, &d, &pr, NULL, NULL, NULL)
        == AFV_OK, "refused");
  afv_init_cluster(N, d.seed, &b, pr.side, drawn);
  for (i = 0; i < N; i++) {
    const double *r = afv_sim_positions(s);
    if (i + 1 < N) {
      double dx = r[2*i+2] - r[2*i], dy = r[2*i+3] - r[2*i+1];
      afv_min_image(&b, &dx, &dy);
      gap += sqrt(dx * dx + dy * dy) / (N - 1);
    }
    sum_s[0] += r[2*i];
    sum_s[1] += r[2*i+1];
    sum_d[0] += drawn[2*i];
    sum_d[1] += drawn[2*i+1];
  }
  CHECK(gap < 3 * p.l, "cells i and i + 1 are %.3g l apart on average", gap);
  CHECK(fabs(sum_s[0] - sum_d[0]) < 1e-9 * fabs(sum_d[0])
        && fabs(sum_s[1] - sum_d[1]) < 1e-9 * fabs(sum_d[1]),
        "the centres are not the square's drawn ones");
  afv_sim_delete(s);
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

/* params.txt records the keys the run uses: init cluster has no spacing,
** init lattice has it (0.4.0 wrote spacing 1.8 for every run).  A run
** whose params.txt records it as 0.4.0 did still resumes, to the bytes of
** one straight run. */
static void test_params_leave_unused_keys_out(void)
{
  const char *fast = "--N 30 --frame_every 5 --checkpoint_every 5 "
                     "--svg_every 0 --quiet";
  const char *files[3] = {"trajectory.dat", "observables.csv",
                          "checkpoint.txt"};
  int k;
  CHECK(test_sh("./afv run %s --steps 10 --out %s/sq", fast, tmp) == 0
        && test_sh("grep -q '^spacing ' %s/sq/params.txt", tmp) != 0,
        "init cluster: params.txt records the lattice's spacing");
  CHECK(test_sh("./afv run %s --steps 0 --init lattice --out %s/lat", fast,
                tmp) == 0
        && test_sh("grep -q '^spacing ' %s/lat/params.txt", tmp) == 0,
        "init lattice: params.txt lacks its spacing");
  /* the run as 0.4.0 recorded it, then resumed for 10 more steps */
  CHECK(test_sh("sed -i 's/^init .*/&\\nspacing          1.8/' "
                "%s/sq/params.txt && grep -q '^spacing ' %s/sq/params.txt",
                tmp, tmp) == 0, "could not write a 0.4.0 params.txt");
  CHECK(test_sh("./afv run --resume %s/sq --steps 10 --quiet", tmp) == 0,
        "a params.txt with an unused spacing does not resume");
  CHECK(test_sh("./afv run %s --steps 20 --out %s/straight", fast, tmp) == 0,
        "the straight run failed");
  for (k = 0; k < 3; k++)
    CHECK(test_sh("cmp -s %s/sq/%s %s/straight/%s", tmp, files[k], tmp,
                  files[k]) == 0, "%s: resumed differs from straight",
          files[k]);
}

void suite_protocol(void)
{
  char cmd[128];
  RUN(test_protocol_reduced);
  RUN(test_protocol_start_is_the_papers_order);
  RUN(test_generated_start_numbered_in_space);
  snprintf(tmp, sizeof tmp, "/tmp/afv_test_protocol.XXXXXX");
  if (!mkdtemp(tmp)) {
    printf("  cannot make a temporary directory\n");
    return;
  }
  RUN(test_run_starts);
  RUN(test_run_relaxation_reports);
  RUN(test_params_leave_unused_keys_out);
  snprintf(cmd, sizeof cmd, "rm -rf %s", tmp);
  if (system(cmd) != 0) printf("  could not remove %s\n", tmp);
}
