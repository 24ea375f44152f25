/*
** fuzz_collect.c -- libFuzzer harness of afv collect's inputs: the input,
** cut at its first NUL byte, is a sweep's points.csv and the summary.txt
** of its job 0001, whose run (params.txt N 1, P0 4, v0 0.5, seed 1, 20
** steps with a frame every 10; a checkpoint at step 20; final.svg; its
** jobs/0001.conf and the sweep's analysis.txt) is made once (its
** fingerprint, which a verified summary names: 938c2ab71e841c38).
** collect (collect.c and collect_figures.c, included with the files of afv run for run_key_check) must exit 0,
** 1 or 2; on 2 it wrote no table; on 0 or 1 its table has the header of
** afv collect and no state point without a verified job, and exit 0
** means every job of points.csv was verified (missing.txt lists none).
*/
#include "../cmd/run.c"          /* afv run, all its files */
#include "../cmd/run_config.c"
#include "../cmd/run_compute.c"
#include "../cmd/run_dir.c"
#include "../cmd/run_resume.c"
#include "../cmd/collect.c"
#include "../cmd/collect_figures.c"
#include "../cmd/figure.c"
#include "reader_fuzz.h"

#include <fcntl.h>

const char *program_name = "afv";

static char sweep[128];

/* The sweep folder with the finished run of job 0001 (once). */
static void make_sweep(void)
{
  char path[256];
  run_cfg cfg;
  afv_checkpoint ck;
  double r[2] = {1, 1}, theta = 0;
  FILE *fp;
  fuzz_path("sweep", sweep, sizeof sweep);
  snprintf(path, sizeof path, "mkdir -p %s/runs/0001/analysis %s/logs "
           "%s/jobs && echo 'P0 4' > %s/jobs/0001.conf && touch "
           "%s/analysis.txt", sweep, sweep, sweep, sweep, sweep);
  REQUIRE(system(path) == 0);
  cfg_defaults(&cfg);
  cfg.N = 1;   /* the checkpoint's */
  cfg.P0 = 4;
  cfg.v0 = 0.5;
  cfg.seed = 1;
  cfg.steps = 20;
  cfg.frame_every = 10;
  snprintf(path, sizeof path, "%s/runs/0001", sweep);
  REQUIRE(write_params(path, &cfg, "none") == AFV_OK);
  memset(&ck, 0, sizeof ck);
  ck.n = 1;
  ck.step = 20;
  ck.t = 0.2;
  ck.seed = 1;
  ck.r = r;
  ck.theta = &theta;
  snprintf(path, sizeof path, "%s/runs/0001/checkpoint.txt", sweep);
  REQUIRE(afv_checkpoint_write(path, &ck) == AFV_OK);
  snprintf(path, sizeof path, "%s/runs/0001/final.svg", sweep);
  REQUIRE((fp = fopen(path, "w")) != NULL && fclose(fp) == 0);
}

/* Writes n bytes of data to DIR/rel. */
static void put(const char *rel, const uint8_t *data, size_t n)
{
  char path[256];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", sweep, rel);
  REQUIRE((fp = fopen(path, "wb")) != NULL);
  REQUIRE(n == 0 || fwrite(data, 1, n, fp) == n);
  REQUIRE(fclose(fp) == 0);
}

/* afv collect DIR with its stdout silenced (stderr stays: a sanitizer
** reports there); its exit status. */
static int collect_quietly(void)
{
  char *argv[] = {"collect", sweep, NULL};
  int out = dup(1), null = open("/dev/null", O_WRONLY), st;
  REQUIRE(out >= 0 && null >= 0);
  fflush(stdout);
  dup2(null, 1);
  st = cmd_collect(2, argv);
  fflush(stdout);
  dup2(out, 1);
  close(out);
  close(null);
  return st;
}

/* Every row of the table (after the header) has n_seeds >= 1: a tabled
** state point has a verified job. */
static int rows_have_seeds(const char *table)
{
  const char *head_end = strchr(table, '\n'), *row, *p;
  int col = 0, k;
  for (p = table; p < strstr(table, "n_seeds"); p++) col += *p == ',';
  for (row = head_end + 1; *row; row = strchr(row, '\n') + 1) {
    for (p = row, k = 0; k < col; k++) p = strchr(p, ',') + 1;
    if (atoi(p) < 1) return 0;
  }
  return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static char text[1 << 16];
  const uint8_t *cut = memchr(data, 0, size);
  size_t m = cut ? (size_t)(cut - data) : size, k;
  char path[256];
  FILE *fp;
  int st;
  if (!sweep[0]) make_sweep();
  put("points.csv", data, m);
  put("runs/0001/analysis/summary.txt", cut ? cut + 1 : data + m,
      cut ? size - m - 1 : 0);
  snprintf(path, sizeof path, "%s/table.csv", sweep);
  remove(path);
  st = collect_quietly();
  REQUIRE(st == 0 || st == 1 || st == 2);
  fp = fopen(path, "r");
  REQUIRE((st == 2) == (fp == NULL));
  if (!fp) return 0;
  k = fread(text, 1, sizeof text - 1, fp);
  text[k] = 0;
  fclose(fp);
  REQUIRE(strstr(text, "n_seeds,ngc_frac_mean,") != NULL
          && strstr(text, ",dynamic_phase_deff\n") != NULL);
  REQUIRE(rows_have_seeds(text));
  if (st == 0) {
    snprintf(path, sizeof path, "%s/missing.txt", sweep);
    REQUIRE((fp = fopen(path, "r")) != NULL);
    k = fread(text, 1, sizeof text - 1, fp);
    text[k] = 0;
    fclose(fp);
    REQUIRE(strchr(text, '\n') == text + strlen(text) - 1);  /* header only */
  }
  return 0;
}
