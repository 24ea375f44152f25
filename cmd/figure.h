/*
** figure.h -- what the figures of afv collect (collect_figures.c) and
** afv paper (paper.c) share (figure.c): the paper's thresholds they
** draw, the colours of their curves and the opening of a figure file.
** Not part of the library.
*/
#ifndef AFV_FIGURE_H
#define AFV_FIGURE_H

#include "cli.h"

#include <stdio.h>

/* The paper's thresholds (Sec. Results): clustered if N_GC/N >= 0.99,
** epithelial if Omega >= 0.5, glassy if D_eff < 1e-8; and afv collect's
** own run-length-independent one, glassy if msd_beta < 0.5: halfway
** between a caged relative MSD (slope 0) and a diffusive one (slope 1),
** at lags set as fractions of the window. */
#define CLUSTER_LEVEL 0.99
#define CONFLUENCY_LEVEL 0.5
#define DEFF_GLASS_LEVEL 1e-8
#define BETA_GLASS_LEVEL 0.5

/* A figure's path DIR/figures/NAME (DIR at most RUN_PATH_MAX), and its
** temporary file's: the path and afv_atomic_open's suffix
** ".PID.SALT.tmp" (at most 43 characters). */
#define FIGURE_PATH_LEN (RUN_PATH_MAX + 128)
#define FIGURE_TMP_LEN  (FIGURE_PATH_LEN + 64)

/* The colour of curve c, cycling through 10 (matplotlib's "tab10"). */
const char *figure_color(int c);

/* Opens DIR/figures/NAME for an atomic write (afv_atomic_open): PATH
** (FIGURE_PATH_LEN) gets the path, TMP (FIGURE_TMP_LEN) the temporary
** file's, which afv_atomic_commit renames to PATH.  NULL with errno set
** if it cannot (ENAMETOOLONG: the path does not fit). */
FILE *figure_open(const char *dir, const char *name, char *path, char *tmp);

#endif /* AFV_FIGURE_H */
