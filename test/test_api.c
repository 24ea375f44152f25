/*
** test_api.c -- the public header afv.h stands alone (issue 23, "Public
** API"): the README's C examples compile against afv.h without
** afv_internal.h, afv.h no longer shows the library's internals (the
** structs of afv_geom and afv_sim, the OpenMP macros), and the accessors
** of the opaque types hand out the library's own fields.
**
** The compile checks run `cc -fsyntax-only` in a directory that holds a
** copy of afv.h and nothing else; they SKIP when cc is missing.  Each
** "must fail" check has a control that compiles the same program against
** the whole source tree (afv_internal.h in reach), so a failure is the
** header's doing, not a broken command.
*/
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */
#include "test.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

static char tmp[64];          /* the suite's directory: the installed headers
                              ** afv.h and afv_config.h alone */
static int  have_cc;          /* 1 if `cc` runs */

/* Writes text to tmp/name; 1 on success. */
static int write_file(const char *name, const char *text)
{
  char path[128];
  FILE *fp;
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  if (!(fp = fopen(path, "w"))) return 0;
  fputs(text, fp);
  return fclose(fp) == 0;
}

/* The k-th (from 0) ```c block of README.md, into buf; 1 if found. */
static int readme_block(int k, char *buf, size_t len)
{
  FILE *fp = fopen("README.md", "r");
  char line[512];
  int on = 0, seen = -1;
  size_t used = 0;
  buf[0] = 0;
  if (!fp) return 0;
  while (fgets(line, sizeof line, fp)) {
    if (!on && strcmp(line, "```c\n") == 0) {
      on = ++seen == k;
      continue;
    }
    if (on && strcmp(line, "```\n") == 0) break;
    if (on && used + strlen(line) + 1 < len) {
      strcpy(buf + used, line);
      used += strlen(line);
    }
  }
  fclose(fp);
  return on && used > 0;
}

/* Exit status of cc -std=c99 -pedantic -Wall -Werror -fsyntax-only on
** tmp/name, with include path inc ("tmp": afv.h alone; ".": the tree). */
static int syntax_check(const char *name, const char *inc)
{
  return test_sh("cc -std=c99 -pedantic -Wall -Werror -fsyntax-only -I%s "
                 "'%s/%s' 2>/dev/null", strcmp(inc, "tmp") ? inc : tmp, tmp,
                 name);
}

static void test_readme_example_needs_only_afv_h(void)
{
  static char block[8192];
  if (!have_cc) { SKIP("cc not found"); return; }
  CHECK(readme_block(0, block, sizeof block), "README.md has no ```c block");
  CHECK(write_file("example.c", block), "cannot write example.c");
  CHECK(syntax_check("example.c", "tmp") == 0, "README's C example does not "
        "compile against afv.h alone");
}

/* The quench fragment of the README, given the names it assumes. */
static void test_readme_quench_needs_only_afv_h(void)
{
  static char block[8192], prog[10000];
  if (!have_cc) { SKIP("cc not found"); return; }
  CHECK(readme_block(1, block, sizeof block), "README.md has no quench block");
  CHECK(strstr(block, "afv_sim_step") != NULL, "second ```c block is not "
        "the quench");
  snprintf(prog, sizeof prog,
           "#include <afv.h>\n"
           "int main(void)\n{\n"
           "  double r[4] = {0, 0, 1.5, 0}, theta[2] = {0, 0};\n"
           "  int n = 2;\n  long k;\n  afv_params p;\n"
           "  afv_box box = {0, 0, 0};\n  afv_params_default(&p);\n"
           "  {\n%s  }\n  return 0;\n}\n", block);
  CHECK(write_file("quench.c", prog), "cannot write quench.c");
  CHECK(syntax_check("quench.c", "tmp") == 0, "README's quench does not "
        "compile against afv.h alone");
}

