/*
** test_runjob.c -- the run directory of `afv run` as a job sees it: one
** writer at a time (real concurrent processes), a resume that is all or
** nothing (the directory byte-compared before and after), parameters
** refused before anything is made when the run could not compute with
** them (they wrote inf and nan), a directory whose run stopped before its
** first checkpoint run again, and messages that name the file and the
** system's reason, and print bounds in full.
**
** Every test runs ./afv (from the repository root, where `make test`
** starts the runner) in a directory under /tmp, removed at the end.
*/
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char root[256];   /* the suite's directory */

/* The whole file at path (NUL-terminated; *len its size), or NULL. */
static char *read_whole(const char *path, long *len)
{
  FILE *fp = fopen(path, "rb");
  char *buf = NULL;
  long n = 0, cap = 0;
  size_t got;
  *len = -1;
  if (!fp) return NULL;
  do {
    char *grown;
    cap = cap ? 2 * cap : 4096;
    if (!(grown = realloc(buf, (size_t)cap + 1))) {
      free(buf);
      fclose(fp);
      return NULL;
    }
    buf = grown;
    got = fread(buf + n, 1, (size_t)(cap - n), fp);
    n += (long)got;
  } while (n == cap);
  fclose(fp);
  buf[n] = 0;
  *len = n;
  return buf;
}

/* The stderr a command left in root/err.txt. */
static char *last_err(void)
{
  char path[512];
  long len;
  char *e;
  snprintf(path, sizeof path, "%s/err.txt", root);
  e = read_whole(path, &len);
  return e ? e : calloc(1, 1);
}

static int exists(const char *sub)
{
  char p[512];
  struct stat sb;
  snprintf(p, sizeof p, "%s/%s", root, sub);
  return stat(p, &sb) == 0;
}

/* 1 if root/a/name and root/b/name exist and are byte-identical. */
static int same_file(const char *a, const char *b, const char *name)
{
  return test_sh("cmp -s %s/%s/%s %s/%s/%s", root, a, name, root, b, name)
         == 0;
}

/* ThreadSanitizer's runtime maps files of its own, which a file-size limit
** breaks (SIGBUS inside the runtime, before afv writes anything). */
#if defined(__SANITIZE_THREAD__)
#define UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define UNDER_TSAN 1
#endif
#endif

/* Runs `./afv run ARGS --out root/sub` under a file size limit of blocks
** 512-byte blocks (POSIX ulimit -f; SIGXFSZ ignored, so write(2) fails
** with EFBIG as on a full disk it fails with ENOSPC): it must fail on
** writing file, exit 2, with one line naming file and EFBIG's reason. */
static void check_size_limit_failure(int blocks, const char *args,
                                     const char *sub, const char *file)
{
  char *e;
  int st;
  st = test_sh("(trap '' XFSZ; ulimit -f %d; exec ./afv run %s --out %s/%s) "
               "2> %s/err.txt", blocks, args, root, sub, root);
  e = last_err();
  CHECK(st == 2, "%s: exit %d, want 2", file, st);
  CHECK(strstr(e, file) && strstr(e, strerror(EFBIG))
        && strchr(e, '\n') == e + strlen(e) - 1, "the message is not one "
        "line naming %s and '%s': %s", file, strerror(EFBIG), e);
  free(e);
}

/* Every file of root/sub, in name order, as "name size\n" + its bytes:
** two pictures compare equal iff no file was added, removed or changed. */
static char *picture(const char *sub, long *len)
{
  char dir[512], path[1024];
  struct dirent **names;
  char *all = calloc(1, 1);
  long total = 0;
  int k, m;
  snprintf(dir, sizeof dir, "%s/%s", root, sub);
  m = scandir(dir, &names, NULL, alphasort);
  for (k = 0; k < m; k++) {
    long n;
    char *bytes, *grown, head[600];
    int h;
    snprintf(path, sizeof path, "%s/%s", dir, names[k]->d_name);
    bytes = names[k]->d_name[0] == '.' ? NULL : read_whole(path, &n);
    if (bytes) {
      h = snprintf(head, sizeof head, "%s %ld\n", names[k]->d_name, n);
      grown = realloc(all, (size_t)(total + h + n + 1));
      if (grown) {
        all = grown;
        memcpy(all + total, head, (size_t)h);
        memcpy(all + total + h, bytes, (size_t)n);
        total += h + n;
        all[total] = 0;
      }
      free(bytes);
    }
    free(names[k]);
  }
  if (m >= 0) free(names);
  *len = total;
  return all;
}

static void sleep_ms(long ms)
{
  struct timespec ts;
  ts.tv_sec = ms / 1000;
  ts.tv_nsec = (ms % 1000) * 1000000L;
  nanosleep(&ts, NULL);
}

/* Starts ./afv with argv (NULL-terminated) in a child, stderr to
** root/name; returns the child's pid.  gate: -1, or the read end of a pipe
** whose write end the parent closes to let every waiting child go at once
** (the child reads it to end of file before exec). */
static pid_t start_afv(const char *const *argv, const char *errname,
                       const int *gate)
{
  pid_t pid = fork();
  if (pid == 0) {
    char path[512], c;
    snprintf(path, sizeof path, "%s/%s", root, errname);
    if (!freopen(path, "w", stderr)) _exit(126);
    if (gate) {
      close(gate[1]);
      while (read(gate[0], &c, 1) > 0) {}
      close(gate[0]);
    }
    execv("./afv", (char *const *)argv);
    _exit(127);
  }
  return pid;
}

