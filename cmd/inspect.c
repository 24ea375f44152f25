/*
** inspect.c -- afv eval, check, draw and meanfield: one configuration
*/
#define _POSIX_C_SOURCE 200809L  /* mkdir, truncate, isatty, clock_gettime */
#include "cli.h"

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
#include <dirent.h>
#include <time.h>
#include <unistd.h>

/* ---- parameters whose energy cannot be computed ----------------------- */
/* Values within a factor HEADROOM of the largest double are refused, as
** afv run refuses them: the energy and the forces are sums and products of
** the terms bounded below, and must stay finite. */
#define HEADROOM AFV_PARAMS_HEADROOM

static int huge(double x)
{
  return !isfinite(x * HEADROOM);
}

/* 1 if the energy of n cells under p stays finite in every state: each
** term's largest value (a cell is inside its disk: 0 <= A <= pi l^2,
** 0 <= P <= 2 pi l) summed over the cells.  Else prints one line naming
** the key (cmd: "eval", "check", "draw") and returns 0. */
static int model_computable(const char *cmd, const afv_params *p, int n)
{
  const double pi = 3.14159265358979323846;
  double Amax = pi * p->l * p->l, Pmax = 2 * pi * p->l;
  double dA = fmax(fabs(p->A0), fabs(Amax - p->A0));
  double dP = fmax(fabs(p->P0), fabs(Pmax - p->P0));
  const char *key = NULL, *what = NULL;
  double v = 0;
  if (huge(Amax) || !(p->l * p->l >= DBL_MIN * HEADROOM)) {
    key = "l"; v = p->l; what = "the disk's area pi l^2 is out of the range "
                               "of doubles";
  } else if (huge(dA * dA)) {
    key = "A0"; v = p->A0; what = "(A - A0)^2 overflows";
  } else if (huge(dP * dP)) {
    key = "P0"; v = p->P0; what = "(P - P0)^2 overflows";
  } else if (huge(n * p->KA * dA * dA)) {
    key = "KA"; v = p->KA; what = "the area term KA (A - A0)^2 summed over "
                                  "the cells overflows";
  } else if (huge(n * p->KP * dP * dP)) {
    key = "KP"; v = p->KP; what = "the perimeter term KP (P - P0)^2 summed "
                                  "over the cells overflows";
  } else if (huge(n * fabs(p->Lambda) * Pmax)) {
    key = "Lambda"; v = p->Lambda; what = "the arc term Lambda L summed over "
                                          "the cells overflows";
  } else if (huge(n * (p->KA * dA * dA + p->KP * dP * dP
                       + fabs(p->Lambda) * Pmax))) {
    key = "KA"; v = p->KA; what = "the energy summed over the cells "
                                  "overflows";
  }
  if (!key) return 1;
  fprintf(stderr, "afv %s: --%s: %g: %s (%d cells)\n", cmd, key, v, what, n);
  return 0;
}

/* ---- afv eval ---------------------------------------------------------- */
/* The first cell whose area, perimeter, arc or force is not finite, or -1
** (the energy too: then cell n - 1 is named). */
static int first_nonfinite(const afv_geom *g, int n, const double *f)
{
  const double *A = afv_geom_area(g), *P = afv_geom_perim(g);
  const double *L = afv_geom_arc(g);
  int i;
  for (i = 0; i < n; i++)
    if (!isfinite(A[i] + P[i] + L[i] + f[2*i] + f[2*i+1])) return i;
  return n > 0 && !isfinite(afv_geom_energy(g)) ? n - 1 : -1;
}

/* afv eval's table: each cell's centre, shape, contacts and force (%.17g,
** read back exactly), then the energy. */
static void print_cells(const afv_geom *g, int n, const double *r,
                        const double *f)
{
  const double *area = afv_geom_area(g), *perim = afv_geom_perim(g);
  const double *arc = afv_geom_arc(g);
  const int *contacts = afv_geom_contacts(g);
  int i;
  printf("# cell x y area perimeter arc_length contacts fx fy\n");
  for (i = 0; i < n; i++)
    printf("%d %.17g %.17g %.17g %.17g %.17g %d %.17g %.17g\n", i, r[2*i],
           r[2*i+1], area[i], perim[i], arc[i], contacts[i], f[2*i],
           f[2*i+1]);
  printf("# energy %.17g\n", afv_geom_energy(g));
}

