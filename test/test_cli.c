/*
** test_cli.c -- the afv program as a user runs it: ./afv through system(),
** from the repository root (where `make test` starts the runner).
**
** Each test writes its input files into a fresh directory made by mkdtemp
** under /tmp, and the directory is removed at the end of the suite.  The
** program's stdout and stderr go to files there and are read back.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define AFV_PROGRAM "./afv"
#define OUT_MAX 65536

static char dir[64];               /* the suite's temporary directory */
static char out[OUT_MAX];          /* stdout of the last run */
static char err[OUT_MAX];          /* stderr of the last run */

/* dir/name into buf. */
static const char *path_in(char *buf, size_t len, const char *name)
{
  snprintf(buf, len, "%s/%s", dir, name);
  return buf;
}

static void write_file(const char *name, const char *text)
{
  char p[128];
  FILE *fp = fopen(path_in(p, sizeof p, name), "w");
  CHECK(fp != NULL, "cannot create %s", p);
  if (!fp) return;
  fputs(text, fp);
  fclose(fp);
}

static void slurp(const char *name, char *buf)
{
  char p[128];
  FILE *fp = fopen(path_in(p, sizeof p, name), "r");
  size_t k = 0;
  buf[0] = 0;
  if (!fp) return;
  k = fread(buf, 1, OUT_MAX - 1, fp);
  buf[k] = 0;
  fclose(fp);
}

