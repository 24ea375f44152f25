/*
** sweep_slurm.c -- afv sweep: what its jobs cost (CPU time, disk, memory),
** printed before anything is written, and the SLURM runner slurm.sh that
** submits them as job arrays with resources from those estimates.
*/
#define _XOPEN_SOURCE 700
#include "sweep.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- SLURM ------------------------------------------------------------------ */
/* Cost of one cell-step of afv run on one core, and of the relaxation
** before it in steps, both measured with afv run --N 400 (cluster start)
** on the 2-core development machine under load: 0.35 us per cell-step
** (5000 -> 20000 steps: +2.1 s of CPU), relaxation 5 s (about 15000
** steps).  The estimate of --time is three times the cost of a task's
** jobs plus 10 minutes: slower cores, the analysis, start-up. */
#define CELL_STEP_SECONDS 0.35e-6
#define RELAX_STEPS 15000.0
#define TIME_FACTOR 3.0
#define TIME_EXTRA_SECONDS 600.0

/* --time for one array task from its jobs' cost (whole minutes, H:MM:00
** or D-HH:MM:00); the estimate in seconds. */
double estimate_time(const sweep_grid *g, const sweep_opts *o,
                     char *text, size_t len)
{
  double job = CELL_STEP_SECONDS * g->max_cells * (g->max_steps + RELAX_STEPS);
  double sec = TIME_FACTOR * job * (double)o->per_task + TIME_EXTRA_SECONDS;
  long min = (long)ceil(sec / 60), d = min / 1440;
  if (d > 365) min = 365 * 1440, d = 365;
  if (d) snprintf(text, len, "%ld-%02ld:%02ld:00", d, min % 1440 / 60, min % 60);
  else snprintf(text, len, "%ld:%02ld:00", min / 60, min % 60);
  return sec;
}

/* Memory of one job: afv run's peak resident size, measured (afv 0.4.0)
** 4.4 MB at N = 400 and 40.6 MB at N = 6400, is about 2 MB plus 6 KB a
** cell; afv analyze holds at most 16 MB of frames more
** (AFV_ANALYSIS_RING_BYTES).  The estimate of --mem is MEM_FACTOR times
** that for the largest N, at least MEM_MIN_MB, in MB. */
#define MEM_BASE_BYTES (2e6 + 16.0 * 1048576)
#define MEM_BYTES_PER_CELL 6e3
#define MEM_FACTOR 2.0
#define MEM_MIN_MB 256

long estimate_mem_mb(const sweep_grid *g)
{
  double bytes = MEM_FACTOR * (MEM_BASE_BYTES + MEM_BYTES_PER_CELL
                               * g->max_cells);
  long mb = (long)ceil(bytes / 1048576);
  return mb < MEM_MIN_MB ? MEM_MIN_MB : mb;
}

/* slurm.sh's header: what it submits and how to call it. */
static void slurm_header(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                         long tasks, long arrays)
{
  fprintf(fp, "#!/bin/sh\n"
          "# afv sweep on SLURM: %ld jobs (jobs.txt), %ld per array task, "
          "%ld tasks\n# in %ld job array(s) of at most %ld tasks (afv sweep "
          "--per-task, --array-max).\n#\n"
          "# Submit from any directory (a login node of the cluster that "
          "shares this\n# folder):\n"
          "#   sh PATH/TO/SWEEP/slurm.sh [--throttle K] [--from-array I] "
          "[SBATCH OPTIONS]\n"
          "# submits the arrays with sbatch --chdir set to this folder "
          "(every path of\n# a job is relative to it, the program too: "
          "./afv) and passes SBATCH\n# OPTIONS on to each sbatch, where "
          "they win over the #SBATCH lines below\n# (e.g. --qos=short).  "
          "--throttle K: at most K tasks of each array run at\n# once "
          "(--array=0-N%%K; afv sweep --throttle sets the default, "
          "now %ld,\n# 0 = no limit).  The arrays are slurm.sh's: an "
          "--array option is refused.\n# If an sbatch fails, the arrays "
          "before it stay submitted, and slurm.sh\n# says how to submit "
          "the rest alone: --from-array I starts at array I\n# (0 is the "
          "first).  Task T of the array that starts at task F runs lines\n"
          "# (F+T)*%ld+1 .. (F+T+1)*%ld of jobs.txt, one after the other.  "
          "Every job is\n# idempotent: submit again (or use make or "
          "parallel) to finish what a crash,\n# a time limit or a scancel "
          "left.\n#\n"
          "# Resources per array task (one core, one job at a time): afv "
          "sweep --time,\n# --mem, --account and --partition set them.  "
          "--time is %s\n",
          g->njobs, o->per_task, tasks, arrays, o->array_max, o->throttle,
          o->per_task, o->per_task, o->time ? "as given." : "estimated:");
  if (!o->time)
    fprintf(fp, "# 3 x (%.3g cells x (%.0f steps + %.0f of relaxation) x "
            "%.2g s per cell-step\n# x %ld job(s)) + 10 min.\n",
            g->max_cells, g->max_steps, RELAX_STEPS, CELL_STEP_SECONDS,
            o->per_task);
  fprintf(fp, "# --mem is %s\n", o->mem ? "as given." : "estimated: twice "
          "a job's peak memory at the largest N (at\n# least 256M).");
  if (!o->account || !o->partition)
    fprintf(fp, "# No --account or --partition line: the cluster's defaults "
            "(give afv sweep\n# --account A --partition P, or pass them to "
            "slurm.sh, where yours requires\n# them).\n");
}

