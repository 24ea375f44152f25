/*
** cli.c -- option parsing and messages shared by the commands of afv
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* ---- the build ---------------------------------------------------------- */
/* "0.3.0 (commit 0123456789ab)" when built from a git checkout (the
** Makefile passes -DAFV_COMMIT), else "0.3.0". */
const char *afv_build_version(void)
{
#ifdef AFV_COMMIT
  return AFV_VERSION " (commit " AFV_COMMIT ")";
#else
  return AFV_VERSION;
#endif
}

/* ---- messages and numbers ---------------------------------------------- */
const char *command_name = NULL;

/* "afv COMMAND: " (or "afv: " before a command is known) on stderr. */
static void message_prefix(void)
{
  if (command_name) fprintf(stderr, "afv %s: ", command_name);
  else fputs("afv: ", stderr);
}

int bad_input(const char *msg)
{
  size_t m = command_name ? strlen(command_name) : 0;
  if (m && strncmp(msg, command_name, m) == 0 && msg[m] == ':')
    fprintf(stderr, "afv %s\n", msg);   /* msg names the command itself */
  else {
    message_prefix();
    fprintf(stderr, "%s\n", msg);
  }
  return EXIT_BAD_INPUT;
}

void cli_errorf(const char *fmt, ...)
{
  va_list ap;
  message_prefix();
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}

const char *real_problem(const char *text, double *out)
{
  char *end;
  errno = 0;
  *out = strtod(text, &end);
  if (end == text || *end) return "is not a number";
  if (isnan(*out))
    return "is not a number (nan)";
  if (isinf(*out) || (errno == ERANGE && fabs(*out) > 1))
    return "is not a finite number (beyond the largest double, "
           "1.7976931348623157e+308)";
  if (errno == ERANGE || (*out != 0 && fabs(*out) < DBL_MIN))
    return "is closer to 0 than the smallest normal double, "
           "2.2250738585072014e-308 (use 0, or a normal number)";
  return NULL;
}

const char *integral_problem(const char *text, long long lo, long long hi,
                             long long *out)
{
  static char why[160];
  const char *p;
  char *end;
  double x;
  errno = 0;
  *out = strtoll(text, &end, 10);
  if (end != text && !*end && errno != ERANGE && *out >= lo && *out <= hi)
    return NULL;
  if (end != text && !*end && errno != ERANGE) {
    snprintf(why, sizeof why, "is outside %lld .. %lld", lo, hi);
    return why;
  }
  if ((p = real_problem(text, &x)) != NULL) return p;
  if (x != floor(x)) return "is not an integer (it has a fractional part)";
  /* (double)LLONG_MAX rounds up to 2^63, which a long long cannot hold:
  ** the cast below needs x < 2^63 as well */
  if (!(x >= (double)lo && x <= (double)hi && x < 9223372036854775808.0)) {
    snprintf(why, sizeof why, "is outside %lld .. %lld", lo, hi);
    return why;
  }
  *out = (long long)x;   /* integral and in range: exact */
  return NULL;
}

/* Edit distance (insertions, deletions, substitutions, transpositions of
** neighbours) between a and b, at most 32 characters each, else 99. */
static int edit_distance(const char *a, const char *b)
{
  int d[33][33], i, j, m = (int)strlen(a), n = (int)strlen(b);
  if (m > 32 || n > 32) return 99;
  for (i = 0; i <= m; i++) d[i][0] = i;
  for (j = 0; j <= n; j++) d[0][j] = j;
  for (i = 1; i <= m; i++)
    for (j = 1; j <= n; j++) {
      int best = d[i-1][j-1] + (a[i-1] != b[j-1]);
      if (d[i-1][j] + 1 < best) best = d[i-1][j] + 1;
      if (d[i][j-1] + 1 < best) best = d[i][j-1] + 1;
      if (i > 1 && j > 1 && a[i-1] == b[j-2] && a[i-2] == b[j-1]
          && d[i-2][j-2] + 1 < best)
        best = d[i-2][j-2] + 1;
      d[i][j] = best;
    }
  return d[m][n];
}

