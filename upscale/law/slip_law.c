/* Apparent permeability with wall slip (see slip_law.h for the equations). */
#include "slip_law.h"

#include <string.h>

const char *const slip_shape_names[SLIP_SHAPE_COUNT + 1] = {"slit", "tube", NULL};
const char *const slip_model_names[SLIP_MODEL_COUNT + 1] = {"navier", "shift", NULL};

static int index_of(const char *const *names, const char *name) {
  for (int i = 0; names[i]; i++)
    if (!strcmp(names[i], name)) return i;
  return -1;
}

int slip_shape_from_name(const char *name) {
  return index_of(slip_shape_names, name);
}

int slip_model_from_name(const char *name) {
  return index_of(slip_model_names, name);
}

const char *slip_size_meaning(slip_shape shape) {
  return shape == SLIP_TUBE ? "tube radius R" : "slit width h";
}

double slip_k_noslip(slip_shape shape, double h, double porosity) {
  return porosity * h * h / (shape == SLIP_TUBE ? 8.0 : 12.0);
}

double slip_coefficient(slip_shape shape) {
  return shape == SLIP_TUBE ? 4.0 : 6.0;
}

double slip_factor(slip_shape shape, slip_model model, double h, double b, double *dfdb) {
  double f, d;
  if (model == SLIP_NAVIER) { /* slit: Q = G h^3/(12 mu) (1 + 6b/h); tube: (1 + 4b/R) */
    const double c = slip_coefficient(shape);
    f = 1.0 + c * b / h;
    d = c / h;
  } else if (shape == SLIP_SLIT) { /* walls moved out by b: (h + 2b)^3 / h^3 */
    const double s = 1.0 + 2.0 * b / h;
    f = s * s * s;
    d = 6.0 * s * s / h;
  } else { /* tube of radius R + b: (R + b)^4 / R^4 */
    const double s = 1.0 + b / h;
    f = s * s * s * s;
    d = 4.0 * s * s * s / h;
  }
  if (dfdb) *dfdb = d;
  return f;
}

double slip_b_min(slip_shape shape, slip_model model, double h) {
  if (model == SLIP_NAVIER) return -h / slip_coefficient(shape);
  return shape == SLIP_SLIT ? -0.5 * h : -h;
}
