/* test_analysis.c -- placeholder: this suite is being written. */
#include "test.h"

void suite_analysis(void) {}
