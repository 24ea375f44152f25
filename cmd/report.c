/*
** report.c -- afv analyze: a run's order parameters and plots, written to files
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>     /* kill(PID, 0): is a staging folder's process alive */
#include <sys/file.h>   /* flock: not POSIX, but in every libc afv meets */
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>


/* Fewer time origins than this behind the lag of D_s earn a warning: the
** average of a handful of displacements is not a diffusivity. */
#define MIN_LAG_ORIGINS 10

/* Lag of D_s when --lag is not given (the paper's, in time units). */
#define DEFAULT_LAG 5000.0

static const char *analyze_usage =
  "usage: afv analyze DIR [--lag L] [--steady-from T] [--l L] [--v0 V]"
  " [--Dr D]\n"
  "                   [--partial]\n\n"
  "Reads DIR/trajectory.dat (and l, v0, Dr from DIR/params.txt, which\n"
  "must be read whole; options override) and writes DIR/analysis/ (two\n"
  "analyses of one run at once: one after the other, each whole):\n"
  "  summary.txt  KEY VALUE: steady means and standard deviations of\n"
  "               N_GC/N, number of clusters and Omega; final T1; D_s,\n"
  "               D_eff = D_s / D_0 (D_0 = v0^2 / (2 Dr); nan at v0 = 0\n"
  "               or Dr = 0, where D_0 is 0 or undefined);\n"
  "               tau_NGC; t1_rate (T1 events per cell per unit time\n"
  "               between steady frames); msd_beta (slope of log MSD_rel\n"
  "               vs log lag, lags 1% .. 10% of the window: ~0 caged,\n"
  "               ~1 fluid); the window, the lag of D_s and its origins;\n"
  "               run_id (DIR's name) and run_fingerprint (of the keys of\n"
  "               params.txt and the id), by which afv collect ties the\n"
  "               summary to its run\n"
  "  series.csv   time, ngc_frac, n_clusters, omega, t1 per frame\n"
  "  msd.csv      lag, msd, msd_rel (relative to contacting neighbours)\n"
  "  csd.csv      n, p(n): cluster size distribution over steady frames\n"
  "  csd_binned.csv  n_lo, n_hi, p_bin, p_per_n: csd.csv in log bins\n"
  "               (sizes 2^k .. 2^(k+1) - 1)\n"
  "  msd.svg, series.svg, csd.svg   plots\n\n"
  "  --lag L          lag for D_s = MSD_rel / (4 L), in time units; the\n"
  "                   computed lag nearest to L is used (default 5000, or\n"
  "                   the longest the run holds); a lag longer than the\n"
  "                   steady window or shorter than a frame is refused\n"
  "  --steady-from T  steady part: frames with time >= T (default 0); a\n"
  "                   window with fewer than 2 frames is refused\n"
  "  --l L            maximal cell radius (default: params.txt, else 1)\n"
  "  --v0 V           self-propulsion speed for D_0 (default: params.txt,\n"
  "                   else 0.5)\n"
  "  --Dr D           rotational diffusion for D_0 (default: params.txt,\n"
  "                   else 0.1)\n"
  "  --partial        analyse a run that has not finished (its checkpoint\n"
  "                   short of its steps, or afv run still writing in DIR)\n"
  "                   from the frames it has so far; without it such a run\n"
  "                   is refused, exit status 1, nothing written\n\n"
  "The trajectory must be the run's: its header has params.txt's N and\n"
  "box; a finished run's has the size and last frame its checkpoint\n"
  "records; no centre moves between two frames S steps apart by more than\n"
  "S (" AFV_STR(AFV_MAX_STEP_DISP) " l + |v0| dt) (a larger move is a jump on every step).\n";


