/*
** claims.c -- the claims table of afv paper: every number or label the
** paper states that the grid can test, afv's value, its error and the
** judgement, by the rules of doc/reproduction/README.md ("How claims are
** judged"):
**
**   number   yes when |afv - paper| <= 2 sqrt(afv_err^2 + paper_err^2);
**   bracket  yes when the paper's value lies within afv +- afv_err (afv_err
**            is then half the grid interval that holds the change);
**   label    yes when afv's mean lies on the paper's side of the threshold.
**
** A claim agrees only when afv's figure is determined.  It is
** `undetermined`, never yes or no, when
**   - a number's or bracket's error is at least as large as the value
**     itself (any paper value would agree within such an error);
**   - a label's mean lies within 2 standard errors of its threshold (the
**     side is not resolved);
**   - a fit's parameter is not identifiable: the dispersal boundary's free
**     three-parameter fit, when its residual profile over alpha is flat
**     within the noise (alpha_interval below).
** `not measured` when the state point has no finished run; `missing`
** when it has fewer seeds than the design (one seed has no standard
** error), or, for a claim drawn from the whole grid (the crossing, the
** fits, the brackets along P0), when any point has: the value is given,
** no verdict is drawn until the runs are in.  The rules are the table
** `rules` below, one row per claim.
**
** Each claim's dependence on dt (the column dt_verdict, and the end of its
** note) comes from the dt study at the paper's length (afv paper
** --dt-table doc/reproduction/model/dt_table.csv), by dt_study.c's rule,
** when the runs were integrated as the study's (Euler at dt 0.01 with its
** cap).  The table's two last columns say where each claim is measured:
**   DTC_LABEL   a label at (P0, v0): the same observable at the same state
**               point, the conclusion the side of the label's threshold
**               (or unresolved, within 2 sem: dt_same_side).
**               msd_beta and D_eff at (P0, 0.4) are the glass rows of the
**               same P0; (8, 0.4) and the states at v0 0.1 and at P0 4.4
**               and 8.8, v0 2.6 are not in the study: `not measured`, the
**               note names the nearest state it has, never its verdict;
**   DTC_NUMBER  the cluster-size exponents at (4 or 8, 1.85): the
**               conclusion is the claim's own judgement against the paper
**               (yes / no / undetermined) at dt 0.01 and at 0.0025;
**   DTC_CURVES  the claims built on the N_GC/N grid (v0*, N_GC/N at v0*,
**               the dispersal line, the collapse, tau_NGC): N_GC/N at the
**               six dispersal states (4 and 8 x 1.4, 1.85, 2.6), the
**               conclusion its value (0.01 against 0.0025 by the same
**               2-sigma rule, since the claims' numbers are built from
**               those values); the worst state's verdict (property of
**               dt = 0.01 if one state is, then not converged, then
**               missing: a state that moves with dt decides the claim
**               whatever the missing ones would say, while "property of
**               the model" needs every state);
**   DTC_OFF     the Omega = 0.5 line at the grid's lowest v0: no state of
**               the study (the note gives Omega at the study's lowest v0);
**   DTC_NONE    the mean field: no dynamics, `none`.
*/
#include "paper.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum {
  BY_NUMBER,    /* within 2 sigma of the paper's number */
  BY_BRACKET,   /* the paper's number inside afv +- afv_err */
  LABEL_ABOVE,  /* the paper's label is the state at or above level */
  LABEL_BELOW   /* the paper's label is the state below level */
} rule_kind;

typedef struct claim {
  double afv, afv_err;          /* afv's figure and its error (NaN: none) */
  char undetermined[200];       /* non-empty: why the figure is not
                                ** determined (a fit's test) */
  char note[1024];              /* what the paper says, how afv measures */
} claim;

/* Where the dt study measures a claim (the header's list). */
typedef enum {
  DTC_NONE,     /* no dynamics: "none" */
  DTC_LABEL,    /* at the rule's (P0, v0): the resolved side of its level */
  DTC_NUMBER,   /* at the rule's (P0, v0): the claim's judgement */
  DTC_CURVES,   /* the value at the dispersal states, the worst verdict */
  DTC_OFF       /* at no state point of the study */
} dt_check;

struct claim_ctx;
typedef struct claim_rule {
  const char *name;
  const char *paper;            /* the paper's value, as printed */
  double value, err;            /* the paper's number, its printed error
                                ** (0: none printed) */
  rule_kind rule;
  int q;                        /* labels: the quantity, */
  double level;                 /* its threshold */
  double p0, v0;                /* the paper's state point (labels, CSD) */
  void (*measure)(const struct claim_ctx *, const struct claim_rule *,
                  claim *);
  dt_check dt;                  /* where the dt study measures it */
  const char *dt_obs;           /* the dt table's observable (NAME_mean) */
} claim_rule;

/* ---- what the claims are computed from, once ----------------------------- */
#define ALPHA_LO 0.05           /* the free fit's alpha range (phase.c's) */
#define ALPHA_HI 12.0
#define PROFILE_POINTS 400      /* log-spaced alphas of the RSS profile */

typedef struct claim_ctx {
  const claim_source *S;
  const plane *P;
  double *y, *e;                /* N_GC/N mean and sem, [ip nv + iv] */
  /* the common crossing from the pairs of P0 curves that cross */
  double v0star, v0star_se, cross_min, cross_max;
  int pairs, crossing;
  char uncrossed[256];          /* "5.6/6.4, ..." */
  afv_collapse cf;
  /* the dispersal boundary: its points, free fit, profile, held fit */
  double bp[MAX_VALUES], bv[MAX_VALUES];
  int nb, fitted;
  afv_boundary fit;
  double alpha_lo, alpha_hi;    /* the profile's 1-sigma interval */
  double held_c, held_se, held_c_lo, held_c_hi;
} claim_ctx;

/* ---- the common crossing: pairs whose order is resolved ---------------- */
/* Where curve a (the lower P0) falls below curve b, counting only the
** points where their gap is resolved, |ya - yb| > 2 sqrt(ea^2 + eb^2):
** a gap within the seeds' noise takes no side (as equal curves take none
** in afv_curves_cross).  Two curves that are both 1 up to v0 = 0.7 and
** differ by 1e-5 there do not cross where they first part. */
static int resolved_cross(const claim_ctx *X, int a, int b, double *xc)
{
  const plane *P = X->P;
  double g[MAX_VALUES], zero[MAX_VALUES];
  int k;
  for (k = 0; k < P->nv; k++) {
    double d = X->y[a * P->nv + k] - X->y[b * P->nv + k];
    double ea = X->e[a * P->nv + k], eb = X->e[b * P->nv + k];
    double noise = 2 * sqrt((isfinite(ea) ? ea * ea : 0)
                            + (isfinite(eb) ? eb * eb : 0));
    g[k] = fabs(d) > noise ? d : isfinite(d) ? 0 : NAN;
    zero[k] = 0;
  }
  return afv_curves_cross(P->nv, P->v0, g, zero, xc);
}

