/* dynamics.c -- being written. */
#include "afv.h"

typedef int afv_dynamics_placeholder;
