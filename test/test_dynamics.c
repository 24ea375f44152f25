/* test_dynamics.c -- placeholder: this suite is being written. */
#include "test.h"

void suite_dynamics(void) {}
