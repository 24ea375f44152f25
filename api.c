/*
** api.c -- the public face of the two opaque types of afv.h, afv_geom and
** afv_sim: their constructors, destructors and accessors.  Each call only
** reads or hands out a field of the struct in afv_internal.h; the work is
** done elsewhere (geometry: neighbours.c, geom.c, afv.c; steps: dynamics.c).
** Then the calls for bindings (Python's ctypes, python/afv/): afv_dyn,
** afv_relax_report, afv_protocol and afv_analysis read and written by
** name, trajectories and MSDs through accessors, the order parameters in
** one call, a picture written to a file.
*/
#include "afv_internal.h"
#include "afv_tool.h"   /* afv_atomic_open: afv_svg_save writes atomically */

#include <assert.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* ---- afv_geom ---------------------------------------------------------- */
afv_geom *afv_geom_new(void)
{
  return calloc(1, sizeof(afv_geom));   /* zeroed: an empty geometry */
}

void afv_geom_delete(afv_geom *g)
{
  if (!g) return;
  afv_geom_free(g);                     /* its buffers */
  free(g);
}

int           afv_geom_n(const afv_geom *g)        { return g->n; }
const double *afv_geom_area(const afv_geom *g)     { return g->area; }
const double *afv_geom_perim(const afv_geom *g)    { return g->perim; }
const double *afv_geom_arc(const afv_geom *g)      { return g->arc; }
const int    *afv_geom_contacts(const afv_geom *g) { return g->contacts; }
double        afv_geom_energy(const afv_geom *g)   { return g->energy; }

int afv_geom_pieces(const afv_geom *g, int i, const afv_piece **pieces)
{
  *pieces = g->pieces + g->piece_start[i];
  return g->n_pieces[i];
}

/* Cell i's list is nbr[nbr_start[i] .. nbr_end[i] - 1] (room kept after it). */
int afv_geom_neighbours(const afv_geom *g, int i, const int **nbr,
                        const double **d)
{
  *nbr = g->nbr + g->nbr_start[i];
  if (d) *d = g->nbr_d + 2 * (size_t)g->nbr_start[i];
  return g->nbr_end[i] - g->nbr_start[i];
}

void afv_geom_bad_pair(const afv_geom *g, int *i, int *j)
{
  *i = g->bad_i;
  *j = g->bad_j;
}

/* ---- afv_sim ----------------------------------------------------------- */
afv_sim *afv_sim_new(void)
{
  return calloc(1, sizeof(afv_sim));    /* zeroed, as afv_sim_init wants */
}

void afv_sim_delete(afv_sim *s)
{
  if (!s) return;
  afv_sim_free(s);                      /* its buffers */
  free(s);
}

int        afv_sim_n(const afv_sim *s)        { return s->n; }
long long  afv_sim_steps(const afv_sim *s)    { return s->step; }
void       afv_sim_set_steps(afv_sim *s, long long step)
{
  s->step = step;
  s->t = (double)step * s->dyn.dt;      /* as afv_sim_step sets it */
}
double     afv_sim_time(const afv_sim *s)     { return s->t; }
double    *afv_sim_positions(afv_sim *s)      { return s->r; }
double    *afv_sim_angles(afv_sim *s)         { return s->theta; }
const double   *afv_sim_forces(const afv_sim *s) { return s->f; }
const afv_geom *afv_sim_geom(const afv_sim *s)   { return &s->geom; }
afv_params *afv_sim_params(afv_sim *s)        { return &s->par; }
afv_box    *afv_sim_box(afv_sim *s)           { return &s->box; }
afv_dyn    *afv_sim_dyn(afv_sim *s)           { return &s->dyn; }
long long  afv_sim_jumps(const afv_sim *s) { return s->jumps; }
double     afv_sim_largest_move(const afv_sim *s) { return s->largest_move; }
int        afv_sim_bad_cell(const afv_sim *s) { return s->bad_cell; }
double     afv_sim_bad_disp(const afv_sim *s) { return s->bad_disp; }

/* ---- for bindings (api.c, afv.h "bindings") ---------------------------- */
const char *afv_version(void) { return AFV_VERSION; }

