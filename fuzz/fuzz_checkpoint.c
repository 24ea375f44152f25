/*
** fuzz_checkpoint.c -- libFuzzer harness of the checkpoint reader
** (afv_checkpoint_read): a refused input gets a one-line message naming
** the file; an accepted one has every field in range (n >= 1, step and
** sizes >= 0, finite time and state), and written back with
** afv_checkpoint_write it reads back bit for bit.
*/
#include "afv.h"
#include "reader_fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char err[512] = "", again_path[128];
  afv_checkpoint c, again;
  int k, i;
  const char *path = fuzz_input_file("checkpoint", data, size);
  if (afv_checkpoint_read(path, &c, err, sizeof err) != AFV_OK) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    REQUIRE(c.r == NULL && c.theta == NULL);
    return 0;
  }
  REQUIRE(c.n >= 1 && c.step >= 0 && isfinite(c.t));
  for (k = 0; k < AFV_CKPT_FILES; k++) REQUIRE(c.bytes[k] >= 0);
  for (i = 0; i < c.n; i++)
    REQUIRE(isfinite(c.r[2*i]) && isfinite(c.r[2*i+1])
            && isfinite(c.theta[i]));
  fuzz_path("checkpoint.again", again_path, sizeof again_path);
  REQUIRE(afv_checkpoint_write(again_path, &c) == AFV_OK);
  REQUIRE(afv_checkpoint_read(again_path, &again, err, sizeof err)
          == AFV_OK);
  REQUIRE(again.n == c.n && again.step == c.step && again.seed == c.seed
          && fuzz_same(&again.t, &c.t, 1));
  for (k = 0; k < AFV_CKPT_FILES; k++) REQUIRE(again.bytes[k] == c.bytes[k]);
  REQUIRE(fuzz_same(again.r, c.r, 2 * (size_t)c.n)
          && fuzz_same(again.theta, c.theta, (size_t)c.n));
  afv_checkpoint_free(&again);
  afv_checkpoint_free(&c);
  return 0;
}
