/*
** require.h -- REQUIRE(cond), shared by the fuzz harnesses: a property of
** what the code under test accepted or computed; a failed one aborts,
** which libFuzzer reports as a crash with its input.
*/
#ifndef AFV_FUZZ_REQUIRE_H
#define AFV_FUZZ_REQUIRE_H

#include <stdio.h>
#include <stdlib.h>

#define REQUIRE(cond)                                                     \
  do {                                                                    \
    if (!(cond)) {                                                        \
      fprintf(stderr, "%s:%d: property failed: %s\n", __FILE__, __LINE__, \
              #cond);                                                     \
      abort();                                                            \
    }                                                                     \
  } while (0)

#endif
