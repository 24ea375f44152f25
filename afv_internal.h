/*
** afv_internal.h -- what the library's own files share and no caller needs
** (included by the library's .c files only; not part of the API, afv.h).
*/
#ifndef AFV_INTERNAL_H
#define AFV_INTERNAL_H

#include "afv.h"

#include <stddef.h>

/* A function for a rare case, kept out of line so that the compiler does
** not hoist its work into the common path that calls it (gcc did, with
** exact_near: its pass cost every cell instructions, though never taken).
** An extension of gcc and clang; other compilers inline as they like. */
#if defined(__GNUC__)
#define COLD __attribute__((noinline, cold))
#else
#define COLD
#endif

/* Makes room for `need` elements of `elem` bytes in *ptr, whose capacity
** *cap grows by doubling (neighbours.c; geom.c, dynamics.c and substeps.c
** use it too).
** AFV_OK or AFV_ENOMEM (then *ptr and *cap are unchanged). */
int afv_grow(void **ptr, int *cap, int need, size_t elem);

#define PI     3.14159265358979323846
#define TWO_PI 6.28318530717958647692

/* OpenMP (make OPENMP=1; the macros are in afv.h): the per-cell loops
** marked AFV_PARALLEL_FOR write only their own cell's entries, so any
** thread count gives the same bits.  Static schedule: each thread gets
** one contiguous, spatially coherent block.  AFV_PARALLEL_REDUCE adds
** reduction clauses, used only for reductions whose result does not
** depend on the order (max, min, | and sums of integers), so again any
** thread count gives the same bits.
** `size` is the loop's length in cells (in bins for the bin loop): below
** AFV_PARALLEL_MIN (afv.h) the loop runs on the calling thread: the
** sub-steps' regions (substeps.c) are tens of cells, each of their force
** evaluations runs about eight such loops, and starting a team of threads
** for each cost more than the loop.  Without OpenMP the macros are empty
** and the files are plain C99. */

/* 0 for a direction in [0, pi) counter-clockwise from +x, 1 in [pi, 2 pi). */
static inline int lower_half(double dx, double dy)
{
  return dy < 0 || (dy == 0 && dx < 0);
}

/* ---- the step (dynamics.c) and its sub-steps (substeps.c) -------------- */
/* dynamics.c: moves the m cells of list by h (Eq. (4): h (mu F_i + v0 n_i),
** with this step's polarity); records a refused step's cell and move and
** returns AFV_EUNSTABLE. */
void afv_move_cells(afv_sim *s, const int *list, int m, double h);
int  afv_unstable(afv_sim *s, int cell, double len);
/* substeps.c: lists the step's fast cells (force move over dt above
** split, from euler_all's move_len) into *nf and moves them over dt in
** pieces, group by group (moved: how far the other cells may have moved
** since the last force evaluation).  AFV_OK or an error (AFV_EUNSTABLE via
** afv_unstable). */
int  afv_substeps(afv_sim *s, double split, double moved, double dt, int *nf);

#endif /* AFV_INTERNAL_H */
