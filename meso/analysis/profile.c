/* Time-averaged 1D profiles with block-averaged errors (see profile.h). */
#include "analysis/profile.h"
#include "common/atomic_file.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Fields per bin: [0, nsp) counts per species, nsp: mobile count, nsp+1..3: sum of v of mobile
 * particles, nsp+4..9: sum of m v_a v_b + W_ab. */
#define F_MOBILE(p) ((p)->nsp)
#define F_V(p) ((p)->nsp + 1)
#define F_P(p) ((p)->nsp + 4)
#define PROFILE_PI 3.14159265358979323846

/* Volume of bin b: a slab of the box, or with a radial profile (output.profile.radial) the shell
 * between its radii: a cylindrical shell times the box length along the axis, or a spherical one. */
static double bin_volume(const profile_t *p, int b) {
  const scene_profile_t *c = &p->scene->profile;
  if (!c->radial) return p->vbin;
  const double r0 = b * c->rmax / p->nbins, r1 = (b + 1) * c->rmax / p->nbins;
  if (c->radial == 1)
    return PROFILE_PI * (r1 * r1 - r0 * r0) *
           (p->scene->box_hi[c->axis] - p->scene->box_lo[c->axis]);
  return 4.0 / 3.0 * PROFILE_PI * (r1 * r1 * r1 - r0 * r0 * r0);
}

/* Radial profiles: the centre of this sample. The given point, or the periodic centre of mass of
 * centre_species: on each axis the angle mean of 2 pi x / L (Bai & Breen, J. Graph. Tools 13,
 * 53 (2008)), which does not depend on where the drop sits across the periodic boundary. */
