/*
** fastmath.h -- the functions of libm whose results feed the state (or an
** analysis result), computed in the library's own arithmetic:
**   afv_angle    the counter-clockwise angle of a vector, atan2(y, x) + 2 pi
**                if negative: every arc of every cell (geom.c, gap_angle);
**   afv_sincos   sin x and cos x: every cell's polarity n_i, every
**                Box-Muller angle (dynamics.c), the cap's chord term
**                (afv.c) and the hexagonal mean field (analysis.c);
**   afv_log      the natural logarithm: every Box-Muller radius (rng.h)
**                and the MSD exponent's fit (analysis.c);
**   afv_hypot    the length of a vector: the relaxation's stopping test
**                (dynamics.c), FIRE's capped move (relax_fire.c).
** All are plain C99 arithmetic, so they give the same bits on every
** machine whose double arithmetic is IEEE 754 and that does not fuse a
** multiply and an add (the C library's functions need not: glibc picks an
** FMA variant of log on a CPU that has FMA, and wasi-libc, the browser
** build's (doc/web.md), differs from glibc in the last bit of log, sin and
** hypot for some inputs); all are checked against the C library in the
** tests (test_core.c, test_dynamics.c) and through the twins (make twins:
** the plain file, reference/afv_plain.c, uses the C library's).
** The code is here, as static inline functions, so that the files of the
** hot path (geom.c, dynamics.c) compile it into their own code: a call
** across files makes the caller save every floating-point register around
** it.  The library's public afv_angle and afv_sincos (fastmath.c) are
** these.
** Library-internal, like afv_internal.h.
*/
#ifndef AFV_FASTMATH_H
#define AFV_FASTMATH_H

#include "afv_internal.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* ---- the angle of a vector ---------------------------------------------- */
/* The angle of every arc is an atan2.  What it costs is its latency more
** than its instructions: the cell's area, hence every term of its gradient,
** waits for it (doc/performance.md).  So afv_angle is written for a short
** dependency chain, one division and no branch on the quadrant:
**   1. lo = min(|x|, |y|), hi = max(|x|, |y|), and the angle is
**      off + sgn atan(lo / hi), (off, sgn) from a table by which of |x|,
**      |y| is larger and by the signs of x and y;
**   2. atan(lo / hi) = atan(c) + atan(u),  u = (lo - c hi) / (hi + c lo)
**      (one division), with c = 7/16, so that u lies in [-7/16, 9/23];
**   3. atan(u) = u - u z Q(z), z = u^2, with Q the polynomial of fdlibm's
**      atan (s_atan.c, Sun Microsystems 1993) for |u| <= 7/16, good to
**      about 2^-58, evaluated by Estrin's scheme (pairs of terms, then
**      pairs of pairs): depth 4 instead of Horner's 10;  atan(7/16) as a
**      sum of two doubles (computed to 60 digits).
** Measured against the C library's atan2 (+ 2 pi if negative, test_core.c):
** within 8.9e-16, an ulp of 2 pi.  The error is absolute: an angle below
** 1e-17 may come out as 0.  (An infinite component gives NaN, where atan2
** gives an angle; the geometry never asks.) */
#define ATAN_C      0.4375                  /* c = 7/16 */
#define ATAN_C_HI   0.4124104415973873      /* atan(7/16) = HI + LO */
#define ATAN_C_LO   (-1.587652227770689e-17)

static inline double afv_angle_inline(double y, double x)
{
  static const double aT[11] = {
    3.33333333333329318027e-01, -1.99999999998764832476e-01,
    1.42857142725034663711e-01, -1.11111104054623557880e-01,
    9.09088713343650656196e-02, -7.69187620504482999495e-02,
    6.66107313738753120669e-02, -5.83357013379057348645e-02,
    4.97687799461593236017e-02, -3.65315727442169155270e-02,
    1.62858201153657823623e-02};
  /* index: 1 if |y| > |x|, + 2 if x < 0, + 4 if y < 0 */
  static const double off[8] = {0, PI / 2, PI, PI / 2, TWO_PI, 1.5 * PI, PI,
                                1.5 * PI};
  static const double sgn[8] = {1, -1, -1, 1, -1, 1, 1, -1};
  double ax = fabs(x), ay = fabs(y), lo, hi, num, den, u, z, z2, z4, Q, a;
  int steep = ay > ax, k;
  if (isnan(x) || isnan(y)) return x + y;
  lo = ay < ax ? ay : ax;                     /* min and max (minsd, maxsd */
  hi = ay > ax ? ay : ax;                     /* on x86): no branch */
  num = lo - ATAN_C * hi;
  den = hi + ATAN_C * lo;
  if (!(den > 0)) {                           /* (0, 0): angle 0 */
    num = -ATAN_C;
    den = 1;
  }
  u = num / den;
  z = u * u;
  z2 = z * z;
  z4 = z2 * z2;
  Q = ((aT[0] + aT[1] * z) + (aT[2] + aT[3] * z) * z2)
      + ((aT[4] + aT[5] * z) + (aT[6] + aT[7] * z) * z2) * z4
      + ((aT[8] + aT[9] * z) + aT[10] * z2) * (z4 * z4);
  a = ATAN_C_HI + (ATAN_C_LO + (u - u * (z * Q)));
  k = steep + 2 * (x < 0) + 4 * (y < 0);
  return off[k] + sgn[k] * a;
}

