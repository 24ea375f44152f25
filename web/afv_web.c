/*
** web/afv_web.c -- what the page (web/afv.js) asks of the library, on
** afv.h alone: one tissue, started as `afv run` starts it, stepped, and
** read back as numbers and as cell outlines to draw.
**
** Built with the library's sources into web/afv.wasm (make web; the
** Makefile's WEB_EXPORTS lists the functions below that the page calls).
** Plain C99 without a line for the browser: the JavaScript passes numbers
** only (a 64-bit seed as two 32-bit halves) and reads the results through
** the pointers returned here.
**
** The start is afv run's default (cmd/run.c, cfg_protocol): init cluster,
** the authors' square of side AFV_AUTHORS_SQUARE L in the periodic box of
** side L = sqrt(N pi l^2 / phi), phi = 0.5, relaxed by the overdamped flow
** at v0 = 0 to max |F| <= 1e-6 or a kink (afv_protocol_start), then v0 on.
** Every other key keeps afv run's default (l, KA, KP, mu = 1, A0 = pi),
** so the page and `afv run --N .. --P0 .. --seed ..` compute the same
** tissue.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "afv.h"

#define WEB_PHI       0.5    /* afv run's default packing fraction */
#define WEB_RELAX_TOL 1e-6   /* afv run's default relax_tol */

/* Called by the relaxation every `progress_every` flow steps (the page's
** JavaScript defines it: it draws the tissue as it relaxes). */
void web_relax_progress(double iter, double energy, double max_force);

/* What web_observe fills, by index (web/afv.js reads the same indices). */
enum { OBS_ENERGY, OBS_GIANT, OBS_OMEGA, OBS_CLUSTERS, OBS_STEP, OBS_TIME,
       OBS_MAX_FORCE, OBS_N, OBS_BOX, OBS_COUNT };

/* The page's tissue: one at a time. */
static afv_sim *sim;
static afv_relax_report relax_report;
static long progress_every;      /* 0: no web_relax_progress calls */
static double observed[OBS_COUNT];
static double order[AFV_ORDER_COUNT];
static int *label;               /* each cell's cluster (n ints) */
static double *shape;            /* web_shapes: the outlines to draw */
static int shape_cap, shape_len; /* its capacity and length, in doubles */

static void relax_monitor(void *ctx, long iter, double energy,
                          double max_force)
{
  (void)ctx;
  if (progress_every > 0 && iter % progress_every == 0)
    web_relax_progress((double)iter, energy, max_force);
}

/* A new tissue of n cells: afv run's default start with these keys
** (seed = seed_hi 2^32 + seed_lo; relax_max_steps as afv run's key, its
** default 100000), relaxed, v0 on, step 0.  Status as afv_protocol_start
** (the page has clamped every value to afv run's ranges before). */
int web_reset(int n, double P0, double v0, double Lambda, double dt,
              double cap, double Dr, double seed_hi, double seed_lo,
              double relax_max_steps, double progress)
{
  afv_params p;
  afv_box b;
  afv_dyn d;
  afv_protocol pr;
  afv_sim_delete(sim);
  free(label);
  label = NULL;
  if (!(sim = afv_sim_new())
      || !(label = malloc((size_t)(n > 0 ? n : 1) * sizeof *label)))
    return AFV_ENOMEM;
  afv_params_default(&p);
  p.P0 = P0; p.Lambda = Lambda; p.cap = cap;
  b.periodic = 1;
  b.Lx = b.Ly = sqrt((double)n * 3.14159265358979323846 * p.l * p.l
                     / WEB_PHI);
  afv_dyn_default(&d);
  d.v0 = v0; d.dt = dt; d.Dr = Dr;
  d.seed = (unsigned long long)seed_hi << 32 | (unsigned long long)seed_lo;
  memset(&pr, 0, sizeof pr);
  pr.start = AFV_START_CLUSTER;
  pr.side = AFV_AUTHORS_SQUARE * b.Lx;
  pr.relax = AFV_RELAX_FLOW;
  pr.relax_tol = WEB_RELAX_TOL;
  pr.relax_max_steps = (long)relax_max_steps;
  progress_every = (long)progress;
  return afv_protocol_start(sim, n, &p, &b, &d, &pr, &relax_report,
                            relax_monitor, NULL);
}

