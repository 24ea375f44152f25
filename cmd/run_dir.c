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
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/file.h>   /* flock: not POSIX, but in every libc afv meets */
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
/* (doc/design.md, "One writer per run directory".)  From before its first
** check of DIR's files to its end, a run holds two kinds of lock:
**  - flock(2) LOCK_EX on DIR itself, through a descriptor of the
**    directory: no file a user deletes, replaces or renames inside DIR
**    touches it, so a second `afv run` on DIR (fresh or --resume) is
**    refused whatever was done to the files (with a lock on
**    observables.csv alone, `rm observables.csv; cp copy observables.csv`
**    let a resume in beside the live run, and deleting it during the
**    relaxation let a second fresh run write params.txt and
**    observables.csv of another seed beside the first one's trajectory);
**  - POSIX record locks (fcntl, a write lock on the whole file) on the
**    files it appends to, LOCKED_FILES: observables.csv from the start,
**    the others from when they are opened.  They name the holder's
**    process id (F_GETLK; flock cannot), afv analyze asks them without
**    side effect (run_lock_holder), and they guard alone where flock on a
**    directory is not supported (NFS emulates flock by fcntl, which a
**    directory cannot take): there, replacing every one of those files of
**    a live run would let a second writer in.
** The kernel drops both when the process ends, however it ends (SIGKILL
** included): no stale lock is ever left to clean up, and afv never
** creates a lock file of its own (an empty file invites cleaning).  The
** locked files keep their inodes for the whole run: they are cut back
** with ftruncate and appended to, never replaced.  fcntl locks belong to
** the process and the file: closing any descriptor of a locked file
** before the end would drop the lock, so within a run observables.csv is
** read only through R->lock_fd, and written through a duplicate of it. */
#define LOCK_FILE "observables.csv"
static const char *const locked_files[] = {
  LOCK_FILE, "trajectory.dat", "trajectory.xyz", "log.txt"};
#define N_LOCKED_FILES (sizeof locked_files / sizeof locked_files[0])

int report_in_use(const char *dir, long pid)
{
  if (pid > 0)
    fprintf(stderr, "afv run: %s is in use by process %ld (it holds the "
            "run directory's lock): a run directory has one writer at a "
            "time; wait for that run to end, or stop it\n", dir, pid);
  else
    fprintf(stderr, "afv run: %s is in use by another process (it holds "
            "the lock on the directory): a run directory has one writer at "
            "a time; wait for that run to end, or stop it\n", dir);
  return EXIT_BAD_INPUT;
}

/* The process holding a write lock that conflicts with one on fd, or 0. */
static long fd_lock_holder(int fd)
{
  struct flock fl;
  memset(&fl, 0, sizeof fl);
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;   /* l_start = l_len = 0: the whole file */
  if (fcntl(fd, F_GETLK, &fl) != 0) return 0;
  return fl.l_type == F_UNLCK ? 0 : (long)fl.l_pid;
}

/* The process holding a lock on one of DIR's LOCKED_FILES, or 0 (none:
** nothing is created; a FIFO or a link there is not opened).  Only for a
** process that holds none of them itself: closing any descriptor of a
** file drops the caller's own locks on it.  (afv analyze asks it too: a
** run still being written is unfinished.) */
long run_lock_holder(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  struct stat sb;
  long pid = 0;
  size_t k;
  for (k = 0; k < N_LOCKED_FILES && pid == 0; k++) {
    int fd;
    snprintf(path, sizeof path, "%s/%s", dir, locked_files[k]);
    if ((fd = open(path, O_RDWR | O_NOFOLLOW | O_NONBLOCK)) < 0) continue;
    if (fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode)) pid = fd_lock_holder(fd);
    close(fd);
  }
  return pid;
}

/* Opens DIR's lock file: created if missing only for a fresh run (create
** = 1; a resume changes nothing before its checks pass), never through a
** symbolic link (a dangling one would make afv create its target), and
** only a regular file.  The descriptor, or -1 with a message. */
static int open_lock_file(const char *path, int create)
{
  struct stat sb;
  int fd = open(path, O_RDWR | O_NOFOLLOW | O_NONBLOCK
                | (create ? O_CREAT : 0), 0666);
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

/* A write lock on the whole of fd's file (the file at path).  1 if this
** process now holds it, else 0 with a message (in use: naming the
** holder). */
int run_file_lock(const char *dir, int fd, const char *path)
{
  struct flock fl;
  long pid;
  int tries;
  for (tries = 0; tries < 100; tries++) {
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(fd, F_SETLK, &fl) == 0) return 1;
    if (errno != EACCES && errno != EAGAIN) break;
    if ((pid = fd_lock_holder(fd)) > 0) {  /* else it just ended: again */
      report_in_use(dir, pid);
      return 0;
    }
  }
  fprintf(stderr, "afv run: %s: cannot lock: %s\n", path,
          tries < 100 ? strerror(errno) : "the lock keeps changing hands");
  return 0;
}

