/*
** twins.c -- the fast and the reference build as twins (make twins).
**
** The reference mode (make REFERENCE=1, doc/reference.md) is chosen at
** compile time, so no one program holds both.  This program is built from
** the library's sources twice, once in each mode (Makefile: test/twins_fast,
** test/twins_ref), and each build prints the results of the same
** configurations (test/fixtures.c, test_config_make) in %.17g:
**   every cell's area, perimeter, arc length, piece and contact counts,
**   the energy and every force;  then 100 steps of active dynamics from
**   four of them: every position and angle, the sub-steps, the status.
** Then
**     twins_fast --compare FAST_OUTPUT REF_OUTPUT
** reads the two outputs line by line and requires
**   shapes     |a - b| <= 1e-12 max(|a|, |b|, 1)   (l = 1: lengths in l,
**              areas in l^2; counts equal)
**   energy     |a - b| <= 1e-12 sum_i |e_i|
**   forces     |a - b| <= 1e-12 max(max_i |F_i|, 1)   (componentwise; the
**              force scale of the configuration, large near detachment, but
**              at least KA l^3 = 1, the size of the chain-rule terms that
**              cancel to rounding in a lattice, where F = 0)
**   dynamics   |a - b| <= 1e-9 l for every coordinate after 100 steps
**              (and 1e-9 for every angle); sub-steps and status equal,
** and prints the largest differences it saw.  It refuses two outputs of
** the same mode (a build that ignored the switch would compare a mode with
** itself).  Exit status 0 if all agree, 1 if not, 2 on bad use or input.
** Why two programs and not the reference functions renamed into the test
** binary: the switch reaches into afv_compute and afv_sim_step (the
** neighbour search, the noise), so a renamed twin would have to duplicate
** the whole library's external names; two builds of the same sources test
** exactly what `make REFERENCE=1` builds.
*/
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STEPS      100
#define SHAPE_TOL  1e-12
#define DYN_TOL    1e-9

/* ---- writing ----------------------------------------------------------- */
static void paper_params(afv_params *p)
{
  afv_params_default(p);   /* l = 1, KA = KP = 1, A0 = pi, Lambda = 0.2 */
  p->P0 = 4.2;
}

static int write_statics(const test_config *c)
{
  afv_params p;
  afv_geom g = {0};
  double *f = malloc((size_t)(2 * c->n + 1) * sizeof(double));
  double escale = 0, fscale = 0;
  int i, st;
  paper_params(&p);
  if (!f) return AFV_ENOMEM;
  st = afv_compute(&g, c->n, c->r, &p, &c->box, f);
  printf("config %s %d %d\n", c->name, c->n, st);
  for (i = 0; st == AFV_OK && i < c->n; i++) {
    printf("shape %d %.17g %.17g %.17g %d %d\n", i, g.area[i], g.perim[i],
           g.arc[i], g.n_pieces[i], g.contacts[i]);
    escale += fabs(afv_cell_energy(&p, i, g.area[i], g.perim[i], g.arc[i]));
    fscale = fmax(fscale, hypot(f[2*i], f[2*i+1]));
  }
  if (st == AFV_OK) {
    printf("energy %.17g %.17g\n", g.energy, escale);
    printf("forces %.17g\n", fscale);
    for (i = 0; i < c->n; i++)
      printf("force %d %.17g %.17g\n", i, f[2*i], f[2*i+1]);
  }
  afv_geom_free(&g);
  free(f);
  return AFV_OK;
}

