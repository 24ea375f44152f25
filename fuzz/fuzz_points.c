/*
** fuzz_points.c -- libFuzzer harness of the POINTS reader (afv_points_read):
** any input either is refused with a message naming the file, or gives
** n >= 0 finite points.
*/
#include "afv.h"
#include "reader_fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char err[512] = "";
  double *r = NULL;
  int n = -1, i;
  const char *path = fuzz_input_file("points", data, size);
  if (afv_points_read(path, &n, &r, err, sizeof err) != AFV_OK) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    REQUIRE(r == NULL && n == 0);
    return 0;
  }
  REQUIRE(n >= 0 && n <= AFV_CELLS_MAX && (n == 0 || r != NULL));
  for (i = 0; i < 2 * n; i++) REQUIRE(isfinite(r[i]));
  free(r);
  return 0;
}
