/* The inputs of `mdpore slip`: permeabilities of one pore shape at several sizes, read from
 *
 *   a CSV            columns h, k, k_err (any order), optional shape (slit|tube, one for all rows)
 *                    and porosity (default 1: k per pore area); '#' lines are comments;
 *   a campaign JSON  `mdpore permeability`'s permeability.json (format mdpore-permeability):
 *                    k = axes.AXIS.k_rc2 +- k_rc2_err, porosity, units.rc_m; the size from the
 *                    suffix FILE@H, else (slit only) h_hydraulic of campaign.txt beside it (2 V / S of
 *                    the pore voxels, the width of a slit; not the radius of a voxel tube).
 *
 * Every problem is reported naming the file (and line), the key or column and what was expected. */
#ifndef MDPORE_UPSCALE_SLIP_INPUT_H
#define MDPORE_UPSCALE_SLIP_INPUT_H

#include "slip_fit.h"

typedef struct {
  slip_point *p;
  int n, cap;
  int shape;                        /* -1 until a CSV's shape column or --shape sets it */
  char shape_from[SLIP_SOURCE_LEN]; /* where the shape was set */
} slip_points;

void slip_points_init(slip_points *ps, int shape);
void slip_points_free(slip_points *ps);

/* Reads one input (CSV or JSON, by content) and appends its points. axis: "x", "y" or "z", or NULL
 * (a JSON with one axis uses it; with several, x). 0 or -1 with a message in err. */
int slip_read_input(slip_points *ps, const char *spec, const char *axis, char *err, int len);
/* The '@SIZE' suffix of an input spec FILE@SIZE (its '@'), or NULL when spec is a file alone. */
const char *slip_input_size(const char *spec);

#endif
