/* mdpore_image: segmented 3D voxel images (FIB-SEM, micro-CT, synthetic).
 *
 * An image is nx x ny x nz uint8 labels, x fastest: voxel (i, j, k) is label[i + nx * (j + ny *
 * k)]. A label map (phase_of) says which label values are pore, organic or inorganic solid. Voxel
 * (i, j, k) occupies [i, i+1) x [j, j+1) x [k, k+1) voxel units; one voxel unit is voxel_size
 * `unit`.
 *
 * Every function that can fail returns 0 on success and non-zero on error, with a message naming
 * the file, key or voxel and what was expected written into err (MDP_IMAGE_ERR_LEN bytes). No
 * function prints or exits. The module does no physics. */
#ifndef MDPORE_IMAGE_H
#define MDPORE_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#define MDP_IMAGE_ERR_LEN 1024
/* The most voxels an image may hold: 2^62, so that voxel indices and counts in int64_t and size_t
 * never overflow (the memory limit is usually far lower). */
#define MDP_IMAGE_MAX_VOXELS 4611686018427387904.0

typedef enum {
  MDP_PHASE_PORE = 0,
  MDP_PHASE_ORGANIC = 1,
  MDP_PHASE_INORGANIC = 2,
  MDP_PHASE_UNSET = 255 /* label value not in the map: an error wherever it occurs in an image */
} mdp_phase_t;

typedef struct {
  int nx, ny, nz;
  double voxel_size;     /* edge of one cubic voxel, in `unit` */
  char unit[8];          /* "m", "mm", "um", "nm" or "voxel" (no physical size known) */
  uint8_t *label;        /* nx*ny*nz label values, x fastest */
  uint8_t phase_of[256]; /* label value -> mdp_phase_t */
} mdp_image_t;

/* How to read a file. Zero-initialise (or call mdp_image_read_opts_init) and set what you know;
 * unset fields are taken from a sidecar header (raw), the file's attributes (HDF5) or defaults. */
typedef struct {
  int nx, ny, nz;         /* raw: dimensions (0 = unset) */
  char type[16];          /* raw: uint8 | int8 | uint16 | int16 | uint32 | int32 ("" = unset) */
  char byte_order[8];     /* raw: little | big */
  char axis_order[4];     /* raw: axes fastest first, e.g. "xyz" (x fastest) or "zyx" */
  long long header_bytes; /* raw: bytes to skip before the data (-1 = unset) */
  double voxel_size;      /* 0 = unset */
  char unit[8];
  char labels[256];  /* label map, e.g. "pore=0,organic=2,inorganic=1,3-5" ("" = unset) */
  char dataset[256]; /* HDF5 dataset path (default "/labels") */
  char format[8];    /* raw | hdf5 | tiff ("" = from the file name) */
} mdp_image_read_opts_t;

/* Default label map when none is given anywhere: pore=0, inorganic=1, organic=2. */
#define MDP_IMAGE_DEFAULT_LABELS "pore=0,inorganic=1,organic=2"

/* ---- basics (image.c) ---- */
static inline size_t mdp_image_index(const mdp_image_t *img, int i, int j, int k) {
  return (size_t)i + (size_t)img->nx * ((size_t)j + (size_t)img->ny * (size_t)k);
}
static inline size_t mdp_image_count(const mdp_image_t *img) {
  return (size_t)img->nx * (size_t)img->ny * (size_t)img->nz;
}
static inline int mdp_image_phase(const mdp_image_t *img, size_t idx) {
  return img->phase_of[img->label[idx]];
}
static inline int mdp_image_is_pore(const mdp_image_t *img, size_t idx) {
  return img->phase_of[img->label[idx]] == MDP_PHASE_PORE;
}
void mdp_image_read_opts_init(mdp_image_read_opts_t *o);
/* Allocate an nx*ny*nz image filled with label 0, map unset, voxel size 1 "voxel". */
int mdp_image_alloc(mdp_image_t *img, int nx, int ny, int nz, char *err);
/* The same for an image made from others that stay allocated meanwhile (a crop, a padded, mirrored,
 * stacked or permuted copy): `held` voxels (1 byte each) are counted with the new image against the
 * memory limit, before the allocation. */
