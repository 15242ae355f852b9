/* Morphological drainage and imbibition of a segmented image (mdpore_image.h, docs/relperm.md
 * section 2): the quasi-static displacement of a wetting liquid by a non-wetting one, in which the
 * non-wetting phase at capillary pressure Pc = 2 gamma cos(theta) / R occupies the union of the
 * balls of radius R that fit in the pore space and (drainage) reach it from the inlet (Hilpert &
 * Miller, Adv. Water Resour. 24 (2001) 243). Per radius: the ball centres are the pore voxels whose
 * centre lies at least R from every solid voxel centre (the exact distance transform, image_edt.c;
 * 4 d^2 >= 4 R^2, integers); drainage keeps the 6-connected clusters of centres that touch the
 * inlet face; the covered voxels, whose centre lies less than R from a kept centre, come from a
 * second distance transform from the centres. Imbibition (R ascending) keeps the non-wetting phase
 * in the opening of the pore space by R. Trapping: the defending phase's clusters that no longer
 * touch the outlet face (the high face of the axis) keep their voxels for every later radius. */
#include "image_internal.h"
#include "mdpore_image.h"

#include "common/size_check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Per voxel state. */
enum { V_SOLID = 0, V_WET = 1, V_NW = 2, V_TRAPPED = 3 /* the defending phase, stuck */ };

typedef struct {
  const mdp_image_t *img;
  const mdp_morph_opts_t *o;
  size_t n;
  int dim[3];
  uint32_t *d4;     /* 4 x squared distance from each voxel centre to the nearest solid centre */
  uint32_t *d4c;    /* ... to the nearest kept ball centre (the dilation) */
  mdp_image_t mask; /* label 1 at the kept ball centres, 0 elsewhere; also the labelling's input */
  int32_t *cluster; /* 6-connected cluster of each selected voxel, -1 elsewhere */
  uint8_t *touch;   /* per cluster: bit 0 the inlet face, bit 1 the outlet face */
  uint8_t *state;   /* V_* per voxel */
  uint32_t *radii4; /* the distinct 4 R^2 of the pore voxels, in the order of the steps */
  int n_radii;
  long long pore;
} morph_t;

static int32_t find(int32_t *parent, int32_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

static void unite(int32_t *parent, int32_t a, int32_t b) {
  a = find(parent, a);
  b = find(parent, b);
  if (a < b)
    parent[b] = a;
  else if (b < a)
    parent[a] = b;
}

/* Clusters of the voxels with mask.label == 1 (6-connected; across the faces of the periodic axes
 * other than the flow axis), numbered 0..*nc-1 in cluster[], and which faces of the flow axis each
 * touches (touch[]). */
static void label_selected(morph_t *m, int *nc) {
  const uint8_t *sel = m->mask.label;
  const int *dim = m->dim;
  const size_t stride[3] = {1, (size_t)dim[0], (size_t)dim[0] * (size_t)dim[1]};
  int32_t *c = m->cluster;
  for (size_t v = 0; v < m->n; v++) c[v] = sel[v] ? (int32_t)v : -1;
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int i = 0; i < dim[0]; i++) {
        const size_t v = (size_t)i + stride[1] * (size_t)j + stride[2] * (size_t)k;
        if (c[v] < 0) continue;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; a++) {
          size_t u;
          if (ijk[a] > 0)
            u = v - stride[a];
          else if (m->o->periodic[a] && a != m->o->axis && dim[a] > 1)
            u = v + (size_t)(dim[a] - 1) * stride[a];
          else
            continue;
          if (c[u] >= 0) unite(c, (int32_t)v, (int32_t)u);
        }
      }
  int count = 0;
  for (size_t v = 0; v < m->n; v++)
    if (c[v] >= 0) c[v] = find(c, (int32_t)v);
  for (size_t v = 0; v < m->n; v++) {
    const int32_t r = c[v];
    if (r < 0) continue;
    c[v] = (size_t)r == v ? -2 - count++ : c[r]; /* roots come first: union by index */
  }
  for (size_t v = 0; v < m->n; v++)
    if (c[v] <= -2) c[v] = -2 - c[v];
  *nc = count;
  const int a = m->o->axis;
  memset(m->touch, 0, (size_t)count + 1);
  if (a < 0) return;
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int i = 0; i < dim[0]; i++) {
        const int ijk[3] = {i, j, k};
        if (ijk[a] != 0 && ijk[a] != dim[a] - 1) continue;
        const size_t v = (size_t)i + stride[1] * (size_t)j + stride[2] * (size_t)k;
        if (c[v] < 0) continue;
        if (ijk[a] == 0) m->touch[c[v]] |= 1u;
        if (ijk[a] == dim[a] - 1) m->touch[c[v]] |= 2u;
      }
}

