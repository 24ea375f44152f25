/*
** test_hostile.c -- afv run and afv analyze against a hostile user (issue
** 38): links and files of a user's at the names afv writes, files of a
** live run deleted or replaced, two analyses of one run at once.  afv
** never follows a link it did not make, never removes a file it did not
** create, and keeps one writer per run directory whatever is done to its
** files.
**
** Every test runs ./afv (from the repository root, where `make test`
** starts the runner) in a directory under /tmp, removed at the end; the
** shell does the file work (ln, cp, cmp).
*/
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

static char root[256];   /* the suite's directory */

/* A fast system: 64 cells, a checkpoint every 5 steps. */
#define QUICK "--N 64 --P0 4.5 --v0 0.3 --sample_every 5 --frame_every 10 " \
              "--checkpoint_every 5 --svg_every 0 --quiet"

/* 1 if root/err.txt (a command's stderr) holds text. */
static int err_says(const char *text)
{
  return test_sh("grep -q -- '%s' %s/err.txt", text, root) == 0;
}

/* Starts a long run of QUICK and args into root/sub in the background
** (the shell's child) and waits for its file sign (checkpoint.txt: its
** first checkpoint; params.txt: its relaxation); its process id, or -1. */
static long start_writer(const char *sub, const char *args,
                         const char *sign)
{
  char path[512];
  long pid = -1;
  FILE *fp;
  test_sh("./afv run " QUICK " %s --steps 100000000 --out %s/%s 2>/dev/null "
          "& echo $! > %s/%s.pid; i=0; while [ $i -lt 2000 ] && [ ! -e "
          "%s/%s/%s ]; do sleep 0.01; i=$((i+1)); done", args, root, sub,
          root, sub, root, sub, sign);
  snprintf(path, sizeof path, "%s/%s.pid", root, sub);
  if ((fp = fopen(path, "r"))) {
    if (fscanf(fp, "%ld", &pid) != 1) pid = -1;
    fclose(fp);
  }
  return pid;
}

/* Kills the writer pid (started by start_writer) and waits until it is
** gone (its parent, the shell, has ended: init reaps it). */
static void stop_writer(long pid)
{
  struct timespec ts = {0, 5000000L};
  int k;
  if (pid <= 0) return;
  kill((pid_t)pid, SIGKILL);
  for (k = 0; k < 400 && kill((pid_t)pid, 0) == 0; k++) nanosleep(&ts, NULL);
}

/* ---- links and files afv did not make ------------------------------------ */
/* Links at the names of afv's temporary files are never written through:
** a resume beside links checkpoint.txt.tmp, params.txt.tmp and
** final.svg.tmp -> victim leaves the victim and the links as they were
** (the code before wrote the checkpoint into the victim).  A link at
** trajectory.dat in a run that stopped before its first checkpoint makes
** a fresh run refuse, naming it (the code before emptied the victim). */
static void test_links_never_followed(void)
{
  int st;
  test_sh("cd %s && printf precious > victim && cp victim victim2", root);
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/l1", root) == 0,
        "the run");
  test_sh("cd %s/l1 && for f in checkpoint.txt params.txt final.svg; do "
          "ln -s %s/victim $f.tmp; done", root, root);
  st = test_sh("./afv run --resume %s/l1 --steps 10 --quiet 2> %s/err.txt",
               root, root);
  CHECK(st == 0, "resume beside links at the temporary names: exit %d", st);
  CHECK(test_sh("cd %s && printf precious | cmp -s - victim && test -L "
                "l1/checkpoint.txt.tmp && test -L l1/final.svg.tmp && test "
                "-L l1/params.txt.tmp && test ! -L l1/checkpoint.txt", root)
        == 0, "the resume wrote through (or replaced) a link it did not "
        "make");
  /* a run stopped before its first checkpoint, a link at trajectory.dat */
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/l2 && cd %s/l2 && "
                "rm checkpoint.txt trajectory.dat && ln -s %s/victim2 "
                "trajectory.dat", root, root, root) == 0, "setup of l2");
  st = test_sh("./afv run " QUICK " --steps 20 --out %s/l2 2> %s/err.txt",
               root, root);
  CHECK(st == 2 && err_says("trajectory.dat: a symbolic link"), "a fresh "
        "run over a link at trajectory.dat: exit %d, want 2 naming it", st);
  CHECK(test_sh("cd %s && printf precious | cmp -s - victim2 && test -L "
                "l2/trajectory.dat", root) == 0, "the fresh run wrote "
        "through (or removed) the link at trajectory.dat");
}