/* The process that holds DIR's flock, by its file locks: a writer takes
** observables.csv's at once after the directory's, so a run that started
** a moment ago is named once it has (tried for up to HOLDER_WAIT_MS); 0
** if none is found (its files were deleted or replaced). */
#define HOLDER_WAIT_MS 200
static long holder_named(const char *dir)
{
  struct timespec ts = {0, 5000000L};   /* 5 ms */
  long pid = 0;
  int waited;
  for (waited = 0; waited < HOLDER_WAIT_MS && !(pid = run_lock_holder(dir));
       waited += 5)
    nanosleep(&ts, NULL);
  return pid;
}

/* flock LOCK_EX on DIR itself (R->dir_fd).  1 if held, or if the file
** system has no such lock for directories (the file locks then guard
** alone); 0 with a message if another process holds it. */
static int lock_dir_itself(run_state *R)
{
  int fd = open(R->dir, O_RDONLY | O_DIRECTORY);
  if (fd < 0) {
    fprintf(stderr, "afv run: %s: cannot open: %s\n", R->dir,
            strerror(errno));
    return 0;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
    R->dir_fd = fd;
    return 1;
  }
  close(fd);
  if (errno != EWOULDBLOCK) return 1;   /* ENOLCK, EBADF (NFS), EINVAL */
  report_in_use(R->dir, holder_named(R->dir));
  return 0;
}

/* Takes DIR's lock: the directory's, then observables.csv's (create: see
** open_lock_file).  1 if this process now holds it (R->dir_fd,
** R->lock_fd), else 0 with a message. */
int lock_run_dir(run_state *R, int create)
{
  char path[RUN_PATH_MAX + 32];
  int fd;
  snprintf(path, sizeof path, "%s/" LOCK_FILE, R->dir);
  if (!lock_dir_itself(R)) return 0;
  if ((fd = open_lock_file(path, create)) < 0) return 0;
  if (!run_file_lock(R->dir, fd, path)) {
    close(fd);
    return 0;
  }
  R->lock_fd = fd;
  return 1;
}

/* Ends this process's hold on the run directory (closing the descriptors
** drops the locks). */
void unlock_run_dir(run_state *R)
{
  if (R->lock_fd >= 0) close(R->lock_fd);
  if (R->dir_fd >= 0) close(R->dir_fd);
  R->lock_fd = R->dir_fd = -1;
}

/* Opens DIR/name, a file the run appends to (LOCKED_FILES), for writing:
** never through a symbolic link, never a FIFO or a device (O_NOFOLLOW |
** O_NONBLOCK, then a regular file only: a FIFO at log.txt blocked
** --resume for ever), created if missing, cut to size bytes (size < 0:
** kept whole), positioned at its end and locked; observables.csv is
** written through a duplicate of R->lock_fd (the file the lock was taken
** on, whatever is at its name now).  The stream, or NULL with a message. */
FILE *run_file_open(run_state *R, const char *name, long long size)
{
  char path[RUN_PATH_MAX + 32];
  struct stat sb;
  FILE *fp = NULL;
  int own_lock = strcmp(name, LOCK_FILE) == 0, fd;
  snprintf(path, sizeof path, "%s/%s", R->dir, name);
  fd = own_lock ? dup(R->lock_fd)
       : open(path, O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK, 0666);
  if (fd < 0) {
    fprintf(stderr, "afv run: %s: cannot open: %s\n", path, errno == ELOOP
            ? "a symbolic link (afv writes only its own files)"
            : strerror(errno));
    return NULL;
  }
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode))
    fprintf(stderr, "afv run: %s: not a regular file (afv writes only its "
            "own files)\n", path);
  else if (own_lock || run_file_lock(R->dir, fd, path)) {
    if ((size < 0 || ftruncate(fd, (off_t)size) == 0)
        && lseek(fd, 0, SEEK_END) >= 0 && (fp = fdopen(fd, "w")))
      return fp;
    fprintf(stderr, "afv run: %s: cannot %s: %s\n", path, size > 0 ? "cut "
            "back to the checkpoint" : "open", strerror(errno));
  }
  close(fd);
  return NULL;
}

/* The files afv run writes in DIR (besides snap_*.svg). */
static const char *const run_files[] = {
  "params.txt", "checkpoint.txt", "trajectory.dat", LOCK_FILE,
  "trajectory.xyz", "log.txt", "t1_reference.txt", "cells.txt", "final.svg"};

/* 1 if name is a snapshot's, snap_DIGITS.svg. */
static int is_snapshot(const char *name)
{
  size_t m = strlen(name);
  return strncmp(name, "snap_", 5) == 0 && m > 9
         && strcmp(name + m - 4, ".svg") == 0
         && strspn(name + 5, "0123456789") == m - 9;
}