/* ---- sine and cosine ---------------------------------------------------- */
/* Every step needs cos and sin of every cell's angle (the polarity) and of
** one Box-Muller angle per two cells, a sizeable part of a step with the
** C library's sincos; afv_sincos takes about half its instructions (doc/
** performance.md), in plain arithmetic without branches:
**   1. reduction: x = k pi/2 + r with k the integer nearest x (2/pi) (to
**      within 2^-32), so |r| <= pi/4 (1 + 2^-30);  r = x - k P1 - k P2 -
**      k P3, where P1 + P2 + P3 = pi/2 to about 2^-150 (fdlibm's split:
**      P1 and P2 have 33 significant bits, so k P1 and k P2 are exact for
**      |k| < 2^20, and x - k P1 is exact by Sterbenz' lemma); the error of
**      r is an ulp of r;
**   2. Taylor series on [-pi/4, pi/4]: sin to the term r^17/17!, cos to
**      r^16/16!; the first term left out is below (pi/4)^18/18! = 2e-18;
**   3. the quadrant k mod 4 picks +-sin r or +-cos r, as the sum
**      a sin r + b cos r with a, b in {-1, 0, 1} from a table: exact, and
**      free of a branch that a random quadrant would mispredict.
** Measured against the C library (test_dynamics.c): within 2.22e-16.
** |x| >= SINCOS_FAST_LIMIT (k would not fit the split), inf and NaN go to
** the C library. */
#define SINCOS_FAST_LIMIT 1e6
#define PIO2_1 1.57079632673412561417e+00   /* first 33 bits of pi/2 */
#define PIO2_2 6.07710050630396597660e-11   /* next 33 bits */
#define PIO2_3 2.02226624879595063154e-21   /* the rest */

static inline void afv_sincos_inline(double x, double *sin_x, double *cos_x)
{
  static const double sa[5] = {1, 0, -1, 0, 1}, sb[5] = {0, 1, 0, -1, 0};
  double t, r, z, sr, cr;
  long m, k;
  unsigned q;
  if (!(fabs(x) < SINCOS_FAST_LIMIT)) {       /* the C library's */
    *sin_x = sin(x);
    *cos_x = cos(x);
    return;
  }
  /* k = floor(x (2/pi) + 1/2), as m - 2^20 with m = (long)(positive): no
  ** branch on the sign of x (truncation of a negative value rounds up) */
  t = x * 0.63661977236758134308 + (0.5 + 1048576.0);
  m = (long)t;
  k = m - 1048576;
  r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
  z = r * r;
  sr = r + r * z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040
       + z * (1.0 / 362880 + z * (-1.0 / 39916800 + z * (1.0 / 6227020800.0
       + z * (-1.0 / 1307674368000.0 + z * (1.0 / 355687428096000.0))))))));
  cr = 1 + z * (-0.5 + z * (1.0 / 24 + z * (-1.0 / 720 + z * (1.0 / 40320
       + z * (-1.0 / 3628800 + z * (1.0 / 479001600.0
       + z * (-1.0 / 87178291200.0 + z * (1.0 / 20922789888000.0))))))));
  q = (unsigned)m & 3u;                      /* k mod 4 */
  /* sin(r + q pi/2) = sin r, cos r, -sin r, -cos r for q = 0..3, and
  ** cos(r + q pi/2) = sin(r + (q + 1) pi/2) */
  *sin_x = sa[q] * sr + sb[q] * cr;
  *cos_x = sa[q + 1] * sr + sb[q + 1] * cr;
}

/* ---- the natural logarithm --------------------------------------------- */
/* fdlibm's e_log.c (Sun Microsystems, 1993: "Permission to use, copy,
** modify, and distribute this software is freely granted, provided that
** this notice is preserved"), in C99 (the words of x through memcpy):
**   1. x = 2^k (1 + f) with sqrt(2)/2 < 1 + f < sqrt(2);
**   2. log(1 + f) = 2s + 2/3 s^3 + 2/5 s^5 + ..., s = f / (2 + f), by the
**      polynomial Lg1 .. Lg7 in s^2 (Remez, |error| < 2^-58.45 on
**      [0, 0.1716]), with f - f^2/2 kept exact enough to add last;
**   3. log x = k ln2_hi + (log(1 + f) + k ln2_lo), ln2_hi with 32 bits, so
**      k ln2_hi is exact for |k| < 2000.
** Its error is below 1 ulp (fdlibm's statement; test_dynamics.c checks it
** against the C library, to 1 ulp, over 10^6 inputs in (0, 1], the
** Box-Muller range, and over the normal doubles).  0 gives -inf, a
** negative x or NaN gives NaN, inf gives inf. */
#define LOG_LN2_HI 6.93147180369123816490e-01  /* 3fe62e42 fee00000 */
#define LOG_LN2_LO 1.90821492927058770002e-10  /* 3dea39ef 35793c76 */
#define LOG_TWO54  1.80143985094819840000e+16  /* 2^54 */