const char *nearest_option(const char *opt, const char *text)
{
  static char best[48];
  const char *p = text, *want = opt;
  int best_d = 99;
  while (*want == '-') want++;
  best[0] = 0;
  while ((p = strstr(p, "--")) != NULL) {
    char name[40];
    size_t m = 0;
    int d;
    p += 2;
    while (m < sizeof name - 1 && (isalnum((unsigned char)p[m])
                                   || p[m] == '_' || p[m] == '-'))
      m++;
    memcpy(name, p, m);
    name[m] = 0;
    p += m;
    if (!m || (d = edit_distance(want, name)) >= best_d || d == 0
        || d > 2 || d >= (int)strlen(want))
      continue;
    best_d = d;
    snprintf(best, sizeof best, "--%s", name);
  }
  return best[0] ? best : NULL;
}

int unknown_option(const char *opt, const char *help_text,
                   const char *more_text)
{
  char first[48] = "";
  const char *near = nearest_option(opt, help_text), *other;
  if (near) {   /* nearest_option's buffer is reused by the next call */
    snprintf(first, sizeof first, "%s", near);
    near = first;
  }
  if (more_text && (other = nearest_option(opt, more_text)) != NULL
      && (!near || edit_distance(opt, other) < edit_distance(opt, near)))
    near = other;
  if (near)
    cli_errorf("unknown option '%s' (did you mean %s? see afv %s --help)",
               opt, near, command_name ? command_name : "--help");
  else
    cli_errorf("unknown option '%s' (see afv %s --help)", opt,
               command_name ? command_name : "--help");
  return EXIT_BAD_INPUT;
}

const char *exact_text(double x, char *buf, size_t len)
{
  /* at least the digits before the point, so that 200 is "200", not
  ** %.1g's "2e+02" (%g writes an exponent when it has fewer digits than
  ** the number before its point) */
  double whole = fabs(x) >= 1 && fabs(x) < 1e17 ? floor(log10(fabs(x))) + 1
                                                : 1;
  int digits;
  for (digits = (int)whole; digits < 17; digits++) {
    snprintf(buf, len, "%.*g", digits, x);
    if (strtod(buf, NULL) == x) return buf;
  }
  snprintf(buf, len, "%.17g", x);
  return buf;
}

/* Parses a whole string as a finite double; message names the option. */
int parse_double(const char *opt, const char *text, double *out)
{
  const char *why = real_problem(text, out);
  if (why) {
    cli_errorf("%s: '%s' %s", opt, text, why);
    return 0;
  }
  return 1;
}

/* ---- model options shared by eval and check ---------------------------- */
const char *model_help =
  "model options (paper symbols; lengths in units of l):\n"
  "  --l VALUE        maximal cell radius l (default 1)\n"
  "  --A0 VALUE       preferred area A0 (default 3.141592653589793 = pi,\n"
  "                   a disk of radius 1; it does not follow --l)\n"
  "  --P0 VALUE       preferred perimeter P0 (default 4.8)\n"
  "  --KA VALUE       area modulus KA (default 1)\n"
  "  --KP VALUE       perimeter modulus KP (default 1)\n"
  "  --Lambda VALUE   extra tension of the free (arc) boundary (default 0.2)\n"
  "  --box open       open space (default)\n"
  "  --box LX,LY      periodic Lx x Ly box, minimum image; each side >= 4l;\n"
  "                   positions outside the box are wrapped\n"
  "  --cap DELTA      contact cap (default 0 = exact -grad E): PyAFV's\n"
  "                   contact truncation delta, the arc-end velocities use\n"
  "                   max(sqrt(4l^2-d^2), DELTA) in the area, perimeter and\n"
  "                   arc terms (the same forces as PyAFV).  With DELTA > 0\n"
  "                   the force is NOT the gradient of E (E is unchanged).\n";