/* afv eval --help (AFV_CONTACT_TOL, then the model options). */
static const char *eval_usage =
  "usage: afv eval POINTS [options]\n\n"
  "Prints '# cell x y area perimeter arc_length contacts fx fy',\n"
  "one line per cell in input order (%%.17g; x y wrapped into a\n"
  "periodic box), then '# energy E'.  contacts counts edges\n"
  "longer than %g l.  POINTS: one 'x y' per line, separated by\n"
  "spaces, tabs or commas; '#' lines ignored.\n\n%s";

int cmd_eval(int argc, char **argv)
{
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_geom *g;
  const char *path = NULL;
  double *r = NULL, *f = NULL;
  int n, k, st, i;
  afv_params_default(&p);
  for (k = 1; k < argc; k++) {
    int m;
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf(eval_usage, AFV_CONTACT_TOL, model_help);
      return 0;
    }
    if ((m = model_option(argc, argv, &k, &p, &b)) < 0) return EXIT_BAD_INPUT;
    if (m) continue;
    if (argv[k][0] == '-' && argv[k][1]) {
      return unknown_option(argv[k], model_help, NULL);
    }
    if (path) return bad_input("eval: more than one POINTS file given");
    path = argv[k];
  }
  if (!path) return bad_input("eval: missing POINTS file (see afv eval --help)");
  if (!model_valid(&p, &b) || !load_points(path, &b, &n, &r))
    return EXIT_BAD_INPUT;
  if (!model_computable("eval", &p, n)) {
    free(r);
    return EXIT_BAD_INPUT;
  }
  f = malloc((size_t)(2 * n + 1) * sizeof(double));
  g = afv_geom_new();
  if (!f || !g) {
    free(f);
    free(r);
    afv_geom_delete(g);
    return bad_input("out of memory");
  }
  st = afv_compute(g, n, r, &p, &b, f);
  if (st != AFV_OK) {
    st = library_error(st, g);
  } else if ((i = first_nonfinite(g, n, f)) >= 0) {
    fprintf(stderr, "afv eval: cell %d: its shape or force is not finite "
            "(the parameters are too large or small for doubles)\n", i);
    st = EXIT_BAD_INPUT;
  } else {
    print_cells(g, n, r, f);
  }
  afv_geom_delete(g);
  free(r);
  free(f);
  return st;
}

/* ---- afv check --------------------------------------------------------- */
/* Prints the report and the verdict: FAIL (exit 1) if an error the
** differences resolve (afv_check_report.max_resolved) exceeds the
** tolerance; else INCONCLUSIVE (exit 4) if one they cannot resolve does
** (a kink of the energy within reach of the step); else PASS (exit 0). */
static int check_verdict(const afv_check_report *rep, const afv_params *p,
                         int n, double h, double tol)
{
  double S = rep->tension_scale > 0 ? rep->tension_scale : 1;
  int fail = !(rep->max_resolved / S <= tol);
  int unsure = !fail && !(rep->max_unresolved / S <= tol);
  printf("cells %d\nstep %.3g\nmax_abs_error %.6e\nforce_scale %.6e\n"
         "max_rel_error %.6e\ntension_scale %.6e\nmax_tension_rel_error "
         "%.6e\ntolerance %.3g (on max_tension_rel_error)\n"
         "worst cell %d component %c\n", n, h, rep->max_abs,
         rep->force_scale, rep->max_rel, rep->tension_scale,
         rep->max_tension_rel, tol, rep->worst_cell,
         rep->worst_comp ? 'y' : 'x');
  if (p->cap > 0)
    printf("note: --cap %g makes the force differ from -grad E on purpose\n",
           p->cap);
  if (unsure)
    printf("note: at cell %d the differences cannot resolve an error of "
           "%.3e (a pair within reach of detaching or meeting: the "
           "energy has a kink there)\n", rep->unresolved_cell,
           rep->max_unresolved);
  printf("%s\n", fail ? "FAIL" : unsure ? "INCONCLUSIVE" : "PASS");
  return fail ? EXIT_CHECK_FAILED : unsure ? EXIT_CHECK_UNSURE : 0;
}