/* 100 steps at self-propulsion v0 from c (angles from afv_init_angles). */
static int write_dynamics(const test_config *c, double v0)
{
  afv_params p;
  afv_dyn d;
  afv_sim s = {0};
  double *theta = malloc((size_t)(c->n + 1) * sizeof(double));
  int k, st;
  if (!theta) return AFV_ENOMEM;
  paper_params(&p);
  afv_dyn_default(&d);      /* mu = 1, Dr = 0.1, dt = 0.01 */
  d.v0 = v0;
  d.seed = 5;
  afv_init_angles(c->n, 11, theta);
  st = afv_sim_init(&s, c->n, c->r, theta, &p, &c->box, &d);
  for (k = 0; st == AFV_OK && k < STEPS; k++) st = afv_sim_step(&s);
  printf("dynamics %s %d %d %lld\n", c->name, k, st,
         st == AFV_OK ? s.substeps : -1LL);
  for (k = 0; st == AFV_OK && k < c->n; k++)
    printf("cell %d %.17g %.17g %.17g\n", k, s.r[2*k], s.r[2*k+1],
           s.theta[k]);
  afv_sim_free(&s);
  free(theta);
  return st == AFV_ENOMEM ? st : AFV_OK;
}

/* The self-propulsion of each configuration's run (0: no run). */
static double run_v0(const char *name)
{
  if (!strcmp(name, "near_detachment")) return 0.3;
  if (!strcmp(name, "lattice_jittered")) return 0.5;
  if (!strcmp(name, "random_periodic") || !strcmp(name, "cluster")) return 1;
  return 0;
}

static int write_all(void)
{
  test_config c;
  int k, made;
  printf("mode %s\n", AFV_REFERENCE_MODE ? "reference" : "fast");
  for (k = 0; (made = test_config_make(k, &c)) == 1; k++) {
    int st = write_statics(&c);
    if (st == AFV_OK && run_v0(c.name) > 0)
      st = write_dynamics(&c, run_v0(c.name));
    test_config_free(&c);
    if (st != AFV_OK) made = -1;
    if (made < 0) break;
  }
  if (made < 0) {
    fprintf(stderr, "twins: out of memory\n");
    return 2;
  }
  return 0;
}

/* ---- comparing ----------------------------------------------------------- */
#define MAXV 8

/* One line: its kind and up to MAXV numbers after it. */
typedef struct line {
  char kind[32], name[64];
  double v[MAXV];
  int nv;
} line;

/* Reads the next line of fp into L; 0 at the end. */
static int read_line(FILE *fp, line *L)
{
  char buf[512], *p, *end;
  if (!fgets(buf, sizeof buf, fp)) return 0;
  L->nv = 0;
  L->name[0] = 0;
  if (sscanf(buf, "%31s", L->kind) != 1) return 0;
  p = buf + strlen(L->kind);
  if (!strcmp(L->kind, "config") || !strcmp(L->kind, "dynamics")
      || !strcmp(L->kind, "mode")) {
    if (sscanf(p, "%63s", L->name) != 1) return 0;
    p = strstr(p, L->name) + strlen(L->name);
  }
  while (L->nv < MAXV) {
    double x = strtod(p, &end);
    if (end == p) break;
    L->v[L->nv++] = x;
    p = end;
  }
  return 1;
}

/* The largest differences seen, relative to each tolerance's scale. */
typedef struct worst {
  double shape, energy, force, pos;
  int bad;
} worst;

static void close_to(worst *w, double *seen, double a, double b, double tol,
                     double scale, const char *what, const line *L)
{
  double diff = fabs(a - b) / scale;
  if (diff > *seen || isnan(diff)) *seen = diff;
  if (!(diff <= tol)) {
    if (w->bad < 10)
      printf("twins: %s %s %g: fast %.17g, reference %.17g (%.3g of the "
             "scale)\n", L->kind, what, L->v[0], a, b, diff);
    w->bad++;
  }
}

static void equal(worst *w, double a, double b, const char *what,
                  const line *L)
{
  if (a != b) {
    if (w->bad < 10)
      printf("twins: %s %s: fast %g, reference %g\n", L->kind, what, a, b);
    w->bad++;
  }
}

