/*
** test_readers.c -- every reader (POINTS, config, CELLS, checkpoint,
** trajectory, T1 reference) against damaged input: each field parsed
** whole and range-checked, counts that cannot overflow, no line split,
** directories and pipes refused, a NUL byte named as one.  Library readers
** are called directly; the config file and the T1 reference through
** ./afv run, as a user meets them.  Each bad input must give one message
** naming the file and line, and (through afv) exit status 2.
**
** Files go to a fresh directory under /tmp, removed at the end.
*/
#define _POSIX_C_SOURCE 200809L  /* mkdtemp, mkfifo */
#include "test.h"
#include "afv.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64];          /* the suite's temporary directory */
static char msg[4096];        /* a reader's message */

/* dir/name in a static buffer (two alternating, for two names in a call). */
static const char *at(const char *name)
{
  static char buf[2][512];
  static int k;
  k = !k;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

/* Writes len bytes (NUL bytes included) to dir/name. */
static void put(const char *name, const char *bytes, size_t len)
{
  FILE *fp = fopen(at(name), "wb");
  CHECK(fp != NULL, "cannot write %s", name);
  if (!fp) return;
  fwrite(bytes, 1, len, fp);
  fclose(fp);
}

static void put_text(const char *name, const char *text)
{
  put(name, text, strlen(text));
}

/* A malloc'd string: head, then `pad` copies of c, then tail. */
static char *padded(const char *head, int pad, char c, const char *tail)
{
  size_t h = strlen(head), t = strlen(tail);
  char *s = malloc(h + (size_t)pad + t + 1);
  if (!s) return NULL;
  memcpy(s, head, h);
  memset(s + h, c, (size_t)pad);
  memcpy(s + h + (size_t)pad, tail, t + 1);
  return s;
}

/* Runs a shell command (printf-style; output to dir/out, dir/err); returns
** the exit status, -1 if it did not exit. */
static int sh(const char *fmt, ...)
{
  char cmd[8192];
  va_list ap;
  int st, m;
  va_start(ap, fmt);
  m = vsnprintf(cmd, sizeof cmd, fmt, ap);
  va_end(ap);
  if (m < 0 || (size_t)m >= sizeof cmd - 80) return -1;
  snprintf(cmd + m, sizeof cmd - (size_t)m, " >%s/out 2>%s/err", dir, dir);
  st = system(cmd);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Contents of dir/name (NUL-ended; at most sizeof msg - 1 bytes). */
static const char *slurp(const char *name, char *buf, size_t len)
{
  FILE *fp = fopen(at(name), "rb");
  size_t k = 0;
  if (fp) {
    k = fread(buf, 1, len - 1, fp);
    fclose(fp);
  }
  buf[k] = 0;
  return buf;
}

/* stderr of the last sh(): exactly one line holding want1 and want2. */
static int one_line_with(const char *want1, const char *want2)
{
  const char *e = slurp("err", msg, sizeof msg);
  const char *nl = strchr(e, '\n');
  return nl && nl[1] == 0 && strstr(e, want1) && (!want2 || strstr(e, want2));
}

/* The message of the last library call holds every given piece. */
static int says(const char *a, const char *b, const char *c)
{
  return strstr(msg, a) && (!b || strstr(msg, b)) && (!c || strstr(msg, c));
}

/* ---- POINTS --------------------------------------------------------------- */
static int read_points(const char *name, int *n)
{
  double *r = NULL;
  int st;
  msg[0] = 0;
  st = afv_points_read(at(name), n, &r, msg, sizeof msg);
  free(r);
  return st;
}

/* A NUL byte is named as one (it was "line longer than 4094 characters"). */
static void test_points_nul_byte_named(void)
{
  int n;
  put("nul.xy", "0 0\n1\0 2\n", 9);
  CHECK(read_points("nul.xy", &n) == AFV_EFORMAT
        && says("nul.xy:2:", "NUL byte", NULL), "message: %s", msg);
}

/* A line longer than the old 4096-byte buffer is read whole (this one
** spans three of afv_lines' blocks). */
static void test_points_long_line_read_whole(void)
{
  char *line = padded("0 0\n1", 20000, ' ', "2\n5 5\n");
  int n = 0, st;
  if (line) put_text("long.xy", line);
  st = read_points("long.xy", &n);
  CHECK(st == AFV_OK && n == 3, "status %d, %d points: %s", st, n, msg);
  free(line);
}

/* A directory is refused with its kind (it was "read error"); so is a
** pipe, without waiting for a writer (it hung in fopen). */
static void test_points_directory_and_pipe_refused(void)
{
  int n;
  mkdir(at("sub"), 0777);
  CHECK(read_points("sub", &n) == AFV_EIO && says("sub: ", "directory", NULL),
        "message: %s", msg);
  CHECK(mkfifo(at("fifo"), 0600) == 0, "mkfifo");
  CHECK(sh("timeout 10 ./afv eval %s", at("fifo")) == 2
        && one_line_with("fifo", "pipe"), "afv eval FIFO: %s", msg);
  /* afv draw first looks whether the file is a trajectory */
  CHECK(sh("timeout 10 ./afv draw %s", at("fifo")) == 2
        && one_line_with("fifo", "pipe"), "afv draw FIFO: %s", msg);
}

/* ---- CELLS ---------------------------------------------------------------- */
static int read_cells(const char *name, afv_cells *c)
{
  msg[0] = 0;
  return afv_cells_read(at(name), c, msg, sizeof msg);
}

/* One row longer than the old 4096-byte buffer: it used to become two
** cells, silently. */
static void test_cells_long_row_not_split(void)
{
  /* "0 0" then spaces up to byte 4095 of the row, then "3 3" */
  char *row = padded("# x y\n0 0", 4092, ' ', "3 3\n");
  char *ok = padded("# x y\n0", 6000, ' ', "0\n");
  afv_cells c;
  int st;
  if (row) put_text("split.cells", row);
  st = read_cells("split.cells", &c);
  CHECK(st == AFV_EFORMAT && says("split.cells:2:", "expected 2 columns",
        "found 4"), "status %d, %d cells, message: %s", st, c.n, msg);
  afv_cells_free(&c);
  if (ok) put_text("long.cells", ok);
  st = read_cells("long.cells", &c);
  CHECK(st == AFV_OK && c.n == 1, "a long row: status %d, %s", st, msg);
  afv_cells_free(&c);
  free(row);
  free(ok);
}

static void test_cells_nul_and_directory(void)
{
  afv_cells c;
  put("nul.cells", "# v0\n1\n\0\n", 10);
  CHECK(read_cells("nul.cells", &c) == AFV_EFORMAT
        && says("nul.cells:3:", "NUL byte", NULL), "message: %s", msg);
  afv_cells_free(&c);
  CHECK(read_cells("sub", &c) == AFV_EIO && says("sub: ", "directory", NULL),
        "message: %s", msg);
  afv_cells_free(&c);
}

/* ---- checkpoints ---------------------------------------------------------- */
/* A valid checkpoint of 2 cells with line `line` (1-based) replaced. */
static void put_checkpoint(const char *name, int line, const char *text)
{
  static const char *const good[] = {
    "# afv checkpoint 1", "cells 2", "step 1500", "time 0x1.ep+3",
    "seed 7", "bytes trajectory.dat 100", "bytes observables.csv 50",
    "bytes trajectory.xyz 0", "0x1p+0 0x0p+0 0x1.8p+1",
    "-0x1p-2 0x1.4p+1 0x0p+0", "end"};
  char buf[2048] = "";
  size_t k, m = 0;
  for (k = 0; k < sizeof good / sizeof good[0]; k++)
    m += (size_t)snprintf(buf + m, sizeof buf - m, "%s\n",
                          (int)k + 1 == line ? text : good[k]);
  put_text(name, buf);
}

static int read_checkpoint(const char *name, afv_checkpoint *c)
{
  int st;
  msg[0] = 0;
  st = afv_checkpoint_read(at(name), c, msg, sizeof msg);
  return st;
}

/* Each field parsed whole and range-checked: "FILE:LINE: field". */
static void test_checkpoint_fields_whole(void)
{
  /* line replaced, its new text, the line the message names, its words */
  static const struct { int line; const char *text; int at;
                        const char *field; } bad[] = {
    {3, "step 15x00", 3, "step: '15x00'"},  /* read as 15, exit status 0 */
    {3, "step -5", 3, "step: -5"},            /* accepted */
    {2, "cells 5x", 2, "cells: '5x'"},        /* read as 5 */
    {2, "cells 2000000000", 2, "cells: 2000000000"},   /* int overflow */
    {2, "cells 99999999999999999999", 2, "cells: 9999"},
    /* found by fuzz_checkpoint on the old reader (UBSan: 2 * 1073741824
    ** overflows int; sscanf's "cells %d" also took "cells1073741824") */
    {2, "cells1073741824", 2, "expected 'cells VALUE'"},
    {2, "cells 1073741824", 2, "cells: 1073741824"},
    {4, "time nan", 4, "time: 'nan'"},        /* accepted */
    {5, "seed -1", 5, "seed: '-1'"},          /* read as 2^64-1 */
    {5, "seed 7x", 5, "seed: '7x'"},          /* read as 7 */
    {6, "bytes trajectory.dat 12x", 6, "trajectory.dat: '12x'"},
    {7, "bytes observables.csv -1", 7, "observables.csv: -1"},
    {9, "0x1p+0 nan 0", 9, "y is not finite"},  /* accepted */
    {10, "1 2 3x", 10, "theta: '3x'"},
    {11, "end\n0 0 0", 12, "text after 'end'"}};      /* ignored */
  afv_checkpoint c;
  char where[32];
  size_t k;
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    int st;
    put_checkpoint("ck", bad[k].line, bad[k].text);
    snprintf(where, sizeof where, "ck:%d: ", bad[k].at);
    st = read_checkpoint("ck", &c);
    CHECK(st == AFV_EFORMAT && says(where, bad[k].field, NULL), "'%s': "
          "status %d, message '%s' (want '%s%s')", bad[k].text, st, msg,
          where, bad[k].field);
    afv_checkpoint_free(&c);
  }
  put_checkpoint("ck", 0, "");
  CHECK(read_checkpoint("ck", &c) == AFV_OK && c.n == 2 && c.step == 1500
        && c.t == 15 && c.seed == 7 && c.bytes[1] == 50 && c.r[2] == -0.25,
        "the good checkpoint: %s", msg);
  afv_checkpoint_free(&c);
}

/* A cell line longer than the old 512-byte buffer is read whole (the rest
** of it was taken for the next line). */
static void test_checkpoint_long_line_read_whole(void)
{
  char *line = padded("0x1p+0 0x0p+0", 700, ' ', "0x1.8p+1");
  afv_checkpoint c;
  if (line) put_checkpoint("ck", 9, line);
  CHECK(read_checkpoint("ck", &c) == AFV_OK && c.theta[0] == 3, "%s", msg);
  afv_checkpoint_free(&c);
  free(line);
}

/* ---- trajectories --------------------------------------------------------- */
static int read_traj(const char *name, const char *text, afv_traj *tr)
{
  put_text(name, text);
  msg[0] = 0;
  return afv_traj_read(at(name), tr, msg, sizeof msg);
}

static void test_trajectory_fields_whole(void)
{
  static const struct { const char *text, *want; } bad[] = {
    /* a count that does not fit: 2n + 1 overflowed int (UBSan) and the
    ** failed allocation left the message unset */
    {"# afv trajectory cells 2000000000 box open\n# step 0 time 0\n0 0 0\n",
     ":1: cells: 2000000000"},
    {"# afv trajectory cells 5000000000 box open\n", ":1: cells: 5000000000"},
    /* found by fuzz_trajectory on the old reader: read as 0 cells */
    {"", ":1: empty file"},
    {"# afv trajectory cells 2x box open\n", ":1: cells: '2x'"},
    {"# afv trajectory cells 1 box open junk\n", ":1: not an afv"},
    {"# afv trajectory cells 1 box periodic nan 10\n", ":1: box LX: 'nan'"},
    {"# afv trajectory cells 1 box periodic 10 -1\n", ":1: box: sides"},
    /* a frame header with trailing characters was taken for a comment */
    {"# afv trajectory cells 1 box open\n# step 0 time 0\n0 0 0\n\n\n"
     "# step 15x00 time 1\n1 1 1\n", ":6: step: '15x00'"},
    {"# afv trajectory cells 1 box open\n# step -5 time 0\n0 0 0\n",
     ":2: step: -5"},
    {"# afv trajectory cells 1 box open\n# step 0 time nan\n0 0 0\n",
     ":2: time: 'nan'"},
    {"# afv trajectory cells 1 box open\n# step 0 time 1 x\n0 0 0\n",
     ":2: expected a frame header"},
    {"# afv trajectory cells 1 box open\n# step 0 time 0\n0 inf 0\n",
     ":3: y is not finite"}};
  afv_traj tr;
  size_t k;
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    int st = read_traj("t.dat", bad[k].text, &tr);
    CHECK(st == AFV_EFORMAT && says("t.dat", bad[k].want, NULL), "case %d: "
          "status %d, message '%s' (want '%s')", (int)k, st, msg,
          bad[k].want);
    afv_traj_free(&tr);
  }
}

