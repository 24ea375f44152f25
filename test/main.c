/* main.c -- runs every test suite and prints "N passed, M failed". */
#include "test.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int test_failures_in_current;
int test_skipped_current;
static int passed, failed, skipped;

void test_fail(const char *file, int line, const char *fmt, ...)
{
  va_list ap;
  test_failures_in_current++;
  printf("  %s:%d: ", file, line);
  va_start(ap, fmt);
  vprintf(fmt, ap);
  va_end(ap);
  printf("\n");
}

int test_close(double got, double want, double rtol, double atol)
{
  return isfinite(got) && fabs(got - want) <= atol + rtol * fabs(want);
}

void test_run(const char *name, void (*fn)(void))
{
  test_failures_in_current = 0;
  test_skipped_current = 0;
  fn();
  if (test_failures_in_current) {
    failed++;
    printf("FAIL %s\n", name);
  } else if (test_skipped_current) {
    skipped++;
    printf("skip %s\n", name);
  } else {
    passed++;
    printf("ok   %s\n", name);
  }
  fflush(stdout);
}

const char *test_golden_dir(void)
{
  const char *env = getenv("AFV_GOLDEN");
  return env && *env ? env : "test/golden";
}

/* The suites in the order they run. */
static const struct { const char *name; void (*run)(void); } suites[] = {
  {"core", suite_core}, {"cli", suite_cli}, {"dynamics", suite_dynamics},
  {"analysis", suite_analysis}, {"perf", suite_perf},
  {"pictures", suite_pictures}, {"readers", suite_readers},
  {"runjob", suite_runjob}, {"hostile", suite_hostile},
  {"reference", suite_reference},
  {"sweep", suite_sweep}, {"geometry", suite_geometry},
  {"protocol", suite_protocol}, {"docs", suite_docs}, {"api", suite_api},
  {"integrator", suite_integrator}, {"paper", suite_paper},
  {"relax_fire", suite_relax_fire}, {"invariants", suite_invariants},
  {"messages", suite_messages}};

/* test/run_tests: every suite; test/run_tests NAME...: those suites only
** (e.g. core geometry, while changing the geometry); test/run_tests
** --except NAME...: every suite but those (make test runs the slow ones
** beside the rest, test/run.sh). */
int main(int argc, char **argv)
{
  size_t k;
  int a, except = argc > 1 && strcmp(argv[1], "--except") == 0;
  for (a = 1 + except; a < argc; a++) {
    for (k = 0; k < sizeof suites / sizeof suites[0]; k++)
      if (strcmp(argv[a], suites[k].name) == 0) break;
    if (k == sizeof suites / sizeof suites[0]) {
      printf("run_tests: no suite %s\n", argv[a]);
      return 2;
    }
  }
  for (k = 0; k < sizeof suites / sizeof suites[0]; k++) {
    int named = 0;
    for (a = 1 + except; a < argc; a++) named |= !strcmp(argv[a], suites[k].name);
    if (argc == 1 || named != except) suites[k].run();
  }
  printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
  return failed ? 1 : 0;
}