/* slurm.sh's submitter (run without SLURM_JOB_ID): its own options, then
** one sbatch per array, each told where its tasks start. */
static void slurm_submitter(FILE *fp)
{
  fputs("if [ -z \"${SLURM_JOB_ID:-}\" ]; then\n"
        "  # the submitter: one sbatch per array of at most array_max tasks\n"
        "  dir=$(cd \"$(dirname \"$0\")\" && pwd) || exit 2\n"
        "  arrays=$(((tasks + array_max - 1) / array_max))\n"
        "  from=0\n"
        "  left=$#\n"
        "  while [ \"$left\" -gt 0 ]; do   # ours out, the others kept in order\n"
        "    a=$1; shift; left=$((left - 1))\n"
        "    case $a in\n"
        "      --throttle|--from-array)\n"
        "        if [ \"$left\" -eq 0 ]; then\n"
        "          echo \"slurm.sh: $a needs a value\" >&2; exit 2\n"
        "        fi\n"
        "        v=$1; shift; left=$((left - 1)) ;;\n"
        "      --throttle=*|--from-array=*) v=${a#*=}; a=${a%%=*} ;;\n"
        "      --array|--array=*|-a|-a?*)\n"
        "        echo \"slurm.sh: $a: the job arrays are slurm.sh's ($tasks \"\\\n"
        "          \"tasks in $arrays array(s)); --throttle K runs at most K \"\\\n"
        "          \"tasks of each at once\" >&2\n"
        "        exit 2 ;;\n"
        "      *) set -- \"$@\" \"$a\"; continue ;;\n"
        "    esac\n"
        "    case $v in\n"
        "      ''|*[!0-9]*) echo \"slurm.sh: $a '$v': expected a whole \"\\\n"
        "        \"number\" >&2; exit 2 ;;\n"
        "    esac\n"
        "    if [ \"$a\" = --throttle ]; then throttle=$v; else from=$v; fi\n"
        "  done\n"
        "  if [ \"$from\" -ge \"$arrays\" ]; then\n"
        "    echo \"slurm.sh: --from-array $from: there are $arrays array(s), \"\\\n"
        "      \"0 .. $((arrays - 1))\" >&2\n"
        "    exit 2\n"
        "  fi\n"
        "  k=0\n"
        "  first=0\n"
        "  while [ \"$first\" -lt \"$tasks\" ]; do\n"
        "    n=$((tasks - first))\n"
        "    if [ \"$n\" -gt \"$array_max\" ]; then n=$array_max; fi\n"
        "    spec=0-$((n - 1))\n"
        "    if [ \"$throttle\" -gt 0 ]; then spec=$spec%$throttle; fi\n"
        "    if [ \"$k\" -ge \"$from\" ] && ! sbatch --chdir=\"$dir\" \\\n"
        "        --array=\"$spec\" --export=ALL,AFV_TASK_OFFSET=\"$first\" \\\n"
        "        \"$@\" \"$dir/slurm.sh\"; then\n"
        "      echo \"slurm.sh: array $k of 0 .. $((arrays - 1)) was not \"\\\n"
        "        \"submitted (sbatch failed); arrays $from .. $((k - 1)) were. \"\\\n"
        "        \"Once the cause is fixed, submit the rest alone: sh \"\\\n"
        "        \"$dir/slurm.sh --from-array $k [the same options]\" >&2\n"
        "      exit 1\n"
        "    fi\n"
        "    first=$((first + n))\n"
        "    k=$((k + 1))\n"
        "  done\n"
        "  exit 0\n"
        "fi\n", fp);
}