/* Voxels of phase `from` in clusters that do not touch the outlet become V_TRAPPED. */
static void trap(morph_t *m, uint8_t from) {
  if (m->o->axis < 0 || !m->o->trapping) return;
  for (size_t v = 0; v < m->n; v++) m->mask.label[v] = m->state[v] == from;
  int nc = 0;
  label_selected(m, &nc);
  for (size_t v = 0; v < m->n; v++)
    if (m->cluster[v] >= 0 && !(m->touch[m->cluster[v]] & 2u)) m->state[v] = V_TRAPPED;
}

/* The balls of 4 R^2 = r4 centred on the voxels with mask.label == 1: d4c < r4 at the voxels they
 * cover (the distance transform with the centres as "solid"). */
static int dilate(morph_t *m, char *err) {
  return mdp_image_pore_distance(&m->mask, MDP_EDT_CENTRES, m->o->periodic, m->d4c, err);
}

/* One step of 4 R^2 = r4. */
static int step(morph_t *m, uint32_t r4, char *err) {
  const int drainage = m->o->mode == MDP_MORPH_DRAINAGE;
  uint8_t *sel = m->mask.label;
  /* the ball centres: pore voxels at least R from every solid centre, outside trapped regions */
  long long centres = 0;
  for (size_t v = 0; v < m->n; v++) {
    sel[v] = m->state[v] != V_SOLID && m->d4[v] >= r4 && (!drainage || m->state[v] != V_TRAPPED);
    centres += sel[v];
  }
  if (drainage && m->o->axis >= 0 && centres > 0) { /* keep the clusters that reach the inlet */
    int nc = 0;
    label_selected(m, &nc);
    centres = 0;
    for (size_t v = 0; v < m->n; v++) {
      sel[v] = m->cluster[v] >= 0 && (m->touch[m->cluster[v]] & 1u);
      centres += sel[v];
    }
  }
  if (centres > 0 && dilate(m, err)) return 1;
  if (drainage) {
    for (size_t v = 0; v < m->n; v++)
      if (centres > 0 && m->state[v] == V_WET && m->d4c[v] < r4) m->state[v] = V_NW;
    trap(m, V_WET); /* wetting cut off from the outlet stays */
  } else {
    for (size_t v = 0; v < m->n; v++)
      if (m->state[v] == V_NW && !(centres > 0 && m->d4c[v] < r4)) m->state[v] = V_WET;
    trap(m, V_NW); /* non-wetting cut off from the outlet stays */
  }
  return 0;
}

/* The step's counts, and whether the non-wetting phase spans the axis (a labelling). */
static void count_step(morph_t *m, uint32_t r4, mdp_morph_step_t *s) {
  const int drainage = m->o->mode == MDP_MORPH_DRAINAGE;
  long long nw = 0, trapped = 0;
  for (size_t v = 0; v < m->n; v++) {
    m->mask.label[v] = m->state[v] == V_NW || (!drainage && m->state[v] == V_TRAPPED);
    nw += m->mask.label[v];
    trapped += m->state[v] == V_TRAPPED;
  }
  s->nw_spans = 0;
  if (m->o->axis >= 0 && nw > 0) {
    int nc = 0;
    label_selected(m, &nc);
    for (int c = 0; c < nc; c++)
      if (m->touch[c] == 3u) s->nw_spans = 1;
  }
  s->radius = 0.5 * sqrt((double)r4);
  s->nw_voxels = nw;
  s->pore_voxels = m->pore;
  s->trapped_voxels = trapped;
  s->snw = m->pore > 0 ? (double)nw / (double)m->pore : 0.0;
}