size_t afv_struct_size(const char *name)
{
  if (!strcmp(name, "afv_params")) return sizeof(afv_params);
  if (!strcmp(name, "afv_box"))    return sizeof(afv_box);
  return 0;
}

/* The scalar fields of afv_dyn that afv_dyn_set/afv_dyn_get know, by name. */
static const struct { const char *name; size_t offset; } dyn_fields[] = {
  {"mu", offsetof(afv_dyn, mu)}, {"v0", offsetof(afv_dyn, v0)},
  {"Dr", offsetof(afv_dyn, Dr)}, {"dt", offsetof(afv_dyn, dt)}
};
#define N_DYN_FIELDS (sizeof dyn_fields / sizeof dyn_fields[0])

static double *dyn_field(afv_dyn *d, const char *name)
{
  size_t k;
  for (k = 0; k < N_DYN_FIELDS; k++)
    if (!strcmp(name, dyn_fields[k].name))
      return (double *)((char *)d + dyn_fields[k].offset);
  return NULL;
}

afv_dyn *afv_dyn_new(void)
{
  afv_dyn *d = calloc(1, sizeof(afv_dyn));
  if (d) afv_dyn_default(d);
  return d;
}

void afv_dyn_delete(afv_dyn *d) { free(d); }

/* 2^64 as a double: a seed must be an integer below it. */
#define SEED_LIMIT 18446744073709551616.0

int afv_dyn_set(afv_dyn *d, const char *name, double value)
{
  double *field;
  if (!strcmp(name, "seed")) {
    if (!(value >= 0 && value < SEED_LIMIT) || value != floor(value))
      return AFV_EINVAL;
    d->seed = (unsigned long long)value;
    return AFV_OK;
  }
  if (!(field = dyn_field(d, name))) return AFV_EINVAL;
  *field = value;
  return AFV_OK;
}

int afv_dyn_get(const afv_dyn *d, const char *name, double *value)
{
  double *field;
  if (!strcmp(name, "seed")) {
    *value = (double)d->seed;
    return AFV_OK;
  }
  if (!(field = dyn_field((afv_dyn *)d, name))) return AFV_EINVAL;
  *value = *field;
  return AFV_OK;
}

int afv_dyn_set_cells(afv_dyn *d, const char *name, const double *values)
{
  if (!strcmp(name, "v0"))      d->v0_i = values;
  else if (!strcmp(name, "Dr")) d->Dr_i = values;
  else return AFV_EINVAL;
  return AFV_OK;
}

afv_relax_report *afv_relax_report_new(void)
{
  return calloc(1, sizeof(afv_relax_report));
}

void afv_relax_report_delete(afv_relax_report *rep) { free(rep); }

int afv_relax_report_get(const afv_relax_report *rep, const char *name,
                         double *value)
{
  if      (!strcmp(name, "iterations")) *value = (double)rep->iterations;
  else if (!strcmp(name, "time"))       *value = rep->time;
  else if (!strcmp(name, "max_force"))  *value = rep->max_force;
  else if (!strcmp(name, "energy0"))    *value = rep->energy0;
  else if (!strcmp(name, "energy"))     *value = rep->energy;
  else if (!strcmp(name, "drift"))      *value = rep->drift;
  else if (!strcmp(name, "drop"))       *value = rep->drop;
  else if (!strcmp(name, "jumps"))      *value = (double)rep->jumps;
  else if (!strcmp(name, "converged"))  *value = rep->converged;
  else if (!strcmp(name, "at_kink"))    *value = rep->at_kink;
  else if (!strcmp(name, "refused"))    *value = rep->refused;
  else return AFV_EINVAL;
  return AFV_OK;
}

int afv_order_parameters(const afv_geom *g, const double *r, double l,
                         const afv_box *b, double *values, int *label)
{
  assert(g != NULL && values != NULL);
  afv_clusters c = {0};
  int st = afv_clusters_compute(&c, g, r, l, b);
  if (st == AFV_OK) {
    values[AFV_ORDER_GIANT] = c.n ? (double)c.giant / c.n : 0;
    values[AFV_ORDER_OMEGA] = c.omega;
    values[AFV_ORDER_CLUSTERS] = c.count;
    values[AFV_ORDER_PAIRS] = c.n_pairs;
    values[AFV_ORDER_JUNCTIONS] = c.n_junctions;
    if (label) memcpy(label, c.label, (size_t)c.n * sizeof *label);
  }
  afv_clusters_free(&c);
  return st;
}

