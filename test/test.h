/*
** test.h -- the smallest test harness that does the job.
**
** A test is a function; RUN(fn) calls it and counts it as passed if none of
** its CHECKs failed.  A failing CHECK prints file:line and a message (with
** the largest error where there is one).  SKIP(why) marks the current test
** skipped.  The runner ends with "N passed, M failed, K skipped" and exits
** non-zero on any failure.
*/
#ifndef AFV_TEST_H
#define AFV_TEST_H

#include <stdio.h>

extern int test_failures_in_current; /* CHECK failures in the running test */
extern int test_skipped_current;     /* the running test called SKIP */

void test_run(const char *name, void (*fn)(void));
void test_fail(const char *file, int line, const char *fmt, ...);
int  test_close(double got, double want, double rtol, double atol);

#define RUN(fn) test_run(#fn, fn)

/* CHECK(cond, printf-style message): message printed only on failure. */
#define CHECK(cond, ...) \
  do { if (!(cond)) test_fail(__FILE__, __LINE__, __VA_ARGS__); } while (0)

/* |got - want| <= atol + rtol |want|, reporting both values on failure. */
#define CHECK_CLOSE(got, want, rtol, atol, what)                             \
  do {                                                                       \
    double got_ = (got), want_ = (want);                                     \
    if (!test_close(got_, want_, (rtol), (atol)))                            \
      test_fail(__FILE__, __LINE__, "%s: got %.17g, want %.17g (diff %.3e)", \
                (what), got_, want_, got_ - want_);                          \
  } while (0)

#define SKIP(...) \
  do { test_skipped_current = 1; printf("  skip: "); printf(__VA_ARGS__); \
       printf("\n"); } while (0)

/* The golden data of other implementations (test/golden/README.md):
** "test/golden" of the repository (the suite runs from its root), or the
** directory named by the environment variable AFV_GOLDEN. */
const char *test_golden_dir(void);

/* Shared fixtures (fixtures.c).  A fixed-seed splitmix64 stream, so every
** "random" configuration is the same on every run; uniforms in [0, 1). */
#include "afv_internal.h"
#include "afv_tool.h"    /* the tests test the program's parts too */
#include "cmd/fits.h"
void               test_rng_seed(unsigned long long s);
unsigned long long test_rng_next(void);
double             test_rng_uniform(void);
double             test_rng_normal(void);        /* Box-Muller */
afv_box test_open_box(void);
afv_box test_periodic_box(double Lx, double Ly);
/* nx x ny triangular lattice of spacing D (ny even for periodicity), first
** cell at (x0, y0), rows offset by D/2; returns its periodic box. */
/* A zeroed trajectory of nframes frames of n cells in box b. */
int test_traj_alloc(afv_traj *tr, int n, int nframes, afv_box b);
afv_box test_tri_lattice(int nx, int ny, double D, double x0, double y0,
                         double *r);

/* Runs a shell command (printf-style); its exit status, -1 if it did not
** exit normally. */
int test_sh(const char *fmt, ...);
/* The configurations of the twin checks (test_reference.c, twins.c),
** numbered from 0: test_config_make fills c (r allocated; l = 1) and
** returns 1; 0 past the last, -1 out of memory. */
typedef struct test_config {
  const char *name;
  int         n;
  double     *r;
  afv_box     box;
} test_config;
int  test_config_make(int k, test_config *c);
void test_config_free(test_config *c);
/* A two-column CSV/space file (the golden data): its n rows as 2n doubles
** (malloc'd), or NULL if it cannot be read. */
double *test_read_pairs(const char *path, int *n);

/* Test suites, one per source file. */
void suite_core(void);
void suite_cli(void);
void suite_dynamics(void);
void suite_analysis(void);
void suite_perf(void);
void suite_pictures(void);
void suite_readers(void);
void suite_runjob(void);
void suite_reference(void);
void suite_sweep(void);
void suite_geometry(void);
void suite_protocol(void);
void suite_docs(void);
void suite_api(void);
void suite_paper(void);
void suite_integrator(void);
void suite_relax_fire(void);
void suite_invariants(void);
void suite_hostile(void);
void suite_messages(void);

#endif