static int exit_status(pid_t pid)
{
  int st;
  if (waitpid(pid, &st, 0) != pid) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* A fast system that writes a checkpoint every 5 steps. */
#define FAST "--N 64 " FAST_SYSTEM
/* (a key is given once: afv run refuses one given twice) */
#define FAST_SYSTEM "--P0 4.5 --v0 0.3 --sample_every 5 --frame_every 10 " \
                    "--checkpoint_every 5 --svg_every 0 --quiet"

/* Starts a long run of FAST's system into root/sub (out receives the
** path) and waits for its first checkpoint; returns the writer's pid and
** puts "process PID" into want. */
static pid_t start_live_writer(const char *sub, char *out, size_t outlen,
                               char *want, size_t wantlen)
{
  const char *argv[] = {"afv", "run", "--N", "64", "--P0", "4.5", "--v0",
                        "0.3", "--sample_every", "5", "--frame_every", "10",
                        "--checkpoint_every", "5", "--svg_every", "0",
                        "--quiet", "--steps", "100000000", "--out", out, NULL};
  char ckpt[96];
  pid_t pid;
  int waited;
  snprintf(out, outlen, "%s/%s", root, sub);
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", sub);
  pid = start_afv(argv, "writer.txt", NULL);
  for (waited = 0; waited < 20000 && !exists(ckpt); waited += 5)
    sleep_ms(5);
  CHECK(exists(ckpt), "the writer never checkpointed");
  snprintf(want, wantlen, "process %ld", (long)pid);
  return pid;
}

/* ---- one writer per run directory --------------------------------------- */
/* While a run writes in DIR, a resume and a fresh run on DIR are refused at
** once (exit 2, naming the writer's pid) and leave it alone; SIGKILLed,
** the writer blocks nothing: the resume that follows continues it, and the
** result equals one uninterrupted run byte for byte.  (The code before:
** the resume exited 0, writing into the same files as the live run.) */
static void test_second_writer_refused(void)
{
  char out[512], want[64], *e;
  pid_t pid = start_live_writer("w", out, sizeof out, want, sizeof want);
  int st;
  st = test_sh("./afv run --resume %s --steps 10 --quiet 2> %s/err.txt", out,
              root);
  e = last_err();
  CHECK(st == 2, "resume beside a live writer: exit %d, want 2", st);
  CHECK(strstr(e, want) != NULL, "the message does not name '%s': %s", want,
        e);
  free(e);
  st = test_sh("./afv run " FAST " --steps 10 --out %s 2> %s/err.txt", out,
              root);
  e = last_err();
  CHECK(st == 2, "fresh run into a live run's directory: exit %d, want 2",
        st);
  CHECK(strstr(e, want) != NULL, "the message does not name '%s': %s", want,
        e);
  free(e);
  kill(pid, SIGKILL);
  CHECK(exit_status(pid) == -1, "the writer ended before it was killed");
  /* no stale lock: the killed writer's directory resumes at once */
  CHECK(test_sh("./afv run --resume %s --steps 20 --quiet 2> %s/err.txt", out,
               root) == 0, "resume after SIGKILL of the writer failed");
  CHECK(test_sh("./afv run --config %s/params.txt --out %s/w_ref", out, root)
        == 0, "the reference run failed");
  CHECK(same_file("w", "w_ref", "trajectory.dat"), "trajectory.dat: killed, "
        "refused twice and resumed, it differs from one straight run");
  CHECK(same_file("w", "w_ref", "observables.csv"), "observables.csv "
        "differs from one straight run");
  CHECK(same_file("w", "w_ref", "checkpoint.txt"), "checkpoint.txt differs "
        "from one straight run");
}

/* The lock cannot be cleaned away: with a run live in DIR, deleting
** DIR/lock (the empty file the code before locked, which stayed after
** every run) and putting a symbolic link in its place leaves a resume
** refused (the code before: the resume exited 0 beside the live run,
** rewrote params.txt's steps and tore trajectory.dat).  A dangling
** symbolic link in a fresh run's directory never makes afv create its
** target (the code before created the target of DIR/lock). */
static void test_lock_survives_cleaning(void)
{
  char out[512], want[64], *e;
  pid_t pid = start_live_writer("lk", out, sizeof out, want, sizeof want);
  int st;
  test_sh("rm -f %s/lock && ln -s %s/lock_target %s/lock", out, root, out);
  st = test_sh("./afv run --resume %s --steps 10 --quiet 2> %s/err.txt", out,
               root);
  e = last_err();
  CHECK(st == 2 && strstr(e, want), "resume beside a live writer whose "
        "lock file was cleaned: exit %d, want 2 naming %s: %s", st, want, e);
  free(e);
  kill(pid, SIGKILL);
  exit_status(pid);
  CHECK(!exists("lock_target"), "afv created the target of a link");
  /* fresh runs into directories holding dangling links */
  CHECK(test_sh("mkdir -p %s/lk2 && ln -s %s/lock_target2 %s/lk2/lock && "
                "./afv run " FAST " --steps 10 --out %s/lk2 2> %s/err.txt",
                root, root, root, root, root) == 0, "a fresh run beside a "
        "stray link");
  CHECK(!exists("lock_target2"), "afv created the target of DIR/lock");
  st = test_sh("mkdir -p %s/lk3 && ln -s %s/obs_target %s/lk3/observables.csv"
               " && ./afv run " FAST " --steps 10 --out %s/lk3 2> %s/err.txt",
               root, root, root, root, root);
  CHECK(st == 2 && !exists("obs_target"), "a link at observables.csv: exit "
        "%d, want 2, and its target not made", st);
}

/* 1 if the stderr a refused run left in root/name says why, rightly: the
** directory is in use, or (its writer done) holds a run. */
static int refused_rightly(const char *name)
{
  char path[512], *e;
  long len;
  int ok;
  snprintf(path, sizeof path, "%s/%s", root, name);
  e = read_whole(path, &len);
  ok = e && (strstr(e, "in use by process") || strstr(e, "already holds"));
  if (!ok) printf("  refused with: %s\n", e ? e : "(nothing)");
  free(e);
  return ok;
}

/* Writes a cells file of n rows (P0 near 4.5, v0 near 0.3) to path; 1 if
** written. */
static int write_cells_file(const char *path, int n, unsigned long long seed)
{
  FILE *fp = fopen(path, "w");
  int i;
  if (!fp) return 0;
  test_rng_seed(seed);
  fputs("# theta v0 Dr KA KP A0 P0\n", fp);
  for (i = 0; i < n; i++)
    fprintf(fp, "%.17g %.17g 0.1 1 1 3.14159 %.17g\n",
            6.28 * test_rng_uniform(), 0.3 + 1e-3 * test_rng_uniform(),
            4.5 + 1e-3 * test_rng_uniform());
  return fclose(fp) == 0;
}

/* A child that takes the fcntl lock on path and holds it until killed;
** its pid, or -1 if it could not lock. */
static pid_t hold_lock(const char *path)
{
  int ready[2];
  char c = 0;
  pid_t pid;
  if (pipe(ready) != 0) return -1;
  if ((pid = fork()) == 0) {
    struct flock fl;
    int fd = open(path, O_RDWR);
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    c = fd >= 0 && fcntl(fd, F_SETLK, &fl) == 0;
    if (write(ready[1], &c, 1) != 1 || !c) _exit(1);
    for (;;) pause();
  }
  close(ready[1]);
  if (read(ready[0], &c, 1) != 1) c = 0;
  close(ready[0]);
  if (c == 1) return pid;
  exit_status(pid);
  return -1;
}

/* Two fresh runs started together (released by one pipe) into the same
** --out: exactly one runs (exit 0, its outputs equal to a run alone), the
** other is refused (exit 2, in use).  A 6000-row cells file, copied into
** the directory, keeps each run a while between its first look at the
** directory and its params.txt.  (The code before: both passed the look,
** and one then failed on the other's files, "cannot write the outputs";
** with other timings both exited 0.) */
static void test_concurrent_fresh_runs(void)
{
  char out[512], ref[512], cells[512], sub[64];
  const char *argv[] = {"afv", "run", "--cells", cells, "--steps", "0",
                        "--relax_max_steps", "0", "--svg_every", "0",
                        "--quiet", "--out", out, NULL};
  static const char *const files[] = {"cells.txt", "params.txt",
                                      "trajectory.dat", "observables.csv",
                                      "checkpoint.txt", "t1_reference.txt"};
  int trial;
  snprintf(cells, sizeof cells, "%s/cells6k.txt", root);
  if (!write_cells_file(cells, 6000, 22)) {
    CHECK(0, "cannot write %s", cells);
    return;
  }
  snprintf(ref, sizeof ref, "%s/c_ref", root);
  argv[12] = ref;
  CHECK(exit_status(start_afv(argv, "ref.txt", NULL)) == 0, "the reference "
        "run");
  argv[12] = out;
  for (trial = 0; trial < 4; trial++) {
    pid_t a, b;
    int sa, sb, gate[2];
    size_t k;
    snprintf(sub, sizeof sub, "c%d", trial);
    snprintf(out, sizeof out, "%s/%s", root, sub);
    if (pipe(gate) != 0) {
      CHECK(0, "pipe: %s", strerror(errno));
      return;
    }
    a = start_afv(argv, "a.txt", gate);
    b = start_afv(argv, "b.txt", gate);
    close(gate[0]);
    close(gate[1]);   /* both go */
    sa = exit_status(a);
    sb = exit_status(b);
    CHECK((sa == 0 && sb == 2) || (sa == 2 && sb == 0), "trial %d: exit "
          "statuses %d and %d, want one 0 and one 2", trial, sa, sb);
    CHECK(refused_rightly(sa == 2 ? "a.txt" : "b.txt"), "trial %d: the "
          "second run was not refused as the directory's second writer",
          trial);
    for (k = 0; k < sizeof files / sizeof files[0]; k++)
      if (k != 1)   /* params.txt names the cells file it copied */
        CHECK(same_file(sub, "c_ref", files[k]), "trial %d: the winner's "
              "%s differs from a run alone", trial, files[k]);
  }
}

/* A fresh run asks for the lock's holder at once, reads its cells, and
** only then looks at the directory and takes the lock.  A run started at
** the same moment can lock the directory and write its files in between:
** the second run then found the first's params.txt (or trajectory.dat)
** and called them a user's files, "holds params.txt but no params.txt"
** (CI saw it once in test_concurrent_fresh_runs).  That moment, held
** still: the run reads 30000 cells (about 0.6 s here) while, 0.1 s after
** its start, a child locks observables.csv in its directory beside a
** trajectory.dat, without params.txt.  The run is refused as the
** directory's second writer, naming the holder, and changes nothing.
** (The code before: "holds trajectory.dat but no params.txt".) */
static void test_run_locked_meanwhile_is_in_use(void)
{
  char dir[512], cells[512], lock[600], want[64], *before, *after, *e;
  const char *argv[] = {"afv", "run", "--cells", cells, "--steps", "0",
                        "--relax_max_steps", "0", "--svg_every", "0",
                        "--quiet", "--out", dir, NULL};
  long nb, na;
  pid_t run, holder;
  int st;
  snprintf(dir, sizeof dir, "%s/meanwhile", root);
  snprintf(cells, sizeof cells, "%s/cells30k.txt", root);
  snprintf(lock, sizeof lock, "%s/observables.csv", dir);
  CHECK(write_cells_file(cells, 30000, 23), "cannot write %s", cells);
  CHECK(test_sh("mkdir -p %s", dir) == 0, "mkdir %s", dir);
  run = start_afv(argv, "err.txt", NULL);
  sleep_ms(100);   /* past its first look at the lock, before its second */
  test_sh("echo t >%s/trajectory.dat && echo o >%s", dir, lock);
  holder = hold_lock(lock);
  CHECK(holder > 0, "the child could not lock %s", lock);
  before = picture("meanwhile", &nb);
  st = exit_status(run);
  after = picture("meanwhile", &na);
  if (holder > 0) {
    kill(holder, SIGKILL);
    exit_status(holder);
  }
  e = last_err();
  snprintf(want, sizeof want, "in use by process %ld", (long)holder);
  CHECK(st == 2 && strstr(e, want), "a run whose directory was locked "
        "while it read its cells: exit %d, want 2 and '%s': %s", st, want, e);
  CHECK(nb == na && memcmp(before, after, (size_t)nb) == 0, "the refused "
        "run changed the directory");
  free(e);
  free(before);
  free(after);
}

/* ---- a resume is all or nothing ----------------------------------------- */
/* A completed run copied, damaged, then resumed: exit 2, a message, and
** every file of the directory as it was (the code before cut
** trajectory.dat back before finding observables.csv short, rewrote
** params.txt before reading the T1 reference, and took --steps
** 2^63 - 1 into a negative step count). */
static void test_failed_resume_changes_nothing(void)
{
  static const char *const cases[][3] = {
    /* damage (shell, in the copy), resume options, the message names */
    {"printf 'torn' >> trajectory.dat && truncate -s 200 observables.csv",
     "", "checkpoint.txt:7: bytes observables.csv"},
    {"printf 'torn' >> trajectory.dat && printf 'torn' >> observables.csv "
     "&& rm trajectory.xyz", "", "trajectory.xyz"},
    {"printf '1\\n' > t1_reference.txt", "--steps 50", "t1_reference.txt"},
    {"rm t1_reference.txt", "--steps 50", "t1_reference.txt"},
    {"printf 'torn' >> trajectory.dat", "--steps 9223372036854775807",
     "--steps"},
    {"printf 'torn' >> trajectory.dat", "--steps 1x0", "--steps"},
    /* params.txt edited to a modulus the run cannot compute with */
    {"sed 's/^KA .*/KA 1e200/' params.txt > p.tmp && mv p.tmp params.txt",
     "--steps 50", "params.txt:6: KA 1e+200, but afv wrote KA 1"},
    /* cell 5's angle (line 14 of the checkpoint) not finite */
    {"awk 'NR == 14 { $3 = \"inf\" } { print }' checkpoint.txt > c.tmp && "
     "mv c.tmp checkpoint.txt", "--steps 50", "checkpoint.txt"},
    /* well-formed checkpoints that do not describe the files (the code
    ** before cut trajectory.dat to nothing, glued a frame onto a line,
    ** and appended frames after later ones) */
    {"awk '/^bytes trajectory.dat/ { $3 = 0 } { print }' checkpoint.txt > "
     "c.tmp && mv c.tmp checkpoint.txt", "", "bytes trajectory.dat 0"},
    {"awk '/^bytes trajectory.dat/ { $3 -= 5 } { print }' checkpoint.txt > "
     "c.tmp && mv c.tmp checkpoint.txt", "--steps 50", "bytes trajectory.dat"},
    /* a whole frame (16 + 20 x 64 bytes) short: the file then ends
    ** with the frame before the checkpoint's */
    {"awk '/^bytes trajectory.dat/ { $3 -= 1296 } { print }' checkpoint.txt"
     " > c.tmp && mv c.tmp checkpoint.txt", "", "whole frame of step 100"},
    /* a format-1 (text) trajectory of afv < 0.3 is not appended to */
    {"sed '1s/^# afv trajectory 2 /# afv trajectory 1 /' trajectory.dat > "
     "t.tmp && mv t.tmp trajectory.dat", "--steps 50", "format 1"},
    {"awk '/^bytes observables.csv/ { $3 -= 9 } { print }' checkpoint.txt > "
     "c.tmp && mv c.tmp checkpoint.txt", "", "bytes observables.csv"},
    {"awk '/^step/ { $2 = 90 } { print }' checkpoint.txt > c.tmp && "
     "mv c.tmp checkpoint.txt", "--steps 50", "checkpoint.txt:4: time"},
    {"awk '/^step/ { $2 = 90 } /^time/ { $2 = \"0x1.ccccccccccccdp-1\" } "
     "{ print }' checkpoint.txt > c.tmp && mv c.tmp checkpoint.txt",
     "--steps 50", "row of step 90"},
    /* a centre of the checkpoint edited: not the last frame's (before the
    ** last frame was checked, the energy of its row told) */
    {"awk 'NR == 12 { $1 = \"0x1p+3\" } { print }' checkpoint.txt > c.tmp "
     "&& mv c.tmp checkpoint.txt", "--steps 50", "not within 0 of the "
     "checkpoint's state"}};
  size_t c;
  CHECK(test_sh("./afv run " FAST " --xyz 1 --steps 100 --out %s/base",
               root) == 0, "the base run");
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    char sub[32], *before, *after, *e;
    long nb, na;
    int st;
    snprintf(sub, sizeof sub, "d%d", (int)c);
    CHECK(test_sh("cp -R %s/base %s/%s && cd %s/%s && %s", root, root, sub,
                 root, sub, cases[c][0]) == 0, "case %d: damaging", (int)c);
    before = picture(sub, &nb);
    st = test_sh("./afv run --resume %s/%s %s --quiet 2> %s/err.txt", root,
                sub, cases[c][1], root);
    after = picture(sub, &na);
    e = last_err();
    CHECK(st == 2, "case %d (%s; %s): exit %d, want 2", (int)c, cases[c][0],
          cases[c][1], st);
    CHECK(nb > 0 && na == nb && memcmp(before, after, (size_t)nb) == 0,
          "case %d (%s; %s): a failed resume changed the directory",
          (int)c, cases[c][0], cases[c][1]);
    CHECK(strstr(e, cases[c][2]) && strchr(e, '\n') == e + strlen(e) - 1,
          "case %d: message not one line naming %s: %s", (int)c,
          cases[c][2], e);
    if (c == 7)   /* the cell, if the checkpoint reader let it through */
      CHECK(strstr(e, "checkpoint.txt:14") || strstr(e, "cell 5"),
            "the message names neither line 14 nor cell 5: %s", e);
    free(before);
    free(after);
    free(e);
  }
  /* the refused --steps left a run that still resumes */
  CHECK(test_sh("./afv run --resume %s/d4 --steps 10 --quiet", root) == 0,
        "after a refused --steps the run no longer resumes");
}

