/*
** api.c -- the public face of the two opaque types of afv.h, afv_geom and
** afv_sim: their constructors, destructors and accessors.  Each call only
** reads or hands out a field of the struct in afv_internal.h; the work is
** done elsewhere (geometry: neighbours.c, geom.c, afv.c; steps: dynamics.c).
** Then the calls for bindings (Python's ctypes, python/afv.py): afv_dyn and
** afv_relax_report read and written by name, the order parameters in one
** call, a picture written to a file.
*/
#include "afv_internal.h"
#include "afv_tool.h"   /* afv_atomic_open: afv_svg_save writes atomically */

#include <assert.h>
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
