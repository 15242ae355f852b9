/* Voxelised DRP sphere pack (Andra et al. 2013; 621 spheres, R = 3.5, periodic box) against bounds
 * computed here from the centres: porosity >= 1 - N V_sphere / V_box (no overlap) and
 * <= that + sum of pairwise lens volumes pi (4R + d)(2R - d)^2 / 12 (triple overlaps are
 * negligible). argv: centres file, box file, voxel size. Skips (77) when the data folder is absent.
 */
#include "check.h"
#include "mdpore_image.h"

#include <stdlib.h>
#include <unistd.h>

int main(int argc, char **argv) {
  if (argc < 4 || access(argv[1], R_OK) != 0) {
    printf("skipped: sphere-pack data not found\n");
    return 77;
  }
  char err[MDP_IMAGE_ERR_LEN], line[512];
  double box[3] = {0, 0, 0}, R = 3.5, dx = atof(argv[3]);
  FILE *f = fopen(argv[2], "r");
  while (f && fgets(line, sizeof line, f)) /* the "Relaxed State" line is the last one */
    if (strstr(line, "Relaxed"))
      sscanf(strstr(line, "Lx:"), "Lx:%lf Ly:%lf Lz:%lf", &box[0], &box[1], &box[2]);
  if (f) fclose(f);
  CHECK(box[0] > 0, "box not read from %s", argv[2]);
  double c[1000][3];
  int n = 0;
  f = fopen(argv[1], "r");
  while (f && n < 1000 && fgets(line, sizeof line, f))
    if (sscanf(line, "%lf %lf %lf", &c[n][0], &c[n][1], &c[n][2]) == 3) n++;
  if (f) fclose(f);
  double vbox = box[0] * box[1] * box[2], vs = 4.0 / 3 * M_PI * R * R * R, lens = 0;
  for (int a = 0; a < n; a++)
    for (int b = a + 1; b < n; b++) {
      double d2 = 0;
      for (int x = 0; x < 3; x++) {
        double d = c[a][x] - c[b][x];
        d -= box[x] * round(d / box[x]);
        d2 += d * d;
      }
      double d = sqrt(d2);
      if (d < 2 * R) lens += M_PI * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12;
    }
  double lo = 1 - n * vs / vbox, hi = lo + lens / vbox;
  mdp_image_t img;
  mdp_image_stats_t st;
  CHECK(mdp_make_sphere_file(&img, argv[1], box, R, dx, err) == 0, "%s", err);
  mdp_image_stats(&img, &st, err);
  double tol = 1e-3; /* voxelisation at dx = R/10 */
  printf("spheres %d, voxels %dx%dx%d, porosity %.6f, bounds [%.6f, %.6f]\n", n, img.nx, img.ny,
         img.nz, st.porosity, lo, hi);
  CHECK(st.porosity >= lo - tol && st.porosity <= hi + tol, "porosity %.6f outside [%.6f, %.6f]",
        st.porosity, lo, hi);
  CHECK(st.spans[0] && st.spans[1] && st.spans[2], "pack must percolate along every axis");
  mdp_image_free(&img);
  printf("%s: %d failures\n", __FILE__, check_failures);
  return check_failures ? 1 : 0;
}
