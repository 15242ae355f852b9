/* Corey and tabulated relative permeabilities, fractional flow (see twophase_relperm.h). */
#include "twophase_relperm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double clamp01(double x) {
  return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

/* Linear interpolation in the table, constant beyond its ends. */
static double table_value(const relperm *r, const double *col, double s) {
  if (s <= r->sw[0]) return col[0];
  if (s >= r->sw[r->rows - 1]) return col[r->rows - 1];
  int lo = 0, hi = r->rows - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (r->sw[mid] <= s)
      lo = mid;
    else
      hi = mid;
  }
  double w = (s - r->sw[lo]) / (r->sw[hi] - r->sw[lo]);
  return col[lo] + w * (col[hi] - col[lo]);
}

void relperm_eval(const relperm *r, double s, double *krw, double *kro) {
  if (r->kind == RELPERM_TABLE) {
    *krw = table_value(r, r->krw, s);
    *kro = table_value(r, r->kro, s);
    return;
  }
  double se = clamp01((s - r->swc) / (1.0 - r->swc - r->sor));
  *krw = r->krw_max * pow(se, r->nw);
  *kro = r->kro_max * pow(1.0 - se, r->no);
}

double relperm_total_mobility(const relperm *r, double s) {
  double krw, kro;
  relperm_eval(r, s, &krw, &kro);
  return krw / r->mu_w + kro / r->mu_o;
}

double relperm_fw(const relperm *r, double s) {
  double krw, kro;
  relperm_eval(r, s, &krw, &kro);
  double lw = krw / r->mu_w, lt = lw + kro / r->mu_o;
  return lt > 0.0 ? lw / lt : 0.0;
}

double relperm_max_dfw(const relperm *r, double s_lo, double s_hi) {
  enum { SAMPLES = 4000 };
  double best = 0.0, ds = (s_hi - s_lo) / SAMPLES;
  if (!(ds > 0)) return 0.0;
  double f0 = relperm_fw(r, s_lo);
  for (int i = 1; i <= SAMPLES; i++) {
    double f1 = relperm_fw(r, s_lo + i * ds);
    best = fmax(best, fabs(f1 - f0) / ds);
    f0 = f1;
  }
  return best;
}

void relperm_range(const relperm *r, double *s_min, double *s_max) {
  if (r->kind == RELPERM_TABLE) {
    *s_min = r->sw[0];
    *s_max = r->sw[r->rows - 1];
  } else {
    *s_min = r->swc;
    *s_max = 1.0 - r->sor;
  }
}

int relperm_check_corey(const relperm *r, char *why, int why_len) {
  const char *key = NULL, *expect = NULL;
  double got = 0;
  if (!(r->nw >= 1.0 && r->nw <= 10.0))
    key = "nw", expect = "an exponent in [1, 10]", got = r->nw;
  else if (!(r->no >= 1.0 && r->no <= 10.0))
    key = "no", expect = "an exponent in [1, 10]", got = r->no;
  else if (!(r->swc >= 0.0 && r->swc < 1.0))
    key = "swc", expect = "a saturation in [0, 1)", got = r->swc;
  else if (!(r->sor >= 0.0 && r->sor < 1.0 - r->swc))
    key = "sor", expect = "a saturation in [0, 1 - swc)", got = r->sor;
  else if (!(r->krw_max > 0.0 && r->krw_max <= 1.0))
    key = "krw_max", expect = "a relative permeability in (0, 1]", got = r->krw_max;
  else if (!(r->kro_max > 0.0 && r->kro_max <= 1.0))
    key = "kro_max", expect = "a relative permeability in (0, 1]", got = r->kro_max;
  if (!key) return 0;
  snprintf(why, why_len, "%s: expected %s (got %g)", key, expect, got);
  return -1;
}

/* Splits a line into up to 8 numbers; returns the count, or -1 with the bad token in bad. */
static int split_numbers(char *line, double *v, char *bad, int bad_len) {
  int n = 0;
  for (char *tok = strtok(line, " \t,;\r\n"); tok; tok = strtok(NULL, " \t,;\r\n")) {
    if (!strcmp(tok, "/")) break;
    char *end;
    double x = strtod(tok, &end);
    if (end == tok || *end) {
      snprintf(bad, bad_len, "'%s'", tok);
      return -1;
    }
    if (n < 8) v[n] = x;
    n++;
  }
  return n;
}

