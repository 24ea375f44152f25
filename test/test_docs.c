/*
** test_docs.c -- what the documentation promises, checked against the code:
**
**   - every key of `afv run --help` states its range, and the program
**     accepts the values inside it and refuses those outside (probed with
**     tiny runs of ./afv); the defaults it prints are the ones a run uses
**     and the library's (afv_params_default, afv_dyn_default), except v0;
**     the constants it quotes are the code's (AFV_MAX_STEP_DISP);
**   - the defaults printed by eval's and analyze's --help agree with them;
**   - the man page doc/afv.1 names every command and every option;
**   - every function, constant, key, figure and file that README.md,
**     doc/ (its .md files) and doc/afv.1 name exists in the tree;
**   - the quench of the README and afv.h: v0 (or per-cell v0) changed
**     between afv_sim_step calls continues as a run started with the new
**     value from that state, and a model parameter changed between steps
**     does so after afv_sim_refresh.
**
** Run from the repository root (make test), like test_cli.c.
*/
#define _POSIX_C_SOURCE 200809L
#include "afv.h"
#include "test.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/wait.h>
#include <unistd.h>

#define AFV_PROGRAM "./afv"
#define MAN_PAGE    "doc/afv.1"
#define TEXT_MAX    65536
#define MAX_KEYS    64

static char tmp[64];        /* the suite's temporary directory */
static char err[TEXT_MAX];  /* stderr of the last afv_status */

/* ---- running the program ------------------------------------------------ */
/* Reads the whole file at path into buf (empty if unreadable). */
static void read_text(const char *path, char *buf, size_t len)
{
  FILE *fp = fopen(path, "r");
  size_t k = 0;
  if (fp) {
    k = fread(buf, 1, len - 1, fp);
    fclose(fp);
  }
  buf[k] = 0;
}

