/*
** cli.c -- option parsing and messages shared by the commands of afv
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"

#include <errno.h>
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

/* ---- messages and numbers ---------------------------------------------- */
int bad_input(const char *msg)
{
  fprintf(stderr, "afv: %s\n", msg);
  return EXIT_BAD_INPUT;
}

/* Parses a whole string as a finite double; message names the option. */
int parse_double(const char *opt, const char *text, double *out)
{
  char *end;
  errno = 0;
  *out = strtod(text, &end);
  if (end == text || *end || errno == ERANGE || !isfinite(*out)) {
    fprintf(stderr, "afv: %s: '%s' is not a finite number\n", opt, text);
    return 0;
  }
  return 1;
}

/* ---- model options shared by eval and check ---------------------------- */
const char *model_help =
  "model options (paper symbols; lengths in units of l):\n"
  "  --l VALUE        maximal cell radius l (default 1)\n"
  "  --A0 VALUE       preferred area A0 (default 3.141592653589793 = pi l^2)\n"
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
  fprintf(stderr, "afv: --box: '%s' is neither 'open' nor LX,LY with "
          "positive numbers\n", text);
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
    fprintf(stderr, "afv: %s needs a value\n", opt);
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
    fprintf(stderr, "afv: --box: %.17g,%.17g is smaller than 4l = %.17g, too "
            "small for the minimum-image convention\n", b->Lx, b->Ly,
            4 * p->l);
    return 0;
  }
  return 1;
}

/* Loads POINTS and wraps them into a periodic box. */
int load_points(const char *path, const afv_box *b, int *n, double **r)
{
  char err[512];
  int i;
  if (afv_read_points(path, n, r, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  for (i = 0; i < *n; i++) afv_wrap(b, &(*r)[2*i], &(*r)[2*i+1]);
  return 1;
}

int library_error(int st, const afv_geom *g)
{
  int i, j;
  if (st == AFV_ECOINCIDENT) {
    afv_geom_bad_pair(g, &i, &j);
    fprintf(stderr, "afv: cells %d and %d (0-based, input order) have the "
            "same centre\n", i, j);
  } else
    fprintf(stderr, "afv: %s\n", afv_strerror(st));
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
    fprintf(stderr, "afv: %s needs a value\n", name);
    *bad = 1;
    return 1;
  }
  (*k)++;
  if (!parse_double(name, argv[*k], out)) *bad = 1;
  return 1;
}