/* A user's files at the names of afv's temporary files stay as they were
** (the code before renamed them away: a fresh run "removed" a user's
** params.txt.tmp, checkpoint.txt.tmp and final.svg.tmp), and afv analyze
** neither empties a user's analysis.tmp/ nor a directory a link
** analysis.tmp points to (the code before removed every file of both). */
static void test_user_files_never_removed(void)
{
  int st;
  test_sh("mkdir -p %s/u && cd %s/u && for f in params.txt checkpoint.txt "
          "final.svg; do echo mine > $f.tmp; done", root, root);
  st = test_sh("./afv run " QUICK " --steps 20 --out %s/u 2> %s/err.txt",
               root, root);
  CHECK(st == 0, "a fresh run beside a user's *.tmp files: exit %d", st);
  CHECK(test_sh("cd %s/u && for f in params.txt checkpoint.txt final.svg; "
                "do echo mine | cmp -s - $f.tmp || exit 1; done", root) == 0,
        "a user's *.tmp file was changed or removed by a fresh run");
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/u2", root) == 0,
        "the second run");
  test_sh("mkdir -p %s/other %s/u/analysis.tmp && echo keep > "
          "%s/other/keep && echo mine > %s/u/analysis.tmp/mine && ln -s "
          "%s/other %s/u2/analysis.tmp", root, root, root, root, root, root);
  st = test_sh("./afv analyze %s/u --steady-from 0 --lag 0.1 > /dev/null 2> "
               "%s/err.txt && ./afv analyze %s/u2 --steady-from 0 --lag 0.1 "
               "> /dev/null 2>> %s/err.txt", root, root, root, root);
  CHECK(st == 0, "analyze beside a user's analysis.tmp: exit %d", st);
  CHECK(test_sh("test -e %s/u/analysis/summary.txt && test -e "
                "%s/u/analysis.tmp/mine && test -e %s/other/keep && test -L "
                "%s/u2/analysis.tmp", root, root, root, root) == 0,
        "analyze emptied a user's analysis.tmp/ or a linked directory");
}

/* The temporaries a killed writer left (NAME.PID.RAND.tmp, NAME a run
** file's, PID gone) are removed by the next writer; a user's file of a
** similar name, another name's, or a live process's stays.  (The code
** before wrote NAME.tmp, which a user could own; now each writer's name
** is its own, and a killed one's would pile up.) */
static void test_stale_temporaries_removed(void)
{
  int st;
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/st", root) == 0,
        "the run");
  test_sh("cd %s/st && for f in checkpoint.txt.999999999.0badf00d.tmp "
          "snap_000000010.svg.999999999.12345678.tmp checkpoint.txt.tmp "
          "notes.999999999.0badf00d.tmp params.txt.%ld.0badf00d.tmp; do "
          "echo x > $f; done", root, (long)getpid());
  st = test_sh("./afv run --resume %s/st --steps 10 --quiet", root);
  CHECK(st == 0, "the resume: exit %d", st);
  CHECK(test_sh("cd %s/st && test ! -e checkpoint.txt.999999999.0badf00d.tmp"
                " && test ! -e snap_000000010.svg.999999999.12345678.tmp",
                root) == 0, "a killed writer's temporaries were left");
  CHECK(test_sh("cd %s/st && test -e checkpoint.txt.tmp && test -e "
                "notes.999999999.0badf00d.tmp && test -e "
                "params.txt.%ld.0badf00d.tmp", root, (long)getpid()) == 0,
        "a file afv did not leave was removed");
}

