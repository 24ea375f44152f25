/* analysis.c -- being written. */
#include "afv.h"

typedef int afv_analysis_placeholder;
