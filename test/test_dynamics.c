/*
** test_dynamics.c -- the random numbers, the integrator, the relaxation and
** the `afv run` job (determinism, resume, kills, bad input).
**
** Library-level tests call dynamics.c directly; the job is driven through
** ./afv (run from the repository root, as `make test` does), writing under
** a private directory in /tmp that is removed at the end.
*/
#define _POSIX_C_SOURCE 200809L  /* fork, kill, waitpid, nanosleep, getpid */
#include "test.h"
#include "afv.h"

#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* ---- random numbers ---------------------------------------------------- */
/* Known answers of Philox4x32-10 from Random123's kat_vectors. */
static void test_philox_known_answers(void)
{
  static const uint32_t ctr[3][4] = {
    {0, 0, 0, 0},
    {0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
    {0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}};
  static const uint32_t key[3][2] = {
    {0, 0}, {0xffffffffu, 0xffffffffu}, {0xa4093822u, 0x299f31d0u}};
  static const uint32_t want[3][4] = {
    {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u},
    {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu},
    {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}};
  int v, k;
  for (v = 0; v < 3; v++) {
    uint32_t out[4];
    afv_philox4x32(ctr[v], key[v], out);
    for (k = 0; k < 4; k++)
      CHECK(out[k] == want[v][k], "vector %d word %d: got %08lx want %08lx",
            v, k, (unsigned long)out[k], (unsigned long)want[v][k]);
  }
}

/* afv_sincos against the C library's sin and cos: 2 million arguments in
** [-pi, pi], [-100, 100], (-1e6, 1e6) and the Box-Muller range (0, 2 pi],
** plus the quadrant boundaries.  Bound: an ulp of 1 (2.2e-16) for the
** rounding of the Taylor sums, half an ulp for that of the reduced
** argument, half an ulp for the library's own rounding: 4.4e-16.  (An
** error in a coefficient or in the quadrant table gives 1e-7 or more.)
** Past 1e6, inf and NaN are the library's own results. */
static void test_sincos_matches_libm(void)
{
  static const double edge[] = {0, 1e-300, 1e-8, PI / 4, PI / 2, 3 * PI / 4,
                                PI, 3 * PI / 2, 2 * PI, -PI / 2, -PI,
                                999999.5, -999999.5};
  double worst = 0, where = 0, s, c;
  int i;
  test_rng_seed(11);
  for (i = 0; i < 2000000 + 13; i++) {
    double u = test_rng_uniform(), x;
    switch (i % 4) {
    case 0: x = PI * (2 * u - 1); break;
    case 1: x = 100 * (2 * u - 1); break;
    case 2: x = 999999 * (2 * u - 1); break;
    default: x = 2 * PI * (1 - u); break;
    }
    if (i >= 2000000) x = edge[i - 2000000];
    afv_sincos(x, &s, &c);
    if (fabs(s - sin(x)) > worst || fabs(c - cos(x)) > worst) {
      worst = fmax(fabs(s - sin(x)), fabs(c - cos(x)));
      where = x;
    }
  }
  CHECK(worst <= 4.4e-16, "largest error %.3g at x = %.17g", worst, where);
  afv_sincos(3e6, &s, &c);
  CHECK(s == sin(3e6) && c == cos(3e6), "past the fast range");
  afv_sincos(NAN, &s, &c);
  CHECK(isnan(s) && isnan(c), "NaN in, NaN out");
  afv_sincos(INFINITY, &s, &c);
  CHECK(isnan(s) && isnan(c), "inf in, NaN out");
}

/* The distance of b from a in units in the last place of a (a finite,
** normal): |b - a| / ulp(a), with ulp(a) the gap above |a|. */
static double ulps(double a, double b)
{
  double gap = nextafter(fabs(a), HUGE_VAL) - fabs(a);
  return fabs(b - a) / gap;
}

/* afv_log (fdlibm's e_log.c, error < 1 ulp) against the C library's log
** (glibc's is good to about half an ulp), to within 1 ulp: 10^6 uniforms
** of the Box-Muller range,
** (k + 1) 2^-53 for k from 53 random bits (the C library's log and
** afv_log differ in the last bit for some of them, which is why afv has
** its own), 10^6 normal doubles of every binade (2^-1022 .. 2^1023), and
** the edges: 1, 2^-53, DBL_MIN, the largest double, a subnormal, 0, a
** negative number, inf and NaN.  (Lg5 = 0.18 instead of 0.1818..: 1.25e5
** ulps.) */
static void test_log_matches_libm(void)
{
  double worst = 0, where = 0, x;
  int i;
  test_rng_seed(12);
  for (i = 0; i < 2000000; i++) {
    double u = test_rng_uniform();      /* (0, 1) */
    if (i % 2 == 0)                     /* the noise's uniforms */
      x = (floor(u * 9007199254740992.0) + 1) / 9007199254740992.0;
    else                                /* any binade */
      x = ldexp(1 + test_rng_uniform(), (int)floor(u * 2046) - 1022);
    if (ulps(log(x), afv_log(x)) > worst) {
      worst = ulps(log(x), afv_log(x));
      where = x;
    }
  }
  CHECK(worst <= 1, "largest difference %.3g ulp at x = %.17g", worst, where);
  CHECK(afv_log(1) == 0 && afv_log(1.0 / 9007199254740992.0)
        == log(1.0 / 9007199254740992.0), "log 1, log 2^-53");
  CHECK(ulps(log(DBL_MIN), afv_log(DBL_MIN)) <= 1
        && ulps(log(DBL_MAX), afv_log(DBL_MAX)) <= 1
        && ulps(log(4.9e-324), afv_log(4.9e-324)) <= 1
        && ulps(log(3e-310), afv_log(3e-310)) <= 1, "the extremes");
  CHECK(afv_log(0) == -HUGE_VAL && afv_log(-0.0) == -HUGE_VAL, "log 0");
  CHECK(isnan(afv_log(-1)) && isnan(afv_log(NAN))
        && afv_log(HUGE_VAL) == HUGE_VAL, "negative, NaN, inf");
}

/* afv_hypot against the C library's hypot (correctly rounded or nearly):
** 10^6 vectors with components of every sign and of magnitudes 1e-3 ..
** 1e3 (afv's lengths), and vectors where the squares would overflow or
** underflow (1e200, 1e-200, the largest double, subnormals): within 1 ulp.
** An infinite component gives inf, even with a NaN. */
static void test_hypot_matches_libm(void)
{
  static const double edge[][2] = {{1e200, 1e200}, {3e-200, -4e-200},
    {DBL_MAX, 1}, {DBL_MAX / 2, DBL_MAX / 3}, {4.9e-324, 4.9e-324},
    {1e-310, 1e-300}, {0, 0}, {-0.0, 5}, {3, 4}, {1e160, 1e-160}};
  double worst = 0, where = 0;
  int i;
  test_rng_seed(13);
  for (i = 0; i < 1000000 + 10; i++) {
    double x, y, h;
    if (i < 1000000) {
      x = (2 * test_rng_uniform() - 1) * pow(10, 6 * test_rng_uniform() - 3);
      y = (2 * test_rng_uniform() - 1) * pow(10, 6 * test_rng_uniform() - 3);
    } else {
      x = edge[i - 1000000][0];
      y = edge[i - 1000000][1];
    }
    h = hypot(x, y);
    if (h > 0 ? ulps(h, afv_hypot(x, y)) > worst : afv_hypot(x, y) != 0) {
      worst = h > 0 ? ulps(h, afv_hypot(x, y)) : HUGE_VAL;
      where = x;
    }
  }
  CHECK(worst <= 1, "largest difference %.3g ulp at x = %.17g", worst, where);
  CHECK(afv_hypot(HUGE_VAL, NAN) == HUGE_VAL
        && afv_hypot(NAN, -HUGE_VAL) == HUGE_VAL, "inf with NaN");
  CHECK(isnan(afv_hypot(NAN, 1)) && isnan(afv_hypot(1, NAN)), "NaN");
}

/* The noise is the library's own arithmetic: every normal of 10^6 pairs is
** sqrt(-2 afv_log(u0)) times afv_sincos(2 pi u1)'s cosine or sine, bit for
** bit, with u the pair's uniforms.  (afv 0.4.0's, with the C library's log,
** fails this for 36385 of these 10^6 pairs with glibc 2.36 on a CPU with
** FMA.) */
static void test_noise_uses_own_log(void)
{
  int bad = 0, first = -1;
  uint32_t pair;
  for (pair = 0; pair < 1000000; pair++) {
    double u[2], z[2], rho, s, c;
    afv_rng_uniform2(5, pair, 17, AFV_RNG_NOISE, u);
    afv_rng_normal2(5, pair, 17, AFV_RNG_NOISE, z);
    rho = sqrt(-2.0 * afv_log(u[0]));
    afv_sincos(2 * PI * u[1], &s, &c);
    if (z[0] != rho * c || z[1] != rho * s) {
      if (first < 0) first = (int)pair;
      bad++;
    }
  }
  CHECK(bad == 0, "%d of 10^6 pairs are not afv_log's (the first: %d)", bad,
        first);
}

/* Mean, variance and tail of the normals, and the range of the uniforms:
** each within 5 standard errors of the exact value. */
static void test_normal_statistics(void)
{
  const int n = 200000;
  double s1 = 0, s2 = 0, s4 = 0, tail = 0, umin = 1, umax = 0, mean, var;
  int i;
  for (i = 0; i < n; i++) {
    double z = afv_rng_normal(7, (uint32_t)(i % 1000), (unsigned)(i / 1000),
                              AFV_RNG_NOISE), u[2];
    s1 += z;
    s2 += z * z;
    s4 += z * z * z * z;
    tail += fabs(z) > 2;
    afv_rng_uniform2(7, (uint32_t)i, 3, AFV_RNG_INIT_POS, u);
    if (u[0] < umin) umin = u[0];
    if (u[1] > umax) umax = u[1];
    CHECK(u[0] > 0 && u[0] <= 1 && u[1] > 0 && u[1] <= 1, "uniform %g %g "
          "outside (0, 1]", u[0], u[1]);
  }
  mean = s1 / n;
  var = s2 / n - mean * mean;
  CHECK(fabs(mean) < 5 / sqrt(n), "mean %g, 5 sigma %g", mean, 5 / sqrt(n));
  CHECK(fabs(var - 1) < 5 * sqrt(2.0 / n), "variance %g, 5 sigma %g", var,
        5 * sqrt(2.0 / n));
  CHECK(fabs(s4 / n - 3) < 5 * sqrt(96.0 / n), "4th moment %g, want 3",
        s4 / n);
  /* P(|z| > 2) = erfc(sqrt 2) = 0.0455003 */
  CHECK(fabs(tail / n - 0.0455003) < 5 * sqrt(0.0455 * 0.9545 / n),
        "P(|z|>2) = %g, want 0.0455", tail / n);
  CHECK(umin < 1e-4 && umax > 1 - 1e-4, "uniform range [%g, %g]", umin, umax);
}

/* Streams of neighbouring cells, steps, purposes and seeds are
** uncorrelated (|r| < 5/sqrt(n)), and a stream is a pure function. */
static void test_streams_independent(void)
{
  const int n = 50000;
  double c[4] = {0, 0, 0, 0}, bound = 5 / sqrt(n);
  int i, k;
  for (i = 0; i < n; i++) {
    double z = afv_rng_normal(1, (uint32_t)i, 10, AFV_RNG_NOISE);
    c[0] += z * afv_rng_normal(1, (uint32_t)i + 1, 10, AFV_RNG_NOISE);
    c[1] += z * afv_rng_normal(1, (uint32_t)i, 11, AFV_RNG_NOISE);
    c[2] += z * afv_rng_normal(2, (uint32_t)i, 10, AFV_RNG_NOISE);
    c[3] += z * afv_rng_normal(1, (uint32_t)i, 10, AFV_RNG_INIT_ANGLE);
    CHECK(z == afv_rng_normal(1, (uint32_t)i, 10, AFV_RNG_NOISE),
          "stream not reproducible at %d", i);
  }
  for (k = 0; k < 4; k++)
    CHECK(fabs(c[k] / n) < bound, "correlation %d: %g (bound %g)", k,
          c[k] / n, bound);
  /* the high word of the step counts */
  CHECK(afv_rng_normal(1, 0, 5, 1) != afv_rng_normal(1, 0, 5ULL + (1ULL << 32),
                                                     1), "step high word");
}

/* ---- helpers ----------------------------------------------------------- */
static void cluster_system(int n, afv_box *b, afv_params *p, double *r)
{
  afv_params_default(p);
  p->P0 = 4;
  if (b->periodic) b->Lx = b->Ly = sqrt(n * PI / 0.5);
  afv_init_lattice(n, 1.8, b, r);
}

/* ---- the integrator ---------------------------------------------------- */
static void test_sim_deterministic(void)
{
  enum { N = 100 };
  afv_box b = {1, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s1, s2;
  double r[2 * N], th[N];
  int k, same = 1;
  memset(&s1, 0, sizeof s1);
  memset(&s2, 0, sizeof s2);
  cluster_system(N, &b, &p, r);
  afv_init_angles(N, 3, th);
  afv_dyn_default(&d);
  d.v0 = 0.3;
  d.seed = 3;
  CHECK(afv_sim_init(&s1, N, r, th, &p, &b, &d) == AFV_OK, "init");
  CHECK(afv_sim_init(&s2, N, r, th, &p, &b, &d) == AFV_OK, "init");
  for (k = 0; k < 200; k++) {
    CHECK(afv_sim_step(&s1) == AFV_OK, "step %d", k);
    CHECK(afv_sim_step(&s2) == AFV_OK, "step %d", k);
  }
  CHECK(memcmp(s1.r, s2.r, sizeof r) == 0, "same seed, different positions");
  CHECK(memcmp(s1.theta, s2.theta, sizeof th) == 0, "same seed, angles");
  CHECK(s1.step == 200 && s1.t == 200 * 0.01, "step %lld t %.17g", s1.step,
        s1.t);
  /* another seed: other angles after the first step */
  d.seed = 4;
  CHECK(afv_sim_init(&s2, N, r, th, &p, &b, &d) == AFV_OK, "init");
  for (k = 0; k < 200; k++) afv_sim_step(&s2);
  for (k = 0; k < N; k++) same &= s1.theta[k] == s2.theta[k];
  CHECK(!same, "seeds 3 and 4 give the same angles");
  afv_sim_free(&s1);
  afv_sim_free(&s2);
}

/* A runaway step (a move beyond AFV_RUNAWAY_MOVE l), or a NaN force, is
** refused with the cell named and the state unchanged. */
static void test_sim_refuses_unstable_step(void)
{
  enum { N = 50 };
  afv_box b = {0, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s;
  double r[2 * N], r0[2 * N];
  memset(&s, 0, sizeof s);
  cluster_system(N, &b, &p, r);
  afv_dyn_default(&d);
  d.v0 = 2 * AFV_RUNAWAY_MOVE;
  d.dt = 1.0;       /* v0 dt = 2 AFV_RUNAWAY_MOVE l */
  CHECK(afv_sim_init(&s, N, r, NULL, &p, &b, &d) == AFV_OK, "init");
  memcpy(r0, s.r, sizeof r0);
  CHECK(afv_sim_step(&s) == AFV_EUNSTABLE, "runaway step accepted");
  CHECK(s.bad_cell >= 0 && s.bad_disp > AFV_RUNAWAY_MOVE, "bad cell %d "
        "disp %g", s.bad_cell, s.bad_disp);
  CHECK(memcmp(r0, s.r, sizeof r0) == 0 && s.step == 0, "state changed");
  s.dyn.dt = 0.01;
  s.dyn.v0 = 0.6;
  s.f[2 * 7] = NAN;
  CHECK(afv_sim_step(&s) == AFV_EUNSTABLE && s.bad_cell == 7
        && isnan(s.bad_disp), "NaN force: status, cell %d", s.bad_cell);
  afv_sim_free(&s);
}

/* Free active Brownian particles (KA = KP = Lambda = 0: E = 0, F = 0).
** Exact: MSD(t) = 2 v0^2/Dr^2 (Dr t - 1 + exp(-Dr t)) and
** <cos(th(t) - th(0))> = exp(-Dr t).  Error bar: the sample standard
** deviation over the cells / sqrt(cells) (cells are independent).
** Criterion: |sample - exact| <= 4 error bars at every checked time.  The
** Euler scheme's own MSD, v0^2 dt^2 (n + 2 sum_m (n-m) exp(-Dr dt m)),
** differs from the formula by 4e-5 relative at t = 1 (less later), far
** below the error bars (0.5% at t = 1, 1.5% at t = 5); a 10% error in the
** noise variance shows as > 5 error bars. */
static void test_free_abp_msd_and_polarity(void)
{
  enum { N = 2000, GRID = 45 };
  const double v0 = 1, Dr = 1, dt = 0.01;
  static const int check_at[] = {100, 200, 300, 500};
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_dyn d;
  afv_sim s;
  double *r0 = malloc(2 * N * sizeof(double)), *th0 = malloc(N * sizeof(double));
  int i, k, c = 0;
  memset(&s, 0, sizeof s);
  afv_params_default(&p);
  p.KA = p.KP = p.Lambda = 0;
  for (i = 0; i < N; i++) {     /* a grid of spacing 3l: isolated cells */
    r0[2*i] = 3.0 * (i % GRID);
    r0[2*i+1] = 3.0 * (i / GRID);
  }
  afv_init_angles(N, 11, th0);
  afv_dyn_default(&d);
  d.v0 = v0;
  d.Dr = Dr;
  d.dt = dt;
  d.seed = 11;
  CHECK(afv_sim_init(&s, N, r0, th0, &p, &b, &d) == AFV_OK, "init");
  for (k = 1; k <= check_at[3]; k++) {
    double t, msd = 0, m2 = 0, cs = 0, cs2 = 0, want, se, pw, pse;
    if (afv_sim_step(&s) != AFV_OK) {
      CHECK(0, "step %d failed", k);
      break;
    }
    if (k != check_at[c]) continue;
    c++;
    t = k * dt;
    for (i = 0; i < N; i++) {
      double dx = s.r[2*i] - r0[2*i], dy = s.r[2*i+1] - r0[2*i+1];
      double q = dx * dx + dy * dy, cc = cos(s.theta[i] - th0[i]);
      msd += q;
      m2 += q * q;
      cs += cc;
      cs2 += cc * cc;
    }
    msd /= N;
    cs /= N;
    se = sqrt((m2 / N - msd * msd) / (N - 1));
    pse = sqrt((cs2 / N - cs * cs) / (N - 1));
    want = 2 * v0 * v0 / (Dr * Dr) * (Dr * t - 1 + exp(-Dr * t));
    pw = exp(-Dr * t);
    printf("  t %4.1f  MSD %.4f exact %.4f  (%+.2f err bars)   "
           "C %.4f exact %.4f (%+.2f)\n", t, msd, want, (msd - want) / se,
           cs, pw, (cs - pw) / pse);
    CHECK(fabs(msd - want) <= 4 * se, "t %g: MSD %g, exact %g, error bar %g",
          t, msd, want, se);
    CHECK(fabs(cs - pw) <= 4 * pse, "t %g: polarity %g, exact %g, bar %g", t,
          cs, pw, pse);
  }
  CHECK(c == 4, "only %d of 4 times checked", c);
  afv_sim_free(&s);
  free(r0);
  free(th0);
}

/* Per-cell v0_i and Dr_i, free cells: v0_i = 0 stays put, Dr_i = 0 keeps
** its angle, and v0_i > 0 with Dr_i = 0 moves ballistically by v0_i t.
** The arrays are copied at init (changing them afterwards has no effect). */
static void test_per_cell_v0_and_Dr(void)
{
  enum { N = 40 };
  afv_box b = {0, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s;
  double r[2 * N], th[N], v0[N], Dr[N], err = 0;
  int i, k;
  memset(&s, 0, sizeof s);
  afv_params_default(&p);
  p.KA = p.KP = p.Lambda = 0;
  for (i = 0; i < N; i++) {
    r[2*i] = 5.0 * i;
    r[2*i+1] = 0;
    th[i] = 0.1 * i;
    v0[i] = i % 2 ? 0.7 : 0;
    Dr[i] = i % 3 ? 0 : 0.5;
  }
  afv_dyn_default(&d);
  d.v0_i = v0;
  d.Dr_i = Dr;
  d.v0 = 100;    /* the scalars must be ignored */
  d.Dr = 100;
  CHECK(afv_sim_init(&s, N, r, th, &p, &b, &d) == AFV_OK, "init");
  for (i = 0; i < N; i++) v0[i] = Dr[i] = 1e9;
  for (k = 0; k < 100; k++) CHECK(afv_sim_step(&s) == AFV_OK, "step %d", k);
  for (i = 0; i < N; i++) {
    double dx = s.r[2*i] - r[2*i], dy = s.r[2*i+1] - r[2*i+1];
    if (i % 2 == 0) err = fmax(err, hypot(dx, dy));
    if (i % 3) err = fmax(err, fabs(s.theta[i] - th[i]));
    if (i % 2 && i % 3) {
      err = fmax(err, fabs(dx - 0.7 * 1.0 * cos(th[i])));
      err = fmax(err, fabs(dy - 0.7 * 1.0 * sin(th[i])));
    }
    if (i % 3 == 0)
      CHECK(s.theta[i] != th[i], "cell %d with Dr 0.5 kept its angle", i);
  }
  CHECK(err < 1e-12, "largest deviation %g", err);
  afv_sim_free(&s);
}

/* At v0 = 0, Dr = 0 one step changes E by -mu |F|^2 dt + O(dt^2): the
** remainder must shrink 4-fold when dt halves (first-order agreement). */
static void test_energy_decrease_first_order(void)
{
  enum { N = 40 };
  afv_box b = {0, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s;
  double r[2 * N], rem[3], dts[3] = {4e-5, 2e-5, 1e-5};
  int k, i;
  memset(&s, 0, sizeof s);
  cluster_system(N, &b, &p, r);
  for (i = 0; i < 2 * N; i++) r[i] *= 0.9;   /* compressed: forces */
  p.cap = 0;                                  /* the exact gradient */
  afv_dyn_default(&d);
  d.Dr = 0;
  d.mu = 0.7;
  for (k = 0; k < 3; k++) {
    double E0, F2 = 0, pred;
    d.dt = dts[k];
    CHECK(afv_sim_init(&s, N, r, NULL, &p, &b, &d) == AFV_OK, "init");
    E0 = s.geom.energy;
    for (i = 0; i < 2 * N; i++) F2 += s.f[i] * s.f[i];
    CHECK(afv_sim_step(&s) == AFV_OK, "step");
    pred = -d.mu * F2 * d.dt;
    rem[k] = (s.geom.energy - E0) - pred;
    CHECK(fabs(rem[k]) < 1e-3 * fabs(pred), "dt %g: dE %.10g, -mu|F|^2 dt "
          "%.10g", d.dt, s.geom.energy - E0, pred);
  }
  CHECK(fabs(rem[1] / rem[0] - 0.25) < 0.02 && fabs(rem[2] / rem[1] - 0.25)
        < 0.02, "remainders %g %g %g do not scale as dt^2", rem[0], rem[1],
        rem[2]);
  afv_sim_free(&s);
}

/* ---- relaxation -------------------------------------------------------- */
typedef struct trace {
  double last;   /* energy after the previous accepted step */
  double worst;  /* largest increase seen (<= 0 if none) */
  long calls;    /* accepted steps */
} trace;

static void trace_energy(void *ctx, long iter, double E, double fmax)
{
  trace *T = ctx;
  (void)iter;
  (void)fmax;
  if (E - T->last > T->worst) T->worst = E - T->last;
  T->last = E;
  T->calls++;
}

static void relax_case(int periodic, int random_start, int exact)
{
  enum { N = 120 };
  afv_box b = {0, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s;
  afv_relax_report rep;
  trace T;
  double r[2 * N], tol = 1e-7, *f2 = malloc(2 * N * sizeof(double));
  afv_geom g;
  int i;
  memset(&s, 0, sizeof s);
  memset(&g, 0, sizeof g);
  b.periodic = periodic;
  cluster_system(N, &b, &p, r);
  if (random_start) afv_init_random(N, 5, &b, 15, r);
  if (exact) p.cap = 0;
  else p.cap = 0.1;
  afv_dyn_default(&d);
  CHECK(afv_sim_init(&s, N, r, NULL, &p, &b, &d) == AFV_OK, "init");
  T.last = s.geom.energy;
  T.worst = -1;
  T.calls = 0;
  CHECK(afv_relax(&s, tol, 100000, &rep, trace_energy, &T) == AFV_OK,
        "relax");
  printf("  %s %s start: %ld steps, E %.6f -> %.6f, max|F| %.2e, largest "
         "rise of E in a step %.2e\n", periodic ? "periodic" : "open",
         random_start ? "random" : "cluster", rep.iterations, rep.energy0,
         rep.energy, rep.max_force, T.worst);
  /* overdamped steps of dt lower E by ~ dt |F|^2 while dt is below the
  ** stability limit; a rise beyond rounding means a step overshot */
  CHECK(T.worst <= 1e-12 * fabs(rep.energy0), "energy rose by %g during "
        "relaxation", T.worst);
  CHECK(rep.energy <= rep.energy0 && T.calls > 0, "E %g -> %g", rep.energy0,
        rep.energy);
  CHECK(T.calls == rep.iterations, "monitor called %ld times for %ld steps",
        T.calls, rep.iterations);
  CHECK(rep.converged && rep.max_force <= tol, "max |F| %g > tol %g",
        rep.max_force, tol);
  /* the reported force is the force of the final state, recomputed */
  CHECK(afv_compute(&g, N, s.r, &p, &b, f2) == AFV_OK, "compute");
  for (i = 0; i < N; i++)
    CHECK(hypot(f2[2*i], f2[2*i+1]) <= tol, "cell %d: |F| %g > tol", i,
          hypot(f2[2*i], f2[2*i+1]));
  CHECK(s.step == 0 && s.t == 0, "relaxation counted as dynamics");
  afv_geom_free(&g);
  afv_sim_free(&s);
  free(f2);
}

static void test_relax_energy_never_increases(void)
{
  relax_case(0, 0, 1);
  relax_case(1, 0, 0);
  relax_case(1, 1, 1);
}

/* A jump is a step that moves some cell farther than half a cell radius
** (AFV_MAX_STEP_DISP = 0.5 l: the forces change on the scale l): two free
** cells (no force) crawling v0 dt = 0.4 l a step take no jump, at 0.6 l
** every step is one. */
static int free_jumps(double v0)
{
  static const double r[4] = {0, 0, 10, 0};
  afv_box b = {0, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim *s = afv_sim_new();
  long long jumps = -1;
  int k;
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.v0 = v0;
  d.Dr = 0;
  if (s && afv_sim_init(s, 2, r, NULL, &p, &b, &d) == AFV_OK) {
    for (k = 0; k < 3; k++) CHECK(afv_sim_step(s) == AFV_OK, "step %d", k);
    CHECK(fabs(afv_sim_largest_move(s) - v0 * d.dt) < 1e-12,
          "largest move %.17g, want %g", afv_sim_largest_move(s), v0 * d.dt);
    jumps = afv_sim_jumps(s);
  }
  afv_sim_delete(s);
  return (int)jumps;
}

static void test_jump_is_a_move_over_half_l(void)
{
  int below = free_jumps(40), above = free_jumps(60);
  CHECK(below == 0, "moves of 0.4 l: %d jumps, want 0", below);
  CHECK(above == 3, "moves of 0.6 l: %d jumps in 3 steps, want 3", above);
}

/* Above P0* the relaxed tissue sits on a kink of E (a triple junction on a
** cell's circle), where the force does not vanish: the relaxation must
** stop there by its criterion (afv.h: every cell's mean force over a
** window small, and small against max |F|; the mean energy steady; max |F|
** of order 1), report the figures, and the stopping point must really be a
** kink (one-sided derivatives differ, so the analytic force disagrees with
** central differences there). */
static void test_relax_stops_at_kink(void)
{
  enum { N = 60 };
  afv_box b = {1, 0, 0};
  afv_params p;
  afv_dyn d;
  afv_sim s;
  afv_relax_report rep;
  afv_check_report chk;
  double r[2 * N];
  memset(&s, 0, sizeof s);
  cluster_system(N, &b, &p, r);
  p.P0 = 6;
  p.cap = 0;
  afv_dyn_default(&d);
  CHECK(afv_sim_init(&s, N, r, NULL, &p, &b, &d) == AFV_OK, "init");
  CHECK(afv_relax(&s, 1e-6, 100000, &rep, NULL, NULL) == AFV_OK, "relax");
  printf("  P0 6: %ld steps, at_kink %d, max|F| %.3g, mean force %.2e, "
         "energy change %.2e\n", rep.iterations, rep.at_kink, rep.max_force,
         rep.drift, rep.drop);
  CHECK(rep.at_kink && !rep.converged && rep.iterations <= 20000,
        "at_kink %d converged %d after %ld steps", rep.at_kink,
        rep.converged, rep.iterations);
  CHECK(rep.max_force <= AFV_RELAX_KINK_FORCE
        && rep.drift <= AFV_RELAX_KINK_DRIFT
        && rep.drift <= AFV_RELAX_KINK_CHATTER * rep.max_force
        && fabs(rep.drop) <= AFV_RELAX_KINK_DROP, "kink claimed outside the "
        "criterion: max|F| %g, mean force %g, energy change %g",
        rep.max_force, rep.drift, rep.drop);
  /* The stop is not exactly on the kink but within one chatter of it
  ** (about dt |F| = 0.005 l): the force of the cell with the largest force
  ** turns back (negative dot product) within the next few steps of the
  ** flow, and central differences over a span of 0.02 l, across the kink,
  ** disagree with the one-sided force. */
  {
    double f0[2], most = 0;
    int i, worst = 0, k, turned = 0;
    for (i = 0; i < N; i++)
      if (hypot(s.f[2*i], s.f[2*i+1]) > most) {
        most = hypot(s.f[2*i], s.f[2*i+1]);
        worst = i;
      }
    f0[0] = s.f[2 * worst];
    f0[1] = s.f[2 * worst + 1];
    CHECK(afv_gradient_check(N, s.r, &p, &b, 1e-2, &chk) == AFV_OK,
          "check");
    CHECK(chk.max_rel > 0.1, "no kink at the stop: force vs differences "
          "over 0.02 l %g", chk.max_rel);
    s.dyn.v0 = 0;
    for (k = 0; k < 10 && !turned; k++) {
      CHECK(afv_sim_step(&s) == AFV_OK, "flow step");
      turned = s.f[2 * worst] * f0[0] + s.f[2 * worst + 1] * f0[1] < 0;
    }
    CHECK(turned, "the force on cell %d (%g) never turned back: not a "
          "chatter", worst, most);
  }
  afv_sim_free(&s);
}

/* ---- initial configurations -------------------------------------------- */
static void test_cluster_start(void)
{
  enum { N = 400 };
  afv_box b = {1, 0, 0};
  double r[2 * N], dmin = 1e9, cx = 0, cy = 0, rmax = 0, L;
  int i, j;
  b.Lx = b.Ly = L = sqrt(N * PI / 0.5);
  CHECK(afv_init_lattice(N, 1.8, &b, r) == AFV_OK, "init");
  for (i = 0; i < N; i++) {
    cx += r[2*i] / N;
    cy += r[2*i+1] / N;
    for (j = 0; j < i; j++) {
      double d = hypot(r[2*i] - r[2*j], r[2*i+1] - r[2*j+1]);
      if (d < dmin) dmin = d;
    }
  }
  for (i = 0; i < N; i++) {
    double q = hypot(r[2*i] - L / 2, r[2*i+1] - L / 2);
    if (q > rmax) rmax = q;
  }
  CHECK_CLOSE(dmin, 1.8, 1e-12, 0, "nearest-neighbour distance");
  CHECK(fabs(cx - L / 2) < 0.5 && fabs(cy - L / 2) < 0.5, "centre %g %g",
        cx, cy);
  /* compact: the disk holding N lattice cells, plus one spacing */
  CHECK(rmax < sqrt(N * 1.8 * 1.8 * 0.8660254 / PI) + 1.8, "radius %g", rmax);
  /* a box too small for spacing 1.8: the spacing shrinks, nothing overlaps
  ** its periodic image */
  b.Lx = b.Ly = 30;
  afv_init_lattice(N, 1.8, &b, r);
  for (i = 0; i < N; i++)
    CHECK(hypot(r[2*i] - 15, r[2*i+1] - 15) < 15, "cell %d outside", i);
}

/* A large cluster gets N distinct sites (an early version generated only
** the lattice rows |j| <= R and left ~0.1% of the cells of N = 40000 on
** top of each other): the geometry accepts it, and every cell has a
** neighbour at exactly the lattice spacing. */
static void test_large_cluster_start(void)
{
  enum { N = 40000 };
  afv_box b = {0, 0, 0};
  afv_geom g;
  double *r = malloc(2 * N * sizeof(double));
  int i, st, far = 0;
  memset(&g, 0, sizeof g);
  CHECK(r && afv_init_lattice(N, 1.8, &b, r) == AFV_OK, "init");
  st = r ? afv_neighbours(&g, N, r, 1.0, &b) : AFV_ENOMEM;
  CHECK(st == AFV_OK, "neighbours: %s (cells %d, %d)", afv_strerror(st),
        g.bad_i, g.bad_j);
  for (i = 0; st == AFV_OK && i < N; i++) {
    double dmin = 1e9;
    int s;
    for (s = g.nbr_start[i]; s < g.nbr_end[i]; s++)
      dmin = fmin(dmin, hypot(g.nbr_d[2*s], g.nbr_d[2*s+1]));
    if (fabs(dmin - 1.8) > 1e-9) far++;
  }
  CHECK(far == 0, "%d cells without a neighbour at the spacing", far);
  afv_geom_free(&g);
  free(r);
}

/* ---- the afv run job --------------------------------------------------- */
static char tmpdir[256];

/* Runs a shell command quietly; returns its exit status (-1 if killed). */
#define sh test_sh

static char *slurp(const char *path, long *len)
{
  FILE *fp = fopen(path, "rb");
  char *buf;
  long n;
  *len = -1;
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  buf = malloc((size_t)n + 1);
  if (buf && fread(buf, 1, (size_t)n, fp) != (size_t)n) n = -1;
  fclose(fp);
  if (buf) buf[n < 0 ? 0 : n] = 0;
  *len = n;
  return buf;
}

/* 1 if DIR_A/name and DIR_B/name exist and are byte-identical. */
static int same_file(const char *a, const char *b, const char *name)
{
  char pa[512], pb[512];
  long na, nb;
  char *x, *y;
  int same;
  snprintf(pa, sizeof pa, "%s/%s/%s", tmpdir, a, name);
  snprintf(pb, sizeof pb, "%s/%s/%s", tmpdir, b, name);
  x = slurp(pa, &na);
  y = slurp(pb, &nb);
  same = x && y && na == nb && memcmp(x, y, (size_t)na) == 0;
  free(x);
  free(y);
  return same;
}

static int exists(const char *sub)
{
  char p[512];
  struct stat sb;
  snprintf(p, sizeof p, "%s/%s", tmpdir, sub);
  return stat(p, &sb) == 0;
}

/* A small fast system: 64 cells at phi 0.5 (L = 20), output every few
** steps, so that every kind of record is exercised. */
#define SMALL "--N 64 --P0 4.5 --v0 0.3 --sample_every 5 --frame_every 10 " \
              "--checkpoint_every 50 --svg_every 100 --xyz 1 --quiet"

static const char *const run_files[] = {
  "trajectory.dat", "observables.csv", "checkpoint.txt", "params.txt",
  "trajectory.xyz", "final.svg"};

static void test_run_deterministic(void)
{
  int k;
  CHECK(sh("./afv run " SMALL " --steps 200 --out %s/a", tmpdir) == 0, "run a");
  CHECK(sh("./afv run " SMALL " --steps 200 --out %s/b", tmpdir) == 0, "run b");
  CHECK(sh("./afv run " SMALL " --steps 200 --seed 2 --out %s/c", tmpdir)
        == 0, "run c");
  for (k = 0; k < 6; k++)
    CHECK(same_file("a", "b", run_files[k]), "%s differs between two runs "
          "with the same seed", run_files[k]);
  CHECK(exists("a/snap_000000100.svg") && exists("a/snap_000000000.svg"),
        "snapshots missing");
  CHECK(!same_file("a", "c", "trajectory.dat"), "seeds 1 and 2 agree");
  /* params.txt repeats the run exactly */
  CHECK(sh("./afv run --config %s/a/params.txt --out %s/d", tmpdir, tmpdir)
        == 0, "run from params.txt");
  for (k = 0; k < 6; k++)
    CHECK(same_file("a", "d", run_files[k]), "%s: --config params.txt does "
          "not repeat the run", run_files[k]);
}

static void test_run_resume_equals_straight_run(void)
{
  int k;
  CHECK(sh("./afv run " SMALL " --steps 300 --out %s/s", tmpdir) == 0,
        "straight run");
  CHECK(sh("./afv run " SMALL " --steps 150 --out %s/r", tmpdir) == 0,
        "first half");
  CHECK(sh("./afv run --resume %s/r --steps 150 --quiet", tmpdir) == 0,
        "resume");
  for (k = 0; k < 6; k++)
    CHECK(same_file("s", "r", run_files[k]), "%s: 150 + resumed 150 steps "
          "differs from 300 steps", run_files[k]);
  /* a completed run resumed without --steps has nothing to do */
  CHECK(sh("./afv run --resume %s/r --quiet", tmpdir) == 0, "resume done");
  CHECK(same_file("s", "r", "trajectory.dat"), "changed by a no-op resume");
}

/* Per-cell values through a CELLS file; the copy in DIR repeats the run. */
static void test_run_cells_file(void)
{
  char path[512];
  FILE *fp;
  int i;
  snprintf(path, sizeof path, "%s/mix.txt", tmpdir);
  fp = fopen(path, "w");
  fprintf(fp, "# v0 P0 Dr\n");
  for (i = 0; i < 64; i++)
    fprintf(fp, "%g %g %g\n", i % 2 ? 0.5 : 0.1, i % 2 ? 5.0 : 4.0,
            i % 3 ? 0.1 : 0.5);
  fclose(fp);
  CHECK(sh("./afv run " SMALL " --steps 100 --cells %s --out %s/m1", path,
           tmpdir) == 0, "run with cells");
  CHECK(exists("m1/cells.txt"), "cells.txt not copied");
  CHECK(sh("./afv run --config %s/m1/params.txt --out %s/m2", tmpdir,
           tmpdir) == 0, "rerun");
  CHECK(same_file("m1", "m2", "trajectory.dat"), "rerun with cells differs");
  CHECK(!same_file("m1", "a", "observables.csv"), "per-cell values ignored");
}

/* Bad options and files: exit 2, a message naming the problem, and no
** output directory. */
static void test_run_bad_input(void)
{
  static const char *const cases[][2] = {
    {"--dt 0", "dt"}, {"--dt -1", "dt"}, {"--N 0", "N"},
    {"--phi 0", "phi"}, {"--phi 1.5", "phi"}, {"--l 0", "l"},
    {"--wrong 1", "--wrong"}, {"--N 2", "phi"}, {"--dt abc", "dt"},
    {"--box square", "box"}, {"--init file", "init"}, {"--steps -5", "steps"},
    {"--KA -1", "KA"}, {"--Dr -0.1", "Dr"}, {"--mu 0", "mu"},
    {"--relax_tol 0", "relax_tol"}, {"--seed -3", "seed"},
    {"--cells /nonexistent/x", "/nonexistent/x"}, {"--N", "needs a value"},
    {"--config /nonexistent/c", "/nonexistent/c"},
    {"--config @/cfg1", "cfg1:3: unknown key 'colour'"},
    {"--config @/cfg2", "cfg2:1: dt"},
    {"--config @/cfg3", "cfg3:2: steps: expected one value"},
    {"--cells @/cells1", "cells1:1: expected a header"},
    {"--cells @/cells2", "cells2:3: expected 3 columns"},
    {"--cells @/cells3", "cells3:2: x: 'abc' is not a number"},
    {"--cells @/cells4 --N 5", "N: 5"},
    {"--cells @/cells5 --box open", "same centre"}};
  static const char *const files[][2] = {
    {"cfg1", "# a comment\nN 64\ncolour red\n"},
    {"cfg2", "dt 0\n"},
    {"cfg3", "N 64\nsteps\n"},
    {"cells1", "x y\n1 2\n"},
    {"cells2", "# x y v0\n0 0 1\n3 0\n"},
    {"cells3", "# x y\nabc 0\n"},
    {"cells4", "# P0\n4\n4\n"},
    {"cells5", "# x y\n0 0\n0 0\n"}};
  char path[512], *err;
  long len;
  size_t c;
  for (c = 0; c < sizeof files / sizeof files[0]; c++) {
    FILE *fp;
    snprintf(path, sizeof path, "%s/%s", tmpdir, files[c][0]);
    fp = fopen(path, "w");
    fputs(files[c][1], fp);
    fclose(fp);
  }
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    char args[512], want[256], *at;
    int st;
    /* '@' stands for the temporary directory */
    snprintf(args, sizeof args, "%s", cases[c][0]);
    if ((at = strchr(args, '@'))) {
      char rest[256];
      snprintf(rest, sizeof rest, "%s", at + 1);
      snprintf(at, sizeof args - (size_t)(at - args), "%s%s", tmpdir, rest);
    }
    snprintf(want, sizeof want, "%s", cases[c][1]);
    st = sh("./afv run --steps 10 %s --out %s/bad 2> %s/err.txt", args,
            tmpdir, tmpdir);
    snprintf(path, sizeof path, "%s/err.txt", tmpdir);
    err = slurp(path, &len);
    CHECK(st == 2, "'%s': exit %d, want 2", args, st);
    CHECK(err && strstr(err, want) && strchr(err, '\n') == err + len - 1,
          "'%s': message '%s' lacks '%s' or is not one line", args,
          err ? err : "", want);
    CHECK(!exists("bad"), "'%s' created the output directory", args);
    free(err);
  }
  /* an existing run is not overwritten; --resume without a run fails */
  CHECK(sh("./afv run --steps 1 --out %s/a 2>/dev/null", tmpdir) == 2,
        "overwrote a run");
  CHECK(sh("./afv run --resume %s/none 2>/dev/null", tmpdir) == 2,
        "resumed nothing");
  CHECK(sh("./afv run --resume %s/a --P0 5 2>/dev/null", tmpdir) == 2,
        "resume accepted a parameter");
  CHECK(sh("./afv run --help | grep -q relax_max_steps") == 0, "help");
}

/* An unstable step: exit 3, a message naming step, cell, time step and
** mu (a mobility far too large for dt, which afv cannot tell before the
** relaxation has moved the cells).  From its step-0 checkpoint the run
** would stop the same way, so none is kept, and a retry with other
** parameters into the same directory runs (the code before kept it: the
** directory was dead, "already holds a run"). */
static void test_run_unstable_exit(void)
{
  char path[512], *err;
  long len;
  int st = sh("./afv run --N 64 --mu 1e10 --steps 10 --quiet --out %s/u "
              "2> %s/err.txt", tmpdir, tmpdir);
  snprintf(path, sizeof path, "%s/err.txt", tmpdir);
  err = slurp(path, &len);
  CHECK(st == 3, "exit %d, want 3", st);
  CHECK(err && strstr(err, "step 1") && strstr(err, "cell")
        && strstr(err, "time step") && strstr(err, "check mu"), "message: "
        "%s", err ? err : "");
  CHECK(!exists("u/checkpoint.txt"), "the step-0 checkpoint was kept");
  CHECK(sh("./afv run --N 64 --steps 10 --quiet --out %s/u 2>/dev/null",
           tmpdir) == 0, "a retry into the directory of the unstable run");
  free(err);
}

static void sleep_ms(long ms)
{
  struct timespec ts;
  ts.tv_sec = ms / 1000;
  ts.tv_nsec = (ms % 1000) * 1000000L;
  nanosleep(&ts, NULL);
}

/* SIGKILL at several moments of a run that checkpoints every 2 steps; each
** time the run resumes from what is on disk, and in the end it equals an
** uninterrupted run byte for byte. */
static void test_run_survives_sigkill(void)
{
  static const long delays_ms[] = {60, 40, 90, 15, 60, 120};
  const char *args = "--N 64 --P0 4.5 --v0 0.3 --sample_every 3 "
                     "--frame_every 4 --checkpoint_every 2 --svg_every 0 "
                     "--xyz 1 --steps 1200 --quiet";
  char out[512];
  int k, killed = 0, torn = 0;
  CHECK(sh("./afv run %s --out %s/k_ref", args, tmpdir) == 0, "reference");
  snprintf(out, sizeof out, "%s/k", tmpdir);
  for (k = 0; k < 6; k++) {
    pid_t pid = fork();
    int status;
    if (pid == 0) {
      if (k == 0)
        execl("./afv", "afv", "run", "--N", "64", "--P0", "4.5", "--v0", "0.3",
              "--sample_every", "3", "--frame_every", "4",
              "--checkpoint_every", "2", "--svg_every", "0", "--xyz", "1",
              "--steps", "1200", "--quiet", "--out", out, (char *)NULL);
      else
        execl("./afv", "afv", "run", "--resume", out, "--quiet", (char *)NULL);
      _exit(127);
    }
    if (k == 0) {   /* a kill before the first checkpoint has nothing to resume */
      int waited;
      for (waited = 0; waited < 20000 && !exists("k/checkpoint.txt"); waited += 5)
        sleep_ms(5);
    }
    sleep_ms(delays_ms[k]);
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    killed += WIFSIGNALED(status);
    torn += sh("ls %s/k | grep -q 'checkpoint.txt.*tmp'", tmpdir) == 0;
  }
  printf("  %d of 6 runs killed before they finished, %d of them while "
         "writing a checkpoint\n", killed, torn);
  CHECK(killed > 0, "no run was killed: the test did not test anything");
  /* What a kill inside a checkpoint write leaves, made on purpose (the
  ** random kills above may miss that window): a partial temporary checkpoint,
  ** and the append-only files flushed past the last checkpoint, ending in
  ** half a record. */
  CHECK(sh("cd %s/k && head -c 100 checkpoint.txt > checkpoint.txt.1.0.tmp && "
           "printf '# step 99999 time 1\n0.5 0.' >> trajectory.dat && "
           "printf '99999,1,2' >> observables.csv && "
           "printf '64\nLattice' >> trajectory.xyz", tmpdir) == 0,
        "making a torn write");
  CHECK(sh("./afv run --resume %s/k --quiet", tmpdir) == 0, "final resume");
  CHECK(same_file("k", "k_ref", "trajectory.dat"), "trajectory differs");
  CHECK(same_file("k", "k_ref", "observables.csv"), "observables differ");
  CHECK(same_file("k", "k_ref", "trajectory.xyz"), "xyz differs");
  CHECK(same_file("k", "k_ref", "checkpoint.txt"), "checkpoint differs");
}

void suite_dynamics(void)
{
  snprintf(tmpdir, sizeof tmpdir, "/tmp/afv_test_dynamics.%ld",
           (long)getpid());
  RUN(test_philox_known_answers);
  RUN(test_sincos_matches_libm);
  RUN(test_log_matches_libm);
  RUN(test_hypot_matches_libm);
  RUN(test_noise_uses_own_log);
  RUN(test_normal_statistics);
  RUN(test_streams_independent);
  RUN(test_sim_deterministic);
  RUN(test_sim_refuses_unstable_step);
  RUN(test_free_abp_msd_and_polarity);
  RUN(test_per_cell_v0_and_Dr);
  RUN(test_energy_decrease_first_order);
  RUN(test_relax_energy_never_increases);
  RUN(test_relax_stops_at_kink);
  RUN(test_jump_is_a_move_over_half_l);
  RUN(test_cluster_start);
  RUN(test_large_cluster_start);
  if (mkdir(tmpdir, 0777) != 0) {
    printf("  cannot create %s\n", tmpdir);
    return;
  }
  RUN(test_run_deterministic);
  RUN(test_run_resume_equals_straight_run);
  RUN(test_run_cells_file);
  RUN(test_run_bad_input);
  RUN(test_run_unstable_exit);
  RUN(test_run_survives_sigkill);
  sh("rm -rf %s", tmpdir);
}
