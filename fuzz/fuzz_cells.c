/*
** fuzz_cells.c -- libFuzzer harness of the CELLS reader (afv_cells_read): a
** refused input gets a one-line message naming the file; an accepted one
** has n >= 1 finite values in its columns (x and y together), and written
** back with afv_cells_write it reads back bit for bit.
*/
#include "afv.h"
#include "reader_fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char err[512] = "", again_path[128];
  afv_cells c, again;
  FILE *fp;
  int k, i;
  const char *path = fuzz_input_file("cells", data, size);
  if (afv_cells_read(path, &c, err, sizeof err) != AFV_OK) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    return 0;
  }
  REQUIRE(c.n >= 1 && c.n <= AFV_CELLS_MAX);
  REQUIRE(c.has[AFV_COL_X] == c.has[AFV_COL_Y]);
  for (k = 0; k < AFV_NCOLS; k++)
    for (i = 0; c.has[k] && i < c.n; i++) REQUIRE(isfinite(c.col[k][i]));
  fp = fopen(fuzz_path("cells.again", again_path, sizeof again_path), "w");
  REQUIRE(fp && afv_cells_write(fp, &c) == AFV_OK && fclose(fp) == 0);
  REQUIRE(afv_cells_read(again_path, &again, err, sizeof err) == AFV_OK);
  REQUIRE(again.n == c.n);
  for (k = 0; k < AFV_NCOLS; k++)
    REQUIRE(again.has[k] == c.has[k]
            && (!c.has[k] || fuzz_same(again.col[k], c.col[k],
                                       (size_t)c.n)));
  afv_cells_free(&again);
  afv_cells_free(&c);
  return 0;
}
