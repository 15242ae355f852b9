/* The measured pressure drop of a pressure-driven run (see pressure_drop.h). */
#include "analysis/pressure_drop.h"
#include "common/atomic_file.h"
#include "effects/effect_list.h"
#include "effects/inlet_force.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Sums per sample: [0, nbins) P_aa * V per bin, then the probe sums and the inlet force. */
#define S_IN(pd) ((pd)->nbins)
#define S_OUT(pd) ((pd)->nbins + 1)
#define S_FORCE(pd) ((pd)->nbins + 2)
#define S_COUNT(pd) ((pd)->nbins + 3)

/* Position along the axis folded into [0, L) from the box's low face. */
static double fold(const pressure_drop_t *pd, double u) {
  double w = u - pd->box_lo;
  w -= pd->box_len * floor(w / pd->box_len);
  return w >= pd->box_len ? 0 : w;
}

static int in_slab(const pressure_drop_t *pd, double w, double lo) {
  double d = w - fold(pd, lo); /* distance past the slab's low face, folded */
  d -= pd->box_len * floor(d / pd->box_len);
  return d < pd->width;
}

int pressure_drop_init(pressure_drop_t *pd, const scene_t *s, long first_sample, int rank) {
  memset(pd, 0, sizeof *pd);
  if (!s->effect[EFFECT_INLET_FORCE]) return 0;
  const inlet_force_options_t *o =
      SCENE_EFFECT_OPTIONS(s, EFFECT_INLET_FORCE, const inlet_force_options_t);
  if (!o->has_sample) return 0;
  pd->on = 1;
  pd->axis = o->force.axis;
  pd->box_lo = s->box_lo[pd->axis];
  pd->box_len = s->box_hi[pd->axis] - pd->box_lo;
  double volume = 1;
  for (int d = 0; d < 3; d++) volume *= s->box_hi[d] - s->box_lo[d];
  pd->area = volume / pd->box_len;
  pd->sample_lo = o->sample_lo;
  pd->sample_hi = o->sample_hi;
  pd->length = o->sample_hi - o->sample_lo;
  pd->width = o->probe_width;
  pd->inlet = o->force;
  pd->inlet.box_lo = pd->box_lo;
  pd->inlet.box_len = pd->box_len;
  pd->in_lo = o->sample_lo - o->probe_gap - o->probe_width;
  pd->out_lo = o->sample_hi + o->probe_gap;
  pd->v_probe = pd->area * pd->width;
  pd->nbins = (int)(pd->box_len / PRESSURE_PROFILE_BIN + 0.5);
  if (pd->nbins < 1) pd->nbins = 1;
  pd->v_bin = volume / pd->nbins;
  pd->first_sample = first_sample;
  const char *slash = strrchr(s->flux.path, '/');
  const int dir_len = slash ? (int)(slash - s->flux.path) + 1 : 0;
  snprintf(pd->profile_path, sizeof pd->profile_path, "%.*spressure_profile.csv", dir_len,
           s->flux.path);
  pd->local = calloc((size_t)pd->nbins + 4, sizeof *pd->local);
  (void)rank;
  return pd->local ? 0 : -1;
}

void pressure_drop_free(pressure_drop_t *pd) {
  series_free(&pd->p_in);
  series_free(&pd->p_out);
  series_free(&pd->dp);
  series_free(&pd->force);
  free(pd->rows);
  free(pd->local);
  memset(pd, 0, sizeof *pd);
}

