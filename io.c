/*
** io.c -- file formats: reading cell centres.
**
** POINTS format: one cell per line, columns "x y" separated by spaces, tabs
** or commas; blank lines and lines starting with '#' are ignored.  Errors
** name the file and line.
*/
#include "afv.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static int is_sep(int c)
{
  return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n';
}

/* Parses up to `want` numbers from a line into v; returns how many fields
** the line has (counting past `want`), or -1 with *bad set to the first
** field that is not a number. */
static int parse_fields(char *line, double *v, int want, char **bad)
{
  int count = 0;
  char *p = line;
  for (;;) {
    char *end;
    double x;
    while (*p && is_sep((unsigned char)*p)) p++;
    if (!*p) return count;
    errno = 0;
    x = strtod(p, &end);
    if (end == p || (*end && !is_sep((unsigned char)*end))) {
      *bad = p;
      return -1;
    }
    if (count < want) v[count] = x;
    count++;
    p = end;
  }
}

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

/* Reads the field that strtod stopped at, for the message: up to the next
** separator, at most 32 characters. */
static void field_text(const char *p, char *out, size_t len)
{
  size_t k = 0;
  while (p[k] && !is_sep((unsigned char)p[k]) && k + 1 < len && k < 32) {
    out[k] = p[k];
    k++;
  }
  out[k] = 0;
}

int afv_read_points(const char *path, int *n_out, double **r_out, char *err,
                    size_t errlen)
{
  FILE *fp = fopen(path, "r");
  char line[4096], text[40];
  double *r = NULL, v[2];
  int n = 0, cap = 0, lineno = 0, st = AFV_OK;
  *n_out = 0;
  *r_out = NULL;
  if (!fp) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
  while (fgets(line, sizeof line, fp)) {
    char *bad = NULL;
    int fields;
    lineno++;
    if (!strchr(line, '\n') && !feof(fp)) {
      afv_errorf(err, errlen, "%s:%d: line longer than %d characters", path,
                 lineno, (int)sizeof line - 2);
      st = AFV_EFORMAT;
      break;
    }
    if (line[strspn(line, " \t\r\n")] == '#') continue;
    fields = parse_fields(line, v, 2, &bad);
    if (fields == 0) continue;
    if (fields < 0) {
      field_text(bad, text, sizeof text);
      afv_errorf(err, errlen, "%s:%d: '%s' is not a number", path, lineno,
                 text);
      st = AFV_EFORMAT;
      break;
    }
    if (fields != 2) {
      afv_errorf(err, errlen, "%s:%d: expected 2 columns (x y), found %d",
                 path, lineno, fields);
      st = AFV_EFORMAT;
      break;
    }
    if (!isfinite(v[0]) || !isfinite(v[1])) {
      afv_errorf(err, errlen, "%s:%d: coordinate is not finite", path,
                 lineno);
      st = AFV_EFORMAT;
      break;
    }
    if ((st = push_point(&r, &n, &cap, v[0], v[1])) != AFV_OK) {
      afv_errorf(err, errlen, "%s: out of memory", path);
      break;
    }
  }
  if (st == AFV_OK && ferror(fp)) {
    afv_errorf(err, errlen, "%s: read error", path);
    st = AFV_EIO;
  }
  fclose(fp);
  if (st != AFV_OK) {
    free(r);
    return st;
  }
  *n_out = n;
  *r_out = r;
  return AFV_OK;
}

/* ---- atomic files ------------------------------------------------------ */
/* A file is written as PATH.tmp and renamed over PATH only when complete:
** rename is atomic on POSIX file systems, so a reader (or a resumed run)
** sees the old file or the new one, never half of one. */
FILE *afv_atomic_open(const char *path, char *tmp, size_t tmplen)
{
  if ((size_t)snprintf(tmp, tmplen, "%s.tmp", path) >= tmplen) return NULL;
  return fopen(tmp, "w");
}

int afv_atomic_commit(FILE *fp, const char *tmp, const char *path)
{
  int bad = fflush(fp) != 0 || ferror(fp);
  bad |= fclose(fp) != 0;
  if (bad || rename(tmp, path) != 0) {
    remove(tmp);
    return AFV_EIO;
  }
  return AFV_OK;
}

