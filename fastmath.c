/*
** fastmath.c -- afv_angle, afv_sincos, afv_log and afv_hypot, the
** library's own atan2, sincos, log and hypot: the code and its reasons are
** in fastmath.h, where the library's files compile it inline.
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

double afv_log(double x)
{
  return afv_log_inline(x);
}

double afv_hypot(double x, double y)
{
  return afv_hypot_inline(x, y);
}