/* The last relaxation's report by field name, as afv_relax_report_get
** (name: a NUL-terminated string the page wrote into web_scratch). */
double web_relax_get(const char *name)
{
  double v = NAN;
  afv_relax_report_get(&relax_report, name, &v);
  return v;
}

/* A buffer of 64 bytes the page writes short strings into. */
char *web_scratch(void)
{
  static char scratch[64];
  return scratch;
}

/* k steps of the active run; stops at the first that fails and returns
** its status (AFV_EUNSTABLE: web_bad_cell, web_bad_disp say why). */
int web_step(int k)
{
  int st = AFV_OK;
  if (!sim) return AFV_EINVAL;
  while (k-- > 0 && (st = afv_sim_step(sim)) == AFV_OK) {}
  return st;
}

int    web_bad_cell(void) { return sim ? afv_sim_bad_cell(sim) : -1; }
double web_bad_disp(void) { return sim ? afv_sim_bad_disp(sim) : NAN; }

/* New values of the keys the page changes while it runs: the model's
** (then the forces are recomputed: afv_sim_refresh) and the dynamics'
** (read afresh by every step).  Status as afv_sim_refresh. */
int web_set(double P0, double v0, double Lambda, double dt, double cap)
{
  afv_params *p;
  afv_dyn *d;
  if (!sim) return AFV_EINVAL;
  p = afv_sim_params(sim);
  d = afv_sim_dyn(sim);
  p->P0 = P0; p->Lambda = Lambda; p->cap = cap;
  d->v0 = v0; d->dt = dt;
  return afv_sim_refresh(sim);
}

/* The numbers the page shows (observed[OBS_*]; NULL before a tissue or
** if the clusters could not be computed): as observables.csv has them. */
double *web_observe(void)
{
  const afv_geom *g;
  afv_params *p;
  if (!sim || !label) return NULL;
  g = afv_sim_geom(sim);
  p = afv_sim_params(sim);
  if (afv_order_parameters(g, afv_sim_positions(sim), p->l, afv_sim_box(sim),
                           order, label) != AFV_OK)
    return NULL;
  observed[OBS_ENERGY] = afv_geom_energy(g);
  observed[OBS_GIANT] = order[AFV_ORDER_GIANT];
  observed[OBS_OMEGA] = order[AFV_ORDER_OMEGA];
  observed[OBS_CLUSTERS] = order[AFV_ORDER_CLUSTERS];
  observed[OBS_STEP] = (double)afv_sim_steps(sim);
  observed[OBS_TIME] = afv_sim_time(sim);
  observed[OBS_MAX_FORCE] = afv_sim_max_force(sim);
  observed[OBS_N] = afv_sim_n(sim);
  observed[OBS_BOX] = afv_sim_box(sim)->Lx;
  return observed;
}

/* 1 if shape has room for m more doubles (grown if needed), else 0. */
static int shape_room(int m)
{
  double *grown;
  int cap;
  if (shape_len + m <= shape_cap) return 1;
  cap = 2 * (shape_len + m);
  if (!(grown = realloc(shape, (size_t)cap * sizeof *grown))) return 0;
  shape = grown;
  shape_cap = cap;
  return 1;
}

/* The outlines of the cells, after web_observe (for the cluster labels):
** per cell, its centre wrapped into the box (x, y), its cluster, the
** number m of its boundary pieces, then per piece its start vertex
** relative to the centre and its neighbour (AFV_ARC: an arc of radius l
** to the next piece's start, counter-clockwise).  Returns the doubles
** written (0: out of memory); web_shape_data points at them. */
int web_shapes(void)
{
  const afv_geom *g = afv_sim_geom(sim);
  const double *r = afv_sim_positions(sim);
  int n = afv_sim_n(sim), i, k;
  shape_len = 0;
  for (i = 0; i < n; i++) {
    const afv_piece *pc;
    int m = afv_geom_pieces(g, i, &pc);
    double *o;
    if (!shape_room(4 + 3 * m)) return 0;
    o = shape + shape_len;
    o[0] = r[2*i];
    o[1] = r[2*i+1];
    afv_wrap(afv_sim_box(sim), &o[0], &o[1]);
    o[2] = label[i];
    o[3] = m;
    for (k = 0; k < m; k++) {
      o[4 + 3*k] = pc[k].x;
      o[5 + 3*k] = pc[k].y;
      o[6 + 3*k] = pc[k].nbr;
    }
    shape_len += 4 + 3 * m;
  }
  return shape_len;
}

double *web_shape_data(void) { return shape; }