/* Programs that use the library's internals: each must compile against
** the tree (control) and fail against afv.h alone. */
static void test_afv_h_hides_internals(void)
{
  static const struct { const char *name, *body; } use[] = {
    {"geom_size.c", "int main(void) { return (int)sizeof(afv_geom); }\n"},
    {"geom_field.c", "int main(void) { afv_geom *g = afv_geom_new();\n"
                     "  int n = g->n; afv_geom_delete(g); return n; }\n"},
    {"sim_field.c", "int main(void) { afv_sim *s = afv_sim_new();\n"
                    "  s->dyn.v0 = 1; afv_sim_delete(s); return 0; }\n"},
    {"omp_macro.c", "int main(void) { return AFV_PARALLEL_MIN; }\n"},
    {"grid_type.c", "int main(void) { afv_grid g; g.nbx = 1; "
                    "return g.nbx; }\n"},
    {"angle.c", "int main(void) { return (int)afv_angle(1, 1); }\n"},
    {"rng.c", "int main(void) { return (int)afv_rng_normal(1, 0, 0, "
              "AFV_RNG_NOISE); }\n"},
  };
  char text[512];
  size_t k;
  if (!have_cc) { SKIP("cc not found"); return; }
  for (k = 0; k < sizeof use / sizeof use[0]; k++) {
    snprintf(text, sizeof text, "#include <afv_internal.h>\n%s", use[k].body);
    CHECK(write_file(use[k].name, text), "cannot write %s", use[k].name);
    CHECK(syntax_check(use[k].name, ".") == 0, "%s: the control (the tree's "
          "afv_internal.h) does not compile", use[k].name);
    snprintf(text, sizeof text, "#include <afv.h>\n%s", use[k].body);
    CHECK(write_file(use[k].name, text), "cannot write %s", use[k].name);
    CHECK(syntax_check(use[k].name, "tmp") != 0, "%s compiles against afv.h "
          "alone: afv.h still shows that internal", use[k].name);
  }
}

/* What only the program uses is in afv_tool.h, not in the installed
** afv.h (issue 29, two headers): each program compiles against the
** tree's afv_tool.h (control) and fails against afv.h alone. */
static void test_afv_h_leaves_the_program_out(void)
{
  static const char *const use[] = {
    "int main(void) { afv_lines L; return (int)sizeof L; }\n",
    "int main(void) { char t[9]; return !afv_atomic_open(\"x\", t, 9); }\n",
    "int main(void) { afv_checkpoint c = {0}; return c.n; }\n",
    "int main(void) { return AFV_CKPT_BYTES_LINE + AFV_CELLS_MAX; }\n",
    "int main(void) { return afv_svg_plot(0, 0, 0, 0); }\n",
  };
  char text[512];
  size_t k;
  if (!have_cc) { SKIP("cc not found"); return; }
  for (k = 0; k < sizeof use / sizeof use[0]; k++) {
    snprintf(text, sizeof text, "#include <afv_tool.h>\n%s", use[k]);
    CHECK(write_file("tool.c", text), "cannot write tool.c");
    CHECK(syntax_check("tool.c", ".") == 0, "the control (the tree's "
          "afv_tool.h) does not compile: %s", use[k]);
    snprintf(text, sizeof text, "#include <afv.h>\n%s", use[k]);
    CHECK(write_file("tool.c", text), "cannot write tool.c");
    CHECK(syntax_check("tool.c", "tmp") != 0, "compiles against afv.h "
          "alone, which should leave it to afv_tool.h: %s", use[k]);
  }
}

/* The library is the model (issue 39): the program's phase diagrams and
** fits (cmd/fits.h) are not in libafv.a, and afv_internal.h, which every
** library file includes, does not bring in the program's afv_tool.h.
** Fails on the tree before, where libafv.a held phase.o and fits.o and
** afv_internal.h included afv_tool.h. */
static void test_library_leaves_the_program_out(void)
{
  static const char *const fits[] = {"afv_curve_cross", "afv_boundary_fit",
    "afv_svg_map", "afv_powerlaw_fit", "afv_curves_cross",
    "afv_curves_cross_common", "afv_collapse_fit"};
  size_t k;
  if (test_sh("nm -g libafv.a >/dev/null 2>&1") != 0) {
    SKIP("nm not found");
    return;
  }
  for (k = 0; k < sizeof fits / sizeof fits[0]; k++)
    CHECK(test_sh("nm -g libafv.a | grep -q ' T %s$'", fits[k]) != 0,
          "libafv.a defines %s, the program's", fits[k]);
  if (!have_cc) return;
  CHECK(write_file("tool.c", "#include <afv_internal.h>\n"
                   "int main(void) { afv_lines L; return (int)sizeof L; }\n"),
        "cannot write tool.c");
  CHECK(syntax_check("tool.c", ".") != 0, "afv_internal.h brings in "
        "afv_tool.h (afv_lines)");
}