/* The staging folders a killed analysis left (analysis.tmp.PID.XXXXXX,
** PID gone) are removed by the next analysis of the run: afv's files in
** them and the folder; a user's file (and the folder holding it), a live
** process's folder and a link of that name stay.  (The code before left
** every killed analysis's folder, with its files, beside the run.) */
static void test_stale_stages_removed(void)
{
  int st;
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/sa", root) == 0,
        "the run");
  test_sh("cd %s/sa && mkdir analysis.tmp.999999999.abcdef "
          "analysis.tmp.999999998.abcdef analysis.tmp.%ld.abcdef ../keepme "
          "&& for f in msd.csv summary.txt msd.svg.999999999.0badf00d.tmp; "
          "do echo x > analysis.tmp.999999999.abcdef/$f; done && echo x > "
          "analysis.tmp.999999998.abcdef/msd.csv && echo mine > "
          "analysis.tmp.999999998.abcdef/mine.txt && echo x > "
          "analysis.tmp.%ld.abcdef/msd.csv && echo x > ../keepme/msd.csv && "
          "ln -s ../keepme analysis.tmp.999999997.abcdef", root,
          (long)getpid(), (long)getpid());
  st = test_sh("./afv analyze %s/sa --steady-from 0 --lag 0.1 > /dev/null",
               root);
  CHECK(st == 0, "the analysis: exit %d", st);
  CHECK(test_sh("test ! -e %s/sa/analysis.tmp.999999999.abcdef", root) == 0,
        "a killed analysis's staging folder was left");
  CHECK(test_sh("cd %s/sa && test ! -e analysis.tmp.999999998.abcdef/msd.csv"
                , root) == 0, "afv's file in a dead folder was left");
  CHECK(test_sh("cd %s/sa && test -e analysis.tmp.999999998.abcdef/mine.txt "
                "&& test -e analysis.tmp.%ld.abcdef/msd.csv && test -L "
                "analysis.tmp.999999997.abcdef && test -e ../keepme/msd.csv",
                root, (long)getpid()) == 0,
        "a user's file, a live analysis's folder or a link was removed");
}

/* ---- one writer per run directory ---------------------------------------- */
/* With a run live in DIR, each file of the run replaced by a copy (a new
** inode), then deleted, one after the other (so that at the end none of
** the live run's files is left), leaves a resume and a fresh run (seed 2)
** refused, exit 2 (in use; or holding a run, or without params.txt), and
** no params.txt of seed 2.  (The code before held
** the lock on observables.csv alone: replacing it let the resume in, both
** writing the same files, and deleting it let a fresh run of another seed
** write its params.txt and observables.csv beside the first run's
** trajectory.) */
static void test_lock_holds_whatever_is_replaced(void)
{
  static const char *const files[] = {"observables.csv", "trajectory.dat",
    "log.txt", "checkpoint.txt", "t1_reference.txt", "params.txt"};
  long pid = start_writer("live", "", "checkpoint.txt");
  size_t k;
  int how;
  CHECK(pid > 0, "the writer did not start");
  for (k = 0; k < sizeof files / sizeof files[0]; k++)
    for (how = 0; how < 2; how++) {
      int resumed, fresh;
      if (how == 0)
        test_sh("cd %s/live && cp %s copy && rm %s && mv copy %s", root,
                files[k], files[k], files[k]);
      else
        test_sh("rm -f %s/live/%s", root, files[k]);
      resumed = test_sh("./afv run --resume %s/live --steps 10 --quiet 2> "
                        "%s/err.txt", root, root);
      CHECK(resumed == 2 && (err_says("in use") || err_says("cannot open")),
            "%s %s: a resume beside the live run: exit %d", files[k],
            how ? "deleted" : "replaced", resumed);
      fresh = test_sh("./afv run " QUICK " --seed 2 --steps 10 --out "
                      "%s/live 2> %s/err.txt", root, root);
      CHECK(fresh == 2 && (err_says("in use") || err_says("already holds")),
            "%s %s: a fresh run into the live run's directory: exit %d",
            files[k], how ? "deleted" : "replaced", fresh);
      CHECK(test_sh("grep -q '^seed  *2' %s/live/params.txt 2>/dev/null",
                    root) != 0,
            "%s %s: params.txt of the second writer", files[k], how ?
            "deleted" : "replaced");
    }
  stop_writer(pid);
  /* a run relaxing (no checkpoint yet), its observables.csv deleted */
  pid = start_writer("relaxing", "--relax_tol 1e-300 --relax_max_steps "
                     "100000000", "params.txt");
  CHECK(pid > 0, "the relaxing writer did not start");
  test_sh("rm %s/relaxing/observables.csv", root);
  CHECK(test_sh("./afv run " QUICK " --seed 2 --steps 10 --out %s/relaxing "
                "2> %s/err.txt", root, root) == 2 && err_says("in use")
        && test_sh("grep -q '^seed  *2' %s/relaxing/params.txt", root) != 0,
        "a fresh run beside a relaxing run whose observables.csv was "
        "deleted was not refused as in use");
  stop_writer(pid);
}

