/*
** test_invariants.c -- the library's invariants and its functions'
** preconditions are checked: in a build without -DNDEBUG a broken one
** stops the program at the assert that states it (geom.c, neighbours.c,
** afv.c headers; the asserts at the entry of the public functions).
** make test runs this suite in test/run_tests_assert, built without
** -DNDEBUG; the default build (-DNDEBUG) compiles the asserts out and runs
** none of it.
*/
#define _POSIX_C_SOURCE 200809L  /* fork, pipe, dup2, waitpid */
#include "test.h"

#include <signal.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef NDEBUG
/* Runs fn(arg) in a child process, its standard error into err (len
** bytes); returns the child's wait status. */
static int run_in_child(void (*fn)(void *), void *arg, char *err, size_t len)
{
  int fd[2], status = 0;
  size_t got = 0;
  ssize_t k;
  pid_t pid;
  if (pipe(fd) != 0) return -1;
  fflush(stdout);
  pid = fork();
  if (pid == 0) {
    close(fd[0]);
    dup2(fd[1], 2);
    fn(arg);
    _exit(0);
  }
  close(fd[1]);
  while (got + 1 < len && (k = read(fd[0], err + got, len - 1 - got)) > 0)
    got += (size_t)k;
  err[got] = 0;
  close(fd[0]);
  if (pid < 0 || waitpid(pid, &status, 0) != pid) return -1;
  return status;
}

static void shape_cell_0(void *g)
{
  afv_cell_shape(g, 0, 1.0);
}

static int shape_in_child(afv_geom *g, char *err, size_t len)
{
  return run_in_child(shape_cell_0, g, err, len);
}

/* Broken preconditions, one per child: NULL positions for 3 cells. */
static void compute_without_positions(void *unused)
{
  afv_params p;
  afv_geom g = {0};
  double f[6];
  (void)unused;
  afv_params_default(&p);
  afv_compute(&g, 3, NULL, &p, NULL, f);
}

static void init_cluster_without_output(void *unused)
{
  (void)unused;
  afv_init_cluster(3, 1, NULL, 2.0, NULL);
}

/* Each public function of the model asserts its preconditions at entry
** (SQLite style): a caller that breaks one is stopped there, with the
** condition named, instead of reading through a NULL pointer. */
static void broken_precondition_stops_at_entry(void)
{
  static const struct { void (*fn)(void *); const char *names; } cases[] = {
    {compute_without_positions, "r != NULL"},
    {init_cluster_without_output, "r != NULL"}};
  char err[512];
  size_t k;
  for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    int status = run_in_child(cases[k].fn, NULL, err, sizeof err);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT
          && strstr(err, cases[k].names) != NULL, "case %d: wait status "
          "%d, message \"%s\" (want SIGABRT naming %s)", (int)k, status, err,
          cases[k].names);
  }
}
#endif

/* Cell 0's neighbour list, sorted by direction (neighbours.c), with two
** slots swapped: the clipping relies on the order, so afv_cell_shape's
** assert must stop the program (SIGABRT) and name the invariant. */
#ifndef NDEBUG
static void unsorted_list_stops_the_clipping(void)
{
  double r[6] = {0, 0, 1, 0, 0, 1};
  afv_params p;
  afv_box open = {0, 0, 0};
  afv_geom g = {0};
  char err[512];
  int s, status, tj;
  double tx, ty;
  afv_params_default(&p);
  CHECK(afv_geometry(&g, 3, r, &p, &open) == AFV_OK, "geometry");
  s = g.nbr_start[0];
  CHECK(g.nbr_end[0] - s == 2, "cell 0 has two neighbours");
  CHECK(afv_slots_sorted(&g, 0), "the list as afv_neighbours leaves it");
  status = shape_in_child(&g, err, sizeof err);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
        "the sorted list is shaped without a stop");
  tj = g.nbr[s]; g.nbr[s] = g.nbr[s + 1]; g.nbr[s + 1] = tj;
  tx = g.nbr_d[2*s]; ty = g.nbr_d[2*s+1];
  g.nbr_d[2*s] = g.nbr_d[2*s+2]; g.nbr_d[2*s+1] = g.nbr_d[2*s+3];
  g.nbr_d[2*s+2] = tx; g.nbr_d[2*s+3] = ty;
  CHECK(!afv_slots_sorted(&g, 0), "two slots swapped");
  status = shape_in_child(&g, err, sizeof err);
  CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT,
        "the unsorted list must stop afv_cell_shape (wait status %d)", status);
  CHECK(strstr(err, "afv_slots_sorted") != NULL,
        "the message names the invariant: \"%s\"", err);
  afv_geom_free(&g);
}
#endif

void suite_invariants(void)
{
#ifdef NDEBUG
  printf("  (built with -DNDEBUG: the asserts are compiled out; make test "
         "runs this suite in test/run_tests_assert)\n");
#else
  RUN(unsorted_list_stops_the_clipping);
  RUN(broken_precondition_stops_at_entry);
#endif
}