/* afv_clusters keeps its results public and its work space opaque: a
** program reading a result compiles against afv.h alone, one reaching
** the union-find's work space (a capacity, the parents) does not. */
static void test_clusters_work_space_hidden(void)
{
  static const char *const reads_result =
    "#include <afv.h>\nint main(void) { afv_clusters c = {0};\n"
    "  return c.count + c.giant + (c.label != 0); }\n";
  static const char *const reads_work[] = {
    "#include <afv.h>\nint main(void) { afv_clusters c = {0};\n"
    "  return c.cap_cells; }\n",
    "#include <afv.h>\nint main(void) { afv_clusters c = {0};\n"
    "  return c.parent != 0; }\n"};
  size_t k;
  if (!have_cc) { SKIP("cc not found"); return; }
  CHECK(write_file("clusters_result.c", reads_result), "cannot write");
  CHECK(syntax_check("clusters_result.c", "tmp") == 0, "a program reading "
        "afv_clusters' results does not compile against afv.h alone");
  for (k = 0; k < sizeof reads_work / sizeof reads_work[0]; k++) {
    CHECK(write_file("clusters_work.c", reads_work[k]), "cannot write");
    CHECK(syntax_check("clusters_work.c", "tmp") != 0, "afv.h still shows "
          "afv_clusters' work space: %s", reads_work[k]);
  }
}

/* Every accessor returns its own field of the struct in afv_internal.h. */
static void test_accessors_hand_out_the_fields(void)
{
  double r[8] = {0, 0, 1.5, 0, 0.7, 1.2, 6, 6};
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_dyn d;
  afv_geom *g = afv_geom_new();
  afv_sim *s = afv_sim_new();
  const afv_piece *pc;
  const int *nbr;
  const double *nd;
  int i, j, m;
  CHECK(g && s, "afv_geom_new or afv_sim_new failed");
  if (!g || !s) { afv_geom_delete(g); afv_sim_delete(s); return; }
  afv_params_default(&p);
  afv_dyn_default(&d);
  d.v0 = 0.3;
  CHECK(afv_compute(g, 4, r, &p, &b, NULL) == AFV_OK, "afv_compute failed");
  CHECK(afv_geom_n(g) == g->n && afv_geom_area(g) == g->area
        && afv_geom_perim(g) == g->perim && afv_geom_arc(g) == g->arc
        && afv_geom_contacts(g) == g->contacts
        && afv_geom_energy(g) == g->energy, "a geometry accessor is wrong");
  for (i = 0; i < 4; i++) {
    m = afv_geom_pieces(g, i, &pc);
    CHECK(m == g->n_pieces[i] && pc == g->pieces + g->piece_start[i],
          "afv_geom_pieces of cell %d", i);
    m = afv_geom_neighbours(g, i, &nbr, &nd);
    CHECK(m == g->nbr_end[i] - g->nbr_start[i]
          && nbr == g->nbr + g->nbr_start[i]
          && nd == g->nbr_d + 2 * g->nbr_start[i],
          "afv_geom_neighbours of cell %d", i);
  }
  CHECK(afv_geom_neighbours(g, 3, &nbr, NULL) == 0, "cell 3 is isolated");
  g->bad_i = 7; g->bad_j = 9;
  afv_geom_bad_pair(g, &i, &j);
  CHECK(i == 7 && j == 9, "afv_geom_bad_pair gave %d %d", i, j);

  CHECK(afv_sim_init(s, 4, r, NULL, &p, &b, &d) == AFV_OK, "init failed");
  CHECK(afv_sim_step(s) == AFV_OK, "step failed");
  CHECK(afv_sim_n(s) == s->n && afv_sim_steps(s) == s->step
        && afv_sim_time(s) == s->t && afv_sim_positions(s) == s->r
        && afv_sim_angles(s) == s->theta && afv_sim_forces(s) == s->f
        && afv_sim_geom(s) == &s->geom && afv_sim_params(s) == &s->par
        && afv_sim_box(s) == &s->box && afv_sim_dyn(s) == &s->dyn,
        "a simulation accessor is wrong");
  s->jumps = 11; s->largest_move = 12.5; s->bad_cell = 2;
  s->bad_disp = 0.75;
  CHECK(afv_sim_jumps(s) == 11 && afv_sim_largest_move(s) == 12.5
        && afv_sim_bad_cell(s) == 2 && afv_sim_bad_disp(s) == 0.75,
        "a counter accessor is wrong");
  afv_sim_set_steps(s, 42);
  CHECK(s->step == 42, "afv_sim_set_steps did not set the step");
  afv_geom_delete(g);
  afv_sim_delete(s);
  afv_geom_delete(NULL);
  afv_sim_delete(NULL);
}

