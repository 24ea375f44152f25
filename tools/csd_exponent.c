/*
** tools/csd_exponent.c -- the cluster-size distribution's power-law
** exponent of one run, fitted as `afv paper` fits Fig. 2(c) (the log bins
** after the densest, sizes up to a quarter of the largest size seen,
** afv_powerlaw_fit), for the model study's
** dt table (tools/model_table.sh), where each seed is fitted on its own.
**
**   tools/csd_exponent RUN/analysis/csd.csv N
**
** Prints "exponent" (nan when fewer than 2 bins are left).  Exit status 2
** on a file that is not afv analyze's csd.csv (header n,p).
*/
#include "afv.h"
#include "cmd/fits.h"   /* afv_powerlaw_fit */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* As cmd/paper.c's plot_csd: the giant cluster is left out of the fit
** (sizes up to this fraction of the largest size seen). */
#define CSD_FIT_FRACTION 0.25

int main(int argc, char **argv)
{
  double *csd;
  int N, n, lineno = 1;
  char line[256];
  afv_powerlaw fit;
  FILE *fp;
  if (argc != 3 || (N = atoi(argv[2])) < 1) {
    fprintf(stderr, "usage: tools/csd_exponent CSD.CSV N\n");
    return 2;
  }
  if (!(fp = fopen(argv[1], "r")) || !fgets(line, sizeof line, fp)) {
    fprintf(stderr, "csd_exponent: %s: cannot read\n", argv[1]);
    return 2;
  }
  csd = calloc((size_t)N + 1, sizeof *csd);
  while (csd && fgets(line, sizeof line, fp)) {
    int s;
    double p;
    lineno++;
    if (sscanf(line, "%d,%lf", &s, &p) != 2 || s < 1 || s > N) {
      fprintf(stderr, "csd_exponent: %s:%d: not a size in 1..%d and a "
              "probability\n", argv[1], lineno, N);
      return 2;
    }
    csd[s] = p;
  }
  fclose(fp);
  for (n = N; n > 0 && csd[n] == 0; n--) continue;
  fit.exponent = NAN;
  if (n > 0) afv_powerlaw_fit(csd, n, (int)(CSD_FIT_FRACTION * n), &fit);
  printf("%.6g\n", fit.exponent);
  free(csd);
  return 0;
}
