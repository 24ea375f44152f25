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
