/*
** run_dir.c -- afv run's directory: one writer at a time (the lock), and
** the files afv did not write, which it refuses to overwrite
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "run.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* Creates the missing parent folders of dir (mkdir -p of its dirname), so
** that many jobs can write to runs/ID of a folder nobody made yet. */
static int make_parents(const char *dir)
{
  char path[RUN_PATH_MAX];
  size_t k;
  snprintf(path, sizeof path, "%s", dir);
  for (k = 1; path[k]; k++) {
    if (path[k] != '/' || path[k - 1] == '/') continue;
    path[k] = 0;
    if (mkdir(path, 0777) != 0 && errno != EEXIST) {
      fprintf(stderr, "afv run: cannot create %s: %s\n", path,
              strerror(errno));
      return 0;
    }
    path[k] = '/';
  }
  return 1;
}

/* ---- one writer per run directory -------------------------------------- */
/* A run holds a POSIX record lock (fcntl, a write lock on the whole file)
** on DIR/observables.csv, the run's own data file, from before its first
** check of DIR's files to its end, so a second `afv run` on DIR (fresh or
** --resume) is refused at once, naming the holder's process id (F_GETLK).
** The kernel drops the lock when the process ends, however it ends
** (SIGKILL included): no stale lock is ever left to clean up.  The lock is
** on a file a user has no reason to delete or replace while the run
** lives (deleting it deletes the results), not on an empty file of its
** own that invites cleaning (a deleted lock file let a second writer in).
** observables.csv keeps its inode for the whole run: a fresh run opens it
** with O_TRUNC, a resume cuts it back with truncate(2), and nothing else
** replaces it.  fcntl locks belong to the process and the file: closing
** any descriptor of observables.csv before the end would drop the lock,
** so within a run the file is read only through R->lock_fd. */
#define LOCK_FILE "observables.csv"

int report_in_use(const char *dir, long pid)
{
  fprintf(stderr, "afv run: %s is in use by process %ld (it holds the lock "
          "on %s/" LOCK_FILE "): a run directory has one writer at a time; "
          "wait for that run to end, or stop it\n", dir, pid, dir);
  return EXIT_BAD_INPUT;
}

/* The process holding DIR's lock, or 0 (none, or no lock file: nothing is
** created).  Only for a process that does not hold the lock itself:
** closing any descriptor of the file drops the caller's own locks on it.
** (afv analyze asks it too: a run still being written is unfinished.) */
long run_lock_holder(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  struct flock fl;
  int fd;
  snprintf(path, sizeof path, "%s/" LOCK_FILE, dir);
  if ((fd = open(path, O_RDWR | O_NOFOLLOW)) < 0) return 0;
  memset(&fl, 0, sizeof fl);
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  if (fcntl(fd, F_GETLK, &fl) != 0) fl.l_type = F_UNLCK;
  close(fd);
  return fl.l_type == F_UNLCK ? 0 : (long)fl.l_pid;
}

/* Opens DIR's lock file: created if missing only for a fresh run (create
** = 1; a resume changes nothing before its checks pass), never through a
** symbolic link (a dangling one would make afv create its target), and
** only a regular file.  The descriptor, or -1 with a message. */
static int open_lock_file(const char *path, int create)
{
  struct stat sb;
  int fd = open(path, O_RDWR | O_NOFOLLOW | (create ? O_CREAT : 0), 0666);
  if (fd < 0) {
    fprintf(stderr, "afv run: %s: cannot open%s: %s\n", path,
            create ? "" : " (a run directory has it from its start)",
            errno == ELOOP ? "a symbolic link (afv writes only its own "
            "files)" : strerror(errno));
    return -1;
  }
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    fprintf(stderr, "afv run: %s: not a regular file\n", path);
    close(fd);
    return -1;
  }
  return fd;
}

/* Takes DIR's lock (create: see open_lock_file).  1 if this process now
** holds it (R->lock_fd), else 0 with a message. */
int lock_run_dir(run_state *R, int create)
{
  char path[RUN_PATH_MAX + 32];
  struct flock fl;
  int fd, tries;
  snprintf(path, sizeof path, "%s/" LOCK_FILE, R->dir);
  if ((fd = open_lock_file(path, create)) < 0) return 0;
  for (tries = 0; tries < 100; tries++) {
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;   /* l_start = l_len = 0: the whole file */
    if (fcntl(fd, F_SETLK, &fl) == 0) {
      R->lock_fd = fd;
      return 1;
    }
    if (errno != EACCES && errno != EAGAIN) break;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(fd, F_GETLK, &fl) != 0) break;
    if (fl.l_type != F_UNLCK) {   /* else the holder just ended: try again */
      report_in_use(R->dir, (long)fl.l_pid);
      close(fd);
      return 0;
    }
  }
  fprintf(stderr, "afv run: %s: cannot lock: %s\n", path,
          tries < 100 ? strerror(errno) : "the lock keeps changing hands");
  close(fd);
  return 0;
}

/* Ends this process's hold on the run directory (closing the file drops
** the lock). */
void unlock_run_dir(run_state *R)
{
  if (R->lock_fd >= 0) close(R->lock_fd);
  R->lock_fd = -1;
}