/* The steady window [steady_from, end] must hold two frames, and a lag
** given by the user (lag_given) must fit in it and be no shorter than the
** frame interval: else D_s would be measured at another lag (before, a
** window past the end gave D_s = 0, a glassy label for any tissue).
** Prints one line and returns 0 when it does not. */
static int window_holds(const afv_traj_file *tr, const char *path,
                        double from, double lag, int lag_given)
{
  int first = 0, last = tr->nframes - 1;
  double span;
  while (first < last && tr->t[first] < from) first++;
  if (tr->t[first] < from || first == last) {
    fprintf(stderr, "afv analyze: --steady-from %g: %s ends at t = %g, the "
            "steady window needs 2 frames or more\n", from, path,
            tr->t[last]);
    return 0;
  }
  span = tr->t[last] - tr->t[first];
  if (lag_given && (lag > span * (1 + 1e-9)
                    || lag < 0.5 * (tr->t[first + 1] - tr->t[first]))) {
    char lag_text[32], span_text[32];   /* in full: 20.0000001 > 20 */
    fprintf(stderr, "afv analyze: --lag %s: the steady window t = %g .. %g "
            "of %s holds lags %g .. %s only\n",
            exact_text(lag, lag_text, sizeof lag_text), tr->t[first],
            tr->t[last], path, tr->t[first + 1] - tr->t[first],
            exact_text(span, span_text, sizeof span_text));
    return 0;
  }
  return 1;
}

/* D_s is only as good as the lag it is measured at: say so when the
** default lag is beyond the run, or has few time origins behind it. */
static void warn_if_lag_unsupported(const afv_analysis *a, double lag)
{
  const afv_msd *m = &a->msd;
  int k;
  for (k = 0; k < m->nlags && m->dt[k] != a->ds_lag; k++) {}
  if (k == m->nlags) return;
  if (lag > 1.5 * a->ds_lag)
    fprintf(stderr, "afv analyze: warning: the default lag %g is beyond the "
            "run; D_s is measured at lag %g instead (give --lag)\n", lag,
            a->ds_lag);
  if (a->n > 0 && m->samples[k] / a->n < MIN_LAG_ORIGINS)
    fprintf(stderr, "afv analyze: warning: D_s at lag %g rests on %ld "
            "time origin(s) only (fewer than %d)\n", a->ds_lag,
            m->samples[k] / a->n, MIN_LAG_ORIGINS);
}

/* The pictures of an analysis, written into dir (the staging folder): the
** numbers come from analysis.c, the drawing from svg.c.  On failure one
** line names the file and the system's reason (ENOSPC: "No space left on
** device", not "input/output error"). */
static int analyze_plots(const char *dir, const afv_analysis *a,
                         const char *keep)
{
  static const char *names[3] = {"msd.svg", "series.svg", "csd.svg"};
  int (*const draw[3])(FILE *, const afv_analysis *) = {
    afv_svg_msd, afv_svg_series, afv_svg_csd
  };
  char path[RUN_PATH_MAX + 96], tmp[RUN_PATH_MAX + 160];
  int k;
  for (k = 0; k < 3; k++) {
    FILE *fp;
    int st, why;
    snprintf(path, sizeof path, "%s/%s", dir, names[k]);
    if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) {
      fprintf(stderr, "afv analyze: %s: cannot create: %s (%s is "
              "unchanged)\n", path, strerror(errno), keep);
      return EXIT_BAD_INPUT;
    }
    st = draw[k](fp, a);
    why = errno;                       /* a failed write's reason */
    if (st != AFV_OK) {
      fclose(fp);
      remove(tmp);
      errno = why;
    } else {
      st = afv_atomic_commit(fp, tmp, path);
    }
    if (st != AFV_OK) {
      fprintf(stderr, "afv analyze: %s: cannot write: %s (%s is "
              "unchanged)\n", path, st == AFV_EIO ? strerror(errno)
              : afv_strerror(st), keep);
      return EXIT_BAD_INPUT;
    }
  }
  return 0;
}