/* The calls for bindings (afv.h, "bindings"): each name reads and writes
** its own field; a name the library does not know, or a seed that is not
** an integer in [0, 2^64), is refused and changes nothing. */
static void test_bindings_by_name(void)
{
  static const char *const names[] = {"mu", "v0", "Dr", "dt"};
  afv_dyn *d = afv_dyn_new(), def;
  afv_relax_report rep;
  double v, cells[3] = {1, 2, 3};
  double *fields[4];
  int k;
  CHECK(d != NULL, "afv_dyn_new failed");
  if (!d) return;
  afv_dyn_default(&def);
  CHECK(d->mu == def.mu && d->v0 == def.v0 && d->Dr == def.Dr
        && d->dt == def.dt && d->seed == def.seed && !d->v0_i && !d->Dr_i,
        "afv_dyn_new is not afv_dyn_default");
  fields[0] = &d->mu; fields[1] = &d->v0; fields[2] = &d->Dr;
  fields[3] = &d->dt;
  for (k = 0; k < 4; k++) {
    CHECK(afv_dyn_set(d, names[k], 10.5 + k) == AFV_OK
          && *fields[k] == 10.5 + k, "afv_dyn_set %s", names[k]);
    CHECK(afv_dyn_get(d, names[k], &v) == AFV_OK && v == 10.5 + k,
          "afv_dyn_get %s gave %g", names[k], v);
  }
  CHECK(afv_dyn_set(d, "seed", 9007199254740992.0) == AFV_OK
        && d->seed == 9007199254740992ULL, "seed 2^53");
  CHECK(afv_dyn_set(d, "seed", -1) == AFV_EINVAL
        && afv_dyn_set(d, "seed", 0.5) == AFV_EINVAL
        && afv_dyn_set(d, "seed", 18446744073709551616.0) == AFV_EINVAL
        && afv_dyn_set(d, "seed", 0.0 / 0.0) == AFV_EINVAL
        && d->seed == 9007199254740992ULL, "a bad seed was accepted");
  CHECK(afv_dyn_set(d, "v1", 1) == AFV_EINVAL
        && afv_dyn_get(d, "seeds", &v) == AFV_EINVAL
        && afv_dyn_set(d, "max_move", 0.05) == AFV_EINVAL
        && afv_dyn_set(d, "integrator", 0) == AFV_EINVAL,
        "an unknown name (or one of afv 0.2.0's sub-steps) was accepted");
  CHECK(afv_dyn_set_cells(d, "v0", cells) == AFV_OK && d->v0_i == cells
        && afv_dyn_set_cells(d, "Dr", cells + 1) == AFV_OK
        && d->Dr_i == cells + 1 && afv_dyn_set_cells(d, "v0", NULL) == AFV_OK
        && !d->v0_i && afv_dyn_set_cells(d, "P0", cells) == AFV_EINVAL,
        "afv_dyn_set_cells");
  afv_dyn_delete(d);
  afv_dyn_delete(NULL);

  memset(&rep, 0, sizeof rep);
  rep.iterations = 1; rep.time = 2; rep.max_force = 3; rep.energy0 = 4;
  rep.energy = 5; rep.drift = 6; rep.drop = 7; rep.jumps = 8;
  rep.converged = 9; rep.at_kink = 10; rep.refused = 11;
  {
    static const char *const rnames[] = {"iterations", "time", "max_force",
      "energy0", "energy", "drift", "drop", "jumps", "converged", "at_kink",
      "refused"};
    for (k = 0; k < 11; k++)
      CHECK(afv_relax_report_get(&rep, rnames[k], &v) == AFV_OK
            && v == k + 1, "afv_relax_report_get %s gave %g", rnames[k], v);
  }
  CHECK(afv_relax_report_get(&rep, "steps", &v) == AFV_EINVAL
        && afv_relax_report_get(&rep, "substeps", &v) == AFV_EINVAL,
        "an unknown report field was accepted");
  CHECK(afv_struct_size("afv_params") == sizeof(afv_params)
        && afv_struct_size("afv_box") == sizeof(afv_box)
        && afv_struct_size("afv_dyn") == 0, "afv_struct_size");
  CHECK(strcmp(afv_version(), AFV_VERSION) == 0, "afv_version");
}

