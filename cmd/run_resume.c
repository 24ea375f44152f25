/*
** run_resume.c -- afv run --resume and --continue: the checkpoint agrees
** with the files it describes, and every check comes before any byte
** changes
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "run.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* Resume: 1 if every append-only file the run writes holds at least the
** bytes the checkpoint records (checked for all before any is cut back);
** the library names the checkpoint's line of a size its file does not
** hold, this loop a file the run writes that is missing altogether. */
static int recorded_sizes_hold(const run_state *R, const afv_checkpoint *ck,
                               char *err, size_t errlen)
{
  char path[RUN_PATH_MAX + 32];
  int k;
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (afv_checkpoint_check_files(path, ck, err, errlen) != AFV_OK) return 0;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    if (k == OUT_XYZ && !R->cfg.xyz) continue;
    snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
    if (access(path, F_OK) != 0) {
      afv_errorf(err, errlen, "%s: %s (the checkpoint records %lld bytes)",
                 path, strerror(errno), (long long)ck->bytes[k]);
      return 0;
    }
  }
  return 1;
}

/* ---- a checkpoint agrees with the files it describes ------------------- */
/* A checkpoint is trusted only when it agrees with its files, checked
** before any byte changes: its time is step x dt (the run sets t so), and
** each append-only file, cut at the recorded size, ends with the record
** of the last output step at or before the checkpoint's step: the
** observables.csv row of that step and time (the header alone without
** samples), the whole trajectory.dat frame of that step and time (the
** header line alone without frames), and the trajectory.xyz frame of that
** step.  When the row is of the checkpoint's own step, its energy must
** equal the checkpointed state's, bit for bit (%.17g reads back exactly):
** a checksum of the state.  A checkpoint that fails any of this (edited,
** or of another run) would have cut the files to a wrong place or
** continued a different state. */

/* Reads bytes [from, to) of fd into buf (to - from <= cap - 1, NUL
** added).  1 if all were read. */
static int read_span(int fd, long long from, long long to, char *buf,
                     size_t cap)
{
  size_t want = (size_t)(to - from), got = 0;
  if (to < from || want >= cap) return 0;
  while (got < want) {
    ssize_t m = pread(fd, buf + got, want - got, (off_t)(from + (long long)got));
    if (m <= 0) return 0;
    got += (size_t)m;
  }
  buf[want] = 0;
  return 1;
}

/* The start of the k-th line (k >= 1) before end, which must follow a
** newline: -1 if the file does not end a line at end or has fewer lines.
** Reads backwards in blocks, so a frame costs its own size. */
static long long line_back(int fd, long long end, long long k)
{
  char buf[65536];
  long long pos = end - 1, seen = 0;
  if (end <= 0 || !read_span(fd, end - 1, end, buf, sizeof buf)
      || buf[0] != '\n')
    return -1;
  while (pos > 0) {
    long long from = pos - (long long)sizeof buf + 1 > 0
                     ? pos - (long long)sizeof buf + 1 : 0;
    long long j;
    if (!read_span(fd, from, pos, buf, sizeof buf)) return -1;
    for (j = pos - 1; j >= from; j--)
      if (buf[j - from] == '\n' && ++seen == k) return j + 1;
    pos = from;
  }
  return seen == k - 1 ? 0 : -1;
}

/* The line of fd starting at start (at most cap - 1 bytes, without its
** newline) into buf; 1 if read. */
static int line_at(int fd, long long start, long long end, char *buf,
                   size_t cap)
{
  long long to = end - start < (long long)cap - 1 ? end : start +
                 (long long)cap - 1;
  char *nl;
  if (!read_span(fd, start, to, buf, cap)) return 0;
  if ((nl = strchr(buf, '\n'))) *nl = 0;
  return 1;
}

/* The last output step at or before step for an interval (0: none). */
static long long last_due(long long step, long long every)
{
  return every > 0 ? step / every * every : -1;
}

typedef struct ckpt_trust {
  const run_state *R;
  const afv_checkpoint *ck;
  char *err;
  size_t errlen;
  double energy;       /* observables' energy at the checkpoint's step */
  int has_energy;      /* 1 if the last row is of the checkpoint's step */
} ckpt_trust;