int mdp_image_alloc_beside(mdp_image_t *img, int nx, int ny, int nz, double held, char *err);
void mdp_image_free(mdp_image_t *img);
int mdp_image_copy_meta(mdp_image_t *dst, const mdp_image_t *src); /* voxel size, unit, map */
/* Voxel edge in metres; returns 0 for unit "voxel". */
double mdp_image_voxel_size_m(const mdp_image_t *img);
/* Parse "10um", "1e-5 m", "3.5" (with default unit) into size and unit. */
int mdp_image_parse_voxel_size(const char *text, double *size, char unit[8], char *err);
const char *mdp_phase_name(int phase);

/* ---- label map (image_labels.c) ---- */
/* Parse "pore=0,organic=2,inorganic=1,3-5" into phase_of (values 0..255, ranges allowed). */
int mdp_image_parse_labels(const char *text, uint8_t phase_of[256], char *err);
/* Canonical text of a map: "pore=0;organic=2;inorganic=1,3" (inverse of mdp_image_parse_labels). */
void mdp_image_format_labels(const uint8_t phase_of[256], char *out, size_t len);
/* Error naming the first voxel whose label is not in the map (source = file name for the message).
 */
int mdp_image_check_labels(const mdp_image_t *img, const char *source, char *err);

/* ---- readers (image_read.c, image_raw.c, image_hdf5.c, image_tiff.c) ---- */
/* Read any supported format: raw (+ sidecar PATH.hdr), HDF5 (.h5/.hdf5), TIFF (.tif/.tiff or a
 * folder of slices). Checks sizes against the file and every label against the map. */
int mdp_image_read(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                   char *err);
int mdp_image_read_raw(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                       char *err);
/* Fill unset fields of opts from a sidecar "key: value" file (see docs/images.md). */
int mdp_image_read_sidecar(const char *path, mdp_image_read_opts_t *opts, char *err);
int mdp_image_read_hdf5(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err);
int mdp_image_read_tiff(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err);
int mdp_image_tiff_available(void); /* 1 when built with libtiff */

/* ---- partial reads (image_read_box.c; the format files read the box) ----
 * The voxels [lo, lo + size) of the file's image (file axes), with the file's label map, voxel size
 * and unit, into img (size[0] x size[1] x size[2]); dims receives the whole image's size. size ==
 * NULL: only dims (img is left empty). Labels are checked inside the box only; an error names the
 * voxel in the whole image's coordinates. HDF5 reads a hyperslab, raw seeks to each run along its
 * fastest axis, TIFF decodes only the pages of the box and its rows up to the last one needed. */
typedef struct {
  int lo[3], size[3];
} mdp_image_box_t;
int mdp_image_read_box(const char *path, const mdp_image_read_opts_t *opts, const int lo[3],
                       const int size[3], mdp_image_t *img, int dims[3], char *err);
/* The per-format readers behind it (box == NULL: the whole image, as mdp_image_read_FORMAT; a box
 * of size 0: dims only). */
int mdp_image_read_raw_box(const char *path, const mdp_image_read_opts_t *opts,
                           const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err);
int mdp_image_read_hdf5_box(const char *path, const mdp_image_read_opts_t *opts,
                            const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err);
int mdp_image_read_tiff_box(const char *path, const mdp_image_read_opts_t *opts,
                            const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err);

/* ---- writers (atomic: temporary file in the same folder, then rename) ---- */
/* HDF5: dataset "/labels" (uint8, dims [nz][ny][nx]) with attributes voxel_size, unit, label_map.
 */
int mdp_image_write_hdf5(const mdp_image_t *img, const char *path, char *err);
/* Raw uint8, x fastest, plus the sidecar PATH.hdr that mdp_image_read_raw understands. */
int mdp_image_write_raw(const mdp_image_t *img, const char *path, char *err);
/* Multi-page 8-bit TIFF, one page per z slice (needs libtiff). */
int mdp_image_write_tiff(const mdp_image_t *img, const char *path, char *err);

/* ---- transformations (image_ops.c); out must not alias in, it is allocated here ---- */
int mdp_image_crop(const mdp_image_t *in, const int lo[3], const int size[3], mdp_image_t *out,
                   char *err);
/* Majority vote of labels over factor^3 blocks (ties: the smaller label value). Voxels beyond the
 * last whole block are dropped; the voxel size grows by factor. */