/* Moves every file of the staging folder into out, summary.txt last (the
** sign that an analysis is complete).  0, or EXIT_BAD_INPUT with a line. */
static int stage_commit(const char *stage, const char *out)
{
  char from[RUN_PATH_MAX + 320], to[RUN_PATH_MAX + 320];
  DIR *d;
  struct dirent *e;
  int last;
  for (last = 0; last < 2; last++) {
    if (!(d = opendir(stage))) break;
    while ((e = readdir(d)))
      if (e->d_name[0] != '.'
          && (strcmp(e->d_name, "summary.txt") == 0) == last) {
        snprintf(from, sizeof from, "%s/%s", stage, e->d_name);
        snprintf(to, sizeof to, "%s/%s", out, e->d_name);
        if (rename(from, to) != 0) {
          fprintf(stderr, "afv analyze: cannot move %s to %s: %s\n", from,
                  to, strerror(errno));
          closedir(d);
          return EXIT_BAD_INPUT;
        }
      }
    closedir(d);
  }
  rmdir(stage);
  return 0;
}

/* The files an analysis writes into its staging folder (analysis.c's
** afv_analysis_write and analyze_plots), and nothing else. */
static const char *const staged_files[] = {
  "msd.csv", "csd.csv", "csd_binned.csv", "series.csv", "summary.txt",
  "msd.svg", "series.svg", "csd.svg"
};

/* 1 if name is one of staged_files or the temporary of one
** (NAME.PID.RAND.tmp, afv_atomic_open). */
static int staged_name(const char *name)
{
  size_t k, m, n = strlen(name);
  for (k = 0; k < sizeof staged_files / sizeof staged_files[0]; k++) {
    m = strlen(staged_files[k]);
    if (strncmp(name, staged_files[k], m) == 0
        && (name[m] == 0 || (name[m] == '.' && n > m + 4
                             && strcmp(name + n - 4, ".tmp") == 0)))
      return 1;
  }
  return 0;
}

/* The process id of a staging folder's name, analysis.tmp.PID.XXXXXX
** (stage_make), or 0 if name is not one. */
static long stage_pid(const char *name)
{
  const char *pid = name + 13, *dot;       /* after "analysis.tmp." */
  if (strncmp(name, "analysis.tmp.", 13) != 0 || !(dot = strchr(pid, '.'))
      || dot == pid || dot - pid > 9 || strlen(dot + 1) != 6
      || strspn(pid, "0123456789") != (size_t)(dot - pid))
    return 0;
  return atol(pid);
}

/* Removes the files of staged_files' names in the staging folder dir,
** then dir itself if it is empty (a user's file in it keeps it). */
static void stage_clear(const char *dir)
{
  remove_named(dir, staged_name);
  rmdir(dir);
}

/* A killed analysis (SIGKILL cannot be caught) leaves its staging folder
** in DIR.  The next analysis of DIR removes every staging folder whose
** process is gone (kill(PID, 0): ESRCH) -- only the files of
** staged_files' names, then the folder if it is empty -- so a folder
** holding anything else (a user's file), a link, or a live analysis's
** folder stays. */
static void remove_stale_stages(const char *dir)
{
  char stage[RUN_PATH_MAX + 300];
  DIR *d = opendir(dir);
  struct dirent *e;
  struct stat sb;
  long pid;
  while (d && (e = readdir(d)) != NULL) {
    if ((pid = stage_pid(e->d_name)) <= 0 || kill((pid_t)pid, 0) == 0
        || errno != ESRCH)
      continue;
    snprintf(stage, sizeof stage, "%s/%s", dir, e->d_name);
    if (lstat(stage, &sb) == 0 && S_ISDIR(sb.st_mode)) stage_clear(stage);
  }
  if (d) closedir(d);
}

/* The staging folder of this analysis: a new directory
** DIR/analysis.tmp.PID.XXXXXX (mkdtemp: a name no one has, created
** exclusively, never through a link), so two analyses of one run never
** share one and a user's analysis.tmp/ (or a link there) is never
** emptied or removed.  1, or 0 with a message. */
static int stage_make(const char *dir, char *stage, size_t len)
{
  snprintf(stage, len, "%s/analysis.tmp.%ld.XXXXXX", dir, (long)getpid());
  if (mkdtemp(stage)) return 1;
  fprintf(stderr, "afv analyze: cannot create %s: %s\n", stage,
          strerror(errno));
  return 0;
}

