/*
** run.c -- afv run: the simulation job (its state, outputs, the run loop,
** a fresh run, cmd_run; cmd/run.h lists the other files of afv run)
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
/* afv.h alone: the job builds its start by afv_protocol_start and reads
** its afv_sim (opaque) through the accessors. */
#include "run.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* Fresh run (resume = 0): C(0) from the current state, written to the
** file; resume = 1: read back.  Prints a message and returns 0 on failure. */
int obs_t1_reference(obs_analysis *an, afv_sim *s,
                            const char *dir, int resume)
{
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 256];
  int st;
  snprintf(path, sizeof path, "%s/t1_reference.txt", dir);
  if (resume)
    return afv_t1_reference_read(path, afv_sim_n(s), &an->t1, err, sizeof err)
           == AFV_OK || !bad_input(err);
  if ((st = afv_clusters_compute(&an->c, afv_sim_geom(s),
                                 afv_sim_positions(s), afv_sim_params(s)->l,
                                 afv_sim_box(s))) == AFV_OK
      && (st = afv_t1_start(&an->t1, &an->c)) == AFV_OK)
    st = afv_t1_reference_write(path, &an->t1);
  if (st != AFV_OK)   /* an I/O error says the system's reason */
    fprintf(stderr, "afv run: %s: cannot write (C(0) of the t1 column): "
            "%s\n", path, st == AFV_EIO && errno ? strerror(errno)
            : afv_strerror(st));
  return st == AFV_OK;
}

static double wall_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void run_log(run_state *R, const char *fmt, ...)
{
  va_list ap;
  if (R->log) {
    va_start(ap, fmt);
    vfprintf(R->log, fmt, ap);
    va_end(ap);
    fflush(R->log);
  }
  if (!R->cfg.quiet) {
    fputs("afv run: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
  }
}

/* log.txt (only): the program that writes what follows, "afv 0.3.0
** (commit ...): a fresh run" or "...: resumed", so each part of a run can
** be traced to its code. */
void log_build(run_state *R, const char *what)
{
  if (!R->log) return;
  fprintf(R->log, "afv %s: %s\n", afv_build_version(), what);
  fflush(R->log);
}

/* Model and dynamics parameters of the configuration, per-cell arrays
** pointing into the cells file's columns. */
void cfg_model(const run_cfg *c, const afv_cells *cl, afv_params *p,
                      afv_box *b, afv_dyn *d)
{
  afv_params_default(p);
  p->l = c->l; p->KA = c->KA; p->KP = c->KP; p->A0 = c->A0; p->P0 = c->P0;
  p->Lambda = c->Lambda; p->cap = c->cap;
  p->KA_i = cl->col[AFV_COL_KA]; p->KP_i = cl->col[AFV_COL_KP];
  p->A0_i = cl->col[AFV_COL_A0]; p->P0_i = cl->col[AFV_COL_P0];
  b->periodic = strcmp(c->box, "periodic") == 0;
  b->Lx = b->Ly = box_side(c);
  afv_dyn_default(d);
  d->mu = c->mu; d->v0 = c->v0; d->Dr = c->Dr; d->dt = c->dt;
  d->seed = c->seed;
  d->v0_i = cl->col[AFV_COL_V0];
  d->Dr_i = cl->col[AFV_COL_DR];
}

/* Distance from cell 0 to its nearest neighbour (minimum image): the
** lattice spacing of a cluster start. */
static double nearest_to_first(int n, const double *r, const afv_box *b)
{
  double best = HUGE_VAL;
  int i;
  for (i = 1; i < n; i++) {
    double dx = r[2*i] - r[0], dy = r[2*i+1] - r[1];
    afv_min_image(b, &dx, &dy);
    if (hypot(dx, dy) < best) best = hypot(dx, dy);
  }
  return best;
}

/* The paper's protocol as the run's keys ask for it (init, spacing, the
** cells file's x y theta; relax, relax_tol and, unless relax_steps is 0,
** relax_max_steps) into pr; r has room for the 2N positions of init file.
** The authors' start (init cluster) is the square of side
** AFV_AUTHORS_SQUARE L, L = sqrt(N pi l^2 / phi). */
static void cfg_protocol(const run_cfg *c, const afv_cells *cl,
                         long relax_steps, double *r, afv_protocol *pr)
{
  int i;
  memset(pr, 0, sizeof *pr);
  if (strcmp(c->init, "cluster") == 0) {
    pr->start = AFV_START_CLUSTER;
    pr->side = AFV_AUTHORS_SQUARE * box_side(c);
  } else if (strcmp(c->init, "lattice") == 0) {
    pr->start = AFV_START_LATTICE;
    pr->spacing = c->spacing * c->l;
  } else if (strcmp(c->init, "random") == 0) {
    pr->start = AFV_START_RANDOM;
    pr->side = box_side(c);
  } else {
    pr->start = AFV_START_GIVEN;
    for (i = 0; i < cl->n; i++) {
      r[2*i] = cl->col[AFV_COL_X][i];
      r[2*i+1] = cl->col[AFV_COL_Y][i];
    }
    pr->r = r;
  }
  pr->theta = cl->has[AFV_COL_THETA] ? cl->col[AFV_COL_THETA] : NULL;
  pr->relax = strcmp(c->relax, "fire") == 0 ? AFV_RELAX_FIRE : AFV_RELAX_FLOW;
  pr->relax_tol = c->relax_tol;
  pr->relax_max_steps = relax_steps;
}

/* R->sim through the protocol (afv_protocol_start): relax_steps 0 gives
** the start alone, as the run checks it before it writes anything;
** relax_steps = relax_max_steps builds that start again (the same
** numbers) and relaxes it, v0 on at the end (rep, mon as afv_relax). */
static int run_protocol(run_state *R, long relax_steps, afv_relax_report *rep,
                        afv_relax_monitor mon)
{
  const run_cfg *c = &R->cfg;
  int n = (int)c->N, st;
  double *r = malloc((size_t)(2 * n + 1) * sizeof(double));
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  if (!r) return AFV_ENOMEM;
  cfg_model(c, &R->cells, &p, &b, &d);
  cfg_protocol(c, &R->cells, relax_steps, r, &pr);
  st = afv_protocol_start(R->sim, n, &p, &b, &d, &pr, rep, mon, R);
  free(r);
  return st;
}

/* energy_computable for the configuration's model (the start refused its
** parameters: afv_params_check's energy bound is energy_computable's). */
static int start_energy_computable(const run_state *R, char *err,
                                   size_t errlen)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  cfg_model(&R->cfg, &R->cells, &p, &b, &d);
  return energy_computable(&p, (int)R->cfg.N, err, errlen);
}