static void radial_centre(const profile_t *p, const particles_t *pt, MPI_Comm comm, double c[3]) {
  const scene_t *s = p->scene;
  const scene_profile_t *pc = &s->profile;
  for (int d = 0; d < 3; d++) c[d] = pc->centre[d];
  if (pc->centre_species < 0) return;
  double sum[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < pt->n_local; i++) {
    if (pt->species[i] != pc->centre_species) continue;
    for (int d = 0; d < 3; d++) {
      const double th =
          2 * PROFILE_PI * (pt->x[d][i] - s->box_lo[d]) / (s->box_hi[d] - s->box_lo[d]);
      sum[2 * d] += cos(th);
      sum[2 * d + 1] += sin(th);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 6, MPI_DOUBLE, MPI_SUM, comm);
  for (int d = 0; d < 3; d++) {
    if (pc->radial == 1 && d == pc->axis) continue;
    if (sum[2 * d] == 0 && sum[2 * d + 1] == 0) continue; /* none of the species: the given point */
    const double th = atan2(-sum[2 * d + 1], -sum[2 * d]) + PROFILE_PI;
    c[d] = s->box_lo[d] + th / (2 * PROFILE_PI) * (s->box_hi[d] - s->box_lo[d]);
  }
}

/* Bin of particle i, or -1 outside a radial profile's rmax. */
static int bin_of(const profile_t *p, const particles_t *pt, int i, const double c[3]) {
  const scene_t *s = p->scene;
  const scene_profile_t *pc = &s->profile;
  if (!pc->radial) {
    double u = (pt->x[p->axis][i] - p->lo) / p->len;
    u -= floor(u); /* periodic image into [0, 1) */
    int b = (int)(u * p->nbins);
    return b >= p->nbins ? p->nbins - 1 : b;
  }
  double r2 = 0;
  for (int d = 0; d < 3; d++) {
    if (pc->radial == 1 && d == pc->axis) continue;
    const double l = s->box_hi[d] - s->box_lo[d];
    double dx = pt->x[d][i] - c[d];
    if (s->periodic[d]) dx -= l * floor(dx / l + 0.5); /* nearest image */
    r2 += dx * dx;
  }
  const int b = (int)(sqrt(r2) / pc->rmax * p->nbins);
  return b < p->nbins ? b : -1;
}

int profile_init(profile_t *p, const scene_t *s, long first, long last, MPI_Comm comm) {
  memset(p, 0, sizeof *p);
  const scene_profile_t *c = &s->profile;
  p->scene = s;
  p->axis = c->axis;
  p->nbins = c->nbins;
  p->nsp = s->n_species;
  p->nf = p->nsp + 10;
  p->lo = s->box_lo[c->axis];
  p->len = s->box_hi[c->axis] - s->box_lo[c->axis];
  double vol = 1;
  for (int d = 0; d < 3; d++) vol *= s->box_hi[d] - s->box_lo[d];
  p->vbin = vol / p->nbins;
  long from = first + 1 > c->start ? first + 1 : c->start;
  for (long t = ((from + c->every - 1) / c->every) * c->every; t <= last; t += c->every)
    p->expected++;
  p->nblocks =
      p->expected < PROFILE_BLOCKS ? (int)(p->expected > 0 ? p->expected : 1) : PROFILE_BLOCKS;
  p->block_len = p->expected / p->nblocks > 0 ? p->expected / p->nblocks : 1;
  int rank;
  MPI_Comm_rank(comm, &rank);
  p->local = calloc((size_t)p->nbins * p->nf, sizeof *p->local);
  if (rank == 0) {
    p->blocks = calloc((size_t)p->nblocks * p->nbins * p->nf, sizeof *p->blocks);
    p->block_samples = calloc((size_t)p->nblocks, sizeof *p->block_samples);
  }
  return p->local && (rank || (p->blocks && p->block_samples)) ? 0 : -1;
}

void profile_free(profile_t *p) {
  free(p->local);
  free(p->blocks);
  free(p->block_samples);
  memset(p, 0, sizeof *p);
}

int profile_wants(const profile_t *p, long step) {
  const scene_profile_t *c = &p->scene->profile;
  return c->nbins > 0 && step >= c->start && step % c->every == 0;
}

void profile_sample(profile_t *p, sim_t *sim) {
  particles_t *pt = sim_particles(sim);
  const scene_t *s = p->scene;
  const int nf = p->nf;
  memset(p->local, 0, (size_t)p->nbins * nf * sizeof *p->local);
  double centre[3] = {0, 0, 0};
  if (s->profile.radial) radial_centre(p, pt, sim_comm(sim), centre);
  for (int i = 0; i < pt->n_local; i++) {
    const int b = bin_of(p, pt, i, centre);
    if (b < 0) continue;
    double *row = p->local + (size_t)b * nf;
    const int sp = pt->species[i];
    const double m = s->species[sp].mass;
    const double v[3] = {pt->v[0][i], pt->v[1][i], pt->v[2][i]};
    row[sp] += 1;
    if (!s->species[sp].frozen) {
      row[F_MOBILE(p)] += 1;
      for (int d = 0; d < 3; d++) row[F_V(p) + d] += v[d];
    }
    const double kin[6] = {m * v[0] * v[0], m * v[1] * v[1], m * v[2] * v[2],
                           m * v[0] * v[1], m * v[0] * v[2], m * v[1] * v[2]};
    for (int k = 0; k < 6; k++)
      row[F_P(p) + k] += kin[k] + (pt->virial ? pt->virial[6 * i + k] : 0);
  }
  MPI_Comm comm = sim_comm(sim);
  int rank;
  MPI_Comm_rank(comm, &rank);
  const int n = p->nbins * nf;
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, p->local, n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(p->local, NULL, n, MPI_DOUBLE, MPI_SUM, 0, comm);
  if (rank == 0) {
    long b = p->samples / p->block_len;
    if (b >= p->nblocks) b = p->nblocks - 1;
    double *blk = p->blocks + (size_t)b * n;
    for (int k = 0; k < n; k++) blk[k] += p->local[k];
    p->block_samples[b]++;
  }
  p->samples++;
}

/* Value of one quantity of one bin from sums over `ns` samples: q = 0..nsp-1 density of a species,
 * nsp total density, nsp+1..3 velocity, nsp+4..9 pressure. */
static double quantity(const profile_t *p, const double *row, long ns, int q, double vbin) {
  if (ns <= 0) return NAN;
  if (q < p->nsp) return row[q] / (ns * vbin);
  if (q == p->nsp) {
    double c = 0;
    for (int k = 0; k < p->nsp; k++) c += row[k];
    return c / (ns * vbin);
  }
  if (q <= p->nsp + 3)
    return row[F_MOBILE(p)] > 0 ? row[F_V(p) + q - p->nsp - 1] / row[F_MOBILE(p)] : 0;
  return row[F_P(p) + q - p->nsp - 4] / (ns * vbin);
}

/* Mean over all samples and block error of quantity q in bin b. */
static void stat(const profile_t *p, int b, int q, double *mean, double *err) {
  const int n = p->nbins * p->nf;
  const double vbin = bin_volume(p, b);
  double *tot = calloc((size_t)p->nf, sizeof *tot);
  if (!tot) {
    *mean = *err = NAN;
    return;
  }
  long ns = 0, used = 0;
  double bm[PROFILE_BLOCKS];
  for (int k = 0; k < p->nblocks; k++) {
    const double *row = p->blocks + (size_t)k * n + (size_t)b * p->nf;
    for (int f = 0; f < p->nf; f++) tot[f] += row[f];
    ns += p->block_samples[k];
    if (p->block_samples[k] > 0) bm[used++] = quantity(p, row, p->block_samples[k], q, vbin);
  }
  *mean = quantity(p, tot, ns, q, vbin);
  double ss = 0;
  for (long k = 0; k < used; k++) ss += (bm[k] - *mean) * (bm[k] - *mean);
  *err = used > 1 ? sqrt(ss / (used - 1) / used) : NAN;
  free(tot);
}

int profile_write(const profile_t *p, const char *path) {
  const scene_t *s = p->scene;
  char tmp[SCENE_PATH_LEN + 32];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  static const char *const vp[] = {"vx", "vy", "vz", "Pxx", "Pyy", "Pzz", "Pxy", "Pxz", "Pyz"};
  fprintf(
      fp,
      "# mdpore profile: scene %s, axis %c, %d bins, %ld samples every %ld steps from step %ld, "
      "%d blocks for errors (<col>_err = block standard error)\n",
      s->name, 'x' + p->axis, p->nbins, p->samples, s->profile.every, s->profile.start, p->nblocks);
  fprintf(fp, "# density = all species; v = mean velocity of mobile particles; P = (kinetic + "
              "virial) / V_bin\n");
  if (s->profile.radial)
    fprintf(fp, "# radial profile: %s about %s (%g, %g, %g)%s%s, r < %g\n",
            s->profile.radial == 1 ? "cylinder shells" : "spherical shells",
            s->profile.radial == 1 ? "the line along the axis through" : "the point",
            s->profile.centre[0], s->profile.centre[1], s->profile.centre[2],
            s->profile.centre_species >= 0 ? ", moved each sample to the centre of mass of " : "",
            s->profile.centre_species >= 0 ? s->species[s->profile.centre_species].name : "",
            s->profile.rmax);
  if (s->profile.radial)
    fprintf(fp, "r,density,density_err");
  else
    fprintf(fp, "%c,density,density_err", 'x' + p->axis);
  for (int k = 0; k < p->nsp; k++)
    fprintf(fp, ",density_%s,density_%s_err", s->species[k].name, s->species[k].name);
  for (int k = 0; k < 9; k++) fprintf(fp, ",%s,%s_err", vp[k], vp[k]);
  fputc('\n', fp);
  for (int b = 0; b < p->nbins; b++) {
    double m, e;
    if (s->profile.radial)
      fprintf(fp, "%.8g", (b + 0.5) * s->profile.rmax / p->nbins);
    else
      fprintf(fp, "%.8g", p->lo + (b + 0.5) * p->len / p->nbins);
    stat(p, b, p->nsp, &m, &e);
    fprintf(fp, ",%.8g,%.4g", m, e);
    for (int k = 0; k < p->nsp; k++) {
      stat(p, b, k, &m, &e);
      fprintf(fp, ",%.8g,%.4g", m, e);
    }
    for (int k = 0; k < 9; k++) {
      stat(p, b, p->nsp + 1 + k, &m, &e);
      fprintf(fp, ",%.8g,%.4g", m, e);
    }
    fputc('\n', fp);
  }
  return atomic_commit(fp, tmp, path);
}

int profile_plateau_density(const profile_t *p, double *mean, double *err, int *interfaces) {
  *mean = *err = NAN;
  *interfaces = 0;
  if (p->samples < 1) return 0;
  /* Mobile density per bin (all blocks), its maximum, and the plateau bins. */
  const int n = p->nbins * p->nf;
  double *dens = calloc((size_t)p->nbins, sizeof *dens), mx = 0, mn = INFINITY;
  int *core = malloc((size_t)p->nbins * sizeof *core), nc = 0;
  if (!dens || !core) { /* no plateau (NaN): the summary says the density is not known */
    free(dens), free(core);
    fprintf(stderr, "mdpore: warning: out of memory for the plateau of a profile of %d bins\n",
            p->nbins);
    return 0;
  }
  for (int b = 0; b < p->nbins; b++) {
    double c = 0;
    for (int k = 0; k < p->nblocks; k++)
      c += p->blocks[(size_t)k * n + (size_t)b * p->nf + F_MOBILE(p)];
    dens[b] = c / (p->samples * bin_volume(p, b));
    if (dens[b] > mx) mx = dens[b];
    if (dens[b] < mn) mn = dens[b];
  }
  /* A liquid-vapour (or vacuum) interface along the axis: some bins hold less than half the
   * liquid density. Without one the profile is uniform and a "surface tension" means nothing. */
  *interfaces = mn < 0.5 * mx;
  /* A liquid-liquid interface: the total stays near uniform, but some mobile species' density
   * falls below half its maximum (two immiscible liquids, docs/twophase.md). */
  for (int sp = 0; sp < p->nsp && !*interfaces; sp++) {
    if (p->scene->species[sp].frozen) continue;
    double smx = 0, smn = INFINITY;
    for (int b = 0; b < p->nbins; b++) {
      double c = 0;
      for (int k = 0; k < p->nblocks; k++) c += p->blocks[(size_t)k * n + (size_t)b * p->nf + sp];
      const double d = c / (p->samples * bin_volume(p, b));
      if (d > smx) smx = d;
      if (d < smn) smn = d;
    }
    *interfaces = smx > 0 && smn < 0.5 * smx;
  }
  for (int b = 0; b < p->nbins; b++)
    if (dens[b] > 0.9 * mx) core[nc++] = b;
  /* Bins next to the interfaces sit on its shoulder: drop 20% at each end of the plateau. */
  int first = 0, last = nc;
  if (nc > 4) {
    const int k = (int)(0.2 * nc) > 1 ? (int)(0.2 * nc) : 1;
    first = k;
    last = nc - k;
  }
  double bm[PROFILE_BLOCKS], tot = 0;
  int used = 0;
  for (int k = 0; k < p->nblocks; k++) {
    if (!p->block_samples[k]) continue;
    double c = 0;
    for (int j = first; j < last; j++)
      c += p->blocks[(size_t)k * n + (size_t)core[j] * p->nf + F_MOBILE(p)];
    if (p->scene->profile.radial) {
      double v = 0;
      for (int j = first; j < last; j++) v += bin_volume(p, core[j]);
      bm[used++] = c / (p->block_samples[k] * v);
    } else
      bm[used++] = c / (p->block_samples[k] * p->vbin * (last - first));
  }
  for (int j = first; j < last; j++) tot += dens[core[j]];
  *mean = tot / (last - first);
  double ss = 0;
  for (int k = 0; k < used; k++) ss += (bm[k] - *mean) * (bm[k] - *mean);
  *err = used > 1 ? sqrt(ss / (used - 1) / used) : NAN;
  free(dens);
  free(core);
  return last - first;
}
