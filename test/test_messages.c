/*
** test_messages.c -- what afv run tells a user at its end and when it is
** stopped (issue 41): a warning for steps that moved a cell too far, with
** the count and what helps; how to go on after Ctrl-C or a kill; numbers
** in messages as a user writes them; and a long run's snapshots bounded.
**
** Every test runs ./afv (from the repository root, where `make test` starts
** the runner) in a directory under /tmp, removed at the end.
*/
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define TEXT_MAX 65536

static char dir[64];              /* the suite's directory */
static char err_text[TEXT_MAX];   /* stderr of the last command */

/* Reads the file dir/rel into buf ("" if missing). */
static const char *read_in(const char *rel, char *buf)
{
  char path[256];
  FILE *fp;
  size_t k = 0;
  snprintf(path, sizeof path, "%s/%s", dir, rel);
  if ((fp = fopen(path, "r"))) {
    k = fread(buf, 1, TEXT_MAX - 1, fp);
    fclose(fp);
  }
  buf[k] = 0;
  return buf;
}

/* ./afv ARGS (each %s is dir), stderr into err_text; the exit status. */
static int afv(const char *args)
{
  char a[1024], cmd[1400];
  int st;
  snprintf(a, sizeof a, args, dir, dir, dir);
  snprintf(cmd, sizeof cmd, "./afv %s >%s/stdout 2>%s/stderr", a, dir, dir);
  st = system(cmd);
  read_in("stderr", err_text);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* A run whose active steps move cells far (dt 1: 1e5 l) says so at its
** end, with the count and the advice; a calm run says nothing of it. */
static void run_warns_of_large_moves(void)
{
  CHECK(afv("run --N 100 --dt 1 --steps 50 --svg_every 0 --out %s/far") == 0,
        "%s", err_text);
  CHECK(strstr(err_text, "warning: 50 step(s) of the active run moved a "
               "cell more than 0.5 l") && strstr(err_text, "a smaller dt, "
               "or --cap 0.45") && strstr(err_text, "more than the box side"),
        "no warning:\n%s", err_text);
  CHECK(afv("run --N 30 --v0 0.1 --steps 100 --relax_max_steps 0 "
            "--init lattice --svg_every 0 --out %s/calm") == 0
        && !strstr(err_text, "warning"), "a calm run warned:\n%s", err_text);
}

/* waitpid with a deadline of seconds; 1 if pid ended (its status in *st). */
static int wait_for(pid_t pid, int *st, double seconds)
{
  struct timespec nap = {0, 20000000};
  double waited = 0;
  while (waited < seconds) {
    if (waitpid(pid, st, WNOHANG) == pid) return 1;
    nanosleep(&nap, NULL);
    waited += 0.02;
  }
  return 0;
}

/* A run stopped by a kill (SIGTERM; Ctrl-C's SIGINT takes the same path)
** in its steps says how to resume, and still dies of the signal. */
static void run_says_how_to_resume(void)
{
  char out[128], errpath[128], ckpt[160];
  struct stat sb;
  int st = 0, k;
  pid_t pid;
  snprintf(out, sizeof out, "%s/killed", dir);
  snprintf(errpath, sizeof errpath, "%s/killed.err", dir);
  snprintf(ckpt, sizeof ckpt, "%s/checkpoint.txt", out);
  fflush(stdout);
  if ((pid = fork()) == 0) {
    if (!freopen(errpath, "w", stderr)) _exit(127);
    execl("./afv", "afv", "run", "--N", "60", "--steps", "100000000",
          "--svg_every", "0", "--quiet", "--out", out, (char *)NULL);
    _exit(127);
  }
  CHECK(pid > 0, "fork");
  if (pid <= 0) return;
  for (k = 0; k < 3000 && stat(ckpt, &sb) != 0; k++) {   /* the steps began */
    struct timespec nap = {0, 10000000};
    nanosleep(&nap, NULL);
  }
  kill(pid, SIGTERM);
  if (!wait_for(pid, &st, 30)) {
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
    CHECK(0, "afv run did not stop on SIGTERM");
    return;
  }
  read_in("killed.err", err_text);
  CHECK(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM, "not ended by the "
        "signal (status %d)", st);
  CHECK(strstr(err_text, "afv run: interrupted") && strstr(err_text,
        "afv run --resume ") && strstr(err_text, "/killed continues it"),
        "no word on resuming:\n%s", err_text);
}

/* --continue against another run's parameters: the numbers as written
** (4.8), not params.txt's %.17g (4.7999999999999998). */
static void continue_mismatch_as_written(void)
{
  CHECK(afv("run --N 10 --steps 20 --svg_every 0 --quiet --out %s/c") == 0,
        "%s", err_text);
  CHECK(afv("run --N 10 --steps 20 --svg_every 0 --quiet --P0 5 --continue "
            "--out %s/c") == 2 && strstr(err_text, "P0: 5 asked, but ")
        && strstr(err_text, "/params.txt has 4.8: "), "%s", err_text);
}

/* Without --svg_every a long run draws a snapshot every steps/20 steps:
** 21 and final.svg for 2 x 10^5 steps (41 at the 5000 of before). */
static void long_run_snapshots_bounded(void)
{
  char buf[TEXT_MAX];
  CHECK(afv("run --N 10 --steps 200000 --frame_every 0 --sample_every 0 "
            "--checkpoint_every 0 --quiet --out %s/long") == 0, "%s",
        err_text);
  CHECK(strstr(read_in("long/params.txt", buf), "\nsvg_every        10000\n")
        != NULL, "params.txt:\n%s", buf);
  CHECK(afv("run --N 10 --steps 20 --svg_every 5000 --quiet --out %s/given")
        == 0 && strstr(read_in("given/params.txt", buf), "\nsvg_every        "
                       "5000\n"), "a given svg_every changed:\n%s", buf);
}

void suite_messages(void)
{
  char cmd[128];
  snprintf(dir, sizeof dir, "/tmp/afv_messages_%ld", (long)getpid());
  if (mkdir(dir, 0700) != 0) {
    printf("  cannot create %s\n", dir);
    return;
  }
  RUN(run_warns_of_large_moves);
  RUN(run_says_how_to_resume);
  RUN(continue_mismatch_as_written);
  RUN(long_run_snapshots_bounded);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) printf("  note: could not remove %s\n", dir);
}
