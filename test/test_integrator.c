/*
** test_integrator.c -- the integration of Eq. (4) (the paper's Euler step)
** and the contact cap (afv_params.cap), as doc/design.md and afv.h state
** them:
**   - a step is Eq. (4) to the bit, a cell that moves 2 l included, and
**     nothing finite is refused;
**   - the detachment mechanism: a pair pulled apart by v0 separates under
**     Euler at dt = 0.01 and stays joined at smaller dt (the exact force
**     diverges as the contact breaks: only a finite step crosses it);
**   - the cap is PyAFV's (golden forces of PyAFV 0.4.16 to 1e-10), it leaves
**     the energy unchanged, and a relaxation with it says so;
**   - integrator substeps and max_move, removed in afv 0.3.0, are refused
**     wherever they are named, and so are the runs of earlier versions that
**     used them, each with the version that finishes it.
*/
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the Euler step ------------------------------------------------------ */

/* A step moves every cell by dt (mu F_i + v0 n_i), with F the force at
** the start and n from the angle at the start, computed here in the same
** order of operations; the angle then gets its noise.  The configuration
** has a pair 0.1 l apart, whose force moves a cell about 2 l in
** dt = 0.01 at KA = 40. */
static void test_euler_step_is_eq4_to_the_bit(void)
{
  enum { N = 6 };
  double r[2 * N] = {0, 0, 0.1, 0, 3, 0.5, 4.6, 0.4, 3.8, 1.9, -2, -1.5};
  double th[N] = {0.3, 1.2, -2.0, 2.8, 0.1, -0.7}, want[2 * N], f0[2 * N];
  double most = 0;
  afv_params p;
  afv_box b = test_open_box();
  afv_dyn d;
  afv_sim s;
  int i;
  afv_params_default(&p);
  p.KA = 40;
  afv_dyn_default(&d);
  d.v0 = 0.7;
  d.mu = 1.3;
  memset(&s, 0, sizeof s);
  CHECK(afv_sim_init(&s, N, r, th, &p, &b, &d) == AFV_OK, "init");
  memcpy(f0, s.f, sizeof f0);
  for (i = 0; i < N; i++) {
    double mx = d.dt * (d.mu * f0[2*i] + d.v0 * cos(th[i]));
    double my = d.dt * (d.mu * f0[2*i+1] + d.v0 * sin(th[i]));
    want[2*i] = r[2*i] + mx;                           /* Eq. (4) */
    want[2*i+1] = r[2*i+1] + my;
    if (hypot(mx, my) > most) most = hypot(mx, my);
  }
  CHECK(most > 2, "largest move %g l: the test needs one above 2 l", most);
  CHECK(afv_sim_step(&s) == AFV_OK, "a finite step refused");
  for (i = 0; i < 2 * N; i++)
    CHECK(s.r[i] == want[i], "coordinate %d: %.17g, Eq. (4) gives %.17g",
          i, s.r[i], want[i]);
  CHECK(afv_sim_jumps(&s) == 1, "jumps %lld, want 1", afv_sim_jumps(&s));
  CHECK_CLOSE(afv_sim_largest_move(&s), most, 1e-12, 0, "largest move");
  CHECK(s.step == 1 && s.t == d.dt, "step %lld t %g", s.step, s.t);
  /* the invariant: the forces are those of the new positions */
  {
    afv_geom g = {0};
    double f[2 * N];
    CHECK(afv_compute(&g, N, s.r, &p, &b, f) == AFV_OK, "compute");
    CHECK(memcmp(f, s.f, sizeof f) == 0, "forces not those at the new r");
    afv_geom_free(&g);
  }
  afv_sim_free(&s);
}

/* Nothing finite is refused, but a force that is not finite is, and the
** state is then unchanged. */
static void test_euler_refuses_only_the_non_finite(void)
{
  double r[4] = {0, 0, 1.5, 0}, keep[4];
  afv_params p;
  afv_box b = test_open_box();
  afv_dyn d;
  afv_sim s;
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.v0 = 80;                         /* v0 dt = 0.8 l */
  memset(&s, 0, sizeof s);
  CHECK(afv_sim_init(&s, 2, r, NULL, &p, &b, &d) == AFV_OK, "init");
  CHECK(afv_sim_step(&s) == AFV_OK, "v0 dt = 0.8 l refused");
  memcpy(keep, s.r, sizeof keep);
  s.f[0] = NAN;                                /* a force not finite */
  CHECK(afv_sim_step(&s) == AFV_EUNSTABLE, "a NaN force was stepped");
  CHECK(memcmp(keep, s.r, sizeof keep) == 0, "refused step moved cells");
  afv_sim_free(&s);
}