/* Opens DIR/analysis/ (created if missing; a directory, never a link) and
** holds an exclusive flock on it until *fd is closed: two analyses of one
** run commit one after the other, so analysis/ holds one analysis whole.
** Where the file system has no flock for directories (NFS), the analysis
** goes on unlocked.  1, or 0 with a message. */
static int analysis_lock(const char *out, int *fd)
{
  struct stat sb;
  if (mkdir(out, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv analyze: cannot create %s: %s\n", out,
            strerror(errno));
    return 0;
  }
  if (lstat(out, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "afv analyze: %s: not a directory (a link, or a file; "
            "afv writes only into its own analysis/)\n", out);
    return 0;
  }
  if ((*fd = open(out, O_RDONLY | O_DIRECTORY | O_NOFOLLOW)) < 0) {
    fprintf(stderr, "afv analyze: %s: cannot open: %s\n", out,
            strerror(errno));
    return 0;
  }
  while (flock(*fd, LOCK_EX) != 0 && errno == EINTR) {}
  return 1;
}

/* A params.txt that cannot be read whole (err: where and why): refused,
** exit status 2, nothing written. */
static int params_unreadable(const char *err)
{
  fprintf(stderr, "afv analyze: %s; analyze takes l, v0 and Dr from it and "
          "uses no defaults for a damaged params.txt; nothing written\n",
          err);
  return EXIT_BAD_INPUT;
}

/* The name of directory dir (its last component, trailing '/' ignored)
** into out. */
static void dir_name(const char *dir, char *out, size_t len)
{
  size_t end = strlen(dir), start;
  while (end > 1 && dir[end - 1] == '/') end--;
  for (start = end; start > 0 && dir[start - 1] != '/'; start--) {}
  snprintf(out, len, "%.*s", (int)(end - start), dir + start);
}

/* Appends the run's id (its directory's name) and fingerprint
** (run_fingerprint: params.txt and the id) to the staged summary.txt, so
** that afv collect can tie the summary to its run.  0, or EXIT_BAD_INPUT
** with a message. */
static int stage_fingerprint(const char *stage, const char *dir)
{
  char path[RUN_PATH_MAX + 96], id[RUN_PATH_MAX], print[32] = "none";
  char err[2 * RUN_PATH_MAX];
  FILE *fp;
  int bad;
  dir_name(dir, id, sizeof id);
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (run_fingerprint(path, id, print, sizeof print, err, sizeof err) < 0)
    return params_unreadable(err);
  snprintf(path, sizeof path, "%s/summary.txt", stage);
  if (!(fp = fopen(path, "a"))) bad = 1;
  else {
    fprintf(fp, "run_id %s\nrun_fingerprint %s\n", id, print);
    bad = fclose(fp) != 0;
  }
  if (bad)
    fprintf(stderr, "afv analyze: %s: cannot write: %s\n", path,
            strerror(errno));
  return bad ? EXIT_BAD_INPUT : 0;
}

