/*
** io.c -- file formats: cell centres (POINTS), atomic writes, trajectories,
** per-cell values (CELLS) and checkpoints.  Each format is described where
** it is read or written.
**
** POINTS format: one cell per line, columns "x y" separated by spaces, tabs
** or commas; blank lines and lines starting with '#' are ignored.  Errors
** name the file and line.
**
** Every reader reads through afv_lines (READING LINES below): a regular
** file only, each line whole, no NUL byte; every field is parsed whole and
** range-checked, and a count is checked against what the file can hold
** before anything is allocated for it.  Messages: "FILE:LINE: field: what".
**
** Invariant of an open afv_lines (asserted by afv_lines_next in a build
** without -DNDEBUG): the unread part of its block is buf[pos .. fill),
** pos <= fill <= AFV_LINES_BLOCK; a line handed out is NUL-ended at len,
** len <= AFV_LINE_MAX.
*/
#define _POSIX_C_SOURCE 200809L  /* stat: readers refuse directories, devices */
#include "afv_internal.h"
#include "afv_tool.h"

#include <assert.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

/* Initial capacity of the points array; small so that growth is exercised
** by every test that reads more than a handful of cells. */
#define POINTS_INITIAL_CAP 8

void afv_errorf(char *err, size_t errlen, const char *fmt, ...)
{
  va_list ap;
  if (!err || errlen == 0) return;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
}

/* ---- reading lines ----------------------------------------------------- */
/* afv_lines reads a file in blocks and hands out one whole line at a time
** (any length up to AFV_LINE_MAX bytes), so no line is ever split; a NUL
** byte, which no text afv reads may hold, is refused where it is. */
static const char *file_kind(mode_t m)
{
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a pipe";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  return "a special file";
}

int afv_lines_open(afv_lines *L, const char *path, char *err, size_t errlen)
{
  struct stat sb;
  memset(L, 0, sizeof *L);
  L->path = path;
  if (stat(path, &sb) != 0) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
  /* checked before fopen: opening a pipe would wait for a writer */
  if (!S_ISREG(sb.st_mode)) {
    afv_errorf(err, errlen, "%s: is %s, not a regular file", path,
               file_kind(sb.st_mode));
    return AFV_EIO;
  }
  if (!(L->fp = fopen(path, "rb"))) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
  L->size = (long long)sb.st_size;
  return AFV_OK;
}

void afv_lines_close(afv_lines *L)
{
  if (L->fp) fclose(L->fp);
  free(L->line);
  L->fp = NULL;
  L->line = NULL;
}

static int lines_fail(afv_lines *L, int status)
{
  L->status = status;
  return -1;
}

/* Appends k bytes of the block to the line (k <= AFV_LINE_MAX - len). */
static int lines_append(afv_lines *L, const char *s, size_t k)
{
  if (L->len + k + 1 > L->cap) {
    size_t nc = L->cap ? L->cap : 256;
    char *q;
    while (nc < L->len + k + 1) nc *= 2;
    if (!(q = realloc(L->line, nc))) return AFV_ENOMEM;
    L->line = q;
    L->cap = nc;
  }
  memcpy(L->line + L->len, s, k);
  L->len += k;
  L->line[L->len] = 0;
  return AFV_OK;
}

int afv_lines_next(afv_lines *L, char *err, size_t errlen)
{
  L->len = 0;
  L->newline = 0;
  L->lineno++;
  if (lines_append(L, "", 0) != AFV_OK) {
    afv_errorf(err, errlen, "%s:%lld: out of memory", L->path, L->lineno);
    return lines_fail(L, AFV_ENOMEM);
  }
  for (;;) {
    const char *at = L->buf + L->pos, *nl, *nul;
    size_t k;
    assert(L->pos <= L->fill && L->fill <= sizeof L->buf);
    if (L->pos == L->fill) {
      L->pos = 0;
      L->fill = fread(L->buf, 1, sizeof L->buf, L->fp);
      if (L->fill == 0 && ferror(L->fp)) {
        afv_errorf(err, errlen, "%s:%lld: read error: %s", L->path,
                   L->lineno, strerror(errno));
        return lines_fail(L, AFV_EIO);
      }
      if (L->fill == 0) break;                    /* end of the file */
      continue;
    }
    nl = memchr(at, '\n', L->fill - L->pos);
    k = nl ? (size_t)(nl - at) : L->fill - L->pos;
    if ((nul = memchr(at, 0, k)) != NULL) {
      afv_errorf(err, errlen, "%s:%lld: NUL byte at column %lu (not a text "
                 "file, or a damaged one)", L->path, L->lineno,
                 (unsigned long)(L->len + (size_t)(nul - at) + 1));
      return lines_fail(L, AFV_EFORMAT);
    }
    if (k > AFV_LINE_MAX - L->len) {
      afv_errorf(err, errlen, "%s:%lld: line longer than %d bytes", L->path,
                 L->lineno, AFV_LINE_MAX);
      return lines_fail(L, AFV_EFORMAT);
    }
    if (lines_append(L, at, k) != AFV_OK) {
      afv_errorf(err, errlen, "%s:%lld: out of memory", L->path, L->lineno);
      return lines_fail(L, AFV_ENOMEM);
    }
    L->pos += k + (nl != NULL);
    if (nl) {
      L->newline = 1;
      break;
    }
  }
  if (L->len == 0 && !L->newline) {           /* nothing after the last \n */
    L->lineno--;
    return 0;
  }
  assert(L->len <= AFV_LINE_MAX && L->line[L->len] == 0);
  return 1;
}

/* ---- fields ------------------------------------------------------------- */
static int is_sep(int c)
{
  return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n';
}

/* 1 if line holds nothing but separators. */
static int is_blank(const char *line)
{
  while (*line && is_sep((unsigned char)*line)) line++;
  return *line == 0;
}

/* 1 if the first non-blank character of line is '#'. */
static int is_comment(const char *line)
{
  return line[strspn(line, " \t\r")] == '#';
}

/* The field at p (up to the next separator) for a message, at most 32
** bytes, control bytes shown as '?', "..." if cut; out holds 40 bytes. */
static const char *shown(const char *p, char *out)
{
  size_t k = 0;
  for (; p[k] && !is_sep((unsigned char)p[k]) && k < 32; k++)
    out[k] = (unsigned char)p[k] < 32 || p[k] == 127 ? '?' : p[k];
  strcpy(out + k, p[k] && !is_sep((unsigned char)p[k]) ? "..." : "");
  return out;
}

/* Splits s in place at spaces, tabs and carriage returns; the first max
** words go to w.  Returns the number of words (counting past max). */
static int split_words(char *s, char **w, int max)
{
  int n = 0;
  for (;;) {
    s += strspn(s, " \t\r");
    if (!*s) return n;
    if (n < max) w[n] = s;
    n++;
    s += strcspn(s, " \t\r");
    if (*s) *s++ = 0;
  }
}