/* A cells file root/name of one column: n cells, all usual but cell odd. */
static void write_column(const char *name, const char *column, int n,
                         int odd, const char *odd_value, const char *usual)
{
  char path[512];
  FILE *fp;
  int i;
  snprintf(path, sizeof path, "%s/%s", root, name);
  if (!(fp = fopen(path, "w"))) {
    CHECK(0, "cannot write %s", path);
    return;
  }
  fprintf(fp, "# %s\n", column);
  for (i = 0; i < n; i++) fprintf(fp, "%s\n", i == odd ? odd_value : usual);
  fclose(fp);
}

/* `afv run --N n --steps 20 ARGS --out root/bad` ('@' in ARGS stands for
** the suite's directory), within 20 s: exit 2, one line "afv run: ..."
** naming want, and no directory made. */
static void check_refused_up_front(int n, const char *args_at,
                                   const char *want)
{
  char args[512], *e, *at;
  int st;
  snprintf(args, sizeof args, "%s", args_at);
  if ((at = strchr(args, '@')))
    snprintf(at, sizeof args - (size_t)(at - args), "%s%s", root,
             strchr(args_at, '@') + 1);
  st = test_sh("timeout 20 ./afv run --N %d --steps 20 --quiet %s --out "
               "%s/bad 2> %s/err.txt", n, args, root, root);
  e = last_err();
  CHECK(st == 2, "'%s': exit %d, want 2", args, st);
  CHECK(strncmp(e, "afv run: ", 9) == 0 && strstr(e, want)
        && strchr(e, '\n') == e + strlen(e) - 1, "'%s': message not one "
        "line 'afv run: ...' naming '%s': %s", args, want, e);
  CHECK(!exists("bad"), "'%s': the directory was made", args);
  free(e);
  test_sh("rm -rf %s/bad", root);
}