/* Mean of the resolved crossings of the pairs without curve `skip` (-1:
** all pairs); NaN if none. */
static double crossing_mean(const claim_ctx *X, int skip)
{
  double s = 0, xc;
  int a, b, m = 0;
  for (a = 0; a < X->P->np; a++)
    for (b = a + 1; b < X->P->np; b++)
      if (a != skip && b != skip && resolved_cross(X, a, b, &xc)) {
        s += xc;
        m++;
      }
  return m ? s / m : NAN;
}

static void common_crossing(claim_ctx *X)
{
  const plane *P = X->P;
  double loo[MAX_VALUES], mean = 0, ss = 0, xc;
  int a, b, m = 0;
  size_t len = 0;
  X->cross_min = HUGE_VAL;
  X->cross_max = -HUGE_VAL;
  X->uncrossed[0] = 0;
  for (a = 0; a < P->np; a++)
    for (b = a + 1; b < P->np; b++) {
      X->pairs++;
      if (resolved_cross(X, a, b, &xc)) {
        X->crossing++;
        X->cross_min = fmin(X->cross_min, xc);
        X->cross_max = fmax(X->cross_max, xc);
      } else if (len + 24 < sizeof X->uncrossed) {
        len += (size_t)snprintf(X->uncrossed + len, sizeof X->uncrossed - len,
                                "%s%g/%g", len ? ", " : "", P->p0[a], P->p0[b]);
      }
    }
  X->v0star = crossing_mean(X, -1);
  /* jackknife over the curves: leave one P0 curve out, recompute */
  for (a = 0; a < P->np; a++)
    if (isfinite(loo[a] = crossing_mean(X, a))) { mean += loo[a]; m++; }
  if (m >= 2) {
    mean /= m;
    for (a = 0; a < P->np; a++)
      if (isfinite(loo[a])) ss += (loo[a] - mean) * (loo[a] - mean);
  }
  X->v0star_se = m >= 2 ? sqrt((m - 1.0) / m * ss) : NAN;
}

/* ---- the dispersal boundary v_s = v0* - c P0^alpha ------------------------ */
/* Least squares of v_s = v0* - c u, u = P0^alpha, at fixed alpha: the
** residual sum of squares (HUGE_VAL if u does not vary). */
static double rss_fixed_alpha(const claim_ctx *X, double alpha)
{
  double su = 0, sv = 0, suu = 0, suv = 0, det, c, v0s, rss = 0;
  int i, n = X->nb;
  for (i = 0; i < n; i++) {
    double u = pow(X->bp[i], alpha);
    su += u; sv += X->bv[i]; suu += u * u; suv += u * X->bv[i];
  }
  det = n * suu - su * su;
  if (!(det > 1e-12 * (suu + 1))) return HUGE_VAL;
  c = -(n * suv - su * sv) / det;
  v0s = (sv + c * su) / n;
  for (i = 0; i < n; i++) {
    double r = X->bv[i] - (v0s - c * pow(X->bp[i], alpha));
    rss += r * r;
  }
  return rss;
}

/* The free fit's identifiability test: the alphas whose residual sum of
** squares is within s^2 = RSS_min / (n - 3) of the minimum (a one-sigma
** profile interval for one parameter).  alpha is not identifiable when the
** interval is wider than alpha itself or reaches an end of the range
** searched: the points then fit about as well with any alpha in it. */
static void alpha_interval(claim_ctx *X)
{
  double best = HUGE_VAL, r, a, bound;
  int k;
  X->alpha_lo = X->alpha_hi = NAN;
  if (!X->fitted || X->nb <= 3) return;
  for (k = 0; k <= PROFILE_POINTS; k++) {
    a = ALPHA_LO * pow(ALPHA_HI / ALPHA_LO, (double)k / PROFILE_POINTS);
    best = fmin(best, rss_fixed_alpha(X, a));
  }
  bound = best * (1 + 1.0 / (X->nb - 3));
  for (k = 0; k <= PROFILE_POINTS; k++) {
    a = ALPHA_LO * pow(ALPHA_HI / ALPHA_LO, (double)k / PROFILE_POINTS);
    if ((r = rss_fixed_alpha(X, a)) > bound) continue;
    if (!(a >= X->alpha_lo)) X->alpha_lo = a;
    X->alpha_hi = a;
  }
}

static int alpha_identifiable(const claim_ctx *X)
{
  return isfinite(X->alpha_lo) && X->alpha_lo > ALPHA_LO * 1.0001
         && X->alpha_hi < ALPHA_HI * 0.9999
         && X->alpha_hi - X->alpha_lo < X->fit.alpha;
}

/* The paper's way: v0* and alpha held at the collapse's values, c fitted
** to the boundary points (one parameter, linear): c = sum u (v0* - v_s) /
** sum u^2, its standard error sqrt(RSS / (n - 1) / sum u^2). */
static double held_c(const claim_ctx *X, double v0star, double alpha,
                     double *se)
{
  double suu = 0, suv = 0, c, rss = 0;
  int i, n = X->nb;
  for (i = 0; i < n; i++) {
    double u = pow(X->bp[i], alpha);
    suu += u * u;
    suv += u * (v0star - X->bv[i]);
  }
  c = suv / suu;
  for (i = 0; i < n; i++) {
    double r = X->bv[i] - (v0star - c * pow(X->bp[i], alpha));
    rss += r * r;
  }
  if (se) *se = n > 1 ? sqrt(rss / (n - 1) / suu) : NAN;
  return n >= 1 && suu > 0 ? c : NAN;
}

static void dispersal_fits(claim_ctx *X)
{
  const plane *P = X->P;
  int ip;
  X->nb = 0;
  for (ip = 0; ip < P->np; ip++)
    if (afv_curve_cross(P->nv, P->v0, X->y + ip * P->nv, CLUSTER_LEVEL,
                        &X->bv[X->nb]))
      X->bp[X->nb++] = P->p0[ip];
  X->fitted = X->nb >= 3
              && afv_boundary_fit(X->nb, X->bp, X->bv, &X->fit) == AFV_OK;
  alpha_interval(X);
  X->held_c = X->held_se = X->held_c_lo = X->held_c_hi = NAN;
  if (X->nb >= 2 && isfinite(X->cf.vstar) && isfinite(X->cf.alpha)) {
    double a = X->cf.alpha, da = X->cf.se_alpha;
    X->held_c = held_c(X, X->cf.vstar, a, &X->held_se);
    if (isfinite(da)) {
      X->held_c_lo = held_c(X, X->cf.vstar, a + da, NULL);
      X->held_c_hi = held_c(X, X->cf.vstar, a - da, NULL);
    }
  }
}

