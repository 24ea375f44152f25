/*
** fuzz_config.c -- libFuzzer harness of afv run's config reader
** (read_config and set_key in run_config.c, included with the other
** files of afv run here so that its static
** functions can be called; the config format belongs to the program, not
** to the library).  A refused input gets one line naming the file; an
** accepted one (with the cells key set back to none, so no other file is
** read) either fails the range checks with a message naming a key, or
** passes them, and then params.txt written from it reads back to the same
** params.txt, byte for byte.
*/
#include "../cmd/run.c"          /* afv run, all its files */
#include "../cmd/run_config.c"
#include "../cmd/run_compute.c"
#include "../cmd/run_dir.c"
#include "../cmd/run_resume.c"
#include "reader_fuzz.h"

/* params.txt of cfg in the directory of name; its contents in buf. */
static size_t params_text(const run_cfg *cfg, const char *name, char *buf,
                          size_t len)
{
  char dir[128], path[160];
  FILE *fp;
  size_t m;
  fuzz_path(name, dir, sizeof dir);
  mkdir(dir, 0700);
  REQUIRE(write_params(dir, cfg, "none") == AFV_OK);
  snprintf(path, sizeof path, "%s/params.txt", dir);
  fp = fopen(path, "rb");
  REQUIRE(fp != NULL);
  m = fread(buf, 1, len, fp);
  fclose(fp);
  REQUIRE(m < len);
  return m;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static char text1[65536], text2[65536];
  char err[2 * RUN_PATH_MAX] = "", params[160];
  int set[N_RUN_KEYS];
  run_cfg cfg, again;
  afv_cells cl;
  size_t m1, m2;
  const char *path = fuzz_input_file("config", data, size);
  memset(set, 0, sizeof set);
  memset(&cl, 0, sizeof cl);
  cfg_defaults(&cfg);
  if (!read_config(path, &cfg, set, err, sizeof err)) {
    REQUIRE(strncmp(err, path, strlen(path)) == 0 && !strchr(err, '\n'));
    return 0;
  }
  snprintf(cfg.cells, sizeof cfg.cells, "none");
  if (!cfg_validate(&cfg, set, &cl, err, sizeof err)) {
    REQUIRE(err[0] && !strchr(err, '\n'));
    afv_cells_free(&cl);
    return 0;
  }
  m1 = params_text(&cfg, "a", text1, sizeof text1);
  cfg_defaults(&again);
  memset(set, 0, sizeof set);
  REQUIRE(read_config(fuzz_path("a/params.txt", params, sizeof params),
                      &again, set, err, sizeof err));
  m2 = params_text(&again, "b", text2, sizeof text2);
  REQUIRE(m1 == m2 && memcmp(text1, text2, m1) == 0);
  return 0;
}
