/* Weighted isotonic regression by pool adjacent violators (see kr_isotonic.h). */
#include "kr_isotonic.h"

#include <stdlib.h>

int kr_isotonic_increasing(double *y, const double *w, int n) {
  if (n <= 0) return 0;
  double *val = malloc((size_t)n * sizeof(double)), *wt = malloc((size_t)n * sizeof(double));
  int *len = malloc((size_t)n * sizeof(int)), nb = 0, moved = 0;
  if (!val || !wt || !len) {
    free(val), free(wt), free(len);
    return -1;
  }
  for (int i = 0; i < n; i++) {
    val[nb] = y[i], wt[nb] = w[i], len[nb] = 1, nb++;
    while (nb > 1 && val[nb - 2] > val[nb - 1]) { /* pool the violating blocks: weighted mean */
      const double ww = wt[nb - 2] + wt[nb - 1];
      val[nb - 2] = (wt[nb - 2] * val[nb - 2] + wt[nb - 1] * val[nb - 1]) / ww;
      wt[nb - 2] = ww, len[nb - 2] += len[nb - 1], nb--;
    }
  }
  for (int b = 0, i = 0; b < nb; b++)
    for (int k = 0; k < len[b]; k++, i++) {
      if (y[i] != val[b]) moved++;
      y[i] = val[b];
    }
  free(val), free(wt), free(len);
  return moved;
}