/* "checkpoint.txt:LINE: bytes FILE B: the file there WHY: not ..." */
static int untrusted(ckpt_trust *T, int k, const char *why)
{
  afv_errorf(T->err, T->errlen, "%s/checkpoint.txt:%d: bytes %s %lld: %s "
             "there %s: the checkpoint does not describe these files (edited,"
             " or another run's); nothing was changed", T->R->dir,
             AFV_CKPT_BYTES_LINE + k, afv_checkpoint_files[k],
             T->ck->bytes[k], afv_checkpoint_files[k], why);
  return 0;
}

/* observables.csv (read through the lock's descriptor: closing another
** would drop the lock): its last line before the recorded size. */
static int obs_agrees(ckpt_trust *T)
{
  const run_state *R = T->R;
  long long end = T->ck->bytes[OUT_OBS], due_step = last_due(T->ck->step,
                  R->cfg.sample_every), start = line_back(R->lock_fd, end, 1);
  char line[4096], why[160];
  long long step;
  double t, e;
  if (start < 0 || !line_at(R->lock_fd, start, end, line, sizeof line))
    return untrusted(T, OUT_OBS, "does not end a line");
  if (due_step < 0)
    return start == 0 && strncmp(line, "step,", 5) == 0
           ? 1 : untrusted(T, OUT_OBS, "is not the header alone "
                           "(sample_every 0)");
  if (sscanf(line, "%lld,%lf,%lf,", &step, &t, &e) != 3 || step != due_step
      || t != (double)step * R->cfg.dt) {
    snprintf(why, sizeof why, "does not end with the row of step %lld "
             "(t = %.17g)", due_step, (double)due_step * R->cfg.dt);
    return untrusted(T, OUT_OBS, why);
  }
  T->has_energy = step == T->ck->step;
  T->energy = e;
  return 1;
}

/* The little-endian IEEE float64 at p (the trajectory's order, io.c). */
static double le_f64(const unsigned char *p)
{
  uint64_t u = 0;
  double x;
  int k;
  for (k = 7; k >= 0; k--) u = u << 8 | p[k];
  memcpy(&x, &u, sizeof x);
  return x;
}

/* The largest |v0| of the run (the cells file's column, if it has one). */
static double largest_v0(const run_state *R)
{
  double v = fabs(R->cfg.v0);
  int i;
  if (R->cells.has[AFV_COL_V0])
    for (i = 0, v = 0; i < R->cells.n; i++)
      v = fmax(v, fabs(R->cells.col[AFV_COL_V0][i]));
  return v;
}

/* The centres of the last frame (its step; its cells from byte from of fd)
** are the checkpoint's, bit for bit, where step is the checkpoint's, else
** within MOVE BOUND (cmd/report.c) of them: (checkpoint step - step) x
** (AFV_MAX_STEP_DISP l + |v0| dt).  (A last frame with x = 1e300 was
** resumed, and appended to, before.) */
static int last_frame_agrees(ckpt_trust *T, int fd, long long from,
                             long long step)
{
  const run_state *R = T->R;
  const double *r = T->ck->r;
  size_t bytes = (size_t)T->ck->n * AFV_TRAJ_CELL_BYTES;
  double bound = (double)(T->ck->step - step)
                 * (AFV_MAX_STEP_DISP * R->cfg.l + largest_v0(R) * R->cfg.dt);
  unsigned char *cells = malloc(bytes + 1);
  char why[224];
  int i, bad = -1;
  if (cells && read_span(fd, from, from + (long long)bytes, (char *)cells,
                         bytes + 1))
    for (i = 0, bad = 0; bad == 0 && i < T->ck->n; i++) {
      const unsigned char *c = cells + (size_t)i * AFV_TRAJ_CELL_BYTES;
      bad = !(fabs(le_f64(c) - r[2*i]) <= bound
              && fabs(le_f64(c + 8) - r[2*i+1]) <= bound) ? i + 1 : 0;
    }
  free(cells);
  if (bad == 0) return 1;
  if (bad < 0)
    return untrusted(T, OUT_TRAJ, "cannot be read at its last frame");
  snprintf(why, sizeof why, "ends with the frame of step %lld, in which cell "
           "%d is not within %g of the checkpoint's state (%lld steps of at "
           "most %g l + |v0| dt)", step, bad - 1, bound,
           T->ck->step - step, AFV_MAX_STEP_DISP);
  return untrusted(T, OUT_TRAJ, why);
}