/* The start (positions and angles) and the simulation at it, unrelaxed;
** for init lattice, the spacing it got (start_spacing). */
int run_start(run_state *R, char *err, size_t errlen)
{
  int st = run_protocol(R, 0, NULL, NULL), i, j;
  if (st == AFV_ECOINCIDENT) {
    afv_geom_bad_pair(afv_sim_geom(R->sim), &i, &j);
    afv_errorf(err, errlen, "cells %d and %d of the start have the same "
               "centre", i, j);
  } else if (st == AFV_EINVAL && !start_energy_computable(R, err, errlen)) {
    ;                 /* afv_params_check's bound, the key named */
  } else if (st != AFV_OK)
    afv_errorf(err, errlen, "start: %s", afv_strerror(st));
  else if (strcmp(R->cfg.init, "lattice") == 0)
    R->start_spacing = R->cfg.N > 1 ? nearest_to_first((int)R->cfg.N,
      afv_sim_positions(R->sim), afv_sim_box(R->sim)) / R->cfg.l : 0;
  return st;
}

/* ---- outputs ------------------------------------------------------------ */
/* Records that writing path failed and why (errno, read at once); returns
** AFV_EIO.  report_io prints it: the file and the system's reason. */
static int io_failed(run_state *R, const char *path)
{
  R->io_errno = errno;
  snprintf(R->io_path, sizeof R->io_path, "%s", path);
  return AFV_EIO;
}

static int report_io(const run_state *R)
{
  fprintf(stderr, "afv run: %s: cannot write: %s\n", R->io_path,
          R->io_errno ? strerror(R->io_errno) : "write error");
  return EXIT_BAD_INPUT;
}

/* observables.csv: one header, one row per sample.  To add a column, add
** its name to the header and its value to the row, at the same place. */
static void obs_write_header(FILE *fp)
{
  fputs("step,time,energy,mean_area,mean_perimeter,mean_arc_length,"
        "mean_contacts,max_force,ngc_frac,n_clusters,omega,t1\n", fp);
}

static int obs_write_row(FILE *fp, afv_sim *s, obs_analysis *an)
{
  const afv_geom *g = afv_sim_geom(s);
  const double *area = afv_geom_area(g), *perim = afv_geom_perim(g);
  const double *arc = afv_geom_arc(g);
  const int *contacts = afv_geom_contacts(g);
  double A = 0, P = 0, L = 0, C = 0;
  int i, n = afv_sim_n(s);
  int st = afv_clusters_compute(&an->c, g, afv_sim_positions(s),
                                afv_sim_params(s)->l, afv_sim_box(s));
  if (st != AFV_OK) return st;   /* no row rather than a row of NaN */
  for (i = 0; i < n; i++) {
    A += area[i];
    P += perim[i];
    L += arc[i];
    C += contacts[i];
  }
  fprintf(fp, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,",
          afv_sim_steps(s), afv_sim_time(s), afv_geom_energy(g), A / n,
          P / n, L / n, C / n, afv_sim_max_force(s));
  fprintf(fp, "%.17g,%d,%.17g,%.17g\n", (double)an->c.giant / n,
          an->c.count, an->c.omega, afv_t1_count(&an->t1, &an->c));
  return AFV_OK;
}

