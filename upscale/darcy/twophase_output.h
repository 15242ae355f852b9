/* Files of the two-phase Darcy solve (docs/twophase-darcy.md, "Output"), written by rank 0:
 * a saturation profile CSV (every block at each output time) and a history CSV (one row per time
 * step: pore volumes injected, water cut, oil recovery). */
#ifndef MDPORE_UPSCALE_TWOPHASE_OUTPUT_H
#define MDPORE_UPSCALE_TWOPHASE_OUTPUT_H

#include <stdio.h>

#include "darcy_config.h"

typedef struct {
  double time, dt;
  double pv_injected;  /* cumulative inflow through the inlet (and sources) / pore volume */
  double water_cut;    /* water / total rate leaving the domain in this step */
  double oil_recovery; /* cumulative oil produced / oil initially in place */
  double inflow_rate;  /* total volumetric rate in */
  double water_out;    /* water and oil volumetric rates out */
  double oil_out;
  double inlet_pressure;
} twophase_history_row;

typedef struct {
  FILE *profiles, *history;
  char profiles_tmp[4200], history_tmp[4200];
} twophase_writer;

/* Opens the files named in c->twophase (temporary names, renamed on close) and writes the headers
 * with the units. Returns 0, or -1 after a message. */
int twophase_output_open(twophase_writer *w, const darcy_config *c);
/* The saturation of every block (natural order) at one time. */
void twophase_output_profile(twophase_writer *w, const darcy_problem *p, double time,
                             double pv_injected, const double *sw);
void twophase_output_history(twophase_writer *w, const twophase_history_row *row);
/* Closes and renames the files into place. Returns 0, or -1 after a message. */
int twophase_output_close(twophase_writer *w, const darcy_config *c);

#endif