/* ---- two analyses of one run ---------------------------------------------- */
/* Two afv analyze of one run at the same moment, at lags 0.5 and 1: both
** succeed, and analysis/ is then exactly the output of one of them alone
** (the code before shared analysis.tmp/: summary.txt of one lag, msd.svg
** of the other, no msd.csv, a stray series.svg.tmp), with no staging
** folder left. */
static void test_two_analyses_serialise(void)
{
  int trial;
  CHECK(test_sh("./afv run " QUICK " --steps 200 --out %s/an", root) == 0,
        "the run");
  CHECK(test_sh("./afv analyze %s/an --steady-from 0 --lag 0.5 > /dev/null "
                "&& cp -r %s/an/analysis %s/lag05 && ./afv analyze %s/an "
                "--steady-from 0 --lag 1 > /dev/null && cp -r "
                "%s/an/analysis %s/lag1", root, root, root, root, root, root)
        == 0, "the two analyses alone");
  for (trial = 0; trial < 4; trial++) {
    int st = test_sh("./afv analyze %s/an --steady-from 0 --lag 0.5 > "
                     "/dev/null 2>&1 & a=$!; ./afv analyze %s/an "
                     "--steady-from 0 --lag 1 > /dev/null 2>&1 & b=$!; "
                     "wait $a && wait $b", root, root);
    CHECK(st == 0, "trial %d: an analysis failed", trial);
    CHECK(test_sh("cd %s && { diff -r an/analysis lag05 >/dev/null || diff "
                  "-r an/analysis lag1 > /dev/null; }", root) == 0,
          "trial %d: analysis/ is not one analysis whole", trial);
    CHECK(test_sh("ls %s/an | grep -q 'analysis\\.tmp'", root) != 0,
          "trial %d: a staging folder was left", trial);
  }
}

/* ---- readers trust nothing they cannot check ------------------------------ */
/* A resume refuses a params.txt whose keys were edited since the run began,
** naming the key, and changes nothing (the code before went on under the
** edited v0, Dr, mu, cap, phi, frame_every, init or relax_tol in the same
** files; only P0, seed, dt and sample_every showed in the checkpoint). */
static void test_resume_refuses_edited_keys(void)
{
  static const char *const edits[][2] = {
    {"v0", "0.7"}, {"Dr", "0.2"}, {"mu", "2"}, {"cap", "0.1"},
    {"phi", "0.4"}, {"frame_every", "5"}, {"init", "lattice"},
    {"relax_tol", "0.001"}};
  size_t k;
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/ed", root) == 0,
        "the run");
  for (k = 0; k < sizeof edits / sizeof edits[0]; k++) {
    char want[64];
    int st;
    test_sh("rm -rf %s/ed1 %s/ed2 && cp -r %s/ed %s/ed1 && sed -i 's/^%s .*/"
            "%s %s/' %s/ed1/params.txt && cp -r %s/ed1 %s/ed2", root, root,
            root, root, edits[k][0], edits[k][0], edits[k][1], root, root,
            root);
    st = test_sh("./afv run --resume %s/ed1 --steps 10 --quiet 2> "
                 "%s/err.txt", root, root);
    snprintf(want, sizeof want, ": %s %s, but afv wrote %s", edits[k][0],
             edits[k][1], edits[k][0]);
    CHECK(st == 2 && err_says(want), "%s edited to %s: exit %d, want 2 "
          "naming it", edits[k][0], edits[k][1], st);
    CHECK(test_sh("diff -r %s/ed1 %s/ed2 > /dev/null", root, root) == 0,
          "%s edited: the refused resume changed the directory",
          edits[k][0]);
  }
}

