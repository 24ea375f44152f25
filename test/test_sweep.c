/*
** test_sweep.c -- afv sweep and afv collect as a user runs them (./afv
** through system(), from the repository root), the boundary fit and the
** crossing of phase.c, and the analysis quantities collect reads (t1_rate,
** msd_beta, the steady window and lag refusals of afv analyze).
** The make runner killed part-way is test/sweep_kill.sh (too slow here).
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define TEXT_MAX 65536

static char base[64];              /* the suite's temporary directory */
static char err_text[TEXT_MAX];    /* stderr of the last command */

static int have_afv(void)
{
  if (access("./afv", X_OK) == 0) return 1;
  SKIP("./afv not built");
  return 0;
}

/* Reads a whole file into buf ("" if missing). */
static const char *slurp(const char *path, char *buf)
{
  FILE *fp = fopen(path, "r");
  size_t k = 0;
  buf[0] = 0;
  if (!fp) return buf;
  k = fread(buf, 1, TEXT_MAX - 1, fp);
  buf[k] = 0;
  fclose(fp);
  return buf;
}

/* Runs "./afv ARGS" (every %s in args is base) with stdout to a file and
** stderr into err_text; returns the exit status. */
static int afv(const char *args)
{
  char a[1024], cmd[1400], se[96];
  const char *p = args;
  size_t m = 0;
  int st;
  while (*p && m < sizeof a - 80) {
    if (p[0] == '%' && p[1] == 's') {
      m += (size_t)snprintf(a + m, sizeof a - m, "%s", base);
      p += 2;
    } else {
      a[m++] = *p++;
    }
  }
  a[m] = 0;
  snprintf(se, sizeof se, "%s/stderr", base);
  snprintf(cmd, sizeof cmd, "./afv %s >%s/stdout 2>%s", a, base, se);
  st = system(cmd);
  slurp(se, err_text);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int exists(const char *rel)
{
  char p[256];
  struct stat sb;
  snprintf(p, sizeof p, "%s/%s", base, rel);
  return stat(p, &sb) == 0;
}

static const char *read_rel(const char *rel, char *buf)
{
  char p[256];
  snprintf(p, sizeof p, "%s/%s", base, rel);
  return slurp(p, buf);
}

static int count_lines(const char *s)
{
  int n = 0;
  for (; *s; s++) n += *s == '\n';
  return n;
}

static void write_rel(const char *rel, const char *text)
{
  char p[256];
  FILE *fp;
  snprintf(p, sizeof p, "%s/%s", base, rel);
  fp = fopen(p, "w");
  CHECK(fp != NULL, "cannot write %s", p);
  if (!fp) return;
  fputs(text, fp);
  fclose(fp);
}

static void shell(const char *fmt, const char *arg)
{
  char cmd[512];
  snprintf(cmd, sizeof cmd, fmt, arg, arg);
  CHECK(system(cmd) == 0, "%s failed", cmd);
}

/* ---- grid syntax ---------------------------------------------------------- */
/* Ranges (inclusive, robust to rounding: 0.1:0.3:0.1 has 3 values, the
** 25th value of 4:8.8:0.2 prints as 8.8), lists, seeds; points.csv in
** job order (first key slowest, seed fastest); the job files hold every
** key; the three runners hold the same job lines. */
static void sweep_grid_ranges_and_lists(void)
{
  static char buf[TEXT_MAX], jobs[TEXT_MAX], mk[TEXT_MAX];
  char line[2048], *p;
  int n = 0;
  if (!have_afv()) return;
  CHECK(afv("sweep --out %s/g1 --P0 4:5:0.5 --v0 0.1:0.3:0.1 --seeds 2 "
            "--steps 10 --frame_every 5 --Dr 0.2 --per-task 5") == 0,
        "sweep: %s", err_text);
  read_rel("g1/points.csv", buf);
  {
    const char *head = "id,P0,v0,seed\n0001,4,0.1,1\n0002,4,0.1,2\n"
                       "0003,4,0.2,1\n";
    CHECK(!strncmp(buf, head, strlen(head)), "points.csv starts:\n%.120s",
          buf);
  }
  CHECK(count_lines(buf) == 1 + 3 * 3 * 2, "points.csv: %d lines",
        count_lines(buf));
  CHECK(strstr(buf, "0018,5,0.3,2\n") != NULL, "last job:\n%s", buf);
  read_rel("g1/jobs/0018.conf", buf);
  CHECK(strstr(buf, "\nP0               5\n") && strstr(buf, "\nv0               "
        "0.29999999999999999\n") && strstr(buf, "\nseed             2\n")
        && strstr(buf, "\nDr               0.20000000000000001\n")
        && strstr(buf, "\nsteps            10\n"), "0018.conf:\n%s", buf);
  read_rel("g1/jobs.txt", jobs);
  read_rel("g1/Makefile", mk);
  CHECK(count_lines(jobs) == 18, "jobs.txt: %d lines", count_lines(jobs));
  for (p = jobs; sscanf(p, "%2047[^\n]", line) == 1; p += strlen(line) + 1) {
    n++;
    CHECK(strstr(mk, line) != NULL, "Makefile lacks the job line %s", line);
    CHECK(strstr(line, " --continue ") != NULL, "job not idempotent: %s",
          line);
  }
  CHECK(n == 18, "%d job lines read", n);
  read_rel("g1/slurm.sh", buf);
  CHECK(strstr(buf, "\ntasks=4\n") && strstr(buf, "per_task=5\n"),
        "slurm.sh: 18 jobs, 5 per task: want 4 tasks");
  CHECK(afv("sweep --out %s/g2 --P0 4:8.8:0.2 --seed 7,9 --N 30") == 0, "%s",
        err_text);
  read_rel("g2/points.csv", buf);
  CHECK(count_lines(buf) == 1 + 25 * 2 && strstr(buf, ",8.8,9\n")
        && strstr(buf, ",5.8,7\n") && strstr(buf, "id,P0,seed\n"),
        "points.csv of 4:8.8:0.2, seeds 7,9:\n%.300s", buf);
}

/* Every bad grid is refused before anything is written: exit status 2,
** one line on stderr naming the option, no DIR. */
static void sweep_bad_values(void)
{
  static const char *bad[] = {
    "--P0 4:x:0.2", "--P0 4:5:0", "--P0 5:4:0.5", "--P0 4:5:0.3",
    "--P0 4:5", "--v0 0.1,,0.2", "--v0 abc", "--v0 0.1,2,nan",
    "--N 0", "--N 50,0", "--bogus 1", "--box square", "--steps 1.5",
    "--seeds 0", "--seeds 2 --seed 1,2", "--P0 4 --P0 5", "--lag 0",
    "--seed -1", "--phi 0,0.5", "--P0", "--KA 1,1e300",
    /* repeated state points (issue 31): as text, as numbers, at the 10
    ** digits of a range */
    "--seed 1,1", "--seed 1,01", "--P0 4,4.0,4.00",
    "--P0 4:4.000000001:1e-10",
    /* a newline or a space in a value would split jobs.txt */
    "--P0 '\n4'", "--v0 ' 0.5'", "--v0 0.5,'1 '",
    /* an analysis the runs cannot give (issue 30): a window past the end,
    ** a lag longer than the window or shorter than a frame, no frames */
    "--steps 2000 --steady-from 1000 --lag 5000",
    "--steps 2000 --frame_every 100 --lag 50",
    "--steps 2000 --frame_every 100 --lag 0.2",
    "--steps 2000 --frame_every 100 --P0 4,8 --steps 1000,100 --steady-from 0.5",
    "--frame_every 0",
    /* SLURM resources */
    "--account 'a b'", "--mem 4X", "--time abc", "--array-max 0",
  };
  char args[256];
  int k;
  if (!have_afv()) return;
  for (k = 0; k < (int)(sizeof bad / sizeof bad[0]); k++) {
    snprintf(args, sizeof args, "sweep --out %%s/bad %s", bad[k]);
    CHECK(afv(args) == 2, "'%s': not exit 2", bad[k]);
    CHECK(count_lines(err_text) == 1 && !strncmp(err_text, "afv", 3),
          "'%s': stderr not one line: %s", bad[k], err_text);
    CHECK(!exists("bad"), "'%s': DIR created", bad[k]);
  }
  CHECK(system("ls -d /tmp/afv_sweep_test_*/bad* >/dev/null 2>&1") != 0,
        "a refused sweep left a folder");
  /* a path the runners cannot use is refused before any folder exists */
  CHECK(afv("sweep --out '%s/x y/s' --P0 4") == 2 && !exists("x y")
        && count_lines(err_text) == 1, "a path with a space: %s", err_text);
  CHECK(afv("sweep --P0 4") == 2 && strstr(err_text, "--out"),
        "no --out: %s", err_text);
  CHECK(afv("sweep --out %s/g1 --P0 4") == 2 || exists("g1"), "existing DIR");
}

/* A stand-in for sbatch in DIR/bin: records its arguments in
** bin/sbatch.log, then runs the array's tasks (0-LAST or 0-LAST%K) one
** after the other in --chdir with the environment SLURM gives them; it
** fails, submitting nothing, for the array at task offset F if the file
** bin/fail_at_F exists. */
static void fake_sbatch(void)
{
  write_rel("bin/sbatch", "#!/bin/sh\n"
            "for a in \"$@\"; do\n"
            "  case $a in\n"
            "    --chdir=*) dir=${a#--chdir=} ;;\n"
            "    --array=0-*) last=${a#--array=0-}; last=${last%%%*} ;;\n"
            "    --export=ALL,AFV_TASK_OFFSET=*) "
            "off=${a#--export=ALL,AFV_TASK_OFFSET=} ;;\n"
            "  esac\n"
            "  script=$a\n"
            "done\n"
            "if [ -f \"$(dirname \"$0\")/fail_at_$off\" ]; then exit 1; fi\n"
            "echo \"$*\" >> \"$(dirname \"$0\")/sbatch.log\"\n"
            "t=0\n"
            "while [ \"$t\" -le \"$last\" ]; do\n"
            "  (cd \"$dir\" && SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=$t "
            "AFV_TASK_OFFSET=$off sh \"$script\") || exit 1\n"
            "  t=$((t + 1))\n"
            "done\n");
  shell("chmod +x %s/bin/sbatch%.0s", base);
}

/* slurm.sh (issue 30): submitted from another directory, it splits the
** tasks into arrays of at most --array-max, passes sbatch options on,
** runs the jobs in the sweep's folder (paths relative to it) and holds
** the resources given; without --time it holds and prints an estimate.
** Then a new analysis of the finished sweep (--reanalyze): checked
** against the runs, nothing rerun, collect flags the old summaries, make
** analyses again and collect tables the new analysis. */
static void sweep_slurm_and_reanalyze(void)
{
  static char buf[TEXT_MAX], log[TEXT_MAX], runlog[TEXT_MAX];
  char cmd[512];
  if (!have_afv()) return;
  shell("mkdir -p %s/bin%.0s", base);
  fake_sbatch();
  CHECK(afv("sweep --out %s/sl --P0 4,8 --seeds 3 --N 10 --steps 20 "
            "--frame_every 10 --svg_every 0 --steady-from 0 --lag 0.1 "
            "--per-task 2 --array-max 2 --account acc --partition part "
            "--mem 500M --time 0:05:00") == 0, "%s", err_text);
  read_rel("sl/slurm.sh", buf);
  CHECK(strstr(buf, "#SBATCH --account=acc\n")
        && strstr(buf, "#SBATCH --partition=part\n")
        && strstr(buf, "#SBATCH --mem=500M\n")
        && strstr(buf, "#SBATCH --time=0:05:00\n"), "resources:\n%s", buf);
  snprintf(cmd, sizeof cmd, "cd / && PATH=%s/bin:$PATH sh %s/sl/slurm.sh "
           "--qos=test >/dev/null", base, base);
  CHECK(system(cmd) == 0, "%s failed", cmd);
  read_rel("bin/sbatch.log", log);
  CHECK(count_lines(log) == 2 && strstr(log, "--array=0-1 "
        "--export=ALL,AFV_TASK_OFFSET=0 --qos=test")
        && strstr(log, "--array=0-0 --export=ALL,AFV_TASK_OFFSET=2 "
        "--qos=test"), "6 jobs, 2 per task, arrays of 2 tasks: want arrays "
        "0-1 and 0-0 (offset 2):\n%s", log);
  CHECK(afv("collect %s/sl") == 0, "the jobs through slurm.sh: %s",
        err_text);
  read_rel("sl/runs/0006/log.txt", runlog);
  /* without --time: an estimate, printed and in slurm.sh */
  CHECK(afv("sweep --out %s/sl2 --N 400 --steps 100000") == 0, "%s",
        err_text);
  read_rel("stdout", buf);
  CHECK(strstr(buf, "--time 0:") && strstr(buf, "estimated"), "no estimate "
        "printed:\n%s", buf);
  read_rel("sl2/slurm.sh", buf);
  CHECK(strstr(buf, "--time is estimated") && strstr(buf, "400 cells x "
        "(100000 steps"), "slurm.sh without the estimate:\n%.2000s", buf);
  /* a new analysis: refused if the runs cannot give it, nothing changed */
  read_rel("sl/analysis.txt", buf);
  CHECK(afv("sweep --reanalyze %s/sl --steady-from 0.15") == 2
        && count_lines(err_text) == 1 && strstr(err_text, "--steady-from"),
        "a window of one frame: %s", err_text);
  CHECK(!strcmp(read_rel("sl/analysis.txt", log), buf), "a refused "
        "--reanalyze changed analysis.txt");
  CHECK(afv("sweep --reanalyze %s/sl --steady-from 0.1") == 0, "%s",
        err_text);
  CHECK(afv("collect %s/sl") == 1 && strstr(err_text, "analysed before "
        "analysis.txt"), "old analyses tabled after --reanalyze: %s",
        err_text);
  shell("make -s -C %s/sl >/dev/null 2>&1%.0s", base);
  CHECK(afv("collect %s/sl") == 0, "after the new analysis: %s", err_text);
  read_rel("sl/runs/0001/analysis/summary.txt", buf);
  CHECK(strstr(buf, "\nsteady_from 0.1\n") != NULL, "not the new window:\n%s",
        buf);
  CHECK(!strcmp(read_rel("sl/runs/0006/log.txt", buf), runlog),
        "the new analysis ran a simulation again");
}

/* slurm.sh's own options (issue 41): --throttle K gives every array %K
** (afv sweep --throttle the default), an --array option is refused with
** nothing submitted, and after a failed sbatch --from-array I submits the
** arrays from I on, not the ones before again.  The runners call the
** sweep's copy of afv by a relative path: the sweep, moved before it
** runs, finishes every job. */
static void sweep_slurm_throttle_and_retry(void)
{
  static char buf[TEXT_MAX], log[TEXT_MAX];
  char cmd[768];
  if (!have_afv()) return;
  shell("mkdir -p %s/bin && rm -f %s/bin/sbatch.log", base);
  fake_sbatch();
  CHECK(afv("sweep --out %s/th --P0 4,8 --seeds 2 --N 10 --steps 20 "
            "--frame_every 10 --svg_every 0 --steady-from 0 --lag 0.1 "
            "--array-max 2 --throttle 1") == 0, "%s", err_text);
  read_rel("th/jobs.txt", buf);
  CHECK(!strncmp(buf, "./afv run --config jobs/0001.conf", 33)
        && !strstr(buf, base) && strstr(read_rel("th/slurm.sh", log),
                                        "\nthrottle=1\n"),
        "jobs.txt calls another afv than ./afv, or no throttle:\n%s", buf);
  shell("mv %s/th %s/th2", base);
  snprintf(cmd, sizeof cmd, "cd / && PATH=%s/bin:$PATH sh %s/th2/slurm.sh "
           "--array=0-9%%2 >/dev/null 2>%s/slurm.err", base, base, base);
  CHECK(system(cmd) != 0 && strstr(read_rel("slurm.err", buf), "--throttle")
        && !exists("bin/sbatch.log"), "--array not refused: %s", buf);
  shell("touch %s/bin/fail_at_2%.0s", base);
  snprintf(cmd, sizeof cmd, "cd / && PATH=%s/bin:$PATH sh %s/th2/slurm.sh "
           "--throttle 2 --qos=test >/dev/null 2>%s/slurm.err", base, base,
           base);
  CHECK(system(cmd) != 0 && strstr(read_rel("slurm.err", buf),
                                   "--from-array 1"),
        "a failed second sbatch: %s", buf);
  CHECK(count_lines(read_rel("bin/sbatch.log", log)) == 1
        && strstr(log, "--array=0-1%2 --export=ALL,AFV_TASK_OFFSET=0 "
                  "--qos=test"), "first array: %s", log);
  shell("rm %s/bin/fail_at_2%.0s", base);
  snprintf(cmd, sizeof cmd, "cd / && PATH=%s/bin:$PATH sh %s/th2/slurm.sh "
           "--qos=test --from-array=1 >/dev/null 2>%s/slurm.err", base, base,
           base);
  CHECK(system(cmd) == 0, "--from-array 1: %s", read_rel("slurm.err", buf));
  read_rel("bin/sbatch.log", log);
  CHECK(count_lines(log) == 2 && strstr(log, " --array=0-1%1 "
        "--export=ALL,AFV_TASK_OFFSET=2 --qos=test"), "the retry submitted "
        "(want the second array alone, with the sweep's throttle 1):\n%s",
        log);
  CHECK(afv("collect %s/th2") == 0, "the moved sweep through slurm.sh: %s",
        err_text);
}

/* afv sweep prints the jobs' CPU time and disk before it writes (issue
** 41), counts the trajectories' exact bytes, and bounds the snapshots
** when --svg_every is not given: at most 20 intervals of a run. */
static void sweep_cost_and_snapshots(void)
{
  static char buf[TEXT_MAX];
  if (!have_afv()) return;
  CHECK(afv("sweep --out %s/cost --P0 4,8 --N 400 --steps 1000000 "
            "--frame_every 1000") == 0, "%s", err_text);
  read_rel("stdout", buf);
  /* 2 x 1001 frames of 16 + 20 x 400 bytes; 2 x (21 snapshots + final) */
  CHECK(!strncmp(buf, "afv sweep: 2 job(s): about ", 27)
        && strstr(buf, "trajectories 16 MB, 44 SVG pictures 10 MB")
        && strstr(buf, "--svg_every 0") && strstr(buf, "jobs in")
        > strstr(buf, "of disk"), "cost:\n%s", buf);
  CHECK(strstr(read_rel("cost/jobs/0001.conf", buf), "\nsvg_every        "
               "50000\n") != NULL, "snapshots not bounded:\n%s", buf);
  CHECK(afv("sweep --out %s/cost0 --N 400 --steps 1000000 --frame_every 1000 "
            "--svg_every 0") == 0 && strstr(read_rel("stdout", buf),
                                            ", 1 SVG pictures"),
        "--svg_every 0:\n%s", buf);
}

/* collect's figures (issue 41): a sweep over P0 alone draws every order
** parameter against P0; a figure with no finite value says "no data" and
** why (msd_beta of windows too short for it); an error bar is a line
** without markers (a marker per state point, not three); msd_beta's
** label is its definition. */
static void collect_figures_of_a_p0_sweep(void)
{
  static char buf[TEXT_MAX];
  if (!have_afv()) return;
  CHECK(afv("sweep --out %s/p0 --P0 4,6 --N 10 --steps 20 --frame_every 10 "
            "--svg_every 0 --seeds 2") == 0, "%s", err_text);
  shell("make -s -C %s/p0 >/dev/null 2>&1%.0s", base);
  CHECK(afv("collect %s/p0") == 0, "%s", err_text);
  read_rel("p0/figures/msd_beta_vs_P0.svg", buf);
  CHECK(strstr(buf, ">no data: msd_beta is nan at every state point")
        && strstr(buf, "msd_beta (slope of log MSD_rel vs log lag, lags "
                  "1-10% of the window)") && strstr(buf, ">P0 (l)<"),
        "msd_beta_vs_P0.svg:\n%.3000s", buf);
  read_rel("p0/figures/D_eff_vs_P0.svg", buf);
  {
    const char *c = buf;
    int circles = 0, lines = 0;
    while ((c = strstr(c, "<circle"))) circles++, c++;
    for (c = buf; (c = strstr(c, "<polyline")); c++) lines++;
    CHECK(circles == 2 && lines == 3 && !strstr(buf, "no data"),
          "D_eff against P0: %d markers (want 2: one a state point), %d "
          "lines (want the curve and 2 error bars)", circles, lines);
  }
}

/* missing.txt names a run stopped short of its steps by what stopped it
** (issue 41: a killed job was blamed on its log's last line, the
** relaxation's kink): interrupted when the log ends on afv run's own news,
** stopped with the log's error otherwise. */
static void collect_names_interrupted_jobs(void)
{
  static char buf[TEXT_MAX];
  if (!have_afv()) return;
  CHECK(afv("sweep --out %s/ki --N 10 --steps 20 --frame_every 10 "
            "--svg_every 0 --P0 4") == 0, "%s", err_text);
  shell("cd %s/ki && ./afv run --config jobs/0001.conf --out runs/0001 "
        "--steps 10 --quiet && sed -i 's/^steps .*/steps 20/' "
        "runs/0001/params.txt%.0s", base);
  write_rel("ki/logs/0001.log", "afv run: relaxation: stopped at a kink of E "
            "(a triple junction on a contact)\n");
  afv("collect %s/ki");
  CHECK(strstr(read_rel("ki/missing.txt", buf), "0001 seed=1: interrupted "
               "at step 10 of 20 (killed or out of time"),
        "an interrupted job:\n%s", buf);
  write_rel("ki/logs/0001.log", "afv run: step 12: cell 3 would move 9 l\n");
  afv("collect %s/ki");
  CHECK(strstr(read_rel("ki/missing.txt", buf), "0001 seed=1: stopped at "
               "step 10 of 20: afv run: step 12: cell 3 would move 9 l"),
        "a job stopped by an error:\n%s", buf);
}

/* A sweep of cells files: each run records its copy (cells.txt) in
** params.txt, and collect verifies it against the file the sweep names. */
static void sweep_of_cells_files(void)
{
  if (!have_afv()) return;
  write_rel("five.txt", "# x y\n1 1\n3 1\n1 3\n3 3\n5 5\n");
  write_rel("four.txt", "# x y\n1 1\n3 1\n1 3\n3 3\n");
  CHECK(afv("sweep --out %s/cf --cells %s/five.txt,%s/four.txt --box open "
            "--steps 20 --frame_every 10 --svg_every 0 --quiet 1") == 0, "%s",
        err_text);
  shell("make -s -C %s/cf >/dev/null 2>&1%.0s", base);
  CHECK(afv("collect %s/cf") == 0, "a sweep of cells files: %s", err_text);
}

/* A value longer than a sweep holds (63 bytes), given as it is or as a
** cells file whose absolute path (what the jobs name) is that long: one
** line naming the key and the limit, exit 2, no DIR.  (The code before:
** "value 1 of the list is too long" for one value, and "Invalid argument"
** for a short relative path with a long absolute one.) */
static void sweep_value_too_long(void)
{
  char name[64], cwd[512], cmd[1400];
  const char *forms[3] = {"--cells %s/%s", "--cells %s/five.txt,%s/%s",
                          "--cells %s"};
  int k;
  if (!have_afv() || !getcwd(cwd, sizeof cwd)) return;
  memset(name, 'c', 44);     /* 48 bytes; base/NAME more than 63 */
  snprintf(name + 44, sizeof name - 44, ".txt");
  write_rel(name, "# x y\n1 1\n3 1\n");
  write_rel("five.txt", "# x y\n1 1\n3 1\n1 3\n3 3\n5 5\n");
  for (k = 0; k < 3; k++) {
    char opt[256], se[128];
    int st;
    if (k == 0) snprintf(opt, sizeof opt, forms[0], base, name);
    else if (k == 1) snprintf(opt, sizeof opt, forms[1], base, base, name);
    else snprintf(opt, sizeof opt, forms[2], name);  /* relative to base */
    snprintf(se, sizeof se, "%s/stderr", base);
    snprintf(cmd, sizeof cmd, "cd %s && %s/afv sweep --out %s/long %s "
             "--steps 20 --frame_every 10 >/dev/null 2>%s", base, cwd, base,
             opt, se);
    st = system(cmd);
    slurp(se, err_text);
    CHECK(st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 2, "'%s': not "
          "exit 2", opt);
    CHECK(count_lines(err_text) == 1 && strstr(err_text, "--cells ")
          && strstr(err_text, "63 bytes"), "'%s': not one line naming "
          "--cells and the 63 bytes: %s", opt, err_text);
    CHECK(!exists("long"), "'%s': DIR created", opt);
  }
}

/* ---- collect ------------------------------------------------------------------ */
/* A finished run of 10 cells and 20 steps (3 frames) in c/template: the
** run of every fake job. */
static void template_run(void)
{
  CHECK(afv("run --out %s/c/template --N 10 --steps 20 --frame_every 10 "
            "--svg_every 0 --quiet") == 0, "template run: %s", err_text);
}

/* The fingerprint afv analyze writes into summary.txt for the run with
** params.txt at rel and the id id (cmd/run_config.c, THE FINGERPRINT),
** computed here on its own from the file's text: FNV-1a 64 over "id=ID\n"
** and "KEY=VALUE\n" for every key line but quiet, checkpoint_every and
** cells (params.txt holds the values as afv writes them), in 16 hex
** digits. */
static unsigned long long fnv1a(unsigned long long h, const char *text)
{
  for (; *text; text++) h = (h ^ (unsigned char)*text) * 0x100000001b3ull;
  return h;
}

static void fingerprint(const char *rel, const char *id, char *out)
{
  static char text[TEXT_MAX];
  char line[8192], key[64], value[4096], *p, *end;
  unsigned long long h = 0xcbf29ce484222325ull;
  read_rel(rel, text);
  snprintf(line, sizeof line, "id=%s\n", id);
  h = fnv1a(h, line);
  for (p = text; *p; p = *end ? end + 1 : end) {
    if (!(end = strchr(p, '\n'))) end = p + strlen(p);
    if (*p == '#' || sscanf(p, "%63s %4095s", key, value) != 2
        || !strcmp(key, "quiet") || !strcmp(key, "checkpoint_every")
        || !strcmp(key, "cells"))
      continue;
    snprintf(line, sizeof line, "%s=%s\n", key, value);
    h = fnv1a(h, line);
  }
  snprintf(out, 17, "%016llx", h);
}

/* Job id of sweep c: the template run with P0, v0 and seed set in its
** params.txt, its (empty) jobs/ID.conf, and a summary.txt as afv analyze
** writes it, with the values collect reads (of 3 frames, the whole run)
** and the run's id and fingerprint. */
static void fake_job(const char *id, const char *p0, const char *v0,
                     const char *seed, double ngc, double ncl, double om,
                     double deff, double tau, double t1, double beta)
{
  char rel[128], text[1024], cmd[4096], print[17];
  snprintf(cmd, sizeof cmd, "rm -rf %s/c/runs/%s && mkdir -p %s/c/runs && "
           "cp -r %s/c/template %s/c/runs/%s && mkdir -p "
           "%s/c/runs/%s/analysis && sed -i -e 's/^P0 .*/P0 %s/' -e "
           "'s/^v0 .*/v0 %s/' -e 's/^seed .*/seed %s/' %s/c/runs/%s/params.txt",
           base, id, base, base, base, id, base, id, p0, v0, seed, base, id);
  CHECK(system(cmd) == 0, "%s failed", cmd);
  snprintf(rel, sizeof rel, "c/jobs/%s.conf", id);
  write_rel(rel, "");
  snprintf(rel, sizeof rel, "c/runs/%s/params.txt", id);
  fingerprint(rel, id, print);
  snprintf(text, sizeof text, "# afv analyze: fake\ncells 10\nframes 3\n"
           "ngc_frac_mean %.17g\nngc_frac_sd 0.1\nn_clusters_mean %.17g\n"
           "omega_mean %.17g\nD_eff %.17g\ntau_NGC %.17g\nt1_rate %.17g\n"
           "msd_beta %.17g\nrun_id %s\nrun_fingerprint %s\n", ngc, ncl, om,
           deff, tau, t1, beta, id, print);
  snprintf(rel, sizeof rel, "c/runs/%s/analysis/summary.txt", id);
  write_rel(rel, text);
}

/* Field k (0-based) of the table row that starts with prefix. */
static double table_field(const char *table, const char *prefix, int k,
                          char *word)
{
  const char *row = strstr(table, prefix);
  int i;
  if (!row) return NAN;
  for (i = 0; i < k; i++) row = strchr(row, ',') + 1;
  sscanf(row, "%63[^,\n]", word);
  return atof(word);
}

/* Known summaries: means and standard errors over the seeds, the labels at
** the thresholds (0.99 exactly is clustered), a missing job named with its
** log's last line in missing.txt and on stderr, exit status 1, and the
** table still written for the finished points. */
static void collect_known_summaries(void)
{
  static char table[TEXT_MAX], miss[TEXT_MAX];
  char w[64];
  const double s2 = sqrt(2.0);
  if (!have_afv()) return;
  shell("mkdir -p %s/c/logs %s/c/jobs", base);
  shell("touch %s/c/analysis.txt%.0s", base);
  template_run();
  write_rel("c/points.csv", "id,P0,v0,seed\n0001,4,0,1\n0002,4,0,2\n"
            "0003,4,1,1\n0004,4,1,2\n0005,8,1,1\n0006,8,1,2\n");
  /* point (4, 0): v0 = 0, D_eff nan (no D_0) */
  fake_job("0001", "4", "0", "1", 1, 1, 0.6, NAN, HUGE_VAL, 0.01, 0.1);
  fake_job("0002", "4", "0", "2", 1, 1, 0.4, NAN, HUGE_VAL, 0.03, 0.3);
  /* point (4, 1): seeds 0.98 and 1.0 */
  fake_job("0003", "4", "1", "1", 0.98, 2, 0.5, 1e-9, 10, 0.2, 0.9);
  fake_job("0004", "4", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  /* point (8, 1): one seed; 0006 failed */
  fake_job("0005", "8", "1", "1", 0.5, 7, 0.1, 0.2, 5, 0.5, 0.95);
  write_rel("c/logs/0006.log", "afv run: relaxation at v0 = 0: ...\n"
            "afv run: step 12: cell 3 would move 9 l: the time step is too "
            "large\n\n");
  CHECK(afv("collect %s/c") == 1, "collect with a missing job: not exit 1 "
        "(%s)", err_text);
  CHECK(strstr(err_text, "0006") && strstr(err_text, "would move 9 l"),
        "stderr does not name the missing job: %s", err_text);
  read_rel("c/missing.txt", miss);
  CHECK(strstr(miss, "0006 P0=8 v0=1 seed=2: afv run: step 12: cell 3 would "
                "move 9 l") != NULL, "missing.txt:\n%s", miss);
  CHECK(count_lines(miss) == 2, "missing.txt has %d lines", count_lines(miss));
  read_rel("c/table.csv", table);
  CHECK(!strncmp(table, "P0,v0,n_seeds,ngc_frac_mean,ngc_frac_sem,"
                 "n_clusters_mean,n_clusters_sem,omega_mean,omega_sem,"
                 "D_eff_mean,D_eff_sem,tau_NGC_mean,tau_NGC_sem,t1_rate_mean,"
                 "t1_rate_sem,msd_beta_mean,msd_beta_sem,cluster_phase,"
                 "confluency_phase,dynamic_phase,dynamic_phase_deff\n", 250),
        "header:\n%.300s", table);
  CHECK(count_lines(table) == 4, "table.csv: %d lines", count_lines(table));
  CHECK_CLOSE(table_field(table, "\n4,1,", 2, w), 2, 0, 0, "n_seeds (4,1)");
  CHECK_CLOSE(table_field(table, "\n4,1,", 3, w), 0.99, 1e-6, 0, "ngc mean");
  /* sem of {0.98, 1}: sd 0.01 sqrt 2 over sqrt 2 = 0.01 */
  CHECK_CLOSE(table_field(table, "\n4,1,", 4, w), 0.01, 1e-5, 0, "ngc sem");
  CHECK_CLOSE(table_field(table, "\n4,1,", 9, w), 2e-9, 1e-5, 0, "D_eff mean");
  CHECK_CLOSE(table_field(table, "\n4,1,", 10, w), 1e-9, 1e-5, 0, "D_eff sem");
  CHECK_CLOSE(table_field(table, "\n4,1,", 13, w), 0.3, 1e-5, 0, "t1 mean");
  CHECK_CLOSE(table_field(table, "\n4,1,", 14, w), 0.1, 1e-5, 0, "t1 sem");
  CHECK_CLOSE(table_field(table, "\n4,0,", 7, w), 0.5, 1e-5, 0, "omega mean");
  CHECK_CLOSE(table_field(table, "\n4,0,", 8, w), 0.1, 1e-5, 0, "omega sem");
  CHECK_CLOSE(table_field(table, "\n4,0,", 16, w), 0.1 * s2 / s2, 1e-5, 0,
              "beta sem");
  CHECK(strstr(table, "\n4,0,2,") && strstr(table, ",clustered,epithelial,"
        "glassy,undefined\n"), "labels of (4, 0):\n%s", table);
  CHECK(strstr(table, ",0.99,0.01,1.5,0.5,0.5,0,2e-09,1e-09,20,10,0.3,0.1,1,"
        "0.1,clustered,epithelial,fluid,glassy\n") != NULL,
        "row (4, 1):\n%s", table);
  table_field(table, "\n4,0,", 9, w);
  CHECK(!strcmp(w, "nan"), "D_eff at v0 = 0: '%s', want nan", w);
  table_field(table, "\n4,0,", 11, w);
  CHECK(!strcmp(w, "inf"), "tau of a constant N_GC: '%s', want inf", w);
  CHECK(strstr(table, "\n8,1,1,0.5,nan,7,nan,0.1,nan,0.2,nan,5,nan,0.5,nan,"
               "0.95,nan,dispersed,mesenchymal,fluid,fluid\n") != NULL,
        "row (8, 1), one seed:\n%s", table);
  /* every job finished: exit 0 */
  fake_job("0006", "8", "1", "2", 0.7, 5, 0.1, 0.2, 5, 0.5, 0.95);
  CHECK(afv("collect %s/c") == 0, "collect of a complete sweep: %s", err_text);
  CHECK(afv("collect %s/nonexistent") == 2, "collect of no sweep: not exit 2");
}

/* collect's stderr and missing.txt name job id as damaged for reason,
** with exit status 1, and the table still holds every point, from the
** other seeds. */
static void expect_damaged(const char *what, const char *id,
                           const char *reason)
{
  static char miss[TEXT_MAX], table[TEXT_MAX];
  char want[128];
  CHECK(afv("collect %s/c") == 1, "%s: not exit 1 (%s)", what, err_text);
  snprintf(want, sizeof want, "damaged job %s: ", id);
  CHECK(strstr(err_text, want) && strstr(err_text, reason), "%s: stderr "
        "does not name job %s as damaged for '%s': %s", what, id, reason,
        err_text);
  read_rel("c/missing.txt", miss);
  snprintf(want, sizeof want, "\n%s ", id);
  CHECK(strstr(miss, want) && strstr(miss, reason), "%s: missing.txt:\n%s",
        what, miss);
  read_rel("c/table.csv", table);
  CHECK(count_lines(table) == 4 && !strstr(table, ",nan,nan,nan,nan,"),
        "%s: a point lost or NaN:\n%s", what, table);
}

/* Runs collect on sweep c with a time limit; its exit status (124: it
** hung). */
static int collect_within(int seconds)
{
  char cmd[512];
  int st;
  snprintf(cmd, sizeof cmd, "timeout %d ./afv collect %s/c >%s/stdout "
           "2>%s/stderr", seconds, base, base, base);
  st = system(cmd);
  read_rel("stderr", err_text);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* collect tables only what it verified (issue 31): an empty, truncated or
** random summary, a foreign run, a run that did not finish, an analysis
** of part of a run are each damaged (exit 1, the reason named, the point
** still tabled from its other seed); a nan value in points.csv, a
** repeated id or (point, seed), a FIFO for points.csv are refused (exit 2,
** one line), not a crash or a hang.  All of these were tabled, crashed or
** hung before. */
static void collect_verifies_jobs(void)
{
  static char table[TEXT_MAX], buf[TEXT_MAX];
  static const char *points = "id,P0,v0,seed\n0001,4,0,1\n0002,4,0,2\n"
    "0003,4,1,1\n0004,4,1,2\n0005,8,1,1\n0006,8,1,2\n";
  char w[64];
  if (!have_afv()) return;
  CHECK(afv("collect %s/c") == 0, "the complete sweep: %s", err_text);
  read_rel("c/table.csv", table);
  /* damaged summaries of 0004 */
  write_rel("c/runs/0004/analysis/summary.txt", "");
  expect_damaged("empty summary", "0004", "lacks ngc_frac_mean");
  read_rel("c/table.csv", buf);
  CHECK_CLOSE(table_field(buf, "\n4,1,", 2, w), 1, 0, 0, "n_seeds of (4, 1) "
              "with a damaged seed");
  CHECK_CLOSE(table_field(buf, "\n4,1,", 3, w), 0.98, 1e-9, 0, "ngc_frac of "
              "(4, 1): its good seed's");
  write_rel("c/runs/0004/analysis/summary.txt", "cells 10\nframes 3\n"
            "ngc_frac_mean 1\nn_clusters_mean 1\nomega_mean 0.5\nD_eff 3e-9\n"
            "tau_NGC 30\nt1_rate 0.4\n");
  expect_damaged("truncated summary", "0004", "lacks msd_beta");
  write_rel("c/runs/0004/analysis/summary.txt", "\x8f\x01\xffz\n\x13 q\n");
  expect_damaged("random summary", "0004", "is not KEY VALUE");
  write_rel("c/runs/0004/analysis/summary.txt", "cells 10\nframes 3\n"
            "ngc_frac_mean nan\nn_clusters_mean 1\nomega_mean 0.5\n"
            "D_eff 3e-9\ntau_NGC 30\nt1_rate 0.4\nmsd_beta 1\n");
  expect_damaged("nan N_GC", "0004", "ngc_frac_mean nan is not finite");
  /* a foreign run (P0 4.8) copied into runs/0004 */
  fake_job("0004", "4.8", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  expect_damaged("foreign run", "0004", "params.txt has P0 4.8, points.csv 4");
  /* a run stopped at step 20 of 40 and analysed by hand */
  fake_job("0004", "4", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  shell("sed -i 's/^steps .*/steps 40/' %s/c/runs/0004/params.txt%.0s", base);
  expect_damaged("unfinished run", "0004", "at step 20 of 40 (unfinished, "
                 "yet analysed: remove runs/0004/analysis");
  /* an analysis of 2 of its 3 frames */
  fake_job("0004", "4", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  shell("sed -i 's/^frames 3/frames 2/' %s/c/runs/0004/analysis/summary.txt"
        "%.0s", base);
  expect_damaged("partial analysis", "0004", "analysed 2 frames of the "
                 "finished run's 3");
  /* a frame count beyond a long (libFuzzer: UBSan's out-of-range cast) */
  fake_job("0004", "4", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  shell("sed -i 's/^frames 3/frames 1111111111111111111111111113/' "
        "%s/c/runs/0004/analysis/summary.txt%.0s", base);
  expect_damaged("frames beyond a long", "0004", "frames "
                 "'1111111111111111111111111113' is not a frame count");
  fake_job("0004", "4", "1", "2", 1.00, 1, 0.5, 3e-9, 30, 0.4, 1.1);
  CHECK(afv("collect %s/c") == 0 && !strcmp(read_rel("c/table.csv", buf),
        table), "the repaired sweep: not the table of before (%s)", err_text);
  /* bad points.csv: refused, one line, the table left as it was */
  write_rel("c/points.csv", "id,P0,v0,seed\n0001,nan,0.5,1\n0002,4,0.5,1\n");
  CHECK(afv("collect %s/c") == 2 && count_lines(err_text) == 1
        && strstr(err_text, "points.csv:2: P0"), "nan P0: %s", err_text);
  write_rel("c/points.csv", "id,P0,v0,seed\n0001,4,0,1\n0002,4,0,2\n"
            "0002,4,0,2\n");
  CHECK(afv("collect %s/c") == 2 && count_lines(err_text) == 1
        && strstr(err_text, "points.csv:4: id 0002 repeats line 3"),
        "repeated id: %s", err_text);
  write_rel("c/points.csv", "id,P0,v0,seed\n0001,4,0,1\n0002,4.0,0,1\n");
  CHECK(afv("collect %s/c") == 2 && count_lines(err_text) == 1
        && strstr(err_text, "repeat line 2"), "repeated point and seed: %s",
        err_text);
  CHECK(!strcmp(read_rel("c/table.csv", buf), table), "a refused collect "
        "changed table.csv");
  shell("rm %s/c/points.csv && mkfifo %s/c/points.csv", base);
  CHECK(collect_within(10) == 2 && strstr(err_text, "not a regular file"),
        "points.csv a FIFO: %s", err_text);
  shell("rm %s/c/points.csv%.0s", base);
  write_rel("c/points.csv", points);
}

/* ---- the boundary fit -------------------------------------------------------- */
/* A sweep whose jobs/ID.conf disagree on cap, cap not a column of
** points.csv: refused (exit 2, one line naming both jobs and cap), nothing
** written; with cap a column the same jobs are two state points. */
static void collect_refuses_mixed_cap(void)
{
  shell("rm -rf %s/mc && mkdir -p %s/mc/jobs", base);
  shell("touch %s/mc/analysis.txt%.0s", base);   /* afv sweep writes it */
  write_rel("mc/points.csv", "id,P0,seed\n0001,4,1\n0002,4,2\n");
  write_rel("mc/jobs/0001.conf", "P0 4\ncap 0\n");
  write_rel("mc/jobs/0002.conf", "P0 4\ncap 0.45\n");
  CHECK(afv("collect %s/mc") == 2 && strstr(err_text, "jobs/0002.conf: cap "
        "0.45, but") && strstr(err_text, "jobs/0001.conf has cap 0")
        && count_lines(err_text) == 1, "mixed cap: '%s'", err_text);
  CHECK(!exists("mc/table.csv") && !exists("mc/missing.txt")
        && !exists("mc/figures"), "mixed cap: something written");
  write_rel("mc/points.csv", "id,P0,cap,seed\n0001,4,0,1\n0002,4,0.45,1\n");
  CHECK(afv("collect %s/mc") == 1 && exists("mc/table.csv"), "cap a column: "
        "not tabled (jobs missing, exit 1): '%s'", err_text);
}

/* 25 points of v_s = 3 - 0.01 P0^2.5 over P0 in [4, 8.8] with Gaussian
** noise 0.01: the fit recovers v0*, c and alpha within twice their
** standard errors, and those are small; with 3 exact points it is exact,
** with standard errors nan. */
static void boundary_fit_recovers(void)
{
  double p0[25], vs[25];
  afv_boundary b;
  int k;
  test_rng_seed(20);
  for (k = 0; k < 25; k++) {
    p0[k] = 4 + 0.2 * k;
    vs[k] = 3 - 0.01 * pow(p0[k], 2.5) + 0.01 * test_rng_normal();
  }
  CHECK(afv_boundary_fit(25, p0, vs, &b) == AFV_OK, "fit failed");
  CHECK(fabs(b.v0star - 3) < 2 * b.se_v0star && b.se_v0star < 0.2,
        "v0* %g +- %g, want 3", b.v0star, b.se_v0star);
  CHECK(fabs(b.c - 0.01) < 2 * b.se_c && b.se_c < 0.01, "c %g +- %g, want "
        "0.01", b.c, b.se_c);
  CHECK(fabs(b.alpha - 2.5) < 2 * b.se_alpha && b.se_alpha < 0.5,
        "alpha %g +- %g, want 2.5", b.alpha, b.se_alpha);
  CHECK(b.n == 25 && b.rss > 0 && b.rss < 25 * 4e-4, "rss %g", b.rss);
  for (k = 0; k < 3; k++) {
    p0[k] = 4 + 2 * k;
    vs[k] = 2.5 - 0.3 * pow(p0[k], 0.7);
  }
  CHECK(afv_boundary_fit(3, p0, vs, &b) == AFV_OK, "3-point fit failed");
  CHECK_CLOSE(b.v0star, 2.5, 1e-6, 0, "3 points: v0*");
  CHECK_CLOSE(b.alpha, 0.7, 1e-6, 0, "3 points: alpha");
  CHECK(isnan(b.se_alpha), "3 points: standard error %g, want nan",
        b.se_alpha);
  CHECK(afv_boundary_fit(2, p0, vs, &b) == AFV_EINVAL, "2 points accepted");
}

/* The first fall below the level, interpolated; NaN points skipped. */
static void crossing_interpolates(void)
{
  const double x[5] = {0.5, 1, 1.5, 2, 2.5}, y[5] = {1, 1, NAN, 0.97, 0.5};
  const double up[3] = {0.5, 0.995, 1};
  double xc = 0;
  CHECK(afv_curve_cross(5, x, y, 0.99, &xc) == 1, "no crossing found");
  CHECK_CLOSE(xc, 1 + 1 * 0.01 / 0.03, 1e-12, 0, "crossing");
  CHECK(afv_curve_cross(3, x, up, 0.99, &xc) == 0, "a rise taken for a fall");
}

/* ---- what afv analyze computes for collect ------------------------------------- */
/* 16 cells on a 4 x 4 square lattice of spacing 1.9 (contacts along the
** rows and columns) in a 20 x 20 box; at odd frames the corner cell 0 sits
** far from all (it loses its 2 contacts, gains none): one T1 event per
** frame interval, t1_rate = 1 / (n dt). */
static void t1_rate_counts_changes(void)
{
  afv_traj tr;
  afv_analysis a;
  int f, i, n = 16;
  if (!test_traj_alloc(&tr, n, 21, test_periodic_box(20, 20))) return;
  for (f = 0; f < 21; f++) {
    double *r = tr.r + (size_t)f * 2 * n;
    tr.t[f] = 0.5 * f;
    for (i = 0; i < n; i++) {
      r[2*i] = 1.9 * (i % 4) + 1;
      r[2*i+1] = 1.9 * (i / 4) + 1;
    }
    if (f % 2) { r[0] = 15; r[1] = 15; }
  }
  CHECK(afv_analyze(&a, &tr, 1.0, 1, 0.1, 0, 1) == AFV_OK, "analyze");
  CHECK_CLOSE(a.t1[1], 1, 0, 0, "T1 at frame 1");
  CHECK_CLOSE(a.t1_rate, 1.0 * 20 / (n * 10.0), 1e-12, 0, "t1_rate");
  afv_analysis_free(&a);
  /* steady part from t = 5: frames 10 .. 20, still one event per interval */
  CHECK(afv_analyze(&a, &tr, 1.0, 1, 0.1, 5, 1) == AFV_OK, "analyze");
  CHECK_CLOSE(a.t1_rate, 1.0 * 10 / (n * 5.0), 1e-12, 0, "steady t1_rate");
  afv_analysis_free(&a);
  afv_traj_free(&tr);
}

/* msd_beta: 2 for ballistic cells, about 1 for random walkers, about 0 for
** cells jittering about fixed sites (no contacts: relative = plain MSD). */
static void msd_beta_slopes(void)
{
  enum { N = 16, F = 1000 };
  afv_traj tr;
  afv_analysis a;
  double want[3] = {2, 1, 0}, tol[3] = {1e-9, 0.15, 0.1};
  int kind, f, i;
  for (kind = 0; kind < 3; kind++) {
    if (!test_traj_alloc(&tr, N, F, test_periodic_box(400, 400))) return;
    test_rng_seed(7 + kind);
    for (f = 0; f < F; f++) {
      double *r = tr.r + (size_t)f * 2 * N, *q = r - 2 * N;
      tr.t[f] = f;
      for (i = 0; i < N; i++) {
        double sx = 100.0 * (i % 4), sy = 100.0 * (i / 4);
        if (kind == 0) { r[2*i] = sx + 0.01 * (i + 1) * f; r[2*i+1] = sy; }
        else if (kind == 1) {
          r[2*i] = f ? q[2*i] + test_rng_normal() : sx;
          r[2*i+1] = f ? q[2*i+1] + test_rng_normal() : sy;
        } else {
          r[2*i] = sx + 0.3 * test_rng_normal();
          r[2*i+1] = sy + 0.3 * test_rng_normal();
        }
      }
    }
    CHECK(afv_analyze(&a, &tr, 1.0, 1, 0.1, 0, 10) == AFV_OK, "analyze");
    CHECK(fabs(a.msd_beta - want[kind]) <= tol[kind], "kind %d: msd_beta "
          "%g, want %g", kind, a.msd_beta, want[kind]);
    afv_analysis_free(&a);
    afv_traj_free(&tr);
  }
}

/* msd_beta is the slope over lags 1% .. 10% of the window, not over all
** lags: 100 isolated cells in an Ornstein-Uhlenbeck cage of correlation
** time 300 frames (window 1999 frames), MSD ~ 1 - exp(-t/300), whose
** log-slope falls from 0.98 at t = 20 to 0.72 at t = 200 and 0.16 at
** t = 900.  Want: the slope of the exact curve at the same lags. */
static void msd_beta_window(void)
{
  enum { N = 100, F = 2000 };
  const double tau = 300, a = exp(-1 / tau), s = sqrt(1 - a * a);
  afv_traj tr;
  afv_analysis an;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, want;
  int f, i, k, m = 0;
  if (!test_traj_alloc(&tr, N, F, test_periodic_box(1000, 1000))) return;
  test_rng_seed(11);
  for (f = 0; f < F; f++) {
    double *r = tr.r + (size_t)f * 2 * N, *q = r - 2 * N;
    tr.t[f] = f;
    for (i = 0; i < N; i++) {
      double cx = 100.0 * (i % 10) + 50, cy = 100.0 * (i / 10) + 50;
      r[2*i] = cx + (f ? a * (q[2*i] - cx) + s * test_rng_normal()
                       : test_rng_normal());
      r[2*i+1] = cy + (f ? a * (q[2*i+1] - cy) + s * test_rng_normal()
                         : test_rng_normal());
    }
  }
  CHECK(afv_analyze(&an, &tr, 1.0, 1, 0.1, 0, 10) == AFV_OK, "analyze");
  for (k = 0; k < an.msd.nlags; k++) {
    double t = an.msd.dt[k], x, y;
    if (t < 0.01 * (F - 1) || t > 0.1 * (F - 1)) continue;
    x = log(t);
    y = log(1 - exp(-t / tau));
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    m++;
  }
  want = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  CHECK(m >= 3 && fabs(an.msd_beta - want) < 0.05, "msd_beta %g, want %g "
        "(%d lags)", an.msd_beta, want, m);
  afv_analysis_free(&an);
  afv_traj_free(&tr);
}

/* afv run creates the parents of --out; --continue leaves a finished run
** alone; afv analyze refuses a window or lag the run does not hold (exit
** 2, one line, no summary), writes D_eff nan at v0 = 0 and records the
** window, the lag and its origins. */
static void analyze_window_and_run_continue(void)
{
  static char buf[TEXT_MAX], before[TEXT_MAX], svg[TEXT_MAX];
  if (!have_afv()) return;
  CHECK(afv("run --out %s/a/b/r --N 30 --v0 0 --steps 400 --frame_every 50 "
            "--svg_every 0 --quiet") == 0, "run into new parents: %s",
        err_text);
  read_rel("a/b/r/trajectory.dat", before);
  CHECK(afv("run --out %s/a/b/r --N 30 --v0 0 --steps 400 --frame_every 50 "
            "--svg_every 0 --quiet --continue") == 0, "--continue: %s",
        err_text);
  CHECK(!strcmp(read_rel("a/b/r/trajectory.dat", buf), before),
        "--continue changed a finished run");
  /* a run killed after its last checkpoint, before final.svg (its last
  ** output) was in place, is finished by --continue: final.svg written,
  ** the same bytes (CI's kill test once caught a job left without it) */
  read_rel("a/b/r/final.svg", svg);
  shell("rm %s/a/b/r/final.svg", base);
  CHECK(afv("run --out %s/a/b/r --N 30 --v0 0 --steps 400 --frame_every 50 "
            "--svg_every 0 --quiet --continue") == 0, "--continue: %s",
        err_text);
  CHECK(exists("a/b/r/final.svg")
        && !strcmp(read_rel("a/b/r/final.svg", buf), svg)
        && !strcmp(read_rel("a/b/r/trajectory.dat", buf), before),
        "--continue of a run killed before final.svg: not finished alike");
  /* a run killed before its first checkpoint starts again, same bytes */
  shell("rm %s/a/b/r/checkpoint.txt", base);
  CHECK(afv("run --out %s/a/b/r --N 30 --v0 0 --steps 400 --frame_every 50 "
            "--svg_every 0 --quiet --continue") == 0, "--continue: %s",
        err_text);
  CHECK(!strcmp(read_rel("a/b/r/trajectory.dat", buf), before)
        && exists("a/b/r/checkpoint.txt"),
        "--continue of a run without checkpoint: not the same trajectory");
  /* an unfinished run (stopped at step 200 of 400: its params.txt says
  ** 400, its checkpoint 200) is resumed to the same bytes */
  CHECK(afv("run --out %s/u --N 30 --v0 0 --steps 200 --frame_every 50 "
            "--checkpoint_every 100 --svg_every 0 --quiet") == 0, "%s",
        err_text);
  shell("sed -i 's/^steps  *200$/steps 400/' %s/u/params.txt", base);
  CHECK(afv("run --out %s/u --N 30 --v0 0 --steps 400 --frame_every 50 "
            "--svg_every 0 --quiet --continue") == 0, "--continue: %s",
        err_text);
  CHECK(!strcmp(read_rel("u/trajectory.dat", buf), before),
        "--continue of an unfinished run: not the uninterrupted trajectory");
  CHECK(afv("analyze %s/a/b/r --steady-from 4.5") == 2
        && count_lines(err_text) == 1 && strstr(err_text, "--steady-from"),
        "window past the end: %s", err_text);
  CHECK(afv("analyze %s/a/b/r --steady-from 1 --lag 3.5") == 2
        && count_lines(err_text) == 1 && strstr(err_text, "--lag"),
        "lag longer than the window: %s", err_text);
  CHECK(afv("analyze %s/a/b/r --steady-from 4") == 2, "a window of one "
        "frame accepted");
  CHECK(afv("analyze %s/a/b/r --lag 0.1") == 2, "lag under a frame accepted");
  CHECK(afv("analyze %s/a/b/r --lag 200") == 2 && strstr(err_text, "--lag "
            "200: ") && strstr(err_text, " .. 4 only"), "a number is echoed "
        "as written: %s", err_text);
  CHECK(!exists("a/b/r/analysis/summary.txt"), "a refused analyze wrote");
  CHECK(afv("analyze %s/a/b/r --steady-from 1 --lag 2") == 0, "%s", err_text);
  read_rel("a/b/r/analysis/summary.txt", buf);
  CHECK(strstr(buf, "\nD_eff nan\n") != NULL, "v0 = 0: D_eff not nan:\n%s",
        buf);
  CHECK(strstr(buf, "\nsteady_from 1\n") && strstr(buf, "\nsteady_to 4\n")
        && strstr(buf, "\nsteady_frames 7\n") && strstr(buf, "\nD_s_lag 2\n")
        && strstr(buf, "\nD_s_origins 3\n") && strstr(buf, "\nt1_rate ")
        && strstr(buf, "\nmsd_beta "), "summary.txt:\n%s", buf);
  /* summary.txt is written last (a sweep's job is done when it is there):
  ** an analysis that cannot write csd.csv, or a plot, leaves none */
  shell("rm -rf %s/a/b/r/analysis && mkdir -p %s/a/b/r/analysis/csd.csv",
        base);
  CHECK(afv("analyze %s/a/b/r --steady-from 1 --lag 2") == 2
        && !exists("a/b/r/analysis/summary.txt"), "summary.txt written "
        "although csd.csv could not be");
  shell("rm -rf %s/a/b/r/analysis && mkdir -p %s/a/b/r/analysis/msd.svg",
        base);
  CHECK(afv("analyze %s/a/b/r --steady-from 1 --lag 2") == 2
        && !exists("a/b/r/analysis/summary.txt"), "summary.txt written "
        "although msd.svg could not be");
}

void suite_sweep(void)
{
  snprintf(base, sizeof base, "/tmp/afv_sweep_test_%ld", (long)getpid());
  if (mkdir(base, 0700) != 0) {
    printf("  cannot create %s\n", base);
    return;
  }
  RUN(sweep_grid_ranges_and_lists);
  RUN(sweep_bad_values);
  RUN(sweep_slurm_and_reanalyze);
  RUN(sweep_slurm_throttle_and_retry);
  RUN(sweep_cost_and_snapshots);
  RUN(collect_figures_of_a_p0_sweep);
  RUN(collect_names_interrupted_jobs);
  RUN(sweep_of_cells_files);
  RUN(sweep_value_too_long);
  RUN(collect_known_summaries);
  RUN(collect_verifies_jobs);
  RUN(collect_refuses_mixed_cap);
  RUN(boundary_fit_recovers);
  RUN(crossing_interpolates);
  RUN(t1_rate_counts_changes);
  RUN(msd_beta_slopes);
  RUN(msd_beta_window);
  RUN(analyze_window_and_run_continue);
  shell("rm -rf %s", base);
}
