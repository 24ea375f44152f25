/*
** rng.c -- the public random-number functions (afv.h): the counter-based
** generator Philox4x32-10 and normals by Box-Muller.  The code and its
** reasons are in rng.h, where dynamics.c compiles it inline.
*/
#include "afv.h"
#include "afv_internal.h"
#include "fastmath.h"
#include "rng.h"

void afv_philox4x32(const uint32_t ctr[4], const uint32_t key[2],
                    uint32_t out[4])
{
  rng_philox(ctr, key, out);
}

void afv_rng_uniform2(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose, double u[2])
{
  rng_uniform2(seed, cell, step, purpose, u);
}

void afv_rng_normal2(unsigned long long seed, uint32_t pair,
                     unsigned long long step, unsigned purpose, double z[2])
{
  double u[2];
  rng_uniform2(seed, pair, step, purpose, u);
  rng_box_muller(u, z);
}

double afv_rng_normal(unsigned long long seed, uint32_t cell,
                      unsigned long long step, unsigned purpose)
{
  double z[2];
  afv_rng_normal2(seed, cell / 2, step, purpose, z);
  return z[cell % 2];
}
