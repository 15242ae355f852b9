/* The reader of a relperm campaign's manifests (see relperm.h, rp_read_manifest): campaign.txt
 * through the campaign library, relperm_runs.txt here. Every line is the writer's
 * (rp_write_manifest, relperm_plan.c): "key: value" lines, each key once, and one "rp: ROLE
 * SW_TARGET SNW_IMAGE SNW_CONNECTED SNW_DISCONNECTED RADIUS" line per run. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "relperm.h"

#define RP_LINE_MAX 1024

enum { K_AXIS, K_WETTING, K_RATIO, K_M, K_MODE, K_TRAPPING, K_G, K_NW_LABEL, K_BOUNDARY, N_KEYS };
static const char *const key_names[N_KEYS] = {
    "axis", "wetting", "viscosity_ratio", "M", "mode", "trapping", "g", "nw_label", "boundary"};

static int bad(const char *path, int ln, const char *key, const char *expected, const char *got) {
  fprintf(stderr, "mdpore relperm: %s:%d: key '%s': expected %s (got '%.80s')\n", path, ln, key,
          expected, got);
  return -1;
}

/* A whole-token number: finite, or NAN where `nan_ok` and the token is "nan" (the writer's NAN:
 * %.17g of a NAN). */
static int number(const char *tok, int nan_ok, double *v) {
  char *end;
  *v = strtod(tok, &end);
  if (end == tok || *end) return -1;
  if (isnan(*v)) return nan_ok && !strcmp(tok, "nan") ? 0 : -1;
  return isfinite(*v) ? 0 : -1;
}

static int integer(const char *tok, long lo, long hi, int *v) {
  char *end;
  const long x = strtol(tok, &end, 10);
  if (end == tok || *end || x < lo || x > hi) return -1;
  *v = (int)x;
  return 0;
}

/* Splits "a b c" (spaces) into at most max tokens; returns the count (max + 1 when more). */
static int tokens(char *s, char **tok, int max) {
  int n = 0;
  for (char *p = strtok(s, " \t"); p; p = strtok(NULL, " \t")) {
    if (n < max) tok[n] = p;
    if (++n > max) break;
  }
  return n;
}

static int run_line(const char *path, int ln, char *value, relperm *rp) {
  char *tok[7];
  const char *fmt = "ROLE SW_TARGET SNW_IMAGE SNW_CONNECTED SNW_DISCONNECTED RADIUS (6 fields)";
  char copy[RP_LINE_MAX];
  snprintf(copy, sizeof copy, "%s", value);
  if (tokens(value, tok, 6) != 6) return bad(path, ln, "rp", fmt, copy);
  if (rp->n_runs >= RP_RUNS) {
    char most[64];
    snprintf(most, sizeof most, "at most %d run lines", RP_RUNS);
    return bad(path, ln, "rp", most, copy);
  }
  rp_run *r = &rp->runs[rp->n_runs];
  memset(r, 0, sizeof *r);
  r->role = !strcmp(tok[0], "two")     ? RP_ROLE_TWO
            : !strcmp(tok[0], "water") ? RP_ROLE_WATER
            : !strcmp(tok[0], "oil")   ? RP_ROLE_OIL
                                       : -1;
  if (r->role < 0) return bad(path, ln, "rp", "the role two, water or oil", tok[0]);
  double *dst[5] = {&r->sw_target, &r->snw_image, &r->snw_connected, &r->snw_disconnected,
                    &r->radius};
  static const char *const what[5] = {
      "a target saturation in [0, 1] or nan", "a saturation in [0, 1] or nan",
      "a saturation in [0, 1] or nan", "a saturation in [0, 1] or nan", "a radius >= 0 or nan"};
  for (int k = 0; k < 5; k++) { /* nan: not applicable (a reference run, a given phase image) */
    double v;
    if (number(tok[k + 1], 1, &v) || (!isnan(v) && (v < 0 || (k < 4 && v > 1))))
      return bad(path, ln, "rp", what[k], tok[k + 1]);
    *dst[k] = v;
  }
  rp->n_runs++;
  return 0;
}