/* afv check --help (then the model options). */
static const char *check_usage =
  "usage: afv check POINTS [options]\n\n"
  "Compares the analytic forces with central differences of the\n"
  "energy (of the cells near each moved cell, in coordinates\n"
  "centred on it: O(N), exact steps at any coordinates) and\n"
  "prints the largest absolute error, the force scale (largest\n"
  "|F| component), the tension scale (rms over cells of\n"
  "|2 KA (A - A0)| l + |2 KP (P - P0)| + Lambda, the size of the\n"
  "pressure and tension terms every force is a sum of: it does\n"
  "not vanish where forces cancel by symmetry) and the error\n"
  "over each.  Each cell's step is at most a hundredth of its\n"
  "distance to a kink of the energy (a pair detaching at 2l or\n"
  "meeting), and two steps are extrapolated; their disagreement\n"
  "and the rounding are the differences' own uncertainty.  Exit\n"
  "status 0 (PASS) if the error over the tension scale is within\n"
  "the tolerance, 1 (FAIL) if an error beyond twice that\n"
  "uncertainty exceeds it, 4 (INCONCLUSIVE) if only errors\n"
  "within it do (finite differences cannot decide there).\n\n"
  "  --h STEP     finite-difference step in units of l "
  "(default 1e-6)\n"
  "  --tol REL    tolerance on max error / tension scale "
  "(default 1e-6)\n\n%s";

int cmd_check(int argc, char **argv)
{
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_check_report rep;
  afv_geom *g;
  const char *path = NULL;
  double *r = NULL, h = 1e-6, tol = 1e-6;
  int n, k, st;
  afv_params_default(&p);
  for (k = 1; k < argc; k++) {
    int m;
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf(check_usage, model_help);
      return 0;
    }
    if ((m = model_option(argc, argv, &k, &p, &b)) < 0) return EXIT_BAD_INPUT;
    if (m) continue;
    if ((strcmp(argv[k], "--h") == 0 || strcmp(argv[k], "--tol") == 0)) {
      double *dst = argv[k][2] == 'h' ? &h : &tol;
      if (k + 1 >= argc) {
        cli_errorf("%s needs a value", argv[k]);
        return EXIT_BAD_INPUT;
      }
      if (!parse_double(argv[k], argv[k + 1], dst)) return EXIT_BAD_INPUT;
      if (*dst <= 0) {
        cli_errorf("%s: must be > 0", argv[k]);
        return EXIT_BAD_INPUT;
      }
      k++;
      continue;
    }
    if (argv[k][0] == '-' && argv[k][1]) {
      return unknown_option(argv[k], model_help, "--h --tol");
    }
    if (path) return bad_input("check: more than one POINTS file given");
    path = argv[k];
  }
  if (!path)
    return bad_input("check: missing POINTS file (see afv check --help)");
  if (!model_valid(&p, &b) || !load_points(path, &b, &n, &r))
    return EXIT_BAD_INPUT;
  if (!model_computable("check", &p, n)) {
    free(r);
    return EXIT_BAD_INPUT;
  }
  if (!(g = afv_geom_new())) {
    free(r);
    return bad_input("out of memory");
  }
  st = afv_compute(g, n, r, &p, &b, NULL);   /* names a coincident pair */
  if (st == AFV_OK) st = afv_gradient_check(n, r, &p, &b, h * p.l, &rep);
  if (st != AFV_OK) st = library_error(st, g);
  afv_geom_delete(g);
  free(r);
  if (st != AFV_OK) return st;
  return check_verdict(&rep, &p, n, h, tol);
}

/* ---- afv draw, afv analyze, afv meanfield (analysis helper) ------------- */
/* Reads the first line of path to tell a trajectory from a POINTS file. */
static int is_trajectory(const char *path)
{
  afv_lines L;
  int yes;
  /* (afv_lines: a pipe is refused, not waited on) */
  if (afv_lines_open(&L, path, NULL, 0) != AFV_OK) return 0;
  yes = afv_lines_next(&L, NULL, 0) > 0
        && strncmp(L.line, "# afv trajectory", 16) == 0;
  afv_lines_close(&L);
  return yes;
}

