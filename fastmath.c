/*
** fastmath.c -- afv_angle and afv_sincos, the library's own atan2 and
** sincos: the code and its reasons are in fastmath.h, where geom.c and
** dynamics.c compile it inline.
*/
#include "afv.h"
#include "afv_internal.h"
#include "fastmath.h"

double afv_angle(double y, double x)
{
  return afv_angle_inline(y, x);
}

void afv_sincos(double x, double *sin_x, double *cos_x)
{
  afv_sincos_inline(x, sin_x, cos_x);
}