/* ---- detachment ---------------------------------------------------------- */

/* Two touching cells, each self-propelled away from the other at v0
** (Dr = 0), from d = 1.9 l, for a time T: their distance at the end, or
** -1 on an error. */
static double pair_pulled_apart(double v0, double dt, double T)
{
  double r[4] = {0, 0, 1.9, 0}, th[2] = {3.14159265358979323846, 0}, d2;
  afv_params p;
  afv_box b = test_open_box();
  afv_dyn d;
  afv_sim s;
  long k, steps = (long)(T / dt + 0.5);
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.v0 = v0;
  d.Dr = 0;
  d.dt = dt;
  memset(&s, 0, sizeof s);
  if (afv_sim_init(&s, 2, r, th, &p, &b, &d) != AFV_OK) return -1;
  for (k = 0; k < steps; k++)
    if (afv_sim_step(&s) != AFV_OK) {
      afv_sim_free(&s);
      return -1;
    }
  d2 = hypot(s.r[2] - s.r[0], s.r[3] - s.r[1]);
  afv_sim_free(&s);
  return d2;
}

/* The mechanism of doc/reproduction/convergence.md, on one pair: the force
** that holds a breaking contact diverges like (2l - d)^(-1/2), so for any
** v0 the continuous-time dynamics stalls at a distance d* < 2l where it
** balances 2 v0 of relative self-propulsion (v0 = 5: d* = 1.9929 l), and
** finer steps follow it there; but that force is so steep at d* that an
** Euler step of dt = 0.01 overshoots past 2l, where it vanishes: the pair
** separates. */
static void test_pair_separates_only_by_a_finite_step(void)
{
  static const double dts[4] = {0.01, 0.001, 1e-4, 1e-5};
  double d[4];
  int k;
  for (k = 0; k < 4; k++) {
    d[k] = pair_pulled_apart(5, dts[k], 2.0);
    printf("  v0 5, dt %g: distance after t = 2: %.6f l\n", dts[k], d[k]);
  }
  CHECK(d[0] > 2, "dt = 0.01: the pair did not separate (d = %g)", d[0]);
  for (k = 1; k < 4; k++)
    CHECK(d[k] > 1.99 && d[k] < 2, "dt = %g: the pair did not stall just "
          "short of 2l (d = %.9g)", dts[k], d[k]);
  CHECK(fabs(d[3] - d[2]) < 1e-5 && fabs(d[2] - d[1]) < 1e-4,
        "finer steps do not converge to one stall distance: %.9g %.9g %.9g",
        d[1], d[2], d[3]);
}

/* ---- the cap ----------------------------------------------------------- */

/* PyAFV's forces (test/golden/pyafv_cap/, PyAFV 0.4.16) with its
** contact truncation delta = 0 and 0.45, against afv's cap, to 1e-10 on
** every component. */
static void test_cap_is_pyafvs(void)
{
  static const char *dirs[4] = {"two_d1.95", "two_d1.999", "three_near",
                                "random60"};
  static const double caps[2] = {0, 0.45};
  static const char *files[2] = {"forces_delta0.csv", "forces_delta0.45.csv"};
  int k, c;
  for (k = 0; k < 4; k++)
    for (c = 0; c < 2; c++) {
      char pts[1024], frc[1024];
      double *r, *want, *f, worst = 0;
      int n = 0, m = 0, i;
      afv_params p;
      afv_geom g = {0};
      afv_box b = test_open_box();
      snprintf(pts, sizeof pts, "%s/pyafv_cap/%s/points.csv",
               test_golden_dir(), dirs[k]);
      snprintf(frc, sizeof frc, "%s/pyafv_cap/%s/%s",
               test_golden_dir(), dirs[k], files[c]);
      r = test_read_pairs(pts, &n);
      want = test_read_pairs(frc, &m);
      CHECK(r && want && n == m, "%s or %s missing or unequal (run from the "
            "repo root)", pts, frc);
      if (!r || !want || n != m) {
        free(r);
        free(want);
        continue;
      }
      afv_params_default(&p);
      p.cap = caps[c];
      f = malloc((size_t)(2 * n) * sizeof(double));
      CHECK(f && afv_compute(&g, n, r, &p, &b, f) == AFV_OK, "compute");
      for (i = 0; f && i < 2 * n; i++)
        if (fabs(f[i] - want[i]) > worst) worst = fabs(f[i] - want[i]);
      CHECK(worst <= 1e-10, "%s, cap %g: largest deviation %.3e", dirs[k],
            caps[c], worst);
      printf("  PyAFV %s, delta %g: largest deviation %.2e\n", dirs[k],
             caps[c], worst);
      free(r);
      free(want);
      free(f);
      afv_geom_free(&g);
    }
}