/* ---- afv draw ----------------------------------------------------------- */
static const char *draw_usage =
  "usage: afv draw FILE [options] > picture.svg\n"
  "       afv draw TRAJECTORY --frames DIR [options]\n\n"
  "Draws one configuration as SVG, like the paper's Fig. 1: red\n"
  "centres, blue contact edges, pink arcs, hollow purple triple\n"
  "junctions, cyan polarity arrows, the periodic box in black.\n"
  "FILE is a POINTS file or a trajectory ('# afv trajectory'\n"
  "header: the box and the angles come from it, and l from\n"
  "params.txt beside it, unless --l is given).  Lines and marks are\n"
  "their size in l, but at least a pixel or two wide.\n\n"
  "  --frame K        trajectory frame K, 0-based (default: last)\n"
  "  --frames DIR     every frame of the trajectory, as DIR/frame_00000.svg,\n"
  "                   frame_00001.svg, ... (DIR is created; nothing is\n"
  "                   written unless every frame is drawn)\n"
  "  --width PX       picture width in pixels, 16 to 100000 (default: the\n"
  "                   longer side is 800)\n"
  "  --crop X0,Y0,X1,Y1  draw only this rectangle (model units; in a\n"
  "                   periodic box within one box side of the box)\n"
  "  --color-by WHAT  fill the cells by cluster (the largest clusters a\n"
  "                   colour each) or by a per-cell parameter: v0, P0, KA,\n"
  "                   KP, A0 or Dr (a colour per value up to 7 values,\n"
  "                   e.g. a mixture of cell types, else a colour ramp),\n"
  "                   with a legend right of the tissue\n"
  "  --cells FILE     per-cell values for --color-by (CELLS format; for a\n"
  "                   trajectory the default is the run's cells.txt beside\n"
  "                   it, and a value it lacks comes from params.txt; for\n"
  "                   a POINTS file from --P0, --KA, --KP, --A0 below)\n"
  "  --caption        a line under the tissue: N, P0, v0, Lambda and the\n"
  "                   time t (a trajectory's v0 from params.txt beside it)\n"
  "  --scale-bar      a bar of length 1 l under the tissue\n\n"
  "With --frames and --color-by cluster a cluster keeps its colour from\n"
  "frame to frame while it keeps more than half of its cells.  DIR must\n"
  "be new, empty or hold only frame_NNNNN.svg files (an earlier --frames):\n"
  "those are replaced, and any beyond the new last frame removed.\n\n";

typedef struct draw_job {
  const char *path, *frames_dir, *cells_path, *color_by;
  long frame;              /* -1: last */
  int l_given;
  int caption;             /* --caption */
  int traj;                /* FILE is a trajectory */
  afv_params p;
  afv_box b;
  afv_draw_opts o;
} draw_job;

/* dir of path (a file in it) + "/" + name into buf; 0 if too long. */
static int beside(const char *path, const char *name, char *buf, size_t len)
{
  const char *slash = strrchr(path, '/');
  int dl = slash ? (int)(slash - path) : 0;
  int m = slash ? snprintf(buf, len, "%.*s/%s", dl, path, name)
                : snprintf(buf, len, "%s", name);
  return m > 0 && (size_t)m < len;
}

/* Value of key in the params.txt beside path; 1 if found. */
static int param_beside(const char *path, const char *key, double *v)
{
  char file[RUN_PATH_MAX + 32];
  return beside(path, "params.txt", file, sizeof file)
         && run_param(file, key, v) > 0;
}

/* "X0,Y0,X1,Y1": four finite numbers, X0 < X1 and Y0 < Y1. */
static int parse_crop(const char *text, afv_draw_opts *o)
{
  double v[4];
  const char *s = text;
  char *end;
  int k;
  for (k = 0; k < 4; k++) {
    errno = 0;
    v[k] = strtod(s, &end);
    if (end == s || errno == ERANGE || !isfinite(v[k])
        || *end != (k < 3 ? ',' : '\0'))
      break;
    s = end + 1;
  }
  if (k < 4 || !(v[0] < v[2]) || !(v[1] < v[3])) {
    cli_errorf("--crop: '%s' is not X0,Y0,X1,Y1 with X0 < X1 and Y0 < Y1",
               text);
    return 0;
  }
  o->crop = 1;
  o->x0 = v[0]; o->y0 = v[1]; o->x1 = v[2]; o->y1 = v[3];
  return 1;
}

static const char *const color_names[] = {"cluster", "v0", "P0", "KA", "KP",
                                          "A0", "Dr"};
#define N_COLOR_BY 7

/* Prints "afv draw: MSG" and returns -1 (a bad option value). */
static int bad_value(const char *msg)
{
  bad_input(msg);
  return -1;
}

