/* svg.c -- being written. */
#include "afv.h"

typedef int afv_svg_placeholder;