/* ---- what the run can compute ------------------------------------------- */
/* Values the checks let through before, but whose energy, force, step
** factors or angle noise overflow: refused with one line naming the key
** (the config file's line, the cells file's cell), and no directory made.  (The code before: KA 1e200 made the
** directory, then failed in the relaxation, leaving a directory neither a
** fresh run nor a resume accepted; KA 1e308 and Dr 1e308 ran and wrote inf
** and nan.) */
static void test_uncomputable_parameters_refused(void)
{
  static const char *const cases[][2] = {
    {"--KA 1e200", "KA:"}, {"--KA 1e308", "KA:"}, {"--A0 1e200", "A0:"},
    {"--P0 1e200", "P0:"}, {"--KP 1e300", "KP:"},
    {"--Lambda 1e300", "Lambda:"}, {"--Dr 1e308", "Dr:"},
    {"--mu 1e300 --dt 1e10 --v0 0", "mu:"}, {"--v0 1e308 --dt 10", "v0:"},
    {"--cells @/dr.txt", "Dr (cells file, cell 3): 1e+308:"},
    {"--config @/cfg.txt", "cfg.txt:2: KA:"},
    /* meaningless: a target no cell can reach (P0 <= 0, A0 <= 0 with a
    ** positive modulus: the relaxation crawled on, silent, for minutes), a
    ** step whose self-propulsion crosses the box (v0 dt > L), an l whose
    ** square leaves the doubles (the code
    ** before: --P0 0 ran past the timeout; --l 1e200 said "start:
    ** parameter out of range", --l 1e-200 blamed phi) */
    {"--P0 0", "P0:"}, {"--P0 -100", "P0:"}, {"--A0 -10", "A0:"},
    {"--v0 1e6", "v0:"}, {"--dt 100", "dt:"}, {"--v0 -1e6", "v0:"},
    {"--cells @/p0.txt", "P0 (cells file, cell 2):"},
    {"--l 1e200", "l: 1e+200"}, {"--l 1e-200", "l: 1e-200"}};
  char path[512];
  size_t c;
  FILE *fp;
  snprintf(path, sizeof path, "%s/cfg.txt", root);
  if ((fp = fopen(path, "w"))) {
    fputs("N 30\nKA 1e200\n", fp);
    fclose(fp);
  }
  write_column("dr.txt", "Dr", 30, 3, "1e308", "0.1");
  write_column("p0.txt", "P0", 30, 2, "0", "4.5");
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++)
    check_refused_up_front(30, cases[c][0], cases[c][1]);
  /* the largest steps reaches the snapshot bound before v0 is refused
  ** (the bound computed steps + 19: signed overflow, which the sanitizer
  ** build reports and stops on) */
  CHECK(test_sh("./afv run --N 30 --steps 9223372036854775807 --v0 1e6 "
                "--quiet --out %s/bad 2> %s/err.txt", root, root) == 2
        && !exists("bad"), "steps 9223372036854775807: not refused by v0");
  /* just inside: the paper's values scaled far up still run; the model
  ** needs no positive target without its modulus */
  CHECK(test_sh("./afv run --N 30 --steps 0 --KA 1e100 --quiet --out %s/big "
               "2> %s/err.txt", root, root) == 0, "KA 1e100 refused");
  CHECK(test_sh("./afv run --N 20 --steps 5 --KP 0 --P0 0 --quiet --out "
                "%s/kp0 2> %s/err.txt", root, root) == 0, "KP 0 P0 0 refused");
}