static int parse_box(const char *text, afv_box *b)
{
  char *end;
  if (strcmp(text, "open") == 0) {
    b->periodic = 0;
    return 1;
  }
  b->periodic = 1;
  errno = 0;
  b->Lx = strtod(text, &end);
  if (end != text && *end == ',') {
    const char *ys = end + 1;
    b->Ly = strtod(ys, &end);
    if (end != ys && !*end && errno != ERANGE && isfinite(b->Lx)
        && isfinite(b->Ly) && b->Lx > 0 && b->Ly > 0)
      return 1;
  }
  cli_errorf("--box: '%s' is neither 'open' nor LX,LY with positive "
             "numbers", text);
  return 0;
}

/* If argv[*k] is a model option, consumes it (and its value) and returns 1;
** returns 0 if it is not one, -1 on a bad value (message printed). */
int model_option(int argc, char **argv, int *k, afv_params *p,
                        afv_box *b)
{
  static const char *names[] = {"--l", "--A0", "--P0", "--KA", "--KP",
                                "--Lambda", "--cap"};
  double *slots[7];
  const char *opt = argv[*k];
  int m;
  slots[0] = &p->l; slots[1] = &p->A0; slots[2] = &p->P0; slots[3] = &p->KA;
  slots[4] = &p->KP; slots[5] = &p->Lambda; slots[6] = &p->cap;
  for (m = 0; m < 7; m++)
    if (strcmp(opt, names[m]) == 0) break;
  if (m == 7 && strcmp(opt, "--box") != 0) return 0;
  if (*k + 1 >= argc) {
    cli_errorf("%s needs a value", opt);
    return -1;
  }
  (*k)++;
  if (m == 7) return parse_box(argv[*k], b) ? 1 : -1;
  return parse_double(opt, argv[*k], slots[m]) ? 1 : -1;
}

/* Range checks of the model options, with messages naming the option. */
int model_valid(const afv_params *p, const afv_box *b)
{
  if (p->l <= 0) return !bad_input("--l: must be > 0");
  if (p->KA < 0) return !bad_input("--KA: must be >= 0");
  if (p->KP < 0) return !bad_input("--KP: must be >= 0");
  if (p->cap < 0) return !bad_input("--cap: must be >= 0");
  if (b->periodic && (b->Lx < 4 * p->l || b->Ly < 4 * p->l)) {
    /* %.17g: a side one ulp below 4l must not print as 4l */
    cli_errorf("--box: %.17g,%.17g is smaller than 4l = %.17g, too small "
               "for the minimum-image convention", b->Lx, b->Ly, 4 * p->l);
    return 0;
  }
  return 1;
}

/* Loads POINTS and wraps them into a periodic box. */
int load_points(const char *path, const afv_box *b, int *n, double **r)
{
  char err[512];
  int i;
  if (afv_points_read(path, n, r, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  for (i = 0; i < *n; i++) afv_wrap(b, &(*r)[2*i], &(*r)[2*i+1]);
  return 1;
}

int library_error(int st, const afv_geom *g)
{
  int i, j;
  if (st == AFV_ECOINCIDENT) {
    afv_geom_bad_pair(g, &i, &j);
    cli_errorf("cells %d and %d (0-based, input order) have the same "
               "centre", i, j);
  } else
    cli_errorf("%s", afv_strerror(st));
  return EXIT_BAD_INPUT;
}

/* Prints text in lines of at most 72 characters, each indented by 6. */
void print_wrapped(const char *text)
{
  const char *p = text;
  while (*p) {
    int m = (int)strlen(p), cut = m;
    if (m > 72) {
      for (cut = 72; cut > 0 && p[cut] != ' '; cut--) {}
      if (cut == 0) cut = 72;
    }
    printf("      %.*s\n", cut, p);
    p += cut;
    while (*p == ' ') p++;
  }
}


/* Option NAME with a finite double value; returns 1 if consumed. */
int double_option(int argc, char **argv, int *k, const char *name,
                         double *out, int *bad)
{
  if (strcmp(argv[*k], name) != 0) return 0;
  if (*k + 1 >= argc) {
    cli_errorf("%s needs a value", name);
    *bad = 1;
    return 1;
  }
  (*k)++;
  if (!parse_double(name, argv[*k], out)) *bad = 1;
  return 1;
}