/* The cap regularises the force only: the geometry and the energy are
** those of the exact model; and where no contact is near detachment the
** force is the exact one, to the bit. */
static void test_cap_changes_only_the_force(void)
{
  double r[6] = {0, 0, 1.97, 0, -0.4, 1.92}, f0[6], f1[6];
  afv_params p;
  afv_geom g0 = {0}, g1 = {0};
  afv_box b = test_open_box();
  int i;
  afv_params_default(&p);
  CHECK(afv_compute(&g0, 3, r, &p, &b, f0) == AFV_OK, "exact");
  p.cap = 0.45;
  CHECK(afv_compute(&g1, 3, r, &p, &b, f1) == AFV_OK, "capped");
  CHECK(g0.energy == g1.energy, "energy %.17g vs %.17g", g0.energy,
        g1.energy);
  for (i = 0; i < 3; i++)
    CHECK(g0.area[i] == g1.area[i] && g0.perim[i] == g1.perim[i]
          && g0.arc[i] == g1.arc[i], "cell %d: shape changed by the cap", i);
  CHECK(fabs(f0[0] - f1[0]) > 1e-3, "the cap changed no force here");
  r[2] = 1.5;                         /* no contact near detachment now */
  r[4] = -0.4; r[5] = 1.6;
  p.cap = 0;
  CHECK(afv_compute(&g0, 3, r, &p, &b, f0) == AFV_OK, "exact, far");
  p.cap = 0.45;
  CHECK(afv_compute(&g1, 3, r, &p, &b, f1) == AFV_OK, "capped, far");
  CHECK(memcmp(f0, f1, sizeof f0) == 0, "the cap changed a force far from "
        "detachment");
  afv_geom_free(&g0);
  afv_geom_free(&g1);
}

/* The file at path, NUL-terminated (NULL if unreadable); *len its size. */
static char *slurp_file(const char *path, long *len)
{
  FILE *fp = fopen(path, "rb");
  char *buf;
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  *len = ftell(fp);
  rewind(fp);
  buf = malloc((size_t)*len + 1);
  if (buf && fread(buf, 1, (size_t)*len, fp) != (size_t)*len) {
    free(buf);
    buf = NULL;
  }
  if (buf) buf[*len] = 0;
  fclose(fp);
  return buf;
}

/* afv run with a cap says in log.txt that its relaxation follows a force
** that is not -grad E, by the flow and by FIRE alike. */
static void test_capped_relaxation_says_so(void)
{
  static const char *const relax[] = {"flow", "fire"};
  char dir[] = "/tmp/afv_capped_XXXXXX", path[256], *log;
  long len;
  int k;
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  for (k = 0; k < 2; k++) {
    CHECK(test_sh("./afv run --N 30 --cap 0.45 --relax %s --steps 10 "
                  "--relax_max_steps 50 --quiet --out %s/%s", relax[k], dir,
                  relax[k]) == 0, "afv run --cap 0.45 --relax %s", relax[k]);
    snprintf(path, sizeof path, "%s/%s/log.txt", dir, relax[k]);
    log = slurp_file(path, &len);
    CHECK(log && strstr(log, "not -grad E"), "relax %s: log.txt does not "
          "say the capped force is not -grad E:\n%s", relax[k],
          log ? log : "(none)");
    free(log);
  }
  test_sh("rm -rf %s", dir);
}

/* An unknown integrator is refused before anything is written, with the
** accepted name. */
static void test_integrator_key_refused_cleanly(void)
{
  char dir[] = "/tmp/afv_integ_XXXXXX", path[256], *err;
  long len;
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  CHECK(test_sh("./afv run --integrator rk4 --out %s/run 2> %s/err",
                dir, dir) == 2, "integrator rk4: exit status not 2");
  snprintf(path, sizeof path, "%s/err", dir);
  err = slurp_file(path, &len);
  CHECK(err && strstr(err, "integrator") && strstr(err, "euler"),
        "the message does not name the key and the choice: %s",
        err ? err : "");
  free(err);
  snprintf(path, sizeof path, "%s/run", dir);
  CHECK(fopen(path, "r") == NULL, "a run directory was created");
  test_sh("rm -rf %s", dir);
}

