/* Units of the `mdpore darcy` inputs and outputs (docs/darcy-config.md, "Units"). A config value is
 * a plain number in the unit system's base unit (SI: m^2, m, Pa, Pa s, ...; reduced: rc^2, rc, ...)
 * or "NUMBER UNIT" with one of the units named here; HDF5 permeability datasets carry a `unit`
 * attribute with the same names. Every output states its unit with darcy_unit_label. */
#ifndef MDPORE_UPSCALE_DARCY_UNITS_H
#define MDPORE_UPSCALE_DARCY_UNITS_H

#include <stddef.h>

typedef enum {
  QTY_PERMEABILITY = 0,
  QTY_LENGTH,
  QTY_PRESSURE,
  QTY_VISCOSITY,
  QTY_DENSITY,
  QTY_GRADIENT,   /* pressure / length (threshold G0, block gradients) */
  QTY_INV_LENGTH, /* Forchheimer beta */
  QTY_RATE,       /* volumetric rate (3D) */
  QTY_RATE_2D,    /* volumetric rate per unit depth (2D) */
  QTY_COUNT
} darcy_quantity;

/* 1 millidarcy in m^2 (1 D = 9.869233e-13 m^2). */
#define DARCY_MD_IN_M2 9.869233e-16

/* Name of the quantity ("permeability", ...) and its base unit in a unit system (si 1: SI, 0:
 * reduced DPD units), e.g. "m^2" or "rc^2". */
const char *darcy_quantity_name(darcy_quantity q);
const char *darcy_unit_label(darcy_quantity q, int si);

/* Factor that converts a value in `unit` to the base unit of the system. Returns 0, or -1 when the
 * unit is not one of darcy_unit_list(q, si) (a unit of the other system included). */
int darcy_unit_factor(const char *unit, darcy_quantity q, int si, double *factor);

/* "m^2, D, mD, uD, nD" into buf (the units accepted for q in that system). */
const char *darcy_unit_list(darcy_quantity q, int si, char *buf, size_t len);

/* Parses "NUMBER" (base unit) or "NUMBER UNIT" into the base unit. Returns 0, or -1 with a reason
 * ("unknown unit 'md'", "not a number") in why. *had_unit tells whether a unit was written. */
int darcy_unit_parse(const char *text, darcy_quantity q, int si, double *value, int *had_unit,
                     char *why, size_t why_len);

#endif