/* One row longer than the old 1024-byte buffer completed a frame of two
** cells by itself; a NUL byte was "expected a frame line". */
static void test_trajectory_no_split_no_nul(void)
{
  char *text = padded("# afv trajectory cells 2 box open\n# step 0 time 0\n"
                      "1 2 3", 1018, ' ', "4 5 6\n");
  afv_traj tr;
  int st = text ? read_traj("t.dat", text, &tr) : -1;
  CHECK(st == AFV_EFORMAT && says("t.dat:3:", "expected 3 columns",
        "found 6"), "status %d, %d frames, message %s", st, tr.nframes, msg);
  afv_traj_free(&tr);
  put("t.dat", "# afv trajectory cells 1 box open\n# step 0 time 0\n0 \0 0\n",
      56);
  msg[0] = 0;
  CHECK(afv_traj_read(at("t.dat"), &tr, msg, sizeof msg) == AFV_EFORMAT
        && says("t.dat:3:", "NUL byte at column 3", NULL), "%s", msg);
  afv_traj_free(&tr);
  free(text);
}

/* Frames whose time runs back or repeats (a damaged or spliced file) were
** analysed with exit 0; now each reader names the first such frame: the
** line in a format-1 file, the frame and byte in a format-2 one. */
static void test_trajectory_time_runs_forward(void)
{
  static const struct { const char *times, *want; } bad[] = {
    {"0 1 2 3 2 1 0 5", ":10: time 2 is not after the previous frame's "
     "time 3"},
    {"0 1 1 2", ":6: time 1 is not after"}};
  static const double t[5] = {0, 1, 2, 1.5, 3};
  double r[2] = {1, 2}, th = 0;
  afv_traj tr;
  size_t k;
  FILE *fp;
  int f, st;
  mkdir(at("run_back"), 0777);
  put_text("run_back/params.txt", "l 1\nv0 0.5\nDr 0.1\n");
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char text[1024] = "# afv trajectory cells 1 box open\n", *p, *end;
    long step = 0;
    for (p = (char *)bad[k].times; *p; p = end, step++) {
      double time = strtod(p, &end);
      snprintf(text + strlen(text), sizeof text - strlen(text),
               "# step %ld time %g\n0 0 0\n", step, time);
    }
    st = read_traj("t.dat", text, &tr);
    CHECK(st == AFV_EFORMAT && says("t.dat", bad[k].want, NULL), "case %d: "
          "status %d: %s", (int)k, st, msg);
    afv_traj_free(&tr);
    put_text("run_back/trajectory.dat", text);
    st = sh("./afv analyze %s", at("run_back"));
    CHECK(st == 2 && one_line_with("run_back/trajectory.dat", bad[k].want),
          "afv analyze, case %d: exit %d: %s", (int)k, st, msg);
  }
  fp = fopen(at("t2.dat"), "wb");
  CHECK(fp != NULL, "cannot write t2.dat");
  if (!fp) return;
  afv_traj_write_header(fp, 1, NULL);
  for (f = 0; f < 5; f++) afv_traj_write_frame(fp, f, t[f], 1, r, &th);
  fclose(fp);
  msg[0] = 0;
  st = afv_traj_read(at("t2.dat"), &tr, msg, sizeof msg);
  CHECK(st == AFV_EFORMAT && says("t2.dat: frame 3 (byte ", "time 1.5 is "
        "not after the previous frame's time 2", NULL), "status %d: %s", st,
        msg);
  afv_traj_free(&tr);
}

