/*
** io.c -- file formats: cell centres (POINTS), atomic writes, trajectories,
** per-cell values (CELLS) and checkpoints.  Each format is described where
** it is read or written.
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
    if (!strchr(line, '\n') && feof(fp)) {
      /* the last line has no newline: an interrupted writer; its frame is
      ** incomplete and is dropped below */
      row = -1;
      break;
    }
    if (lineno == 1) {
      if (!parse_traj_header(line, tr)) {
        afv_errorf(err, errlen, "%s:1: not an afv trajectory header", path);
        st = AFV_EFORMAT;
      }
      continue;
    }
    if (sscanf(line, "# step %lld time %lf", &step, &t) == 2) {
      if (tr->nframes > 0 && row != tr->n) {
        afv_errorf(err, errlen, "%s:%d: the frame before this line has %d "
                   "of %d cells", path, lineno, row, tr->n);
        st = AFV_EFORMAT;
        break;
      }
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
  /* a last frame cut short (an interrupted writer) is dropped; a short
  ** frame anywhere else is an error (above) */
  if (st == AFV_OK && tr->nframes > 0 && row != tr->n) tr->nframes--;
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

/* Parses the header's names into order[] (column index of each field). */
static int parse_cells_header(char *line, afv_cells *c, int *order,
                              int *nf, char *name, size_t namelen)
{
  char *tok = strtok(line + strspn(line, " \t#"), " \t,\r\n");
  *nf = 0;
  for (; tok; tok = strtok(NULL, " \t,\r\n")) {
    int k;
    for (k = 0; k < AFV_NCOLS; k++)
      if (strcmp(tok, afv_cell_columns[k]) == 0) break;
    snprintf(name, namelen, "%s", tok);
    if (k == AFV_NCOLS || c->has[k] || *nf >= AFV_NCOLS) return 0;
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

int afv_read_cells(const char *path, afv_cells *c, char *err, size_t errlen)
{
  FILE *fp = fopen(path, "r");
  char line[4096], text[40];
  double v[AFV_NCOLS];
  int order[AFV_NCOLS], nf = -1, lineno = 0, cap = 0, st = AFV_OK, k;
  memset(c, 0, sizeof *c);
  if (!fp) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
  while (st == AFV_OK && fgets(line, sizeof line, fp)) {
    char *bad = NULL;
    int fields;
    lineno++;
    if (line[strspn(line, " \t\r\n")] == 0) continue;
    if (nf < 0) {                             /* the header */
      if (line[strspn(line, " \t")] != '#'
          || !parse_cells_header(line, c, order, &nf, text, sizeof text)) {
        afv_errorf(err, errlen, "%s:%d: expected a header '# x y [theta] "
                   "[v0] [Dr] [KA] [KP] [A0] [P0]' (columns in any order, "
                   "x and y together)%s%s", path, lineno,
                   text[0] && nf >= 0 ? "; bad column " : "", text);
        st = AFV_EFORMAT;
      }
      continue;
    }
    if (line[strspn(line, " \t")] == '#') continue;
    fields = parse_fields(line, v, nf, &bad);
    if (fields < 0) {
      field_text(bad, text, sizeof text);
      afv_errorf(err, errlen, "%s:%d: '%s' is not a number", path, lineno,
                 text);
      st = AFV_EFORMAT;
    } else if (fields != nf) {
      afv_errorf(err, errlen, "%s:%d: expected %d columns, found %d", path,
                 lineno, nf, fields);
      st = AFV_EFORMAT;
    } else {
      for (k = 0; k < nf; k++)
        if (!isfinite(v[k])) break;
      if (k < nf) {
        afv_errorf(err, errlen, "%s:%d: %s is not finite", path, lineno,
                   afv_cell_columns[order[k]]);
        st = AFV_EFORMAT;
      } else if ((st = cells_push(c, order, nf, v, &cap)) != AFV_OK) {
        afv_errorf(err, errlen, "%s: out of memory", path);
      }
    }
  }
  fclose(fp);
  if (st == AFV_OK && c->n == 0) {
    afv_errorf(err, errlen, "%s: no cells (a header line and at least one "
               "cell line are needed)", path);
    st = AFV_EFORMAT;
  }
  if (st != AFV_OK) afv_cells_free(c);
  return st;
}

int afv_write_cells(FILE *fp, const afv_cells *c)
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

static int ckpt_fail(const char *path, int lineno, const char *what,
                     char *err, size_t errlen)
{
  afv_errorf(err, errlen, "%s:%d: %s", path, lineno, what);
  return AFV_EFORMAT;
}

int afv_checkpoint_read(const char *path, afv_checkpoint *c, char *err,
                        size_t errlen)
{
  FILE *fp = fopen(path, "r");
  char line[512], name[64], *bad;
  double v[3];
  int lineno = 0, i, st = AFV_OK, k;
  memset(c, 0, sizeof *c);
  if (!fp) {
    afv_errorf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return AFV_EIO;
  }
#define NEXT_LINE() (lineno++, fgets(line, sizeof line, fp) != NULL)
  if (!NEXT_LINE() || strcmp(line, "# afv checkpoint 1\n") != 0)
    st = ckpt_fail(path, lineno, "not an afv checkpoint", err, errlen);
  if (st == AFV_OK && !(NEXT_LINE() && sscanf(line, "cells %d", &c->n) == 1
                        && c->n >= 0))
    st = ckpt_fail(path, lineno, "expected 'cells N'", err, errlen);
  if (st == AFV_OK && !(NEXT_LINE() && sscanf(line, "step %lld", &c->step) == 1))
    st = ckpt_fail(path, lineno, "expected 'step S'", err, errlen);
  if (st == AFV_OK && !(NEXT_LINE() && strncmp(line, "time ", 5) == 0
                        && parse_fields(line + 5, &c->t, 1, &bad) == 1))
    st = ckpt_fail(path, lineno, "expected 'time T'", err, errlen);
  if (st == AFV_OK && !(NEXT_LINE() && sscanf(line, "seed %llu", &c->seed) == 1))
    st = ckpt_fail(path, lineno, "expected 'seed SEED'", err, errlen);
  for (k = 0; st == AFV_OK && k < AFV_CKPT_FILES; k++)
    if (!(NEXT_LINE() && sscanf(line, "bytes %63s %lld", name, &c->bytes[k]) == 2
          && strcmp(name, afv_checkpoint_files[k]) == 0 && c->bytes[k] >= 0))
      st = ckpt_fail(path, lineno, "expected 'bytes FILE SIZE'", err, errlen);
  if (st == AFV_OK) {
    c->r = malloc((size_t)(2 * c->n + 1) * sizeof(double));
    c->theta = malloc((size_t)(c->n + 1) * sizeof(double));
    if (!c->r || !c->theta) st = AFV_ENOMEM;
  }
  for (i = 0; st == AFV_OK && i < c->n; i++)
    if (NEXT_LINE() && parse_fields(line, v, 3, &bad) == 3) {
      c->r[2*i] = v[0];
      c->r[2*i+1] = v[1];
      c->theta[i] = v[2];
    } else {
      st = ckpt_fail(path, lineno, "expected 'x y theta'", err, errlen);
    }
  if (st == AFV_OK && !(NEXT_LINE() && strcmp(line, "end\n") == 0))
    st = ckpt_fail(path, lineno, "missing 'end' (incomplete file)", err,
                   errlen);
#undef NEXT_LINE
  fclose(fp);
  if (st != AFV_OK) afv_checkpoint_free(c);
  return st;
}