/* Extended XYZ (OVITO): wrapped positions, z = 0, polarity as a column. */
static void xyz_write_frame(FILE *fp, afv_sim *s)
{
  const afv_box *b = afv_sim_box(s);
  const double *r = afv_sim_positions(s), *theta = afv_sim_angles(s);
  int i, n = afv_sim_n(s);
  fprintf(fp, "%d\n", n);
  if (b->periodic)
    fprintf(fp, "Lattice=\"%.17g 0 0 0 %.17g 0 0 0 1\" pbc=\"T T F\" ",
            b->Lx, b->Ly);
  fprintf(fp, "Properties=species:S:1:pos:R:3:theta:R:1 Time=%.17g "
          "Step=%lld\n", afv_sim_time(s), afv_sim_steps(s));
  for (i = 0; i < n; i++) {
    double x = r[2*i], y = r[2*i+1];
    afv_wrap(b, &x, &y);
    fprintf(fp, "C %.17g %.17g 0 %.17g\n", x, y, theta[i]);
  }
}

/* An SVG of the current state, written atomically to DIR/name. */
static int write_svg(run_state *R, const char *name)
{
  char path[RUN_PATH_MAX + 64], tmp[RUN_PATH_MAX + 96];
  afv_sim *s = R->sim;
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp)))
    return io_failed(R, tmp);
  if (afv_svg_write(fp, afv_sim_geom(s), afv_sim_n(s), afv_sim_positions(s),
                    afv_sim_angles(s), afv_sim_params(s), afv_sim_box(s))
      != AFV_OK) {
    io_failed(R, tmp);
    fclose(fp);
    remove(tmp);
    return AFV_EIO;
  }
  if (afv_atomic_commit(fp, tmp, path) != AFV_OK) return io_failed(R, path);
  return AFV_OK;
}

/* Flushes the append-only files and records their sizes with the state. */
static int write_checkpoint(run_state *R)
{
  char path[RUN_PATH_MAX + 32];
  afv_checkpoint c;
  int k;
  memset(&c, 0, sizeof c);
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k]) {
      if (fflush(R->out[k]) != 0 || ferror(R->out[k])
          || (c.bytes[k] = (long long)ftell(R->out[k])) < 0) {
        snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
        return io_failed(R, path);
      }
    }
  c.n = afv_sim_n(R->sim);
  c.step = afv_sim_steps(R->sim);
  c.t = afv_sim_time(R->sim);
  c.seed = afv_sim_dyn(R->sim)->seed;
  c.r = afv_sim_positions(R->sim);
  c.theta = afv_sim_angles(R->sim);
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (afv_checkpoint_write(path, &c) != AFV_OK) return io_failed(R, path);
  R->ckpt_step = afv_sim_steps(R->sim);
  return AFV_OK;
}

static int due(long long step, long long every)
{
  return every > 0 && step % every == 0;
}

/* 1 if anything is written at the current step. */
static int outputs_due(const run_state *R)
{
  const run_cfg *c = &R->cfg;
  long long step = afv_sim_steps(R->sim);
  return due(step, c->sample_every) || due(step, c->frame_every)
         || due(step, c->svg_every) || due(step, c->checkpoint_every);
}

/* Everything that is written at the current step (also at step 0).  A
** state that is not finite is never written: AFV_ENONFINITE (state_finite
** says what), and the files end at the last good state. */
static int run_outputs(run_state *R)
{
  const run_cfg *c = &R->cfg;
  afv_sim *s = R->sim;
  char name[64], what[512];
  int st, k;
  if (!outputs_due(R)) return AFV_OK;
  if (!state_finite(s, what, sizeof what)) return AFV_ENONFINITE;
  if (due(afv_sim_steps(s), c->sample_every)
      && (st = obs_write_row(R->out[OUT_OBS], s, &R->an)) != AFV_OK)
    return st;
  if (due(afv_sim_steps(s), c->frame_every)) {
    afv_traj_write_frame(R->out[OUT_TRAJ], afv_sim_steps(s),
                         afv_sim_time(s), afv_sim_n(s),
                         afv_sim_positions(s), afv_sim_angles(s));
    if (R->out[OUT_XYZ]) xyz_write_frame(R->out[OUT_XYZ], s);
  }
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k] && ferror(R->out[k])) {
      char path[RUN_PATH_MAX + 32];
      snprintf(path, sizeof path, "%s/%s", R->dir, afv_checkpoint_files[k]);
      return io_failed(R, path);
    }
  if (due(afv_sim_steps(s), c->svg_every)) {
    snprintf(name, sizeof name, "snap_%09lld.svg", afv_sim_steps(s));
    if (write_svg(R, name) != AFV_OK) return AFV_EIO;
  }
  if (due(afv_sim_steps(s), c->checkpoint_every)) return write_checkpoint(R);
  return AFV_OK;
}