/* A key the run does not use (spacing without init lattice) is in neither
** params.txt nor its record, so a resume finds nothing edited, and the
** params.txt written from a config that gives it reads back to the same
** bytes (fuzz_config found both: the record held spacing=4, params.txt
** none, and the resume was refused as edited). */
static void test_unused_key_resumes(void)
{
  CHECK(test_sh("./afv run " QUICK " --steps 20 --spacing 4 --out %s/uk",
                root) == 0, "the run");
  CHECK(test_sh("grep -q spacing %s/uk/params.txt", root) != 0,
        "params.txt records spacing for init cluster");
  CHECK(test_sh("./afv run --resume %s/uk --steps 10 --quiet 2> %s/err.txt",
                root, root) == 0, "the resume of a run given an unused key "
        "was refused");
  CHECK(!err_says("but afv wrote"), "the resume says spacing was edited");
}

/* afv analyze refuses a params.txt it cannot read whole (empty, garbage,
** v0 missing, v0 not a number), exit 2, nothing written (the code before
** used v0 = 0.5 and friends silently, D_eff 25 times off, and skipped the
** unfinished-run check). */
static void test_analyze_refuses_damaged_params(void)
{
  static const char *const damage[] = {
    ": > params.txt", "echo garbage > params.txt",
    "sed -i '/^v0 /d' params.txt", "sed -i 's/^v0 .*/v0 abc/' params.txt"};
  size_t k;
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/ap", root) == 0,
        "the run");
  for (k = 0; k < sizeof damage / sizeof damage[0]; k++) {
    int st;
    test_sh("rm -rf %s/ap1 && cp -r %s/ap %s/ap1 && cd %s/ap1 && %s", root,
            root, root, root, damage[k]);
    st = test_sh("./afv analyze %s/ap1 --steady-from 0 --lag 0.1 > "
                 "/dev/null 2> %s/err.txt", root, root);
    CHECK(st == 2 && err_says("params.txt") && test_sh("test -e "
          "%s/ap1/analysis", root) != 0, "'%s': exit %d, want 2 naming "
          "params.txt, and no analysis/", damage[k], st);
  }
}

/* Writes x as a little-endian float64 (the trajectory's order, io.c)
** over the x centre of cell i in frame k of the 64-cell trajectory at
** root/rel; 1 if written. */
static int patch_centre(const char *rel, int k, int i, double x)
{
  char path[512], line[256];
  unsigned char b[8];
  unsigned long long u;
  long head;
  FILE *fp;
  int j, ok;
  snprintf(path, sizeof path, "%s/%s", root, rel);
  if (!(fp = fopen(path, "r+b"))) return 0;
  ok = fgets(line, sizeof line, fp) != NULL;
  head = (long)strlen(line);
  memcpy(&u, &x, sizeof u);
  for (j = 0; j < 8; j++) b[j] = (unsigned char)(u >> (8 * j));
  ok = ok && fseek(fp, head + (long)k * (16 + 20 * 64) + 16 + 20L * i,
                   SEEK_SET) == 0 && fwrite(b, 1, 8, fp) == 8;
  return fclose(fp) == 0 && ok;
}