/* One draw option at argv[*k] (consumed with its value): 1, 0 if not a
** draw option, -1 on a bad value (message printed). */
static int draw_option(int argc, char **argv, int *k, draw_job *J)
{
  const char *opt = argv[*k], *val;
  char *end;
  int m;
  if (strcmp(opt, "--caption") == 0 || strcmp(opt, "--scale-bar") == 0) {
    if (opt[2] == 'c') J->caption = 1;
    else J->o.scale_bar = 1;
    return 1;
  }
  if (strcmp(opt, "--frame") && strcmp(opt, "--frames")
      && strcmp(opt, "--width") && strcmp(opt, "--crop")
      && strcmp(opt, "--color-by") && strcmp(opt, "--cells"))
    return 0;
  if (*k + 1 >= argc) {
    cli_errorf("%s needs a value", opt);
    return -1;
  }
  val = argv[++*k];
  if (strcmp(opt, "--frame") == 0) {
    errno = 0;
    J->frame = strtol(val, &end, 10);
    if (end == val || *end || errno || J->frame < 0)
      return bad_value("--frame: must be an integer >= 0");
  } else if (strcmp(opt, "--frames") == 0) {
    if (!*val || strlen(val) > RUN_PATH_MAX - 64)
      return bad_value("--frames: DIR is empty or too long");
    J->frames_dir = val;
  } else if (strcmp(opt, "--width") == 0) {
    if (!parse_double(opt, val, &J->o.width)) return -1;
    if (!(J->o.width >= 16 && J->o.width <= 100000))
      return bad_value("--width: must be 16 to 100000 pixels");
  } else if (strcmp(opt, "--crop") == 0) {
    if (!parse_crop(val, &J->o)) return -1;
  } else if (strcmp(opt, "--color-by") == 0) {
    for (m = 0; m < N_COLOR_BY && strcmp(val, color_names[m]); m++) {}
    if (m == N_COLOR_BY) {
      cli_errorf("--color-by: '%s' is not one of cluster, v0, P0, KA, KP, "
                 "A0, Dr", val);
      return -1;
    }
    J->color_by = color_names[m];
  } else {
    J->cells_path = val;
  }
  return 1;
}

static int draw_parse(int argc, char **argv, draw_job *J)
{
  int k, m;
  for (k = 1; k < argc; k++) {
    if (strcmp(argv[k], "--l") == 0) J->l_given = 1;
    if ((m = model_option(argc, argv, &k, &J->p, &J->b)) < 0) return 0;
    if (m) continue;
    if ((m = draw_option(argc, argv, &k, J)) < 0) return 0;
    if (m) continue;
    if (argv[k][0] == '-' && argv[k][1]) {
      unknown_option(argv[k], draw_usage, model_help);
      return 0;
    }
    if (J->path) return !bad_input("draw: more than one FILE given");
    J->path = argv[k];
  }
  if (!J->path) return !bad_input("draw: missing FILE (see afv draw --help)");
  if (J->frames_dir && J->frame >= 0)
    return !bad_input("draw: --frame and --frames exclude each other");
  return 1;
}

/* The options that depend on the configuration: the crop within one box
** side of a periodic box. */
static int draw_check_box(const draw_job *J)
{
  const afv_draw_opts *o = &J->o;
  if (o->crop && J->b.periodic
      && (o->x0 < -J->b.Lx || o->x1 > 2 * J->b.Lx || o->y0 < -J->b.Ly
          || o->y1 > 2 * J->b.Ly)) {
    fprintf(stderr, "afv draw: --crop: %g,%g,%g,%g reaches more than one box "
            "side beyond the periodic box %g x %g\n", o->x0, o->y0, o->x1,
            o->y1, J->b.Lx, J->b.Ly);
    return 0;
  }
  return 1;
}

/* Per-cell values of the parameter J->color_by for n cells, into *out
** (malloc'd): the CELLS column if there is one, else the run's value
** (params.txt beside a trajectory; the model options for POINTS). */
static int color_values(const draw_job *J, int traj, int n, double **out)
{
  static const int col[] = {AFV_COL_V0, AFV_COL_P0, AFV_COL_KA, AFV_COL_KP,
                            AFV_COL_A0, AFV_COL_DR};
  char path[RUN_PATH_MAX + 32], err[RUN_PATH_MAX + 128];
  const char *cells = J->cells_path;
  double scalar[6];
  afv_cells cl;
  int w, i, have;
  for (w = 0; strcmp(color_names[w + 1], J->color_by); w++) {}
  memset(&cl, 0, sizeof cl);
  if (!cells && traj && beside(J->path, "cells.txt", path, sizeof path)
      && access(path, F_OK) == 0)
    cells = path;
  if (cells && afv_cells_read(cells, &cl, err, sizeof err) != AFV_OK)
    return !bad_input(err);
  if (cells && cl.n != n) {
    fprintf(stderr, "afv draw: %s: %d cells, the picture has %d\n", cells,
            cl.n, n);
    afv_cells_free(&cl);
    return 0;
  }
  scalar[1] = J->p.P0; scalar[2] = J->p.KA; scalar[3] = J->p.KP;
  scalar[4] = J->p.A0;
  have = w >= 1 && w <= 4;           /* POINTS: the model options */
  if (traj) have = param_beside(J->path, J->color_by, &scalar[w]);
  if (!cl.has[col[w]] && !have) {
    fprintf(stderr, "afv draw: --color-by %s: no %s in %s%s%s; give --cells "
            "FILE with a %s column\n", J->color_by, J->color_by,
            cells ? cells : "", cells ? " or " : "", traj ? "params.txt "
            "beside the trajectory" : "a POINTS file", J->color_by);
    afv_cells_free(&cl);
    return 0;
  }
  if ((*out = malloc((size_t)n * sizeof(double) + 1)) != NULL)
    for (i = 0; i < n; i++)
      (*out)[i] = cl.has[col[w]] ? cl.col[col[w]][i] : scalar[w];
  afv_cells_free(&cl);
  return *out ? 1 : !bad_input("out of memory");
}

