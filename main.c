/*
** main.c -- the afv command-line program.
**
**   afv eval POINTS [options]     geometry, energy and forces of one configuration
**   afv check POINTS [options]    analytic forces against finite differences
**
** Exit status: 0 success, 1 a check failed, 2 bad input or options.
** Only this file decides to exit; the library returns status codes.
*/
#include "afv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXIT_CHECK_FAILED 1
#define EXIT_BAD_INPUT    2

static const char *usage_text =
  "usage: afv COMMAND [ARGS] [OPTIONS]\n"
  "\n"
  "Active Finite Voronoi model of epithelial and mesenchymal tissue.\n"
  "\n"
  "commands:\n"
  "  eval POINTS     print each cell's geometry and force, and the energy\n"
  "  check POINTS    compare analytic forces with finite differences\n"
  "\n"
  "Run 'afv COMMAND --help' for the options of a command.\n";

/* ---- messages and numbers ---------------------------------------------- */
static int bad_input(const char *msg)
{
  fprintf(stderr, "afv: %s\n", msg);
  return EXIT_BAD_INPUT;
}

/* Parses a whole string as a finite double; message names the option. */
static int parse_double(const char *opt, const char *text, double *out)
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
static const char *model_help =
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
  "  --cap DELTA      contact cap: arc-end derivatives use\n"
  "                   max(sqrt(4l^2-d^2), DELTA); default 0 = exact -grad E.\n"
  "                   With DELTA > 0 the force is NOT the gradient of E.\n";

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
static int model_option(int argc, char **argv, int *k, afv_params *p,
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
static int model_valid(const afv_params *p, const afv_box *b)
{
  if (p->l <= 0) return !bad_input("--l: must be > 0");
  if (p->KA < 0) return !bad_input("--KA: must be >= 0");
  if (p->KP < 0) return !bad_input("--KP: must be >= 0");
  if (p->cap < 0) return !bad_input("--cap: must be >= 0");
  if (b->periodic && (b->Lx < 4 * p->l || b->Ly < 4 * p->l)) {
    fprintf(stderr, "afv: --box: %g,%g is smaller than 4l = %g, too small "
            "for the minimum-image convention\n", b->Lx, b->Ly, 4 * p->l);
    return 0;
  }
  return 1;
}

/* Loads POINTS and wraps them into a periodic box. */
static int load_points(const char *path, const afv_box *b, int *n, double **r)
{
  char err[512];
  int i;
  if (afv_read_points(path, n, r, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  for (i = 0; i < *n; i++) afv_wrap(b, &(*r)[2*i], &(*r)[2*i+1]);
  return 1;
}

static int library_error(int st, const afv_geom *g)
{
  if (st == AFV_ECOINCIDENT)
    fprintf(stderr, "afv: cells %d and %d (0-based, input order) have the "
            "same centre\n", g->bad_i, g->bad_j);
  else
    fprintf(stderr, "afv: %s\n", afv_strerror(st));
  return EXIT_BAD_INPUT;
}

/* ---- afv eval ---------------------------------------------------------- */
static int cmd_eval(int argc, char **argv)
{
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_geom g;
  const char *path = NULL;
  double *r = NULL, *f = NULL;
  int n, k, st, i;
  afv_params_default(&p);
  memset(&g, 0, sizeof g);
  for (k = 1; k < argc; k++) {
    int m;
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf("usage: afv eval POINTS [options]\n\n"
             "Prints '# cell x y area perimeter arc_length contacts fx fy',\n"
             "one line per cell in input order (%%.17g; x y wrapped into a\n"
             "periodic box), then '# energy E'.  contacts counts edges\n"
             "longer than %g l.  POINTS: one 'x y' per line, separated by\n"
             "spaces, tabs or commas; '#' lines ignored.\n\n%s",
             AFV_CONTACT_TOL, model_help);
      return 0;
    }
    if ((m = model_option(argc, argv, &k, &p, &b)) < 0) return EXIT_BAD_INPUT;
    if (m) continue;
    if (argv[k][0] == '-' && argv[k][1]) {
      fprintf(stderr, "afv eval: unknown option '%s' (see afv eval --help)\n",
              argv[k]);
      return EXIT_BAD_INPUT;
    }
    if (path) return bad_input("eval: more than one POINTS file given");
    path = argv[k];
  }
  if (!path) return bad_input("eval: missing POINTS file (see afv eval --help)");
  if (!model_valid(&p, &b) || !load_points(path, &b, &n, &r))
    return EXIT_BAD_INPUT;
  f = malloc((size_t)(2 * n + 1) * sizeof(double));
  if (!f) return bad_input("out of memory");
  st = afv_compute(&g, n, r, &p, &b, f);
  if (st != AFV_OK) {
    st = library_error(st, &g);
  } else {
    printf("# cell x y area perimeter arc_length contacts fx fy\n");
    for (i = 0; i < n; i++)
      printf("%d %.17g %.17g %.17g %.17g %.17g %d %.17g %.17g\n", i, r[2*i],
             r[2*i+1], g.area[i], g.perim[i], g.arc[i], g.contacts[i],
             f[2*i], f[2*i+1]);
    printf("# energy %.17g\n", g.energy);
  }
  afv_geom_free(&g);
  free(r);
  free(f);
  return st;
}

/* ---- afv check --------------------------------------------------------- */
static int cmd_check(int argc, char **argv)
{
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_check_report rep;
  afv_geom g;
  const char *path = NULL;
  double *r = NULL, h = 1e-6, tol = 1e-6;
  int n, k, st;
  afv_params_default(&p);
  memset(&g, 0, sizeof g);
  for (k = 1; k < argc; k++) {
    int m;
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf("usage: afv check POINTS [options]\n\n"
             "Compares the analytic forces with central differences of the\n"
             "total energy and prints the largest absolute error, the force\n"
             "scale (largest |F| component) and their ratio.  Exit status 0\n"
             "if the ratio is within the tolerance, 1 if not.\n\n"
             "  --h STEP     finite-difference step in units of l "
             "(default 1e-6)\n"
             "  --tol REL    tolerance on max error / force scale "
             "(default 1e-6)\n\n%s", model_help);
      return 0;
    }
    if ((m = model_option(argc, argv, &k, &p, &b)) < 0) return EXIT_BAD_INPUT;
    if (m) continue;
    if ((strcmp(argv[k], "--h") == 0 || strcmp(argv[k], "--tol") == 0)) {
      double *dst = argv[k][2] == 'h' ? &h : &tol;
      if (k + 1 >= argc) {
        fprintf(stderr, "afv: %s needs a value\n", argv[k]);
        return EXIT_BAD_INPUT;
      }
      if (!parse_double(argv[k], argv[k + 1], dst)) return EXIT_BAD_INPUT;
      if (*dst <= 0) {
        fprintf(stderr, "afv: %s: must be > 0\n", argv[k]);
        return EXIT_BAD_INPUT;
      }
      k++;
      continue;
    }
    if (argv[k][0] == '-' && argv[k][1]) {
      fprintf(stderr, "afv check: unknown option '%s' (see afv check "
              "--help)\n", argv[k]);
      return EXIT_BAD_INPUT;
    }
    if (path) return bad_input("check: more than one POINTS file given");
    path = argv[k];
  }
  if (!path)
    return bad_input("check: missing POINTS file (see afv check --help)");
  if (!model_valid(&p, &b) || !load_points(path, &b, &n, &r))
    return EXIT_BAD_INPUT;
  st = afv_compute(&g, n, r, &p, &b, NULL);  /* names a coincident pair */
  if (st == AFV_OK) st = afv_gradient_check(n, r, &p, &b, h * p.l, &rep);
  if (st != AFV_OK) st = library_error(st, &g);
  afv_geom_free(&g);
  free(r);
  if (st != AFV_OK) return st;
  printf("cells %d\nstep %.3g\nmax_abs_error %.6e\nforce_scale %.6e\n"
         "max_rel_error %.6e\ntolerance %.3g\nworst cell %d component %c\n",
         n, h, rep.max_abs, rep.force_scale, rep.max_rel, tol,
         rep.worst_cell, rep.worst_comp ? 'y' : 'x');
  if (p.cap > 0)
    printf("note: --cap %g makes the force differ from -grad E on purpose\n",
           p.cap);
  printf("%s\n", rep.max_rel <= tol ? "PASS" : "FAIL");
  return rep.max_rel <= tol ? 0 : EXIT_CHECK_FAILED;
}

/* ---- dispatch ---------------------------------------------------------- */
typedef struct command {
  const char *name;
  int (*run)(int argc, char **argv);
} command;

static const command commands[] = {
  {"eval", cmd_eval},
  {"check", cmd_check},
};

int main(int argc, char **argv)
{
  size_t c;
  if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0
      || strcmp(argv[1], "help") == 0) {
    fputs(usage_text, argc < 2 ? stderr : stdout);
    return argc < 2 ? EXIT_BAD_INPUT : 0;
  }
  for (c = 0; c < sizeof commands / sizeof commands[0]; c++)
    if (strcmp(argv[1], commands[c].name) == 0)
      return commands[c].run(argc - 1, argv + 1);
  fprintf(stderr, "afv: unknown command '%s' (see afv --help)\n", argv[1]);
  return EXIT_BAD_INPUT;
}