/* ---- --continue holds to the run in DIR ---------------------------------- */
/* --continue with parameters other than DIR's run: refused (exit 2, one
** line naming the key), the directory unchanged, whether the run is
** finished or not; with its own parameters (and a copy of its cells file)
** it goes on.  (The code before: "finished already", exit 0, for --P0 5
** on a P0 4 run, and an unfinished run resumed with its old N, P0, v0.) */
static void test_continue_other_parameters_refused(void)
{
  static const char *const cases[][2] = {
    {"--P0 5", "P0: 5 asked"}, {"--v0 2 --mu 3", "mu: 3 asked"},
    {"--steps 40", "steps: 40 asked"},
    {"--cells @/c2.txt", "cells: the cells file"}};
  size_t c;
  write_column("c1.txt", "v0", 30, 1, "0.2", "0.3");
  write_column("c2.txt", "v0", 30, 1, "0.25", "0.3");
  CHECK(test_sh("./afv run --N 30 " FAST_SYSTEM " --cells %s/c1.txt --steps "
                "20 --out %s/co && rm %s/co/final.svg", root, root, root) == 0,
        "the run, made unfinished");
  /* its keys as a config, which the options of each case override (a key
  ** given twice on the command line is refused) */
  test_sh("grep -v '^quiet\\|^cells' %s/co/params.txt > %s/co.conf && echo "
          "'cells c1.txt' >> %s/co.conf", root, root, root);
  for (c = 0; c < 2 * sizeof cases / sizeof cases[0]; c++) {
    const char *const *k = cases[c % 4];
    char args[512], *at, *before, *after, *e;
    long nb, na;
    int st;
    snprintf(args, sizeof args, "%s", k[0]);
    while ((at = strchr(args, '@'))) {   /* '@': the suite's directory */
      char rest[512];
      snprintf(rest, sizeof rest, "%s", at + 1);
      snprintf(at, sizeof args - (size_t)(at - args), "%s%s", root, rest);
    }
    if (c == 4)   /* the second round: the run finished */
      CHECK(test_sh("./afv run --resume %s/co --quiet", root) == 0,
            "finishing the run");
    before = picture("co", &nb);
    st = test_sh("./afv run --config %s/co.conf %s --continue --out %s/co "
                 "2> %s/err.txt", root, args, root, root);
    after = picture("co", &na);
    e = last_err();
    CHECK(st == 2 && strstr(e, k[1]) && strchr(e, '\n') == e + strlen(e) - 1,
          "'%s' (%s run): exit %d, want 2 and one line naming '%s': %s",
          args, c >= 4 ? "finished" : "unfinished", st, k[1], e);
    CHECK(na == nb && memcmp(before, after, (size_t)nb) == 0, "'%s': the "
          "run's directory changed", args);
    free(before);
    free(after);
    free(e);
  }
  CHECK(test_sh("cp %s/c1.txt %s/c1copy.txt && ./afv run --N 30 " FAST_SYSTEM " "
                "--cells %s/c1copy.txt --steps 20 --continue --out %s/co",
                root, root, root, root) == 0, "--continue with the run's own "
        "parameters");
}