/* ---- trajectories ------------------------------------------------------ */
/* TRAJECTORY format (text, numpy- and gnuplot-readable):
**   # afv trajectory cells N box open            (or: box periodic LX LY)
** then per frame
**   # step S time T
**   x y theta        N lines: unwrapped centre and polarity angle (radians)
**   <two blank lines> (gnuplot's "index" separator)
** numpy: np.loadtxt(f).reshape(-1, N, 3); gnuplot: plot f index K u 1:2 */
int afv_traj_write_header(FILE *fp, int n, const afv_box *b)
{
  if (b && b->periodic)
    fprintf(fp, "# afv trajectory cells %d box periodic %.17g %.17g\n", n,
            b->Lx, b->Ly);
  else
    fprintf(fp, "# afv trajectory cells %d box open\n", n);
  return ferror(fp) ? AFV_EIO : AFV_OK;
}

int afv_traj_write_frame(FILE *fp, long long step, double t, int n,
                         const double *r, const double *theta)
{
  int i;
  fprintf(fp, "# step %lld time %.17g\n", step, t);
  for (i = 0; i < n; i++)
    fprintf(fp, "%.17g %.17g %.17g\n", r[2*i], r[2*i+1],
            theta ? theta[i] : 0.0);
  fputs("\n\n", fp);
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

static int parse_traj_header(const char *line, afv_traj *tr)
{
  char kind[16];
  double lx, ly;
  if (sscanf(line, "# afv trajectory cells %d box %15s %lf %lf", &tr->n, kind,
             &lx, &ly) == 4 && strcmp(kind, "periodic") == 0) {
    tr->box.periodic = 1;
    tr->box.Lx = lx;
    tr->box.Ly = ly;
    return tr->n >= 0;
  }
  tr->box.periodic = 0;
  return sscanf(line, "# afv trajectory cells %d box %15s", &tr->n, kind) == 2
         && strcmp(kind, "open") == 0 && tr->n >= 0;
}

/* Makes room for one more frame (capacity doubles). */
static int traj_grow(afv_traj *tr, int *cap)
{
  int nc;
  void *a, *b, *c, *d;
  if (tr->nframes < *cap) return AFV_OK;
  nc = *cap ? 2 * *cap : 4;
  a = realloc(tr->step, (size_t)nc * sizeof *tr->step);
  if (a) tr->step = a;
  b = realloc(tr->t, (size_t)nc * sizeof *tr->t);
  if (b) tr->t = b;
  c = realloc(tr->r, (size_t)nc * (size_t)(2 * tr->n + 1) * sizeof(double));
  if (c) tr->r = c;
  d = realloc(tr->theta, (size_t)nc * (size_t)(tr->n + 1) * sizeof(double));
  if (d) tr->theta = d;
  if (!a || !b || !c || !d) return AFV_ENOMEM;
  *cap = nc;
  return AFV_OK;
}

int afv_traj_read(const char *path, afv_traj *tr, char *err, size_t errlen)
{
  FILE *fp = fopen(path, "r");
  char line[1024];
  int lineno = 0, cap = 0, row = 0, st = AFV_OK;
  memset(tr, 0, sizeof *tr);
  if (!fp) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
  while (st == AFV_OK && fgets(line, sizeof line, fp)) {
    double v[3];
    char *bad;
    long long step;
    double t;
    int f;
    lineno++;
    if (lineno == 1) {
      if (!parse_traj_header(line, tr)) {
        afv_errorf(err, errlen, "%s:1: not an afv trajectory header", path);
        st = AFV_EFORMAT;
      }
      continue;
    }
    if (sscanf(line, "# step %lld time %lf", &step, &t) == 2) {
      if (tr->nframes > 0 && row != tr->n) break;
      if ((st = traj_grow(tr, &cap)) != AFV_OK) break;
      tr->step[tr->nframes] = step;
      tr->t[tr->nframes] = t;
      tr->nframes++;
      row = 0;
      continue;
    }
    f = parse_fields(line, v, 3, &bad);
    if (f == 0 || line[strspn(line, " \t\r\n")] == '#') continue;
    if (f != 3 || tr->nframes == 0 || row >= tr->n) {
      afv_errorf(err, errlen, "%s:%d: expected a frame line 'x y theta'",
                 path, lineno);
      st = AFV_EFORMAT;
      break;
    }
    f = tr->nframes - 1;
    tr->r[(size_t)f * 2 * tr->n + 2 * row] = v[0];
    tr->r[(size_t)f * 2 * tr->n + 2 * row + 1] = v[1];
    tr->theta[(size_t)f * tr->n + row] = v[2];
    row++;
  }
  fclose(fp);
  /* a last frame cut short (an interrupted writer) is dropped */
  if (st == AFV_OK && tr->nframes > 0 && row != tr->n) tr->nframes--;
  if (st != AFV_OK) afv_traj_free(tr);
  return st;
}