void write_slurm(FILE *fp, const sweep_grid *g, const sweep_opts *o,
                 const char *afv)
{
  long tasks = (g->njobs + o->per_task - 1) / o->per_task;
  long arrays = (tasks + o->array_max - 1) / o->array_max;
  char est[32];
  (void)afv;
  estimate_time(g, o, est, sizeof est);
  slurm_header(fp, g, o, tasks, arrays);
  fprintf(fp, "#SBATCH --job-name=afv-sweep\n#SBATCH --ntasks=1\n"
          "#SBATCH --cpus-per-task=1\n#SBATCH --time=%s\n",
          o->time ? o->time : est);
  if (o->mem) fprintf(fp, "#SBATCH --mem=%s\n", o->mem);
  else fprintf(fp, "#SBATCH --mem=%ldM\n", estimate_mem_mb(g));
  if (o->account) fprintf(fp, "#SBATCH --account=%s\n", o->account);
  if (o->partition) fprintf(fp, "#SBATCH --partition=%s\n", o->partition);
  fprintf(fp, "#SBATCH --output=logs/slurm-%%A_%%a.out\n"
          "set -u\n"
          "tasks=%ld\nper_task=%ld\narray_max=%ld\nthrottle=%ld\n",
          tasks, o->per_task, o->array_max, o->throttle);
  slurm_submitter(fp);
  fputs("if [ -z \"${SLURM_ARRAY_TASK_ID:-}\" ] || [ ! -f jobs.txt ]; then\n"
        "  echo \"slurm.sh: submit it with sh PATH/TO/SWEEP/slurm.sh (not "
        "sbatch): it submits the job arrays\" >&2\n"
        "  exit 2\n"
        "fi\n"
        "task=$((${AFV_TASK_OFFSET:-0} + SLURM_ARRAY_TASK_ID))\n"
        "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}\n"
        "status=0\n"
        "line=$((task * per_task + 1))\n"
        "last=$((line + per_task - 1))\n"
        "while [ \"$line\" -le \"$last\" ]; do\n"
        "  job=$(sed -n \"${line}p\" jobs.txt)\n"
        "  if [ -n \"$job\" ]; then sh -c \"$job\" || status=1; fi\n"
        "  line=$((line + 1))\n"
        "done\n"
        "exit $status\n", fp);
}

/* ---- cost: CPU time and disk, printed before anything is written -------- */
/* Bytes of afv run's outputs, measured (afv 0.4.0, N = 400 and 6400): an
** SVG picture (a snapshot or final.svg) 520 - 565 bytes a cell; a
** trajectory frame 16 + 20 N bytes (io.c, TRAJECTORY); checkpoint.txt
** and t1_reference.txt together about 90 bytes a cell; a row of
** observables.csv about 150 bytes; analysis/ about 20 KB and 25 bytes a
** frame. */
#define SVG_BYTES_PER_CELL 570.0
#define FRAME_HEAD_BYTES 16.0
#define FRAME_BYTES_PER_CELL 20.0
#define STATE_BYTES_PER_CELL 90.0
#define SAMPLE_BYTES 150.0
#define ANALYSIS_BYTES 20e3
#define ANALYSIS_BYTES_PER_FRAME 25.0

/* afv run's value of key for job j: the sweep's, else afv run's default. */
static double job_key(const sweep_grid *g, long j, const char *key)
{
  double def = 0;
  whole_double(run_key_default(key), &def);
  return job_number(g, j, key, def);
}

/* Outputs at steps 0, every, 2 every, ... <= steps (none if every is 0). */
static double count_every(double steps, double every)
{
  return every > 0 ? floor(steps / every) + 1 : 0;
}