/* Opens the append-only files (run_file_open: regular files only, never
** through a link, locked): fresh (with headers) or cut back to the sizes
** of the checkpoint (recorded_sizes_hold checked them) and appended to;
** and log.txt, appended to.  1, or 0 with a message printed. */
int open_outputs(run_state *R, const afv_checkpoint *ck)
{
  int k;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    if (k == OUT_XYZ && !R->cfg.xyz) continue;
    if (!(R->out[k] = run_file_open(R, afv_checkpoint_files[k],
                                    ck ? ck->bytes[k] : 0)))
      return 0;
  }
  if (!ck) {
    afv_traj_write_header(R->out[OUT_TRAJ], afv_sim_n(R->sim),
                          afv_sim_box(R->sim));
    obs_write_header(R->out[OUT_OBS]);
  }
  return (R->log = run_file_open(R, "log.txt", -1)) != NULL;
}

static void close_outputs(run_state *R)
{
  int k;
  for (k = 0; k < AFV_CKPT_FILES; k++)
    if (R->out[k]) fclose(R->out[k]);
  if (R->log) fclose(R->log);
  memset(R->out, 0, sizeof R->out);
  R->log = NULL;
}

/* Seconds between progress lines when stderr is not a terminal (a log
** file, a SLURM job's output). */
#define PROGRESS_LOG_SECONDS 30.0

/* Not on a terminal (and not quiet): a whole line every
** PROGRESS_LOG_SECONDS with the step, the percentage, the elapsed time
** and the estimated time left. */
static void log_progress(run_state *R, double now)
{
  long long step = afv_sim_steps(R->sim);
  double done = (double)(step - R->start_step), rate;
  if (R->cfg.quiet || now - R->last_progress < PROGRESS_LOG_SECONDS) return;
  R->last_progress = now;
  rate = done / (now - R->wall0 > 1e-9 ? now - R->wall0 : 1e-9);
  fprintf(stderr, "afv run: step %lld of %lld (%.1f%%), %.0f s elapsed, "
          "about %.0f s left\n", step, R->cfg.steps,
          100.0 * (double)step / (double)R->cfg.steps, now - R->wall0,
          rate > 0 ? (double)(R->cfg.steps - step) / rate : 0);
  fflush(stderr);
}

static void show_progress(run_state *R, int final)
{
  double now = wall_seconds(), done, rate, left;
  if (!R->progress && !final) log_progress(R, now);
  if (!R->progress || (!final && now - R->last_progress < 0.5)) return;
  R->last_progress = now;
  done = (double)(afv_sim_steps(R->sim) - R->start_step);
  rate = done / (now - R->wall0 > 1e-9 ? now - R->wall0 : 1e-9);
  left = rate > 0 ? (double)(R->cfg.steps - afv_sim_steps(R->sim)) / rate : 0;
  fprintf(stderr, "\rstep %lld/%lld  t %.6g  %.0f steps/s  %.0f s left   %s",
          afv_sim_steps(R->sim), R->cfg.steps, afv_sim_time(R->sim), rate,
          left, final ? "\n" : "");
  fflush(stderr);
}

/* ---- the run ------------------------------------------------------------ */
static void monitor_relax(void *ctx, long iter, double E, double fmax)
{
  run_state *R = ctx;
  double now = wall_seconds();
  if (!R->progress) {   /* a log, a SLURM output: a line every 30 s, and
                        ** in log.txt, so a slow relaxation is never mute */
    if (now - R->last_progress < PROGRESS_LOG_SECONDS) return;
    R->last_progress = now;
    if (R->log) {
      fprintf(R->log, "relaxing: step %ld of at most %lld, E %.10g, max |F| "
              "%.3e\n", iter, R->cfg.relax_max_steps, E, fmax);
      fflush(R->log);
    }
    if (!R->cfg.quiet)
      fprintf(stderr, "afv run: relaxing: step %ld of at most %lld, E %.10g, "
              "max |F| %.3e\n", iter, R->cfg.relax_max_steps, E, fmax);
    return;
  }
  if (now - R->last_progress < 0.5) return;
  R->last_progress = now;
  fprintf(stderr, "\rrelaxing: step %ld  E %.10g  max|F| %.3e   ", iter, E,
          fmax);
  fflush(stderr);
}

