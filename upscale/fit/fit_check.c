/* Degenerate flow tables, refused before fitting (see fit_check.h). */
#include "fit_check.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(char *err, int errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The non-zero |G| of the table, sorted; returns their count (-1 when out of memory). */
static int sorted_gradients(const flow_table *t, double **out) {
  double *g = malloc((size_t)(t->n > 0 ? t->n : 1) * sizeof *g);
  int m = 0;
  if (!g) return -1;
  for (int i = 0; i < t->n; i++)
    if (t->G[i] != 0) g[m++] = fabs(t->G[i]);
  qsort(g, (size_t)m, sizeof *g, cmp_double);
  *out = g;
  return m;
}

static int count_levels(const double *g, int m) {
  int levels = m > 0;
  for (int i = 1; i < m; i++)
    if (g[i] - g[i - 1] > FIT_SAME_VALUE_RTOL * g[m - 1]) levels++;
  return levels;
}

int fit_distinct_gradients(const flow_table *t) {
  double *g;
  const int m = sorted_gradients(t, &g);
  if (m < 0) return -1;
  const int levels = count_levels(g, m);
  free(g);
  return levels;
}

int fit_check_table(const flow_table *t, const flow_law_kind *kinds, int nk, char *err,
                    int errlen) {
  int np = 0, nlaws = 0;
  char laws[128] = ""; /* the requested laws with the most parameters, e.g. "threshold and power" */
  for (int i = 0; i < nk; i++)
    np = flow_law_nparams(kinds[i]) > np ? flow_law_nparams(kinds[i]) : np;
  for (int i = 0; i < nk; i++)
    if (flow_law_nparams(kinds[i]) == np) nlaws++;
  for (int i = 0, k = 0, len = 0; i < nk; i++) {
    if (flow_law_nparams(kinds[i]) != np) continue;
    k++;
    len += snprintf(laws + len, sizeof laws - len, "%s%s",
                    k == 1 ? "" : (k == nlaws ? " and " : ", "), flow_law_name(kinds[i]));
    if (len >= (int)sizeof laws) break;
  }
  const char *has = nlaws > 1 ? "laws have" : "law has";
  const char *only_darcy = np > 1 ? " (or fit darcy alone: --models darcy)" : "";
  if (t->n < np + 1)
    return fail(err, errlen,
                "%s: %d data row%s, but fitting %d-parameter laws needs at least %d (one more "
                "point than parameters, for chi2/dof)",
                t->path, t->n, t->n == 1 ? "" : "s", np, np + 1);

  double *g;
  const int m = sorted_gradients(t, &g);
  if (m < 0) return fail(err, errlen, "%s: out of memory", t->path);
  const int levels = count_levels(g, m);
  int rc = 0;
  if (levels == 0)
    rc =
        fail(err, errlen,
             "%s: every %s value is 0: no driving gradient; expected at least %d distinct "
             "non-zero gradient%s (the %s %s %d parameter%s)",
             t->path, t->driving_column, np, np == 1 ? "" : "s", laws, has, np, np == 1 ? "" : "s");
  else if (levels < np && g[0] == g[m - 1])
    rc = fail(err, errlen,
              "%s: one gradient: all %d rows with a non-zero %s have |G| = %.6g; the %s %s %d "
              "parameters, so expected at least %d distinct gradients%s",
              t->path, m, t->driving_column, g[0], laws, has, np, np, only_darcy);
  else if (levels < np)
    rc = fail(err, errlen,
              "%s: zero variance in the %s column: the non-zero gradients differ by at most %.1e "
              "relative (|G| from %.17g to %.17g), which is one gradient; the %s %s %d "
              "parameters, so expected at least %d gradients that differ by more than %.0e "
              "relative%s",
              t->path, t->driving_column, (g[m - 1] - g[0]) / g[m - 1], g[0], g[m - 1], laws, has,
              np, np, FIT_SAME_VALUE_RTOL, only_darcy);
  free(g);
  if (rc) return rc;

  double qmax = 0, spread = 0;
  for (int i = 0; i < t->n; i++) {
    qmax = fmax(qmax, fabs(t->q[i]));
    spread = fmax(spread, fabs(t->q[i] - t->q[0]));
  }
  if (qmax == 0)
    return fail(err, errlen,
                "%s: every darcy_velocity value is 0: no flow, so no flow law can be fitted; "
                "expected fluxes that change with %s",
                t->path, t->driving_column);
  if (spread <= FIT_SAME_VALUE_RTOL * qmax)
    return fail(err, errlen,
                "%s: all %d darcy_velocity values are equal (q = %.6g%s): the flux does not "
                "change with the gradient, so no flow law can be fitted; expected fluxes that "
                "change with %s",
                t->path, t->n, t->q[0], spread > 0 ? ", within the rounding tolerance" : "",
                t->driving_column);
  return 0;
}