int mdp_image_downsample(const mdp_image_t *in, int factor, mdp_image_t *out, char *err);
/* b after a along axis (0..2): the other sizes, label maps and voxel sizes must agree. */
int mdp_image_concat(const mdp_image_t *a, const mdp_image_t *b, int axis, mdp_image_t *out,
                     char *err);
/* widths[6] = x-, x+, y-, y+, z-, z+ layers of `label` added around the image. */
int mdp_image_pad(const mdp_image_t *in, const int widths[6], uint8_t label, mdp_image_t *out,
                  char *err);

/* Mirror extension (image_mirror.c): along each axis with mirror[a] != 0 the image is followed by
 * its reflection (2n voxels), so that the periodic wrap joins each face to itself. */
int mdp_image_mirror(const mdp_image_t *in, const int mirror[3], mdp_image_t *out, char *err);

/* How well the last slice along an axis continues into the first (the periodic seam), measured by
 * the pore Jaccard index (pore on both / pore on either) of the two slices against its mean over
 * adjacent interior slices. A periodic image's seam is one more interior step (continuity ~1); the
 * end slices of a crop of a rock are unrelated (continuity ~ porosity / the interior overlap). */
#define MDP_SEAM_PERIODIC_CONTINUITY 0.8
typedef struct {
  double seam_overlap;     /* Jaccard of the last and first slices */
  double interior_overlap; /* mean Jaccard of adjacent slices inside the image */
  double continuity;       /* seam_overlap / interior_overlap */
  int periodic;            /* continuity >= MDP_SEAM_PERIODIC_CONTINUITY */
} mdp_image_seam_t;
int mdp_image_seam(const mdp_image_t *img, int axis, mdp_image_seam_t *seam);

/* Reorder the axes (image_axes.c): output axis d is input axis axis_map[d], so out(i0, i1, i2) =
 * in(j) with j[axis_map[d]] = i_d; a scene's geometry.axis_map turns image axes into box axes. */
int mdp_image_permute_axes(const mdp_image_t *in, const int axis_map[3], mdp_image_t *out,
                           char *err);

/* ---- statistics (image_stats.c) ---- */
typedef struct {
  long long n_voxels, n_pore, n_organic, n_inorganic;
  double porosity;               /* pore voxels / all voxels */
  int n_clusters;                /* 6-connected pore clusters */
  int spans[3];                  /* 1 when some cluster connects face 0 to face n-1 of that axis */
  long long connected_voxels[3]; /* pore voxels in clusters spanning that axis */
  double connected_porosity[3];  /* connected_voxels / all voxels */
  int n_isolated_clusters;       /* clusters touching no face of the box (enclosed pores) */
  long long isolated_voxels;
  int n_nonspanning_clusters; /* clusters spanning no axis (isolated + dead-end at a face) */
  long long nonspanning_voxels;
  long long largest_cluster;
} mdp_image_stats_t;

/* Phase counts and 6-connected pore clusters (union-find). */
int mdp_image_stats(const mdp_image_t *img, mdp_image_stats_t *st, char *err);
/* Optional per-voxel cluster id (-1 for solid), for callers that want to drop isolated pores. */
int mdp_image_label_clusters(const mdp_image_t *img, int32_t *cluster, int *n_clusters, char *err);
/* Error unless pore space is non-empty and spans the axis (0 x, 1 y, 2 z). */
int mdp_image_require_percolation(const mdp_image_t *img, const mdp_image_stats_t *st, int axis,
                                  const char *source, char *err);

/* ---- flow paths (image_spanning.c) ---- */
/* Turns solid every pore cluster (6-connected) that does not connect the inlet face to the outlet
 * face along `axis` (0 x, 1 y, 2 z): isolated pores and clusters open to one face only carry no
 * flow. Dead-end branches of a spanning cluster are part of it and stay pore. Dropped voxels take
 * the label of a solid voxel of the image (the last one in x-fastest order); *dropped = their
 * number. If no cluster spans the axis the whole pore space is dropped (check with
 * mdp_image_require_percolation first). Shared by `mdpore foam` and the mDPD wall builder. */
int mdp_image_drop_nonspanning(mdp_image_t *img, int axis, long long *dropped, char *err);