/* Where the relaxation stopped and why, with its figures (the kink
** criterion: afv.h, afv_relax). */
static void log_relax(run_state *R, const afv_relax_report *rep)
{
  int fire = strcmp(R->cfg.relax, "fire") == 0;
  if (fire) {                                   /* relax_fire.c, STOPS */
    run_log(R, "relaxation by FIRE 2.0 (relax fire; a cell moves at most "
            "0.1 l a step): %ld steps (FIRE time %.6g), energy %.10g -> "
            "%.10g, max |F| %.3e: %s\n", rep->iterations, rep->time,
            rep->energy0, rep->energy, rep->max_force, rep->converged
            ? "converged" : rep->at_kink ? "stopped at a kink of E (the "
            "lowest energy stopped falling, max |F| <= 5 there); the "
            "lowest-energy state kept" : rep->refused ? "FIRE cannot step "
            "down from here (2000 uphill restarts in a row, or the lowest "
            "energy stopped falling at max |F| > 5); the lowest-energy state "
            "kept, relax_tol NOT reached, the run goes on" : "NOT reached "
            "within relax_max_steps; the lowest-energy state kept, the run "
            "goes on");
  } else
    run_log(R, "relaxation at v0 = 0 (Euler steps of dt = %g): %ld steps "
            "(t = %.6g; %lld moved a cell more than %g l), energy %.10g -> "
            "%.10g, max |F| %.3e\n", afv_sim_dyn(R->sim)->dt,
            rep->iterations, rep->time, rep->jumps, AFV_MAX_STEP_DISP,
            rep->energy0, rep->energy, rep->max_force);
  if (R->cfg.cap > 0)
    run_log(R, "relaxation: with cap %g the force is regularised near "
            "detachment (PyAFV's contact truncation), so it is not -grad E: "
            "the relaxation follows that force, and E may rise in a step\n",
            R->cfg.cap);
  if (fire) return;                   /* FIRE's stop is in its line above */
  if (rep->converged)
    run_log(R, "relaxation: converged, max |F| %.3e <= relax_tol %g\n",
            rep->max_force, R->cfg.relax_tol);
  else if (rep->at_kink)
    run_log(R, "relaxation: stopped at a kink of E (a triple junction on a "
            "cell's circle, where the force jumps and does not vanish): "
            "over the last %d steps every cell's mean force <= %.2e (bound "
            "%g), mean energy change %.2e of sum |e_i| (bound %g), max |F| "
            "%.3g (bound %g); relax_tol %g not reached\n", AFV_RELAX_WINDOW,
            rep->drift, AFV_RELAX_KINK_DRIFT, rep->drop, AFV_RELAX_KINK_DROP,
            rep->max_force, AFV_RELAX_KINK_FORCE, R->cfg.relax_tol);
  else if (rep->refused)
    run_log(R, "relaxation: stopped at step %ld, which it cannot take: cell "
            "%d would move %g l (> %g l, a runaway) in one step (forces far "
            "too large for mu = %g, dt = %g: check mu, KA, KP, Lambda); "
            "relax_tol %g NOT reached, the run goes on from here\n",
            rep->iterations + 1, afv_sim_bad_cell(R->sim),
            afv_sim_bad_disp(R->sim), AFV_RUNAWAY_MOVE, R->cfg.mu, R->cfg.dt,
            R->cfg.relax_tol);
  else
    run_log(R, "relaxation: NOT reached within relax_max_steps %lld: max "
            "|F| %.3e > relax_tol %g, no kink shown (last window: mean "
            "force %.2e, bound %g; energy change %.2e, bound %g); the run "
            "goes on from here\n", R->cfg.relax_max_steps, rep->max_force,
            R->cfg.relax_tol, rep->drift, AFV_RELAX_KINK_DRIFT, rep->drop,
            AFV_RELAX_KINK_DROP);
}

/* ---- Ctrl-C ------------------------------------------------------------ */
/* Ctrl-C (SIGINT) or a kill (SIGTERM) ends the run at once, as without a
** handler (status 128 + the signal; the files stay as at any moment), after
** one line that says how to go on.  The line is made before the steps: a
** handler may only write(2) it.  A signal the caller ignores (a background
** job's SIGINT) stays ignored. */
static char interrupt_text[2 * RUN_PATH_MAX + 256];
static size_t interrupt_len;

static void on_interrupt(int sig)
{
  ssize_t w = write(STDERR_FILENO, interrupt_text, interrupt_len);
  (void)w;
  signal(sig, SIG_DFL);
  raise(sig);
}

static void catch_interrupt(int sig)
{
  if (signal(sig, on_interrupt) == SIG_IGN) signal(sig, SIG_IGN);
}