/* Compares line a (fast) with line b (reference), of the same kind. */
static void compare_line(worst *w, const line *a, const line *b,
                         double *escale, double *fscale)
{
  int k;
  if (!strcmp(a->kind, "shape")) {
    for (k = 1; k <= 3; k++)
      close_to(w, &w->shape, a->v[k], b->v[k], SHAPE_TOL,
               fmax(1, fmax(fabs(a->v[k]), fabs(b->v[k]))),
               k == 1 ? "area" : k == 2 ? "perimeter" : "arc", a);
    equal(w, a->v[4], b->v[4], "pieces", a);
    equal(w, a->v[5], b->v[5], "contacts", a);
  } else if (!strcmp(a->kind, "energy")) {
    *escale = a->v[1];
    close_to(w, &w->energy, a->v[0], b->v[0], SHAPE_TOL, *escale, "E", a);
  } else if (!strcmp(a->kind, "forces")) {
    *fscale = fmax(a->v[0], 1);
  } else if (!strcmp(a->kind, "force")) {
    for (k = 1; k <= 2; k++)
      close_to(w, &w->force, a->v[k], b->v[k], SHAPE_TOL, *fscale,
               k == 1 ? "F_x" : "F_y", a);
  } else if (!strcmp(a->kind, "cell")) {
    for (k = 1; k <= 3; k++)
      close_to(w, &w->pos, a->v[k], b->v[k], DYN_TOL, 1,
               k == 1 ? "x" : k == 2 ? "y" : "theta", a);
  } else {                        /* config, dynamics: every number equal */
    if (strcmp(a->name, b->name)) w->bad++;
    for (k = 0; k < a->nv; k++) equal(w, a->v[k], b->v[k], a->name, a);
  }
}

static int compare(const char *fast_path, const char *ref_path)
{
  FILE *fa = fopen(fast_path, "r"), *fb = fopen(ref_path, "r");
  line a, b;
  worst w = {0, 0, 0, 0, 0};
  double escale = 1, fscale = 1;
  long lines = 0;
  int ra, rb;
  if (!fa || !fb) {
    fprintf(stderr, "twins: cannot read %s\n", !fa ? fast_path : ref_path);
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return 2;
  }
  ra = read_line(fa, &a);
  rb = read_line(fb, &b);
  if (!ra || !rb || strcmp(a.kind, "mode") || strcmp(b.kind, "mode")
      || strcmp(a.name, "fast") || strcmp(b.name, "reference")) {
    fprintf(stderr, "twins: want a fast output, then a reference one "
            "(got '%s', '%s')\n", ra ? a.name : "", rb ? b.name : "");
    fclose(fa);
    fclose(fb);
    return 2;
  }
  for (;;) {
    ra = read_line(fa, &a);
    rb = read_line(fb, &b);
    if (!ra || !rb) break;
    lines++;
    if (strcmp(a.kind, b.kind) || a.nv != b.nv) {
      printf("twins: line %ld differs in form: %s, %s\n", lines + 1, a.kind,
             b.kind);
      w.bad++;
      break;
    }
    compare_line(&w, &a, &b, &escale, &fscale);
  }
  if (ra != rb) {
    printf("twins: one output ends before the other\n");
    w.bad++;
  }
  fclose(fa);
  fclose(fb);
  printf("twins: %ld lines; largest differences: shapes %.3g, energy %.3g, "
         "forces %.3g (of 1e-12), dynamics %.3g l (of 1e-9 l)\n", lines,
         w.shape, w.energy, w.force, w.pos);
  printf("twins: %s\n", w.bad ? "the two modes DIFFER" : "the two modes agree");
  return w.bad ? 1 : 0;
}

int main(int argc, char **argv)
{
  if (argc == 1) return write_all();
  if (argc == 4 && !strcmp(argv[1], "--compare"))
    return compare(argv[2], argv[3]);
  fprintf(stderr, "usage: twins | twins --compare FAST_OUTPUT REF_OUTPUT\n");
  return 2;
}