/* stdout of ./afv ARGS into buf; returns the exit status (-1 if none). */
static int afv_output(const char *args, char *buf, size_t len)
{
  char cmd[1024], path[128];
  int st;
  snprintf(path, sizeof path, "%s/stdout", tmp);
  snprintf(cmd, sizeof cmd, "%s %s >%s 2>/dev/null", AFV_PROGRAM, args, path);
  st = system(cmd);
  read_text(path, buf, len);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Exit status of ./afv ARGS, its stderr in err (stdout discarded). */
static int afv_status(const char *args)
{
  char cmd[2048], path[128];
  int st;
  snprintf(path, sizeof path, "%s/stderr", tmp);
  snprintf(cmd, sizeof cmd, "%s %s >/dev/null 2>%s", AFV_PROGRAM, args, path);
  st = system(cmd);
  read_text(path, err, sizeof err);
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* ---- afv run --help, parsed --------------------------------------------- */
/* One key as --help prints it: "  NAME DEFAULT [UNIT]", then its meaning
** on lines indented by six spaces (joined here with single spaces). */
typedef struct help_key {
  char name[32], def[64], unit[64], text[1024];
} help_key;

static int parse_run_help(help_key *keys, int max)
{
  static char help[TEXT_MAX];
  char *line, *save = NULL;
  int n = 0;
  afv_output("run --help", help, sizeof help);
  for (line = strtok_r(help, "\n", &save); line;
       line = strtok_r(NULL, "\n", &save)) {
    if (strncmp(line, "      ", 6) == 0 && n > 0) {   /* a meaning line */
      help_key *k = &keys[n - 1];
      size_t m = strlen(k->text);
      snprintf(k->text + m, sizeof k->text - m, "%s%s", m ? " " : "",
               line + 6);
    } else if (strncmp(line, "  ", 2) == 0 && line[2] != ' ' && n < max
               && strchr(line, '[')) {                  /* a key line */
      help_key *k = &keys[n];
      memset(k, 0, sizeof *k);
      if (sscanf(line, " %31s %63s [%63[^]]]", k->name, k->def, k->unit) == 3)
        n++;
    }
  }
  return n;
}

static const help_key *key_named(const help_key *keys, int n, const char *name)
{
  int k;
  for (k = 0; k < n; k++)
    if (strcmp(keys[k].name, name) == 0) return &keys[k];
  return NULL;
}

/* ---- ranges as the help states them -------------------------------------- */
/* "any finite number", or "must be" followed by "> A", ">= A",
** "in (A, B]" (either bracket) or "in A .. B" (integers, inclusive). */
typedef struct range {
  int any;                 /* any finite number */
  int integer;             /* an integer range (A .. B) */
  char lo[32], hi[32];     /* the bounds as written ("" = none) */
  int lo_open, hi_open;    /* 1: the bound itself is outside */
} range;

static int parse_range(const char *text, range *rg)
{
  const char *p = strstr(text, "must be ");
  memset(rg, 0, sizeof *rg);
  if (strstr(text, "any finite number")) return rg->any = 1;
  if (!p) return 0;
  p += 8;
  if (strncmp(p, ">= ", 3) == 0) return sscanf(p + 3, "%31[^ ;,)]", rg->lo);
  if (strncmp(p, "> ", 2) == 0) {
    rg->lo_open = 1;
    return sscanf(p + 2, "%31[^ ;,)]", rg->lo);
  }
  if (strncmp(p, "in (", 4) == 0 || strncmp(p, "in [", 4) == 0) {
    char close = 0;
    rg->lo_open = p[3] == '(';
    if (sscanf(p + 4, "%31[^,], %31[^])]%c", rg->lo, rg->hi, &close) != 3)
      return 0;
    rg->hi_open = close == ')';
    return 1;
  }
  if (strncmp(p, "in ", 3) == 0) {
    rg->integer = 1;
    return sscanf(p + 3, "%31s .. %31[0-9]", rg->lo, rg->hi) == 2;
  }
  return 0;
}

/* The decimal string s plus one (s non-negative) or minus one, into out. */
static void integer_step(const char *s, int up, char *out, size_t len)
{
  if (up) {
    unsigned long long v = strtoull(s, NULL, 10);
    if (v == ~0ULL) snprintf(out, len, "18446744073709551616");
    else snprintf(out, len, "%llu", v + 1);
  } else {
    snprintf(out, len, "%lld", strtoll(s, NULL, 10) - 1);
  }
}

/* A real just beyond the bound b, downwards (up = 0) or upwards. */
static void real_step(const char *b, int up, char *out, size_t len)
{
  double v = strtod(b, NULL), d = fabs(v) > 1 ? 1e-3 * fabs(v) : 1e-3;
  snprintf(out, len, "%.17g", up ? v + d : v - d);
}

/* The keys of a probe: a tiny open-space run that does no step.  (Each
** probe's key replaces its entry here, or is added.) */
static const char *const probe_base[][2] = {
  {"N", "12"}, {"box", "open"}, {"steps", "0"}, {"relax_max_steps", "0"},
  {"sample_every", "0"}, {"frame_every", "0"}, {"svg_every", "0"},
  {"checkpoint_every", "0"}, {"quiet", "1"}};
#define N_PROBE_BASE ((int)(sizeof probe_base / sizeof probe_base[0]))

/* Runs afv run with KEY VALUE on top of probe_base; returns the status. */
static int probe(const char *key, const char *value)
{
  static int count;
  char args[1536];
  size_t m;
  int k, replaced = 0;
  m = (size_t)snprintf(args, sizeof args, "run --out %s/probe%d", tmp,
                       count++);
  for (k = 0; k < N_PROBE_BASE; k++) {
    const char *v = probe_base[k][1];
    if (strcmp(probe_base[k][0], key) == 0) v = value, replaced = 1;
    m += (size_t)snprintf(args + m, sizeof args - m, " --%s %s",
                          probe_base[k][0], v);
  }
  if (!replaced)
    m += (size_t)snprintf(args + m, sizeof args - m, " --%s %s", key, value);
  if (strcmp(key, "init") == 0 && strcmp(value, "file") == 0)
    snprintf(args + m, sizeof args - m, " --cells %s/cells.txt", tmp);
  return afv_status(args);
}

static void expect_accepted(const char *key, const char *value)
{
  int st = probe(key, value);
  CHECK(st == 0, "afv run --%s %s: the help allows it, the program exits %d: "
        "%.200s", key, value, st, err);
}

static void expect_refused(const char *key, const char *value)
{
  int st = probe(key, value);
  CHECK(st == 2 && strstr(err, key) != NULL, "afv run --%s %s: outside the "
        "help's range, but the program exits %d: %.200s", key, value, st,
        err);
}

/* The bounds of rg probed on both sides. */
static void probe_range(const help_key *K, const range *rg)
{
  char v[64];
  if (rg->any) {
    expect_accepted(K->name, "-1");
    expect_accepted(K->name, "0.5");
    expect_refused(K->name, "nan");
    return;
  }
  if (rg->lo[0]) {
    if (rg->integer) integer_step(rg->lo, 0, v, sizeof v);
    else real_step(rg->lo, !rg->lo_open ? 0 : 1, v, sizeof v);
    if (rg->lo_open) {
      expect_refused(K->name, rg->lo);
      expect_accepted(K->name, v);
    } else {
      expect_accepted(K->name, rg->lo);
      if (!rg->integer && strcmp(K->unit, "steps") == 0)
        snprintf(v, sizeof v, "%lld", strtoll(rg->lo, NULL, 10) - 1);
      expect_refused(K->name, v);
    }
  }
  if (rg->hi[0]) {
    if (rg->integer) integer_step(rg->hi, 1, v, sizeof v);
    else real_step(rg->hi, 1, v, sizeof v);
    /* N = 100000000 would be a real run of that size: only the refusal */
    if (!rg->hi_open && strtod(rg->hi, NULL) <= 1e6)
      expect_accepted(K->name, rg->hi);
    expect_refused(K->name, rg->hi_open ? rg->hi : v);
  }
}

/* The choices of a key whose unit lists them (a|b|c): each accepted, a
** word outside them refused. */
static void probe_choices(const help_key *K)
{
  char choices[64], *w, *save = NULL;
  snprintf(choices, sizeof choices, "%s", K->unit);
  for (w = strtok_r(choices, "|", &save); w; w = strtok_r(NULL, "|", &save))
    expect_accepted(K->name, w);
  expect_refused(K->name, "bogus");
}

static void write_cells_file(void)
{
  char path[128];
  FILE *fp;
  int i;
  snprintf(path, sizeof path, "%s/cells.txt", tmp);
  if (!(fp = fopen(path, "w"))) return;
  fprintf(fp, "# x y\n");
  for (i = 0; i < 12; i++) fprintf(fp, "%d %d\n", 2 * (i % 4), 2 * (i / 4));
  fclose(fp);
}

/* Every key's help states its range, and the program keeps to it. */
static void test_run_help_ranges_true(void)
{
  help_key keys[MAX_KEYS];
  int n = parse_run_help(keys, MAX_KEYS), k;
  CHECK(n >= 25, "afv run --help lists %d keys", n);
  write_cells_file();
  for (k = 0; k < n; k++) {
    const help_key *K = &keys[k];
    range rg;
    if (strchr(K->unit, '|') || strcmp(K->unit, K->def) == 0)
      probe_choices(K);                  /* choices (one: the default) */
    else if (strcmp(K->unit, "file") == 0) continue;   /* a path */
    else if (!parse_range(K->text, &rg))
      CHECK(0, "afv run --help, key %s: no range stated (\"must be ...\" or "
            "\"any finite number\"): '%s'", K->name, K->text);
    else probe_range(K, &rg);
  }
}

/* Numbers of two help texts agree (both parsed by strtod). */
static void check_same_number(const char *what, const char *a, double b)
{
  char *end;
  double v = strtod(a, &end);
  CHECK(end != a && v == b, "%s: help says %s, the code %.17g", what, a, b);
}

/* The defaults --help prints are what a run uses and, for the model and
** dynamics keys, the library's own defaults; the constants it quotes are
** the code's. */
static void test_run_help_defaults_true(void)
{
  static char params[TEXT_MAX];
  static const char *const lib_keys[] = {"l", "KA", "KP", "A0", "P0",
                                         "Lambda", "cap", "mu", "Dr", "dt",
                                         "seed"};
  help_key keys[MAX_KEYS];
  int n = parse_run_help(keys, MAX_KEYS), k;
  afv_params p;
  afv_dyn d;
  const help_key *K;
  char args[256], path[128], *at;
  double lib[11], disp = -1;
  afv_params_default(&p);
  afv_dyn_default(&d);
  lib[0] = p.l; lib[1] = p.KA; lib[2] = p.KP; lib[3] = p.A0; lib[4] = p.P0;
  lib[5] = p.Lambda; lib[6] = p.cap; lib[7] = d.mu; lib[8] = d.Dr;
  lib[9] = d.dt; lib[10] = (double)d.seed;
  for (k = 0; k < 11; k++) {
    CHECK((K = key_named(keys, n, lib_keys[k])) != NULL, "no key %s",
          lib_keys[k]);
    if (K) check_same_number(lib_keys[k], K->def, lib[k]);
  }
  /* v0: the library's default is 0 (no activity); afv run's is a state of
  ** the paper's diagram (README.md, "Using the library").  Nothing else
  ** may differ. */
  snprintf(args, sizeof args, "run --steps 0 --relax_max_steps 0 --quiet "
           "--out %s/defaults", tmp);
  CHECK(afv_status(args) == 0, "default run failed: %.200s", err);
  snprintf(path, sizeof path, "%s/defaults/params.txt", tmp);
  read_text(path, params, sizeof params);
  for (k = 0; k < n; k++) {
    char pat[48], value[1100];
    K = &keys[k];
    if (!strcmp(K->name, "steps") || !strcmp(K->name, "relax_max_steps")
        || !strcmp(K->name, "quiet"))
      continue;                               /* set by the run above */
    if (!strcmp(K->name, "spacing"))
      continue;          /* init lattice's only: not in this run's params */
    snprintf(pat, sizeof pat, "\n%s ", K->name);
    at = strstr(params, pat);
    CHECK(at && sscanf(at + strlen(pat), " %1099s", value) == 1,
          "params.txt has no %s", K->name);
    if (!at) continue;
    if (strtod(K->def, NULL) != 0 || strchr("0123456789.-", K->def[0]))
      check_same_number(K->name, K->def, strtod(value, NULL));
    else
      CHECK(strcmp(K->def, value) == 0, "%s: help default %s, a run uses %s",
            K->name, K->def, value);
  }
  /* the constant quoted by integrator */
  K = key_named(keys, n, "integrator");
  at = K ? strstr(K->text, "more than ") : NULL;
  CHECK(at && sscanf(at, "more than %lf", &disp) == 1
        && disp == AFV_MAX_STEP_DISP, "integrator: help counts moves of more "
        "than %g l, the code AFV_MAX_STEP_DISP = %g", disp,
        AFV_MAX_STEP_DISP);
}

/* The number after `after` in the help of option opt (its line and those
** continuing it), or NaN. */
static double option_number(const char *help, const char *opt,
                            const char *after)
{
  char pat[64];
  const char *at, *end;
  snprintf(pat, sizeof pat, "  %s ", opt);
  if (!(at = strstr(help, pat))) return NAN;
  end = strstr(at + 2, "\n  --");        /* the next option */
  at = strstr(at, after);
  if (!at || (end && at > end)) return NAN;
  return strtod(at + strlen(after), NULL);
}

/* eval's model options and analyze's fall-backs print the same defaults
** as the library and afv run. */
static void test_other_help_defaults_true(void)
{
  static char help[TEXT_MAX];
  static const char *const opts[] = {"--l", "--A0", "--P0", "--KA", "--KP",
                                     "--Lambda"};
  help_key keys[MAX_KEYS];
  int n = parse_run_help(keys, MAX_KEYS), k;
  afv_params p;
  double want[6];
  const char *run_keys[3] = {"l", "v0", "Dr"};
  afv_params_default(&p);
  want[0] = p.l; want[1] = p.A0; want[2] = p.P0; want[3] = p.KA;
  want[4] = p.KP; want[5] = p.Lambda;
  afv_output("eval --help", help, sizeof help);
  for (k = 0; k < 6; k++) {
    double v = option_number(help, opts[k], "(default ");
    /* A0 is printed to 16 digits: pi to within its last digit */
    CHECK(test_close(v, want[k], 1e-15, 0), "afv eval --help: %s default "
          "%.17g, afv_params_default %.17g", opts[k], v, want[k]);
  }
  afv_output("analyze --help", help, sizeof help);
  for (k = 0; k < 3; k++) {
    char opt[8];
    const help_key *K = key_named(keys, n, run_keys[k]);
    double v;
    snprintf(opt, sizeof opt, "--%s", run_keys[k]);
    v = option_number(help, opt, "else ");
    CHECK(K && v == strtod(K->def, NULL), "afv analyze --help: %s falls "
          "back to %g, afv run's default is %s", opt, v, K ? K->def : "?");
  }
}

/* 1 for a placeholder such as KEY in "--KEY VALUE" (no lower case). */
static int is_placeholder(const char *opt)
{
  for (; *opt; opt++)
    if (*opt >= 'a' && *opt <= 'z') return 0;
  return 1;
}

/* --opt as man(7) writes it: every '-' as "\-". */
static void man_option(const char *opt, char *out, size_t len)
{
  size_t m = (size_t)snprintf(out, len, "\\-\\-");
  for (; *opt && m + 3 < len; opt++) {
    if (*opt == '-') out[m++] = '\\';
    out[m++] = *opt;
  }
  out[m] = 0;
}

/* The man page names every command of `afv --help` and every option of
** each command's --help (and every run key). */
static void test_man_page_covers_options(void)
{
  static char man[TEXT_MAX * 2], top[TEXT_MAX], help[TEXT_MAX];
  char *line, *save = NULL;
  int commands = 0;
  read_text(MAN_PAGE, man, sizeof man);
  CHECK(man[0], "%s: missing", MAN_PAGE);
  afv_output("--help", top, sizeof top);
  line = strstr(top, "commands:");
  for (line = line ? strtok_r(line, "\n", &save) : NULL; line;
       line = strtok_r(NULL, "\n", &save)) {
    char cmd[32], args[64], pat[80];
    const char *p;
    if (strncmp(line, "  ", 2) != 0) {
      if (commands > 0) break;                  /* past the command list */
      continue;
    }
    if (sscanf(line, " %31s", cmd) != 1) continue;
    commands++;
    snprintf(pat, sizeof pat, ".SS %s", cmd);
    CHECK(strstr(man, pat) != NULL, "%s: no section '.SS %s'", MAN_PAGE, cmd);
    snprintf(args, sizeof args, "%s --help", cmd);
    afv_output(args, help, sizeof help);
    for (p = strstr(help, "--"); p; p = strstr(p + 2, "--")) {
      char opt[48], manopt[128];
      if (sscanf(p + 2, "%47[A-Za-z0-9_-]", opt) != 1 || !strcmp(opt, "help")
          || is_placeholder(opt))
        continue;
      man_option(opt, manopt, sizeof manopt);
      CHECK(strstr(man, manopt) != NULL, "%s: afv %s --%s is not in it",
            MAN_PAGE, cmd, opt);
    }
  }
  CHECK(commands >= 6, "afv --help lists %d commands", commands);
  {
    help_key keys[MAX_KEYS];
    int n = parse_run_help(keys, MAX_KEYS), k;
    for (k = 0; k < n; k++) {
      char pat[128];
      man_option(keys[k].name, pat, sizeof pat);
      CHECK(strstr(man, pat) != NULL, "%s: run key %s missing", MAN_PAGE,
            keys[k].name);
    }
  }
}

/* ---- quench: parameters changed between steps ------------------------- */
/* A jittered periodic 10 x 10 triangular tissue with random polarities,
** P0 4.8, v0 0.3, initialised into s and stepped k steps; p and d get
** its parameters.  (Contacts break once v0 is large.) */
#define QN 100
static int steps(afv_sim *s, int k)
{
  int st = AFV_OK;
  while (k-- > 0 && st == AFV_OK) st = afv_sim_step(s);
  return st;
}

static void quench_start(afv_sim *s, afv_params *p, afv_dyn *d, int k)
{
  double r[2 * QN], th[QN];
  afv_box b = test_tri_lattice(10, 10, 1.75, 0.5, 0.5, r);
  int i;
  test_rng_seed(23);
  for (i = 0; i < 2 * QN; i++) r[i] += 0.2 * (test_rng_uniform() - 0.5);
  afv_init_angles(QN, 9, th);
  afv_params_default(p);
  afv_dyn_default(d);
  d->v0 = 0.3;
  memset(s, 0, sizeof *s);
  CHECK(afv_sim_init(s, QN, r, th, p, &b, d) == AFV_OK, "init");
  CHECK(steps(s, k) == AFV_OK, "%d steps at v0 0.3", k);
}

/* A fresh simulation of the state of s (positions, angles, step count)
** with parameters p and d. */
static int restart_from(afv_sim *fresh, const afv_sim *s, const afv_params *p,
                        const afv_dyn *d)
{
  int st = afv_sim_init(fresh, s->n, s->r, s->theta, p, &s->box, d);
  fresh->step = s->step;     /* the noise is drawn per (cell, step) */
  fresh->t = s->t;
  return st;
}

static int same_state(const afv_sim *a, const afv_sim *b)
{
  size_t two = 2 * (size_t)a->n * sizeof(double);
  return a->n == b->n && a->step == b->step
         && memcmp(a->r, b->r, two) == 0 && memcmp(a->f, b->f, two) == 0
         && memcmp(a->theta, b->theta, two / 2) == 0;
}

/* v0 changed between steps: the next steps are those of a run started
** from that state with the new v0 (bit for bit), and not those of the
** old v0 (so a v0 cached anywhere would be caught). */
static void test_quench_v0_between_steps(void)
{
  afv_params p;
  afv_dyn d, hot;
  afv_sim s, fresh, old;
  long long before;
  quench_start(&s, &p, &d, 30);
  memset(&fresh, 0, sizeof fresh);
  memset(&old, 0, sizeof old);
  hot = d;
  hot.v0 = 2.5;
  CHECK(restart_from(&fresh, &s, &p, &hot) == AFV_OK, "fresh start");
  CHECK(restart_from(&old, &s, &p, &d) == AFV_OK, "old start");
  before = s.jumps;
  s.dyn.v0 = 2.5;                              /* the quench */
  CHECK(steps(&s, 60) == AFV_OK && steps(&fresh, 60) == AFV_OK
        && steps(&old, 60) == AFV_OK, "60 steps after the quench");
  CHECK(same_state(&s, &fresh), "quenched run differs from a fresh run at "
        "the new v0");
  CHECK(!same_state(&s, &old), "the quench changed nothing");
  CHECK(s.jumps - before == fresh.jumps, "jumps after the quench: %lld "
        "quenched, %lld fresh", s.jumps - before, fresh.jumps);
  afv_sim_free(&s);
  afv_sim_free(&fresh);
  afv_sim_free(&old);
}

/* Per-cell v0 changed between steps through an array the caller owns. */
static void test_quench_per_cell_v0(void)
{
  double v0[QN];
  afv_params p;
  afv_dyn d, hot;
  afv_sim s, fresh;
  int i;
  quench_start(&s, &p, &d, 20);
  memset(&fresh, 0, sizeof fresh);
  for (i = 0; i < QN; i++) v0[i] = i % 2 ? 2.0 : 0.1;  /* two cell types */
  hot = d;
  hot.v0_i = v0;
  CHECK(restart_from(&fresh, &s, &p, &hot) == AFV_OK, "fresh start");
  s.dyn.v0_i = v0;                     /* caller-owned, alive while used */
  CHECK(steps(&s, 40) == AFV_OK && steps(&fresh, 40) == AFV_OK, "40 steps");
  CHECK(same_state(&s, &fresh), "per-cell quench differs from a fresh run");
  afv_sim_free(&s);
  afv_sim_free(&fresh);
}

/* A model parameter (P0) changed between steps: the forces of the last
** step are stale until afv_sim_refresh; after it the run continues as a
** fresh one at the new P0. */
static void test_parameter_change_needs_refresh(void)
{
  afv_params p, soft;
  afv_dyn d;
  afv_sim s, fresh;
  quench_start(&s, &p, &d, 20);
  memset(&fresh, 0, sizeof fresh);
  soft = p;
  soft.P0 = 7.0;
  CHECK(restart_from(&fresh, &s, &soft, &d) == AFV_OK, "fresh start");
  s.par.P0 = 7.0;
  CHECK(memcmp(s.f, fresh.f, 2 * QN * sizeof(double)) != 0,
        "forces at P0 4.8 and 7 are the same: the test cannot see a stale "
        "force");
  CHECK(afv_sim_refresh(&s) == AFV_OK, "afv_sim_refresh");
  CHECK(s.geom.energy == fresh.geom.energy, "energy after refresh %.17g, "
        "fresh %.17g", s.geom.energy, fresh.geom.energy);
  CHECK(steps(&s, 40) == AFV_OK && steps(&fresh, 40) == AFV_OK, "40 steps");
  CHECK(same_state(&s, &fresh), "refreshed run differs from a fresh run");
  s.par.KA = -1;                       /* out of range: refused, unchanged */
  CHECK(afv_sim_refresh(&s) == AFV_EINVAL, "KA -1 accepted by refresh");
  afv_sim_free(&s);
  afv_sim_free(&fresh);
}

/* ---- every name in the docs exists in the tree -------------------------- */
/* README.md, doc/ (its .md files) and doc/afv.1 name functions, constants,
** keys and files; a rename leaves them behind.  Checked:
**   - a `backticked` span of a .md file that is a C identifier with an
**     underscore (a function, a constant, a key, a figure: afv_compute,
**     AFV_CONTACT_TOL, relax_tol, fig2a_ngc_vs_v0; "()" after it allowed)
**     occurs as a whole word in the tree's sources (.c, .h, scripts,
**     Makefile, .ci/run);
**   - a file named exists: a path into one of the tree's folders
**     (`test/twins.c`, fuzz/fuzz_*.c: from the root or from doc/, by
**     glob), ending in .c, .h, .md, .sh or .py; a bare name ending in .c,
**     .h or .md (geom.c), anywhere in the tree.
** Not checked: words without an underscore (`cap`, `euler`: too common),
** paths into folders the tree does not have (a run's out/run/, an
** install's include/afv.h), and examples: fenced (``` lines) or indented
** code blocks, and backticked commands (spans with a space). */
#include <dirent.h>
#include <glob.h>
#include <sys/stat.h>

#define TREE_TEXT (8 << 20)

typedef struct tree_text {
  char *src;        /* the sources' text, concatenated */
  size_t src_len;
  char *paths;      /* "\n" + every file's path, one per line */
  size_t paths_len;
} tree_text;

/* 1 if s ends with suffix. */
static int ends_with(const char *s, const char *suffix)
{
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && !strcmp(s + n - m, suffix);
}

static int is_source(const char *path)
{
  return ends_with(path, ".c") || ends_with(path, ".h")
         || ends_with(path, ".sh") || ends_with(path, ".py")
         || ends_with(path, "/Makefile") || ends_with(path, "/.ci/run");
}

/* Appends len bytes of text to buf (of capacity TREE_TEXT). */
static void append(char *buf, size_t *at, const char *text, size_t len)
{
  if (*at + len + 1 >= TREE_TEXT) return;
  memcpy(buf + *at, text, len);
  *at += len;
  buf[*at] = 0;
}

/* Every file under dir (a path from the root, "." for it) into T: its path,
** and its text if a source.  Skips .git, build and output folders. */
static void walk_tree(const char *dir, tree_text *T)
{
  static const char *const skip[] = {"./.git", "./fuzz/build", "./fuzz/corpus",
                                     "./out", "./runs", "./paper"};
  DIR *d = opendir(dir);
  struct dirent *e;
  size_t k;
  for (k = 0; k < sizeof skip / sizeof skip[0]; k++)
    if (!strcmp(dir, skip[k])) {
      if (d) closedir(d);
      return;
    }
  while (d && (e = readdir(d)) != NULL) {
    char path[1024];
    struct stat st;
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (stat(path, &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) {
      walk_tree(path, T);
      continue;
    }
    append(T->paths, &T->paths_len, path + 1, strlen(path + 1));  /* "/x" */
    append(T->paths, &T->paths_len, "\n", 1);
    if (is_source(path)) {
      FILE *fp = fopen(path, "r");
      size_t n;
      if (!fp) continue;
      n = fread(T->src + T->src_len, 1, TREE_TEXT - T->src_len - 2, fp);
      T->src_len += n;
      T->src[T->src_len++] = '\n';
      T->src[T->src_len] = 0;
      fclose(fp);
    }
  }
  if (d) closedir(d);
}

static int word_char(int c)
{
  return c == '_' || (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z')
         || (c >= 'A' && c <= 'Z');
}

/* 1 if name occurs in text as a whole word (after a "\n" or "\t" of a
** C string too). */
static int has_word(const char *text, const char *name)
{
  size_t n = strlen(name);
  const char *p = text;
  while ((p = strstr(p, name)) != NULL) {
    int escape = p - text >= 2 && p[-2] == '\\';
    if ((p == text || escape || !word_char((unsigned char)p[-1]))
        && !word_char((unsigned char)p[n]))
      return 1;
    p++;
  }
  return 0;
}

/* 1 if the file named exists: with a '/', as a path from the root or
** from doc/ (glob patterns allowed); without, anywhere in the tree. */
/* 1 if path starts with a folder of the tree (at the root or in doc/). */
static int into_tree(const char *path)
{
  char dir[300];
  const char *slash = strchr(path, '/');
  struct stat st;
  size_t n = slash ? (size_t)(slash - path) : 0;
  if (n == 0 || n + 5 >= sizeof dir) return 0;
  memcpy(dir, path, n);
  dir[n] = 0;
  if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode)) return 1;
  snprintf(dir, sizeof dir, "doc/%.*s", (int)n, path);
  return stat(dir, &st) == 0 && S_ISDIR(st.st_mode);
}

static int file_exists(const tree_text *T, const char *name)
{
  char pat[600];
  const char *const base[] = {"", "doc/"};
  size_t k;
  if (!strchr(name, '/')) {
    snprintf(pat, sizeof pat, "/%s\n", name);
    return strstr(T->paths, pat) != NULL;
  }
  for (k = 0; k < 2; k++) {
    glob_t g;
    int found;
    snprintf(pat, sizeof pat, "%s%s", base[k], name);
    found = glob(pat, 0, NULL, &g) == 0 && g.gl_pathc > 0;
    globfree(&g);
    if (found) return 1;
  }
  return 0;
}

/* A C identifier with an underscore (after "()" is stripped). */
static int is_identifier(const char *s)
{
  const char *p;
  if (!word_char((unsigned char)*s) || (*s >= '0' && *s <= '9')) return 0;
  for (p = s; *p; p++)
    if (!word_char((unsigned char)*p)) return 0;
  return strchr(s, '_') != NULL;
}

/* A file of the tree, by its name: see the header of this part. */
static int is_file_name(const char *s)
{
  const char *base = strrchr(s, '/') ? strrchr(s, '/') + 1 : s;
  if (strchr(s, ' ') || base[0] == '.') return 0;   /* ".md": no name */
  if (strchr(s, '/'))
    return into_tree(s) && (ends_with(s, ".c") || ends_with(s, ".h")
                            || ends_with(s, ".md") || ends_with(s, ".sh")
                            || ends_with(s, ".py"));
  return ends_with(s, ".c") || ends_with(s, ".h") || ends_with(s, ".md");
}

/* Checks one name of doc (line) against the tree; counts what is missing. */
static void check_name(const tree_text *T, const char *doc, int line,
                       const char *name, int backticked, int *missing)
{
  if (is_file_name(name)) {
    if (file_exists(T, name)) return;
    CHECK(0, "%s:%d names the file %s, which is not in the tree", doc, line,
          name);
    (*missing)++;
  } else if (backticked && is_identifier(name) && !has_word(T->src, name)) {
    CHECK(0, "%s:%d names `%s`, which no source file holds", doc, line, name);
    (*missing)++;
  }
}

/* The words of a line that may be file names: runs of letters, digits and
** _ . / * -, without a trailing '.' (a full stop); not inside a backticked
** command (a span with a space). */
static void check_bare_files(const tree_text *T, const char *doc, int line,
                             const char *text, int *missing)
{
  const char *p = text;
  int in_span = 0, command = 0;
  while (*p) {
    if (*p == '`') {
      const char *end = strchr(p + 1, '`');
      in_span = !in_span;
      /* (a span left open runs on to the next line) */
      command = in_span && (end ? memchr(p + 1, ' ', (size_t)(end - p - 1))
                                  != NULL
                                : strchr(p + 1, ' ') != NULL);
      p++;
      continue;
    }
    if (command) {
      p++;
      continue;
    }
    char w[256];
    size_t n = 0;
    while (*p && (word_char((unsigned char)*p) || strchr("./*-", *p))) {
      if (n + 1 < sizeof w) w[n++] = *p;
      p++;
    }
    while (n > 0 && w[n - 1] == '.') n--;
    w[n] = 0;
    if (n > 0 && strchr(w, '.')) check_name(T, doc, line, w, 0, missing);
    if (*p) p++;
  }
}

/* Every name of one document: backticked spans (.md) and file words. */
static void check_document(const tree_text *T, const char *doc, char *text,
                           int *names, int *missing)
{
  char *line = text, *next;
  int number = 0, fenced = 0, md = ends_with(doc, ".md");
  for (; line; line = next) {
    char *tick;
    next = strchr(line, '\n');
    if (next) *next++ = 0;
    number++;
    if (md && !strncmp(line, "```", 3)) {
      fenced = !fenced;
      continue;
    }
    if (fenced || (md && !strncmp(line, "    ", 4))) continue;
    check_bare_files(T, doc, number, line, missing);
    for (tick = md ? strchr(line, '`') : NULL; tick; ) {
      char *end = strchr(tick + 1, '`'), span[256];
      size_t n;
      if (!end) break;
      n = (size_t)(end - tick - 1);
      if (n < sizeof span) {
        memcpy(span, tick + 1, n);
        span[n] = 0;
        if (n > 2 && !strcmp(span + n - 2, "()")) span[n - 2] = 0;
        check_name(T, doc, number, span, 1, missing);
        (*names)++;
      }
      tick = strchr(end + 1, '`');
    }
  }
}

static void test_doc_names_exist(void)
{
  tree_text T;
  glob_t docs;
  char *text = malloc(TEXT_MAX * 4);
  size_t k;
  int names = 0, missing = 0;
  T.src = malloc(TREE_TEXT);
  T.paths = malloc(TREE_TEXT);
  T.src_len = T.paths_len = 0;
  CHECK(text && T.src && T.paths, "out of memory");
  if (!text || !T.src || !T.paths) goto out;
  T.src[0] = 0;
  append(T.paths, &T.paths_len, "\n", 1);
  walk_tree(".", &T);
  if (glob("doc/*.md", 0, NULL, &docs) != 0) docs.gl_pathc = 0;
  for (k = 0; k < docs.gl_pathc + 2; k++) {
    const char *doc = k == 0 ? "README.md" : k == 1 ? MAN_PAGE
                    : docs.gl_pathv[k - 2];
    read_text(doc, text, TEXT_MAX * 4);
    CHECK(text[0], "%s: cannot read", doc);
    check_document(&T, doc, text, &names, &missing);
  }
  if (docs.gl_pathc) globfree(&docs);
  printf("  %d backticked names, %d missing\n", names, missing);
out:
  free(text);
  free(T.src);
  free(T.paths);
}

/* ---- doc/reproduction names versions ------------------------------------- */
/* A run is traced by `afv --version` (params.txt records it), not by the
** history of the repository: no commit hash, issue number or branch in
** doc/reproduction/.  A commit-like token: 7 to 40 lower-case hex digits
** with a digit and a letter other than e (so no number such as 1234567e,
** the digits of a float), not after '#' (a colour) or '.'. */
static int is_commit_like(const char *line, const char *p, size_t n)
{
  size_t k;
  int digit = 0, letter = 0;
  if (n < 7 || n > 40 || (p > line && (p[-1] == '#' || p[-1] == '.')))
    return 0;
  for (k = 0; k < n; k++) {
    if (p[k] >= '0' && p[k] <= '9') digit = 1;
    else if (p[k] >= 'a' && p[k] <= 'f') letter |= p[k] != 'e';
    else return 0;
  }
  return digit && letter;
}

/* 1 if the n characters at p are word, in any case. */
static int word_is(const char *p, size_t n, const char *word)
{
  return n == strlen(word) && strncasecmp(p, word, n) == 0;
}

/* The first history reference in line ("issue 30", "branch", a commit
** hash) into what; 1 if there is one. */
static int history_reference(const char *line, char *what, size_t len)
{
  const char *p = line;
  while (*p) {
    size_t n = 0;
    while (word_char((unsigned char)p[n]) && p[n] != '_') n++;
    if (n == 0) { p++; continue; }
    if (is_commit_like(line, p, n) || word_is(p, n, "branch")
        || word_is(p, n, "branches")) {
      snprintf(what, len, "%.*s", (int)n, p);
      return 1;
    }
    if (word_is(p, n, "issue") || word_is(p, n, "issues")) {
      const char *q = p + n;
      while (*q == ' ' || *q == '#') q++;
      if (*q >= '0' && *q <= '9') {
        snprintf(what, len, "%.*s", (int)(q - p + strspn(q, "0123456789")),
                 p);
        return 1;
      }
    }
    p += n;
  }
  return 0;
}

/* Checks every text file under dir (recursively); the number of files. */
static int check_reproduction_dir(const char *dir, char *text, size_t len)
{
  DIR *d = opendir(dir);
  struct dirent *e;
  int files = 0;
  while (d && (e = readdir(d)) != NULL) {
    char path[1024], what[64], *line, *save = NULL;
    struct stat st;
    int lineno = 0;
    if (e->d_name[0] == '.') continue;
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (stat(path, &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) {
      files += check_reproduction_dir(path, text, len);
      continue;
    }
    if (!ends_with(path, ".md") && !ends_with(path, ".csv")
        && !ends_with(path, ".txt") && !ends_with(path, ".svg"))
      continue;
    files++;
    read_text(path, text, len);
    for (line = text; line; line = save) {
      if ((save = strchr(line, '\n'))) *save++ = 0;
      lineno++;
      CHECK(!history_reference(line, what, sizeof what), "%s:%d: '%s': "
            "doc/reproduction names versions (afv --version of the run), "
            "not commits, issues or branches", path, lineno, what);
    }
  }
  if (d) closedir(d);
  return files;
}

static void test_reproduction_names_versions(void)
{
  char *text = malloc(TREE_TEXT);
  int files;
  if (!text) return;
  files = check_reproduction_dir("doc/reproduction", text, TREE_TEXT);
  CHECK(files > 0, "doc/reproduction: no text file");
  printf("  doc/reproduction: %d files\n", files);
  free(text);
}

/* ---- the record's status line counts what its claims.csv says ------------ */
/* doc/reproduction/paper/README.md opens with a hand-written "How much is
** in" line: how many claims agree, are undetermined, do not (before
** "Against dt") and how many have each dt verdict (after it).  A
** regenerated claims.csv leaves it behind unless it is rewritten: every
** "N WORDS" of a verdict in that line must be claims.csv's count, and a
** verdict claims.csv gives must be counted there. */

/* The count of claims.csv rows whose column (5: agrees, 6: dt_verdict) is
** value: the first six columns hold no comma (the note, quoted, is last). */
static int claims_with(const char *csv, int column, const char *value)
{
  const char *line = strchr(csv, '\n');
  int n = 0;
  while (line && *++line) {
    const char *f = line;
    int c;
    size_t len = strlen(value);
    for (c = 1; c < column && f; c++)
      if ((f = strchr(f, ','))) f++;
    if (f && strncmp(f, value, len) == 0 && (f[len] == ',' || f[len] == '\n'))
      n++;
    line = strchr(line, '\n');
  }
  return n;
}

/* In text[0..len): every "N words" names count, and it is there if count > 0. */
static void check_status_count(const char *doc, const char *text, size_t len,
                               const char *words, int count)
{
  const char *p = text;
  int found = 0;
  size_t w = strlen(words);
  while ((p = strstr(p, words)) && (size_t)(p - text) + w <= len) {
    const char *q = p - 1;
    if (q > text && *q == ' ' && isdigit((unsigned char)q[-1])) {
      int n;
      for (q--; q > text && isdigit((unsigned char)q[-1]); q--) {}
      n = atoi(q);
      found = 1;
      if (n != count)
        printf("    %s: \"%d %s\", claims.csv has %d\n", doc, n, words, count);
      CHECK(n == count, "the status line's count is claims.csv's");
    }
    p += w;
  }
  if (count > 0 && !found)
    printf("    %s: claims.csv has %d \"%s\", the status line none\n", doc,
           count, words);
  CHECK(count == 0 || found, "the status line counts every verdict given");
}

static void test_record_status_counts_claims(void)
{
  static const char *const agrees[] = {"agree", "are undetermined", "do not",
                                       "missing", "not measured"};
  static const char *const agrees_value[] = {"yes", "undetermined", "no",
                                             "missing", "not measured"};
  static const char *const dt[] = {"are a property of dt = 0.01",
                                   "are a property of the model",
                                   "not converged", "not measured", "missing",
                                   "none"};
  static const char *const dt_value[] = {"property of dt = 0.01",
                                         "property of the model",
                                         "not converged", "not measured",
                                         "missing", "none"};
  const char *doc = "doc/reproduction/paper/README.md";
  char *readme = malloc(TEXT_MAX), *csv = malloc(TEXT_MAX);
  const char *start, *end, *split;
  size_t k;
  if (!readme || !csv) { free(readme); free(csv); return; }
  read_text(doc, readme, TEXT_MAX);
  read_text("doc/reproduction/paper/claims.csv", csv, TEXT_MAX);
  start = strstr(readme, "**How much is in");
  CHECK(start != NULL && *csv, "the record's README has a status line");
  if (start && *csv) {
    end = strstr(start + 2, "**");
    split = strstr(start, "Against dt");
    CHECK(end && split && split < end, "the status line has its dt part");
    if (end && split && split < end) {
      int rows = -1, counted = 0, measured = -1, all = -1;
      const char *c;
      for (c = csv; (c = strchr(c, '\n')); c++) rows++;  /* after the header */
      for (k = 0; k < sizeof agrees / sizeof *agrees; k++) {
        int n = claims_with(csv, 5, agrees_value[k]);
        counted += n;
        check_status_count(doc, start, (size_t)(split - start), agrees[k], n);
      }
      CHECK(counted == rows, "claims.csv: %d rows, %d with a known agrees",
            rows, counted);
      if ((c = strstr(start, " of the ")) && c < split) {  /* "N of the M" */
        while (c > start && isdigit((unsigned char)c[-1])) c--;
        sscanf(c, "%d of the %d claims measured", &measured, &all);
      }
      CHECK(measured == rows - claims_with(csv, 5, "not measured")
            && all == rows, "\"%d of the %d claims measured\": claims.csv "
            "has %d rows, %d measured", measured, all, rows,
            rows - claims_with(csv, 5, "not measured"));
      for (k = 0; k < sizeof dt / sizeof *dt; k++)
        check_status_count(doc, split, (size_t)(end - split), dt[k],
                           claims_with(csv, 6, dt_value[k]));
    }
  }
  free(readme);
  free(csv);
}

/* ---- the docs name this version and real make targets --------------------- */
/* README.md, the .md files of doc/ (not doc/reproduction, whose runs were
** made by earlier versions) and the program's help name the shared
** library with its version, and make targets in commands; a release or a
** renamed target leaves them behind.  Checked: every "libafv.so.X.Y.Z"
** names AFV_VERSION; every command "make TARGET" (after a backtick, or
** first on a line of code: indented) is a target of the Makefile (a line
** "TARGET:" or "TARGET ...:"). */
static int makefile_has_target(const char *makefile, const char *target)
{
  const char *p = makefile;
  size_t n = strlen(target);
  for (; p; p = strchr(p, '\n')) {
    if (*p == '\n') p++;
    if (strncmp(p, target, n) == 0 && (p[n] == ':' || p[n] == ' ')) {
      const char *colon = strchr(p, ':'), *end = strchr(p, '\n');
      if (colon && (!end || colon < end) && colon[1] != '=') return 1;
    }
  }
  return 0;
}

static void check_versions_and_targets(const char *path, const char *text,
                                       const char *makefile, int *bad)
{
  const char *p;
  for (p = strstr(text, "libafv.so."); p; p = strstr(p + 1, "libafv.so.")) {
    const char *v = p + strlen("libafv.so.");
    if (v[0] >= '0' && v[0] <= '9' && strchr(v, '.') - v < 4
        && strncmp(v, AFV_VERSION, strlen(AFV_VERSION)) != 0) {
      CHECK(0, "%s: '%.20s' is not libafv.so.%s", path, p, AFV_VERSION);
      (*bad)++;
    }
  }
  for (p = strstr(text, "make "); p; p = strstr(p + 1, "make ")) {
    char target[64];
    int n = 0;
    const char *q = p;
    while (q > text && q[-1] == ' ') q--;
    if (!(p > text && p[-1] == '`') && !(q < p && (q == text || q[-1] == '\n')))
      continue;                              /* prose: "make it", "make the" */
    while (n < 63 && (islower((unsigned char)p[5 + n]) || p[5 + n] == '-'
                      || (n > 0 && isdigit((unsigned char)p[5 + n]))))
      target[n] = p[5 + n], n++;
    target[n] = 0;
    if (n < 2 || !islower((unsigned char)target[0])
        || (p[5 + n] && !strchr(" \n`.,;:)'", p[5 + n])))
      continue;
    if (!makefile_has_target(makefile, target)) {
      CHECK(0, "%s: 'make %s': the Makefile has no target %s", path, target,
            target);
      (*bad)++;
    }
  }
}

static void test_docs_name_version_and_targets(void)
{
  static const char *const extra[] = {"README.md", "cmd/cli.c", "cmd/main.c"};
  char *text = malloc(TEXT_MAX * 4), *makefile = malloc(TEXT_MAX * 4);
  glob_t docs;
  size_t k;
  int bad = 0, files = 0;
  if (!text || !makefile) { free(text); free(makefile); return; }
  read_text("Makefile", makefile, TEXT_MAX * 4);
  if (glob("doc/*.md", 0, NULL, &docs) != 0) docs.gl_pathc = 0;
  for (k = 0; k < docs.gl_pathc + 3; k++) {
    const char *path = k < 3 ? extra[k] : docs.gl_pathv[k - 3];
    read_text(path, text, TEXT_MAX * 4);
    check_versions_and_targets(path, text, makefile, &bad);
    files++;
  }
  if (docs.gl_pathc) globfree(&docs);
  printf("  %d files, %d stale versions or targets\n", files, bad);
  CHECK(files > 3, "no doc/*.md read");
  free(text);
  free(makefile);
}

/* doc/paper_states.sh prints the README's table from the runs it finds
** and runs nothing without --run (issue 41: it started four 10^6-step
** runs when asked for the table): a finished state's numbers, "(not run)"
** for the others, no run folder made. */
static void test_paper_states_prints_without_running(void)
{
  char path[256], out[TEXT_MAX];
  FILE *fp;
  snprintf(path, sizeof path, "%s/states/p4_v0.1/analysis", tmp);
  CHECK(test_sh("mkdir -p '%s'", path) == 0, "mkdir %s", path);
  snprintf(path, sizeof path, "%s/states/p4_v0.1/analysis/summary.txt", tmp);
  if (!(fp = fopen(path, "w"))) {
    CHECK(0, "cannot write %s", path);
    return;
  }
  fputs("ngc_frac_mean 1\nomega_mean 0.989\nD_eff 2e-06\nmsd_beta 0.09\n"
        "t1_final 5.5\n", fp);
  fclose(fp);
  snprintf(path, sizeof path, "%s/states.txt", tmp);
  CHECK(test_sh("timeout 20 sh doc/paper_states.sh '%s/states' >'%s' "
                "2>/dev/null", tmp, path) == 0, "sh doc/paper_states.sh");
  read_text(path, out, sizeof out);
  CHECK(strstr(out, "\n4     0.1   1              0.989       2e-06    0.09"
               "      5.5\n") && strstr(out, "\n8.8   2.6   (not run)\n"),
        "the table:\n%s", out);
  snprintf(path, sizeof path, "%s/states/p8.8_v0.1", tmp);
  CHECK(access(path, F_OK) != 0, "%s: a run was started", path);
}

void suite_docs(void)
{
  char cmd[96];
  strcpy(tmp, "/tmp/afv_docs_XXXXXX");
  if (!mkdtemp(tmp)) {
    printf("  cannot create a temporary directory under /tmp: %s\n",
           strerror(errno));
    return;
  }
  RUN(test_run_help_ranges_true);
  RUN(test_run_help_defaults_true);
  RUN(test_other_help_defaults_true);
  RUN(test_man_page_covers_options);
  RUN(test_quench_v0_between_steps);
  RUN(test_quench_per_cell_v0);
  RUN(test_parameter_change_needs_refresh);
  RUN(test_doc_names_exist);
  RUN(test_reproduction_names_versions);
  RUN(test_record_status_counts_claims);
  RUN(test_docs_name_version_and_targets);
  RUN(test_paper_states_prints_without_running);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);   /* mkdtemp's own dir */
  if (system(cmd) != 0) printf("  note: could not remove %s\n", tmp);
}