static inline int32_t log_high_word(double x)
{
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  return (int32_t)(uint32_t)(b >> 32);
}

static inline double log_with_high_word(double x, int32_t hi)
{
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  b = (b & 0xffffffffu) | ((uint64_t)(uint32_t)hi << 32);
  memcpy(&x, &b, sizeof x);
  return x;
}

static inline double afv_log_inline(double x)
{
  static const double Lg1 = 6.666666666666735130e-01,  /* 3FE55555 55555593 */
    Lg2 = 3.999999999940941908e-01,                    /* 3FD99999 9997FA04 */
    Lg3 = 2.857142874366239149e-01,                    /* 3FD24924 94229359 */
    Lg4 = 2.222219843214978396e-01,                    /* 3FCC71C5 1D8E78AF */
    Lg5 = 1.818357216161805012e-01,                    /* 3FC74664 96CB03DE */
    Lg6 = 1.531383769920937332e-01,                    /* 3FC39A09 D078C69F */
    Lg7 = 1.479819860511658591e-01;                    /* 3FC2F112 DF3E5244 */
  double hfsq, f, s, z, R, w, t1, t2, dk;
  int32_t k = 0, hx = log_high_word(x), i, j;
  if (!(x >= 2.2250738585072014e-308)) {       /* below the normals, NaN */
    if (x == 0) return -HUGE_VAL;
    if (!(x > 0)) return NAN;                  /* negative or NaN */
    k -= 54;                                   /* subnormal: scale it up */
    x *= LOG_TWO54;
    hx = log_high_word(x);
  }
  if (hx >= 0x7ff00000) return x + x;          /* inf */
  k += (hx >> 20) - 1023;
  hx &= 0x000fffff;
  i = (hx + 0x95f64) & 0x100000;
  x = log_with_high_word(x, hx | (i ^ 0x3ff00000));  /* x or x/2 in */
  k += i >> 20;                                /* [sqrt(2)/2, sqrt(2)) */
  f = x - 1.0;
  dk = (double)k;
  /* fdlibm returns f - (...) where k = 0; dk ln2_hi - ((... - dk ln2_lo)
  ** - f) is the same bits there (0 - (a - f) = f - a exactly, and adding
  ** 0 changes nothing but the sign of a 0), without a branch that the
  ** noise's uniforms (k = 0 for 29% of them) would mispredict */
  if ((0x000fffff & (2 + hx)) < 3) {           /* |f| < 2^-20 */
    if (f == 0) return dk * LOG_LN2_HI + dk * LOG_LN2_LO;
    R = f * f * (0.5 - 0.33333333333333333 * f);
    return dk * LOG_LN2_HI - ((R - dk * LOG_LN2_LO) - f);
  }
  s = f / (2.0 + f);
  z = s * s;
  i = hx - 0x6147a;
  w = z * z;
  j = 0x6b851 - hx;
  t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  i |= j;
  R = t2 + t1;
  hfsq = 0.5 * f * f;
  /* 1 + f far from 1 (i > 0) or not: both forms, then a select */
  t1 = hfsq - (s * (hfsq + R) + dk * LOG_LN2_LO);
  t2 = s * (f - R) - dk * LOG_LN2_LO;
  return dk * LOG_LN2_HI - ((i > 0 ? t1 : t2) - f);
}

/* ---- the length of a vector --------------------------------------------- */
/* sqrt(x^2 + y^2): correctly rounded sums and a correctly rounded sqrt
** (IEEE 754), within about 1 ulp of the length.  A vector whose larger
** component lies outside [2^-500, 2^500] is scaled by a power of 2 (exact)
** so that the squares neither overflow nor lose their bits; a component
** that the scale-down makes subnormal is below 2^-100 of the other, whose
** square it cannot change.  An infinite component gives inf, else a NaN
** gives NaN (as C99's hypot). */
#define HYPOT_BIG   3.273390607896142e+150    /* 2^500 */
#define HYPOT_SMALL 3.054936363499605e-151    /* 2^-500 */
#define HYPOT_DOWN  2.409919865102884e-181    /* 2^-600 */
#define HYPOT_UP    4.149515568880993e+180    /* 2^600 */

static inline double afv_hypot_inline(double x, double y)
{
  double ax = fabs(x), ay = fabs(y), big = ax > ay ? ax : ay, scale = 1;
  if (isinf(x) || isinf(y)) return HUGE_VAL;
  if (big > HYPOT_BIG) scale = HYPOT_DOWN;
  else if (big < HYPOT_SMALL) scale = HYPOT_UP;
  if (scale == 1) return sqrt(x * x + y * y);
  ax *= scale;
  ay *= scale;
  return sqrt(ax * ax + ay * ay) / scale;
}

#endif /* AFV_FASTMATH_H */
