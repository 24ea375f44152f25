/*
** inspect.c -- afv eval, check, draw and meanfield: one configuration
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

/* ---- afv eval ---------------------------------------------------------- */
int cmd_eval(int argc, char **argv)
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
int cmd_check(int argc, char **argv)
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

/* ---- afv draw, afv analyze, afv meanfield (analysis helper) ------------- */
/* Reads the first line of path to tell a trajectory from a POINTS file. */
static int is_trajectory(const char *path)
{
  char line[64] = "";
  FILE *fp = fopen(path, "r");
  if (!fp) return 0;
  if (!fgets(line, sizeof line, fp)) line[0] = 0;
  fclose(fp);
  return strncmp(line, "# afv trajectory", 16) == 0;
}

/* Frame `frame` (-1: last) of a trajectory: positions, angles and box. */
static int load_frame(const char *path, long frame, afv_box *b, int *n,
                      double **r, double **theta)
{
  char err[512];
  afv_traj tr;
  size_t m;
  if (afv_traj_read(path, &tr, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  if (tr.nframes == 0 || frame >= tr.nframes) {
    fprintf(stderr, "afv draw: %s: --frame %ld: the file has %d frame(s)\n",
            path, frame, tr.nframes);
    afv_traj_free(&tr);
    return 0;
  }
  if (frame < 0) frame = tr.nframes - 1;
  *n = tr.n;
  *b = tr.box;
  m = (size_t)tr.n;
  *r = malloc((2 * m + 1) * sizeof(double));
  *theta = malloc((m + 1) * sizeof(double));
  if (*r && *theta) {
    memcpy(*r, tr.r + (size_t)frame * 2 * m, 2 * m * sizeof(double));
    memcpy(*theta, tr.theta + (size_t)frame * m, m * sizeof(double));
  }
  afv_traj_free(&tr);
  if (!*r || !*theta) return !bad_input("out of memory");
  return 1;
}


int cmd_draw(int argc, char **argv)
{
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_geom g;
  const char *path = NULL;
  double *r = NULL, *theta = NULL;
  long frame = -1;
  int n = 0, k, st, ok, l_given = 0;
  afv_params_default(&p);
  memset(&g, 0, sizeof g);
  for (k = 1; k < argc; k++) {
    int m;
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf("usage: afv draw FILE [options] > picture.svg\n\n"
             "Draws one configuration as SVG, like the paper's Fig. 1: red\n"
             "centres, blue contact edges, pink arcs, hollow purple triple\n"
             "junctions, cyan polarity arrows, the periodic box in black.\n"
             "FILE is a POINTS file or a trajectory ('# afv trajectory'\n"
             "header: the box and the angles come from it, and l from\n"
             "params.txt beside it, unless --l is given).  Only --l and\n"
             "--box (POINTS files) change the picture.\n\n"
             "  --frame K        trajectory frame K, 0-based (default: last)\n"
             "\n%s", model_help);
      return 0;
    }
    if (strcmp(argv[k], "--l") == 0) l_given = 1;
    if ((m = model_option(argc, argv, &k, &p, &b)) < 0) return EXIT_BAD_INPUT;
    if (m) continue;
    if (strcmp(argv[k], "--frame") == 0) {
      char *end;
      if (k + 1 >= argc) return bad_input("--frame needs a value");
      errno = 0;
      frame = strtol(argv[++k], &end, 10);
      if (end == argv[k] || *end || errno || frame < 0)
        return bad_input("--frame: must be an integer >= 0");
      continue;
    }
    if (argv[k][0] == '-' && argv[k][1]) {
      fprintf(stderr, "afv draw: unknown option '%s' (see afv draw --help)\n",
              argv[k]);
      return EXIT_BAD_INPUT;
    }
    if (path) return bad_input("draw: more than one FILE given");
    path = argv[k];
  }
  if (!path) return bad_input("draw: missing FILE (see afv draw --help)");
  if (is_trajectory(path) && !l_given) run_l_beside(path, &p.l);
  if (is_trajectory(path)) ok = load_frame(path, frame, &b, &n, &r, &theta);
  else if (frame >= 0) ok = !bad_input("draw: --frame needs a trajectory");
  else ok = model_valid(&p, &b) && load_points(path, &b, &n, &r);
  if (ok && !model_valid(&p, &b)) ok = 0;
  if (!ok) {
    free(r);
    free(theta);
    return EXIT_BAD_INPUT;
  }
  st = afv_geometry(&g, n, r, &p, &b);
  if (st != AFV_OK) st = library_error(st, &g);
  else if (afv_svg_write(stdout, &g, n, r, theta, &p, &b) != AFV_OK
           || fflush(stdout) != 0)
    st = bad_input("draw: cannot write the SVG");
  afv_geom_free(&g);
  free(r);
  free(theta);
  return st;
}


int cmd_meanfield(int argc, char **argv)
{
  double Lambda = 0.2, A0 = 3.14159265358979323846, KP = 1, KA = 1;
  int k, bad = 0;
  for (k = 1; k < argc && !bad; k++) {
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf("usage: afv meanfield [--Lambda V] [--A0 V] [--KP V] [--KA V]"
             "\n\nPrints P0*, the preferred perimeter below which the\n"
             "hexagonal (honeycomb) packing closes its gaps: the paper's\n"
             "mean-field epithelial/mesenchymal point (lengths in l).\n"
             "Defaults: the paper's Lambda 0.2, A0 pi, KP 1, KA 1 "
             "(P0* = 5.73).\n");
      return 0;
    }
    if (double_option(argc, argv, &k, "--Lambda", &Lambda, &bad)
        || double_option(argc, argv, &k, "--A0", &A0, &bad)
        || double_option(argc, argv, &k, "--KP", &KP, &bad)
        || double_option(argc, argv, &k, "--KA", &KA, &bad))
      continue;
    fprintf(stderr, "afv meanfield: unknown argument '%s' (see afv "
            "meanfield --help)\n", argv[k]);
    return EXIT_BAD_INPUT;
  }
  if (bad) return EXIT_BAD_INPUT;
  if (!(KP > 0) || !(KA > 0)) return bad_input("meanfield: KP and KA must "
                                               "be > 0");
  printf("%.4f\n", afv_meanfield_p0(Lambda / KA, A0, KP / KA));
  return 0;
}
