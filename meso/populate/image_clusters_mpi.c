/* The pore clusters of a geometry image without any rank holding the image (image_walls.h,
 * docs/walls.md sections 2 and 6). Each rank labels the 6-connected pore components of its gen
 * voxels (its own voxels and at least one voxel around them, no edge across a periodic face: the
 * clusters are the image's own). A component that touches nothing outside the rank's own voxels
 * and no periodic face is a whole cluster and is classified where it is. The others ("open") go to
 * rank 0 with two small lists: (voxel, component) for every pore voxel that another rank's
 * labelling also sees (the rank's gen voxels outside its own, and its own voxels next to another
 * rank's), and (voxel, component) for its own pore voxels on periodic faces. Rank 0 joins the
 * components that share a voxel (union-find over the sorted list: the same cluster seen by two
 * ranks), then the clusters that face each other across a periodic face (the "joined" rule),
 * counts, and sends every rank the fill flag of its open components. The lists scale with the
 * ranks' surfaces, not with the image. */
#include "populate/image_walls.h"
#include "mdpore_image.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

enum { FACE_LO = 1, FACE_HI = 2, FACE_ANY = 4 };

static long uf_find(long *parent, long a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

static void uf_join(long *parent, long a, long b) {
  a = uf_find(parent, a), b = uf_find(parent, b);
  if (a < b)
    parent[b] = a;
  else if (b < a)
    parent[a] = b;
}

static int by_voxel(const void *p, const void *q) {
  const int64_t *a = p, *b = q;
  return (a[0] > b[0]) - (a[0] < b[0]);
}

/* category counts: clusters, spanning, joined, isolated, dead-end, then their voxels, largest */
enum { C_CLUSTERS, C_SPAN, C_JOINED, C_ISO, C_DEAD, C_SPAN_V, C_JOINED_V, C_ISO_V, C_DEAD_V, C_N };

static void count_cluster(long long *c, int faces, int joined, long long size) {
  c[C_CLUSTERS]++;
  const int k = (faces & 3) == 3 ? 0 : joined ? 1 : !(faces & FACE_ANY) ? 2 : 3;
  c[C_SPAN + k]++;
  c[C_SPAN_V + k] += size;
}

/* Rank 0: join the gathered open components (size, faces) by the shared-voxel records and the
 * periodic-face records; counts into c, largest cluster into *largest, fill flag per component. */
static int merge(const image_walls_t *g, long nc, const int64_t *comp, int64_t *rec, long nrec,
                 int64_t *prec, long nprec, long long *c, long long *largest, uint8_t *fill) {
  long *p1 = malloc(((size_t)nc + 1) * sizeof *p1), *p2 = malloc(((size_t)nc + 1) * sizeof *p2);
  long long *size = calloc((size_t)nc + 1, sizeof *size);
  uint8_t *faces = calloc((size_t)nc + 1, 1), *span = calloc((size_t)nc + 1, 1);
  if (!p1 || !p2 || !size || !faces || !span) {
    free(p1), free(p2), free(size), free(faces), free(span);
    return -1;
  }
  for (long i = 0; i < nc; i++) p1[i] = i;
  qsort(rec, (size_t)nrec, 2 * sizeof *rec, by_voxel);
  for (long r = 1; r < nrec; r++)
    if (rec[2 * r] == rec[2 * r - 2]) uf_join(p1, rec[2 * r + 1], rec[2 * r - 1]);
  for (long i = 0; i < nc; i++) {
    const long r = uf_find(p1, i);
    size[r] += comp[2 * i], faces[r] |= (uint8_t)comp[2 * i + 1];
  }
  /* the periodic faces: the pore voxel at 0 and its partner at n - 1 of a periodic axis */
  memcpy(p2, p1, (size_t)nc * sizeof *p2);
  qsort(prec, (size_t)nprec, 2 * sizeof *prec, by_voxel);
  const int64_t stride[3] = {1, g->n[0], (int64_t)g->n[0] * g->n[1]};
  for (long r = 0; r < nprec; r++) {
    const int64_t v = prec[2 * r];
    for (int a = 0; a < 3; a++) {
      if (!g->periodic[a] || v / stride[a] % g->n[a] != 0) continue;
      const int64_t key[2] = {v + (int64_t)(g->n[a] - 1) * stride[a], 0};
      const int64_t *hit = bsearch(key, prec, (size_t)nprec, 2 * sizeof *prec, by_voxel);
      if (hit) uf_join(p2, prec[2 * r + 1], hit[1]);
    }
  }
  for (long i = 0; i < nc; i++)
    if (uf_find(p1, i) == i && (faces[i] & 3) == 3) span[uf_find(p2, i)] = 1;
  for (long i = 0; i < nc; i++) {
    if (uf_find(p1, i) == i && size[i] > 0) { /* (a set of no own voxel is part of another) */
      count_cluster(c, faces[i], span[uf_find(p2, i)], size[i]);
      if (size[i] > *largest) *largest = size[i];
    }
    fill[i] = span[uf_find(p2, i)];
  }
  free(p1), free(p2), free(size), free(faces), free(span);
  return 0;
}

/* A growing list of int64 pairs. */
typedef struct {
  int64_t *v;
  long n, cap;
} pairs_t;

static int push(pairs_t *p, int64_t a, int64_t b) {
  if (p->n == p->cap) {
    const long cap = p->cap ? 2 * p->cap : 1024;
    int64_t *v = realloc(p->v, 2 * (size_t)cap * sizeof *v);
    if (!v) return -1;
    p->v = v, p->cap = cap;
  }
  p->v[2 * p->n] = a, p->v[2 * p->n + 1] = b;
  p->n++;
  return 0;
}

/* Gather a list of int64 pairs on rank 0 (counts must fit an int). */
static int gather_pairs(const pairs_t *p, MPI_Comm comm, int rank, int size, int64_t **out,
                        long *nout, int **counts_out) {
  int mine = (int)(2 * p->n);
  int *counts = rank == 0 ? calloc((size_t)size, sizeof *counts) : NULL;
  int *displ = rank == 0 ? calloc((size_t)size, sizeof *displ) : NULL;
  MPI_Gather(&mine, 1, MPI_INT, counts, 1, MPI_INT, 0, comm);
  long total = 0;
  int bad = 0;
  if (rank == 0) {
    bad = !counts || !displ;
    for (int r = 0; !bad && r < size; r++) {
      displ[r] = (int)total;
      total += counts[r];
      bad |= total > INT_MAX;
    }
  }
  MPI_Bcast(&bad, 1, MPI_INT, 0, comm);
  int64_t *all = NULL;
  if (!bad && rank == 0) {
    all = malloc(((size_t)total + 2) * sizeof *all);
    bad = !all;
  }
  MPI_Bcast(&bad, 1, MPI_INT, 0, comm);
  if (bad) {
    free(counts), free(displ), free(all);
    return -1;
  }
  MPI_Gatherv(p->v, mine, MPI_INT64_T, all, counts, displ, MPI_INT64_T, 0, comm);
  *out = all;
  *nout = total / 2;
  free(displ);
  if (counts_out)
    *counts_out = counts;
  else
    free(counts);
  return 0;
}

int image_clusters_classify(const scene_t *s, image_walls_t *g, const uint8_t *phase, char *err,
                            size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  const int fa = geo->flow_axis, *gn = g->gen_n, *n = g->n;
  MPI_Comm comm = g->work;
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  long long G = (long long)gn[0] * gn[1] * gn[2];
  int off[3]; /* gen coordinate + off = window coordinate */
  for (int d = 0; d < 3; d++) off[d] = ((g->gen_lo[d] - g->win_lo[d]) % n[d] + n[d]) % n[d];
  int fail = G >= INT32_MAX;
  int32_t *lab = fail ? NULL : malloc((size_t)(G ? G : 1) * sizeof *lab);
  fail |= !lab;
  if (!fail) image_walls_mem(g, G * 4);
  long nloc = 0; /* components */
  long long *csize = NULL;
  uint8_t *cfaces = NULL, *copen = NULL;
  pairs_t rec = {0}, prec = {0};
  /* window index of gen coordinates: gen lies inside the window, but may wrap around its start
   * when the window is a whole periodic axis */
#define WIN(c0, c1, c2)                                                                            \
  ((long long)(((c0) + off[0]) % n[0]) +                                                           \
   (long long)g->win_n[0] *                                                                        \
       ((long long)(((c1) + off[1]) % n[1]) + (long long)g->win_n[1] * (((c2) + off[2]) % n[2])))
  if (!fail) {
    /* union-find over the gen voxels (lab: parent, -1 solid), edges only between voxels adjacent in
     * the image (not across a periodic face) */
    for (int k = 0; k < gn[2]; k++)
      for (int j = 0; j < gn[1]; j++)
        for (int i = 0; i < gn[0]; i++) {
          const int32_t x = (int32_t)(i + gn[0] * (j + gn[1] * k));
          lab[x] = phase[WIN(i, j, k)] == MDP_PHASE_PORE ? x : -1;
        }
    for (int k = 0; k < gn[2]; k++)
      for (int j = 0; j < gn[1]; j++)
        for (int i = 0; i < gn[0]; i++) {
          const int32_t x = (int32_t)(i + gn[0] * (j + gn[1] * k));
          if (lab[x] < 0) continue;
          const int ijk[3] = {i, j, k};
          const int32_t step[3] = {1, gn[0], gn[0] * gn[1]};
          for (int a = 0; a < 3; a++) {
            if (ijk[a] + 1 >= gn[a] || (g->gen_lo[a] + ijk[a]) % n[a] == n[a] - 1) continue;
            const int32_t y = x + step[a];
            if (lab[y] < 0) continue;
            int32_t rx = x, ry = y;
            while (lab[rx] != rx) rx = lab[rx] = lab[lab[rx]];
            while (lab[ry] != ry) ry = lab[ry] = lab[lab[ry]];
            if (rx < ry)
              lab[ry] = rx;
            else if (ry < rx)
              lab[rx] = ry;
          }
        }
    /* components: the roots numbered in voxel order (lab of a root becomes -2 - component) */
    for (long long x = 0; x < G; x++)
      if (lab[x] >= 0 && lab[x] == x) nloc++;
    csize = calloc((size_t)nloc + 1, sizeof *csize);
    cfaces = calloc((size_t)nloc + 1, 1);
    copen = calloc((size_t)nloc + 1, 1);
    fail = !csize || !cfaces || !copen;
    image_walls_mem(g, (long long)nloc * 10);
  }
  if (!fail) {
    long next = 0;
    for (long long x = 0; x < G; x++) {
      if (lab[x] < 0) continue;
      int32_t r = (int32_t)x;
      while (lab[r] >= 0 && lab[r] != r) r = lab[r];
      if (lab[r] == r) lab[r] = -2 - (int32_t)next++; /* a root, numbered */
      lab[x] = lab[r] <= -2 ? lab[r] : lab[x];
    }
    /* the rest of the pass: sizes and faces of own voxels, the records */
    for (int k = 0; k < gn[2] && !fail; k++)
      for (int j = 0; j < gn[1] && !fail; j++)
        for (int i = 0; i < gn[0] && !fail; i++) {
          const int32_t x = (int32_t)(i + gn[0] * (j + gn[1] * k));
          if (lab[x] == -1) continue;
          const long cc = -2 - (long)lab[x];
          const int lc[3] = {i, j, k};
          int q[3];
          image_walls_global(g, g->gen_lo, lc, q);
          const int64_t v = image_walls_voxel(g, q);
          if (!image_walls_in_range(g, g->own_lo, g->own_n, q)) {
            copen[cc] = 1;
            fail |= push(&rec, v, cc);
            continue;
          }
          csize[cc]++;
          for (int a = 0; a < 3; a++)
            if (q[a] == 0 || q[a] == n[a] - 1) cfaces[cc] |= FACE_ANY;
          if (q[fa] == 0) cfaces[cc] |= FACE_LO;
          if (q[fa] == n[fa] - 1) cfaces[cc] |= FACE_HI;
          /* another rank's gen reaches 2 voxels into this rank's own ones (gen = the voxels
           * overlapping a subdomain, one more each side), so those voxels are recorded: every
           * voxel that two ranks label is then in the list of both */
          int edge = 0;
          for (int a = 0; a < 3 && !edge; a++)
            for (int step = -2; step <= 2; step++) {
              int r[3] = {q[0], q[1], q[2]};
              r[a] = ((r[a] + step) % n[a] + n[a]) % n[a];
              if (!image_walls_in_range(g, g->own_lo, g->own_n, r)) edge = 1;
            }
          if (edge) copen[cc] = 1, fail |= push(&rec, v, cc);
          for (int a = 0; a < 3; a++)
            if (g->periodic[a] && (q[a] == 0 || q[a] == n[a] - 1)) {
              copen[cc] = 1;
              fail |= push(&prec, v, cc);
              break;
            }
        }
  }
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  /* the closed components are whole clusters; the open ones go to rank 0 */
  long long cnt[C_N + 1] = {0}, largest = 0;
  pairs_t comps = {0};
  long *open_index = NULL;
  if (!fail) {
    open_index = malloc(((size_t)nloc + 1) * sizeof *open_index);
    fail = !open_index;
  }
  long nopen = 0;
  for (long cc = 0; !fail && cc < nloc; cc++) {
    if (copen[cc]) {
      open_index[cc] = nopen++;
      fail |= push(&comps, csize[cc], cfaces[cc]);
    } else {
      count_cluster(cnt, cfaces[cc], 0, csize[cc]);
      if (csize[cc] > largest) largest = csize[cc];
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  long first = 0;
  if (!fail) {
    MPI_Exscan(&nopen, &first, 1, MPI_LONG, MPI_SUM, comm);
    if (rank == 0) first = 0;
    for (long r = 0; r < rec.n; r++) rec.v[2 * r + 1] = first + open_index[rec.v[2 * r + 1]];
    for (long r = 0; r < prec.n; r++) prec.v[2 * r + 1] = first + open_index[prec.v[2 * r + 1]];
  }
  int64_t *all_comp = NULL, *all_rec = NULL, *all_prec = NULL;
  long nall = 0, nrec = 0, nprec = 0;
  int *ccount = NULL;
  if (!fail) fail = gather_pairs(&comps, comm, rank, size, &all_comp, &nall, &ccount);
  if (!fail) fail = gather_pairs(&rec, comm, rank, size, &all_rec, &nrec, NULL);
  if (!fail) fail = gather_pairs(&prec, comm, rank, size, &all_prec, &nprec, NULL);
  uint8_t *all_fill = NULL, *fill = malloc((size_t)nopen + 1);
  if (!fail && rank == 0) {
    image_walls_mem(g, (long long)(nall + nrec + nprec) * 16);
    all_fill = malloc((size_t)nall + 1);
    fail = !all_fill ||
           merge(g, nall, all_comp, all_rec, nrec, all_prec, nprec, cnt, &largest, all_fill);
    image_walls_mem(g, -(long long)(nall + nrec + nprec) * 16);
  }
  MPI_Bcast(&fail, 1, MPI_INT, 0, comm);
  int *displ = rank == 0 && !fail ? malloc((size_t)size * sizeof *displ) : NULL;
  fail |= !fill || (rank == 0 && !displ);
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) free(displ);
  if (!fail) {
    if (rank == 0) {
      long at = 0;
      for (int r = 0; r < size; r++) ccount[r] /= 2, displ[r] = (int)at, at += ccount[r];
    }
    MPI_Scatterv(all_fill, ccount, displ, MPI_UINT8_T, fill, (int)nopen, MPI_UINT8_T, 0, comm);
    free(displ);
    /* the counts: closed components of every rank plus rank 0's merge */
    long long mine[C_N + 1];
    memcpy(mine, cnt, sizeof mine);
    mine[C_N] = largest;
    MPI_Allreduce(MPI_IN_PLACE, cnt, C_N, MPI_LONG_LONG, MPI_SUM, comm);
    MPI_Allreduce(&mine[C_N], &largest, 1, MPI_LONG_LONG, MPI_MAX, comm);
  }
  free(all_comp), free(all_rec), free(all_prec), free(all_fill), free(ccount);
  free(comps.v), free(rec.v), free(prec.v);
  if (fail) {
    free(lab), free(csize), free(cfaces), free(copen), free(open_index), free(fill);
    snprintf(err, errlen, "%s: geometry: out of memory for the pore clusters", s->file);
    return -1;
  }
  image_walls_counts_t *ct = &g->count;
  ct->clusters = (int)cnt[C_CLUSTERS];
  ct->spanning = (int)cnt[C_SPAN], ct->joined = (int)cnt[C_JOINED];
  ct->isolated = (int)cnt[C_ISO], ct->dead_end = (int)cnt[C_DEAD];
  ct->spanning_voxels = cnt[C_SPAN_V], ct->joined_voxels = cnt[C_JOINED_V];
  ct->isolated_voxels = cnt[C_ISO_V], ct->dead_end_voxels = cnt[C_DEAD_V];
  /* FLUID / EMPTY on the pore voxels of gen */
  const int fill_others = geo->isolated_pores == ISOLATED_FILL;
  long long fluid_own = 0;
  for (int k = 0; k < gn[2]; k++)
    for (int j = 0; j < gn[1]; j++)
      for (int i = 0; i < gn[0]; i++) {
        const int32_t x = (int32_t)(i + gn[0] * (j + gn[1] * k));
        if (lab[x] == -1) continue;
        const long cc = -2 - (long)lab[x];
        const int f = fill_others || (copen[cc] ? fill[open_index[cc]] : (cfaces[cc] & 3) == 3);
        g->cls[WIN(i, j, k)] = f ? IMAGE_VOXEL_FLUID : IMAGE_VOXEL_EMPTY;
        const int lc[3] = {i, j, k};
        int q[3];
        image_walls_global(g, g->gen_lo, lc, q);
        fluid_own += f && image_walls_in_range(g, g->own_lo, g->own_n, q);
      }
#undef WIN
  MPI_Allreduce(MPI_IN_PLACE, &fluid_own, 1, MPI_LONG_LONG, MPI_SUM, comm);
  ct->fluid_voxels = fluid_own;
  image_walls_mem(g, -G * 4 - (long long)nloc * 10);
  free(lab), free(csize), free(cfaces), free(copen), free(open_index), free(fill);
  if (ct->spanning == 0) {
    snprintf(err, errlen,
             "%s: key 'geometry.flow_axis': expected a box axis along which the pore space "
             "percolates (after axis_map): %s: axis %c does not percolate: no pore cluster "
             "connects the %c = 0 face to the %c = %d face (%d clusters, largest %lld voxels); "
             "choose another axis or a larger crop",
             s->file, geo->image, 'x' + fa, 'x' + fa, 'x' + fa, n[fa] - 1, ct->clusters, largest);
    return -1;
  }
  return 0;
}