/* The cost of every job of g (a cells file's N counts as --N's). */
void sweep_cost_of(const sweep_grid *g, sweep_cost *c)
{
  long j;
  memset(c, 0, sizeof *c);
  for (j = 0; j < g->njobs; j++) {
    double n = job_key(g, j, "N"), steps = job_key(g, j, "steps");
    double frames = count_every(steps, job_key(g, j, "frame_every"));
    double pictures = count_every(steps, job_key(g, j, "svg_every")) + 1;
    double job = CELL_STEP_SECONDS * n * (steps + RELAX_STEPS);
    c->cpu += job;
    if (job > c->cpu_max) c->cpu_max = job;
    c->trajectory += frames * (FRAME_HEAD_BYTES + FRAME_BYTES_PER_CELL * n);
    c->pictures += pictures * SVG_BYTES_PER_CELL * n;
    c->npictures += pictures;
    c->rest += STATE_BYTES_PER_CELL * n + ANALYSIS_BYTES
               + SAMPLE_BYTES * count_every(steps, job_key(g, j,
                                                           "sample_every"))
               + ANALYSIS_BYTES_PER_FRAME * frames;
  }
}

/* A CPU time as "40 s", "12 min" or "3.5 h". */
static const char *cpu_text(double sec, char *buf, size_t len)
{
  if (sec < 120) snprintf(buf, len, "%.0f s", sec);
  else if (sec < 7200) snprintf(buf, len, "%.0f min", sec / 60);
  else snprintf(buf, len, "%.3g h", sec / 3600);
  return buf;
}

/* A size as "512 KB", "1.2 GB", ... (powers of 1000). */
static const char *bytes_text(double b, char *buf, size_t len)
{
  static const char *unit[] = {"B", "KB", "MB", "GB", "TB", "PB"};
  int k = 0;
  while (b >= 1000 && k < 5) b /= 1000, k++;
  snprintf(buf, len, k ? "%.3g %s" : "%.0f %s", b, unit[k]);
  return buf;
}

void print_cost(const sweep_cost *c, long njobs)
{
  char t[4][32], b[4][32];
  printf("afv sweep: %ld job(s): about %s of CPU in all (%s for the longest "
         "job, on one core) and %s of disk: trajectories %s, %.0f SVG "
         "pictures %s, the rest %s.\n  Fewer --steps, --N or --seeds, a "
         "larger --frame_every and --svg_every 0 cut them (afv sweep --help, "
         "\"Cost\").\n", njobs, cpu_text(c->cpu, t[0], sizeof t[0]),
         cpu_text(c->cpu_max, t[1], sizeof t[1]),
         bytes_text(c->trajectory + c->pictures + c->rest, b[0], sizeof b[0]),
         bytes_text(c->trajectory, b[1], sizeof b[1]), c->npictures,
         bytes_text(c->pictures, b[2], sizeof b[2]),
         bytes_text(c->rest, b[3], sizeof b[3]));
  fflush(stdout);
}

/* Without --svg_every: a fixed svg_every of max(afv run's default, the
** largest steps / SWEEP_SNAPSHOTS), as a key the sweep gives every job
** (o->ax; the seed axis stays last in the grid).  0 if out of memory. */
int bound_snapshots(sweep_opts *o)
{
  double def = 5000, steps = 0, every;
  sweep_axis *x;
  int k, v;
  for (k = 0; k < o->nax; k++) {
    if (!strcmp(o->ax[k].key, "svg_every")) return 1;
    for (v = 0; !strcmp(o->ax[k].key, "steps") && v < o->ax[k].n; v++) {
      double s;
      if (whole_double(o->ax[k].value[v], &s) && s > steps) steps = s;
    }
  }
  if (o->nax == SWEEP_MAX_KEYS) return 1;    /* no room: run's default */
  whole_double(run_key_default("svg_every"), &def);
  if (steps == 0) whole_double(run_key_default("steps"), &steps);
  every = fmax(def, ceil(steps / SWEEP_SNAPSHOTS));
  x = &o->ax[o->nax];
  if (!(x->value = malloc(sizeof *x->value))) return 0;
  x->key = "svg_every";
  x->text = "(afv sweep: at most " AFV_STR(SWEEP_SNAPSHOTS) " snapshots)";
  x->n = 1;
  snprintf(x->value[0], VALUE_MAX, "%.0f", every);
  o->nax++;
  return 1;
}