/* Writes the analysis into its own staging folder (stage_make), then,
** once every file is written, moves them into DIR/analysis/ under its
** lock: a full disk or any other write error leaves DIR/analysis/ as it
** was, and a second analysis at the same time waits for the first's
** commit. */
static int analyze_write(const char *dir, const afv_analysis *a)
{
  char out[RUN_PATH_MAX + 32], stage[RUN_PATH_MAX + 64];
  char err[RUN_PATH_MAX + 128];
  int lock = -1, st;
  snprintf(out, sizeof out, "%s/analysis", dir);
  remove_stale_stages(dir);
  if (!stage_make(dir, stage, sizeof stage)) return EXIT_BAD_INPUT;
  if (analyze_plots(stage, a, out) != 0) {
    stage_clear(stage);
    return EXIT_BAD_INPUT;
  }
  if (afv_analysis_write(a, stage, err, sizeof err) != AFV_OK) {
    stage_clear(stage);
    fprintf(stderr, "afv analyze: %s (%s is unchanged)\n", err, out);
    return EXIT_BAD_INPUT;
  }
  if (stage_fingerprint(stage, dir) != 0) {
    stage_clear(stage);
    return EXIT_BAD_INPUT;
  }
  st = analysis_lock(out, &lock) ? stage_commit(stage, out) : EXIT_BAD_INPUT;
  if (lock >= 0) close(lock);
  if (st != 0) {
    stage_clear(stage);
    return st;
  }
  printf("frames %d (steady from %d)\nngc_frac_mean %.6g\nn_clusters_mean "
         "%.6g\nomega_mean %.6g\nt1_final %g\nD_s %.6g\nD_eff %.6g\n"
         "tau_NGC %.6g\nt1_rate %.6g\nmsd_beta %.6g\nwritten: %s/\n",
         a->nframes, a->first, a->mean[0], a->mean[1], a->mean[2],
         a->t1_final, a->ds, a->deff, a->tau_ngc, a->t1_rate, a->msd_beta,
         out);
  return 0;
}

/* 1 if dir is a directory holding a trajectory.dat; else one line naming
** what is missing, before any other message (a typo in DIR must not first
** read as a missing params.txt). */
static int run_dir_readable(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  struct stat sb;
  if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "afv analyze: %s: %s\n", dir, stat(dir, &sb) != 0
            ? strerror(errno) : "not a directory");
    return 0;
  }
  snprintf(path, sizeof path, "%s/trajectory.dat", dir);
  if (access(path, R_OK) != 0) {
    fprintf(stderr, "afv analyze: %s: no run here: %s: %s\n", dir, path,
            strerror(errno));
    return 0;
  }
  return 1;
}

/* 1 if the run in dir has not finished, with the reason in why: afv run
** still writes in it (it holds the lock on observables.csv), or its
** checkpoint is short of the steps params.txt asks for (or missing, or
** unreadable), or it stopped before writing final.svg, its last output.
** 0 if it finished, or if dir holds no params.txt (steps < 0: a
** trajectory from elsewhere, nothing to compare with). */
static int run_unfinished(const char *dir, long long steps, char *why,
                          size_t len)
{
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 128];
  long pid = run_lock_holder(dir);
  afv_checkpoint ck;
  long long at;
  if (pid > 0) {
    snprintf(why, len, "the run is still being written by process %ld (it "
             "holds the lock on %s/observables.csv)", pid, dir);
    return 1;
  }
  if (steps < 0) return 0;   /* no params.txt */
  snprintf(path, sizeof path, "%s/checkpoint.txt", dir);
  if (afv_checkpoint_read(path, &ck, err, sizeof err) != AFV_OK) {
    snprintf(why, len, "the run's end is unknown: %s", err);
    return 1;
  }
  at = ck.step;
  afv_checkpoint_free(&ck);
  snprintf(path, sizeof path, "%s/final.svg", dir);
  if (at >= steps && access(path, F_OK) == 0) return 0;
  snprintf(why, len, "the run is unfinished: checkpoint.txt is at step %lld "
           "of the %lld in params.txt%s", at, steps, at >= steps
           ? ", and final.svg, its last output, is missing" : "");
  return 1;
}

/* Refuses an unfinished run (exit EXIT_RUN_UNFINISHED), or with --partial
** (accept) says that its frames so far are analysed; 0 to go on, with
** *finished = 1 if the run is an afv run's that reached its end. */
static int refuse_unfinished(const char *dir, long long steps, int accept,
                             int *finished)
{
  char why[2 * RUN_PATH_MAX + 256];
  *finished = 0;
  if (!run_unfinished(dir, steps, why, sizeof why)) {
    *finished = steps >= 0;
    return 0;
  }
  if (accept) {
    fprintf(stderr, "afv analyze: warning: %s: %s: analysing its frames so "
            "far (--partial)\n", dir, why);
    return 0;
  }
  fprintf(stderr, "afv analyze: %s: %s; nothing written (--partial "
          "analyses its frames so far)\n", dir, why);
  return EXIT_RUN_UNFINISHED;
}