/* Says on Ctrl-C what dir holds: in the relaxation (before the first
** checkpoint) the same command starts the run again; in the steps, afv
** run --resume continues it from the last checkpoint to the same bytes. */
static void say_on_interrupt(const char *dir, int stepping)
{
  int m = stepping
    ? snprintf(interrupt_text, sizeof interrupt_text, "\nafv run: "
               "interrupted: %s holds the run up to its last checkpoint; afv "
               "run --resume %s continues it (the same results as a run never "
               "stopped)\n", dir, dir)
    : snprintf(interrupt_text, sizeof interrupt_text, "\nafv run: "
               "interrupted in the relaxation of the start, before the first "
               "checkpoint: the same afv run command starts %s again\n", dir);
  interrupt_len = m > 0 && (size_t)m < sizeof interrupt_text ? (size_t)m : 0;
  catch_interrupt(SIGINT);
  catch_interrupt(SIGTERM);
}

static int relax_start(run_state *R)
{
  afv_relax_report rep;
  int st;
  if (R->cfg.relax_max_steps == 0) {
    run_log(R, "relaxation skipped (relax_max_steps 0); max |F| %.6e\n",
            afv_sim_max_force(R->sim));
    return AFV_OK;
  }
  R->last_progress = wall_seconds();
  say_on_interrupt(R->dir, 0);
  st = run_protocol(R, (long)R->cfg.relax_max_steps, &rep, monitor_relax);
  if (R->progress) fprintf(stderr, "\r%70s\r", "");
  if (st != AFV_OK) return st;
  R->relax_jumps = afv_sim_jumps(R->sim);
  R->relax_largest = afv_sim_largest_move(R->sim);
  log_relax(R, &rep);
  return AFV_OK;
}

/* The end of a stop message: where the run can go on from.  A run whose
** last checkpoint is at step 0 (or that has none yet) would stop the same
** way from it (a run depends on its seed and parameters only), so that
** checkpoint is removed: DIR then holds a run that stopped before its
** first checkpoint, which a fresh run, with other parameters, replaces
** (before, such a directory was dead: a retry was refused as "already
** holds a run" and a resume stopped again). */
static const char *resume_point(const run_state *R, char *buf, size_t len)
{
  char path[RUN_PATH_MAX + 32];
  if (R->ckpt_step > 0) {
    snprintf(buf, len, "last good checkpoint: %s/checkpoint.txt (step %lld)",
             R->dir, R->ckpt_step);
    return buf;
  }
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  remove(path);
  snprintf(buf, len, "no checkpoint kept (from its start the run would stop "
           "the same way): afv run --out %s with other parameters replaces "
           "this run", R->dir);
  return buf;
}

/* The state became non-finite (a step failed on it, or it was about to be
** written): names the cells and what of them; nothing of it is written.
** Exit status 3, like an unstable step: the last checkpoint resumes. */
static int report_nonfinite(run_state *R)
{
  afv_sim *s = R->sim;
  char what[512];
  if (state_finite(s, what, sizeof what))
    snprintf(what, sizeof what, "a step made a position NaN or infinite "
             "(and was undone)");
  char where[RUN_PATH_MAX + 256];
  fprintf(stderr, "%safv run: step %lld (t = %g): %s; not written, the run "
          "stops; %s\n", R->progress ? "\n" : "", afv_sim_steps(s),
          afv_sim_time(s), what, resume_point(R, where, sizeof where));
  if (R->log)
    fprintf(R->log, "stopped at step %lld: %s\n", afv_sim_steps(s), what);
  return EXIT_UNSTABLE;
}

/* What a refused step means (afv_sim_step, AFV_EUNSTABLE). */
static const char *unstable_reason(afv_sim *s)
{
  if (!isfinite(afv_sim_bad_disp(s)))
    return "its force or position is not finite";
  return "a runaway: the forces are far too large for the time step "
         "(check mu, then KA, KP, Lambda)";
}

/* The relaxation refused a step (AFV_EUNSTABLE): says which cell and why,
** discards the run (nothing to keep: from its start it would stop the
** same way) and returns exit status 3, as an unstable step of the run.
** (Before: exit 2, "a move > l/2" where the limit is AFV_RUNAWAY_MOVE, and
** the run's first four files left.) */
static int relax_unstable(run_state *R)
{
  afv_sim *s = R->sim;
  fprintf(stderr, "afv run: relaxation: cell %d would move %g l (> %g l) "
          "in a time %g: %s; nothing kept (from its start the run would "
          "stop the same way)\n", afv_sim_bad_cell(s), afv_sim_bad_disp(s),
          AFV_RUNAWAY_MOVE, afv_sim_dyn(s)->dt, unstable_reason(s));
  discard_run(R);
  return EXIT_UNSTABLE;
}

