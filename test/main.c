/* main.c -- runs every test suite and prints "N passed, M failed". */
#include "test.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>

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

const char *test_shared_dir(void)
{
  const char *env = getenv("AFV_SHARED");
  return env && *env ? env : "../shared";
}

int main(void)
{
  suite_core();
  suite_cli();
  suite_dynamics();
  suite_analysis();
  suite_perf();
  suite_pictures();
  suite_readers();
  suite_runjob();
  suite_hostile();
  suite_reference();
  suite_sweep();
  suite_geometry();
  suite_protocol();
  suite_docs();
  suite_api();
  suite_integrator();
  suite_paper();
  suite_relax_fire();
  suite_invariants();
  printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
  return failed ? 1 : 0;
}
