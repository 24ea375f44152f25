/*
** dt_study.c -- the rule that says whether a conclusion drawn at the
** paper's dt = 0.01 belongs to the AFV model, applied to the dt study's
** table (tools/model_table.sh's dt_table.csv: one row per state point
** (P0, v0) and dt, each observable's mean over the seeds and its
** standard error).  The rule is doc/reproduction/model/README.md's ("The
** rule (decided before the runs)"), and this file is its only copy: the
** claims table (claims.c) and dt_verdicts.csv (afv paper --dt-verdicts,
** which tools/model_table.sh calls) both use dt_rule.
**
**   missing         the numbers the rule needs are not all there: two
**                   seeds (a mean and a standard error) at dt 0.005 and
**                   0.0025, and the mean at dt 0.01;
**   property of dt = 0.01
**                   the conclusion at dt 0.0025 differs from the one at
**                   0.01 (whether or not the finest two agree: the
**                   direction is then known, the limit is not);
**   property of the model
**                   converged, |mean_0.005 - mean_0.0025| <= 2 sqrt(sem_1^2
**                   + sem_2^2), and the same conclusion at 0.0025 as at
**                   0.01;
**   not converged   the same conclusion, but the finest two differ.
**
** What "the conclusion" is depends on the claim (dt_same_fn): the side of
** a threshold (a label), the claim's judgement against the paper, or the
** value itself within the same 2-sigma rule (dt_same_value).
*/
#include "paper.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const double dt_steps[DT_STEPS] = {0.01, 0.005, 0.0025};

/* The observables of dt_table.csv (tools/model_table.sh's OBS, each as
** NAME_mean and NAME_sem) and the threshold of the label drawn from each
** (NaN: none; the levels of paper.h, as afv collect labels). */
static const struct {
  const char *name;
  double level;
} observables[] = {
  {"ngc_frac_mean", CLUSTER_LEVEL},  {"n_clusters_mean", NAN},
  {"omega_mean", CONFLUENCY_LEVEL},  {"D_eff", DEFF_GLASS_LEVEL},
  {"msd_beta", BETA_GLASS_LEVEL},    {"beta_long", NAN},
  {"t1_rate", NAN},                  {"csd_exponent", NAN},
};
#define N_OBS ((int)(sizeof observables / sizeof observables[0]))
typedef char obs_fit_dt_table[N_OBS <= DT_OBS_MAX ? 1 : -1];

/* The columns of T->key, in find_columns' order. */
enum { K_P0, K_V0, K_DT, K_CAP, K_SEEDS };

static const char *const verdict_names[] = {
  "property of the model", "property of dt = 0.01", "not converged",
  "missing", "not measured", "none"};

const char *dt_verdict_name(dt_verdict v) { return verdict_names[v]; }

/* Two values of a table (printed with %g or %.6g) name the same P0, v0
** or dt. */
static int same_number(double a, double b)
{
  return fabs(a - b) <= 1e-9 * fmax(1, fabs(a));
}

/* ---- reading the table --------------------------------------------------- */
/* Bad input: one line naming the file, the line and the key; 0. */
static int dt_bad(const dt_table *T, int row, const char *key,
                  const char *what)
{
  fprintf(stderr, "afv paper: %s line %d: %s: %s\n", T->path,
          row < 0 ? 1 : T->t.line[row], key, what);
  return 0;
}

/* Cell (row, col) as a number: the whole field must read (empty is NaN
** where empty_ok: a standard error of one seed); 0 if it does not. */
static int cell_number(const dt_table *T, int row, int col, int empty_ok,
                       double *x)
{
  const char *s = csv_str(&T->t, row, col);
  char *end;
  if (!*s) { *x = NAN; return empty_ok; }
  *x = strtod(s, &end);
  return end != s && *end == 0;
}

/* The columns: P0, v0, dt, cap, n_seeds, then NAME_mean, NAME_sem per
** observable; 0 (message) if one is absent. */
static int find_columns(dt_table *T)
{
  static const char *const keys[DT_KEYS] = {"P0", "v0", "dt", "cap",
                                            "n_seeds"};
  char name[CELL_MAX];
  int k;
  for (k = 0; k < DT_KEYS; k++)
    if ((T->key[k] = csv_col(&T->t, keys[k])) < 0)
      return dt_bad(T, -1, keys[k], "no such column");
  for (k = 0; k < 2 * N_OBS; k++) {
    snprintf(name, sizeof name, "%s_%s", observables[k / 2].name,
             k % 2 ? "sem" : "mean");
    if ((T->obs[k] = csv_col(&T->t, name)) < 0)
      return dt_bad(T, -1, name, "no such column");
  }
  return 1;
}

