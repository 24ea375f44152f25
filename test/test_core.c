/* test_core.c -- placeholder: this suite is being written. */
#include "test.h"

void suite_core(void) {}