/* The caption of a picture of n cells at time t (NAN: a POINTS file):
** N, P0, v0, Lambda, t; a trajectory's values from the params.txt beside
** it where it has them (v0 only from there). */
static void caption_text(const draw_job *J, int n, double t, char *buf,
                         size_t len)
{
  double P0 = J->p.P0, v0 = NAN, Lambda = J->p.Lambda;
  int m;
  if (J->traj) {
    param_beside(J->path, "P0", &P0);
    param_beside(J->path, "v0", &v0);
    param_beside(J->path, "Lambda", &Lambda);
  }
  m = snprintf(buf, len, "N = %d, P0 = %g", n, P0);
  if (!isnan(v0) && m > 0 && (size_t)m < len)
    m += snprintf(buf + m, len - (size_t)m, ", v0 = %g", v0);
  if (m > 0 && (size_t)m < len)
    m += snprintf(buf + m, len - (size_t)m, ", Lambda = %g", Lambda);
  if (!isnan(t) && m > 0 && (size_t)m < len)
    snprintf(buf + m, len - (size_t)m, ", t = %g", t);
}

/* Draws configuration r (angles theta, may be NULL; time t, NAN for a
** POINTS file) to out; color: the cluster colours along a movie (or
** NULL). */
static int draw_one(FILE *out, const draw_job *J, afv_geom *g, int n,
                    const double *r, const double *theta, double t,
                    int *color)
{
  char caption[160];
  afv_draw_opts o = J->o;
  int st = afv_geometry(g, n, r, &J->p, &J->b);
  if (st != AFV_OK) return library_error(st, g);
  if (J->caption) {
    caption_text(J, n, t, caption, sizeof caption);
    o.caption = caption;
  }
  o.cluster_color = color;
  st = afv_svg_draw(out, g, n, r, theta, &J->p, &J->b, &o);
  if (st != AFV_OK) return library_error(st, g);
  return 0;
}

/* Removes the first m frame files of dir, then dir. */
static void remove_frames(const char *dir, long m)
{
  char name[RUN_PATH_MAX + 96];
  long f;
  for (f = 0; f < m; f++) {
    snprintf(name, sizeof name, "%s/frame_%05ld.svg", dir, f);
    remove(name);
  }
  rmdir(dir);
}

/* 1 if name is a frame file of --frames: frame_ and 5 or more digits,
** .svg; its number in *k. */
static int frame_name(const char *name, long *k)
{
  const char *d = name + 6;
  size_t m = strlen(name);
  char *end;
  if (strncmp(name, "frame_", 6) != 0 || m < 15
      || strcmp(name + m - 4, ".svg") != 0 || !(*d >= '0' && *d <= '9'))
    return 0;
  *k = strtol(d, &end, 10);
  return end == name + m - 4 && end - d >= 5;
}

/* 1 if DIR holds nothing but frame files (an earlier --frames, which may
** be replaced); else says what else is there. */
static int frames_dir_ours(const char *dir)
{
  DIR *d = opendir(dir);
  struct dirent *e;
  long k;
  if (!d) {
    fprintf(stderr, "afv draw: --frames %s: %s\n", dir, strerror(errno));
    return 0;
  }
  while ((e = readdir(d)) != NULL) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")
        || frame_name(e->d_name, &k))
      continue;
    fprintf(stderr, "afv draw: --frames %s: holds '%s', not a frame of afv "
            "draw: give a new or empty directory\n", dir, e->d_name);
    closedir(d);
    return 0;
  }
  closedir(d);
  return 1;
}