static int ctx_init(claim_ctx *X, const claim_source *S)
{
  const plane *P = S->P;
  int ip, iv;
  memset(X, 0, sizeof *X);
  X->S = S;
  X->P = P;
  X->y = malloc((size_t)(2 * P->np * P->nv + 1) * sizeof *X->y);
  if (!X->y) return 0;
  X->e = X->y + P->np * P->nv;
  for (ip = 0; ip < P->np; ip++)
    for (iv = 0; iv < P->nv; iv++) {
      X->y[ip * P->nv + iv] = at(P, Q_NGC, ip, iv, 0);
      X->e[ip * P->nv + iv] = at(P, Q_NGC, ip, iv, 1);
    }
  common_crossing(X);
  afv_collapse_fit(P->np, P->nv, P->v0, X->y, P->p0, &X->cf);
  dispersal_fits(X);
  return 1;
}

/* ---- the measurements: one function per kind of claim ------------------- */
#define NOTE(c, ...) snprintf((c)->note, sizeof (c)->note, __VA_ARGS__)

static void m_v0_star(const claim_ctx *X, const claim_rule *r, claim *c)
{
  (void)r;
  c->afv = X->v0star;
  c->afv_err = X->v0star_se;
  NOTE(c, "paper (clustering section): all N_GC/N curves cross at v0* = "
       "1.85 +- 0.06; afv: mean crossing of the pairs of P0 curves (grid "
       "means) whose order is resolved (gap > 2 sem), error by jackknife over "
       "the P0 curves. %d of %d pairs cross, from %.3g to %.3g (a zone, not "
       "a point); not crossing: %s", X->crossing, X->pairs, X->cross_min,
       X->cross_max, X->uncrossed[0] ? X->uncrossed : "none");
}

static void m_ngc_at_v0_star(const claim_ctx *X, const claim_rule *r,
                             claim *c)
{
  const plane *P = X->P;
  double s = 0, s2 = 0, v;
  int ip, iv, m = 0;
  (void)r;
  for (ip = 0; ip < P->np && isfinite(X->v0star); ip++)
    for (iv = 0; iv + 1 < P->nv; iv++)
      if (P->v0[iv] <= X->v0star && X->v0star <= P->v0[iv + 1]) {
        double t = (X->v0star - P->v0[iv]) / (P->v0[iv + 1] - P->v0[iv]);
        v = (1 - t) * X->y[ip * P->nv + iv] + t * X->y[ip * P->nv + iv + 1];
        if (isfinite(v)) { s += v; s2 += v * v; m++; }
        break;
      }
  c->afv = m ? s / m : NAN;
  c->afv_err = m > 1 ? sqrt(fmax(0, (s2 - s * s / m) / (m - 1))) : NAN;
  NOTE(c, "paper: N_GC/N ~ 0.7 at v0* whatever P0; afv: mean over %d P0 "
       "curves at afv's v0*, error = their standard deviation", m);
}

/* The free fit's profile: RSS at a few alphas, for the notes. */
static void profile_text(const claim_ctx *X, char *buf, size_t len)
{
  static const double alphas[6] = {0.1, 0.5, 1, 1.5, 2, 3};
  size_t used = 0;
  int k;
  buf[0] = 0;
  for (k = 0; k < 6 && used < len; k++)
    used += (size_t)snprintf(buf + used, len - used, "%s%g: %.3g",
                             k ? ", " : "", alphas[k],
                             rss_fixed_alpha(X, alphas[k]));
}

/* vs_alpha, vs_v0_star, vs_c_free: the three parameters of the free fit. */
static void m_vs_free(const claim_ctx *X, const claim_rule *r, claim *c)
{
  char prof[160];
  int which = r->name[3] == 'a' ? 0 : r->name[3] == 'v' ? 1 : 2;
  if (X->fitted) {
    c->afv = which == 0 ? X->fit.alpha : which == 1 ? X->fit.v0star : X->fit.c;
    c->afv_err = which == 0 ? X->fit.se_alpha
                 : which == 1 ? X->fit.se_v0star : X->fit.se_c;
  } else {
    c->afv = c->afv_err = NAN;
  }
  profile_text(X, prof, sizeof prof);
  if (X->fitted && !alpha_identifiable(X))
    snprintf(c->undetermined, sizeof c->undetermined, "the free fit is not "
             "identifiable: RSS within s^2 of its minimum for alpha from "
             "%.3g to %.3g", X->alpha_lo, X->alpha_hi);
  NOTE(c, "paper: v_s(P0) = v0* - c P0^alpha with v0* = 1.85 +- 0.06, alpha "
       "= 1.50 +- 0.12 (collapse), c = 0.06 +- 0.005; afv: the free "
       "three-parameter least squares (afv_boundary_fit) to the %d P0 where "
       "the mean N_GC/N crosses 0.99, alpha %.3g, v0* %.3g, c %.3g, RSS "
       "%.3g; RSS profile over alpha (v0*, c refitted) %s", X->nb,
       X->fit.alpha, X->fit.v0star, X->fit.c, X->fit.rss, prof);
}

static void m_vs_c_held(const claim_ctx *X, const claim_rule *r, claim *c)
{
  (void)r;
  c->afv = X->held_c;
  c->afv_err = X->held_se;
  NOTE(c, "paper: c = 0.06 +- 0.005 'obtained through fitting to the "
       "location where N_GC/N drops below 99%%', with v0* and alpha from the "
       "collapse; afv the same way: v0* = %.4g and alpha = %.4g held at "
       "afv's collapse, c fitted to the %d points, its standard error from "
       "the fit (with alpha moved by its error %.2g: c from %.3g to %.3g)",
       X->cf.vstar, X->cf.alpha, X->nb, X->cf.se_alpha, X->held_c_lo,
       X->held_c_hi);
}

static void m_collapse(const claim_ctx *X, const claim_rule *r, claim *c)
{
  int alpha = strstr(r->name, "alpha") != NULL;
  c->afv = alpha ? X->cf.alpha : X->cf.vstar;
  c->afv_err = alpha ? X->cf.se_alpha : X->cf.se_vstar;
  NOTE(c, "paper: collapse N_GC/N = G((v0 - v0*)/P0^alpha) with v0* = 1.85 "
       "+- 0.06, alpha = 1.50 +- 0.12; afv: afv_collapse_fit on the grid "
       "means (alpha in [0, 4]), jackknife error over the P0 curves");
}

/* Splits a line of claims.csv (modified) into at most CLAIM_FIELDS
** fields, quoted ones unquoted ("" is a quote); returns their number. */
#define CLAIM_FIELDS 8
static int claims_fields(char *line, char **field)
{
  int n = 0;
  char *s = line, *w;
  line[strcspn(line, "\r\n")] = 0;
  while (n < CLAIM_FIELDS) {
    field[n++] = w = s;
    if (*s == '"') {
      for (s++; *s && !(s[0] == '"' && s[1] != '"'); s++) {
        if (s[0] == '"') s++;       /* "" -> " */
        *w++ = *s;
      }
      if (*s == '"') s++;
    } else {
      while (*s && *s != ',') *w++ = *s++;
    }
    if (*s != ',') { *w = 0; break; }
    *w = 0;
    s++;
  }
  return n;
}