/* Row r: every field a number (a standard error may be empty: one seed),
** the cap the first row's, no second row for the same (P0, v0, dt). */
static int check_row(dt_table *T, int r)
{
  double x, key[DT_KEYS];
  int k, q;
  for (k = 0; k < DT_KEYS; k++)
    if (!cell_number(T, r, T->key[k], 0, &key[k]) || !isfinite(key[k]))
      return dt_bad(T, r, T->t.name[T->key[k]], "not a number");
  for (k = 0; k < 2 * N_OBS; k++)
    if (!cell_number(T, r, T->obs[k], k % 2, &x))
      return dt_bad(T, r, T->t.name[T->obs[k]], "not a number");
  if (key[K_SEEDS] < 1 || key[K_SEEDS] != floor(key[K_SEEDS]))
    return dt_bad(T, r, "n_seeds", "not a whole number of seeds");
  if (r == 0) T->cap = key[K_CAP];
  else if (!same_number(key[K_CAP], T->cap))
    return dt_bad(T, r, "cap", "differs from the first row's: one dt table "
                  "holds one model");
  for (q = 0; q < r; q++)
    if (same_number(csv_num(&T->t, q, T->key[K_P0]), key[K_P0])
        && same_number(csv_num(&T->t, q, T->key[K_V0]), key[K_V0])
        && same_number(csv_num(&T->t, q, T->key[K_DT]), key[K_DT]))
      return dt_bad(T, r, "dt", "a second row for this P0, v0 and dt");
  return 1;
}

int dt_table_read(const char *path, dt_table *T)
{
  int r;
  memset(T, 0, sizeof *T);
  snprintf(T->path, sizeof T->path, "%s", path);
  if (!csv_read(path, &T->t)) return 0;
  if (!find_columns(T)) { csv_free(&T->t); return 0; }
  for (r = 0; r < T->t.nrow; r++)
    if (!check_row(T, r)) { csv_free(&T->t); return 0; }
  return 1;
}

void dt_table_free(dt_table *T) { csv_free(&T->t); }

static int obs_index(const char *name)
{
  int k;
  for (k = 0; k < N_OBS; k++)
    if (!strcmp(observables[k].name, name)) return k;
  return -1;
}

/* Observable `name` at (p0, v0): its mean, sem and seeds at each dt of
** dt_steps (seeds 0 where no row); 0 if no row holds (p0, v0). */
int dt_series_at(const dt_table *T, double p0, double v0, const char *name,
                 dt_series *s)
{
  int r, i, o = obs_index(name), found = 0;
  s->p0 = p0;
  s->v0 = v0;
  for (i = 0; i < DT_STEPS; i++) {
    s->mean[i] = s->sem[i] = NAN;
    s->seeds[i] = 0;
  }
  for (r = 0; o >= 0 && r < T->t.nrow; r++) {
    if (!same_number(csv_num(&T->t, r, T->key[K_P0]), p0)
        || !same_number(csv_num(&T->t, r, T->key[K_V0]), v0))
      continue;
    found = 1;
    for (i = 0; i < DT_STEPS; i++)
      if (same_number(csv_num(&T->t, r, T->key[K_DT]), dt_steps[i])) {
        s->seeds[i] = (int)csv_num(&T->t, r, T->key[K_SEEDS]);
        s->mean[i] = csv_num(&T->t, r, T->obs[2 * o]);
        s->sem[i] = *csv_str(&T->t, r, T->obs[2 * o + 1])   /* empty: */
                    ? csv_num(&T->t, r, T->obs[2 * o + 1]) : NAN; /* 1 seed */
      }
  }
  return found;
}

/* ---- the rule -------------------------------------------------------------- */
/* dt index i has a mean and, with two seeds or more, its standard error. */
static int has_mean(const dt_series *s, int i)
{
  return s->seeds[i] >= 1 && isfinite(s->mean[i]);
}

static int has_sem(const dt_series *s, int i)
{
  return has_mean(s, i) && s->seeds[i] >= 2 && isfinite(s->sem[i]);
}

/* |mean_a - mean_b| <= 2 sqrt(sem_a^2 + sem_b^2): the seed means at dt
** index a and b agree (both must have their sem). */
int dt_agree(const dt_series *s, int a, int b)
{
  return fabs(s->mean[a] - s->mean[b])
         <= 2 * sqrt(s->sem[a] * s->sem[a] + s->sem[b] * s->sem[b]);
}

/* A label's conclusion at dt index i, as the claims table draws it
** (claims.c's judge): above (1) or below (-1) the level, or unresolved
** (0) when the mean lies within 2 standard errors of it. */
static int resolved_side(const dt_series *s, int i, double level)
{
  if (fabs(s->mean[i] - level) <= 2 * s->sem[i]) return 0;
  return s->mean[i] >= level ? 1 : -1;
}

/* The same conclusion of a label at dt 0.01 and 0.0025: the same resolved
** side; missing (-1) without the standard error at 0.01 (one seed). */
int dt_same_side(const dt_series *s, const void *level)
{
  double l = *(const double *)level;
  if (!has_sem(s, 0)) return -1;
  return resolved_side(s, 0, l) == resolved_side(s, DT_STEPS - 1, l);
}

int dt_same_value(const dt_series *s, const void *unused)
{
  (void)unused;
  if (!has_sem(s, 0)) return -1;
  return dt_agree(s, 0, DT_STEPS - 1);
}

