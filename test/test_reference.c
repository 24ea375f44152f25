/* test_reference.c -- the reference twins (doc/reference.md). */
#include "test.h"

void suite_reference(void)
{
}