/* afv analyze refuses a trajectory that is not its finished run's: cut to
** 10 of its 31 frames, a centre of 1e5 in frame 5, the header's box edited
** to 4 or 1e308 (exit 2, nothing written; the code before analysed each,
** D_s 3.5e6 for the centre); afv run --resume refuses a last frame with x
** = 1e300, changing nothing (the code before appended to it). */
static void test_trajectory_checked(void)
{
  static const char *const damage[][2] = {
    {"truncate -s $(( $(head -1 trajectory.dat | wc -c) + 10 * 1296 )) "
     "trajectory.dat", "records"},
    {"sed -i '1s/periodic .*/periodic 4 4/' trajectory.dat", "trajectory"},
    {"sed -i '1s/periodic .*/periodic 1e308 1e308/' trajectory.dat",
     "trajectory"}, {"", "since the frame before, beyond"}};
  size_t k;
  int st;
  CHECK(test_sh("./afv run " QUICK " --steps 300 --out %s/tr && ./afv "
                "analyze %s/tr --steady-from 0 --lag 0.5 > /dev/null 2>&1",
                root, root) == 0, "the run and its analysis");
  for (k = 0; k < sizeof damage / sizeof damage[0]; k++) {
    test_sh("rm -rf %s/tr1 && cp -r %s/tr %s/tr1 && rm -r %s/tr1/analysis "
            "&& cd %s/tr1 && %s", root, root, root, root, root,
            damage[k][0][0] ? damage[k][0] : "true");
    if (!damage[k][0][0])
      CHECK(patch_centre("tr1/trajectory.dat", 5, 3, 1e5), "patching");
    st = test_sh("./afv analyze %s/tr1 --steady-from 0 --lag 0.5 > /dev/null "
                 "2> %s/err.txt", root, root);
    CHECK(st == 2 && err_says(damage[k][1]) && test_sh("test ! -e "
          "%s/tr1/analysis", root) == 0, "damage %d: exit %d, want 2 "
          "naming '%s', nothing written", (int)k, st, damage[k][1]);
  }
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/lf", root) == 0,
        "the run to resume");
  CHECK(patch_centre("lf/trajectory.dat", 2, 0, 1e300), "patching");
  test_sh("cp -r %s/lf %s/lf0", root, root);
  st = test_sh("./afv run --resume %s/lf --steps 10 --quiet 2> %s/err.txt",
               root, root);
  CHECK(st == 2 && err_says("is not within 0 of the checkpoint")
        && test_sh("diff -r %s/lf %s/lf0 > /dev/null", root, root) == 0,
        "a last frame with x = 1e300: exit %d, want 2, nothing changed", st);
}

/* ---- smaller ---------------------------------------------------------------- */
/* A FIFO at log.txt makes a resume refuse at once, naming it (the code
** before blocked for ever in fopen; timeout ends it here, exit 124). */
static void test_fifo_log_does_not_block(void)
{
  int st;
  CHECK(test_sh("./afv run " QUICK " --steps 20 --out %s/ff && rm "
                "%s/ff/log.txt && mkfifo %s/ff/log.txt", root, root, root)
        == 0, "setup");
  st = test_sh("timeout 10 ./afv run --resume %s/ff --steps 10 --quiet 2> "
               "%s/err.txt", root, root);
  CHECK(st == 2 && err_says("log.txt: not a regular file"), "a FIFO at "
        "log.txt: exit %d, want 2 naming it", st);
}

/* A relaxation that cannot step (mu 1e300: a move that is not finite)
** stops with exit status 3, says so with the real bound (1e8 l), and
** leaves nothing (the code before: exit 2, "a move > l/2", and params.txt,
** log.txt, observables.csv and trajectory.dat left). */
static void test_unstable_relaxation(void)
{
  int st = test_sh("./afv run --N 50 --mu 1e300 --steps 10 --out %s/mu 2> "
                   "%s/err.txt", root, root);
  CHECK(st == 3 && err_says("relaxation: cell") && err_says("1e+08 l")
        && !err_says("l/2"), "exit %d, want 3 and the relaxation's bound",
        st);
  CHECK(test_sh("test -e %s/mu", root) != 0, "the stopped run left %s/mu",
        root);
}