/* trajectory.dat (format 2, io.c): its text header line, then frames of
** AFV_TRAJ_FRAME_HEAD + AFV_TRAJ_CELL_BYTES N bytes (step and time, which
** afv_traj_frame_head decodes, then the cells); the file must end, at the
** checkpoint's size, with the whole frame of the last frame step.  A
** format-1 (text) trajectory of afv < 0.3 is not appended to: its run is
** finished with the afv that began it. */
static int traj_agrees(ckpt_trust *T, int fd)
{
  const run_state *R = T->R;
  long long end = T->ck->bytes[OUT_TRAJ], frame = AFV_TRAJ_FRAME_HEAD
                + (long long)AFV_TRAJ_CELL_BYTES * R->cfg.N,
            due_step = last_due(T->ck->step, R->cfg.frame_every), head, step;
  char line[256], why[160];
  unsigned char rec[AFV_TRAJ_FRAME_HEAD + 1] = {0}; /* read_span ends what
                                                    ** it reads with 0 */
  double t = 0;
  if (!line_at(fd, 0, end, line, sizeof line)
      || strncmp(line, "# afv trajectory ", 17) != 0)
    return untrusted(T, OUT_TRAJ, "does not start with a trajectory header");
  if (strncmp(line, "# afv trajectory 2 ", 19) != 0)
    return untrusted(T, OUT_TRAJ, "is in format 1 (text, afv < 0.3), which "
                     "this afv does not append to: finish the run with the "
                     "afv that began it");
  head = (long long)strlen(line) + 1;
  if (due_step < 0)
    return end == head ? 1 : untrusted(T, OUT_TRAJ, "is not the header "
                                       "alone (frame_every 0)");
  if (end < head + frame || (end - head) % frame != 0
      || !read_span(fd, end - frame, end - frame + AFV_TRAJ_FRAME_HEAD,
                    (char *)rec, sizeof rec))
    step = -1;
  else
    afv_traj_frame_head(rec, &step, &t);
  if (step != due_step || t != (double)step * R->cfg.dt) {
    snprintf(why, sizeof why, "does not end with the whole frame of step "
             "%lld", due_step);
    return untrusted(T, OUT_TRAJ, why);
  }
  return last_frame_agrees(T, fd, end - frame + AFV_TRAJ_FRAME_HEAD, step);
}

/* trajectory.dat (above); trajectory.xyz: the count line, a comment with
** Step=S and N rows. */
static int frames_agree(ckpt_trust *T)
{
  const run_state *R = T->R;
  char path[RUN_PATH_MAX + 32];
  int ok, fd;
  long long n = R->cfg.N;
  snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[OUT_TRAJ]);
  if ((fd = open(path, O_RDONLY)) < 0)
    return untrusted(T, OUT_TRAJ, "cannot be read");
  ok = traj_agrees(T, fd);
  close(fd);
  if (!ok || !R->cfg.xyz) return ok;
  snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[OUT_XYZ]);
  if ((fd = open(path, O_RDONLY)) < 0)
    return untrusted(T, OUT_XYZ, "cannot be read");
  {   /* the comment line: "... Properties=... Time=T Step=S" */
    long long start = line_back(fd, T->ck->bytes[OUT_XYZ], n + 1);
    char line[4096], *at;
    long long step = -1, due_step = last_due(T->ck->step, R->cfg.frame_every);
    if (due_step < 0)
      ok = T->ck->bytes[OUT_XYZ] == 0
           || untrusted(T, OUT_XYZ, "holds frames (frame_every 0)");
    else if (start < 0 || !line_at(fd, start, T->ck->bytes[OUT_XYZ], line,
                                   sizeof line)
             || !(at = strstr(line, "Step=")) || sscanf(at, "Step=%lld",
                                                        &step) != 1
             || step != due_step) {
      char why[96];
      snprintf(why, sizeof why, "does not end with the whole frame of step "
               "%lld", due_step);
      ok = untrusted(T, OUT_XYZ, why);
    }
  }
  close(fd);
  return ok;
}