/* Parses up to `want` numbers from a line into v; returns how many fields
** the line has (counting past `want`), or -1 with *bad set to the first
** field that is not a number and *at to its index. */
static int parse_fields(char *line, double *v, int want, char **bad, int *at)
{
  int count = 0;
  char *p = line;
  for (;;) {
    char *end;
    double x;
    while (*p && is_sep((unsigned char)*p)) p++;
    if (!*p) return count;
    x = strtod(p, &end);
    if (end == p || (*end && !is_sep((unsigned char)*end))) {
      *bad = p;
      *at = count;
      return -1;
    }
    if (count < want) v[count] = x;
    count++;
    p = end;
  }
}

/* The numbers of one data line: exactly `want` finite ones, names[k] the
** name of field k.  Returns want, 0 for a blank line, or -1 with
** "FILE:LINE: ..." in err. */
static int number_row(const afv_lines *L, double *v, int want,
                      const char *const *names, char *err, size_t errlen)
{
  char *bad = NULL, q[40];
  int at = 0, f = parse_fields(L->line, v, want, &bad, &at), k;
  if (f == 0) return 0;
  if (f < 0) {
    afv_errorf(err, errlen, "%s:%lld: %s: '%s' is not a number", L->path,
               L->lineno, at < want ? names[at] : "extra column",
               shown(bad, q));
    return -1;
  }
  if (f != want) {
    afv_errorf(err, errlen, "%s:%lld: expected %d columns (%s%s%s%s), found "
               "%d", L->path, L->lineno, want, names[0],
               want > 1 ? " " : "", want > 1 ? names[1] : "",
               want > 2 ? " ..." : "", f);
    return -1;
  }
  for (k = 0; k < want; k++)
    if (!isfinite(v[k])) {
      afv_errorf(err, errlen, "%s:%lld: %s is not finite", L->path,
                 L->lineno, names[k]);
      return -1;
    }
  return f;
}

/* s as a whole decimal integer: 1 (in *v), 0 if it is not one, 2 if it is
** one but does not fit a long long. */
static int whole_ll(const char *s, long long *v)
{
  char *end;
  const char *d = s + (s[0] == '-');
  if (*d < '0' || *d > '9') return 0;
  errno = 0;
  *v = strtoll(s, &end, 10);
  if (*end) return 0;
  return errno == ERANGE ? 2 : 1;
}

/* The integer field `name` of line L in [lo, hi]; `why` says what bounds it
** from above.  1, or 0 with "FILE:LINE: name: ..." in err. */
static int int_field(const afv_lines *L, const char *name, const char *s,
                     long long lo, long long hi, const char *why,
                     long long *v, char *err, size_t errlen)
{
  char q[40];
  int k = whole_ll(s, v);
  if (k == 0)
    afv_errorf(err, errlen, "%s:%lld: %s: '%s' is not an integer", L->path,
               L->lineno, name, shown(s, q));
  else if ((k == 2 && s[0] == '-') || (k == 1 && *v < lo))
    afv_errorf(err, errlen, "%s:%lld: %s: %s is less than %lld", L->path,
               L->lineno, name, shown(s, q), lo);
  else if (k == 2 || *v > hi)
    afv_errorf(err, errlen, "%s:%lld: %s: %s is more than %lld (%s)",
               L->path, L->lineno, name, shown(s, q), hi, why);
  else
    return 1;
  return 0;
}

/* The real field `name` of line L: a whole finite number (hex floats
** included, as %a writes them).  1, or 0 with the message in err. */
static int real_field(const afv_lines *L, const char *name, const char *s,
                      double *v, char *err, size_t errlen)
{
  char *end, q[40];
  *v = strtod(s, &end);
  if (end != s && *end == 0 && isfinite(*v)) return 1;
  afv_errorf(err, errlen, "%s:%lld: %s: '%s' is not a finite number",
             L->path, L->lineno, name, shown(s, q));
  return 0;
}

/* "FILE:LINE: " and the message in err; returns status. */
static int line_fail(const afv_lines *L, int status, char *err, size_t errlen,
                     const char *fmt, ...)
{
  va_list ap;
  size_t m;
  afv_errorf(err, errlen, "%s:%lld: ", L->path, L->lineno);
  if (!err || (m = strlen(err)) + 1 >= errlen) return status;
  va_start(ap, fmt);
  vsnprintf(err + m, errlen - m, fmt, ap);
  va_end(ap);
  return status;
}

/* ---- POINTS ------------------------------------------------------------- */
static int push_point(double **r, int *n, int *cap, double x, double y)
{
  if (*n >= *cap) {
    int nc = *cap ? 2 * *cap : POINTS_INITIAL_CAP;
    double *q = realloc(*r, (size_t)nc * 2 * sizeof(double));
    if (!q) return AFV_ENOMEM;
    *r = q;
    *cap = nc;
  }
  (*r)[2 * *n] = x;
  (*r)[2 * *n + 1] = y;
  (*n)++;
  return AFV_OK;
}

int afv_points_read(const char *path, int *n_out, double **r_out, char *err,
                    size_t errlen)
{
  static const char *const names[2] = {"x", "y"};
  afv_lines L;
  double *r = NULL, v[2];
  int n = 0, cap = 0, st, got = 0;
  *n_out = 0;
  *r_out = NULL;
  if ((st = afv_lines_open(&L, path, err, errlen)) != AFV_OK) return st;
  while (st == AFV_OK && (got = afv_lines_next(&L, err, errlen)) > 0) {
    if (is_comment(L.line)) continue;
    int fields = number_row(&L, v, 2, names, err, errlen);
    if (fields < 0) st = AFV_EFORMAT;
    else if (fields > 0 && n >= AFV_CELLS_MAX)
      st = line_fail(&L, AFV_EFORMAT, err, errlen, "more than %d cells",
                     AFV_CELLS_MAX);
    else if (fields > 0 && push_point(&r, &n, &cap, v[0], v[1]) != AFV_OK)
      st = line_fail(&L, AFV_ENOMEM, err, errlen, "out of memory");
  }
  if (st == AFV_OK && got < 0) st = L.status;
  afv_lines_close(&L);
  if (st != AFV_OK) {
    free(r);
    return st;
  }
  *n_out = n;
  *r_out = r;
  return AFV_OK;
}

/* ---- atomic files ------------------------------------------------------ */
/* A file is written as a temporary PATH.PID.RAND.tmp and renamed over PATH
** only when complete: rename is atomic on POSIX file systems, so a reader
** (or a resumed run) sees the old file or the new one, never half of one.
** The temporary is created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW), so
** it is always a new file of this process: a file or a symbolic link a
** user left at any name is never written through, truncated or removed
** (with the fixed name PATH.tmp and fopen "w", a link there made afv
** overwrite the file it points to, and a user's PATH.tmp was removed).
** PID is afv_atomic_pid (the program sets it to its process id; the
** library calls no getpid, which WASI lacks); RAND mixes the time, a
** counter, an address and PID; a name that exists already is skipped (up
** to ATOMIC_TRIES names). */
#define ATOMIC_TRIES 64

long afv_atomic_pid;

/* 32 bits that differ between calls and processes (not for statistics:
** they only make a name no one else has; O_EXCL makes it safe anyway). */
static unsigned long atomic_salt(void)
{
  static unsigned long counter;
  unsigned long here = 0;
  uint64_t z = (uint64_t)time(NULL) ^ (uint64_t)(uintptr_t)&here << 16
               ^ (uint64_t)++counter * 0x9E3779B97F4A7C15ull
               ^ (uint64_t)afv_atomic_pid << 40;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;   /* splitmix64's finaliser */
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return (unsigned long)((z ^ (z >> 31)) & 0xffffffffu);
}