/* Format 2 (binary frames): centres read back bit for bit, angles as
** float32 of the angle reduced to [-pi, pi]; 16 + 20 N bytes a frame; a
** record cut short at the end is no frame.  Format 1 (text) is still read. */
static void test_trajectory_format2_exact_format1_read(void)
{
  double r[6] = {0.1, -1234.5678901234567, 1e-300, 3.0000000000000004,
                 50.123456789012345, -7.25};
  double th[3] = {7.5, -100.0, 3.0}, r2[6];
  afv_box b = {1, 50.5, 40.25};
  afv_traj tr;
  FILE *fp = fopen(at("f2.dat"), "wb");
  struct stat sb;
  long head = 0;
  int i, k, st;
  CHECK(fp != NULL, "cannot write f2.dat");
  if (!fp) return;
  afv_traj_write_header(fp, 3, &b);
  head = ftell(fp);
  for (k = 0; k < 2; k++) {
    for (i = 0; i < 6; i++) r2[i] = r[i] + k;
    afv_traj_write_frame(fp, 10 * k, 0.5 * k, 3, r2, th);
  }
  fwrite("partial", 1, 7, fp);          /* an interrupted writer */
  fclose(fp);
  CHECK(stat(at("f2.dat"), &sb) == 0 && sb.st_size == head + 2 * 76 + 7,
        "size %ld, want %ld", (long)sb.st_size, head + 2 * 76 + 7);
  msg[0] = 0;
  st = afv_traj_read(at("f2.dat"), &tr, msg, sizeof msg);
  CHECK(st == AFV_OK && tr.n == 3 && tr.nframes == 2 && tr.box.periodic
        && tr.box.Lx == 50.5 && tr.box.Ly == 40.25 && tr.step[1] == 10
        && tr.t[1] == 0.5, "status %d, %d frames: %s", st, tr.nframes, msg);
  for (k = 0; st == AFV_OK && k < 2; k++)
    for (i = 0; i < 3; i++) {
      double x = r[2*i] + k, y = r[2*i+1] + k;
      float a = (float)remainder(th[i], 6.28318530717958647692);
      CHECK(tr.r[6*k + 2*i] == x && tr.r[6*k + 2*i + 1] == y
            && tr.theta[3*k + i] == (double)a, "frame %d cell %d: %.17g %.17g"
            " %.9g", k, i, tr.r[6*k + 2*i], tr.r[6*k + 2*i + 1],
            tr.theta[3*k + i]);
    }
  afv_traj_free(&tr);
  st = read_traj("f1.dat", "# afv trajectory cells 1 box periodic 10 10\n"
                 "# step 0 time 0\n0.1 0.2 9\n\n\n# step 5 time 0.05\n"
                 "0.30000000000000004 0.2 9\n\n\n", &tr);
  CHECK(st == AFV_OK && tr.nframes == 2 && tr.r[2] == 0.30000000000000004
        && tr.theta[1] == 9, "format 1: status %d: %s", st, msg);
  afv_traj_free(&tr);
}