/* The checkpoint's clock and each file's last record (above).  1, or 0
** with the reason in err. */
static int checkpoint_agrees(const run_state *R, const afv_checkpoint *ck,
                             ckpt_trust *T, char *err, size_t errlen)
{
  memset(T, 0, sizeof *T);
  T->R = R;
  T->ck = ck;
  T->err = err;
  T->errlen = errlen;
  if (ck->t != (double)ck->step * R->cfg.dt) {
    afv_errorf(err, errlen, "%s/checkpoint.txt:4: time %.17g, but step %lld "
               "x dt %g is %.17g: the checkpoint does not describe this run "
               "(edited, or another run's); nothing was changed", R->dir,
               ck->t, ck->step, R->cfg.dt, (double)ck->step * R->cfg.dt);
    return 0;
  }
  return obs_agrees(T) && frames_agree(T);
}

/* --steps MORE of a resume: a count of steps, 0 .. 2^63 - 1. */
static int parse_more_steps(const char *text, long long *more)
{
  const char *why = integral_problem(text, 0, LLONG_MAX, more);
  if (!why) return 1;
  cli_errorf("--steps: '%s' %s: not a count of steps (an integer from 0 to "
             "%lld)", text, why, LLONG_MAX);
  return 0;
}

/* NOISE OF 0.5.0.  afv 0.5.0 draws the noise with the library's own log
** (fastmath.h, afv_log) where earlier versions used the C library's, whose
** last bit differs for some uniforms (with glibc on a CPU with FMA, for
** 3.6% of them): a run of afv 0.4.0 or earlier, continued by 0.5.0, would
** be neither its version's run nor 0.5.0's.  So a params.txt whose first
** line says "written by afv X.Y.Z" with X.Y.Z before 0.5.0 is refused,
** naming the version that finishes it (its own); one without that line
** (written by hand) is taken as it is.  0 if the run may go on, else an
** exit status with the message printed. */
static int noise_of_0_5_0(const char *params)
{
  char line[512];
  const char *at;
  int major, minor, patch;
  FILE *fp = fopen(params, "r");
  if (!fp) return 0;                   /* read_config says why */
  if (!fgets(line, sizeof line, fp)) line[0] = 0;
  fclose(fp);
  if (!(at = strstr(line, "written by afv "))
      || sscanf(at + 15, "%d.%d.%d", &major, &minor, &patch) != 3
      || major > 0 || minor >= 5)
    return 0;
  fprintf(stderr, "afv run: %s: a run of afv %d.%d.%d, whose noise used the "
          "C library's log; afv 0.5.0 draws it with its own (other last "
          "bits), so it would not continue this run; finish it with afv "
          "%d.%d.%d\n", params, major, minor, patch, major, minor, patch);
  return EXIT_BAD_INPUT;
}

/* Resume: params.txt (and the cells file it names) into R->cfg; set[k]
** records the line of key k.  0, or an exit status with the message
** printed. */
static int resume_params(run_state *R, const run_args *a, int *set,
                         const char *params)
{
  char err[2 * RUN_PATH_MAX];
  int st;
  if ((st = written_after_0_1_0(params)) != 0) return st;
  if (!read_config(params, &R->cfg, set, err, sizeof err))
    return bad_input(err);
  if ((st = noise_of_0_5_0(params)) != 0) return st;
  if (a->quiet) R->cfg.quiet = a->quiet > 0;
  if (!cfg_validate(&R->cfg, set, &R->cells, err, sizeof err)) {
    locate_error(err, sizeof err, set, params);
    return bad_input(err);
  }
  if (!record_agrees(params, &R->cfg, set, err, sizeof err))
    return bad_input(err);
  return 0;
}