FILE *afv_atomic_open(const char *path, char *tmp, size_t tmplen)
{
  int k, fd = -1;
  FILE *fp;
  for (k = 0; k < ATOMIC_TRIES && fd < 0; k++) {
    if ((size_t)snprintf(tmp, tmplen, "%s.%ld.%08lx.tmp", path,
                         afv_atomic_pid, atomic_salt()) >= tmplen) {
      errno = ENAMETOOLONG;
      return NULL;
    }
    fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0666);
    if (fd < 0 && errno != EEXIST) return NULL;
  }
  if (fd < 0) return NULL;   /* errno: EEXIST */
  if (!(fp = fdopen(fd, "w"))) {
    int why = errno;
    close(fd);
    remove(tmp);
    errno = why;
  }
  return fp;
}

/* On failure errno keeps the system's reason (ENOSPC on a full disk), not
** that of the clean-up: the caller names it. */
int afv_atomic_commit(FILE *fp, const char *tmp, const char *path)
{
  int bad = fflush(fp) != 0 || ferror(fp), why = errno;  /* a failed write */
  if (fclose(fp) != 0 && !bad) bad = 1, why = errno;
  if (!bad && rename(tmp, path) != 0) bad = 1, why = errno;
  if (bad) {
    remove(tmp);
    errno = why ? why : EIO;
    return AFV_EIO;
  }
  return AFV_OK;
}

/* ---- trajectories ------------------------------------------------------ */
/* TRAJECTORY format 2 (what afv run writes): one text line,
**   # afv trajectory 2 cells N box open          (or: box periodic LX LY)
** then per frame a binary record of 16 + 20 N bytes, little-endian IEEE:
**   int64 step, float64 time,
**   N times (float64 x, float64 y, float32 theta)
** x, y are the unwrapped centres, exact: they are all afv analyze reads, so
** its results are the bits it would get from the simulation's own state.
** theta is the polarity angle reduced to [-pi, pi] in float32 (about 1e-7
** rad; afv draw's arrows read it, no analysis does).  20 bytes a cell:
** a 10^6-step job of 400 cells with a frame every 1000 steps writes 8.0 MB
** (62 bytes a cell in %.17g text before).  A record cut short at the end
** of the file (an interrupted writer) is no frame.
** Format 1 (earlier versions of afv; still read, whole, into memory):
**   # afv trajectory cells N box open             (or: box periodic LX LY)
** then per frame "# step S time T", N lines "x y theta" (%.17g), two blank
** lines.  In both formats frames run forward: each step and time larger
** than the frame's before. */
#define TRAJ_CHUNK 256          /* cells encoded per fwrite */

/* The format assumes 8-byte doubles and 4-byte floats (IEEE on every
** machine afv builds on); a compile error otherwise. */
typedef char traj_double_is_8_bytes[sizeof(double) == 8 ? 1 : -1];
typedef char traj_float_is_4_bytes[sizeof(float) == 4 ? 1 : -1];

static void put_u64(unsigned char *p, uint64_t u)
{
  int k;
  for (k = 0; k < 8; k++) p[k] = (unsigned char)(u >> (8 * k));
}

static uint64_t get_u64(const unsigned char *p)
{
  uint64_t u = 0;
  int k;
  for (k = 7; k >= 0; k--) u = (u << 8) | p[k];
  return u;
}

static void put_f64(unsigned char *p, double v)
{
  uint64_t u;
  memcpy(&u, &v, 8);
  put_u64(p, u);
}

static double get_f64(const unsigned char *p)
{
  uint64_t u = get_u64(p);
  double v;
  memcpy(&v, &u, 8);
  return v;
}

static void put_f32(unsigned char *p, float v)
{
  uint32_t u;
  int k;
  memcpy(&u, &v, 4);
  for (k = 0; k < 4; k++) p[k] = (unsigned char)(u >> (8 * k));
}

static float get_f32(const unsigned char *p)
{
  uint32_t u = 0;
  float v;
  int k;
  for (k = 3; k >= 0; k--) u = (u << 8) | p[k];
  memcpy(&v, &u, 4);
  return v;
}

/* The angle as stored: reduced to [-pi, pi] (remainder is exact), then
** float32; a value out of range never reaches the conversion. */
static float stored_angle(double theta)
{
  double a = remainder(theta, TWO_PI);
  return isfinite(a) ? (float)a : 0.0f;
}

int afv_traj_write_header(FILE *fp, int n, const afv_box *b)
{
  if (b && b->periodic)
    fprintf(fp, "# afv trajectory 2 cells %d box periodic %.17g %.17g\n", n,
            b->Lx, b->Ly);
  else
    fprintf(fp, "# afv trajectory 2 cells %d box open\n", n);
  return ferror(fp) ? AFV_EIO : AFV_OK;
}

int afv_traj_write_frame(FILE *fp, long long step, double t, int n,
                         const double *r, const double *theta)
{
  unsigned char buf[TRAJ_CHUNK * AFV_TRAJ_CELL_BYTES];
  int i, m = 0;
  put_u64(buf, (uint64_t)step);
  put_f64(buf + 8, t);
  fwrite(buf, 1, AFV_TRAJ_FRAME_HEAD, fp);
  for (i = 0; i < n; i++) {
    unsigned char *p = buf + (size_t)m * AFV_TRAJ_CELL_BYTES;
    put_f64(p, r[2*i]);
    put_f64(p + 8, r[2*i+1]);
    put_f32(p + 16, theta ? stored_angle(theta[i]) : 0.0f);
    if (++m == TRAJ_CHUNK || i == n - 1) {
      fwrite(buf, AFV_TRAJ_CELL_BYTES, (size_t)m, fp);
      m = 0;
    }
  }
  return ferror(fp) ? AFV_EIO : AFV_OK;
}

void afv_traj_free(afv_traj *tr)
{
  free(tr->step);
  free(tr->t);
  free(tr->r);
  free(tr->theta);
  memset(tr, 0, sizeof *tr);
}