static int compare_u32(const void *a, const void *b) {
  const uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

static void morph_free(morph_t *m) {
  free(m->d4), free(m->d4c), free(m->cluster), free(m->touch), free(m->state), free(m->radii4);
  mdp_image_free(&m->mask);
  memset(m, 0, sizeof *m);
}

/* Checks, arrays, the distance transform and the radii. */
static int morph_init(morph_t *m, const mdp_image_t *img, const mdp_morph_opts_t *o, char *err) {
  memset(m, 0, sizeof *m);
  m->img = img, m->o = o;
  m->dim[0] = img->nx, m->dim[1] = img->ny, m->dim[2] = img->nz;
  if (o->mode != MDP_MORPH_DRAINAGE && o->mode != MDP_MORPH_IMBIBITION) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: mode %d: expected drainage (0) or imbibition (1)",
             o->mode);
    return 1;
  }
  if (o->axis < -1 || o->axis > 2) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: axis %d: expected 0, 1, 2 (x, y, z) or -1 (none)",
             o->axis);
    return 1;
  }
  const double voxels = (double)img->nx * (double)img->ny * (double)img->nz;
  char msg[512];
  /* d4, d4c, cluster, the radii (4 bytes each), mask, state, touch (1 byte each) */
  if (mdp_size_check(voxels, (double)INT32_MAX, 19.0, "voxels of the morphology", msg,
                     sizeof msg)) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: %d x %d x %d voxels: %s", img->nx, img->ny,
             img->nz, msg);
    return 1;
  }
  m->n = mdp_image_count(img);
  m->d4 = malloc(m->n * sizeof *m->d4);
  m->d4c = malloc(m->n * sizeof *m->d4c);
  m->cluster = malloc(m->n * sizeof *m->cluster);
  m->touch = malloc(m->n + 1);
  m->state = malloc(m->n);
  if (!m->d4 || !m->d4c || !m->cluster || !m->touch || !m->state) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: out of memory for %zu voxels", m->n);
    return 1;
  }
  if (mdp_image_alloc(&m->mask, img->nx, img->ny, img->nz, err) ||
      mdp_image_parse_labels("pore=0,inorganic=1", m->mask.phase_of, err) ||
      mdp_image_pore_distance(img, MDP_EDT_CENTRES, o->periodic, m->d4, err))
    return 1;
  for (size_t v = 0; v < m->n; v++) {
    const int pore = mdp_image_is_pore(img, v);
    m->state[v] = pore ? (o->mode == MDP_MORPH_DRAINAGE ? V_WET : V_NW) : V_SOLID;
    m->pore += pore;
    if (pore && m->d4[v] == MDP_EDT_NO_SOLID) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "morphology: the image has no solid voxel%s: no ball size is bounded",
               o->periodic[0] || o->periodic[1] || o->periodic[2] ? "" : " (faces open)");
      return 1;
    }
  }
  if (m->pore == 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: the image has no pore voxel");
    return 1;
  }
  /* the distinct 4 R^2 of the pore voxels (sorted copy, then unique) */
  uint32_t *r = malloc((size_t)m->pore * sizeof *r);
  if (!r) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: out of memory for %lld radii", m->pore);
    return 1;
  }
  long long k = 0;
  for (size_t v = 0; v < m->n; v++)
    if (m->state[v] != V_SOLID) r[k++] = m->d4[v];
  qsort(r, (size_t)k, sizeof *r, compare_u32);
  int u = 0;
  for (long long i = 0; i < k; i++)
    if (u == 0 || r[i] != r[u - 1]) r[u++] = r[i];
  if (o->mode == MDP_MORPH_DRAINAGE) /* descending */
    for (int i = 0; i < u / 2; i++) {
      const uint32_t t = r[i];
      r[i] = r[u - 1 - i], r[u - 1 - i] = t;
    }
  m->radii4 = r;
  m->n_radii = u;
  /* imbibition starts from the pore space full of non-wetting liquid; that cut off from the
   * outlet is trapped from the start */
  if (o->mode == MDP_MORPH_IMBIBITION) trap(m, V_NW);
  return 0;
}

