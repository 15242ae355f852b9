/* The capillary-pressure curve Pc(Sw) = p_o - p_w read from the pc_morph.csv of `mdpore image
 * drainage` (docs/relperm.md section 2): '#' comment lines, a header, comma-separated rows. The
 * columns read (header names, case-insensitive): Sw, and pc_Pa (Pa) when it is given on every row,
 * else pc (reduced units, kT/rc^3; pc_Pa is empty when the image has no physical voxel size). */
#ifndef MDPORE_UPSCALE_PC_CURVE_H
#define MDPORE_UPSCALE_PC_CURVE_H

typedef struct {
  char path[4096];
  int n;
  double *sw, *pc; /* sorted by increasing Sw */
  int in_pa;       /* 1: pc in Pa; 0: reduced units */
  int merged;      /* rows merged into one of equal Sw (the largest Pc kept) */
} pc_curve;

/* Rows of equal Sw become one with the largest Pc (a drainage curve's Sw = 1 rows below the entry
 * pressure: the entry pressure is kept). Returns 0, or -1 with "FILE:LINE: column 'NAME': expected
 * ... (got ...)" (no Sw or Pc column, a non-number, NaN or inf, Sw outside [0, 1], fewer than 2 rows
 * of different Sw). */
int pc_curve_read(const char *path, pc_curve *c, char *err, int errlen);
/* Pc at sw: linear interpolation, held constant beyond the first and last rows. */
double pc_curve_at(const pc_curve *c, double sw);
void pc_curve_free(pc_curve *c);

#endif