/* Line 1: "# afv trajectory [2] cells N box open" or "... box periodic LX
** LY"; *format 2 with the "2", else 1. */
static int parse_traj_header(afv_lines *L, afv_traj *tr, int *format,
                             char *err, size_t errlen)
{
  char *w[12], **v = w;
  int nw = split_words(L->line, w, 12);
  long long n;
  *format = nw >= 4 && strcmp(w[3], "2") == 0 ? 2 : 1;
  if (*format == 2) {   /* the same words after the version */
    v = w + 1;
    nw--;
  }
  if (!(nw == 7 || nw == 9) || strcmp(w[0], "#") || strcmp(w[1], "afv")
      || strcmp(w[2], "trajectory") || strcmp(v[3], "cells")
      || strcmp(v[5], "box")
      || strcmp(v[6], nw == 7 ? "open" : "periodic"))
    return line_fail(L, AFV_EFORMAT, err, errlen, "not an afv trajectory "
                     "header ('# afv trajectory 2 cells N box open' or '... "
                     "box periodic LX LY'; format 1 without the 2)");
  if (!int_field(L, "cells", v[4], 1, AFV_CELLS_MAX, "the most afv reads",
                 &n, err, errlen))
    return AFV_EFORMAT;
  tr->n = (int)n;
  tr->box.periodic = nw == 9;
  if (nw == 9 && (!real_field(L, "box LX", v[7], &tr->box.Lx, err, errlen)
                  || !real_field(L, "box LY", v[8], &tr->box.Ly, err,
                                 errlen)))
    return AFV_EFORMAT;
  if (nw == 9 && !(tr->box.Lx > 0 && tr->box.Ly > 0))
    return line_fail(L, AFV_EFORMAT, err, errlen, "box: sides %g x %g, "
                     "must be > 0", tr->box.Lx, tr->box.Ly);
  return AFV_OK;
}

/* A "# step S time T" line (1 if w, nw are one); 0 if it is another
** comment; -1 with the message in err if it starts "# step" but is not a
** whole one. */
static int parse_frame_header(const afv_lines *L, char **w, int nw,
                              long long *step, double *t, char *err,
                              size_t errlen)
{
  if (nw < 2 || strcmp(w[0], "#") || strcmp(w[1], "step")) return 0;
  if (nw != 5 || strcmp(w[3], "time")) {
    line_fail(L, AFV_EFORMAT, err, errlen, "expected a frame header '# step "
              "S time T'");
    return -1;
  }
  if (!int_field(L, "step", w[2], 0, LLONG_MAX, "a long long", step, err,
                 errlen)
      || !real_field(L, "time", w[4], t, err, errlen))
    return -1;
  return 1;
}

/* Frames run forward: frame k's step and time after those of frame k - 1
** (a time that runs back or repeats is a damaged or a spliced file, whose
** MSD and series would be silently wrong).  1, or 0 with "what: why" in
** why (the caller prefixes the place). */
static int runs_forward(const long long *step, const double *t, int k,
                        char *why, size_t len)
{
  if (k == 0) return 1;
  if (!(t[k] > t[k-1]))
    snprintf(why, len, "time %.17g is not after the previous frame's time "
             "%.17g (frames must run forward in time)", t[k], t[k-1]);
  else if (step[k] <= step[k-1])
    snprintf(why, len, "step %lld is not after the previous frame's step "
             "%lld (frames must run forward)", step[k], step[k-1]);
  else
    return 1;
  return 0;
}

/* Room for one more frame's step and time (capacity doubles). */
static int traj_grow_frames(afv_traj *tr, int *cap)
{
  int nc;
  long long *s;
  double *t;
  if (tr->nframes < *cap) return AFV_OK;
  if (*cap > INT_MAX / 2) return AFV_ENOMEM;
  nc = *cap ? 2 * *cap : 4;
  if ((s = realloc(tr->step, (size_t)nc * sizeof *s)) != NULL) tr->step = s;
  if ((t = realloc(tr->t, (size_t)nc * sizeof *t)) != NULL) tr->t = t;
  if (!s || !t) return AFV_ENOMEM;
  *cap = nc;
  return AFV_OK;
}

/* Room for one more cell line (rows counts them over all frames): the
** arrays grow with what the file holds, never with what its header says. */
static int traj_grow_rows(afv_traj *tr, size_t rows, size_t *cap)
{
  size_t nc;
  double *r, *th;
  if (rows < *cap) return AFV_OK;
  if (*cap > ((size_t)-1) / 32) return AFV_ENOMEM;
  nc = *cap ? 2 * *cap : 64;
  if ((r = realloc(tr->r, nc * 2 * sizeof(double))) != NULL) tr->r = r;
  if ((th = realloc(tr->theta, nc * sizeof(double))) != NULL) tr->theta = th;
  if (!r || !th) return AFV_ENOMEM;
  *cap = nc;
  return AFV_OK;
}

/* A format-1 "# step S time T" line: a new frame, after a whole one. */
static int traj_text_frame(afv_lines *L, afv_traj *tr, int row,
                           int *cap_frames, long long step, double t,
                           char *err, size_t errlen)
{
  char why[160];
  if (tr->nframes > 0 && row != tr->n)
    return line_fail(L, AFV_EFORMAT, err, errlen, "the frame before this "
                     "line has %d of %d cells", row, tr->n);
  if (tr->nframes == INT_MAX || traj_grow_frames(tr, cap_frames) != AFV_OK)
    return line_fail(L, AFV_ENOMEM, err, errlen, "out of memory (frame "
                     "%d)", tr->nframes);
  tr->step[tr->nframes] = step;
  tr->t[tr->nframes] = t;
  if (!runs_forward(tr->step, tr->t, tr->nframes, why, sizeof why))
    return line_fail(L, AFV_EFORMAT, err, errlen, "%s", why);
  tr->nframes++;
  return AFV_OK;
}

/* One line of a format-1 body: a frame header, a comment, a blank line or
** a cell line "x y theta" of the current frame (row of it). */
static int traj_line(afv_lines *L, afv_traj *tr, int *row, int *cap_frames,
                     size_t *cap_rows, char *err, size_t errlen)
{
  static const char *const names[3] = {"x", "y", "theta"};
  char *w[6];
  double v[3], t;
  long long step;
  size_t rows;
  int h, f;
  if (is_comment(L->line)) {
    /* a frame header, or another comment (ignored) */
    h = parse_frame_header(L, w, split_words(L->line, w, 6), &step, &t, err,
                           errlen);
    if (h <= 0) return h < 0 ? AFV_EFORMAT : AFV_OK;
    h = traj_text_frame(L, tr, *row, cap_frames, step, t, err, errlen);
    *row = 0;
    return h;
  }
  f = number_row(L, v, 3, names, err, errlen);
  if (f <= 0) return f < 0 ? AFV_EFORMAT : AFV_OK;
  if (tr->nframes == 0)
    return line_fail(L, AFV_EFORMAT, err, errlen, "a cell line before the "
                     "first '# step S time T' line");
  if (*row >= tr->n)
    return line_fail(L, AFV_EFORMAT, err, errlen, "more than the header's %d "
                     "cells in this frame", tr->n);
  rows = (size_t)(tr->nframes - 1) * (size_t)tr->n + (size_t)*row;
  if (traj_grow_rows(tr, rows, cap_rows) != AFV_OK)
    return line_fail(L, AFV_ENOMEM, err, errlen, "out of memory");
  tr->r[2 * rows] = v[0];
  tr->r[2 * rows + 1] = v[1];
  tr->theta[rows] = v[2];
  (*row)++;
  return AFV_OK;
}