/* The steps 0..stop (all with stop < 0) into steps[] (up to max_steps of them). */
static int morph_run(morph_t *m, int stop, mdp_morph_step_t *steps, int max_steps, char *err) {
  const int last = stop < 0 || stop >= m->n_radii ? m->n_radii - 1 : stop;
  for (int i = 0; i <= last; i++) {
    if (step(m, m->radii4[i], err)) return 1;
    if (steps && i < max_steps) count_step(m, m->radii4[i], &steps[i]);
  }
  return 0;
}

int mdp_image_morph_curve(const mdp_image_t *img, const mdp_morph_opts_t *o,
                          mdp_morph_step_t *steps, int max_steps, int *n_steps, char *err) {
  morph_t m;
  int rc = morph_init(&m, img, o, err);
  if (!rc) {
    *n_steps = m.n_radii;
    if (steps) {
      if (max_steps < m.n_radii) {
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "morphology: the curve has %d steps, room was given for %d (call with steps = "
                 "NULL for the count)",
                 m.n_radii, max_steps);
        rc = 1;
      } else {
        rc = morph_run(&m, -1, steps, max_steps, err);
      }
    }
  }
  morph_free(&m);
  return rc;
}

int mdp_image_morph_at(const mdp_image_t *img, const mdp_morph_opts_t *o, double target_snw,
                       uint8_t nw_label, mdp_image_t *out, mdp_morph_step_t *achieved, char *err) {
  memset(out, 0, sizeof *out);
  if (!(target_snw >= 0 && target_snw <= 1)) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "morphology: target non-wetting saturation %g: expected a number in [0, 1]",
             target_snw);
    return 1;
  }
  if (img->phase_of[nw_label] != MDP_PHASE_UNSET) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "morphology: label %d for the non-wetting phase: expected a label the image does not "
             "use (it is %s in the label map)",
             nw_label, mdp_phase_name(img->phase_of[nw_label]));
    return 1;
  }
  for (size_t v = 0; v < mdp_image_count(img); v++)
    if (img->label[v] == nw_label) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "morphology: label %d for the non-wetting phase: expected a label the image does "
               "not use (voxel %zu carries it)",
               nw_label, v);
      return 1;
    }
  int n_steps = 0;
  if (mdp_image_morph_curve(img, o, NULL, 0, &n_steps, err)) return 1;
  mdp_morph_step_t *steps = malloc((size_t)n_steps * sizeof *steps);
  if (!steps) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "morphology: out of memory for %d steps", n_steps);
    return 1;
  }
  morph_t m;
  int rc = morph_init(&m, img, o, err) || morph_run(&m, -1, steps, n_steps, err);
  int best = 0; /* the step nearest the target (the first of equals) */
  for (int i = 1; !rc && i < n_steps; i++)
    if (fabs(steps[i].snw - target_snw) < fabs(steps[best].snw - target_snw)) best = i;
  morph_free(&m);
  if (!rc) rc = morph_init(&m, img, o, err) || morph_run(&m, best, NULL, 0, err);
  if (!rc) rc = mdp_image_alloc(out, img->nx, img->ny, img->nz, err);
  if (!rc) {
    mdp_image_copy_meta(out, img);
    out->phase_of[nw_label] = MDP_PHASE_PORE;
    const int drainage = o->mode == MDP_MORPH_DRAINAGE;
    for (size_t v = 0; v < m.n; v++) {
      const int nw = m.state[v] == V_NW || (!drainage && m.state[v] == V_TRAPPED);
      out->label[v] = nw ? nw_label : img->label[v];
    }
    if (achieved) *achieved = steps[best];
  }
  if (rc) mdp_image_free(out);
  morph_free(&m);
  free(steps);
  return rc;
}