/* ---- how periodic an image is (image_periodicity.c) ----
 * Per axis: the pore of the two end slices (slice 0 and slice n-1 face each other across the seam
 * of a periodic box) and percolation along the axis without and with the periodic wrap along it.
 * Percolation with the wrap: a 6-connected pore path that winds once around the axis in the box
 * that is periodic along that axis (the other faces closed); found by a union-find over the
 * clusters without wrap, joined across the seam, with each cluster's winding offset kept. */
typedef struct {
  long long face_voxels;                /* voxels of one end slice (the face area) */
  long long pore_first, pore_last;      /* pore voxels of slice 0 and of slice n-1 */
  long long pore_both, pore_either;     /* pore on both end slices at the same place / on either */
  double overlap;                       /* pore_both / pore_either (1: the end slices match) */
  double overlap_face;                  /* pore_both / face_voxels */
  int percolates_open, percolates_wrap; /* face to face without the wrap / around with it */
  long long connected_open, connected_wrap; /* pore voxels that percolate without / with */
  int wrap_only_clusters;                   /* clusters percolating only through the wrap */
  long long wrap_only_voxels;               /* ... their pore voxels: connected porosity it adds */
  int seam_blocked_clusters;     /* face-to-face clusters that do not percolate with it */
  long long seam_blocked_voxels; /* ... their pore voxels: connected porosity it blocks */
} mdp_image_axis_periodicity_t;
int mdp_image_periodicity(const mdp_image_t *img, mdp_image_axis_periodicity_t per[3], char *err);

/* ---- distance transform (image_edt.c) ----
 * d4[p] = 4 x the squared Euclidean distance (voxel units) from lattice point p to the nearest
 * solid (not pore) voxel centre, an integer; MDP_EDT_NO_SOLID without any solid voxel. The point
 * of voxel (i, j, k) is its centre (MDP_EDT_CENTRES) or its corner (i, j, k) + 1/2
 * (MDP_EDT_CORNERS; those of the last layer lie on the high face). Along an axis with periodic[a]
 * the distance is measured across the faces, else nothing lies beyond them (open faces). Exact
 * (Felzenszwalb & Huttenlocher separable transform); d4 holds one uint32 per voxel. */
enum { MDP_EDT_CENTRES = 0, MDP_EDT_CORNERS = 1 };
#define MDP_EDT_NO_SOLID UINT32_MAX
int mdp_image_pore_distance(const mdp_image_t *img, int lattice, const int periodic[3],
                            uint32_t *d4, char *err);

/* ---- pore and throat sizes (image_pore_sizes.c) ----
 * Of the percolating pore space (clusters spanning some axis face to face): the inscribed diameter
 * at each pore voxel, D = 2 r - 1 voxels with r the distance from its centre to the nearest solid
 * voxel centre (the widest ball centred there that enters no solid voxel along an axis; the middle
 * of a slit of odd width w has D = w), its quantiles; and per axis the critical throat: the largest
 * diameter d (whole voxels) such that the centres of the digital balls of diameter d that hold no
 * solid voxel (voxel centres for odd d, voxel corners for even d, each ball d voxels across)
 * percolate face to face along the axis: the breakthrough of mercury intrusion. A slit of width w
 * voxels gives w, a channel with a narrower constriction the constriction. Bisection on d with
 * mdp_image_stats. */
typedef struct {
  int periodic[3];      /* distances measured across the faces of these axes */
  long long voxels;     /* pore voxels of the percolating pore space */
  double diameter_q[5]; /* 10, 25, 50, 75, 90 % quantiles of D (voxels), by pore volume */
  double diameter_mean, diameter_max;
  int throat[3];  /* critical throat per axis (voxels); 0: the axis does not percolate */
  int no_solid;   /* 1: no solid voxel, every size unbounded (throat = the box size) */
  int labellings; /* cluster labellings the bisection made */
} mdp_image_pore_sizes_t;
int mdp_image_pore_sizes(const mdp_image_t *img, const int periodic[3], mdp_image_pore_sizes_t *ps,
                         char *err);

