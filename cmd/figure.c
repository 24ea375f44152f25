/*
** figure.c -- what the figures of afv collect and afv paper share
** (figure.h): the colours of their curves, the opening of a figure file.
*/
#include "figure.h"

#include <errno.h>

static const char *const palette[] = {
  "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
  "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
#define N_COLORS ((int)(sizeof palette / sizeof palette[0]))

const char *figure_color(int c)
{
  return palette[c % N_COLORS];
}

FILE *figure_open(const char *dir, const char *name, char *path, char *tmp)
{
  if (snprintf(path, FIGURE_PATH_LEN, "%s/figures/%s", dir, name)
      >= FIGURE_PATH_LEN) {
    errno = ENAMETOOLONG;
    return NULL;
  }
  return afv_atomic_open(path, tmp, FIGURE_TMP_LEN);
}