static int key_line(const char *path, int ln, int key, char *value, relperm *rp) {
  char *tok[3];
  char copy[RP_LINE_MAX];
  snprintf(copy, sizeof copy, "%s", value);
  const int n = tokens(value, tok, 2);
  const char *name = key_names[key];
  if (key == K_M) {
    if (n != 2 || number(tok[0], 0, &rp->liq.M) || number(tok[1], 0, &rp->liq.M_err) ||
        !(rp->liq.M > 0) || rp->liq.M_err < 0)
      return bad(path, ln, name, "the viscosity ratio M > 0 and its error >= 0", copy);
    return 0;
  }
  if (n != 1) return bad(path, ln, name, "one value", copy);
  const char *v = tok[0];
  switch (key) {
  case K_AXIS:
    if (strlen(v) != 1 || v[0] < 'x' || v[0] > 'z') return bad(path, ln, name, "x, y or z", v);
    rp->axis = v[0] - 'x';
    return 0;
  case K_WETTING:
    if (strcmp(v, "water") && strcmp(v, "oil")) return bad(path, ln, name, "water or oil", v);
    rp->wetting = strcmp(v, "oil") ? RP_WET_WATER : RP_WET_OIL;
    return 0;
  case K_RATIO:
    if (integer(v, 1, 5, &rp->ratio) || rp->ratio == 3 || rp->ratio == 4)
      return bad(path, ln, name, "1, 2 or 5", v);
    return 0;
  case K_MODE:
    rp->mode = rp_mode_parse(v);
    if (rp->mode < 0) return bad(path, ln, name, "drainage, imbibition or given", v);
    return 0;
  case K_TRAPPING:
    if (integer(v, 0, 1, &rp->trapping)) return bad(path, ln, name, "0 or 1", v);
    return 0;
  case K_G:
    if (number(v, 0, &rp->g) || !(rp->g > 0 && rp->g < 1))
      return bad(path, ln, name, "a body force 0 < g < 1", v);
    return 0;
  case K_NW_LABEL:
    if (integer(v, 1, 255, &rp->nw_label)) return bad(path, ln, name, "a label 1..255", v);
    return 0;
  default: /* K_BOUNDARY */
    if (camp_boundary_parse(v) <= CAMP_BOUNDARY_AUTO)
      return bad(path, ln, name, "periodic, mirror or reservoir", v);
    snprintf(rp->boundary, sizeof rp->boundary, "%s", v);
    return 0;
  }
}

static int read_runs(const char *path, FILE *f, relperm *rp) {
  char line[RP_LINE_MAX + 1];
  int ln = 0, seen[N_KEYS] = {0};
  rp->n_runs = 0;
  while (fgets(line, sizeof line, f)) {
    ln++;
    const size_t len = strlen(line);
    if (len == RP_LINE_MAX && line[len - 1] != '\n') {
      fprintf(stderr, "mdpore relperm: %s:%d: expected lines of at most %d characters\n", path, ln,
              RP_LINE_MAX - 1);
      return -1;
    }
    line[strcspn(line, "\r\n")] = 0;
    if (ln == 1) {
      if (strcmp(line, RP_MANIFEST_HEAD)) {
        fprintf(stderr, "mdpore relperm: %s:1: expected the line '%s'\n", path, RP_MANIFEST_HEAD);
        return -1;
      }
      continue;
    }
    if (!line[0] || line[0] == '#') continue;
    char *colon = strchr(line, ':');
    if (!colon) {
      fprintf(stderr, "mdpore relperm: %s:%d: expected 'key: value' (got '%.80s')\n", path, ln,
              line);
      return -1;
    }
    *colon = 0;
    char *value = colon + 1;
    while (isspace((unsigned char)*value)) value++;
    if (!strcmp(line, "rp")) {
      if (run_line(path, ln, value, rp)) return -1;
      continue;
    }
    int key = -1;
    for (int k = 0; k < N_KEYS; k++)
      if (!strcmp(line, key_names[k])) key = k;
    if (key < 0) {
      fprintf(stderr,
              "mdpore relperm: %s:%d: unexpected key '%.80s' (expected %s, %s, %s, %s, "
              "%s, %s, %s, %s, %s or rp)\n",
              path, ln, line, key_names[0], key_names[1], key_names[2], key_names[3], key_names[4],
              key_names[5], key_names[6], key_names[7], key_names[8]);
      return -1;
    }
    if (seen[key]) {
      fprintf(stderr, "mdpore relperm: %s:%d: key '%s': expected once (also on line %d)\n", path,
              ln, key_names[key], seen[key]);
      return -1;
    }
    seen[key] = ln;
    if (key_line(path, ln, key, value, rp)) return -1;
  }
  if (ln == 0) {
    fprintf(stderr, "mdpore relperm: %s: empty: expected the line '%s'\n", path, RP_MANIFEST_HEAD);
    return -1;
  }
  for (int k = 0; k < N_KEYS; k++)
    if (!seen[k]) {
      fprintf(stderr, "mdpore relperm: %s: key '%s': expected a line '%s: ...' (got none)\n", path,
              key_names[k], key_names[k]);
      return -1;
    }
  return 0;
}

int rp_read_manifest(const char *workdir, relperm *rp) {
  campaign *c = &rp->c;
  if (camp_read_manifest_runs(workdir, c, 0)) return -1; /* every saturation at one g */
  /* the folders under this work folder (it may have moved since the plan) */
  for (int i = 0; i < c->n_runs; i++) {
    const char *name = strrchr(c->runs[i].dir, '/');
    char dir[CAMP_PATH];
    snprintf(dir, sizeof dir, "%.3000s/runs/%.900s", workdir, name ? name + 1 : c->runs[i].dir);
    snprintf(c->runs[i].dir, sizeof c->runs[i].dir, "%s", dir);
  }
  char path[CAMP_PATH + 32];
  snprintf(path, sizeof path, "%s/%s", workdir, RP_MANIFEST);
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr,
            "mdpore relperm: %s: cannot read it: expected a folder made by mdpore relperm\n", path);
    return -1;
  }
  int rc = read_runs(path, f, rp);
  fclose(f);
  if (!rc && rp->n_runs != c->n_runs) {
    fprintf(stderr, "mdpore relperm: %s: %d runs, campaign.txt %d: expected the same runs\n", path,
            rp->n_runs, c->n_runs);
    rc = -1;
  }
  return rc;
}
