/*
** fuzz_trajectory.c -- libFuzzer harness of the trajectory reader
** (afv_traj_read): a refused input gets a one-line message naming the
** file; an accepted one has n >= 1, steps >= 0, finite times and
** coordinates, a valid box, and written back (afv_traj_write_header and
** _frame: format 2) it reads back bit for bit, the angles as the float32
** of the angle reduced to [-pi, pi].
*/
#include "afv.h"
#include "reader_fuzz.h"

#include <math.h>

/* Writes tr with the library's writers to path. */
static void write_back(const afv_traj *tr, const char *path)
{
  FILE *fp = fopen(path, "w");
  int f;
  REQUIRE(fp && afv_traj_write_header(fp, tr->n, &tr->box) == AFV_OK);
  for (f = 0; f < tr->nframes; f++)
    REQUIRE(afv_traj_write_frame(fp, tr->step[f], tr->t[f], tr->n,
                                 tr->r + (size_t)f * 2 * (size_t)tr->n,
                                 tr->theta + (size_t)f * (size_t)tr->n)
            == AFV_OK);
  REQUIRE(fclose(fp) == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  char err[512] = "", again_path[128];
  afv_traj tr, again;
  size_t cells;
  int f;
  const char *path = fuzz_input_file("trajectory", data, size);
  if (afv_traj_read(path, &tr, err, sizeof err) != AFV_OK) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    REQUIRE(tr.r == NULL && tr.nframes == 0);
    return 0;
  }
  REQUIRE(tr.n >= 1 && tr.n <= AFV_CELLS_MAX && tr.nframes >= 0);
  REQUIRE(!tr.box.periodic || (isfinite(tr.box.Lx) && tr.box.Lx > 0
                               && isfinite(tr.box.Ly) && tr.box.Ly > 0));
  cells = (size_t)tr.nframes * (size_t)tr.n;
  for (f = 0; f < tr.nframes; f++)
    REQUIRE(tr.step[f] >= 0 && isfinite(tr.t[f]));
  for (f = 0; (size_t)f < cells; f++)
    REQUIRE(isfinite(tr.r[2*f]) && isfinite(tr.r[2*f+1])
            && isfinite(tr.theta[f]));
  write_back(&tr, fuzz_path("trajectory.again", again_path,
                            sizeof again_path));
  REQUIRE(afv_traj_read(again_path, &again, err, sizeof err) == AFV_OK);
  REQUIRE(again.n == tr.n && again.nframes == tr.nframes
          && again.box.periodic == tr.box.periodic);
  REQUIRE(!tr.box.periodic || (again.box.Lx == tr.box.Lx
                               && again.box.Ly == tr.box.Ly));
  for (f = 0; f < tr.nframes; f++)
    REQUIRE(again.step[f] == tr.step[f] && fuzz_same(&again.t[f], &tr.t[f], 1));
  REQUIRE(fuzz_same(again.r, tr.r, 2 * cells));
  for (f = 0; (size_t)f < cells; f++)
    REQUIRE(again.theta[f]
            == (double)(float)remainder(tr.theta[f], 6.28318530717958647692));
  afv_traj_free(&again);
  afv_traj_free(&tr);
  return 0;
}