/* ---- morphological drainage and imbibition (image_morph.c; docs/relperm.md section 2) ----
 * The quasi-static displacement of a wetting liquid by a non-wetting one (Hilpert & Miller 2001):
 * at sphere radius R (voxels) the non-wetting phase holds the voxels whose centre lies less than R
 * from a ball centre, the ball centres being the pore voxels whose centre lies at least R from
 * every solid voxel centre (exact distance transform). Drainage (R descending, from the pore space
 * full of wetting liquid) keeps only the centres that reach the inlet face (voxel 0 along axis)
 * through 6-connected centres or already invaded voxels; imbibition (R ascending, from the pore space full of non-wetting liquid)
 * keeps the non-wetting phase in the opening of the pore space by R. With trapping, the clusters
 * of the defending phase that do not touch the outlet face (voxel n-1 along axis) keep their
 * voxels for every later R (wetting in drainage, non-wetting in imbibition); without an axis
 * (-1) there is no connectivity rule and no trapping. The radii are the distinct distances of
 * the pore voxels to the solid, one step each. Clusters connect across the faces of the periodic
 * axes other than the flow axis. Memory: 19 bytes per voxel. */
enum { MDP_MORPH_DRAINAGE = 0, MDP_MORPH_IMBIBITION = 1 };
typedef struct {
  int mode;        /* MDP_MORPH_DRAINAGE | MDP_MORPH_IMBIBITION */
  int axis;        /* 0,1,2: drainage invades from the low face of this axis (inlet), imbibition's
                      non-wetting phase escapes through the high face (outlet); -1: no
                      connectivity rule (pure size-based, e.g. for periodic samples) */
  int periodic[3]; /* distances (EDT) measured across these faces */
  int trapping;    /* 1: the defending phase that loses its connection to the outlet stays */
} mdp_morph_opts_t;
typedef struct {
  double radius; /* sphere radius, voxels (the invading interface's radius of curvature) */
  double snw;    /* non-wetting saturation = nw pore voxels / pore voxels */
  long long nw_voxels, pore_voxels, trapped_voxels;
  int nw_spans; /* 1: a non-wetting cluster touches both faces of the axis (0 without an axis) */
} mdp_morph_step_t;
/* The whole quasi-static curve, one step per radius (descending for drainage, ascending for
   imbibition). steps may be NULL to get the count. */
int mdp_image_morph_curve(const mdp_image_t *img, const mdp_morph_opts_t *o,
                          mdp_morph_step_t *steps, int max_steps, int *n_steps, char *err);
/* The phase distribution nearest a target non-wetting saturation: out = a copy of img in which the
   non-wetting pore voxels carry label nw_label (mapped to pore in out->phase_of); nw_label must be
   unused in img (refused otherwise). *achieved = the step used. */
int mdp_image_morph_at(const mdp_image_t *img, const mdp_morph_opts_t *o, double target_snw,
                       uint8_t nw_label, mdp_image_t *out, mdp_morph_step_t *achieved, char *err);

/* ---- synthetic images (image_make.c); all labels: 0 pore, 1 inorganic solid ---- */
/* Slit along x: n_pore pore layers between `wall` solid layers normal to y; nx = length, nz =
 * depth. */
int mdp_make_slit(mdp_image_t *img, int n_pore, int wall, int length, int depth, char *err);
/* Square array: one cylinder (axis z) per L x L cell, cells x cells cells, depth nz, solid fraction
 * c in voxels as close to c as whole rings of voxels allow. achieved_c may be NULL. */
int mdp_make_cylinders(mdp_image_t *img, int L, double c, int cells, int nz, double *achieved_c,
                       char *err);
/* Simple-cubic array: one sphere per L^3 cell, cells^3 cells, voxel solid fraction closest to c. */
int mdp_make_spheres(mdp_image_t *img, int L, double c, int cells, double *achieved_c, char *err);
/* Random overlapping spheres (Boolean model, periodic) of radius r voxels added until the porosity
 * is at or just below target. */
int mdp_make_random_spheres(mdp_image_t *img, int n, double radius, double porosity, uint64_t seed,
                            char *err);
/* Spheres from a centres file ("x y z [...]" per line, '#' comments) in a periodic box of size
 * box[3] (same length unit as the centres), voxel edge dx in that unit. */
int mdp_make_sphere_file(mdp_image_t *img, const char *centres, const double box[3], double radius,
                         double dx, char *err);

#endif