/* ---- a directory that is not a run's ----------------------------------- */
/* A user's own log.txt and trajectory.dat (no params.txt), or a params.txt
** that afv did not write: a fresh run is refused (exit 2, naming the
** file) and every file stays as it was.  (The code before overwrote them
** without a word.) */
static void test_foreign_directory_kept(void)
{
  static const char *const setups[][2] = {
    {"echo mine > log.txt && echo 1 2 3 > trajectory.dat", "trajectory.dat"},
    {"echo 'N 5' > params.txt && echo mine > notes.txt", "params.txt"},
    {"echo '<svg/>' > snap_000000100.svg", "snap"}};
  size_t c;
  for (c = 0; c < sizeof setups / sizeof setups[0]; c++) {
    char sub[32], *before, *after, *e;
    long nb, na;
    int st;
    snprintf(sub, sizeof sub, "own%d", (int)c);
    CHECK(test_sh("mkdir -p %s/%s && cd %s/%s && %s", root, sub, root, sub,
                  setups[c][0]) == 0, "setup %d", (int)c);
    before = picture(sub, &nb);
    st = test_sh("./afv run " FAST " --steps 10 --out %s/%s 2> %s/err.txt",
                 root, sub, root);
    after = picture(sub, &na);
    e = last_err();
    CHECK(st == 2, "case %d: exit %d, want 2", (int)c, st);
    CHECK(na == nb && memcmp(before, after, (size_t)nb) == 0, "case %d: "
          "the user's files changed", (int)c);
    CHECK(strstr(e, setups[c][1]) && strchr(e, '\n') == e + strlen(e) - 1,
          "case %d: message not one line naming %s: %s", (int)c,
          setups[c][1], e);
    free(before);
    free(after);
    free(e);
  }
}

