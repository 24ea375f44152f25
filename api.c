/*
** api.c -- the public face of the two opaque types of afv.h, afv_geom and
** afv_sim: their constructors, destructors and accessors.  Each call only
** reads or hands out a field of the struct in afv_internal.h; the work is
** done elsewhere (geometry: neighbours.c, geom.c, afv.c; steps: dynamics.c).
*/
#include "afv_internal.h"

#include <stdlib.h>

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
void       afv_sim_set_steps(afv_sim *s, long long step) { s->step = step; }
double     afv_sim_time(const afv_sim *s)     { return s->t; }
double    *afv_sim_positions(afv_sim *s)      { return s->r; }
double    *afv_sim_angles(afv_sim *s)         { return s->theta; }
const double   *afv_sim_forces(const afv_sim *s) { return s->f; }
const afv_geom *afv_sim_geom(const afv_sim *s)   { return &s->geom; }
afv_params *afv_sim_params(afv_sim *s)        { return &s->par; }
afv_box    *afv_sim_box(afv_sim *s)           { return &s->box; }
afv_dyn    *afv_sim_dyn(afv_sim *s)           { return &s->dyn; }
long long  afv_sim_substeps(const afv_sim *s) { return s->substeps; }
long long  afv_sim_halvings(const afv_sim *s) { return s->halvings; }
long long  afv_sim_jumps(const afv_sim *s) { return s->jumps; }
double     afv_sim_largest_move(const afv_sim *s) { return s->largest_move; }
int        afv_sim_bad_cell(const afv_sim *s) { return s->bad_cell; }
double     afv_sim_bad_disp(const afv_sim *s) { return s->bad_disp; }
double     afv_sim_bad_time(const afv_sim *s) { return s->bad_time; }