/* afv_order_parameters hands out afv_clusters_compute's results. */
static void test_order_parameters_are_the_clusters(void)
{
  /* a pair, a triangle and two lone cells */
  double r[14] = {0, 0, 1.5, 0, 10, 0, 11.5, 0, 10.7, 1.2, 20, 20, -20, 20};
  double v[AFV_ORDER_COUNT];
  int label[7], i;
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_clusters c = {0};
  afv_geom *g = afv_geom_new();
  if (!g) { CHECK(0, "afv_geom_new failed"); return; }
  afv_params_default(&p);
  CHECK(afv_geometry(g, 7, r, &p, &b) == AFV_OK
        && afv_clusters_compute(&c, g, r, p.l, &b) == AFV_OK
        && afv_order_parameters(g, r, p.l, &b, v, label) == AFV_OK,
        "geometry or clusters failed");
  CHECK(v[AFV_ORDER_GIANT] == 3.0 / 7 && c.giant == 3
        && v[AFV_ORDER_OMEGA] == c.omega
        && v[AFV_ORDER_CLUSTERS] == 4 && c.count == 4
        && v[AFV_ORDER_PAIRS] == c.n_pairs && c.n_pairs == 4
        && v[AFV_ORDER_JUNCTIONS] == c.n_junctions,
        "order parameters %g %g %g %g %g", v[0], v[1], v[2], v[3], v[4]);
  for (i = 0; i < 7; i++)
    CHECK(label[i] == c.label[i], "label of cell %d", i);
  afv_clusters_free(&c);
  afv_geom_delete(g);
}

/* afv_svg_save writes afv_svg_write's bytes (afv_svg_draw's with cluster
** colours), atomically: a path it cannot write leaves nothing. */
static void test_svg_save_is_svg_write(void)
{
  double r[6] = {0, 0, 1.5, 0, 0.7, 1.2};
  afv_params p;
  afv_box b = {0, 0, 0};
  afv_draw_opts o = {0};
  afv_geom *g = afv_geom_new();
  char a[128], w[128], c[128];
  FILE *fp;
  if (!g) { CHECK(0, "afv_geom_new failed"); return; }
  afv_params_default(&p);
  CHECK(afv_geometry(g, 3, r, &p, &b) == AFV_OK, "geometry failed");
  snprintf(a, sizeof a, "%s/saved.svg", tmp);
  snprintf(w, sizeof w, "%s/written.svg", tmp);
  snprintf(c, sizeof c, "%s/clusters.svg", tmp);
  CHECK(afv_svg_save(a, g, 3, r, NULL, &p, &b, 0) == AFV_OK,
        "afv_svg_save failed");
  if ((fp = fopen(w, "w"))) {
    CHECK(afv_svg_write(fp, g, 3, r, NULL, &p, &b) == AFV_OK, "svg_write");
    fclose(fp);
  }
  CHECK(test_sh("cmp -s '%s' '%s'", a, w) == 0,
        "afv_svg_save differs from afv_svg_write");
  CHECK(afv_svg_save(c, g, 3, r, NULL, &p, &b, 1) == AFV_OK
        && test_sh("grep -q 'class=\"cell\"' '%s'", c) == 0,
        "afv_svg_save with cluster colours has no filled cells");
  o.color_by_cluster = 1;
  if ((fp = fopen(w, "w"))) {
    CHECK(afv_svg_draw(fp, g, 3, r, NULL, &p, &b, &o) == AFV_OK, "draw");
    fclose(fp);
  }
  CHECK(test_sh("cmp -s '%s' '%s'", c, w) == 0,
        "afv_svg_save by cluster differs from afv_svg_draw's");
  snprintf(a, sizeof a, "%s/no/such/dir.svg", tmp);
  CHECK(afv_svg_save(a, g, 3, r, NULL, &p, &b, 0) == AFV_EIO
        && test_sh("test -e '%s' || test -e '%s.tmp'", a, a) != 0,
        "an unwritable path gave no AFV_EIO or left a file");
  afv_geom_delete(g);
}