/* ---- a run that stopped before its first checkpoint ---------------------- */
/* 120 cells 2.5 l apart, not relaxed: no contact, so t1_reference.txt is
** a few bytes, params.txt about 1.3 KB, and the frame of step 0 in
** trajectory.dat 2.5 KB, the largest file written before the first
** checkpoint. */
#define APART "--N 120 " FAST_SYSTEM " --init lattice --spacing 2.5 " \
              "--relax_max_steps 0 --steps 50"

/* trajectory.dat past a file size limit (ulimit -f 4: 2048 bytes, POSIX
** counts 512-byte blocks): the run stops with the file and the system's
** reason; its directory has no checkpoint, a resume is refused,
** proposing a fresh run from the directory's own params.txt into it,
** which is accepted and equals a run elsewhere.  (The code before:
** "cannot write the outputs" without file or reason, then refused both a
** fresh run and a resume.  This test made the disk full by a link
** trajectory.dat -> /dev/full, which afv now refuses to write through.) */
static void test_unfinished_run_rerunnable(void)
{
  char *e;
  int st;
#ifdef UNDER_TSAN
  SKIP("ThreadSanitizer's runtime cannot run under ulimit -f");
  return;
#endif
  check_size_limit_failure(4, APART, "u", "u/trajectory.dat");
  CHECK(!exists("u/checkpoint.txt") && exists("u/params.txt"),
        "not the state of a run stopped before its first checkpoint");
  st = test_sh("./afv run --resume %s/u 2> %s/err.txt", root, root);
  e = last_err();
  CHECK(st == 2 && strstr(e, "--config"), "resume without a checkpoint: "
        "exit %d, message %s", st, e);
  free(e);
  /* as the resume's message says: its own params.txt, into itself */
  CHECK(test_sh("./afv run --config %s/u/params.txt --out %s/u 2> "
                "%s/err.txt", root, root, root) == 0, "a fresh run into the "
        "unfinished directory was refused");
  CHECK(test_sh("./afv run " APART " --out %s/u_ref", root) == 0,
        "the reference run");
  CHECK(same_file("u", "u_ref", "trajectory.dat")
        && same_file("u", "u_ref", "observables.csv"), "the re-run differs "
        "from a run in a fresh directory");
  /* now it holds a run: a fresh run is refused, nothing changes */
  CHECK(test_sh("./afv run " APART " --out %s/u 2>/dev/null", root) == 2,
        "a completed run was overwritten");
}

/* ---- afv analyze on a run that has not finished ---------------------------- */
/* The size of root/sub/file, -1 if it has none. */
static long file_size(const char *sub, const char *file)
{
  char p[512];
  struct stat sb;
  snprintf(p, sizeof p, "%s/%s/%s", root, sub, file);
  return stat(p, &sb) == 0 ? (long)sb.st_size : -1;
}

/* analyze on a run still being written, then on the same run killed short
** of its steps: refused (exit 1, one line saying why, naming the writer's
** process while it lives), nothing written or changed; with --partial
** analysed from the frames so far (exit 0).  (The code before: exit 0
** from the frames so far, without a word.) */
static void test_analyze_refuses_unfinished_run(void)
{
  char out[512], want[64], *e, *before, *after;
  long n0, n1;
  pid_t pid = start_live_writer("an", out, sizeof out, want, sizeof want);
  int st, waited;
  for (waited = 0; waited < 20000 && file_size("an", "trajectory.dat")
       < 4 * (16 + 20 * 64); waited += 5)   /* 4 frames of 64 cells */
    sleep_ms(5);
  st = test_sh("./afv analyze %s --steady-from 0 --lag 0.1 > /dev/null "
               "2> %s/err.txt", out, root);
  e = last_err();
  CHECK(st == 1, "analyze of a live run: exit %d, want 1: %s", st, e);
  CHECK(strstr(e, want) && strchr(e, '\n') == e + strlen(e) - 1,
        "the message is not one line naming %s: %s", want, e);
  CHECK(!exists("an/analysis"), "analyze of a live run wrote analysis/");
  free(e);
  st = test_sh("./afv analyze %s --steady-from 0 --lag 0.1 --partial "
               "> /dev/null 2> %s/err.txt", out, root);
  CHECK(st == 0 && exists("an/analysis/summary.txt"), "analyze --partial of "
        "a live run: exit %d, no summary.txt", st);
  kill(pid, SIGKILL);
  exit_status(pid);
  before = picture("an/analysis", &n0);
  st = test_sh("./afv analyze %s --steady-from 0 --lag 0.1 > /dev/null "
               "2> %s/err.txt", out, root);
  e = last_err();
  CHECK(st == 1 && strstr(e, "unfinished") && strstr(e, "of the 100000000"),
        "analyze of a killed run: exit %d, want 1 saying it is unfinished: "
        "%s", st, e);
  after = picture("an/analysis", &n1);
  CHECK(n0 == n1 && memcmp(before, after, (size_t)n0) == 0, "the refused "
        "analyze changed analysis/");
  free(e);
  free(before);
  free(after);
}