double pressure_drop_sample(pressure_drop_t *pd, sim_t *sim, int rank) {
  particles_t *pt = sim_particles(sim);
  const scene_t *s = sim_scene(sim);
  const int a = pd->axis, n = pd->nbins + 4;
  if (!pt->virial) {
    /* The initial state's sample (no force pass with the virial yet): left out, and the series
     * starts one flux sample later. Every rank sees the same. */
    if (pd->dp.n == 0 && pd->n_rows == 0) pd->first_sample++;
    return NAN;
  }
  memset(pd->local, 0, (size_t)n * sizeof *pd->local);
  for (int i = 0; i < pt->n_local; i++) {
    const int sp = pt->species[i];
    const double u = pt->x[a][i], v = pt->v[a][i];
    /* P_aa * V contribution: kinetic m v_a^2 plus the particle's share of the pair virial */
    const double paa = s->species[sp].mass * v * v + pt->virial[6 * (size_t)i + a];
    const double w = fold(pd, u);
    int b = (int)(w / pd->box_len * pd->nbins);
    if (b >= pd->nbins) b = pd->nbins - 1;
    pd->local[b] += paa;
    if (in_slab(pd, w, pd->in_lo)) pd->local[S_IN(pd)] += paa;
    if (in_slab(pd, w, pd->out_lo)) pd->local[S_OUT(pd)] += paa;
    if (inlet_force_in_slab(&pd->inlet, u)) {
      pd->local[S_FORCE(pd)] += pd->inlet.g[sp][a];
      pd->local[S_COUNT(pd)] += 1;
    }
  }
  MPI_Comm comm = sim_comm(sim);
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, pd->local, n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(pd->local, NULL, n, MPI_DOUBLE, MPI_SUM, 0, comm);
  if (rank != 0) return NAN;
  const double p_in = pd->local[S_IN(pd)] / pd->v_probe;
  const double p_out = pd->local[S_OUT(pd)] / pd->v_probe;
  series_push(&pd->p_in, p_in);
  series_push(&pd->p_out, p_out);
  series_push(&pd->dp, p_in - p_out);
  series_push(&pd->force, pd->local[S_FORCE(pd)]);
  if (pd->n_rows + 1 > pd->cap_rows) {
    const long cap = pd->cap_rows ? 2 * pd->cap_rows : 256;
    double *r = realloc(pd->rows, (size_t)cap * pd->nbins * sizeof *r);
    if (!r) return (p_in - p_out) / pd->length; /* the profile stops growing; dp goes on */
    pd->rows = r;
    pd->cap_rows = cap;
  }
  for (int b = 0; b < pd->nbins; b++)
    pd->rows[(size_t)pd->n_rows * pd->nbins + b] = pd->local[b] / pd->v_bin;
  pd->n_rows++;
  return (p_in - p_out) / pd->length;
}

/* Index into this object's series of flux series index `flux_start`. */
static long local_start(const pressure_drop_t *pd, long flux_start, long n) {
  long k = flux_start - pd->first_sample;
  if (k < 0) k = 0;
  if (k > n) k = n;
  return k;
}

void pressure_drop_analyse(const pressure_drop_t *pd, long flux_start, pressure_drop_result_t *r) {
  memset(r, 0, sizeof *r);
  const long n = pd->dp.n, k = local_start(pd, flux_start, n);
  r->samples_used = n - k;
  r->p_in = block_average_plateau(pd->p_in.x + k, n - k);
  r->p_out = block_average_plateau(pd->p_out.x + k, n - k);
  r->dp = block_average_plateau(pd->dp.x + k, n - k);
  r->force = block_average_plateau(pd->force.x + k, n - k);
  r->G = r->dp.mean / pd->length;
  r->G_err = r->dp.err / pd->length;
  r->force_per_area = r->force.mean / pd->area;
  r->force_per_area_err = r->force.err / pd->area;
  r->balance = r->dp.mean / r->force_per_area;
}

int pressure_drop_write_profile(const pressure_drop_t *pd, long flux_start, const char *path) {
  char tmp[SCENE_PATH_LEN + 32];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  const long n = pd->n_rows, k = local_start(pd, flux_start, n);
  const char ax = (char)('x' + pd->axis);
  fprintf(fp,
          "# mdpore pressure profile along %c: P_%c%c = sum_{i in bin} (m v_%c^2 + W_i,%c%c) / "
          "V_bin over all particles (walls included), %d bins, mean of %ld samples from the "
          "flux's steady state on; err = block standard error (Flyvbjerg-Petersen plateau)\n",
          ax, ax, ax, ax, ax, ax, pd->nbins, n - k);
  fprintf(fp, "# sample [%.8g, %.8g]; probe slabs [%.8g, %.8g) upstream, [%.8g, %.8g) downstream\n",
          pd->sample_lo, pd->sample_hi, pd->in_lo, pd->in_lo + pd->width, pd->out_lo,
          pd->out_lo + pd->width);
  fprintf(fp, "%c,P%c%c,P%c%c_err\n", ax, ax, ax, ax, ax);
  double *col = malloc((size_t)(n - k > 0 ? n - k : 1) * sizeof *col);
  if (!col) {
    fclose(fp);
    return -1;
  }
  for (int b = 0; b < pd->nbins; b++) {
    for (long j = k; j < n; j++) col[j - k] = pd->rows[(size_t)j * pd->nbins + b];
    const block_average_t m = block_average_plateau(col, n - k);
    fprintf(fp, "%.8g,%.8g,%.4g\n", pd->box_lo + (b + 0.5) * pd->box_len / pd->nbins, m.mean,
            m.err);
  }
  free(col);
  return atomic_commit(fp, tmp, path);
}