/* ---- the trajectory is the run's ---------------------------------------- */
/* afv analyze trusts a trajectory only as far as it agrees with its run
** (an edited header box of 4 or 1e308, a file cut to 10 of its 31 frames,
** a centre of 1e5 gave numbers before, D_s 3.5e6):
**  - the header: params.txt's N cells, its box (periodic of side L = sqrt(N
**    pi l^2 / phi), bit for bit, or open);
**  - a finished run's: the size its checkpoint records, so every frame,
**    the last one of the last frame step, its centres those of the
**    checkpoint, bit for bit, where that step is the checkpoint's;
**  - MOVE BOUND: between two frames S steps apart no centre moves more than
**    S (AFV_MAX_STEP_DISP l + |v0| dt): a step that moves a cell farther
**    than AFV_MAX_STEP_DISP l is a jump (counted in log.txt), and a run in
**    which every step jumps is no run to analyse.  Not checked for runs
**    with per-cell v0 (a cells file). */

/* Step of the last frame at or before step, frames every `every` steps. */
static long long last_frame_step(long long step, long long every)
{
  return every > 0 ? step / every * every : -1;
}

static int traj_header_ok(const afv_traj_file *tr, const char *path,
                          const run_params_info *P)
{
  if (!P->afv_run) return 1;
  if (tr->n != P->N) {
    fprintf(stderr, "afv analyze: %s: %d cells, but params.txt has N %lld: "
            "not this run's trajectory\n", path, tr->n, P->N);
    return 0;
  }
  if (tr->box.periodic != P->periodic
      || (P->periodic && (tr->box.Lx != P->L || tr->box.Ly != P->L))) {
    fprintf(stderr, "afv analyze: %s: its header's box (%s %.17g x %.17g) "
            "is not params.txt's (%s, side %.17g): not this run's "
            "trajectory\n", path, tr->box.periodic ? "periodic" : "open",
            tr->box.Lx, tr->box.Ly, P->periodic ? "periodic" : "open", P->L);
    return 0;
  }
  return 1;
}

