/* The local list of a geometry build and the ids the whole list would give it (image_walls.h,
 * docs/walls.md section 6). The whole list is walls in voxel order, then fluid in voxel order, so
 * the first id of a voxel is the number of wall (fluid) particles in the voxels before it. The
 * image lines (x rows) are cut by the ranks' own x ranges into segments; every rank adds the
 * particle counts of its own voxels to a table of (line, segment) counts, an MPI_Allreduce sums it,
 * and its prefix in voxel order gives the first id at every segment start. A rank then walks each
 * line of its gen voxels from its own cut (or from the line's ends across a periodic x face),
 * adding the counts of the voxels it passes, which it knows: they are all in its window. The table
 * holds 16 bytes per line and segment (2 MB for a 256^3 image cut twice along x). */
#include "populate/image_walls.h"

#include <stdlib.h>
#include <string.h>

static int by_int(const void *p, const void *q) {
  const int a = *(const int *)p, b = *(const int *)q;
  return (a > b) - (a < b);
}

/* Wall and kept fluid particles of the gen voxel at local coordinates c (global q). */
static void voxel_counts(const image_walls_t *g, const uint16_t *kept, const int c[3],
                         const int q[3], long cnt[2]) {
  const int64_t v = image_walls_voxel(g, q);
  cnt[0] = image_walls_voxel_count(g, v);
  const long long w = image_walls_win(g, q);
  cnt[1] = (g->cls[w] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_FLUID
               ? kept[c[0] + (long long)g->gen_n[0] * (c[1] + (long long)g->gen_n[1] * c[2])]
               : 0;
}

/* Append a voxel to a local list (start[] holds one more entry than the voxels). */
static int append(int64_t **vox, int64_t **id, long **start, long *n, long *cap, int64_t v,
                  int64_t first, long count) {
  if (*n + 1 >= *cap) {
    const long c = *cap ? 2 * *cap : 1024;
    int64_t *a = realloc(*vox, (size_t)c * sizeof *a);
    if (a) *vox = a;
    int64_t *b = realloc(*id, (size_t)c * sizeof *b);
    if (b) *id = b;
    long *s = realloc(*start, ((size_t)c + 1) * sizeof *s);
    if (s) *start = s;
    if (!a || !b || !s) return -1;
    *cap = c;
  }
  if (*n == 0) (*start)[0] = 0;
  (*vox)[*n] = v, (*id)[*n] = first;
  (*start)[*n + 1] = (*start)[*n] + count;
  (*n)++;
  return 0;
}

int image_ids_assign(image_walls_t *g, const uint16_t *kept, char *err, size_t errlen) {
  const scene_t *s = g->scene;
  MPI_Comm comm = g->work;
  int size;
  MPI_Comm_size(comm, &size);
  const int *n = g->n, nx = n[0];
  /* the x cuts: every rank's own x range ends */
  int mine[2] = {g->own_lo[0], g->own_lo[0] + g->own_n[0]};
  int *cut = malloc((2 * (size_t)size + 2) * sizeof *cut);
  int fail = !cut;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    snprintf(err, errlen, "%s: geometry: out of memory for the id table", s->file);
    return -1;
  }
  MPI_Allgather(mine, 2, MPI_INT, cut, 2, MPI_INT, comm);
  int ncut = 2 * size;
  cut[ncut++] = 0, cut[ncut++] = nx;
  qsort(cut, (size_t)ncut, sizeof *cut, by_int);
  int u = 0;
  for (int i = 0; i < ncut; i++)
    if (u == 0 || cut[i] != cut[u - 1]) cut[u++] = cut[i];
  const int nseg = u - 1; /* segments [cut[s], cut[s + 1]), none empty */
  long long nlines = (long long)n[1] * n[2], cells;
  if (__builtin_mul_overflow(nlines, 2LL * nseg, &cells) || (size_t)cells > SIZE_MAX / 8) {
    free(cut);
    snprintf(err, errlen, "%s: geometry: the id table (%lld lines x %d segments) overflows",
             s->file, nlines, nseg);
    return -1;
  }
  int64_t *tab = calloc((size_t)cells + 2, sizeof *tab);
  int *seg_of = malloc(((size_t)nx + 1) * sizeof *seg_of);
  fail = !tab || !seg_of;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    free(cut), free(tab), free(seg_of);
    snprintf(err, errlen, "%s: geometry: out of memory for the id table (%lld entries)", s->file,
             cells);
    return -1;
  }
  image_walls_mem(g, cells * 8 + (long long)nx * 4);
  for (int sg = 0; sg < nseg; sg++)
    for (int x = cut[sg]; x < cut[sg + 1]; x++) seg_of[x] = sg;
  seg_of[nx] = nseg;
  /* this rank's own voxels into the table, and its own wall particles per species */
  const int *gn = g->gen_n;
  long own_wall[2] = {0, 0};
  for (int c2 = 0; c2 < gn[2]; c2++)
    for (int c1 = 0; c1 < gn[1]; c1++)
      for (int c0 = 0; c0 < gn[0]; c0++) {
        const int c[3] = {c0, c1, c2};
        int q[3];
        image_walls_global(g, g->gen_lo, c, q);
        if (!image_walls_in_range(g, g->own_lo, g->own_n, q)) continue;
        long cnt[2];
        voxel_counts(g, kept, c, q, cnt);
        const long long cell = 2 * ((long long)(q[1] + n[1] * q[2]) * nseg + seg_of[q[0]]);
        tab[cell] += cnt[0], tab[cell + 1] += cnt[1];
        if (cnt[0])
          own_wall[(g->cls[image_walls_win(g, q)] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_INORGANIC] +=
              cnt[0];
      }
  /* the sum in pieces of at most 2^30 entries (MPI counts are ints) */
  for (long long at = 0; at < cells; at += 1LL << 30) {
    const long long len = cells - at < (1LL << 30) ? cells - at : (1LL << 30);
    MPI_Allreduce(MPI_IN_PLACE, tab + at, (int)len, MPI_INT64_T, MPI_SUM, comm);
  }
  MPI_Allreduce(MPI_IN_PLACE, own_wall, 2, MPI_LONG, MPI_SUM, comm);
  g->count.wall_particles[0] = own_wall[0], g->count.wall_particles[1] = own_wall[1];
  /* exclusive prefix in voxel order: lines, then segments */
  int64_t run[2] = {0, 0};
  for (long long cell = 0; cell < cells; cell += 2)
    for (int t = 0; t < 2; t++) {
      const int64_t c = tab[cell + t];
      tab[cell + t] = run[t];
      run[t] += c;
    }
  g->n_wall = (long)run[0];
  const long fluid_check = g->n_fluid;
  g->n_fluid = (long)run[1];
  /* the first id at cut position a of line L, and the line's end (a = nx) */
#define AT(L, a, t)                                                                                \
  ((a) < nx           ? tab[2 * ((long long)(L)*nseg + seg_of[a]) + (t)]                           \
   : (L) + 1 < nlines ? tab[2 * ((long long)((L) + 1) * nseg) + (t)]                               \
                      : run[t])
  /* walk every gen line from the rank's own x cut (forward and back, across the periodic x face
   * from the line's ends) */
  const int a = g->own_lo[0]; /* nx when the rank owns no x column at the end */
  const int full = gn[0] == nx;
  const long u0 = full ? 0 : (long)a - (((long)a - g->gen_lo[0]) % nx + nx) % nx;
  long *cw = malloc((size_t)gn[0] * 2 * sizeof *cw);
  int64_t *first = malloc((size_t)gn[0] * 2 * sizeof *first);
  long wcap = 0, fcap = 0;
  fail = !cw || !first;
  g->n_wall_vox = g->n_fluid_vox = 0;
  for (int c2 = 0; c2 < gn[2] && !fail; c2++)
    for (int c1 = 0; c1 < gn[1] && !fail; c1++) {
      int q[3] = {0, 0, 0};
      const int c0[3] = {0, c1, c2};
      image_walls_global(g, g->gen_lo, c0, q);
      const long long L = q[1] + (long long)n[1] * q[2];
      for (int c = 0; c < gn[0]; c++) { /* counts along the line, unwrapped x = u0 + c */
        const int cc[3] = {c, c1, c2};
        q[0] = (int)((((u0 + c) % nx) + nx) % nx);
        long cnt[2];
        voxel_counts(g, kept, cc, q, cnt);
        cw[2 * c] = cnt[0], cw[2 * c + 1] = cnt[1];
      }
      for (int t = 0; t < 2; t++) {
        const long ref = full ? 0 : (long)a - u0; /* line position of the reference cut */
        int64_t acc = full ? AT(L, 0, t) : AT(L, a, t);
        for (long c = ref; c < gn[0]; c++) {
          if (!full && u0 + c == nx) acc = AT(L, 0, t); /* across the periodic x face */
          first[2 * c + t] = acc;
          acc += cw[2 * c + t];
        }
        acc = full ? 0 : AT(L, a, t);
        for (long c = ref - 1; c >= 0; c--) {
          if (u0 + c == -1) acc = AT(L, nx, t); /* back across the periodic x face */
          acc -= cw[2 * c + t];
          first[2 * c + t] = acc;
        }
      }
      for (int c = 0; c < gn[0] && !fail; c++) {
        q[0] = (int)((((u0 + c) % nx) + nx) % nx);
        const int64_t v = image_walls_voxel(g, q);
        if (cw[2 * c])
          fail |= append(&g->wall_vox, &g->wall_id, &g->wall_start, &g->n_wall_vox, &wcap, v,
                         first[2 * c], cw[2 * c]);
        if (cw[2 * c + 1])
          fail |= append(&g->fluid_vox, &g->fluid_id, &g->fluid_start, &g->n_fluid_vox, &fcap, v,
                         first[2 * c + 1], cw[2 * c + 1]);
      }
    }
#undef AT
  free(cw), free(first), free(cut), free(tab), free(seg_of);
  image_walls_mem(g, -(cells * 8 + (long long)nx * 4));
  image_walls_mem(g, (wcap + fcap) * 24);
  if (!fail && g->n_wall_vox == 0)
    fail = append(&g->wall_vox, &g->wall_id, &g->wall_start, &g->n_wall_vox, &wcap, 0, 0, 0) ||
           (g->n_wall_vox = 0, 0);
  if (!fail && g->n_fluid_vox == 0)
    fail = append(&g->fluid_vox, &g->fluid_id, &g->fluid_start, &g->n_fluid_vox, &fcap, 0, 0, 0) ||
           (g->n_fluid_vox = 0, 0);
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    snprintf(err, errlen, "%s: geometry: out of memory for the local particle list", s->file);
    return -1;
  }
  if (g->n_fluid != fluid_check) {
    snprintf(err, errlen,
             "%s: geometry: internal error: the id table counts %ld fluid particles, the fluid "
             "count %ld",
             s->file, g->n_fluid, fluid_check);
    return -1;
  }
  return 0;
}