/* 1 (with a message) if R->dir holds a run: it has a checkpoint (a run
** that stopped before its first checkpoint has nothing to resume, and a
** fresh run replaces it).  A run still being written is named by its
** writer's process id. */
static int holds_run(const run_state *R)
{
  char path[RUN_PATH_MAX + 32];
  long pid;
  snprintf(path, sizeof path, "%s/checkpoint.txt", R->dir);
  if (access(path, F_OK) != 0) return 0;
  if (R->lock_fd < 0 && (pid = run_lock_holder(R->dir)) > 0)
    report_in_use(R->dir, pid);
  else
    fprintf(stderr, "afv run: %s already holds a run (checkpoint.txt): "
            "continue it with --resume %s, or choose another --out\n",
            R->dir, R->dir);
  return 1;
}

/* 1 if name is a snapshot's, snap_DIGITS.svg. */
static int is_snapshot(const char *name)
{
  size_t m = strlen(name);
  return strncmp(name, "snap_", 5) == 0 && m > 9
         && strcmp(name + m - 4, ".svg") == 0
         && strspn(name + 5, "0123456789") == m - 9;
}

/* Files a run that stopped before its first checkpoint may have left and
** a fresh run does not always rewrite (the others it rewrites). */
static void clear_unfinished_run(const char *dir)
{
  static const char *const left[] = {"log.txt", "cells.txt",
                                      "trajectory.xyz", "final.svg"};
  char path[RUN_PATH_MAX + 300];
  size_t k;
  DIR *d;
  struct dirent *e;
  for (k = 0; k < sizeof left / sizeof left[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, left[k]);
    remove(path);
  }
  if (!(d = opendir(dir))) return;
  while ((e = readdir(d)) != NULL)   /* its snapshots, of any step */
    if (is_snapshot(e->d_name)) {
      snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
      remove(path);
    }
  closedir(d);
}

/* The files afv run writes in DIR (besides snap_*.svg). */
static const char *const run_files[] = {
  "params.txt", "checkpoint.txt", "trajectory.dat", LOCK_FILE,
  "trajectory.xyz", "log.txt", "t1_reference.txt", "cells.txt", "final.svg"};

/* DIR's params.txt: 1 if afv wrote it, 0 if there is none, -1 if it is
** a user's file (it does not start with afv's first line). */
static int params_written_by_afv(const char *dir)
{
  char path[RUN_PATH_MAX + 32], line[64] = "";
  struct stat sb;
  FILE *fp;
  snprintf(path, sizeof path, "%s/params.txt", dir);
  if (lstat(path, &sb) != 0) return 0;
  if ((fp = fopen(path, "r"))) {
    if (!fgets(line, sizeof line, fp)) line[0] = 0;
    fclose(fp);
  }
  return strncmp(line, "# afv run parameters", 20) == 0 ? 1 : -1;
}

/* 1 (with a message) if DIR holds files of a run's names that afv did not
** write: a params.txt that is not afv's, or any of run_files, or a
** snapshot, without a params.txt.  A fresh run would overwrite them
** (before, a user's own log.txt and trajectory.dat were, without a
** word).  An empty observables.csv is the lock of a run being started
** (it writes params.txt next), not a user's file.  This look comes before
** the lock, so a run started at the same moment may write its files
** during it: they are that run's when DIR is locked, or when afv's
** params.txt has appeared meanwhile (before, such a run's params.txt was
** reported as a foreign file, "holds params.txt but no params.txt"). */
static int foreign_files(const char *dir)
{
  char path[RUN_PATH_MAX + 300];
  struct stat sb;
  size_t k;
  long holder;
  DIR *d;
  struct dirent *e;
  const char *found = NULL;
  int params = params_written_by_afv(dir);
  if (params > 0) return 0;
  if (params < 0) found = "params.txt";
  /* run_files[0] is params.txt, looked at above */
  for (k = 1; !found && k < sizeof run_files / sizeof run_files[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, run_files[k]);
    if (lstat(path, &sb) == 0 && !(strcmp(run_files[k], LOCK_FILE) == 0
                                   && S_ISREG(sb.st_mode) && sb.st_size == 0))
      found = run_files[k];
  }
  if (!found && (d = opendir(dir))) {
    while (!found && (e = readdir(d)) != NULL)
      if (is_snapshot(e->d_name)) found = "a snapshot snap_*.svg";
    closedir(d);
  }
  if (!found) return 0;
  if ((holder = run_lock_holder(dir)) > 0) {
    report_in_use(dir, holder);
    return 1;
  }
  if (params == 0 && params_written_by_afv(dir) > 0)
    return 0;   /* a run's, started meanwhile: the lock or holds_run says */
  if (params < 0)
    fprintf(stderr, "afv run: %s/params.txt is not afv's (it does not start "
            "with '# afv run parameters'): afv run writes only into a new or "
            "empty directory or a run directory of its own; choose another "
            "--out\n", dir);
  else
    fprintf(stderr, "afv run: %s holds %s but no params.txt: not a run "
            "directory of afv, and a run would overwrite it; choose another "
            "--out, or move that file away\n", dir, found);
  return 1;
}

/* Creates DIR for a fresh run and takes its lock.  DIR may exist, but must
** not hold a run (holds_run).  Two fresh runs to the same DIR: mkdir lets
** both in, the lock lets one on, and the other is refused (in use, or,
** once the first has checkpointed, holding a run). */
int make_out_dir(run_state *R)
{
  const char *dir = R->dir;
  if (holds_run(R) || foreign_files(dir))
    return 0;                       /* refused before anything changes */
  if (!make_parents(dir)) return 0;
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "afv run: cannot create %s: %s\n", dir, strerror(errno));
    return 0;
  }
  if (!lock_run_dir(R, 1) || holds_run(R)) return 0;
  clear_unfinished_run(dir);
  return 1;
}