/* A finished run's trajectory ends where its checkpoint says; r has room
** for a frame. */
static int traj_ends_at_checkpoint(afv_traj_file *tr, const char *dir,
                                   const char *path,
                                   const run_params_info *P, double *r)
{
  char ckpt[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 128];
  struct stat sb;
  afv_checkpoint ck;
  long long want;
  int last = tr->nframes - 1, ok = 1;
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", dir);
  if (afv_checkpoint_read(ckpt, &ck, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  want = last_frame_step(ck.step, P->frame_every);
  if (stat(path, &sb) != 0 || (long long)sb.st_size != ck.bytes[0]
      || tr->step[last] != want) {
    fprintf(stderr, "afv analyze: %s: %lld bytes, %d frames, the last of "
            "step %lld, but its checkpoint (%s) records %lld bytes and step "
            "%lld: the trajectory is not the finished run's (cut, or "
            "edited)\n", path, (long long)sb.st_size, tr->nframes,
            tr->step[last], ckpt, ck.bytes[0], want);
    ok = 0;
  } else if (want == ck.step
             && (afv_traj_frame(tr, last, r, NULL, err, sizeof err) != AFV_OK
                 || memcmp(r, ck.r, 2 * (size_t)ck.n * sizeof *r) != 0)) {
    fprintf(stderr, "afv analyze: %s: its last frame (step %lld) is not "
            "the state its checkpoint records: not the finished run's\n",
            path, want);
    ok = 0;
  }
  afv_checkpoint_free(&ck);
  return ok;
}

/* MOVE BOUND over every pair of frames; a and b have room for a frame. */
static int traj_moves_bounded(afv_traj_file *tr, const char *path,
                              const run_params_info *P, double *a, double *b)
{
  char err[RUN_PATH_MAX + 128];
  int k, i;
  for (k = 0; k < tr->nframes; k++) {
    double *now = k % 2 ? b : a, *before = k % 2 ? a : b, bound;
    if (afv_traj_frame(tr, k, now, NULL, err, sizeof err) != AFV_OK)
      return !bad_input(err);
    if (k == 0) continue;
    bound = (double)(tr->step[k] - tr->step[k - 1])
            * (AFV_MAX_STEP_DISP * P->l + fabs(P->v0) * P->dt);
    for (i = 0; i < tr->n; i++) {
      double d = hypot(now[2*i] - before[2*i], now[2*i+1] - before[2*i+1]);
      if (d <= bound) continue;
      fprintf(stderr, "afv analyze: %s: frame %d (step %lld): cell %d moved "
              "%g since the frame before, beyond %g, %lld steps of at most "
              "%g l + |v0| dt (a larger move is a jump on every step): not "
              "a trajectory of this run (edited?)\n", path, k, tr->step[k],
              i, d, bound, tr->step[k] - tr->step[k - 1], AFV_MAX_STEP_DISP);
      return 0;
    }
  }
  return 1;
}

/* The checks above (finished: the run reached its end). */
static int traj_is_the_runs(afv_traj_file *tr, const char *dir,
                            const char *path, const run_params_info *P,
                            int finished)
{
  double *a, *b;
  int ok;
  if (!traj_header_ok(tr, path, P)) return 0;
  if (!P->afv_run) return 1;
  a = malloc(2 * (size_t)tr->n * sizeof *a + 1);
  b = malloc(2 * (size_t)tr->n * sizeof *b + 1);
  ok = a && b && (!finished || traj_ends_at_checkpoint(tr, dir, path, P, a))
       && (P->cells || traj_moves_bounded(tr, path, P, a, b));
  if (!a || !b) bad_input("analyze: out of memory");
  free(a);
  free(b);
  return ok;
}

/* The command line of afv analyze. */
typedef struct analyze_args {
  const char *dir;
  double lag, from;        /* lag NAN: not given */
  double l, v0, Dr;        /* NAN: not given (params.txt's, else defaults) */
  int partial;             /* --partial */
} analyze_args;

/* Reads the options into o: 0, -1 after --help (exit 0), or an exit
** status with the message printed. */
static int analyze_options(int argc, char **argv, analyze_args *o)
{
  int k, bad = 0;
  memset(o, 0, sizeof *o);
  o->lag = o->l = o->v0 = o->Dr = NAN;
  for (k = 1; k < argc && !bad; k++) {
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      fputs(analyze_usage, stdout);
      return -1;
    }
    if (strcmp(argv[k], "--partial") == 0) {
      o->partial = 1;
      continue;
    }
    if (double_option(argc, argv, &k, "--lag", &o->lag, &bad)
        || double_option(argc, argv, &k, "--steady-from", &o->from, &bad)
        || double_option(argc, argv, &k, "--l", &o->l, &bad)
        || double_option(argc, argv, &k, "--v0", &o->v0, &bad)
        || double_option(argc, argv, &k, "--Dr", &o->Dr, &bad))
      continue;
    if (argv[k][0] == '-' && argv[k][1])
      return unknown_option(argv[k], analyze_usage, NULL);
    if (o->dir) return bad_input("analyze: more than one DIR given");
    o->dir = argv[k];
  }
  if (bad) return EXIT_BAD_INPUT;
  if (!o->dir)
    return bad_input("analyze: missing DIR (see afv analyze --help)");
  if (strlen(o->dir) > RUN_PATH_MAX - 64)
    return bad_input("analyze: DIR too long");
  return 0;
}

/* l, v0 and Dr of the analysis: the options, else params.txt's (read
** whole into P), else the defaults for a trajectory without one.  0, or
** an exit status with the message printed. */
static int analyze_params(const analyze_args *o, run_params_info *P,
                          double *l, double *v0, double *Dr)
{
  char path[RUN_PATH_MAX + 32], err[2 * RUN_PATH_MAX];
  int st;
  snprintf(path, sizeof path, "%s/params.txt", o->dir);
  if ((st = run_params_read(path, P, err, sizeof err)) < 0)
    return params_unreadable(err);
  if (st == 0) {
    fprintf(stderr, "afv analyze: %s not found: using l = 1, v0 = 0.5, "
            "Dr = 0.1 unless given\n", path);
    memset(P, 0, sizeof *P);
    P->steps = -1;
    P->l = 1;
    P->v0 = 0.5;
    P->Dr = 0.1;
  }
  *l = isnan(o->l) ? P->l : o->l;
  *v0 = isnan(o->v0) ? P->v0 : o->v0;
  *Dr = isnan(o->Dr) ? P->Dr : o->Dr;
  if (!(*l > 0)) return bad_input("analyze: l must be > 0");
  if (!(*Dr >= 0)) {                 /* a variance rate: never negative */
    fprintf(stderr, "afv analyze: --Dr: %g: must be >= 0\n", *Dr);
    return EXIT_BAD_INPUT;
  }
  return 0;
}

/* The run's trajectory, opened into tr and checked (traj_is_the_runs,
** window_holds).  0, or an exit status with the message printed (tr
** closed). */
static int analyze_open(const analyze_args *o, const run_params_info *P,
                        int finished, double lag, afv_traj_file *tr)
{
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 128];
  snprintf(path, sizeof path, "%s/trajectory.dat", o->dir);
  if (afv_traj_open(tr, path, err, sizeof err) != AFV_OK)
    return bad_input(err);
  if (tr->nframes == 0)
    fprintf(stderr, "afv analyze: %s: no complete frame\n", path);
  /* afv run writes unwrapped centres (io.c, TRAJECTORY format): no
  ** unwrapping here, which would fold moves of more than half a box
  ** between two frames back into the box */
  if (tr->nframes > 0 && traj_is_the_runs(tr, o->dir, path, P, finished)
      && window_holds(tr, path, o->from, lag, !isnan(o->lag)))
    return 0;
  afv_traj_close(tr);
  return EXIT_BAD_INPUT;
}