/* A key given twice, on the command line or in a config, is refused by
** name, nothing made (the code before: the last one won, silently); nan
** is "not a number", not "beyond the largest double". */
static void test_key_twice_and_nan_refused(void)
{
  int st = test_sh("./afv run --steps 0 --relax_max_steps 0 --v0 1 --v0 2 "
                   "--out %s/tw 2> %s/err.txt", root, root);
  CHECK(st == 2 && err_says("--v0: given twice"), "--v0 twice: exit %d",
        st);
  test_sh("printf 'v0 1\\nsteps 0\\nv0 2\\n' > %s/tw.conf", root);
  st = test_sh("./afv run --config %s/tw.conf --relax_max_steps 0 --out "
               "%s/tw 2> %s/err.txt", root, root, root);
  CHECK(st == 2 && err_says("tw.conf:3: v0: given twice (line 1"), "v0 "
        "twice in a config: exit %d", st);
  CHECK(test_sh("test -e %s/tw", root) != 0, "a refused run made its "
        "directory");
  st = test_sh("./afv run --v0 nan --out %s/tw 2> %s/err.txt", root, root);
  CHECK(st == 2 && err_says("not a number (nan)")
        && !err_says("beyond the largest"), "nan: exit %d", st);
}

/* A small sweep: 2 jobs (v0 0.1 and 0.3), 20 cells, 20 steps. */
#define SWEEP "--P0 4 --v0 0.1,0.3 --N 20 --steps 20 --frame_every 5 " \
              "--lag 0.05"

/* A killed afv sweep leaves DIR.writing-PID (SIGKILL cannot be caught);
** the next sweep to DIR removes such a folder of a process that is gone,
** afv's files only: one holding a user's file keeps it (and itself).  (The
** code before left every one behind, 46 MB for a large grid.) */
static void test_stale_sweep_folder_removed(void)
{
  int st;
  test_sh("cd %s && for d in sw.writing-999999998 sw.writing-999999999; do "
          "mkdir -p $d/jobs $d/runs $d/logs && echo x > $d/jobs/0001.conf && "
          "echo x > $d/jobs/0002.conf.7.0badf00d.tmp && echo x > "
          "$d/points.csv && echo x > $d/Makefile; done && echo mine > "
          "sw.writing-999999998/mine.txt", root);
  st = test_sh("./afv sweep --out %s/sw " SWEEP " > /dev/null 2> "
               "%s/err.txt", root, root);
  CHECK(st == 0, "the sweep: exit %d", st);
  CHECK(test_sh("test ! -e %s/sw.writing-999999999", root) == 0,
        "a dead sweep's folder was left");
  CHECK(test_sh("cd %s/sw.writing-999999998 && test -e mine.txt && test ! "
                "-e points.csv && test ! -e jobs/0001.conf", root) == 0,
        "a dead sweep's folder with a user's file: the user's file removed, "
        "or afv's left");
}

/* afv collect on a copy of the finished sweep root/sc after the shell
** command damage: its exit status, its stderr in root/err.txt. */
static int collect_after(const char *damage)
{
  return test_sh("rm -rf %s/swc && cp -r %s/sc %s/swc && cd %s/swc && %s && "
                 "cd - > /dev/null && ./afv collect %s/swc > /dev/null 2> "
                 "%s/err.txt", root, root, root, root, damage, root, root);
}

