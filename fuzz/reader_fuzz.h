/*
** reader_fuzz.h -- what the reader harnesses (fuzz/fuzz_NAME.c) share.
**
** The readers take a path, so each input is written to a file first (in
** /dev/shm when there is one: memory, not disk) and read from there, as a
** user's file is.  REQUIRE states a property of what a reader accepted;
** a failed one aborts, which libFuzzer reports as a crash with its input.
*/
#ifndef AFV_READER_FUZZ_H
#define AFV_READER_FUZZ_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "require.h"   /* REQUIRE(cond) */
#include "afv_tool.h"  /* afv_lines, AFV_CELLS_MAX, checkpoints */

static char fuzz_dir[64];

static void fuzz_remove_dir(void)
{
  char cmd[96];
  snprintf(cmd, sizeof cmd, "rm -rf %s", fuzz_dir);
  if (system(cmd) != 0) fprintf(stderr, "cannot remove %s\n", fuzz_dir);
}

/* A directory of this process's own (made on the first call): path of
** name in it. */
static const char *fuzz_path(const char *name, char *buf, size_t len)
{
  if (!fuzz_dir[0]) {
    struct stat sb;
    const char *base = stat("/dev/shm", &sb) == 0 && S_ISDIR(sb.st_mode)
                       ? "/dev/shm" : "/tmp";
    snprintf(fuzz_dir, sizeof fuzz_dir, "%s/afv_fuzz_%ld", base,
             (long)getpid());
    if (mkdir(fuzz_dir, 0700) != 0 && access(fuzz_dir, W_OK) != 0) abort();
    atexit(fuzz_remove_dir);
  }
  snprintf(buf, len, "%s/%s", fuzz_dir, name);
  return buf;
}

/* Writes the input to the file `name` of the process's directory. */
static const char *fuzz_input_file(const char *name, const uint8_t *data,
                                   size_t size)
{
  static char path[128];
  FILE *fp = fopen(fuzz_path(name, path, sizeof path), "wb");
  if (!fp) abort();
  if (size && fwrite(data, 1, size, fp) != size) abort();
  if (fclose(fp) != 0) abort();
  return path;
}

/* 1 if a and b hold the same n doubles, bit for bit. */
static inline int fuzz_same(const double *a, const double *b, size_t n)
{
  return n == 0 || memcmp(a, b, n * sizeof *a) == 0;
}

#endif
