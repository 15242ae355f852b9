/* Small queries on a parsed scene: species lookup, paths relative to the scene file, physics hash. */
#include "scene/scene.h"
#include <math.h>

#include <libgen.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

int scene_relative_path(const char *scene_file, const char *p, char *out, size_t len) {
  if (p[0] == '/') return (size_t)snprintf(out, len, "%s", p) < len ? 0 : -1;
  char tmp[SCENE_PATH_LEN];
  snprintf(tmp, sizeof tmp, "%s", scene_file);
  const char *dir = dirname(tmp);
  if (!strcmp(dir, ".")) return (size_t)snprintf(out, len, "%s", p) < len ? 0 : -1;
  /* never the path alone when folder + path is too long: that would read another file */
  return (size_t)snprintf(out, len, "%s/%s", dir, p) < len ? 0 : -1;
}

int scene_species_index(const scene_t *s, const char *name) {
  for (int i = 0; i < s->n_species; i++)
    if (!strcmp(s->species[i].name, name)) return i;
  return -1;
}

/* FNV-1a over the bytes of the fields that shape the trajectory. */
static uint64_t fnv(uint64_t h, const void *p, size_t n) {
  const unsigned char *c = p;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
  return h;
}

uint64_t scene_physics_hash(const scene_t *s) {
  uint64_t h = 14695981039346656037ull;
  h = fnv(h, s->box_lo, sizeof s->box_lo);
  h = fnv(h, s->box_hi, sizeof s->box_hi);
  h = fnv(h, s->periodic, sizeof s->periodic);
  h = fnv(h, &s->n_species, sizeof s->n_species);
  for (int a = 0; a < s->n_species; a++) {
    h = fnv(h, s->species[a].name, strlen(s->species[a].name));
    h = fnv(h, &s->species[a].mass, sizeof(double));
    h = fnv(h, &s->species[a].frozen, sizeof(int));
    if (s->species[a].moving) h = fnv(h, s->species[a].velocity, sizeof s->species[a].velocity);
    for (int b = 0; b < s->n_species; b++) {
      /* s only when set, so scenes without it keep the hash (and checkpoints) they had */
      h = fnv(h, &s->pair[a][b], offsetof(scene_pair_t, s));
      if (s->pair[a][b].s != 0) h = fnv(h, &s->pair[a][b].s, sizeof(double));
    }
  }
  h = fnv(h, &s->density_kernel, sizeof s->density_kernel);
  h = fnv(h, &s->kT, sizeof s->kT);
  h = fnv(h, &s->vv_lambda, sizeof s->vv_lambda);
  h = fnv(h, s->effect, sizeof s->effect);
  for (int e = 0; e < SCENE_MAX_EFFECTS; e++) /* the options of the named effects, as parsed */
    if (s->effect[e]) h = fnv(h, &s->effect_options[e], sizeof s->effect_options[e]);
  if (s->geometry.on) h = fnv(h, &s->geometry, sizeof s->geometry);
  h = fnv(h, &s->dt, sizeof s->dt);
  h = fnv(h, &s->seed, sizeof s->seed);
  return h;
}

double scene_circle_overlap(double a0, double a1, double b0, double b1, double L) {
  double total = 0;
  for (int k = -1; k <= 1; k++) {
    const double lo = fmax(a0, b0 + k * L), hi = fmin(a1, b1 + k * L);
    if (hi > lo) total += hi - lo;
  }
  return total;
}
