/* test_cli.c -- placeholder: this suite is being written. */
#include "test.h"

void suite_cli(void) {}