/* afv collect ties every summary to its run and range-checks it: a
** summary copied from the other job, values out of range, a key twice, a
** cell count not N, D_eff nan at v0 > 0, and a missing jobs/ID.conf make
** the job damaged (exit 1, the reason named); a missing analysis.txt, a
** repeated key column and a points.csv of its header alone are bad input
** (exit 2); a full disk says why.  (The code before verified every one of
** these, exit 0, and said "cannot write" without the reason.) */
static void test_collect_ties_and_checks(void)
{
  static const char *const damaged[][2] = {
    {"cp runs/0001/analysis/summary.txt runs/0002/analysis/", "is of run "
     "0001"},
    {"sed -i 's/^ngc_frac_mean .*/ngc_frac_mean 7/' S", "ngc_frac_mean 7 is "
     "out of its range"},
    {"sed -i 's/^omega_mean .*/omega_mean -3/' S", "omega_mean -3 is out"},
    {"sed -i 's/^D_eff .*/D_eff -5/' S", "D_eff -5 is out"},
    {"sed -i 's/^D_eff .*/D_eff inf/' S", "D_eff inf is out"},
    {"sed -i 's/^D_eff .*/D_eff nan/' S", "D_eff nan, but v0"},
    {"sed -i 's/^msd_beta .*/msd_beta inf/' S", "msd_beta inf is out"},
    {"sed -i 's/^cells .*/cells 21/' S", "counts 21 cells"},
    {"echo 'ngc_frac_mean 0.5' >> S", "ngc_frac_mean given twice"},
    {"rm jobs/0002.conf", "jobs/0002.conf: No such file"}};
  static const char *const bad[] = {
    "rm analysis.txt",
    ("sed -i 's/^id,/id,v0,/; 2,$ s/^\\([^,]*\\),/\\1,0.1,/'"
     " points.csv"),
    "sed -i '2,$ d' points.csv"};
  size_t k;
  CHECK(test_sh("./afv sweep --out %s/sc " SWEEP " > /dev/null && make -s "
                "-C %s/sc > /dev/null 2>&1 && ./afv collect %s/sc > /dev/null",
                root, root, root) == 0, "the sweep, run and collected");
  for (k = 0; k < sizeof damaged / sizeof damaged[0]; k++) {
    char cmd[256], *at;
    int st;
    snprintf(cmd, sizeof cmd, "%s", damaged[k][0]);
    if ((at = strstr(cmd, " S")) && at[2] == 0)   /* S: job 0002's summary */
      snprintf(at, sizeof cmd - (size_t)(at - cmd),
               " runs/0002/analysis/summary.txt");
    st = collect_after(cmd);
    CHECK(st == 1 && err_says(damaged[k][1]) && err_says("job 0002"),
          "'%s': exit %d, want 1 and job 0002 damaged: %s", cmd, st,
          damaged[k][1]);
  }
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    int st = collect_after(bad[k]);
    CHECK(st == 2, "'%s': exit %d, want 2", bad[k], st);
  }
  /* (stderr through a pipe: a file would be past the limit too) */
  test_sh("{ (trap '' XFSZ; ulimit -f 0; exec ./afv collect %s/sc) 2>&1 > "
          "/dev/null; echo \"exit $?\"; } | cat > %s/err.txt", root, root);
  CHECK(err_says("table.csv: cannot write: ") && err_says(strerror(EFBIG))
        && err_says("exit 2"), "collect past a file size limit does not "
        "say why");
}

void suite_hostile(void)
{
  snprintf(root, sizeof root, "/tmp/afv_test_hostile.%ld", (long)getpid());
  test_sh("rm -rf %s && mkdir -p %s", root, root);
  RUN(test_links_never_followed);
  RUN(test_user_files_never_removed);
  RUN(test_stale_temporaries_removed);
  RUN(test_stale_stages_removed);
  RUN(test_lock_holds_whatever_is_replaced);
  RUN(test_two_analyses_serialise);
  RUN(test_resume_refuses_edited_keys);
  RUN(test_unused_key_resumes);
  RUN(test_analyze_refuses_damaged_params);
  RUN(test_trajectory_checked);
  RUN(test_fifo_log_does_not_block);
  RUN(test_unstable_relaxation);
  RUN(test_key_twice_and_nan_refused);
  RUN(test_stale_sweep_folder_removed);
  RUN(test_collect_ties_and_checks);
  test_sh("rm -rf %s", root);
}
