/* Unit tables and "NUMBER UNIT" parsing (see darcy_units.h). */
#include "darcy_units.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  darcy_quantity q;
  int si;
  const char *name;
  double factor; /* to the base unit (the first entry of each quantity and system) */
} unit_entry;

#define PSI 6894.757293168
static const unit_entry units[] = {
    {QTY_PERMEABILITY, 1, "m^2", 1.0},
    {QTY_PERMEABILITY, 1, "D", 1e3 * DARCY_MD_IN_M2},
    {QTY_PERMEABILITY, 1, "mD", DARCY_MD_IN_M2},
    {QTY_PERMEABILITY, 1, "uD", 1e-3 * DARCY_MD_IN_M2},
    {QTY_PERMEABILITY, 1, "nD", 1e-6 * DARCY_MD_IN_M2},
    {QTY_PERMEABILITY, 0, "rc^2", 1.0},
    {QTY_LENGTH, 1, "m", 1.0},
    {QTY_LENGTH, 1, "cm", 1e-2},
    {QTY_LENGTH, 1, "mm", 1e-3},
    {QTY_LENGTH, 1, "um", 1e-6},
    {QTY_LENGTH, 1, "nm", 1e-9},
    {QTY_LENGTH, 1, "ft", 0.3048},
    {QTY_LENGTH, 0, "rc", 1.0},
    {QTY_PRESSURE, 1, "Pa", 1.0},
    {QTY_PRESSURE, 1, "kPa", 1e3},
    {QTY_PRESSURE, 1, "MPa", 1e6},
    {QTY_PRESSURE, 1, "GPa", 1e9},
    {QTY_PRESSURE, 1, "bar", 1e5},
    {QTY_PRESSURE, 1, "psi", PSI},
    {QTY_PRESSURE, 0, "kT/rc^3", 1.0},
    {QTY_VISCOSITY, 1, "Pa s", 1.0},
    {QTY_VISCOSITY, 1, "mPa s", 1e-3},
    {QTY_VISCOSITY, 1, "cP", 1e-3},
    {QTY_VISCOSITY, 0, "m/(rc tau)", 1.0},
    {QTY_DENSITY, 1, "kg/m^3", 1.0},
    {QTY_DENSITY, 1, "g/cm^3", 1e3},
    {QTY_DENSITY, 0, "m/rc^3", 1.0},
    {QTY_GRADIENT, 1, "Pa/m", 1.0},
    {QTY_GRADIENT, 1, "kPa/m", 1e3},
    {QTY_GRADIENT, 1, "MPa/m", 1e6},
    {QTY_GRADIENT, 1, "bar/m", 1e5},
    {QTY_GRADIENT, 1, "psi/ft", PSI / 0.3048},
    {QTY_GRADIENT, 0, "kT/rc^4", 1.0},
    {QTY_INV_LENGTH, 1, "1/m", 1.0},
    {QTY_INV_LENGTH, 0, "1/rc", 1.0},
    {QTY_RATE, 1, "m^3/s", 1.0},
    {QTY_RATE, 0, "rc^3/tau", 1.0},
    {QTY_RATE_2D, 1, "m^2/s", 1.0},
    {QTY_RATE_2D, 0, "rc^2/tau", 1.0},
};
static const int n_units = (int)(sizeof units / sizeof units[0]);

static const char *const qty_names[QTY_COUNT] = {
    "permeability",   "length",          "pressure",
    "viscosity",      "density",         "gradient",
    "inverse length", "volumetric rate", "volumetric rate per unit depth"};

const char *darcy_quantity_name(darcy_quantity q) {
  return qty_names[q];
}

const char *darcy_unit_label(darcy_quantity q, int si) {
  for (int i = 0; i < n_units; i++)
    if (units[i].q == q && units[i].si == !!si) return units[i].name;
  return "?";
}

int darcy_unit_factor(const char *unit, darcy_quantity q, int si, double *factor) {
  for (int i = 0; i < n_units; i++)
    if (units[i].q == q && units[i].si == !!si && !strcmp(units[i].name, unit)) {
      *factor = units[i].factor;
      return 0;
    }
  return -1;
}

const char *darcy_unit_list(darcy_quantity q, int si, char *buf, size_t len) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < n_units; i++)
    if (units[i].q == q && units[i].si == !!si && used < len) {
      int w = snprintf(buf + used, len - used, "%s%s", used ? ", " : "", units[i].name);
      if (w > 0) used += (size_t)w;
    }
  return buf;
}

int darcy_unit_parse(const char *text, darcy_quantity q, int si, double *value, int *had_unit,
                     char *why, size_t why_len) {
  char *end;
  errno = 0;
  double v = strtod(text, &end);
  *had_unit = 0;
  if (end == text || errno || !isfinite(v)) {
    snprintf(why, why_len, "not a number");
    return -1;
  }
  while (isspace((unsigned char)*end)) end++;
  if (!*end) {
    *value = v;
    return 0;
  }
  char unit[32];
  snprintf(unit, sizeof unit, "%s", end);
  for (size_t n = strlen(unit); n && isspace((unsigned char)unit[n - 1]);) unit[--n] = '\0';
  double f;
  if (darcy_unit_factor(unit, q, si, &f)) {
    double other;
    if (!darcy_unit_factor(unit, q, !si, &other))
      snprintf(why, why_len, "'%s' is a %s unit, this config is in %s units", unit,
               si ? "reduced" : "SI", si ? "SI" : "reduced");
    else
      snprintf(why, why_len, "unknown %s unit '%s'", qty_names[q], unit);
    return -1;
  }
  *had_unit = 1;
  *value = v * f;
  return 0;
}
