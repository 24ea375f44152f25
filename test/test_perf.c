/* test_perf.c -- placeholder: this suite is being written. */
#include "test.h"

void suite_perf(void) {}