/* The column `name` of a claims.csv header (split by claims_fields). */
static int claims_column(char **head, int n, const char *name)
{
  int k;
  for (k = 0; k < n; k++) if (!strcmp(head[k], name)) return k;
  return -1;
}

/* The row `name` of the claims.csv at path (may be NULL): its afv,
** afv_err and note, found by the header's names (a claims.csv with or
** without dt_verdict); 0 if the file or the row is not there. */
static int claims_row(const char *path, const char *name, double *afv,
                      double *err, char *note, size_t len)
{
  char head[512], line[8192], *h[CLAIM_FIELDS], *f[CLAIM_FIELDS];
  FILE *fp = path ? fopen(path, "r") : NULL;
  int found = 0, nh = 0, ca, ce, cn;
  if (fp && fgets(head, sizeof head, fp)) nh = claims_fields(head, h);
  ca = claims_column(h, nh, "afv");
  ce = claims_column(h, nh, "afv_err");
  cn = claims_column(h, nh, "note");
  while (fp && ca >= 0 && ce >= 0 && cn >= 0 && !found
         && fgets(line, sizeof line, fp))
    if (claims_fields(line, f) == nh && strcmp(f[0], name) == 0) {
      *afv = strtod(f[ca], NULL);
      *err = strtod(f[ce], NULL);
      snprintf(note, len, "%s", f[cn]);
      found = 1;
    }
  if (fp) fclose(fp);
  return found;
}

/* The row `name` of the earlier claims.csv (afv paper --claims-from). */
static int previous_claim(const claim_ctx *X, const char *name, double *afv,
                          double *err, char *note, size_t len)
{
  return claims_row(X->S->previous, name, afv, err, note, len);
}

/* The note of a carried-over claim: the earlier note without its
** "[integration]" tail, marked once as carried over. */
static void carried_note(const char *old, claim *c)
{
  static const char mark[] = " (carried over from the earlier claims.csv: "
                             "the table holds no cluster-size distribution)";
  const char *tail = strstr(old, " [");
  int keep = tail ? (int)(tail - old) : (int)strlen(old);
  NOTE(c, "%.*s%s", keep, old, strstr(old, mark) ? "" : mark);
}

static void m_csd(const claim_ctx *X, const claim_rule *r, claim *c)
{
  const plane *P = X->P;
  afv_powerlaw fit;
  int ip = nearest(P->p0, P->np, r->p0), iv = nearest(P->v0, P->nv, r->v0);
  int n = 0;
  double *csd = X->S->have_runs ? pooled_csd(P, ip, iv, &n) : NULL;
  char old[sizeof c->note];
  c->afv = c->afv_err = NAN;
  if (!X->S->have_runs) {
    if (previous_claim(X, r->name, &c->afv, &c->afv_err, old, sizeof old)
        && isfinite(c->afv)) {
      carried_note(old, c);
      return;
    }
    c->afv = c->afv_err = NAN;
    NOTE(c, "paper Fig. 2(c): decay n^%g at P0 = %g, v0 = v0*; afv: the "
         "table holds no cluster-size distribution and no earlier claims.csv "
         "gives a value", r->value, r->p0);
    return;
  }
  fit.lo = fit.hi = 0;
  if (csd && n >= 1
      && afv_powerlaw_fit(csd, n, (int)(CSD_FIT_FRACTION * n), &fit) == AFV_OK) {
    c->afv = fit.exponent;
    c->afv_err = fit.se;
  }
  free(csd);
  NOTE(c, "paper Fig. 2(c): decay n^%g at P0 = %g, v0 = v0* (a visual aid, no "
       "error given); afv: grid point nearest (%g, %g), seeds pooled, log "
       "bins, fit over sizes %d..%d (the bins after the densest, sizes <= "
       "N/4)", r->value, r->p0, r->p0, r->v0, fit.lo, fit.hi);
}

/* Where tau_NGC turns finite at v0 = 1: between the last P0 with an
** infinite mean (some seed's N_GC constant) and the first finite one. */
static void m_tau(const claim_ctx *X, const claim_rule *r, claim *c)
{
  const plane *P = X->P;
  int iv = nearest(P->v0, P->nv, r->v0), ip, last_inf = -1, first_fin = -1;
  int ordered = 1;
  for (ip = 0; ip < P->np; ip++) {
    double t = at(P, Q_TAU, ip, iv, 0);
    if (isinf(t)) {
      last_inf = ip;
      if (first_fin >= 0) ordered = 0;
    } else if (isfinite(t) && first_fin < 0) {
      first_fin = ip;
    }
  }
  c->afv = c->afv_err = NAN;
  if (last_inf >= 0 && first_fin >= 0 && ordered) {
    c->afv = 0.5 * (P->p0[last_inf] + P->p0[first_fin]);
    c->afv_err = 0.5 * (P->p0[first_fin] - P->p0[last_inf]);
  }
  NOTE(c, "paper Fig. 3(c): at v0 = 1 tau_NGC is infinite for P0 < 5 and "
       "finite above; afv: midpoint (and half gap) between the largest grid "
       "P0 with an infinite mean tau_NGC (some seed's N_GC constant) and the "
       "smallest with a finite one%s", ordered ? "" : "; NOT ordered: an "
       "infinite value above a finite one");
}

static void m_meanfield(const claim_ctx *X, const claim_rule *r, claim *c)
{
  (void)X; (void)r;
  c->afv = afv_meanfield_p0(0.2, acos(-1.0), 1);
  c->afv_err = 0;
  NOTE(c, "paper (EMT section, hexagonal mean field): P0* = 5.73 for Lambda "
       "= 0.2, A0 = pi, kP = 1; afv: afv_meanfield_p0 (the paper's error: "
       "the rounding of 5.73)");
}