/* A write that fails during afv analyze (a file size limit: ulimit -f,
** with SIGXFSZ ignored, makes write(2) fail with EFBIG, as a full disk
** makes it fail with ENOSPC): exit 2, one line naming the file and the
** system's reason, and the earlier analysis/ unchanged, no staging folder
** left.  (The code before: "msd.svg: input/output error", and the files
** written before the failing one replaced.) */
static void test_analyze_write_error_changes_nothing(void)
{
  char *e, *before, *after;
  long n0, n1;
  int st;
#ifdef UNDER_TSAN
  SKIP("ThreadSanitizer's runtime cannot run under ulimit -f");
  return;
#endif
  CHECK(test_sh("./afv run " FAST " --steps 200 --out %s/full", root) == 0
        && test_sh("./afv analyze %s/full --steady-from 0 --lag 0.5 "
                   "> /dev/null 2>&1", root) == 0, "the run and analysis");
  before = picture("full/analysis", &n0);
  st = test_sh("(trap '' XFSZ; ulimit -f 1; exec ./afv analyze %s/full "
               "--steady-from 0 --lag 1 > /dev/null) 2> %s/err.txt", root,
               root);
  e = last_err();
  CHECK(st == 2, "analyze with writes failing: exit %d, want 2", st);
  CHECK(strstr(e, "msd.svg") && strstr(e, strerror(EFBIG))
        && strchr(e, '\n') == e + strlen(e) - 1, "the message is not one "
        "line naming msd.svg and '%s': %s", strerror(EFBIG), e);
  after = picture("full/analysis", &n1);
  CHECK(n0 > 0 && n0 == n1 && memcmp(before, after, (size_t)n0) == 0,
        "a failed analyze changed analysis/");
  CHECK(test_sh("ls %s/full | grep -q analysis.tmp", root) != 0,
        "a staging folder analysis.tmp.* left behind");
  free(e);
  free(before);
  free(after);
}

/* ---- messages ------------------------------------------------------------ */
/* A snapshot that cannot be written: the message names the file and the
** reason (the code before: "DIR: cannot write the outputs").  The writes
** fail by a file size limit (ulimit -f 8: 4096 bytes), which the 14 KB snapshot of step 0 is the first to reach
** (params.txt, observables.csv, trajectory.dat and t1_reference.txt come
** before it and are smaller).  (A directory at the temporary's old name
** snap_000000000.svg.tmp made it fail before; the temporary's name is now
** afv's alone.) */
static void test_io_error_names_file_and_reason(void)
{
#ifdef UNDER_TSAN
  SKIP("ThreadSanitizer's runtime cannot run under ulimit -f");
  return;
#endif
  check_size_limit_failure(8, "--N 30 --steps 10 --quiet", "s",
                           "snap_000000000.svg");
}

/* Values a hair past a bound are printed in full, not rounded onto the
** bound ("4,4 is smaller than 4l = 4"): a box side one ulp below 4l (afv
** eval --box, and afv run's L from phi) and phi one ulp above 1. */
static void test_bounds_printed_in_full(void)
{
  static const char *const cases[][2] = {
    {"eval --box 3.9999999999999996,4 @", "3.9999999999999996,4 "},
    {"run --N 5 --phi 0.98174770424681057 --out @/no", "L = sqrt(N pi "
     "l^2/phi) = 3.9999999999999996 "},
    {"run --phi 1.0000000000000002 --out @/no", "got 1.0000000000000002"}};
  char pts[512];
  size_t c;
  FILE *fp;
  snprintf(pts, sizeof pts, "%s/pts.txt", root);
  if ((fp = fopen(pts, "w"))) {
    fputs("0 0\n1 1\n", fp);
    fclose(fp);
  }
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    char args[512], *e, *at;
    int st;
    snprintf(args, sizeof args, "%s", cases[c][0]);
    if ((at = strchr(args, '@')))   /* '@': pts.txt, or the directory */
      snprintf(at, sizeof args - (size_t)(at - args), "%s%s",
               c == 0 ? pts : root, strchr(cases[c][0], '@') + 1);
    st = test_sh("./afv %s > /dev/null 2> %s/err.txt", args, root);
    e = last_err();
    CHECK(st == 2, "'%s': exit %d, want 2", args, st);
    CHECK(strstr(e, cases[c][1]) != NULL, "'%s': the value is not printed "
          "in full ('%s'): %s", args, cases[c][1], e);
    free(e);
  }
}

/* A lag a hair past the window is printed in full (the code before: "--lag
** 2: ... holds lags 0.1 .. 2 only" for --lag 2.0000001). */
static void test_lag_printed_in_full(void)
{
  char *e;
  int st;
  CHECK(test_sh("./afv run " FAST " --steps 200 --out %s/lag", root) == 0,
        "the run");
  st = test_sh("./afv analyze %s/lag --steady-from 0 --lag 2.0000001 "
               "> /dev/null 2> %s/err.txt", root, root);
  e = last_err();
  CHECK(st == 2 && strstr(e, "--lag 2.0000001:") && strstr(e, ".. 2 only"),
        "exit %d: %s", st, e);
  free(e);
}

void suite_runjob(void)
{
  snprintf(root, sizeof root, "/tmp/afv_test_runjob.%ld", (long)getpid());
  test_sh("rm -rf %s && mkdir -p %s", root, root);
  RUN(test_second_writer_refused);
  RUN(test_concurrent_fresh_runs);
  RUN(test_run_locked_meanwhile_is_in_use);
  RUN(test_lock_survives_cleaning);
  RUN(test_failed_resume_changes_nothing);
  RUN(test_uncomputable_parameters_refused);
  RUN(test_foreign_directory_kept);
  RUN(test_continue_other_parameters_refused);
  RUN(test_unfinished_run_rerunnable);
  RUN(test_io_error_names_file_and_reason);
  RUN(test_bounds_printed_in_full);
  RUN(test_lag_printed_in_full);
  RUN(test_analyze_refuses_unfinished_run);
  RUN(test_analyze_write_error_changes_nothing);
  test_sh("rm -rf %s", root);
}