dt_verdict dt_rule(const dt_series *s, dt_same_fn same, const void *how)
{
  int same_conclusion;
  if (!has_mean(s, 0) || !has_sem(s, 1) || !has_sem(s, 2)) return DT_MISSING;
  same_conclusion = same(s, how);
  if (same_conclusion < 0) return DT_MISSING;
  if (!same_conclusion) return DT_OF_DT;
  return dt_agree(s, 1, 2) ? DT_MODEL : DT_NOT_CONVERGED;
}

/* The worse of two verdicts of one claim's state points: property of dt =
** 0.01 above all (one state that moves with dt decides the claim, whatever
** a missing state would say), then not converged, then missing (or not
** measured), and property of the model only when every state is. */
dt_verdict dt_worse(dt_verdict a, dt_verdict b)
{
  static const int rank[] = {0, 3, 2, 1, 1, 0};
  return rank[b] > rank[a] ? b : a;
}

/* "0.083 +- 0.016 | 0.0417 +- 0.012 | 0.0478 (1 seed)": the means at dt
** 0.01 | 0.005 | 0.0025 ("-" where no row). */
void dt_series_text(const dt_series *s, char *buf, size_t len)
{
  size_t used = 0;
  int i;
  buf[0] = 0;
  for (i = 0; i < DT_STEPS && used < len; i++) {
    const char *sep = i ? " | " : "";
    if (!s->seeds[i])
      used += (size_t)snprintf(buf + used, len - used, "%s-", sep);
    else if (has_sem(s, i))
      used += (size_t)snprintf(buf + used, len - used, "%s%.3g +- %.2g", sep,
                               s->mean[i], s->sem[i]);
    else
      used += (size_t)snprintf(buf + used, len - used, "%s%.3g%s", sep,
                               s->mean[i], !isfinite(s->mean[i]) ? ""
                               : s->seeds[i] == 1 ? " (1 seed)" : " (no sem)");
  }
}

/* ---- dt_verdicts.csv ------------------------------------------------------ */
/* "yes,DIFF,BOUND" (dt index a against b by dt_agree) or "missing,,". */
static void put_comparison(FILE *fp, const dt_series *s, int a, int b)
{
  double d = fabs(s->mean[a] - s->mean[b]);
  if (!has_sem(s, a) || !has_sem(s, b)) { fputs(",missing,,", fp); return; }
  fprintf(fp, ",%s,%.4g,%.4g", dt_agree(s, a, b) ? "yes" : "no", d,
          2 * sqrt(s->sem[a] * s->sem[a] + s->sem[b] * s->sem[b]));
}

static void put_verdict_row(FILE *fp, const dt_series *s, int o)
{
  double level = observables[o].level;
  int i;
  fprintf(fp, "%g,%g,%s", s->p0, s->v0, observables[o].name);
  for (i = 0; i < DT_STEPS; i++)
    if (s->seeds[i]) fprintf(fp, ",%.6g", s->mean[i]);
    else fputc(',', fp);
  put_comparison(fp, s, 1, 2);
  put_comparison(fp, s, 0, 2);
  if (isfinite(level))
    fprintf(fp, ",%g,%s,%s\n", level,
            dt_verdict_name(dt_rule(s, dt_same_value, NULL)),
            dt_verdict_name(dt_rule(s, dt_same_side, &level)));
  else
    fprintf(fp, ",,%s,\n", dt_verdict_name(dt_rule(s, dt_same_value, NULL)));
}

int dt_state_points(const dt_table *T, double (*pt)[2], int max)
{
  int r, k, n = 0;
  for (r = 0; r < T->t.nrow; r++) {
    double p0 = csv_num(&T->t, r, T->key[K_P0]);
    double v0 = csv_num(&T->t, r, T->key[K_V0]);
    for (k = 0; k < n; k++)
      if (same_number(pt[k][0], p0) && same_number(pt[k][1], v0)) break;
    if (k < n || n == max) continue;
    for (k = n++; k > 0 && (pt[k - 1][0] > p0
                            || (pt[k - 1][0] == p0 && pt[k - 1][1] > v0)); k--) {
      pt[k][0] = pt[k - 1][0];
      pt[k][1] = pt[k - 1][1];
    }
    pt[k][0] = p0;
    pt[k][1] = v0;
  }
  return n;
}

int dt_verdicts_write(const dt_table *T, const char *path)
{
  char tmp[PATH_LEN + 16];
  double pt[DT_MAX_POINTS][2];
  dt_series s;
  FILE *fp = afv_atomic_open(path, tmp, sizeof tmp);
  int o, k, n = dt_state_points(T, pt, DT_MAX_POINTS);
  if (!fp) return 0;
  fprintf(fp, "P0,v0,observable,at_0.01,at_0.005,at_0.0025,"
          "converged_0.005_0.0025,diff_fine,bound_fine,same_at_0.01,"
          "diff_0.01,bound_0.01,threshold,verdict_value,verdict_threshold\n");
  for (o = 0; o < N_OBS; o++)
    for (k = 0; k < n; k++) {
      dt_series_at(T, pt[k][0], pt[k][1], observables[o].name, &s);
      put_verdict_row(fp, &s, o);
    }
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}