/* 1 if DIR/name is not there or is a regular file; else 0 with a message
** (a symbolic link, a FIFO, a directory: afv never made it, and would
** write through it, block on it, or remove it). */
static int regular_or_absent(const char *dir, const char *name)
{
  char path[RUN_PATH_MAX + 300];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  if (lstat(path, &sb) != 0 || S_ISREG(sb.st_mode)) return 1;
  fprintf(stderr, "afv run: %s: %s, which afv never makes: afv writes and "
          "removes only its own files; move it away\n", path,
          S_ISLNK(sb.st_mode) ? "a symbolic link" : S_ISDIR(sb.st_mode)
          ? "a directory" : "not a regular file");
  return 0;
}

/* 1 if every file of a run's names in DIR (run_files, the snapshots) is a
** regular file, as afv makes them; else 0 with a message naming the first
** that is not.  Checked under the lock before any byte changes. */
int run_files_regular(const char *dir)
{
  size_t k;
  int ok = 1;
  DIR *d;
  struct dirent *e;
  for (k = 0; ok && k < sizeof run_files / sizeof run_files[0]; k++)
    ok = regular_or_absent(dir, run_files[k]);
  if (ok && (d = opendir(dir))) {
    while (ok && (e = readdir(d)) != NULL)
      if (is_snapshot(e->d_name)) ok = regular_or_absent(dir, e->d_name);
    closedir(d);
  }
  return ok;
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

/* DIR's params.txt: params_written_by_afv. */
static int dir_params_by_afv(const char *dir)
{
  char path[RUN_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/params.txt", dir);
  return params_written_by_afv(path);
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
  int params = dir_params_by_afv(dir);
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
  if (params == 0 && dir_params_by_afv(dir) > 0)
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
  if (mkdir(dir, 0777) == 0)
    R->made_dir = 1;
  else if (errno != EEXIST) {
    fprintf(stderr, "afv run: cannot create %s: %s\n", dir, strerror(errno));
    return 0;
  }
  if (!lock_run_dir(R, 1) || holds_run(R) || !run_files_regular(dir))
    return 0;
  clear_unfinished_run(dir);
  remove_stale_temporaries(dir);
  return 1;
}

/* Removes what a fresh run made, for a run that stops before it has
** anything to keep (an unstable relaxation: from its start it would stop
** the same way): its files (run_files; under the lock, after
** clear_unfinished_run and run_files_regular, every one there is this
** run's) and DIR itself if this process created it. */
void discard_run(run_state *R)
{
  char path[RUN_PATH_MAX + 32];
  size_t k;
  for (k = 0; k < sizeof run_files / sizeof run_files[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", R->dir, run_files[k]);
    remove(path);
  }
  if (R->made_dir) rmdir(R->dir);
}

/* 1 if name is a temporary of afv_atomic_open (io.c) of a file of a run,
** NAME.PID.RAND.tmp with NAME one of run_files or a snapshot, whose
** process PID is gone (kill(PID, 0): ESRCH): a killed writer's. */
static int stale_temporary(const char *name)
{
  char base[300];
  const char *end = name + strlen(name), *rand, *pid;
  size_t k;
  long p;
  if (end - name < 15 || strcmp(end - 4, ".tmp") != 0) return 0;
  rand = end - 13;                       /* ".XXXXXXXX.tmp" */
  if (rand[0] != '.' || strspn(rand + 1, "0123456789abcdef") != 8) return 0;
  for (pid = rand - 1; pid > name && pid[-1] != '.'; pid--) {}
  if (pid <= name + 1 || strspn(pid, "0123456789") != (size_t)(rand - pid)
      || rand - pid > 9)
    return 0;
  p = atol(pid);
  snprintf(base, sizeof base, "%.*s", (int)(pid - 1 - name), name);
  for (k = 0; k < sizeof run_files / sizeof run_files[0]; k++)
    if (strcmp(base, run_files[k]) == 0) break;
  if (k == sizeof run_files / sizeof run_files[0] && !is_snapshot(base))
    return 0;
  return p > 0 && kill((pid_t)p, 0) != 0 && errno == ESRCH;
}

void remove_named(const char *dir, int (*named)(const char *name))
{
  char path[RUN_PATH_MAX + 300];
  DIR *d = opendir(dir);
  struct dirent *e;
  while (d && (e = readdir(d)) != NULL)
    if (named(e->d_name)) {
      snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
      unlink(path);
    }
  if (d) closedir(d);
}

/* Removes the temporaries a killed writer left in DIR (stale_temporary),
** under the lock (no other afv process writes in DIR); nothing else. */
void remove_stale_temporaries(const char *dir)
{
  remove_named(dir, stale_temporary);
}