/* ---- large moves --------------------------------------------------------- */
/* At the end: steps of the active run that moved a cell more than
** AFV_MAX_STEP_DISP l (the forces change on the scale l, so Euler's steps
** no longer followed the dynamics there) earn a warning with their count
** and what helps; a largest move above l that the relaxation of the start
** made (its overlapping cells pushing apart, which sets no result) a note
** that says so.  Where the largest move was: afv_sim_largest_move is a
** running maximum, so the active run made it if it grew after the
** relaxation. */
static void tell_large_moves(run_state *R)
{
  afv_sim *s = R->sim;
  double most = afv_sim_largest_move(s);
  long long active = afv_sim_jumps(s) - R->relax_jumps;
  int relaxed = R->relax_largest > 0 && most <= R->relax_largest;
  const char *where = relaxed ? "in the relaxation of the start, where "
                      "overlapping cells push apart" : "in the active run";
  const char *box = afv_sim_box(s)->periodic
                    && most * R->cfg.l > afv_sim_box(s)->Lx
                    ? ", more than the box side" : "";
  if (active > 0) {
    fprintf(stderr, "afv run: warning: %lld step(s) of the active run moved "
            "a cell more than %g l, where Euler's steps no longer follow the "
            "dynamics (the forces change on the scale l): a smaller dt, or "
            "--cap 0.45 (bounded forces near detachment), keeps the moves "
            "small; the largest move in one step, %.3g l%s, was %s\n",
            active, AFV_MAX_STEP_DISP, most, box, where);
    if (R->log)
      fprintf(R->log, "warning: %lld step(s) of the active run moved a cell "
              "more than %g l; the largest move in one step, %.3g l%s, was "
              "%s\n", active, AFV_MAX_STEP_DISP, most, box, where);
  } else if (most > 1) {
    run_log(R, "note: the largest move of a cell in one step, %.3g l%s, was "
            "%s; no step of the active run moved a cell more than %g l\n",
            most, box, where, AFV_MAX_STEP_DISP);
  }
}


/* The run's last line of log.txt: steps, time, speed, the large moves
** and where the outputs are. */
static void log_finish(run_state *R)
{
  afv_sim *s = R->sim;
  double w = wall_seconds() - R->wall0;
  long long k = afv_sim_steps(s) - R->start_step;
  run_log(R, "%d cells, steps %lld..%lld (t = %.6g) in %.3g s (%.0f "
          "steps/s; Euler steps that moved a cell more than %g l: "
          "%lld, since this process started, relaxation included; "
          "largest move of a cell in one step %.3g l); outputs in %s/: "
          "observables.csv, trajectory.dat, snapshots snap_*.svg and "
          "final.svg\n", afv_sim_n(s), R->start_step, afv_sim_steps(s),
          afv_sim_time(s), w, w > 0 ? (double)k / w : 0.0,
          AFV_MAX_STEP_DISP, afv_sim_jumps(s), afv_sim_largest_move(s),
          R->dir);
}

