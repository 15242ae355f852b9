/* Reading simpleFoam logs and the volFieldValue output of the "flow" function object. */
#include "foam_case.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mdp_foam_parse_log(const char *log, int axis, double *last_time, double *res_p, double *res_u,
                       int *solver_converged) {
  FILE *f = fopen(log, "r");
  if (!f) return 1;
  char line[1024], ufield[16];
  snprintf(ufield, sizeof ufield, "for U%c,", 'x' + axis);
  *solver_converged = 0;
  int first_p = 0; /* the first p solve of a step (PISO solves p several times per step) */
  while (fgets(line, sizeof line, f)) {
    char *s;
    if (!strncmp(line, "Time = ", 7)) *last_time = atof(line + 7), first_p = 1;
    if (strstr(line, "solution converged in")) *solver_converged = 1;
    if (!(s = strstr(line, "Initial residual = "))) continue;
    double v = atof(s + 19);
    if (strstr(line, "for p,") && first_p) *res_p = v, first_p = 0;
    if (strstr(line, ufield)) *res_u = v;
  }
  fclose(f);
  return 0;
}

typedef struct {
  double start;
  char name[256];
} start_dir_t;

static int by_start(const void *a, const void *b) {
  double x = ((const start_dir_t *)a)->start, y = ((const start_dir_t *)b)->start;
  return (x > y) - (x < y);
}

int mdp_foam_read_flow(const char *dir, double **rows, int *n_rows, char *err) {
  char base[4200];
  snprintf(base, sizeof base, "%s/postProcessing/flow", dir);
  DIR *d = opendir(base);
  if (!d) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: no function-object output (did simpleFoam run?)",
             base);
    return 1;
  }
  start_dir_t starts[256];
  int ns = 0;
  struct dirent *e;
  while ((e = readdir(d)) && ns < 256) {
    if (e->d_name[0] == '.') continue;
    starts[ns].start = atof(e->d_name);
    snprintf(starts[ns].name, sizeof starts[ns].name, "%s", e->d_name);
    ns++;
  }
  closedir(d);
  qsort(starts, (size_t)ns, sizeof *starts, by_start);
  int cap = 1024, n = 0;
  double *r = malloc(sizeof *r * 5 * (size_t)cap);
  for (int s = 0; s < ns && r; s++) {
    char file[4600], line[1024];
    snprintf(file, sizeof file, "%s/%s/volFieldValue.dat", base, starts[s].name);
    FILE *f = fopen(file, "r");
    if (!f) continue;
    while (r && fgets(line, sizeof line, f)) {
      double v[5];
      if (line[0] == '#') continue;
      if (sscanf(line, "%lf (%lf %lf %lf) %lf", &v[0], &v[1], &v[2], &v[3], &v[4]) != 5) continue;
      while (n > 0 && r[5 * (n - 1)] >= v[0]) n--; /* a restart repeats or rewinds iterations */
      if (n == cap) {
        double *grown = realloc(r, sizeof *r * 5 * (size_t)(cap *= 2));
        if (!grown) free(r);
        if (!(r = grown)) break;
      }
      memcpy(r + 5 * n, v, sizeof v);
      n++;
    }
    fclose(f);
  }
  if (!r) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: out of memory for %d rows of volume integrals", base,
             n);
    *rows = NULL;
    *n_rows = 0;
    return 1;
  }
  *rows = r;
  *n_rows = n;
  if (!n) snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: no rows of volume integrals", base);
  return n == 0;
}

int mdp_foam_parse_checkmesh(const char *log, double *volume, char *failed, size_t len,
                             int *fatal) {
  FILE *f = fopen(log, "r");
  if (!f) return 1;
  char line[1024];
  *volume = NAN, *fatal = 0;
  snprintf(failed, len, "ok");
  int n_failed = 0;
  while (fgets(line, sizeof line, f)) {
    char *s = strstr(line, "Total volume = ");
    if (s) *volume = atof(s + 15);
    if (!(s = strstr(line, "***"))) continue;
    /* a cell that is inverted, open or not closed makes the mesh unusable; quality warnings (high
     * non-orthogonality, skewness) do not */
    if (strstr(s, "negative") || strstr(s, "Error") || strstr(s, "open") ||
        strstr(s, "ncorrectly oriented") || strstr(s, "not closed"))
      *fatal = 1;
    s[strcspn(s, "\r\n")] = 0;
    for (char *c = s; *c; c++) /* the text goes into a JSON string */
      if (*c == '"' || *c == '\\' || (unsigned char)*c < 32) *c = '\'';
    size_t used = n_failed ? strlen(failed) : 0;
    if (used + strlen(s) + 3 < len)
      snprintf(failed + used, len - used, "%s%s", n_failed ? "; " : "", s + 3);
    n_failed++;
  }
  fclose(f);
  return 0;
}
