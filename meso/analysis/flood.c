/* The flood's census and what follows from it (flood.h). */
#include "analysis/flood.h"
#include "physics/periodic_slab.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the fluid number density from the fill: mobile particles over the fill regions' volume */
static double fill_density(const scene_t *s, double mobile) {
  double v = 0;
  for (int k = 0; k < s->init.n_fill; k++) {
    const scene_fill_t *r = &s->init.fill[k];
    if (s->species[r->species].frozen) continue;
    double w = 1;
    for (int d = 0; d < 3; d++) w *= r->hi[d] - r->lo[d];
    v += w;
  }
  return v > 0 ? mobile / v : NAN;
}

int flood_init(flood_t *f, const scene_t *s, sim_t *sim) {
  memset(f, 0, sizeof *f);
  const scene_flood_t *o = &s->flood;
  if (!o->on) return 0;
  f->on = 1;
  f->axis = o->axis;
  f->nbins = o->nbins;
  f->inv = o->invading;
  f->def = o->defending;
  f->lo = o->sample_lo;
  f->hi = o->sample_hi;
  f->length = f->hi - f->lo;
  f->bin_w = f->length / f->nbins;
  f->area = 1;
  for (int d = 0; d < 3; d++)
    if (d != f->axis) f->area *= s->box_hi[d] - s->box_lo[d];
  f->volume = f->area * f->length;
  f->bin_inv = calloc((size_t)f->nbins, sizeof *f->bin_inv);
  f->bin_def = calloc((size_t)f->nbins, sizeof *f->bin_def);
  int bad = !f->bin_inv || !f->bin_def, rank;
  MPI_Comm_rank(sim_comm(sim), &rank);
  if (o->density > 0) {
    f->n_fluid = o->density;
    f->density_source = "flood.density";
  } else if (s->geometry.on) {
    f->n_fluid = s->geometry.fluid_density;
    f->density_source = "geometry.fluid_density";
  } else {
    double count[SCENE_MAX_SPECIES], vsum[SCENE_MAX_SPECIES], mobile = 0;
    if (sim_flux_sums(sim, f->axis, count, vsum)) bad = 1;
    for (int sp = 0; sp < s->n_species; sp++) mobile += count[sp];
    f->n_fluid = fill_density(s, mobile);
    f->density_source = "initial.fill (mobile particles / fill volume)";
  }
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, sim_comm(sim));
  if (bad) {
    if (rank == 0) fprintf(stderr, "mdpore: out of memory for the flood's bins\n");
    return -1;
  }
  if (!(f->n_fluid > 0)) {
    if (rank == 0)
      fprintf(stderr,
              "%s: key 'flood.density': expected the fluid number density n of the phase "
              "velocities (the scene has no geometry.fluid_density and no fill of a liquid)\n",
              s->file);
    return -1;
  }
  return 0;
}

void flood_free(flood_t *f) {
  free(f->bin_inv);
  free(f->bin_def);
  f->bin_inv = f->bin_def = NULL;
}

int flood_census(flood_t *f, sim_t *sim) {
  const scene_t *s = sim_scene(sim);
  const particles_t *p = sim_particles(sim);
  const int nb = f->nbins, a = f->axis;
  const size_t nval = 2 * (size_t)nb + 6;
  double *v = calloc(nval, sizeof *v);
  int bad = v == NULL;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, sim_comm(sim));
  if (bad) {
    free(v);
    fprintf(stderr, "mdpore: out of memory for the flood's census\n");
    return -1;
  }
  double *bin_inv = v, *bin_def = v + nb, *tail = v + 2 * nb;
  const double box_lo = s->box_lo[a], box_len = s->box_hi[a] - box_lo;
  for (int i = 0; i < p->n_local; i++) {
    const int sp = p->species[i];
    if (sp != f->inv && sp != f->def) continue;
    const int k = sp == f->inv ? 0 : 1;
    tail[4 + k] += 1.0; /* whole box */
    const double c = periodic_image(p->x[a][i], box_lo, box_len);
    if (c < f->lo || c >= f->hi) continue;
    int b = (int)((c - f->lo) / f->bin_w);
    if (b >= nb) b = nb - 1;
    (k ? bin_def : bin_inv)[b] += 1.0;
    tail[k] += 1.0;
    tail[2 + k] += p->v[a][i];
  }
  MPI_Allreduce(MPI_IN_PLACE, v, (int)nval, MPI_DOUBLE, MPI_SUM, sim_comm(sim));
  memcpy(f->bin_inv, bin_inv, (size_t)nb * sizeof *bin_inv);
  memcpy(f->bin_def, bin_def, (size_t)nb * sizeof *bin_def);
  f->n_inv = tail[0];
  f->n_def = tail[1];
  f->v_inv = tail[2];
  f->v_def = tail[3];
  f->box_inv = tail[4];
  f->box_def = tail[5];
  free(v);
  return 0;
}

double flood_bin_saturation(const flood_t *f, int b) {
  const double n = f->bin_inv[b] + f->bin_def[b];
  return n > 0 ? f->bin_inv[b] / n : NAN;
}

void flood_update(flood_t *f, const scene_t *s, long step) {
  const scene_flood_t *o = &s->flood;
  f->step = step;
  f->time = step * s->dt;
  const double n_all = f->n_inv + f->n_def;
  f->s_inv = n_all > 0 ? f->n_inv / n_all : NAN;
  f->q_inv = f->v_inv / (f->n_fluid * f->volume);
  f->q_def = f->v_def / (f->n_fluid * f->volume);
  f->front = 0;
  for (int b = f->nbins - 1; b >= 0; b--)
    if (flood_bin_saturation(f, b) >= 0.5) {
      f->front = (b + 1) * f->bin_w;
      break;
    }
  if (step < o->start) {
    f->recovery = 0;
    f->pvi = 0;
    return;
  }
  const double u = n_all > 0 ? (f->v_inv + f->v_def) / n_all : 0; /* mean fluid velocity */
  if (!f->started) {
    f->started = 1;
    f->n_def_start = f->n_def;
    f->pvi = 0;
  } else {
    f->pvi += 0.5 * (u + f->u_prev) * (f->time - f->t_prev) / f->length; /* trapezoid */
    f->q_sum += f->q_inv + f->q_def;
    f->q_n += 1;
  }
  f->t_prev = f->time;
  f->u_prev = u;
  f->recovery = f->n_def_start > 0 ? 1.0 - f->n_def / f->n_def_start : NAN;
  const double s_last = flood_bin_saturation(f, f->nbins - 1);
  if (!f->broke_through && step > o->start && s_last >= o->breakthrough) {
    f->broke_through = 1;
    f->bt_step = step;
    f->bt_time = (step - o->start) * s->dt;
    f->bt_recovery = f->recovery;
    f->bt_pvi = f->pvi;
    f->bt_s_inv = f->s_inv;
  }
}
