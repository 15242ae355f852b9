/* Cut placement by cost (balance.h). */
#include "balance.h"

#include <math.h>
#include <stdlib.h>

int balance_nbins(const decomp_t *dc, int d) {
  double nb = ceil(dc->L[d] / (dc->rcut / 16.0));
  if (nb < 8.0 * dc->dims[d]) nb = 8.0 * dc->dims[d];
  if (nb > 65536) nb = 65536;
  return (int)nb;
}

void balance_histogram_add(const decomp_t *dc, const particles_t *p, const int *is_frozen,
                           double frozen_weight, double scale, double *const hist[3]) {
  for (int d = 0; d < 3; d++) {
    const int nb = balance_nbins(dc, d);
    const double inv = nb / dc->L[d];
    for (int i = 0; i < p->n_local; i++) {
      int b = (int)((p->x[d][i] - dc->box_lo[d]) * inv);
      b = b < 0 ? 0 : (b >= nb ? nb - 1 : b);
      hist[d][b] += scale * (is_frozen[p->species[i]] ? frozen_weight : 1.0);
    }
  }
}

static double positive(double v) {
  return v > 0 ? v : 0;
}

/* Cost of [lo, x) over the histogram (linear inside a bin). */
static double cost_below(const double *w, int nb, double lo, double width, double x) {
  const double u = (x - lo) / width;
  int b = (int)floor(u);
  if (b < 0) return 0;
  double c = 0;
  for (int k = 0; k < b && k < nb; k++) c += w[k];
  if (b < nb) c += (u - b) * w[b];
  return c;
}

int balance_cuts_1d(const double *w, int nb, double lo, double hi, int m, double min_width,
                    double *cuts) {
  if (m * min_width > hi - lo) return -1;
  const double width = (hi - lo) / nb;
  double total = 0;
  for (int b = 0; b < nb; b++) total += positive(w[b]);
  cuts[0] = lo;
  cuts[m] = hi;
  if (!(total > 0)) { /* nothing to weigh: uniform */
    for (int k = 1; k < m; k++) cuts[k] = lo + k * ((hi - lo) / m);
  } else {
    double acc = 0; /* cost of bins [0, b) */
    int b = 0;
    for (int k = 1; k < m; k++) { /* targets increase with k: one sweep over the bins */
      const double target = total * k / m;
      while (b < nb && acc + positive(w[b]) < target) acc += positive(w[b++]);
      const double in_bin = b < nb && w[b] > 0 ? (target - acc) / w[b] : 0;
      cuts[k] = lo + (b + in_bin) * width;
    }
  }
  /* No slab thinner than min_width: push forward, then back from the top. */
  for (int k = 1; k < m; k++)
    if (cuts[k] < cuts[k - 1] + min_width) cuts[k] = cuts[k - 1] + min_width;
  for (int k = m - 1; k >= 1; k--)
    if (cuts[k] > cuts[k + 1] - min_width) cuts[k] = cuts[k + 1] - min_width;
  for (int k = 0; k < m; k++)
    if (!(cuts[k + 1] - cuts[k] >= min_width * (1 - 1e-12))) return -1;
  return 0;
}

double balance_slab_imbalance(const double *w, int nb, double lo, double hi, int m,
                              const double *cuts) {
  const double width = (hi - lo) / nb;
  double max = 0, sum = 0;
  for (int k = 0; k < m; k++) {
    const double c =
        cost_below(w, nb, lo, width, cuts[k + 1]) - cost_below(w, nb, lo, width, cuts[k]);
    sum += c;
    if (c > max) max = c;
  }
  return sum > 0 ? max / (sum / m) : 1.0;
}