/* Removes the frame files of dir numbered from `from` on (an earlier,
** longer --frames). */
static void remove_frames_from(const char *dir, long from)
{
  char name[RUN_PATH_MAX + 300];
  DIR *d = opendir(dir);
  struct dirent *e;
  long k;
  while (d && (e = readdir(d)) != NULL)
    if (frame_name(e->d_name, &k) && k >= from) {
      snprintf(name, sizeof name, "%s/%s", dir, e->d_name);
      remove(name);
    }
  if (d) closedir(d);
}

/* Every frame into a fresh directory beside DIR, then moved into DIR:
** DIR gets all the frames or, on any failure, nothing; a DIR of earlier
** frames keeps none of them.  Clusters keep their colours from frame to
** frame (afv_draw_opts.cluster_color). */
static int draw_frames(const draw_job *J, const afv_traj *tr, afv_geom *g)
{
  char tmp[RUN_PATH_MAX + 32], from[RUN_PATH_MAX + 96], to[RUN_PATH_MAX + 96];
  const char *dir = J->frames_dir;
  struct stat sb;
  size_t m = (size_t)tr->n;
  long f;
  int st = 0, fresh = stat(dir, &sb) != 0, *color;
  if (!fresh && !S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "afv draw: --frames: %s exists and is not a directory\n",
            dir);
    return EXIT_BAD_INPUT;
  }
  if (!fresh && !frames_dir_ours(dir)) return EXIT_BAD_INPUT;
  if (!(color = malloc(m * sizeof(int) + 1)))
    return bad_input("draw: out of memory");
  for (f = 0; f < (long)m; f++) color[f] = -1;
  snprintf(tmp, sizeof tmp, "%s.tmpXXXXXX", dir);
  if (!mkdtemp(tmp)) {
    fprintf(stderr, "afv draw: --frames %s: cannot create a directory there: "
            "%s\n", dir, strerror(errno));
    free(color);
    return EXIT_BAD_INPUT;
  }
  for (f = 0; f < tr->nframes && st == 0; f++) {
    FILE *fp;
    snprintf(from, sizeof from, "%s/frame_%05ld.svg", tmp, f);
    if (!(fp = fopen(from, "w"))) {
      fprintf(stderr, "afv draw: cannot create %s: %s\n", from,
              strerror(errno));
      st = EXIT_BAD_INPUT;
      break;
    }
    st = draw_one(fp, J, g, tr->n, tr->r + (size_t)f * 2 * m,
                  tr->theta + (size_t)f * m, tr->t[f], color);
    if (fclose(fp) != 0 && st == 0)
      st = bad_input("draw: --frames: a frame could not be written");
    if (st) fprintf(stderr, "afv draw: frame %ld of %s not drawn\n", f,
                    J->path);
  }
  free(color);
  if (st == 0 && fresh && rename(tmp, dir) != 0)
    st = bad_input("draw: --frames: cannot rename the frames' directory");
  for (f = 0; st == 0 && !fresh && f < tr->nframes; f++) {
    snprintf(from, sizeof from, "%s/frame_%05ld.svg", tmp, f);
    snprintf(to, sizeof to, "%s/frame_%05ld.svg", dir, f);
    if (rename(from, to) != 0)
      st = bad_input("draw: --frames: cannot move a frame into DIR");
  }
  if (st == 0 && !fresh) remove_frames_from(dir, tr->nframes);
  if (st != 0 || !fresh) remove_frames(tmp, tr->nframes);
  if (st == 0)
    fprintf(stderr, "afv draw: %d frames written to %s/\n", tr->nframes, dir);
  return st;
}