/* Omega = 0.5 along P0 at the lowest v0, as a bracket (the tau_NGC rule):
** from the largest grid P0 whose mean Omega is resolved above 0.5 (mean -
** 2 sem > 0.5) to the next P0 resolved below it (mean + 2 sem < 0.5); afv =
** its midpoint, afv_err = its half width.  The grid says only that the
** line lies in the bracket: half the gap is a bound, not a standard error,
** so it is not doubled as a number's error is.  The linear interpolation
** is given in the note, not judged. */
static void m_omega_half(const claim_ctx *X, const claim_rule *r, claim *c)
{
  const plane *P = X->P;
  double row[MAX_VALUES], xc = NAN;
  int ip, above = -1, below = -1;
  (void)r;
  for (ip = 0; ip < P->np; ip++) {
    double m = at(P, Q_OMEGA, ip, 0, 0), e = at(P, Q_OMEGA, ip, 0, 1);
    row[ip] = m;
    if (!isfinite(e)) e = 0;                 /* one seed: no error known */
    if (below < 0 && m - 2 * e > CONFLUENCY_LEVEL) above = ip;
    if (above >= 0 && below < 0 && m + 2 * e < CONFLUENCY_LEVEL) below = ip;
  }
  c->afv = c->afv_err = NAN;
  if (above >= 0 && below > above) {
    c->afv = 0.5 * (P->p0[above] + P->p0[below]);
    c->afv_err = 0.5 * (P->p0[below] - P->p0[above]);
  }
  if (!afv_curve_cross(P->np, P->p0, row, CONFLUENCY_LEVEL, &xc)) xc = NAN;
  if (!isfinite(c->afv) && isfinite(xc)) {   /* crosses within the noise */
    c->afv = xc;
    snprintf(c->undetermined, sizeof c->undetermined, "the mean Omega "
             "crosses 0.5 near P0 %.3g, but no grid P0 on either side is "
             "resolved from 0.5 by 2 sem", xc);
  }
  NOTE(c, "paper: the mean-field P0* = 5.73 'provides a reasonable "
       "approximation for the phase boundary' Omega = 0.5 'in the limit of "
       "v0 -> 0' (no measured value printed, no tolerance); afv: the bracket "
       "at v0 = %g (the grid's lowest) between the largest P0 whose mean "
       "Omega is above 0.5 by more than 2 sem and the next below it by more "
       "than 2 sem, midpoint +- half width; linear interpolation puts the "
       "line at %.3g", P->v0[0], xc);
}

/* A label at the grid point nearest the paper's (P0, v0). */
static void m_label(const claim_ctx *X, const claim_rule *r, claim *c)
{
  const plane *P = X->P;
  int ip = nearest(P->p0, P->np, r->p0), iv = nearest(P->v0, P->nv, r->v0);
  static const char *const what[N_Q] = {"N_GC/N", "", "Omega", "D_eff", "",
                                        "", "msd_beta"};
  c->afv = at(P, r->q, ip, iv, 0);
  c->afv_err = at(P, r->q, ip, iv, 1);
  NOTE(c, "paper: (P0, v0) = (%g, %g) is %s; afv: mean %s over the seeds at "
       "(%g, %g), the paper's state %s %g", r->p0, r->v0, r->paper,
       what[r->q], P->p0[ip], P->v0[iv],
       r->rule == LABEL_ABOVE ? "if >=" : "if <", r->level);
}

static void m_beta(const claim_ctx *X, const claim_rule *r, claim *c)
{
  char label[sizeof c->note];
  m_label(X, r, c);
  snprintf(label, sizeof label, "%s", c->note);
  NOTE(c, "paper (glassy dynamics section): MSD ~ lag^beta with beta ~ %s "
       "for P0 %s at v0 = 0.4; afv: msd_beta, the slope of log MSD_rel over "
       "lags 1%%..10%% of the steady window (afv collect's label, glassy "
       "below 0.5). %.500s", r->paper, r->value < 0.5 ? "<= 4" : ">= 7", label);
}

static void m_glassy_deff(const claim_ctx *X, const claim_rule *r, claim *c)
{
  char label[sizeof c->note];
  m_label(X, r, c);
  snprintf(label, sizeof label, "%s", c->note);
  NOTE(c, "paper Fig. 5(d)/6: glassy means D_eff = D_s/D_0 < 1e-8 (D_s at "
       "lag 5000 of a 1e4 run). %.500s; a caged D_eff falls like 1/lag, so "
       "msd_beta_P0_4_v0_0.4 is the length-independent test", label);
}

/* ---- the rules: one row per claim ---------------------------------------- */
static const claim_rule rules[] = {
/* name                      paper          value  err    rule         q        level  P0   v0    measured by       dt check    dt observable */
{"v0_star",                  "1.85",        1.85,  0.06,  BY_NUMBER,   Q_NGC,   0,     0,   0,    m_v0_star,        DTC_CURVES, "ngc_frac_mean"},
{"ngc_at_v0_star",           "0.7",         0.7,   0,     BY_NUMBER,   Q_NGC,   0,     0,   0,    m_ngc_at_v0_star, DTC_CURVES, "ngc_frac_mean"},
{"vs_c",                     "0.06",        0.06,  0.005, BY_NUMBER,   Q_NGC,   0,     0,   0,    m_vs_c_held,      DTC_CURVES, "ngc_frac_mean"},
{"vs_alpha",                 "1.5",         1.5,   0.12,  BY_NUMBER,   Q_NGC,   0,     0,   0,    m_vs_free,        DTC_CURVES, "ngc_frac_mean"},
{"vs_v0_star",               "1.85",        1.85,  0.06,  BY_NUMBER,   Q_NGC,   0,     0,   0,    m_vs_free,        DTC_CURVES, "ngc_frac_mean"},
{"vs_c_free",                "0.06",        0.06,  0.005, BY_NUMBER,   Q_NGC,   0,     0,   0,    m_vs_free,        DTC_CURVES, "ngc_frac_mean"},
{"collapse_v0_star",         "1.85",        1.85,  0.06,  BY_NUMBER,   Q_NGC,   0,     0,   0,    m_collapse,       DTC_CURVES, "ngc_frac_mean"},
{"collapse_alpha",           "1.5",         1.5,   0.12,  BY_NUMBER,   Q_NGC,   0,     0,   0,    m_collapse,       DTC_CURVES, "ngc_frac_mean"},
{"csd_exponent_P0_4",        "-1.25",      -1.25,  0,     BY_NUMBER,   Q_NGC,   0,     4,   1.85, m_csd,            DTC_NUMBER, "csd_exponent"},
{"csd_exponent_P0_8",        "-1.75",      -1.75,  0,     BY_NUMBER,   Q_NGC,   0,     8,   1.85, m_csd,            DTC_NUMBER, "csd_exponent"},
{"tau_ngc_infinite_below_P0","5",           5,     0,     BY_BRACKET,  Q_TAU,   0,     0,   1,    m_tau,            DTC_CURVES, "ngc_frac_mean"},
{"meanfield_P0_star",        "5.73",        5.73,  0.005, BY_NUMBER,   Q_OMEGA, 0,     0,   0,    m_meanfield,      DTC_NONE,   NULL},
{"P0_omega_half_low_v0",     "5.73",        5.73,  0,     BY_BRACKET,  Q_OMEGA, 0,     0,   0,    m_omega_half,     DTC_OFF,    "omega_mean"},
{"msd_beta_P0_4_v0_0.4",     "0",           0,     0,     LABEL_BELOW, Q_BETA,  0.5,   4,   0.4,  m_beta,           DTC_LABEL,  "msd_beta"},
{"msd_beta_P0_7.2_v0_0.4",   "1",           1,     0,     LABEL_ABOVE, Q_BETA,  0.5,   7.2, 0.4,  m_beta,           DTC_LABEL,  "msd_beta"},
{"msd_beta_P0_8_v0_0.4",     "1",           1,     0,     LABEL_ABOVE, Q_BETA,  0.5,   8,   0.4,  m_beta,           DTC_LABEL,  "msd_beta"},
{"msd_beta_P0_8.8_v0_0.4",   "1",           1,     0,     LABEL_ABOVE, Q_BETA,  0.5,   8.8, 0.4,  m_beta,           DTC_LABEL,  "msd_beta"},
{"glassy_P0_4_v0_0.4_D_eff", "<1e-8",       1e-8,  0,     LABEL_BELOW, Q_DEFF,  1e-8,  4,   0.4,  m_glassy_deff,    DTC_LABEL,  "D_eff"},
{"state_P0_4_v0_0.1_cluster",        "clustered",   1, 0, LABEL_ABOVE, Q_NGC,   0.99,  4,   0.1,  m_label,          DTC_LABEL,  "ngc_frac_mean"},
{"state_P0_4_v0_0.1_confluency",     "epithelial",  1, 0, LABEL_ABOVE, Q_OMEGA, 0.5,   4,   0.1,  m_label,          DTC_LABEL,  "omega_mean"},
{"state_P0_8.8_v0_0.1_cluster",      "clustered",   1, 0, LABEL_ABOVE, Q_NGC,   0.99,  8.8, 0.1,  m_label,          DTC_LABEL,  "ngc_frac_mean"},
{"state_P0_8.8_v0_0.1_confluency",   "mesenchymal", 0, 0, LABEL_BELOW, Q_OMEGA, 0.5,   8.8, 0.1,  m_label,          DTC_LABEL,  "omega_mean"},
{"state_P0_4.4_v0_2.6_cluster",      "dispersed",   0, 0, LABEL_BELOW, Q_NGC,   0.99,  4.4, 2.6,  m_label,          DTC_LABEL,  "ngc_frac_mean"},
{"state_P0_4.4_v0_2.6_confluency",   "epithelial",  1, 0, LABEL_ABOVE, Q_OMEGA, 0.5,   4.4, 2.6,  m_label,          DTC_LABEL,  "omega_mean"},
{"state_P0_8.8_v0_2.6_cluster",      "dispersed",   0, 0, LABEL_BELOW, Q_NGC,   0.99,  8.8, 2.6,  m_label,          DTC_LABEL,  "ngc_frac_mean"},
{"state_P0_8.8_v0_2.6_confluency",   "mesenchymal", 0, 0, LABEL_BELOW, Q_OMEGA, 0.5,   8.8, 2.6,  m_label,          DTC_LABEL,  "omega_mean"},
};
#define N_RULES ((int)(sizeof rules / sizeof rules[0]))