int afv_svg_save(const char *path, const afv_geom *g, int n, const double *r,
                 const double *theta, const afv_params *p, const afv_box *b,
                 int color_by_cluster)
{
  assert(path != NULL && g != NULL);
  char tmp[4096];
  afv_draw_opts o = {0};
  FILE *fp;
  int st;
  o.color_by_cluster = color_by_cluster;
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) return AFV_EIO;
  st = afv_svg_draw(fp, g, n, r, theta, p, b, &o);
  if (st != AFV_OK) {
    fclose(fp);
    remove(tmp);
    return st;
  }
  return afv_atomic_commit(fp, tmp, path);
}

/* ---- trajectories, analysis and the protocol, for bindings ------------- */
afv_traj *afv_traj_new(void) { return calloc(1, sizeof(afv_traj)); }

void afv_traj_delete(afv_traj *tr)
{
  if (!tr) return;
  afv_traj_free(tr);
  free(tr);
}

/* Copies count values of size bytes from src, or zeroes them if src is
** NULL; NULL if out of memory (count 0 allocates one byte: never NULL). */
static void *copy_or_zero(const void *src, size_t count, size_t size)
{
  void *p = calloc(count ? count : 1, size);
  if (p && src) memcpy(p, src, count * size);
  return p;
}

int afv_traj_set(afv_traj *tr, int n, int nframes, const afv_box *b,
                 const long long *step, const double *t, const double *r,
                 const double *theta)
{
  size_t frames = (size_t)(nframes > 0 ? nframes : 0);
  int k;
  if (n < 0 || nframes < 0 || !t || !r) return AFV_EINVAL;
  afv_traj_free(tr);
  tr->step = copy_or_zero(step, frames, sizeof *tr->step);
  tr->t = copy_or_zero(t, frames, sizeof *tr->t);
  tr->r = copy_or_zero(r, frames * 2 * (size_t)n, sizeof *tr->r);
  tr->theta = copy_or_zero(theta, frames * (size_t)n, sizeof *tr->theta);
  if (!tr->step || !tr->t || !tr->r || !tr->theta) {
    afv_traj_free(tr);
    return AFV_ENOMEM;
  }
  if (!step)                      /* no steps given: the frames' order */
    for (k = 0; k < nframes; k++) tr->step[k] = k;
  tr->n = n;
  tr->nframes = nframes;
  tr->box = *b;
  return AFV_OK;
}

int              afv_traj_n(const afv_traj *tr)       { return tr->n; }
int              afv_traj_nframes(const afv_traj *tr) { return tr->nframes; }
const afv_box   *afv_traj_box(const afv_traj *tr)     { return &tr->box; }
const long long *afv_traj_steps(const afv_traj *tr)   { return tr->step; }
const double    *afv_traj_times(const afv_traj *tr)   { return tr->t; }
const double    *afv_traj_positions(const afv_traj *tr) { return tr->r; }
const double    *afv_traj_angles(const afv_traj *tr)  { return tr->theta; }

afv_msd *afv_msd_new(void) { return calloc(1, sizeof(afv_msd)); }

void afv_msd_delete(afv_msd *m)
{
  if (!m) return;
  afv_msd_free(m);
  free(m);
}

const double *afv_msd_series(const afv_msd *m, const char *name, int *count)
{
  *count = m->nlags;
  if (!strcmp(name, "lag"))     return m->dt;
  if (!strcmp(name, "msd"))     return m->msd;
  if (!strcmp(name, "msd_rel")) return m->msd_rel;
  *count = 0;
  return NULL;
}

afv_analysis *afv_analysis_new(void) { return calloc(1, sizeof(afv_analysis)); }

void afv_analysis_delete(afv_analysis *a)
{
  if (!a) return;
  afv_analysis_free(a);
  free(a);
}

const afv_msd *afv_analysis_msd(const afv_analysis *a) { return &a->msd; }