int cmd_analyze(int argc, char **argv)
{
  char err[RUN_PATH_MAX + 128];
  double l, v0, Dr, lag;
  analyze_args o;
  run_params_info P;
  afv_traj_file tr;
  afv_analysis a;
  int st, finished = 0;
  if ((st = analyze_options(argc, argv, &o)) != 0) return st < 0 ? 0 : st;
  if (!run_dir_readable(o.dir)) return EXIT_BAD_INPUT;
  if (o.lag <= 0) return bad_input("--lag: must be > 0");
  lag = isnan(o.lag) ? DEFAULT_LAG : o.lag;
  if ((st = analyze_params(&o, &P, &l, &v0, &Dr)) != 0
      || (st = refuse_unfinished(o.dir, P.steps, o.partial, &finished)) != 0
      || (st = analyze_open(&o, &P, finished, lag, &tr)) != 0)
    return st;
  err[0] = 0;
  st = afv_analyze_file(&a, &tr, l, v0, Dr, o.from, lag, err, sizeof err);
  afv_traj_close(&tr);
  if (st == AFV_OK) warn_if_lag_unsupported(&a, lag);
  if (st != AFV_OK && err[0]) return bad_input(err);
  if (st != AFV_OK) {
    fprintf(stderr, "afv analyze: %s/trajectory.dat: %s\n", o.dir,
            afv_strerror(st));
    return EXIT_BAD_INPUT;
  }
  st = analyze_write(o.dir, &a);
  afv_analysis_free(&a);
  return st;
}