/* Resume: the checkpoint at ckpt against params.txt (cells, seed), its
** step plus --steps MORE (no overflow) and the recorded sizes against
** their files.  *new_steps = 1 if MORE changes the run's steps (R->cfg
** then has the new count).  0, or an exit status with the message
** printed. */
static int resume_checkpoint(run_state *R, long long more, const char *ckpt,
                             afv_checkpoint *ck, int *new_steps,
                             ckpt_trust *T)
{
  char err[2 * RUN_PATH_MAX];
  if (access(ckpt, F_OK) != 0) {
    fprintf(stderr, "afv run: %s has no checkpoint.txt: its run stopped "
            "before its first checkpoint; start it again with afv run "
            "--config %s/params.txt --out %s (a fresh run replaces a run "
            "without a checkpoint)\n", R->dir, R->dir, R->dir);
    return EXIT_BAD_INPUT;
  }
  if (afv_checkpoint_read(ckpt, ck, err, sizeof err) != AFV_OK)
    return bad_input(err);
  if (ck->n != R->cfg.N || ck->seed != R->cfg.seed) {
    fprintf(stderr, "afv run: %s: %d cells and seed %llu, but params.txt "
            "has N %lld and seed %llu: not this run's checkpoint\n", ckpt,
            ck->n, ck->seed, R->cfg.N, R->cfg.seed);
    return EXIT_BAD_INPUT;
  }
  if (ck->step < 0) {
    fprintf(stderr, "afv run: %s: step %lld is negative\n", ckpt, ck->step);
    return EXIT_BAD_INPUT;
  }
  if (more >= 0 && more > LLONG_MAX - ck->step) {
    cli_errorf("--steps: %lld more steps past the checkpoint's step %lld "
               "exceed the largest step count (%lld)", more, ck->step,
               LLONG_MAX);
    return EXIT_BAD_INPUT;
  }
  *new_steps = more >= 0 && R->cfg.steps != ck->step + more;
  if (more >= 0) R->cfg.steps = ck->step + more;
  if (!recorded_sizes_hold(R, ck, err, sizeof err)
      || !checkpoint_agrees(R, ck, T, err, sizeof err))
    return bad_input(err);
  return 0;
}

/* Resume: the simulation at the checkpoint's state, which must be one the
** run can compute with (run_computable), and the T1 reference.  0, or an
** exit status with the message printed. */
static int resume_state(run_state *R, const afv_checkpoint *ck,
                        const char *ckpt, const int *set, const char *params,
                        const ckpt_trust *T)
{
  char err[2 * RUN_PATH_MAX];
  afv_params p;
  afv_box b;
  afv_dyn d;
  int st, i, j;
  cfg_model(&R->cfg, &R->cells, &p, &b, &d);
  st = afv_sim_init(R->sim, ck->n, ck->r, ck->theta, &p, &b, &d);
  afv_geom_bad_pair(afv_sim_geom(R->sim), &i, &j);
  if (st == AFV_ECOINCIDENT)
    afv_errorf(err, sizeof err, "%s: cells %d and %d have the same centre",
               ckpt, i, j);
  else if (st != AFV_OK)
    afv_errorf(err, sizeof err, "%s: %s", ckpt, afv_strerror(st));
  if (st != AFV_OK) return bad_input(err);
  afv_sim_set_steps(R->sim, ck->step);   /* t = step dt: ck->t, checked */
  R->ckpt_step = ck->step;
  if (!run_computable(R, ckpt, err, sizeof err)) {
    locate_error(err, sizeof err, set, params);  /* a key: its line */
    return bad_input(err);
  }
  if (T->has_energy && T->energy != afv_geom_energy(afv_sim_geom(R->sim))) {
    fprintf(stderr, "afv run: %s: its state has the energy %.17g under "
            "params.txt, but observables.csv's row of step %lld has %.17g: "
            "the checkpoint and params.txt do not describe these files "
            "(edited, or another run's); nothing was changed\n", ckpt,
            afv_geom_energy(afv_sim_geom(R->sim)), ck->step, T->energy);
    return EXIT_BAD_INPUT;
  }
  if (!obs_t1_reference(&R->an, R->sim, R->dir, 1)) return EXIT_BAD_INPUT;
  return 0;
}

/* Every check of a resume, before any byte of any file changes: params.txt
** (and the cells file), the checkpoint (against params.txt, --steps MORE,
** every recorded size against its file, the state computable) and the T1
** reference.  Fills R (cfg, sim, an) and *ck.  0, or an exit status with
** the message printed. */
static int resume_checks(run_state *R, const run_args *a, long long more,
                         afv_checkpoint *ck, int *new_steps)
{
  char params[RUN_PATH_MAX + 32], ckpt[RUN_PATH_MAX + 32];
  int set[N_RUN_KEYS], st;
  ckpt_trust T;
  memset(set, 0, sizeof set);
  memset(&T, 0, sizeof T);
  snprintf(params, sizeof params, "%s/params.txt", R->dir);
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", R->dir);
  if ((st = resume_params(R, a, set, params)) != 0
      || (st = resume_checkpoint(R, more, ckpt, ck, new_steps, &T)) != 0)
    return st;
  return resume_state(R, ck, ckpt, set, params, &T);
}