/* ---- integrator substeps, removed in afv 0.3.0 ------------------------ */

/* 1 if the file at path is one line that holds every string of want (up
** to a NULL); else says what it holds. */
static int one_line_with(const char *path, const char *const *want)
{
  long len = 0;
  char *text = slurp_file(path, &len);
  int ok = text && len > 0 && strchr(text, '\n') == text + len - 1, k;
  for (k = 0; ok && want[k]; k++) ok = strstr(text, want[k]) != NULL;
  if (!ok) printf("  %s: '%s'\n", path, text ? text : "(none)");
  free(text);
  return ok;
}

/* integrator substeps and its max_move, on the command line, in a config
** file (named with its line) and as a sweep's key: exit 2, one line that
** says they were removed in afv 0.3.0 and that afv 0.2.0 finishes a run
** that uses them, and nothing written.  (afv 0.2.0 ran them.) */
static void test_substeps_refused_naming_0_2_0(void)
{
  static const char *const cases[][2] = {
    {"run --integrator substeps --steps 5 --out %s/out", "integrator"},
    {"run --integrator=substeps --steps 5 --out %s/out", "integrator"},
    {"run --max_move 0.05 --steps 5 --out %s/out", "max_move"},
    {"run --config %s/sub.conf --out %s/out", "sub.conf:2: integrator"},
    {"run --config %s/mm.conf --out %s/out", "mm.conf:3: max_move"},
    {"sweep --out %s/out --max_move 0.05,0.1", "max_move"}};
  char dir[] = "/tmp/afv_substeps_XXXXXX", cmd[700], err[300], out[300];
  int k;
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  CHECK(test_sh("printf 'N 30\\nintegrator substeps\\nsteps 5\\n' > %s/sub.conf"
                " && printf 'N 30\\nintegrator euler\\nmax_move 0.05\\n' > "
                "%s/mm.conf", dir, dir) == 0, "writing the configs");
  snprintf(err, sizeof err, "%s/err", dir);
  snprintf(out, sizeof out, "%s/out", dir);
  for (k = 0; k < 6; k++) {
    const char *const want[] = {cases[k][1], "removed in afv 0.3.0",
                                "afv 0.2.0", NULL};
    char args[300];
    snprintf(args, sizeof args, cases[k][0], dir, dir);
    snprintf(cmd, sizeof cmd, "./afv %s 2> %s", args, err);
    CHECK(test_sh("%s", cmd) == 2, "afv %s: exit status not 2", args);
    CHECK(one_line_with(err, want), "afv %s: not one line naming %s, afv "
          "0.3.0 and afv 0.2.0", args, cases[k][1]);
    CHECK(fopen(out, "r") == NULL, "afv %s: wrote %s", args, out);
    test_sh("rm -rf %s", out);            /* each case on its own */
  }
  test_sh("rm -rf %s", dir);
}

/* The run to edit into an old version's: DIR/new (DIR made from the
** template), short, with checkpoints.  1 if made. */
#define OLD_RUN_ARGS "--N 30 --steps 20 --checkpoint_every 10 " \
                     "--relax_max_steps 50 --quiet"
static int made_run_to_edit(char *dir)
{
  int failures = test_failures_in_current;
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  CHECK(test_sh("./afv run %s --out %s/new", OLD_RUN_ARGS, dir) == 0,
        "the run to edit");
  return test_failures_in_current == failures;
}

/* The run at DIR/copy, copied to DIR/old, is refused by --resume and by
** --continue (with run_args): exit 2, one line holding each of want, and
** no file of it changed.  what names the case in a failure. */
static void check_refused_both_ways(const char *dir, const char *run_args,
                                    const char *const *want, const char *what)
{
  char err[300];
  int how;
  snprintf(err, sizeof err, "%s/err", dir);
  for (how = 0; how < 2; how++) {
    CHECK(test_sh("rm -rf %s/old && cp -r %s/copy %s/old", dir, dir, dir)
          == 0, "restoring the run");      /* each way on its own */
    if (how == 0)
      CHECK(test_sh("./afv run --resume %s/old --steps 10 2> %s", dir, err)
            == 2, "%s: --resume: exit status not 2", what);
    else
      CHECK(test_sh("./afv run %s --out %s/old --continue 2> %s", run_args,
                    dir, err) == 2, "%s: --continue: exit status not 2",
            what);
    CHECK(one_line_with(err, want), "%s: not one line naming %s and %s",
          what, want[0], want[1]);
    CHECK(test_sh("diff -r %s/old %s/copy > /dev/null", dir, dir) == 0,
          "%s: a file of the run changed", what);
  }
}

