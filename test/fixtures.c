/* fixtures.c -- small helpers shared by the test suites. */
#define _POSIX_C_SOURCE 200809L   /* sys/wait.h */
#include "test.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <sys/wait.h>

#define PI 3.14159265358979323846

/* ---- fixed-seed random numbers: splitmix64 (Steele, Lea, Flood 2014) -- */
static unsigned long long rng_state;

void test_rng_seed(unsigned long long s) { rng_state = s; }

unsigned long long test_rng_next(void)
{
  unsigned long long z = (rng_state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double test_rng_uniform(void)
{
  return (double)(test_rng_next() >> 11) * (1.0 / 9007199254740992.0);
}

double test_rng_normal(void)
{
  double u = 1 - test_rng_uniform();          /* (0, 1]: log is finite */
  return sqrt(-2 * log(u)) * cos(2 * PI * test_rng_uniform());
}

/* ---- boxes and lattices ------------------------------------------------ */
afv_box test_open_box(void)
{
  afv_box b;
  b.periodic = 0;
  b.Lx = b.Ly = 0;
  return b;
}

afv_box test_periodic_box(double Lx, double Ly)
{
  afv_box b;
  b.periodic = 1;
  b.Lx = Lx;
  b.Ly = Ly;
  return b;
}

afv_box test_tri_lattice(int nx, int ny, double D, double x0, double y0,
                         double *r)
{
  double rowh = D * sqrt(3.0) / 2;
  int i, j;
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      r[2 * (j * nx + i)] = x0 + (i + 0.5 * (j % 2)) * D;
      r[2 * (j * nx + i) + 1] = y0 + j * rowh;
    }
  return test_periodic_box(nx * D, ny * rowh);
}

/* ---- shell commands ----------------------------------------------------- */
int test_sh(const char *fmt, ...)
{
  char cmd[4096];
  va_list ap;
  int st;
  va_start(ap, fmt);
  vsnprintf(cmd, sizeof cmd, fmt, ap);
  va_end(ap);
  st = system(cmd);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}