/* Draws the configuration (and, for --frames, every frame) of J. */
static int draw_run(draw_job *J)
{
  afv_traj tr;
  afv_geom *g = NULL;
  double *r = NULL, *theta = NULL, *value = NULL;
  char err[RUN_PATH_MAX + 128];
  int traj = J->traj = is_trajectory(J->path), n = 0, st = EXIT_BAD_INPUT;
  memset(&tr, 0, sizeof tr);
  if (traj && !J->l_given) run_l_beside(J->path, &J->p.l);
  if (!traj && (J->frame >= 0 || J->frames_dir))
    return bad_input(J->frame >= 0 ? "draw: --frame needs a trajectory"
                     : "draw: --frames needs a trajectory");
  if (traj) {
    if (afv_traj_read(J->path, &tr, err, sizeof err) != AFV_OK)
      return bad_input(err);
    if (tr.nframes == 0 || J->frame >= tr.nframes) {
      fprintf(stderr, "afv draw: %s: --frame %ld: the file has %d frame(s)\n",
              J->path, J->frame, tr.nframes);
      afv_traj_free(&tr);
      return EXIT_BAD_INPUT;
    }
    n = tr.n;
    J->b = tr.box;
    if (J->frame < 0) J->frame = tr.nframes - 1;
    r = tr.r + (size_t)J->frame * 2 * n;
    theta = tr.theta + (size_t)J->frame * n;
  } else if (!model_valid(&J->p, &J->b) || !load_points(J->path, &J->b, &n,
                                                         &r)) {
    return EXIT_BAD_INPUT;
  }
  if (n == 0) {
    fprintf(stderr, "afv draw: %s: no cells to draw (the %s holds none)\n",
            J->path, traj ? "trajectory" : "POINTS file");
    if (traj) afv_traj_free(&tr);
    else free(r);
    return EXIT_BAD_INPUT;
  }
  if (model_valid(&J->p, &J->b) && draw_check_box(J)
      && (!J->color_by || strcmp(J->color_by, "cluster") == 0
          || color_values(J, traj, n, &value))
      && (g = afv_geom_new()) != NULL) {
    J->o.color_by_cluster = J->color_by && !strcmp(J->color_by, "cluster");
    J->o.value = value;
    J->o.value_name = J->color_by;
    if (J->frames_dir) st = draw_frames(J, &tr, g);
    else if ((st = draw_one(stdout, J, g, n, r, theta,
                            traj ? tr.t[J->frame] : NAN, NULL)) == 0
             && fflush(stdout) != 0)
      st = bad_input("draw: cannot write the SVG");
  }
  afv_geom_delete(g);
  if (traj) afv_traj_free(&tr);
  else free(r);
  free(value);
  return st;
}

int cmd_draw(int argc, char **argv)
{
  draw_job J;
  int k;
  memset(&J, 0, sizeof J);
  J.frame = -1;
  afv_params_default(&J.p);
  for (k = 1; k < argc; k++)
    if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
      printf("%s%s", draw_usage, model_help);
      return 0;
    }
  if (!draw_parse(argc, argv, &J)) return EXIT_BAD_INPUT;
  return draw_run(&J);
}


/* 1 if P0* = 6 + (2 Lambda/KA - A0 + 3 sqrt(3)/2) / (4 KP/KA (1 - sqrt(3)/2))
** is finite, with each step of it; else names the key that overflows it
** (or underflows KP/KA) and returns 0. */
static int meanfield_computable(double Lambda, double A0, double KP, double KA)
{
  double lam = Lambda / KA, kp = KP / KA, num = 2 * lam - A0 + 1.5 * sqrt(3.0);
  const char *key = NULL;
  double v = 0;
  if (huge(lam)) {
    key = fabs(Lambda) >= 1 ? "Lambda" : "KA";
    v = fabs(Lambda) >= 1 ? Lambda : KA;
  } else if (!(kp * HEADROOM >= DBL_MIN) || huge(kp)) {
    key = KP < 1 ? "KP" : "KA";
    v = KP < 1 ? KP : KA;
  } else if (huge(num)) {
    key = fabs(A0) > fabs(2 * lam) ? "A0" : "Lambda";
    v = fabs(A0) > fabs(2 * lam) ? A0 : Lambda;
  } else if (huge(6 + num / (4 * kp * (1 - 0.5 * sqrt(3.0))))) {
    key = "KP"; v = KP;
  }
  if (!key) return 1;
  fprintf(stderr, "afv meanfield: --%s: %g: P0* overflows (Lambda %g, A0 %g, "
          "KP %g, KA %g)\n", key, v, Lambda, A0, KP, KA);
  return 0;
}

int cmd_meanfield(int argc, char **argv)
{
  double Lambda = 0.2, A0 = 3.14159265358979323846, KP = 1, KA = 1, pstar;
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
  if (!meanfield_computable(Lambda, A0, KP, KA)) return EXIT_BAD_INPUT;
  pstar = afv_meanfield_p0(Lambda / KA, A0, KP / KA);
  printf(fabs(pstar) < 1e15 ? "%.4f\n" : "%.6e\n", pstar);   /* no 300 digits */
  return 0;
}