/* ---- the judgement ----------------------------------------------------------- */
/* 1 (why says what) when the runs a claim is drawn from are not all in:
** the claim's own point (a label, an exponent) short of the design's
** seeds, or any point of the grid for the claims drawn from all of it.
** The mean field reads no run. */
static int runs_missing(const claim_ctx *X, const claim_rule *r, char *why,
                        size_t len)
{
  const plane *P = X->P;
  int design = P->design_seeds, all = runs_designed(P);
  if (r->measure == m_meanfield) return 0;
  if (r->measure == m_label || r->measure == m_beta
      || r->measure == m_glassy_deff || r->measure == m_csd) {
    int ip = nearest(P->p0, P->np, r->p0), iv = nearest(P->v0, P->nv, r->v0);
    int n = seeds_at(P, ip, iv);
    if (n >= design) return 0;
    snprintf(why, len, "%d of %d seeds in at (%g, %g)%s", n, design,
             P->p0[ip], P->v0[iv], n == 1 ? ": one seed has no standard "
             "error" : "");
    return 1;
  }
  if (runs_in(P) >= all) return 0;
  snprintf(why, len, "the grid is partial: %d of %d runs in (%d P0 x %d v0 x "
           "%d seeds); the value is from those in", runs_in(P), all, P->np,
           P->nv, design);
  return 1;
}

/* "yes", "no", "undetermined" or "not measured" by the claim's rule (the
** header's list); why: the reason of an undetermined figure, for the note. */
static const char *judge(const claim_rule *r, const claim *c, char *why,
                         size_t len)
{
  double e = isfinite(c->afv_err) ? c->afv_err : 0;
  int above;
  why[0] = 0;
  if (!isfinite(c->afv)) return "not measured";
  if (c->undetermined[0]) {
    snprintf(why, len, "%s", c->undetermined);
    return "undetermined";
  }
  if (r->rule == BY_NUMBER || r->rule == BY_BRACKET) {
    if (e > 0 && e >= fabs(c->afv)) {     /* 0 +- 0 can still fail */
      snprintf(why, len, "its error %.3g is at least its value %.3g", e,
               c->afv);
      return "undetermined";
    }
    if (r->rule == BY_BRACKET) return fabs(c->afv - r->value) <= e ? "yes" : "no";
    return fabs(c->afv - r->value) <= 2 * sqrt(e * e + r->err * r->err)
           ? "yes" : "no";
  }
  if (fabs(c->afv - r->level) <= 2 * e) {
    snprintf(why, len, "%.3g +- %.3g is within 2 standard errors of the "
             "threshold %g", c->afv, e, r->level);
    return "undetermined";
  }
  above = c->afv >= r->level;
  return above == (r->rule == LABEL_ABOVE) ? "yes" : "no";
}

/* The claim's verdict on the grid's runs: judge's, or "missing" (why
** says which runs) when its runs are not all in. */
static const char *judge_claim(const claim_ctx *X, const claim_rule *r,
                               const claim *c, char *why, size_t len)
{
  why[0] = 0;
  if (isfinite(c->afv) && runs_missing(X, r, why, len)) return "missing";
  return judge(r, c, why, len);
}

/* ---- the dependence on dt (the header's list; the rule is dt_study.c's) -- */
/* The six states of the dt study's dispersal sweeps (model/README.md). */
static const double dispersal_states[][2] = {
  {4, 1.4}, {4, 1.85}, {4, 2.6}, {8, 1.4}, {8, 1.85}, {8, 2.6}};
#define N_DISPERSAL ((int)(sizeof dispersal_states / sizeof dispersal_states[0]))

static const char *const dt_short[] = {"model", "dt 0.01", "not converged",
                                       "missing", "not measured", "none"};

/* The short study (convergence.md, t = 1500) measured N_GC/N at P0 4, 8 x
** v0 1, 1.85, 2.6 against dt: pointed to by the claims built on N_GC/N
** when the paper-length study gives them no verdict. */
static const char *short_study(const claim_rule *r)
{
  if (r->dt == DTC_CURVES || (r->dt == DTC_NUMBER && r->v0 == 1.85))
    return " The short study (convergence.md, t = 1500) measured N_GC/N at "
           "P0 4 and 8, v0 1, 1.85, 2.6 against dt: 0.61, 0.77, 1.00 at "
           "(4, 1.85) for dt 0.01, 0.005, 0.0025.";
  return "";
}