/* The first line of file that starts with prefix, the rest of it (without
** its newline) into buf; 1 if found. */
static int line_after(const char *file, const char *prefix, char *buf,
                      size_t len)
{
  FILE *fp = fopen(file, "r");
  char line[512];
  size_t n = strlen(prefix);
  int found = 0;
  if (!fp) return 0;
  while (!found && fgets(line, sizeof line, fp))
    if (strncmp(line, prefix, n) == 0) {
      line[strcspn(line, "\r\n")] = 0;
      snprintf(buf, len, "%s", line + n);
      found = 1;
    }
  fclose(fp);
  return found;
}

/* The binding calls of trajectories, analyses and the protocol hand out
** the structs' own fields by name, refuse unknown names and bad values,
** and afv_protocol_new's protocol starts as afv_protocol does. */
static void test_analysis_and_protocol_by_name(void)
{
  static const char *const names[] = {"cells", "frames", "first",
    "ngc_frac_mean", "ngc_frac_sd", "n_clusters_mean", "n_clusters_sd",
    "omega_mean", "omega_sd", "t1_final", "D_s", "D_s_lag", "D_s_origins",
    "D_s_plain", "D_0", "D_eff", "tau_NGC", "tau_NGC_reliable", "t1_rate",
    "msd_beta"};
  enum { N = 30 };
  double t[3] = {0, 1, 2}, r[3 * 2 * N], v, side = 9;
  afv_box b = test_periodic_box(20, 20);
  afv_traj *tr = afv_traj_new();
  afv_analysis *a = afv_analysis_new();
  afv_protocol *pr = afv_protocol_new(), by_hand = {0};
  afv_sim *s1 = afv_sim_new(), *s2 = afv_sim_new();
  afv_params p;
  afv_dyn d;
  size_t k;
  int count;
  if (!tr || !a || !pr || !s1 || !s2) {
    CHECK(0, "out of memory");
    return;
  }
  for (k = 0; k < 3; k++) afv_init_cluster(N, 5 + k, &b, side, r + 2 * N * k);
  CHECK(afv_traj_set(tr, N, 3, &b, NULL, t, r, NULL) == AFV_OK
        && afv_traj_steps(tr)[2] == 2 && afv_traj_angles(tr)[3 * N - 1] == 0
        && afv_traj_positions(tr)[6 * N - 1] == r[6 * N - 1]
        && afv_traj_box(tr)->Lx == 20, "afv_traj_set");
  CHECK(afv_traj_set(tr, -1, 3, &b, NULL, t, r, NULL) == AFV_EINVAL,
        "a negative count accepted");
  CHECK(afv_traj_set(tr, N, 3, &b, NULL, t, r, NULL) == AFV_OK
        && afv_analyze(a, tr, 1, 0.5, 0.1, 0, 1) == AFV_OK, "afv_analyze");
  for (k = 0; k < sizeof names / sizeof *names; k++)
    CHECK(afv_analysis_get(a, names[k], &v) == AFV_OK, "%s", names[k]);
  CHECK(afv_analysis_get(a, "D_eff", &v) == AFV_OK && v == a->deff
        && afv_analysis_get(a, "omega_sd", &v) == AFV_OK && v == a->sd[2]
        && afv_analysis_get(a, "deff", &v) == AFV_EINVAL, "by name");
  CHECK(afv_analysis_series(a, "omega", &count) == a->omega && count == 3
        && afv_analysis_series(a, "csd", &count) == a->csd + 1 && count == N
        && afv_analysis_series(a, "msd_rel", &count) == a->msd.msd_rel
        && count == a->msd.nlags && !afv_analysis_series(a, "x", &count)
        && count == 0, "series");
  CHECK(afv_protocol_set(pr, "start", 4) == AFV_EINVAL
        && afv_protocol_set(pr, "relax", 2) == AFV_EINVAL
        && afv_protocol_set(pr, "relax_max_steps", -1) == AFV_EINVAL
        && afv_protocol_set(pr, "relax_max_steps", 0.5) == AFV_EINVAL
        && afv_protocol_set(pr, "sides", 1) == AFV_EINVAL
        && afv_protocol_set_cells(pr, "x", r) == AFV_EINVAL, "bad values");
  CHECK(afv_protocol_set(pr, "side", side) == AFV_OK
        && afv_protocol_set(pr, "relax_max_steps", 300) == AFV_OK, "set");
  by_hand.start = AFV_START_CLUSTER;
  by_hand.side = side;
  by_hand.relax = AFV_RELAX_FLOW;
  by_hand.relax_tol = 1e-6;
  by_hand.relax_max_steps = 300;
  afv_params_default(&p);
  afv_dyn_default(&d);
  CHECK(afv_protocol_start(s1, N, &p, &b, &d, pr, NULL, NULL, NULL) == AFV_OK
        && afv_protocol_start(s2, N, &p, &b, &d, &by_hand, NULL, NULL, NULL)
           == AFV_OK
        && !memcmp(afv_sim_positions(s1), afv_sim_positions(s2),
                   sizeof(double) * 2 * N), "afv_protocol_new's start");
  afv_sim_delete(s1);
  afv_sim_delete(s2);
  afv_protocol_delete(pr);
  afv_analysis_delete(a);
  afv_traj_delete(tr);
}