int afv_analysis_get(const afv_analysis *a, const char *name, double *value)
{
  static const char *means[3] = {"ngc_frac", "n_clusters", "omega"};
  char key[32];
  int k;
  for (k = 0; k < 3; k++) {
    snprintf(key, sizeof key, "%s_mean", means[k]);
    if (!strcmp(name, key)) {
      *value = a->mean[k];
      return AFV_OK;
    }
    snprintf(key, sizeof key, "%s_sd", means[k]);
    if (!strcmp(name, key)) {
      *value = a->sd[k];
      return AFV_OK;
    }
  }
  if      (!strcmp(name, "cells"))        *value = a->n;
  else if (!strcmp(name, "frames"))       *value = a->nframes;
  else if (!strcmp(name, "first"))        *value = a->first;
  else if (!strcmp(name, "t1_final"))     *value = a->t1_final;
  else if (!strcmp(name, "D_s"))          *value = a->ds;
  else if (!strcmp(name, "D_s_lag"))      *value = a->ds_lag;
  else if (!strcmp(name, "D_s_origins"))  *value = (double)a->ds_origins;
  else if (!strcmp(name, "D_s_plain"))    *value = a->ds_plain;
  else if (!strcmp(name, "D_0"))          *value = a->d0;
  else if (!strcmp(name, "D_eff"))        *value = a->deff;
  else if (!strcmp(name, "tau_NGC"))      *value = a->tau_ngc;
  else if (!strcmp(name, "tau_NGC_reliable")) *value = a->tau_reliable;
  else if (!strcmp(name, "t1_rate"))      *value = a->t1_rate;
  else if (!strcmp(name, "msd_beta"))     *value = a->msd_beta;
  else return AFV_EINVAL;
  return AFV_OK;
}

const double *afv_analysis_series(const afv_analysis *a, const char *name,
                                  int *count)
{
  *count = a->nframes;
  if (!strcmp(name, "time"))       return a->t;
  if (!strcmp(name, "ngc_frac"))   return a->ngc_frac;
  if (!strcmp(name, "n_clusters")) return a->n_clusters;
  if (!strcmp(name, "omega"))      return a->omega;
  if (!strcmp(name, "t1"))         return a->t1;
  *count = a->n;
  if (!strcmp(name, "csd")) return a->csd ? a->csd + 1 : NULL;
  return afv_msd_series(&a->msd, name, count);
}

afv_protocol *afv_protocol_new(void)
{
  afv_protocol *pr = calloc(1, sizeof(afv_protocol));
  if (!pr) return NULL;
  pr->start = AFV_START_CLUSTER;
  pr->relax = AFV_RELAX_FLOW;
  pr->relax_tol = 1e-6;
  pr->relax_max_steps = 100000;
  return pr;
}

void afv_protocol_delete(afv_protocol *pr) { free(pr); }

int afv_protocol_set(afv_protocol *pr, const char *name, double value)
{
  if (!strcmp(name, "start")) {
    if (!(value >= AFV_START_CLUSTER && value <= AFV_START_GIVEN)
        || value != floor(value))
      return AFV_EINVAL;
    pr->start = (int)value;
  } else if (!strcmp(name, "relax")) {
    if (value != AFV_RELAX_FLOW && value != AFV_RELAX_FIRE) return AFV_EINVAL;
    pr->relax = (int)value;
  } else if (!strcmp(name, "relax_max_steps")) {
    if (!(value >= 0 && value <= (double)LONG_MAX) || value != floor(value))
      return AFV_EINVAL;
    pr->relax_max_steps = (long)value;
  } else if (!strcmp(name, "side"))      pr->side = value;
  else if (!strcmp(name, "spacing"))     pr->spacing = value;
  else if (!strcmp(name, "relax_tol"))   pr->relax_tol = value;
  else return AFV_EINVAL;
  return AFV_OK;
}

int afv_protocol_set_cells(afv_protocol *pr, const char *name,
                           const double *values)
{
  if (!strcmp(name, "r"))          pr->r = values;
  else if (!strcmp(name, "theta")) pr->theta = values;
  else return AFV_EINVAL;
  return AFV_OK;
}