/* The runs were integrated as the study's: Euler at dt 0.01 with the
** table's cap (paper_integration, e.g. "afv 0.4.0, integrator euler, dt
** 0.01, exact force"). */
static int study_applies(const dt_table *T)
{
  static const char how[] = "integrator euler, dt 0.01, ";
  const char *at = strstr(paper_integration, how);
  if (!at) return 0;
  at += sizeof how - 1;
  if (T->cap == 0) return strncmp(at, "exact force", 11) == 0;
  return strncmp(at, "cap ", 4) == 0 && strtod(at + 4, NULL) == T->cap;
}

/* The claim's judgement (judge) with afv's figure the mean at dt index i. */
static const char *judged_at(const claim_rule *r, const dt_series *s, int i)
{
  claim c;
  char why[256];
  memset(&c, 0, sizeof c);
  c.afv = s->mean[i];
  c.afv_err = s->sem[i];
  return judge(r, &c, why, sizeof why);
}

/* The judgement weighs afv's figure by its error (judge: 2 sigma, or
** undetermined within it), so at dt 0.01 it needs the standard error of
** two seeds: without it (one seed, an empty field) the judgement is not
** drawn and the rule says missing (-1), as dt_same_value does. */
static int same_judgement(const dt_series *s, const void *rule)
{
  if (s->seeds[0] < 2 || !isfinite(s->sem[0])) return -1;
  return !strcmp(judged_at(rule, s, 0), judged_at(rule, s, DT_STEPS - 1));
}

/* "above", "below", or with ", unresolved" when the mean lies within 2
** standard errors of the level (the label's side is then not known). */
static const char *side_text(double mean, double sem, double level)
{
  int unresolved = isfinite(sem) && fabs(mean - level) <= 2 * sem;
  if (mean >= level) return unresolved ? "above (unresolved: within 2 sem)"
                                       : "above";
  return unresolved ? "below (unresolved: within 2 sem)" : "below";
}

/* What the verdict rests on, for the note: the conclusions at dt 0.01
** and 0.0025, and the finest two's gap when they differ. */
static void conclusion_text(const claim_rule *r, const dt_series *s,
                            dt_verdict v, char *buf, size_t len)
{
  const int f = DT_STEPS - 1;
  size_t used = 0;
  buf[0] = 0;
  if (v == DT_MISSING) {
    snprintf(buf, len, "; the rule needs two seeds at dt 0.005 and 0.0025 "
             "and the mean at 0.01%s", r->dt == DTC_LABEL ? ""
             : " with its error");
    return;
  }
  if (r->dt == DTC_LABEL)
    used = (size_t)snprintf(buf, len, "; %s %g at dt 0.01, %s at 0.0025",
                            side_text(s->mean[0], s->sem[0], r->level),
                            r->level, side_text(s->mean[f], s->sem[f],
                                                r->level));
  else
    used = (size_t)snprintf(buf, len, "; against the paper: %s at dt 0.01, "
                            "%s at 0.0025 (the study's exponent is each run's "
                            "fit, tools/csd_exponent, averaged over the "
                            "seeds: another estimate than this claim's, "
                            "the seeds pooled)", judged_at(r, s, 0),
                            judged_at(r, s, f));
  if (v != DT_MODEL && !dt_agree(s, 1, 2) && used < len)
    snprintf(buf + used, len - used, "; dt 0.005 and 0.0025 differ by more "
             "than 2 sqrt(sem^2 + sem^2)");
}

/* "obs at (p0, v0) m | m | m at dt 0.01 | 0.005 | 0.0025" of the state of
** the table nearest (p0, v0) (the claim's own when it is there). */
static void state_text(const dt_table *T, const char *obs, double p0,
                       double v0, char *buf, size_t len)
{
  dt_series s;
  char nums[160];
  dt_series_at(T, p0, v0, obs, &s);
  dt_series_text(&s, nums, sizeof nums);
  snprintf(buf, len, "%s at (%g, %g) %s at dt 0.01 | 0.005 | 0.0025", obs,
           p0, v0, nums);
}

/* A label's state point that the study does not hold: not measured; the
** note names the nearest state it holds within NEAR_STATE in (P0, v0)
** (the grid's P0 step is 0.8, its v0 step near 0.3 to 0.5; farther
** states say nothing about the claim's), never its verdict. */
#define NEAR_STATE 1.0
static dt_verdict dt_absent(const dt_table *T, const claim_rule *r,
                            char *text, size_t len)
{
  double pt[DT_MAX_POINTS][2], best = HUGE_VAL;
  char near[300] = "";
  int k, n = dt_state_points(T, pt, DT_MAX_POINTS), kb = -1;
  for (k = 0; k < n; k++) {
    double d = hypot(pt[k][0] - r->p0, pt[k][1] - r->v0);
    if (d < best && d <= NEAR_STATE) { best = d; kb = k; }
  }
  if (kb >= 0)
    state_text(T, r->dt_obs, pt[kb][0], pt[kb][1], near, sizeof near);
  snprintf(text, len, " dt: not measured: the dt table has no row at (%g, "
           "%g)%s%s%s.%s", r->p0, r->v0, kb >= 0 ? " (nearest: " : "", near,
           kb >= 0 ? "; its verdict is not this claim's)" : "",
           short_study(r));
  return DT_NOT_MEASURED;
}

/* A label or a number at the rule's own (P0, v0). */
static dt_verdict dt_at_state(const dt_table *T, const claim_rule *r,
                              char *text, size_t len)
{
  dt_series s;
  char state[300], why[400];
  dt_verdict v;
  if (!dt_series_at(T, r->p0, r->v0, r->dt_obs, &s))
    return dt_absent(T, r, text, len);
  v = r->dt == DTC_LABEL ? dt_rule(&s, dt_same_side, &r->level)
                         : dt_rule(&s, same_judgement, r);
  state_text(T, r->dt_obs, r->p0, r->v0, state, sizeof state);
  conclusion_text(r, &s, v, why, sizeof why);
  snprintf(text, len, " dt: %s: %s%s.", dt_verdict_name(v), state, why);
  return v;
}

/* The claims built on the N_GC/N curves: the value at each dispersal
** state, the worst verdict (a state the table lacks is missing). */
static dt_verdict dt_curves(const dt_table *T, const claim_rule *r,
                            char *text, size_t len)
{
  char list[900], nums[160];
  size_t used = 0;
  dt_verdict v = DT_MODEL, one;
  dt_series s;
  int k, found = 0;
  list[0] = 0;
  for (k = 0; k < N_DISPERSAL && used < sizeof list; k++) {
    if (dt_series_at(T, dispersal_states[k][0], dispersal_states[k][1],
                     r->dt_obs, &s)) {
      found = 1;
      one = dt_rule(&s, dt_same_value, NULL);
      dt_series_text(&s, nums, sizeof nums);
    } else {
      one = DT_MISSING;
      snprintf(nums, sizeof nums, "no row");
    }
    v = dt_worse(v, one);
    used += (size_t)snprintf(list + used, sizeof list - used, "%s(%g, %g) "
                             "%s %s", k ? "; " : "", dispersal_states[k][0],
                             dispersal_states[k][1], nums, dt_short[one]);
  }
  if (!found) {
    snprintf(text, len, " dt: not measured: the dt study holds none of the "
             "dispersal states (P0 4 and 8 x v0 1.4, 1.85, 2.6).%s",
             short_study(r));
    return DT_NOT_MEASURED;
  }
  snprintf(text, len, " dt: %s, the worst of the dispersal states, N_GC/N "
           "at dt 0.01 | 0.005 | 0.0025 by value (0.01 against 0.0025 by the "
           "2-sigma rule): %s.%s", dt_verdict_name(v), list,
           v == DT_MISSING ? short_study(r) : "");
  return v;
}