/* The frames of a format-1 file after its header line, every one into tr. */
static int traj_read_text(afv_lines *L, afv_traj *tr, char *err,
                          size_t errlen)
{
  size_t cap_rows = 0;
  int cap_frames = 0, row = 0, st = AFV_OK, got;
  while (st == AFV_OK && (got = afv_lines_next(L, err, errlen)) > 0) {
    /* the last line has no newline: an interrupted writer; its frame is
    ** incomplete and is dropped below */
    if (!L->newline) break;
    st = traj_line(L, tr, &row, &cap_frames, &cap_rows, err, errlen);
  }
  if (st == AFV_OK && got < 0) st = L->status;
  /* a last frame cut short (an interrupted writer) is dropped; a short
  ** frame anywhere else is an error (above) */
  if (st == AFV_OK && tr->nframes > 0 && row != tr->n) tr->nframes--;
  return st;
}

/* "FILE: frame K (byte B): " and the message in err; returns status. */
static int frame_fail(const afv_traj_file *f, int k, int status, char *err,
                      size_t errlen, const char *fmt, ...)
{
  va_list ap;
  size_t m;
  afv_errorf(err, errlen, "%s: frame %d (byte %lld): ", f->path, k,
             f->head + (long long)k * f->record);
  if (!err || (m = strlen(err)) + 1 >= errlen) return status;
  va_start(ap, fmt);
  vsnprintf(err + m, errlen - m, fmt, ap);
  va_end(ap);
  return status;
}

/* Reads len bytes of the record of frame k at offset `at` in it. */
static int traj_fetch(afv_traj_file *f, int k, long long at, void *buf,
                      size_t len, char *err, size_t errlen)
{
  if (fseeko(f->fp, (off_t)(f->head + (long long)k * f->record + at),
             SEEK_SET) != 0
      || fread(buf, 1, len, f->fp) != len)
    return frame_fail(f, k, AFV_EIO, err, errlen, "cannot read: %s",
                      ferror(f->fp) ? strerror(errno) : "the file is "
                      "shorter than when it was opened");
  return AFV_OK;
}

void afv_traj_frame_head(const unsigned char *b, long long *step, double *t)
{
  uint64_t s = get_u64(b);
  *step = s <= (uint64_t)LLONG_MAX ? (long long)s : -1;
  *t = get_f64(b + 8);
}

/* Format 2: every whole record's step and time, checked. */
static int traj_index(afv_traj_file *f, long long size, char *err,
                      size_t errlen)
{
  long long frames = (size - f->head) / f->record;
  unsigned char b[AFV_TRAJ_FRAME_HEAD];
  char why[160];
  int k, st = AFV_OK;
  if (frames > INT_MAX)
    return frame_fail(f, INT_MAX, AFV_EFORMAT, err, errlen, "more than %d "
                      "frames", INT_MAX);
  f->step = malloc((size_t)(frames + 1) * sizeof *f->step);
  f->t = malloc((size_t)(frames + 1) * sizeof *f->t);
  if (!f->step || !f->t)
    return frame_fail(f, 0, AFV_ENOMEM, err, errlen, "out of memory for "
                      "%lld frames", frames);
  for (k = 0; st == AFV_OK && k < frames; k++) {
    if ((st = traj_fetch(f, k, 0, b, sizeof b, err, errlen)) != AFV_OK)
      break;
    afv_traj_frame_head(b, &f->step[k], &f->t[k]);
    if (f->step[k] < 0)
      st = frame_fail(f, k, AFV_EFORMAT, err, errlen, "step: %llu is not "
                      "in 0 .. 2^63-1", (unsigned long long)get_u64(b));
    else if (!isfinite(f->t[k]))
      st = frame_fail(f, k, AFV_EFORMAT, err, errlen, "time is not finite");
    else if (!runs_forward(f->step, f->t, k, why, sizeof why))
      st = frame_fail(f, k, AFV_EFORMAT, err, errlen, "%s", why);
  }
  f->nframes = (int)frames;
  return st;
}

int afv_traj_open(afv_traj_file *f, const char *path, char *err,
                  size_t errlen)
{
  afv_lines L;
  afv_traj head;
  int st, got;
  memset(f, 0, sizeof *f);
  memset(&head, 0, sizeof head);
  f->path = path;
  if ((st = afv_lines_open(&L, path, err, errlen)) != AFV_OK) return st;
  got = afv_lines_next(&L, err, errlen);
  if (got == 0 && ++L.lineno)
    st = line_fail(&L, AFV_EFORMAT, err, errlen, "empty file, not an afv "
                   "trajectory");
  else if (got < 0)
    st = L.status;
  else
    st = parse_traj_header(&L, &head, &f->format, err, errlen);
  if (st == AFV_OK && f->format == 1) {
    st = traj_read_text(&L, &head, err, errlen);
    f->text = head;
    f->step = head.step;
    f->t = head.t;
    f->nframes = head.nframes;
  }
  f->n = head.n;
  f->box = head.box;
  f->head = (long long)L.len + 1;
  f->record = AFV_TRAJ_FRAME_HEAD + (long long)AFV_TRAJ_CELL_BYTES * f->n;
  if (st == AFV_OK && f->format == 2 && !L.newline)
    f->nframes = 0;                       /* a header cut short: no frame */
  else if (st == AFV_OK && f->format == 2 && !(f->fp = fopen(path, "rb")))
    st = frame_fail(f, 0, AFV_EIO, err, errlen, "cannot open: %s",
                    strerror(errno));
  else if (st == AFV_OK && f->format == 2)
    st = traj_index(f, L.size, err, errlen);
  afv_lines_close(&L);
  if (st != AFV_OK) {
    if (f->format != 1) afv_traj_free(&head);
    afv_traj_close(f);
  }
  return st;
}

int afv_traj_frame(afv_traj_file *f, int k, double *r, double *theta,
                   char *err, size_t errlen)
{
  size_t n = (size_t)f->n, i;
  int st;
  if (k < 0 || k >= f->nframes) return AFV_EINVAL;
  if (f->format == 1) {
    memcpy(r, f->text.r + (size_t)k * 2 * n, 2 * n * sizeof(double));
    if (theta) memcpy(theta, f->text.theta + (size_t)k * n,
                      n * sizeof(double));
    return AFV_OK;
  }
  if (!f->buf && !(f->buf = malloc(n * AFV_TRAJ_CELL_BYTES)))
    return frame_fail(f, k, AFV_ENOMEM, err, errlen, "out of memory");
  if ((st = traj_fetch(f, k, AFV_TRAJ_FRAME_HEAD, f->buf,
                       n * AFV_TRAJ_CELL_BYTES, err, errlen)) != AFV_OK)
    return st;
  for (i = 0; i < n; i++) {
    const unsigned char *p = f->buf + i * AFV_TRAJ_CELL_BYTES;
    r[2*i] = get_f64(p);
    r[2*i+1] = get_f64(p + 8);
    if (theta) theta[i] = get_f32(p + 16);
    if (!isfinite(r[2*i]) || !isfinite(r[2*i+1]) || !isfinite(get_f32(p + 16)))
      return frame_fail(f, k, AFV_EFORMAT, err, errlen, "cell %lu: %s is "
                        "not finite", (unsigned long)i, !isfinite(r[2*i])
                        ? "x" : !isfinite(r[2*i+1]) ? "y" : "theta");
  }
  return AFV_OK;
}

void afv_traj_close(afv_traj_file *f)
{
  if (f->fp) fclose(f->fp);
  if (f->format == 1) {
    afv_traj_free(&f->text);
  } else {
    free(f->step);
    free(f->t);
  }
  free(f->buf);
  memset(f, 0, sizeof *f);
}