/* ---- through afv run: config file, T1 reference, resume ------------------- */
#define QUICK "--N 64 --relax_max_steps 0 --svg_every 0 --quiet"

/* The value of key in dir/name (a params.txt), or -1. */
static long long param(const char *name, const char *key)
{
  char buf[4096], *p;
  size_t m = strlen(key);
  slurp(name, buf, sizeof buf);
  for (p = buf; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
    if (strncmp(p, key, m) == 0 && p[m] == ' ') return atoll(p + m);
  return -1;
}

static int exists(const char *name)
{
  struct stat sb;
  return stat(at(name), &sb) == 0;
}

/* --config DIR read as an empty file and started a default run. */
static void test_config_directory_refused(void)
{
  int st = sh("./afv run --config %s " QUICK " --steps 1 --out %s",
              at("sub"), at("run_dir"));
  CHECK(st == 2 && one_line_with("sub: is a directory", NULL), "exit %d: %s",
        st, msg);
  CHECK(!exists("run_dir"), "a run started");
}

/* A comment longer than the old 2048-byte buffer: its tail was read as a
** line of its own, here "steps 7". */
static void test_config_long_line_not_split(void)
{
  /* "#" and 2046 x fill the old buffer: " steps 7" was the next "line" */
  char *text = padded("steps 3\n#", 2046, 'x', " steps 7\n");
  char *huge = padded("#", AFV_LINE_MAX + 10, 'x', "\n");
  int st;
  if (text) put_text("long.cfg", text);
  st = sh("./afv run --config %s " QUICK " --out %s", at("long.cfg"),
          at("run_long"));
  CHECK(st == 0 && param("run_long/params.txt", "steps") == 3, "exit %d, "
        "steps %lld", st, param("run_long/params.txt", "steps"));
  /* longer than any line a reader accepts: refused, naming the line */
  if (huge) put_text("huge.cfg", huge);
  st = sh("./afv run --config %s " QUICK " --out %s", at("huge.cfg"),
          at("run_huge"));
  CHECK(st == 2 && one_line_with("huge.cfg:1: line longer than", NULL),
        "exit %d: %s", st, msg);
  free(text);
  free(huge);
}

/* "steps 1\0junk" read as "steps 1"; a path too long for the run's buffer
** was cut and another file opened. */
static void test_config_nul_and_long_path(void)
{
  char *cells = padded("cells /", 1500, 'p', "\n");
  int st;
  put("nul.cfg", "steps 1\0junk\n", 13);
  st = sh("./afv run --config %s " QUICK " --out %s", at("nul.cfg"),
          at("run_nul"));
  CHECK(st == 2 && one_line_with("nul.cfg:1: NUL byte at column 8", NULL),
        "exit %d: %s", st, msg);
  if (cells) put_text("path.cfg", cells);
  st = sh("./afv run --config %s " QUICK " --out %s", at("path.cfg"),
          at("run_path"));
  CHECK(st == 2 && one_line_with("path.cfg:1: cells: path longer than", NULL),
        "exit %d: %s", st, msg);
  CHECK(!exists("run_nul") && !exists("run_path"), "a run started");
  free(cells);
}

/* A run to damage: 64 cells, 20 steps, checkpoints every 10. */
static int make_run(const char *name)
{
  return sh("rm -rf %s && ./afv run " QUICK " --steps 20 --frame_every 10 "
            "--sample_every 5 --checkpoint_every 10 --out %s", at(name),
            at(name));
}

/* A recorded size larger than its file is named with the checkpoint's
** line (afv run --resume checks them before it cuts anything; before, the
** message was "shorter than the checkpoint records", without the line). */
static void test_checkpoint_sizes_against_files(void)
{
  afv_checkpoint c;
  char bytes[100];
  int st;
  mkdir(at("ckdir"), 0777);
  put_checkpoint("ckdir/checkpoint.txt", 0, "");   /* 100, 50 and 0 bytes */
  CHECK(afv_checkpoint_read(at("ckdir/checkpoint.txt"), &c, msg, sizeof msg)
        == AFV_OK, "%s", msg);
  memset(bytes, 'x', sizeof bytes);
  put("ckdir/trajectory.dat", bytes, 100);   /* exactly the size: fine */
  put("ckdir/observables.csv", bytes, 49);   /* one byte short */
  msg[0] = 0;
  st = afv_checkpoint_check_files(at("ckdir/checkpoint.txt"), &c, msg,
                                  sizeof msg);
  CHECK(st == AFV_EFORMAT && says("checkpoint.txt:7: bytes observables.csv: "
        "50, larger than the file (49 bytes)", NULL, NULL), "%s", msg);
  put("ckdir/observables.csv", bytes, 50);
  msg[0] = 0;
  CHECK(afv_checkpoint_check_files(at("ckdir/checkpoint.txt"), &c, msg,
        sizeof msg) == AFV_OK, "sizes that fit: %s", msg);
  remove(at("ckdir/trajectory.dat"));
  CHECK(afv_checkpoint_check_files(at("ckdir/checkpoint.txt"), &c, msg,
        sizeof msg) == AFV_EFORMAT && says("checkpoint.txt:6: bytes "
        "trajectory.dat: 100, but ", "No such file", NULL), "%s", msg);
  afv_checkpoint_free(&c);
}

/* The T1 reference, read back on --resume: count, order, whole fields. */
static void test_resume_t1_reference_checked(void)
{
  static const struct { const char *text, *want; } bad[] = {
    /* 2m + 1 overflowed int; the message said only "file format error" */
    {"2000000000\n0 1\n", "t1_reference.txt:2: pairs: 2000000000"},
    {"3\n0 1\n0 1\n2 3\n", "t1_reference.txt:4: pair 0 1 is not after"},
    {"2\n0 2\n0 1\n", "t1_reference.txt:4: pair 0 1 is not after"},
    {"1\n0 1x\n", "t1_reference.txt:3: j: '1x'"},
    {"1\n3 64\n", "t1_reference.txt:3: j: 64 is more than 63"},
    {"1\n0 1\n1 2\n", "t1_reference.txt:4: more pairs"},
    {"1x\n0 1\n", "t1_reference.txt:2: pairs: '1x'"}};
  size_t k;
  CHECK(make_run("r3") == 0, "run");
  CHECK(sh("cp -r %s %s", at("r3"), at("r3_saved")) == 0, "cp");
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char text[256];
    int st;
    sh("rm -rf %s && cp -r %s %s", at("r3"), at("r3_saved"), at("r3"));
    snprintf(text, sizeof text, "# afv t1 reference: contacting pairs at "
             "step 0\n%s", bad[k].text);
    put_text("r3/t1_reference.txt", text);
    st = sh("./afv run --resume %s --steps 5", at("r3"));
    CHECK(st == 2 && one_line_with(bad[k].want, NULL), "case %d: exit %d: "
          "%s(want '%s')", (int)k, st, msg, bad[k].want);
  }
}

void suite_readers(void)
{
  strcpy(dir, "/tmp/afv_test_readers_XXXXXX");
  if (!mkdtemp(dir)) {
    printf("  cannot create a temporary directory under /tmp\n");
    return;
  }
  RUN(test_points_nul_byte_named);
  RUN(test_points_long_line_read_whole);
  RUN(test_points_directory_and_pipe_refused);
  RUN(test_cells_long_row_not_split);
  RUN(test_cells_nul_and_directory);
  RUN(test_checkpoint_fields_whole);
  RUN(test_checkpoint_long_line_read_whole);
  RUN(test_trajectory_fields_whole);
  RUN(test_trajectory_no_split_no_nul);
  RUN(test_trajectory_time_runs_forward);
  RUN(test_trajectory_format2_exact_format1_read);
  RUN(test_config_directory_refused);
  RUN(test_config_long_line_not_split);
  RUN(test_config_nul_and_long_path);
  RUN(test_checkpoint_sizes_against_files);
  RUN(test_resume_t1_reference_checked);
  sh("rm -rf %s", dir);
}
