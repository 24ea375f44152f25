/*
** fuzz_t1ref.c -- libFuzzer harness of the T1 reference reader
** (afv_t1_reference_read).  The first input byte gives the number of cells
** n (0 .. 255), the rest is the file.  A refused input gets a one-line
** message naming the file and leaves the reference as it was; an accepted
** one holds pairs 0 <= i < j < n in strictly increasing order (what
** afv_t1_count's merge needs), and written back it reads back the same.
*/
#include "afv.h"
#include "reader_fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char err[512] = "", again_path[128];
  afv_t1 t = {0, NULL}, again = {0, NULL};
  int n, k;
  const char *path;
  if (size == 0) return 0;
  n = data[0];
  path = fuzz_input_file("t1_reference", data + 1, size - 1);
  if (afv_t1_reference_read(path, n, &t, err, sizeof err) != AFV_OK) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    REQUIRE(t.pairs0 == NULL && t.n_pairs0 == 0);
    return 0;
  }
  REQUIRE(t.n_pairs0 >= 0 && (t.n_pairs0 == 0 || t.pairs0 != NULL));
  for (k = 0; k < t.n_pairs0; k++) {
    const int *p = t.pairs0 + 2 * k;
    REQUIRE(0 <= p[0] && p[0] < p[1] && p[1] < n);
    REQUIRE(k == 0 || p[-2] < p[0] || (p[-2] == p[0] && p[-1] < p[1]));
  }
  fuzz_path("t1_reference.again", again_path, sizeof again_path);
  REQUIRE(afv_t1_reference_write(again_path, &t) == AFV_OK);
  REQUIRE(afv_t1_reference_read(again_path, n, &again, err, sizeof err)
          == AFV_OK && again.n_pairs0 == t.n_pairs0);
  REQUIRE(t.n_pairs0 == 0 || memcmp(again.pairs0, t.pairs0, (size_t)t.n_pairs0
                                    * 2 * sizeof(int)) == 0);
  afv_t1_free(&again);
  afv_t1_free(&t);
  return 0;
}