/* Every frame of an opened format-2 file into tr. */
static int traj_load(afv_traj_file *f, afv_traj *tr, char *err,
                     size_t errlen)
{
  size_t n = (size_t)f->n, frames = (size_t)f->nframes;
  int k, st = AFV_OK;
  tr->r = malloc((frames * n + 1) * 2 * sizeof(double));
  tr->theta = malloc((frames * n + 1) * sizeof(double));
  if (!tr->r || !tr->theta)
    return frame_fail(f, 0, AFV_ENOMEM, err, errlen, "out of memory for "
                      "%d frames", f->nframes);
  for (k = 0; st == AFV_OK && k < f->nframes; k++)
    st = afv_traj_frame(f, k, tr->r + (size_t)k * 2 * n,
                        tr->theta + (size_t)k * n, err, errlen);
  tr->step = f->step;
  tr->t = f->t;
  f->step = NULL;
  f->t = NULL;
  return st;
}

int afv_traj_read(const char *path, afv_traj *tr, char *err, size_t errlen)
{
  afv_traj_file f;
  int st;
  memset(tr, 0, sizeof *tr);
  if ((st = afv_traj_open(&f, path, err, errlen)) != AFV_OK) return st;
  if (f.format == 1) {
    *tr = f.text;
    memset(&f.text, 0, sizeof f.text);
  } else {
    tr->n = f.n;
    tr->box = f.box;
    tr->nframes = f.nframes;
    st = traj_load(&f, tr, err, errlen);
  }
  afv_traj_close(&f);
  if (st != AFV_OK) afv_traj_free(tr);
  return st;
}

/* ---- per-cell files ---------------------------------------------------- */
/* CELLS format (text): the first non-blank line is a header naming the
** columns, e.g. "# x y theta v0 P0"; names from afv_cell_columns, each at
** most once, x and y together or not at all.  Then one line per cell with
** one number per column (spaces, tabs or commas), '#' lines ignored. */
const char *const afv_cell_columns[AFV_NCOLS] = {
  "x", "y", "theta", "v0", "Dr", "KA", "KP", "A0", "P0"
};

void afv_cells_free(afv_cells *c)
{
  int k;
  for (k = 0; k < AFV_NCOLS; k++) free(c->col[k]);
  memset(c, 0, sizeof *c);
}

/* Parses the header's names into order[] (column index of each field).
** 1, or 0 with the offending name (if any) in name. */
static int parse_cells_header(char *line, afv_cells *c, int *order,
                              int *nf, char *name)
{
  char *tok = strtok(line + strspn(line, " \t#"), " \t,\r");
  *nf = 0;
  name[0] = 0;
  for (; tok; tok = strtok(NULL, " \t,\r")) {
    int k;
    for (k = 0; k < AFV_NCOLS; k++)
      if (strcmp(tok, afv_cell_columns[k]) == 0) break;
    shown(tok, name);
    if (k == AFV_NCOLS || c->has[k]) return 0;
    c->has[k] = 1;
    order[(*nf)++] = k;
  }
  name[0] = 0;
  return *nf > 0 && c->has[AFV_COL_X] == c->has[AFV_COL_Y];
}

static int cells_push(afv_cells *c, const int *order, int nf,
                      const double *v, int *cap)
{
  int k;
  if (c->n >= *cap) {
    int nc = *cap ? 2 * *cap : POINTS_INITIAL_CAP;
    for (k = 0; k < nf; k++) {
      double *q = realloc(c->col[order[k]], (size_t)nc * sizeof(double));
      if (!q) return AFV_ENOMEM;
      c->col[order[k]] = q;
    }
    *cap = nc;
  }
  for (k = 0; k < nf; k++) c->col[order[k]][c->n] = v[k];
  c->n++;
  return AFV_OK;
}

/* One line after the header: a cell (pushed), a comment or a blank. */
static int cells_line(const afv_lines *L, afv_cells *c, const int *order,
                      int nf, int *cap, char *err, size_t errlen)
{
  const char *names[AFV_NCOLS];
  double v[AFV_NCOLS];
  int k, f;
  if (is_comment(L->line)) return AFV_OK;
  for (k = 0; k < nf; k++) names[k] = afv_cell_columns[order[k]];
  f = number_row(L, v, nf, names, err, errlen);
  if (f <= 0) return f < 0 ? AFV_EFORMAT : AFV_OK;
  if (c->n >= AFV_CELLS_MAX)
    return line_fail(L, AFV_EFORMAT, err, errlen, "more than %d cells",
                     AFV_CELLS_MAX);
  if (cells_push(c, order, nf, v, cap) != AFV_OK)
    return line_fail(L, AFV_ENOMEM, err, errlen, "out of memory");
  return AFV_OK;
}

int afv_cells_read(const char *path, afv_cells *c, char *err, size_t errlen)
{
  afv_lines L;
  char name[40] = "";
  int order[AFV_NCOLS], nf = -1, cap = 0, st, got = 0;
  memset(c, 0, sizeof *c);
  if ((st = afv_lines_open(&L, path, err, errlen)) != AFV_OK) return st;
  while (st == AFV_OK && (got = afv_lines_next(&L, err, errlen)) > 0) {
    if (is_blank(L.line)) continue;
    if (nf >= 0) {
      st = cells_line(&L, c, order, nf, &cap, err, errlen);
    } else if (!is_comment(L.line)
               || !parse_cells_header(L.line, c, order, &nf, name)) {
      st = line_fail(&L, AFV_EFORMAT, err, errlen, "expected a header '# x "
                     "y [theta] [v0] [Dr] [KA] [KP] [A0] [P0]' (columns in "
                     "any order, each once, x and y together)%s%s",
                     name[0] ? "; bad column " : "", name);
      nf = 0;
    }
  }
  if (st == AFV_OK && got < 0) st = L.status;
  afv_lines_close(&L);
  if (st == AFV_OK && c->n == 0) {
    afv_errorf(err, errlen, "%s: no cells (a header line and at least one "
               "cell line are needed)", path);
    st = AFV_EFORMAT;
  }
  if (st != AFV_OK) afv_cells_free(c);
  return st;
}

int afv_cells_write(FILE *fp, const afv_cells *c)
{
  int i, k, first = 1;
  fputs("#", fp);
  for (k = 0; k < AFV_NCOLS; k++)
    if (c->has[k]) fprintf(fp, " %s", afv_cell_columns[k]);
  fputs("\n", fp);
  for (i = 0; i < c->n; i++) {
    first = 1;
    for (k = 0; k < AFV_NCOLS; k++)
      if (c->has[k]) {
        fprintf(fp, first ? "%.17g" : " %.17g", c->col[k][i]);
        first = 0;
      }
    fputs("\n", fp);
  }
  return ferror(fp) ? AFV_EIO : AFV_OK;
}