/* The Omega line at the grid's lowest v0: no state of the study; the note
** gives Omega at the study's lowest v0 along P0. */
static dt_verdict dt_off_study(const dt_table *T, const claim_rule *r,
                               char *text, size_t len)
{
  double pt[DT_MAX_POINTS][2], low = HUGE_VAL;
  char list[700] = "", state[300];
  size_t used = 0;
  int k, n = dt_state_points(T, pt, DT_MAX_POINTS);
  for (k = 0; k < n; k++) low = fmin(low, pt[k][1]);
  for (k = 0; k < n && used < sizeof list; k++)
    if (pt[k][1] == low) {
      state_text(T, r->dt_obs, pt[k][0], low, state, sizeof state);
      used += (size_t)snprintf(list + used, sizeof list - used, "%s%s",
                               used ? "; " : " (nearest: ", state);
    }
  snprintf(text, len, " dt: not measured: the line is at no state point of "
           "the dt study%s%s.", list, used ? "; not this claim's verdict)"
           : "");
  return DT_NOT_MEASURED;
}

/* The claim's dt verdict and the text that ends its note. */
static dt_verdict dt_dependence(const claim_source *S, const claim_rule *r,
                                char *text, size_t len)
{
  if (r->dt == DTC_NONE) {
    snprintf(text, len, " dt: none (the mean field has no dynamics).");
    return DT_NONE;
  }
  if (!S->dt) {
    snprintf(text, len, " dt: not measured (no dt study given: afv paper "
             "--dt-table FILE, e.g. doc/reproduction/model/dt_table.csv).%s",
             short_study(r));
    return DT_NOT_MEASURED;
  }
  if (!study_applies(S->dt)) {
    snprintf(text, len, " dt: not measured (the dt study %.200s is of Euler "
             "steps from dt 0.01 at cap %g, 0 the exact force; these runs "
             "are not).%s", S->dt->path, S->dt->cap, short_study(r));
    return DT_NOT_MEASURED;
  }
  if (r->dt == DTC_CURVES) return dt_curves(S->dt, r, text, len);
  if (r->dt == DTC_OFF) return dt_off_study(S->dt, r, text, len);
  return dt_at_state(S->dt, r, text, len);
}

/* A CSV field: quoted if it holds a comma or a quote. */
static void put_field(FILE *fp, const char *s)
{
  if (!strpbrk(s, ",\"\n")) { fputs(s, fp); return; }
  fputc('"', fp);
  for (; *s; s++) { if (*s == '"') fputc('"', fp); fputc(*s, fp); }
  fputc('"', fp);
}

int claims_integration(const char *path, char *buf, size_t len)
{
  double afv, err;
  char note[1024], *a, *b;
  if (!claims_row(path, rules[0].name, &afv, &err, note, sizeof note)
      || !(a = strrchr(note, '[')) || !(b = strchr(a, ']')))
    return 0;
  snprintf(buf, len, "%.*s", (int)(b - a - 1), a + 1);
  return 1;
}

/* The integration of the runs: read_integration's, or with the runs gone,
** the "[...]" that ends the earlier claims.csv's first note. */
static void integration_from_previous(const claim_ctx *X)
{
  if (X->S->previous)
    claims_integration(X->S->previous, paper_integration,
                       sizeof paper_integration);
}

/* One row of claims.csv: the claim measured, judged against the paper
** and against dt; counts[] of the agrees (0 yes, 1 undetermined,
** COUNT_MISSING missing) and of the dt verdicts (2 + verdict). */
#define COUNT_MISSING (2 + DT_NONE + 1)
static void claim_row(FILE *fp, const claim_ctx *X, const claim_rule *r,
                      int *counts)
{
  char why[256], dt_text[1200], note[3072];
  claim c;
  const char *verdict;
  dt_verdict dv;
  memset(&c, 0, sizeof c);
  r->measure(X, r, &c);
  verdict = judge_claim(X, r, &c, why, sizeof why);
  counts[0] += !strcmp(verdict, "yes");
  counts[1] += !strcmp(verdict, "undetermined");
  counts[COUNT_MISSING] += !strcmp(verdict, "missing");
  dv = dt_dependence(X->S, r, dt_text, sizeof dt_text);
  counts[2 + dv]++;
  if (paper_smoke) verdict = "not established (smoke run)";
  put_field(fp, r->name);
  fputc(',', fp);
  put_field(fp, r->paper);
  fprintf(fp, ",%.6g,%.6g,%s,%s,", c.afv, c.afv_err, verdict,
          dt_verdict_name(dv));
  snprintf(note, sizeof note, "%s%s%s%s%s [%s]%s", c.note,
           why[0] ? "; " : "", why[0] ? verdict : "", why[0] ? ": " : "",
           why, paper_integration, dt_text);
  put_field(fp, note);
  fputc('\n', fp);
}

int claims_table(const claim_source *S, const char *path, char *summary,
                 size_t len)
{
  char tmp[PATH_LEN + 16];
  claim_ctx X;
  FILE *fp;
  int k, counts[2 + DT_NONE + 2] = {0};
  if (!ctx_init(&X, S)) return 0;
  if (!S->have_runs) integration_from_previous(&X);
  if (!(fp = afv_atomic_open(path, tmp, sizeof tmp))) { free(X.y); return 0; }
  fprintf(fp, "claim,paper,afv,afv_err,agrees,dt_verdict,note\n");
  for (k = 0; k < N_RULES; k++) claim_row(fp, &X, &rules[k], counts);
  free(X.y);
  snprintf(summary, len, "%d claims, %d agree, %d undetermined, %d missing "
           "(runs not in); dt: %d "
           "property of the model, %d property of dt = 0.01, %d not "
           "converged, %d missing, %d not measured, %d none", N_RULES,
           counts[0], counts[1], counts[COUNT_MISSING],
           counts[2 + DT_MODEL], counts[2 + DT_OF_DT],
           counts[2 + DT_NOT_CONVERGED], counts[2 + DT_MISSING],
           counts[2 + DT_NOT_MEASURED], counts[2 + DT_NONE]);
  return afv_atomic_commit(fp, tmp, path) == AFV_OK;
}