int run_resume(run_state *R, const run_args *a)
{
  char path[RUN_PATH_MAX + 32];
  afv_checkpoint ck;
  long long more = -1;
  int st, new_steps = 0;
  if (a->n_keys > (a->steps != NULL) + a->quiet_kv || a->config || a->out)
    return bad_input("run: with --resume only --steps MORE and --quiet are "
                     "allowed (the parameters are DIR/params.txt)");
  if (a->steps && !parse_more_steps(a->steps, &more)) return EXIT_BAD_INPUT;
  if (strlen(a->resume) > RUN_PATH_MAX - 64)
    return bad_input("--resume: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->resume);
  snprintf(path, sizeof path, "%s/params.txt", R->dir);
  if (access(path, F_OK) != 0) {   /* not a run: refused before the lock */
    fprintf(stderr, "afv run: %s: cannot open: %s (--resume needs a run "
            "directory)\n", path, strerror(errno));
    return EXIT_BAD_INPUT;
  }
  if (!lock_run_dir(R, 0) || !run_files_regular(R->dir))
    return EXIT_BAD_INPUT;
  memset(&ck, 0, sizeof ck);
  st = resume_checks(R, a, more, &ck, &new_steps);
  /* all checked: from here on files change (params.txt atomically) */
  if (st == 0 && new_steps
      && write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
         != AFV_OK)
    st = write_failed(R, "params.txt");
  if (st == 0) remove_stale_temporaries(R->dir);
  if (st == 0 && !open_outputs(R, &ck)) st = EXIT_BAD_INPUT;
  afv_checkpoint_free(&ck);
  if (st != 0) return st;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  log_build(R, "resumed");
  run_log(R, "resuming at step %lld (t = %.6g), to step %lld\n",
          afv_sim_steps(R->sim), afv_sim_time(R->sim), R->cfg.steps);
  return run_loop(R);
}

/* 1 if the run in dir has reached its steps (its checkpoint is at the end)
** and written final.svg, its last output (a run killed between the two is
** resumed, at no step, to write it); -1 if params.txt or the checkpoint
** cannot be read (message printed). */
static int run_finished(const char *dir)
{
  char path[RUN_PATH_MAX + 32], err[2 * RUN_PATH_MAX];
  int set[N_RUN_KEYS], done;
  run_cfg cfg;
  afv_checkpoint ck;
  memset(set, 0, sizeof set);
  cfg_defaults(&cfg);
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (!read_config(path, &cfg, set, err, sizeof err)) return -bad_input(err);
  snprintf(path, sizeof path, "%s/checkpoint.txt", dir);
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK)
    return -bad_input(err);
  snprintf(path, sizeof path, "%s/final.svg", dir);
  done = ck.step >= cfg.steps && access(path, F_OK) == 0;
  afv_checkpoint_free(&ck);
  return done;
}

/* --continue --out DIR: the idempotent job of afv sweep.  No checkpoint in
** DIR (no run, or one that stopped before its first checkpoint, which a
** fresh run replaces): a fresh run.  A checkpointed run short of its
** steps: resumed.  A finished run: left alone.  The fresh run and the
** resume take DIR's lock as always, so a run still being written by
** another process is refused, not touched. */
int run_continue(run_state *R, run_args *a, int argc, char **argv)
{
  char ckpt[RUN_PATH_MAX + 32];
  run_args resume;
  int done;
  if (strlen(a->out) > RUN_PATH_MAX - 64) return bad_input("--out: path too long");
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", a->out);
  if (access(ckpt, F_OK) != 0) return run_fresh(R, a, argc, argv);
  if ((done = same_run_asked(a, argc, argv)) != 0) return done;
  if ((done = run_finished(a->out)) != 0) {
    if (done > 0 && !a->quiet)
      fprintf(stderr, "afv run: %s: finished already\n", a->out);
    return done > 0 ? 0 : EXIT_BAD_INPUT;
  }
  memset(&resume, 0, sizeof resume);
  resume.resume = a->out;
  resume.quiet = a->quiet;
  return run_resume(R, &resume);
}