/* The heading of CHANGELOG.md's newest version, "VERSION (YYYY-MM-DD)":
** the first line underlined with a line of '-' after the title,
** "Unreleased" skipped; "" if none. */
static void newest_changelog_heading(char *got, size_t len)
{
  char line[512], prev[512] = "";
  FILE *fp = fopen("CHANGELOG.md", "r");
  int k = 0;
  got[0] = 0;
  if (!fp) return;
  while (fgets(line, sizeof line, fp)) {
    int underline = line[0] == '-'
                    && strspn(line, "-") == strcspn(line, "\r\n");
    if (++k > 2 && underline && prev[0] != '\n'
        && strncmp(prev, "Unreleased", 10) != 0) {
      prev[strcspn(prev, "\r\n")] = 0;
      snprintf(got, len, "%s", prev);
      break;
    }
    snprintf(prev, sizeof prev, "%s", line);
  }
  fclose(fp);
}

/* 1 if text is a date YYYY-MM-DD (digits and dashes in place). */
static int is_date(const char *text)
{
  int k;
  for (k = 0; k < 10; k++)
    if (k == 4 || k == 7 ? text[k] != '-' : !isdigit((unsigned char)text[k]))
      return 0;
  return text[10] == 0;
}

/* CITATION.cff cites this version with its release date, and CHANGELOG.md's
** newest version is it, dated the same ("0.4.0 (2026-12-02)"). */
static void test_version_in_citation_and_changelog(void)
{
  char got[128] = "", date[64] = "", want[160];
  CHECK(line_after("CITATION.cff", "version: ", got, sizeof got)
        && strcmp(got, AFV_VERSION) == 0,
        "CITATION.cff: version '%s', afv.h: %s", got, AFV_VERSION);
  CHECK(line_after("CITATION.cff", "date-released: ", date, sizeof date)
        && is_date(date), "CITATION.cff: date-released '%s'", date);
  newest_changelog_heading(got, sizeof got);
  snprintf(want, sizeof want, "%s (%s)", AFV_VERSION, date);
  CHECK(strcmp(got, want) == 0, "CHANGELOG.md's newest entry is '%s', want "
        "'%s' (afv.h's version, CITATION.cff's date)", got, want);
  CHECK(line_after("LICENSE", "MIT License", got, sizeof got),
        "LICENSE is not the MIT licence");
}

void suite_api(void)
{
  char cmd[96];
  strcpy(tmp, "/tmp/afv_api_XXXXXX");
  if (!mkdtemp(tmp)) {
    printf("  cannot create a temporary directory under /tmp: %s\n",
           strerror(errno));
    return;
  }
  have_cc = test_sh("cc --version >/dev/null 2>&1") == 0;
  if (test_sh("cp afv.h afv_config.h '%s/'", tmp) != 0)
    printf("  cannot copy afv.h and afv_config.h into %s\n", tmp);
  RUN(test_readme_example_needs_only_afv_h);
  RUN(test_readme_quench_needs_only_afv_h);
  RUN(test_afv_h_hides_internals);
  RUN(test_library_leaves_the_program_out);
  RUN(test_afv_h_leaves_the_program_out);
  RUN(test_clusters_work_space_hidden);
  RUN(test_accessors_hand_out_the_fields);
  RUN(test_bindings_by_name);
  RUN(test_order_parameters_are_the_clusters);
  RUN(test_svg_save_is_svg_write);
  RUN(test_analysis_and_protocol_by_name);
  RUN(test_version_in_citation_and_changelog);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);   /* mkdtemp's own dir */
  if (system(cmd) != 0) printf("  note: could not remove %s\n", tmp);
}