/* A run to go on with (--resume, --continue) whose params.txt names the
** removed keys (a run of afv 0.2.0) or has no integrator key (a run of
** afv 0.1.0, whose sub-steps had no name) is refused, exit 2, in one line
** naming the version that finishes it, and no file of it changes.  (afv
** 0.2.0 resumed both: the first with the sub-steps or plain Euler, the
** second with the sub-steps.) */
static void test_old_runs_refused_naming_their_version(void)
{
  static const char *const edits[3][2] = {
    {"s/^integrator .*/integrator       substeps/", "0.2.0"},
    {"/^integrator/a max_move         0.05", "0.2.0"},
    {"/^integrator/c max_move         0.05", "0.1.0"}};
  const char *run_args = OLD_RUN_ARGS;
  char dir[] = "/tmp/afv_oldrun_XXXXXX", what[200];
  int k;
  if (!made_run_to_edit(dir)) return;
  for (k = 0; k < 3; k++) {
    const char *const want[] = {"params.txt", edits[k][1], NULL};
    CHECK(test_sh("rm -rf %s/copy && cp -r %s/new %s/copy && "
                  "sed -i '%s' %s/copy/params.txt", dir, dir, dir,
                  edits[k][0], dir) == 0,
          "making the run of afv %s", edits[k][1]);
    snprintf(what, sizeof what, "edit '%s'", edits[k][0]);
    check_refused_both_ways(dir, run_args, want, what);
  }
  test_sh("rm -rf %s", dir);
}

/* A run written by afv 0.4.0 or 0.3.0 (params.txt's first line says so),
** whose noise used the C library's log, is refused by --resume and
** --continue, exit 2, in one line naming params.txt and the version that
** finishes it, and no file of it changes; a run of 0.5.0 and one whose
** params.txt has no such line go on.  (The copies lack final.svg, as a
** run stopped before its end, which --continue resumes: it leaves a
** finished run alone.  afv 0.4.0 resumed both.) */
static void test_run_of_0_4_0_refused_naming_0_4_0(void)
{
  static const char *const versions[] = {"0.4.0", "0.3.0"};
  const char *run_args = OLD_RUN_ARGS;
  char dir[] = "/tmp/afv_run040_XXXXXX", err[300];
  int k;
  if (!made_run_to_edit(dir)) return;
  snprintf(err, sizeof err, "%s/err", dir);
  for (k = 0; k < 2; k++) {
    char finish[40], what[40];
    const char *const want[] = {"params.txt", finish, NULL};
    snprintf(finish, sizeof finish, "finish it with afv %s", versions[k]);
    snprintf(what, sizeof what, "a run of afv %s", versions[k]);
    CHECK(test_sh("rm -rf %s/copy && cp -r %s/new %s/copy && sed -i "
                  "'1s/written by afv [0-9.]*/written by afv %s/' "
                  "%s/copy/params.txt && grep -q 'by afv %s (' "
                  "%s/copy/params.txt && rm %s/copy/final.svg", dir, dir, dir,
                  versions[k], dir, versions[k], dir, dir) == 0,
          "making %s", what);
    check_refused_both_ways(dir, run_args, want, what);
  }
  CHECK(test_sh("cp -r %s/new %s/own && ./afv run --resume %s/own --steps "
                "10 2> %s", dir, dir, dir, err) == 0,
        "a run of this version was not resumed");
  CHECK(test_sh("cp -r %s/new %s/hand && sed -i 1d %s/hand/params.txt && "
                "./afv run --resume %s/hand --steps 10 2> %s", dir, dir, dir,
                dir, err) == 0,
        "a params.txt without its first line was not resumed");
  test_sh("rm -rf %s", dir);
}

void suite_integrator(void)
{
  RUN(test_euler_step_is_eq4_to_the_bit);
  RUN(test_euler_refuses_only_the_non_finite);
  RUN(test_pair_separates_only_by_a_finite_step);
  RUN(test_cap_is_pyafvs);
  RUN(test_cap_changes_only_the_force);
  RUN(test_capped_relaxation_says_so);
  RUN(test_integrator_key_refused_cleanly);
  RUN(test_substeps_refused_naming_0_2_0);
  RUN(test_old_runs_refused_naming_their_version);
  RUN(test_run_of_0_4_0_refused_naming_0_4_0);
}
