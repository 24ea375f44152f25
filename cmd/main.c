/*
** main.c -- the afv command-line program's dispatcher: afv COMMAND ARGS
** calls cmd_COMMAND (cli.h lists the files that hold them).
**
**   afv eval POINTS [options]     geometry, energy and forces of one configuration
**   afv check POINTS [options]    analytic forces against finite differences
**   afv run [options] --out DIR   the simulation job (relax, then dynamics)
**   afv draw FILE [options]       SVG of a POINTS file or a trajectory frame
**   afv analyze DIR [options]     order parameters, MSD and plots of a run
**   afv meanfield [options]       the hexagonal mean-field E/M point P0*
**   afv sweep --out DIR [options] a grid of runs and its runners
**   afv collect DIR               a sweep's table, fits and figures
**   afv paper DIR                 the paper's figures and claims (make paper)
**
** Exit status: 0 success, 1 a check failed, 2 bad input or options,
** 3 a run stopped on an unstable step.
*/
#define _POSIX_C_SOURCE 200809L  /* getpid */
#include "afv.h"
#include "cli.h"

#include <unistd.h>

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage_text =
  "usage: afv COMMAND [ARGS] [OPTIONS]\n"
  "\n"
  "Active Finite Voronoi model of epithelial and mesenchymal tissue.\n"
  "\n"
  "commands:\n"
  "  eval POINTS     print each cell's geometry and force, and the energy\n"
  "  check POINTS    compare analytic forces with finite differences\n"
  "  run             simulate: relax a cluster, then active dynamics\n"
  "  draw FILE       SVG picture of a POINTS file or a trajectory frame\n"
  "  analyze DIR     order parameters, MSD and plots of a run\n"
  "  meanfield       the hexagonal mean-field E/M point P0*\n"
  "  sweep           a grid of runs (make, GNU parallel or SLURM runs it)\n"
  "  collect DIR     a sweep's table, phase labels, fits and figures\n"
  "  paper DIR       the paper's figures and claims table (make paper)\n"
  "\n"
  "  version         print afv's version (also afv --version)\n"
  "\n"
  "Run 'afv COMMAND --help' for the options of a command (afv run --help\n"
  "lists every simulation key with its default, unit and meaning).\n";

/* ---- dispatch ---------------------------------------------------------- */
typedef struct command {
  const char *name;
  int (*run)(int argc, char **argv);
} command;

static const command commands[] = {
  {"eval", cmd_eval},
  {"check", cmd_check},
  {"run", cmd_run},
  {"draw", cmd_draw},
  {"analyze", cmd_analyze},
  {"meanfield", cmd_meanfield},
  {"sweep", cmd_sweep},
  {"collect", cmd_collect},
  {"paper", cmd_paper},
};

const char *program_name = "afv";

/* 1 if arg is --KEY=VALUE with KEY a word (letters, digits, _ and -). */
static int is_key_value(const char *arg)
{
  const char *p = arg + 2;
  if (strncmp(arg, "--", 2) != 0 || !isalpha((unsigned char)*p)) return 0;
  while (isalnum((unsigned char)*p) || *p == '_' || *p == '-') p++;
  return *p == '=';
}

/* argv with every --KEY=VALUE split into --KEY and VALUE (at the first
** '=', which becomes the end of --KEY: argv's strings are the program's
** to modify), so that each command takes both forms; *argc_out its
** length.  NULL if out of memory; the caller frees the array. */
static char **split_key_values(int argc, char **argv, int *argc_out)
{
  char **out = malloc((size_t)(2 * argc + 1) * sizeof *out);
  int k, m = 0;
  if (!out) return NULL;
  for (k = 0; k < argc; k++) {
    if (is_key_value(argv[k])) {
      char *eq = strchr(argv[k], '=');
      *eq = 0;
      out[m++] = argv[k];
      out[m++] = eq + 1;
    } else
      out[m++] = argv[k];
  }
  out[m] = NULL;
  *argc_out = m;
  return out;
}

int main(int argc, char **argv)
{
  size_t c;
  if (argc > 0 && argv[0]) program_name = argv[0];
  afv_atomic_pid = (long)getpid();   /* in the names of temporary files */
  if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0
      || strcmp(argv[1], "help") == 0) {
    fputs(usage_text, argc < 2 ? stderr : stdout);
    if (argc >= 2) printf("\nOptions of eval, check and draw:\n%s", model_help);
    return argc < 2 ? EXIT_BAD_INPUT : 0;
  }
  if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "version") == 0) {
    printf("afv %s\n", afv_build_version());
    return 0;
  }
  for (c = 0; c < sizeof commands / sizeof commands[0]; c++)
    if (strcmp(argv[1], commands[c].name) == 0) {
      char **args = split_key_values(argc - 1, argv + 1, &argc);
      if (!args) {
        fputs("afv: out of memory\n", stderr);
        return EXIT_BAD_INPUT;
      }
      int status;
      command_name = commands[c].name;
      status = commands[c].run(argc, args);
      free(args);
      return status;
    }
  fprintf(stderr, "afv: unknown command '%s' (see afv --help)\n", argv[1]);
  return EXIT_BAD_INPUT;
}