/* ---- checkpoints ------------------------------------------------------- */
/* CHECKPOINT format (text, exact):
**   # afv checkpoint 1
**   cells N / step S / time T / seed SEED
**   bytes NAME B      (one line per append-only output file)
**   x y theta         N lines, C99 hex floats (%a): exact doubles
**   end
** The final "end" line marks a complete file; afv_atomic_open/commit make
** sure a reader never sees a file without it anyway. */
void afv_checkpoint_free(afv_checkpoint *c)
{
  free(c->r);
  free(c->theta);
  memset(c, 0, sizeof *c);
}

int afv_checkpoint_write(const char *path, const afv_checkpoint *c)
{
  char tmp[4096];
  FILE *fp = afv_atomic_open(path, tmp, sizeof tmp);
  int i;
  if (!fp) return AFV_EIO;
  fprintf(fp, "# afv checkpoint 1\ncells %d\nstep %lld\ntime %a\nseed %llu\n",
          c->n, c->step, c->t, c->seed);
  for (i = 0; i < AFV_CKPT_FILES; i++)
    fprintf(fp, "bytes %s %lld\n", afv_checkpoint_files[i], c->bytes[i]);
  for (i = 0; i < c->n; i++)
    fprintf(fp, "%a %a %a\n", c->r[2*i], c->r[2*i+1], c->theta[i]);
  fputs("end\n", fp);
  return afv_atomic_commit(fp, tmp, path);
}

const char *const afv_checkpoint_files[AFV_CKPT_FILES] = {
  "trajectory.dat", "observables.csv", "trajectory.xyz"
};

/* The next line, which the format requires (what: what it should hold).
** AFV_OK, or a status with the message in err. */
static int ckpt_next(afv_lines *L, const char *what, char *err,
                     size_t errlen)
{
  int got = afv_lines_next(L, err, errlen);
  if (got > 0) return AFV_OK;
  if (got < 0) return L->status;
  L->lineno++;
  return line_fail(L, AFV_EFORMAT, err, errlen, "the file ends before %s "
                   "(incomplete file)", what);
}

/* The next line as exactly "NAME VALUE"; *value points into the line. */
static int ckpt_keyed(afv_lines *L, const char *name, char **value,
                      char *err, size_t errlen)
{
  char *w[3];
  int st = ckpt_next(L, name, err, errlen);
  if (st != AFV_OK) return st;
  if (split_words(L->line, w, 3) != 2 || strcmp(w[0], name) != 0)
    return line_fail(L, AFV_EFORMAT, err, errlen, "expected '%s VALUE'",
                     name);
  *value = w[1];
  return AFV_OK;
}

/* The seed: a whole decimal number in 0 .. 2^64-1. */
static int ckpt_seed(const afv_lines *L, const char *s,
                     unsigned long long *seed, char *err, size_t errlen)
{
  char *end, q[40];
  errno = 0;
  if (*s >= '0' && *s <= '9') *seed = strtoull(s, &end, 10);
  if (*s >= '0' && *s <= '9' && *end == 0 && errno != ERANGE) return AFV_OK;
  return line_fail(L, AFV_EFORMAT, err, errlen, "seed: '%s' is not an "
                   "integer in 0 .. 2^64-1", shown(s, q));
}

/* Lines 1 to 5: header, cells, step, time, seed. */
static int ckpt_head(afv_lines *L, afv_checkpoint *c, char *err,
                     size_t errlen)
{
  /* a cell line holds at least "0 0 0\n": 6 bytes */
  long long room = L->size / 6, n;
  char *v, why[64];
  int st = ckpt_next(L, "the header", err, errlen);
  if (st == AFV_OK && strcmp(L->line, "# afv checkpoint 1") != 0)
    st = line_fail(L, AFV_EFORMAT, err, errlen, "not an afv checkpoint "
                   "(expected '# afv checkpoint 1')");
  snprintf(why, sizeof why, "a file of %lld bytes holds no more cells",
           L->size);
  if (st == AFV_OK && (st = ckpt_keyed(L, "cells", &v, err, errlen)) == AFV_OK
      && !int_field(L, "cells", v, 1, room < AFV_CELLS_MAX ? room
                    : AFV_CELLS_MAX, why, &n, err, errlen))
    st = AFV_EFORMAT;
  if (st == AFV_OK) c->n = (int)n;
  if (st == AFV_OK && (st = ckpt_keyed(L, "step", &v, err, errlen)) == AFV_OK
      && !int_field(L, "step", v, 0, LLONG_MAX, "a long long", &c->step, err,
                    errlen))
    st = AFV_EFORMAT;
  if (st == AFV_OK && (st = ckpt_keyed(L, "time", &v, err, errlen)) == AFV_OK
      && !real_field(L, "time", v, &c->t, err, errlen))
    st = AFV_EFORMAT;
  if (st == AFV_OK && (st = ckpt_keyed(L, "seed", &v, err, errlen)) == AFV_OK)
    st = ckpt_seed(L, v, &c->seed, err, errlen);
  return st;
}

/* Lines 6 to 8: "bytes FILE SIZE", the files in afv_checkpoint_files order. */
static int ckpt_sizes(afv_lines *L, afv_checkpoint *c, char *err,
                      size_t errlen)
{
  char *w[4];
  int k, st = AFV_OK;
  for (k = 0; st == AFV_OK && k < AFV_CKPT_FILES; k++) {
    if ((st = ckpt_next(L, "'bytes FILE SIZE'", err, errlen)) != AFV_OK)
      break;
    if (split_words(L->line, w, 4) != 3 || strcmp(w[0], "bytes") != 0
        || strcmp(w[1], afv_checkpoint_files[k]) != 0)
      st = line_fail(L, AFV_EFORMAT, err, errlen, "expected 'bytes %s SIZE'",
                     afv_checkpoint_files[k]);
    else if (!int_field(L, afv_checkpoint_files[k], w[2], 0, LLONG_MAX,
                        "a long long", &c->bytes[k], err, errlen))
      st = AFV_EFORMAT;
  }
  return st;
}

/* The n cell lines "x y theta", then "end" and nothing after it. */
static int ckpt_state(afv_lines *L, afv_checkpoint *c, char *err,
                      size_t errlen)
{
  static const char *const names[3] = {"x", "y", "theta"};
  double v[3];
  int i, st = AFV_OK;
  c->r = malloc((size_t)c->n * 2 * sizeof(double));
  c->theta = malloc((size_t)c->n * sizeof(double));
  if (!c->r || !c->theta)
    return line_fail(L, AFV_ENOMEM, err, errlen, "out of memory for %d "
                     "cells", c->n);
  for (i = 0; st == AFV_OK && i < c->n; i++) {
    if ((st = ckpt_next(L, "the cell lines end", err, errlen)) != AFV_OK)
      break;
    if (number_row(L, v, 3, names, err, errlen) == 3) {
      c->r[2*i] = v[0];
      c->r[2*i+1] = v[1];
      c->theta[i] = v[2];
    } else if (is_blank(L->line)) {
      st = line_fail(L, AFV_EFORMAT, err, errlen, "expected 'x y theta' of "
                     "cell %d", i);
    } else {
      st = AFV_EFORMAT;
    }
  }
  if (st == AFV_OK && (st = ckpt_next(L, "'end'", err, errlen)) == AFV_OK
      && strcmp(L->line, "end") != 0)
    st = line_fail(L, AFV_EFORMAT, err, errlen, "expected 'end' after %d "
                   "cells", c->n);
  if (st == AFV_OK && afv_lines_next(L, err, errlen) != 0)
    st = L->status ? L->status
         : line_fail(L, AFV_EFORMAT, err, errlen, "text after 'end'");
  return st;
}