/* Integrates to cfg.steps.  Returns an exit status. */
int run_loop(run_state *R)
{
  afv_sim *s = R->sim;
  char what[512], where[RUN_PATH_MAX + 256];
  int st = AFV_OK;
  say_on_interrupt(R->dir, 1);
  R->start_step = afv_sim_steps(s);
  R->wall0 = R->last_progress = wall_seconds();
  while (afv_sim_steps(s) < R->cfg.steps) {
    if ((st = afv_sim_step(s)) != AFV_OK) break;
    if ((st = run_outputs(R)) != AFV_OK) break;
    show_progress(R, 0);
  }
  if (st == AFV_EUNSTABLE) {
    int i = afv_sim_bad_cell(s);
    fprintf(stderr, "%safv run: step %lld (t = %g): cell %d would move %g l "
            "(> %g l) in a time %g: %s; %s\n",
            R->progress ? "\n" : "", afv_sim_steps(s) + 1, afv_sim_time(s),
            i, afv_sim_bad_disp(s), AFV_RUNAWAY_MOVE, afv_sim_dyn(s)->dt,
            unstable_reason(s), resume_point(R, where, sizeof where));
    if (R->log) fprintf(R->log, "stopped: unstable step %lld, cell %d\n",
                        afv_sim_steps(s) + 1, i);
    return EXIT_UNSTABLE;
  }
  if (st == AFV_OK && R->ckpt_step != afv_sim_steps(s)
      && !state_finite(s, what, sizeof what))
    st = AFV_ENONFINITE;   /* the final checkpoint would record it */
  if (st == AFV_ECOINCIDENT) {   /* after a step */
    int i, j;
    afv_geom_bad_pair(afv_sim_geom(s), &i, &j);
    fprintf(stderr, "%safv run: step %lld: %s (cells %d and %d): the time "
            "step dt = %g is probably too large; %s\n",
            R->progress ? "\n" : "", afv_sim_steps(s), afv_strerror(st),
            i, j, afv_sim_dyn(s)->dt, resume_point(R, where, sizeof where));
    return EXIT_UNSTABLE;
  }
  if (st == AFV_ENONFINITE) return report_nonfinite(R);
  if (st == AFV_EIO) return report_io(R);
  if (st != AFV_OK) {
    fprintf(stderr, "afv run: step %lld: %s\n", afv_sim_steps(s),
            afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if ((R->ckpt_step != afv_sim_steps(s) && write_checkpoint(R) != AFV_OK)
      || write_svg(R, "final.svg") != AFV_OK)
    return report_io(R);
  show_progress(R, 1);
  log_finish(R);
  tell_large_moves(R);
  return 0;
}

/* Prints "afv run: DIR/NAME: cannot write: REASON" (errno at the call);
** EXIT_BAD_INPUT. */
int write_failed(run_state *R, const char *name)
{
  char path[RUN_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  io_failed(R, path);
  return report_io(R);
}

int run_fresh(run_state *R, const run_args *a, int argc, char **argv)
{
  char err[2 * RUN_PATH_MAX] = "";
  int set[N_RUN_KEYS], st;
  memset(set, 0, sizeof set);
  long holder;
  if (strlen(a->out) > RUN_PATH_MAX - 64) return bad_input("--out: path too long");
  snprintf(R->dir, sizeof R->dir, "%s", a->out);
  if ((holder = run_lock_holder(R->dir)) > 0)   /* at once, before the start */
    return report_in_use(R->dir, holder);
  if ((st = requested_cfg(&R->cfg, &R->cells, a, argc, argv, set)) != 0)
    return st;
  if (run_start(R, err, sizeof err) != AFV_OK) return bad_input(err);
  if (!run_computable(R, "the start", err, sizeof err)) {
    locate_error(err, sizeof err, set, a->config);
    return bad_input(err);
  }
  /* everything is checked: only now is anything created */
  if (!make_out_dir(R)) return EXIT_BAD_INPUT;
  R->progress = !R->cfg.quiet && isatty(STDERR_FILENO);
  /* params.txt first: a directory with it is afv's (foreign_files) */
  if (write_params(R->dir, &R->cfg, R->cells.n ? "cells.txt" : "none")
      != AFV_OK)
    return write_failed(R, "params.txt");
  if (R->cells.n && write_cells_copy(R->dir, &R->cells) != AFV_OK)
    return write_failed(R, "cells.txt");
  if (!open_outputs(R, NULL)) return EXIT_BAD_INPUT;
  log_build(R, "a fresh run");
  if (R->start_spacing > 0
      && R->start_spacing < R->cfg.spacing * (1 - 1e-9))
    run_log(R, "cluster start: spacing %.6g l instead of %.6g l, so that "
            "the cluster fits the box\n", R->start_spacing, R->cfg.spacing);
  if ((st = relax_start(R)) == AFV_ENONFINITE) return report_nonfinite(R);
  if (st == AFV_EUNSTABLE) return relax_unstable(R);
  if (st != AFV_OK) {
    fprintf(stderr, "afv run: relaxation: %s\n", afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  if (!obs_t1_reference(&R->an, R->sim, R->dir, 0)) return EXIT_BAD_INPUT;
  st = run_outputs(R);
  if (st == AFV_OK && !due(0, R->cfg.checkpoint_every))
    st = write_checkpoint(R);
  if (st == AFV_ENONFINITE) return report_nonfinite(R);
  if (st != AFV_OK) return report_io(R);
  return run_loop(R);
}

int cmd_run(int argc, char **argv)
{
  run_state R;
  run_args a;
  int m = scan_args(argc, argv, &a), status;
  if (m < 0) return 0;
  if (m == 0) return EXIT_BAD_INPUT;
  if (!a.out == !a.resume)
    return bad_input("run: give either --out DIR (a new run) or --resume "
                     "DIR (see afv run --help)");
  if (a.cont && !a.out)
    return bad_input("run: --continue goes with --out DIR (see afv run "
                     "--help)");
  memset(&R, 0, sizeof R);
  R.lock_fd = R.dir_fd = -1;
  cfg_defaults(&R.cfg);
  if (!(R.sim = afv_sim_new())) return bad_input("run: out of memory");
  status = a.resume ? run_resume(&R, &a)
           : a.cont ? run_continue(&R, &a, argc, argv)
           : run_fresh(&R, &a, argc, argv);
  close_outputs(&R);
  unlock_run_dir(&R);
  afv_sim_delete(R.sim);
  afv_cells_free(&R.cells);
  afv_clusters_free(&R.an.c);
  afv_t1_free(&R.an.t1);
  return status;
}