static int table_row_check(const relperm *r, int i, char *why, int why_len, const char *file,
                           int line) {
  static const char *const names[] = {"Sw", "krw", "kro"};
  const double v[3] = {r->sw[i], r->krw[i], r->kro[i]};
  for (int c = 0; c < 3; c++)
    if (!(v[c] >= 0.0 && v[c] <= 1.0)) {
      snprintf(why, why_len, "%s:%d: column %d '%s': expected a value in [0, 1] (got %g)", file,
               line, c + 1, names[c], v[c]);
      return -1;
    }
  if (!(r->krw[i] + r->kro[i] > 0.0)) {
    snprintf(why, why_len,
             "%s:%d: expected krw + kro > 0 (got krw = kro = 0 at Sw = %g: no phase could flow)",
             file, line, r->sw[i]);
    return -1;
  }
  if (i == 0) return 0;
  if (!(r->sw[i] > r->sw[i - 1])) {
    snprintf(why, why_len,
             "%s:%d: column 1 'Sw': expected values strictly increasing down the table (got %g "
             "after %g)",
             file, line, r->sw[i], r->sw[i - 1]);
    return -1;
  }
  if (r->krw[i] < r->krw[i - 1] || r->kro[i] > r->kro[i - 1]) {
    int w = r->krw[i] < r->krw[i - 1];
    snprintf(why, why_len, "%s:%d: column %d '%s': expected %s with Sw (got %g after %g)", file,
             line, w ? 2 : 3, w ? "krw" : "kro", w ? "non-decreasing" : "non-increasing",
             w ? r->krw[i] : r->kro[i], w ? r->krw[i - 1] : r->kro[i - 1]);
    return -1;
  }
  return 0;
}

int relperm_read_table(const char *path, relperm *r, int *had_pc, char *why, int why_len) {
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(why, why_len, "%s: cannot open the relative-permeability table", path);
    return -1;
  }
  char line[1024], bad[64];
  int lineno = 0, cap = 0, rc = 0;
  r->kind = RELPERM_TABLE;
  r->rows = 0;
  *had_pc = 0;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    char *s = line + strspn(line, " \t");
    if (*s == '#' || !strncmp(s, "--", 2) || *s == '\n' || *s == '\r' || !*s) continue;
    if (!strncmp(s, "SWOF", 4)) continue; /* an Eclipse keyword line */
    if (*s == '/') break;
    double v[8];
    int n = split_numbers(s, v, bad, sizeof bad);
    if (n < 0 || n < 3 || n > 4) {
      if (n < 0)
        snprintf(why, why_len, "%s:%d: expected numbers Sw krw kro [Pc] (got %s)", path, lineno,
                 bad);
      else
        snprintf(why, why_len, "%s:%d: expected 3 or 4 columns Sw krw kro [Pc] (got %d)", path,
                 lineno, n);
      rc = -1;
      break;
    }
    if (r->rows == cap) {
      const int grown = cap ? 2 * cap : 32;
      double *sw = realloc(r->sw, (size_t)grown * sizeof(double));
      if (sw) r->sw = sw;
      double *krw = realloc(r->krw, (size_t)grown * sizeof(double));
      if (krw) r->krw = krw;
      double *kro = realloc(r->kro, (size_t)grown * sizeof(double));
      if (kro) r->kro = kro;
      if (!sw || !krw || !kro) {
        snprintf(why, why_len, "%s:%d: out of memory for %d rows", path, lineno, grown);
        rc = -1;
        break;
      }
      cap = grown;
    }
    r->sw[r->rows] = v[0];
    r->krw[r->rows] = v[1];
    r->kro[r->rows] = v[2];
    if (n == 4 && v[3] != 0.0) *had_pc = 1;
    if (table_row_check(r, r->rows, why, why_len, path, lineno)) {
      rc = -1;
      break;
    }
    r->rows++;
  }
  fclose(f);
  if (!rc && r->rows < 2) {
    snprintf(why, why_len, "%s: expected at least 2 rows Sw krw kro [Pc] (got %d)", path, r->rows);
    rc = -1;
  }
  return rc;
}

void relperm_free(relperm *r) {
  free(r->sw);
  free(r->krw);
  free(r->kro);
  r->sw = r->krw = r->kro = NULL;
  r->rows = 0;
}