int afv_checkpoint_read(const char *path, afv_checkpoint *c, char *err,
                        size_t errlen)
{
  afv_lines L;
  int st;
  memset(c, 0, sizeof *c);
  if ((st = afv_lines_open(&L, path, err, errlen)) != AFV_OK) return st;
  if ((st = ckpt_head(&L, c, err, errlen)) == AFV_OK
      && (st = ckpt_sizes(&L, c, err, errlen)) == AFV_OK)
    st = ckpt_state(&L, c, err, errlen);
  afv_lines_close(&L);
  if (st != AFV_OK) afv_checkpoint_free(c);
  return st;
}

int afv_checkpoint_check_files(const char *path, const afv_checkpoint *c,
                               char *err, size_t errlen)
{
  const char *slash = strrchr(path, '/');
  int dirlen = slash ? (int)(slash - path) + 1 : 0, k;
  for (k = 0; k < AFV_CKPT_FILES; k++) {
    char file[4096];
    struct stat sb;
    int missing;
    if (c->bytes[k] == 0) continue;        /* not written (xyz off) */
    if (snprintf(file, sizeof file, "%.*s%s", dirlen, path,
                 afv_checkpoint_files[k]) >= (int)sizeof file) {
      afv_errorf(err, errlen, "%s: path too long", path);
      return AFV_EIO;
    }
    if ((missing = stat(file, &sb) != 0) || !S_ISREG(sb.st_mode)) {
      afv_errorf(err, errlen, "%s:%d: bytes %s: %lld, but %s: %s", path,
                 AFV_CKPT_BYTES_LINE + k, afv_checkpoint_files[k],
                 c->bytes[k], file, missing ? strerror(errno)
                 : "not a regular file");
      return AFV_EFORMAT;
    }
    if ((long long)sb.st_size < c->bytes[k]) {
      afv_errorf(err, errlen, "%s:%d: bytes %s: %lld, larger than the file "
                 "(%lld bytes): not the file this checkpoint was written "
                 "with", path, AFV_CKPT_BYTES_LINE + k,
                 afv_checkpoint_files[k], c->bytes[k],
                 (long long)sb.st_size);
      return AFV_EFORMAT;
    }
  }
  return AFV_OK;
}

/* ---- T1 reference --------------------------------------------------------- */
/* T1 REFERENCE format (text): C(0), the contacting pairs at step 0 of a run
** (analysis.c, afv_t1):
**   # afv t1 reference: contacting pairs at step 0
**   M                 the number of pairs
**   i j               M lines, 0 <= i < j < N, in increasing order of (i, j)
** The order is the one afv_t1_count merges in, so the reader checks it. */
static const char t1_header[] = "# afv t1 reference: contacting pairs at "
                                "step 0";

int afv_t1_reference_write(const char *path, const afv_t1 *t)
{
  char tmp[4096];
  FILE *fp = afv_atomic_open(path, tmp, sizeof tmp);
  int k;
  if (!fp) return AFV_EIO;
  fprintf(fp, "%s\n%d\n", t1_header, t->n_pairs0);
  for (k = 0; k < t->n_pairs0; k++)
    fprintf(fp, "%d %d\n", t->pairs0[2*k], t->pairs0[2*k+1]);
  return afv_atomic_commit(fp, tmp, path);
}

/* Pair line k: "i j" with 0 <= i < j < n, after the pair prev (NULL for
** the first). */
static int t1_pair(afv_lines *L, int n, const int *prev, int *q, char *err,
                   size_t errlen)
{
  char *w[3];
  long long i, j;
  if (split_words(L->line, w, 3) != 2)
    return line_fail(L, AFV_EFORMAT, err, errlen, "expected a pair 'i j'");
  if (!int_field(L, "i", w[0], 0, n - 1, "the cells of the run", &i, err,
                 errlen)
      || !int_field(L, "j", w[1], i + 1, n - 1, "the cells of the run", &j,
                    err, errlen))
    return AFV_EFORMAT;
  q[0] = (int)i;
  q[1] = (int)j;
  if (prev && (q[0] < prev[0] || (q[0] == prev[0] && q[1] <= prev[1])))
    return line_fail(L, AFV_EFORMAT, err, errlen, "pair %d %d is not after "
                     "the pair %d %d (pairs are in increasing order, each "
                     "once)", q[0], q[1], prev[0], prev[1]);
  return AFV_OK;
}

/* Lines 1 and 2: the header and the count M (at most what the file can
** hold: a pair line has at least 4 bytes). */
static int t1_head(afv_lines *L, long long *m, char *err, size_t errlen)
{
  long long room = L->size / 4;
  char *w[2], why[64];
  int st = ckpt_next(L, "the header", err, errlen);
  if (st == AFV_OK && strcmp(L->line, t1_header) != 0)
    st = line_fail(L, AFV_EFORMAT, err, errlen, "not an afv t1 reference "
                   "(expected '%s')", t1_header);
  if (st == AFV_OK) st = ckpt_next(L, "the number of pairs", err, errlen);
  if (st == AFV_OK && split_words(L->line, w, 2) != 1)
    st = line_fail(L, AFV_EFORMAT, err, errlen, "expected the number of "
                   "pairs");
  snprintf(why, sizeof why, "a file of %lld bytes holds no more pairs",
           L->size);
  if (st == AFV_OK && !int_field(L, "pairs", w[0], 0, room < INT_MAX / 2
                                 ? room : INT_MAX / 2, why, m, err, errlen))
    st = AFV_EFORMAT;
  return st;
}

int afv_t1_reference_read(const char *path, int n, afv_t1 *t, char *err,
                          size_t errlen)
{
  afv_lines L;
  long long m = 0, k;
  int *pairs = NULL, st;
  if ((st = afv_lines_open(&L, path, err, errlen)) != AFV_OK) return st;
  if ((st = t1_head(&L, &m, err, errlen)) == AFV_OK
      && !(pairs = malloc((size_t)(m > 0 ? m : 1) * 2 * sizeof(int))))
    st = line_fail(&L, AFV_ENOMEM, err, errlen, "out of memory");
  for (k = 0; st == AFV_OK && k < m; k++)
    if ((st = ckpt_next(&L, "the last pair", err, errlen)) == AFV_OK)
      st = t1_pair(&L, n, k > 0 ? pairs + 2 * (k - 1) : NULL, pairs + 2 * k,
                   err, errlen);
  if (st == AFV_OK && afv_lines_next(&L, err, errlen) != 0)
    st = L.status ? L.status
         : line_fail(&L, AFV_EFORMAT, err, errlen, "more pairs than the "
                     "count on line 2 (%lld)", m);
  afv_lines_close(&L);
  if (st != AFV_OK) {
    free(pairs);
    return st;
  }
  free(t->pairs0);
  t->pairs0 = pairs;
  t->n_pairs0 = (int)m;
  return AFV_OK;
}