/* Runs ./afv with the given arguments ("%s" in args is replaced by dir);
** returns the exit status (-1 if it did not exit normally). */
static int afv(const char *args)
{
  char cmd[1200], a[768], so[128], se[128];
  const char *mark = strstr(args, "%s");
  int st;
  if (mark)
    snprintf(a, sizeof a, "%.*s%s%s", (int)(mark - args), args, dir,
             mark + 2);
  else
    snprintf(a, sizeof a, "%s", args);
  snprintf(cmd, sizeof cmd, "%s %s >%s 2>%s", AFV_PROGRAM, a,
           path_in(so, sizeof so, "stdout"), path_in(se, sizeof se, "stderr"));
  st = system(cmd);
  slurp("stdout", out);
  slurp("stderr", err);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int count_lines(const char *s)
{
  int n = 0;
  for (; *s; s++) n += *s == '\n';
  return n;
}

/* A small configuration with contacts, arcs and separators of every kind. */
static const char *good_points =
  "# three touching cells and one alone\n"
  "0 0\n"
  "1.5,0.2\n"
  "\n"
  "0.7\t1.3\n"
  "  6 6  \n";

/* ---- help ---------------------------------------------------------------- */
static void test_cli_help(void)
{
  static const char *opts[] = {"--l", "--A0", "--P0", "--KA", "--KP",
                               "--Lambda", "--box", "--cap"};
  int k;
  static const char *commands[] = {"eval", "check", "run", "draw",
                                   "analyze", "meanfield", "sweep",
                                   "collect", "paper"};
  char line[32];
  CHECK(afv("--help") == 0, "afv --help: exit status not 0");
  for (k = 0; k < (int)(sizeof commands / sizeof commands[0]); k++) {
    snprintf(line, sizeof line, "\n  %s ", commands[k]);
    CHECK(strstr(out, line) != NULL, "afv --help does not list the command "
          "%s:\n%s", commands[k], out);
  }
  CHECK(afv("eval --help") == 0, "afv eval --help: exit status not 0");
  for (k = 0; k < 8; k++) {
    const char *at = strstr(out, opts[k]);
    CHECK(at != NULL, "afv eval --help does not list %s", opts[k]);
    /* the line of each model option states its default */
    if (at && k != 6)
      CHECK(strstr(at, "default") && strstr(at, "default") < strchr(at,
            '\n') + 80, "afv eval --help: no default near %s", opts[k]);
  }
  CHECK(strstr(out, "# cell x y area perimeter arc_length contacts fx fy"),
        "afv eval --help does not show the output header");
  CHECK(afv("check --help") == 0, "afv check --help: exit status not 0");
  CHECK(strstr(out, "--h") && strstr(out, "--tol") && strstr(out, "--cap"),
        "afv check --help misses --h, --tol or --cap");
}

/* ---- afv eval output ----------------------------------------------------- */
/* Splits a line into whitespace-separated tokens (modifies it). */
static int tokens(char *line, char **tok, int max)
{
  int n = 0;
  char *t = strtok(line, " \n");
  while (t && n < max) {
    tok[n++] = t;
    t = strtok(NULL, " \n");
  }
  return n;
}

/* A number printed with %.17g reads back and prints again identically. */
static int is_17g(const char *tok)
{
  char again[64];
  snprintf(again, sizeof again, "%.17g", strtod(tok, NULL));
  return strcmp(again, tok) == 0;
}

static void test_cli_eval_format(void)
{
  char p[128], *line, *save = NULL, copy[OUT_MAX];
  double *r = NULL, f[8], E;
  int n = 0, st, row = 0, bad = 0;
  afv_params prm;
  afv_box b = {0, 0, 0};
  afv_geom g = {0};
  write_file("good.xy", good_points);
  st = afv("eval %s/good.xy");
  CHECK(st == 0, "afv eval: exit status %d, stderr: %s", st, err);
  CHECK(err[0] == 0, "afv eval wrote to stderr: %s", err);
  /* the reference: the library on the same points */
  afv_params_default(&prm);
  CHECK(afv_points_read(path_in(p, sizeof p, "good.xy"), &n, &r, NULL, 0)
        == AFV_OK && n == 4, "reading good.xy");
  CHECK(r && afv_compute(&g, n, r, &prm, &b, f) == AFV_OK, "compute");
  E = g.energy;
  memcpy(copy, out, sizeof out);
  CHECK(strncmp(copy, "# cell x y area perimeter arc_length contacts fx "
        "fy\n", 52) == 0, "first line: %.60s", copy);
  CHECK(count_lines(copy) == n + 2, "%d lines, want %d", count_lines(copy),
        n + 2);
  for (line = strtok_r(copy, "\n", &save); line && r;
       line = strtok_r(NULL, "\n", &save)) {
    char *tok[12], buf[1024];
    int nt, k;
    if (line[0] == '#') continue;
    snprintf(buf, sizeof buf, "%s", line);
    nt = tokens(buf, tok, 12);
    CHECK(nt == 9, "line '%s' has %d columns", line, nt);
    if (nt != 9 || row >= n) {
      bad++;
      continue;
    }
    for (k = 1; k < 9; k++)
      if (k != 6 && !is_17g(tok[k])) bad++;
    bad += atoi(tok[0]) != row || atoi(tok[6]) != g.contacts[row];
    bad += strtod(tok[1], NULL) != r[2*row] || strtod(tok[2], NULL)
           != r[2*row+1];
    bad += strtod(tok[3], NULL) != g.area[row]
           || strtod(tok[4], NULL) != g.perim[row]
           || strtod(tok[5], NULL) != g.arc[row];
    bad += strtod(tok[7], NULL) != f[2*row]
           || strtod(tok[8], NULL) != f[2*row+1];
    row++;
  }
  CHECK(row == n && bad == 0, "%d cell lines, %d fields differ from the "
        "library or are not %%.17g", row, bad);
  {
    char *last = strstr(out, "# energy ");
    CHECK(last && strtod(last + 9, NULL) == E && strchr(last, '\n')
          && strchr(last, '\n')[1] == 0, "last line is not '# energy %.17g'",
          E);
  }
  free(r);
  afv_geom_free(&g);
}

/* --box LX,LY wraps positions into the box, and the flags reach the model. */
static void test_cli_eval_options(void)
{
  double x = NAN, y = NAN;
  const char *second;
  int st;
  write_file("wrap.xy", "-1 13\n2 2\n");
  st = afv("eval %s/wrap.xy --box 10,12 --l 1.5 --A0 7 --P0 9 --KA 2 "
           "--KP 3 --Lambda 0.5 --cap 0");
  CHECK(st == 0, "exit status %d: %s", st, err);
  second = strchr(out, '\n');      /* the first cell's line follows */
  CHECK(second && sscanf(second + 1, "0 %lf %lf", &x, &y) == 2 && x == 9
        && y == 1, "wrapped position (%g, %g), want (9, 1)", x, y);
  /* an isolated cell of radius 1.5: E = KA (A - A0)^2 + KP (P - P0)^2
  ** + Lambda L for each of the two cells */
  {
    double A = 3.14159265358979323846 * 2.25, P = 3.14159265358979323846 * 3;
    double E = 2 * (2 * (A - 7) * (A - 7) + 3 * (P - 9) * (P - 9) + 0.5 * P);
    const char *last = strstr(out, "# energy ");
    CHECK(last && fabs(strtod(last + 9, NULL) - E) <= 1e-12 * E,
          "energy %s, want %.17g", last ? last : "(none)", E);
  }
}

/* ---- afv check ----------------------------------------------------------- */
static void test_cli_check(void)
{
  int st;
  write_file("good.xy", good_points);
  st = afv("check %s/good.xy");
  CHECK(st == 0, "afv check on a good file: exit %d\n%s%s", st, out, err);
  CHECK(strstr(out, "max_rel_error") && strstr(out, "PASS"), "afv check "
        "output:\n%s", out);
  /* the same with a deliberately wrong force: the cap at 2l */
  st = afv("check %s/good.xy --cap 2");
  CHECK(st == 1 && strstr(out, "FAIL"), "afv check with a wrong force: exit "
        "%d\n%s", st, out);
}

/* ---- bad input ----------------------------------------------------------- */
/* Runs args, expects exit 2, nothing on stdout and exactly one stderr line
** containing every one of the (up to two) given substrings. */
static void expect_bad(const char *args, const char *want1, const char *want2)
{
  char w1[256];
  int st = afv(args);
  const char *m1 = want1;
  if (want1 && strstr(want1, "%s")) {
    snprintf(w1, sizeof w1, want1, dir);
    m1 = w1;
  }
  CHECK(st == 2, "afv %s: exit status %d, want 2", args, st);
  CHECK(out[0] == 0, "afv %s: wrote to stdout: %.80s", args, out);
  CHECK(count_lines(err) == 1, "afv %s: %d stderr lines: %s", args,
        count_lines(err), err);
  CHECK(!m1 || strstr(err, m1), "afv %s: message '%s' lacks '%s'", args,
        err, m1);
  CHECK(!want2 || strstr(err, want2), "afv %s: message '%s' lacks '%s'",
        args, err, want2);
}

static void test_cli_bad_input(void)
{
  write_file("good.xy", good_points);
  write_file("word.xy", "0 0\n1 abc\n");
  write_file("cols.xy", "0 0\n1 1\n2 2 2\n");
  write_file("one.xy", "0 0\n5\n");
  write_file("nan.xy", "0 0\nnan 1\n");
  write_file("inf.xy", "# c\n0 0\n1 -inf\n");
  write_file("same.xy", "0 0\n3 3\n0 0\n");
  write_file("sameimg.xy", "0 0\n10 0\n");
  expect_bad("eval %s/missing.xy", "%s/missing.xy", "cannot open");
  expect_bad("eval %s/word.xy", "%s/word.xy:2:", "abc");
  expect_bad("eval %s/cols.xy", "%s/cols.xy:3:", "column");
  expect_bad("eval %s/one.xy", "%s/one.xy:2:", "column");
  expect_bad("eval %s/nan.xy", "%s/nan.xy:2:", "finite");
  expect_bad("eval %s/inf.xy", "%s/inf.xy:3:", "finite");
  expect_bad("eval %s/good.xy --bogus 1", "--bogus", NULL);
  expect_bad("eval %s/good.xy --l 0", "--l", NULL);
  expect_bad("eval %s/good.xy --l -2", "--l", NULL);
  expect_bad("eval %s/good.xy --l abc", "--l", "abc");
  expect_bad("eval %s/good.xy --KA", "--KA", "value");
  expect_bad("eval %s/good.xy --box 3.9,10", "--box", "4l");
  expect_bad("eval %s/good.xy --l 2 --box 7,9", "--box", "4l");
  expect_bad("eval %s/good.xy --box 10", "--box", NULL);
  expect_bad("eval %s/same.xy", "cells 0 and 2", NULL);
  expect_bad("eval %s/sameimg.xy --box 10,10", "cells 0 and 1", NULL);
  expect_bad("eval", "POINTS", NULL);
  expect_bad("check %s/word.xy", "%s/word.xy:2:", NULL);
  expect_bad("check %s/same.xy", "cells 0 and 2", NULL);
  expect_bad("check %s/good.xy --h 0", "--h", NULL);
  expect_bad("frobnicate", "frobnicate", NULL);
}

/* ---- argument habits ------------------------------------------------------ */
/* --KEY=VALUE is --KEY VALUE; an unknown option gets the nearest one; an
** integer key takes an integral real (1e2) and refuses 2.5 saying why; a
** subnormal value is named as such, not "not a finite number"; every
** message starts with the command; the help does not promise that A0
** follows l.  (The code before: "unknown option '--P0=4.2'", no "did you
** mean", "'1e2' is not an integer", "afv: " for a config file's error,
** "(default ... = pi l^2)".) */
static void test_cli_argument_habits(void)
{
  static char params[OUT_MAX];
  const char *a0;
  write_file("good.xy", good_points);
  write_file("bad.conf", "N 20\nv00 1\n");
  CHECK(afv("run --N=20 --steps=1e2 --P0=4.25 --relax_max_steps 1e1 "
            "--quiet --out %s/hab") == 0, "afv run with --KEY=VALUE and 1e2 "
        "steps: %s", err);
  slurp("hab/params.txt", params);
  CHECK(strstr(params, "\nsteps            100\n")
        && strstr(params, "\nP0               4.25\n")
        && strstr(params, "\nrelax_max_steps  10\n"), "params.txt: %s",
        params);
  expect_bad("run --vo 1 --out %s/x", "afv run: ", "did you mean --v0");
  expect_bad("run --stpes 10 --out %s/x", "did you mean --steps", NULL);
  expect_bad("eval %s/good.xy --Lamda 1", "afv eval: ", "did you mean "
             "--Lambda");
  expect_bad("check %s/good.xy --toll 1", "afv check: ", "did you mean "
             "--tol");
  expect_bad("draw %s/good.xy --widht 300", "afv draw: ", "did you mean "
             "--width");
  expect_bad("sweep --out %s/sw --vo 1,2", "afv sweep: ", "did you mean "
             "--v0");
  expect_bad("analyze %s/a %s/b", "afv analyze: more than one DIR", NULL);
  expect_bad("run --steps 2.5 --out %s/x", "afv run: steps: '2.5'",
             "fractional");
  expect_bad("run --P0 1e-320 --out %s/x", "afv run: P0: '1e-320'",
             "smallest normal double");
  expect_bad("run --config %s/bad.conf --out %s/x", "afv run: ", "v00");
  expect_bad("eval %s/good.xy --P0=abc", "afv eval: --P0: 'abc'", NULL);
  expect_bad("eval %s/good.xy --KA", "afv eval: --KA needs a value", NULL);
  CHECK(afv("eval %s/good.xy --P0=5 --box=20,20") == 0, "afv eval "
        "--P0=5 --box=20,20: %s", err);
  CHECK(afv("run --help") == 0 && (a0 = strstr(out, "\n  A0 "))
        && (!strstr(a0, "pi l^2") || strstr(a0, "pi l^2") > strstr(a0,
            "\n  P0 ")), "afv run --help says A0 is pi l^2");
  CHECK(afv("eval --help") == 0 && (a0 = strstr(out, "--A0"))
        && (!strstr(a0, "pi l^2") || strstr(a0, "pi l^2") > strstr(a0,
            "--P0")), "afv eval --help says A0 is pi l^2");
}

/* params.txt and log.txt name the program that wrote them: afv's version
** and, built from a git checkout, its commit (the code before: neither). */
static void test_cli_run_records_version(void)
{
  static char params[OUT_MAX], log[OUT_MAX];
  char want[64], commit[64] = "";
  FILE *git = popen("git rev-parse --short=12 HEAD 2>/dev/null", "r");
  if (git) {
    if (!fgets(commit, sizeof commit, git)) commit[0] = 0;
    commit[strcspn(commit, "\n")] = 0;
    pclose(git);
  }
  CHECK(afv("run --N 12 --steps 2 --quiet --out %s/ver") == 0, "afv run: %s",
        err);
  slurp("ver/params.txt", params);
  slurp("ver/log.txt", log);
  snprintf(want, sizeof want, "# afv run parameters, written by afv %s",
           AFV_VERSION);
  CHECK(strstr(params, want) != NULL, "params.txt lacks '%s':\n%.300s", want,
        params);
  snprintf(want, sizeof want, "afv %s", AFV_VERSION);
  CHECK(strncmp(log, want, strlen(want)) == 0, "log.txt does not start with "
        "'%s':\n%.300s", want, log);
  if (commit[0])   /* a git checkout: the commit the tests were built at */
    CHECK(strstr(params, commit) && strstr(log, commit), "params.txt or "
          "log.txt lacks the commit %s", commit);
  test_sh("rm -rf %s/ver", dir);
}

static void remove_dir(void)
{
  static const char *names[] = {"stdout", "stderr", "good.xy", "word.xy",
                                "bad.conf",
                                "cols.xy", "one.xy", "nan.xy", "inf.xy",
                                "same.xy", "sameimg.xy", "wrap.xy"};
  char p[128];
  size_t k;
  for (k = 0; k < sizeof names / sizeof names[0]; k++)
    remove(path_in(p, sizeof p, names[k]));
  test_sh("rm -rf %s", path_in(p, sizeof p, "hab"));
  if (rmdir(dir) != 0) printf("  note: could not remove %s\n", dir);
}

static void test_cli_program_exists(void)
{
  if (access(AFV_PROGRAM, X_OK) != 0)
    CHECK(0, "%s not found: run the tests from the repository root "
          "(make test)", AFV_PROGRAM);
}

void suite_cli(void)
{
  strcpy(dir, "/tmp/afv_test_XXXXXX");
  if (!mkdtemp(dir)) {
    printf("  cannot create a temporary directory under /tmp\n");
    RUN(test_cli_program_exists);
    return;
  }
  RUN(test_cli_program_exists);
  RUN(test_cli_help);
  RUN(test_cli_eval_format);
  RUN(test_cli_eval_options);
  RUN(test_cli_check);
  RUN(test_cli_bad_input);
  RUN(test_cli_argument_habits);
  RUN(test_cli_run_records_version);
  remove_dir();
}
