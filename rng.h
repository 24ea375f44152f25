/*
** rng.h -- the random numbers of afv: Philox4x32-10 and Box-Muller
** (library-internal; the public functions are in rng.c, afv.h).
**
** RANDOM NUMBERS.  Philox4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel
** random numbers: as easy as 1, 2, 3", SC'11), a counter-based generator:
** each output is a keyed bijection of a 128-bit counter, with no state to
** carry.  The normals of cells 2k and 2k + 1 at step s are drawn from the
** counter (k, s mod 2^32, s div 2^32, purpose) under the key seed.  So a
** run depends only on (seed, parameters): not on the order in which cells
** are visited (any number of threads gives the same bits), and a resumed
** run needs only the step count to continue the same streams.  Philox
** passes BigCrush and costs 10 multiply rounds.
** Normals come from the Box-Muller transform, both branches (cosine for
** the even cell of the pair, sine for the odd): it is exact, one counter
** gives two independent normals, so the generator, the log and the sincos
** are paid once per two cells, and it takes a fixed number of
** uniforms per normal, so each (pair, step) uses exactly one counter; a
** rejection method (polar, ziggurat) would need a variable number and
** break the one-counter-per-draw bookkeeping.  The uniforms have 53 random
** bits and lie in (0, 1], so log(u) is finite and
** |xi| <= sqrt(2 * 53 ln 2) = 8.57.  The log, cos and sin are the
** library's own arithmetic (afv_log, afv_sincos: fastmath.h), so the noise
** has the same bits on every IEEE 754 machine and in the browser build;
** before afv 0.5.0 the log was the C library's, whose last bit depends on
** the C library and, in glibc, on whether the CPU has FMA.
** The code is here, as static inline functions, so that the noise loop
** (dynamics.c, rotate_block) and the initial states compile it into their
** own code; rng.c's public functions are these.
*/
#ifndef AFV_RNG_H
#define AFV_RNG_H

#include "afv_internal.h"
#include "fastmath.h"

#include <math.h>
#include <stdint.h>

/* ---- Philox4x32-10 ----------------------------------------------------- */
/* Multipliers and Weyl key increments from Random123 (philox.h). */
#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u  /* golden ratio */
#define PHILOX_W1 0xBB67AE85u  /* sqrt(3) - 1 */
#define PHILOX_ROUNDS 10

static inline void rng_philox(const uint32_t ctr[4], const uint32_t key[2],
                              uint32_t out[4])
{
  uint32_t c0 = ctr[0], c1 = ctr[1], c2 = ctr[2], c3 = ctr[3];
  uint32_t k0 = key[0], k1 = key[1];
  int round;
  for (round = 0; round < PHILOX_ROUNDS; round++) {
    uint64_t p0 = (uint64_t)PHILOX_M0 * c0, p1 = (uint64_t)PHILOX_M1 * c2;
    c0 = (uint32_t)(p1 >> 32) ^ c1 ^ k0;
    c1 = (uint32_t)p1;
    c2 = (uint32_t)(p0 >> 32) ^ c3 ^ k1;
    c3 = (uint32_t)p0;
    k0 += PHILOX_W0;          /* the key is bumped between rounds (the bump */
    k1 += PHILOX_W1;          /* after the last is unused: no branch) */
  }
  out[0] = c0; out[1] = c1; out[2] = c2; out[3] = c3;
}

/* 53 bits from two words -> (0, 1]: (k + 1) 2^-53, k in [0, 2^53). */
static inline double unit53(uint32_t hi, uint32_t lo)
{
  double k = (double)(hi >> 5) * 67108864.0 + (double)(lo >> 6);
  return (k + 1.0) * (1.0 / 9007199254740992.0);
}

/* afv_rng_uniform2 (afv.h): the counter (cell, step, purpose), key seed. */
static inline void rng_uniform2(unsigned long long seed, uint32_t cell,
                                unsigned long long step, unsigned purpose,
                                double u[2])
{
  uint32_t ctr[4], key[2], out[4];
  ctr[0] = cell;
  ctr[1] = (uint32_t)(step & 0xffffffffu);
  ctr[2] = (uint32_t)(step >> 32);
  ctr[3] = (uint32_t)purpose;
  key[0] = (uint32_t)(seed & 0xffffffffu);
  key[1] = (uint32_t)(seed >> 32);
  rng_philox(ctr, key, out);
  u[0] = unit53(out[0], out[1]);
  u[1] = unit53(out[2], out[3]);
}

/* Box-Muller: two independent standard normals from two uniforms in (0, 1]
** (u[0] = 1 gives rho = 0; u[0] > 0 keeps the log finite). */
static inline void rng_box_muller(const double u[2], double z[2])
{
  double rho = sqrt(-2.0 * afv_log_inline(u[0])), c, sn;
  afv_sincos_inline(TWO_PI * u[1], &sn, &c);
  z[0] = rho * c;
  z[1] = rho * sn;
}

#endif /* AFV_RNG_H */
