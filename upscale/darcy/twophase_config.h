/* The `twophase:` block of a `mdpore darcy` config (docs/twophase-darcy.md): water injected into
 * oil, solved by IMPES (twophase_impes.h). */
#ifndef MDPORE_UPSCALE_TWOPHASE_CONFIG_H
#define MDPORE_UPSCALE_TWOPHASE_CONFIG_H

#include "twophase_relperm.h"

typedef struct {
  int enabled;
  relperm kr;      /* relative permeabilities and phase viscosities */
  double porosity; /* uniform porosity phi */
  double s_init;   /* initial water saturation of every block */
  double s_inj;    /* water saturation of the fluid entering through the inlet face */
  int inlet_face;  /* FACE_XM..FACE_ZP: where water is injected */
  double rate;     /* total volumetric rate through the inlet face (2D: per unit depth); 0: the
                          boundary pressures drive the flow */
  double cfl;      /* time step = cfl x the explicit upwind stability limit */
  double t_end;    /* end time */
  int n_out;       /* output times, increasing, <= t_end */
  double *t_out;
  char profiles_csv[4096]; /* saturation of every block at each output time */
  char history_csv[4096];  /* water cut and recovery against pore volumes injected, every step */
  char config_path[4096];  /* the config file (messages) */
} twophase_config;

/* The most CFL steps an end time may ask for (twophase.end_time is refused beyond it). */
#define TWOPHASE_MAX_STEPS 1e7

void twophase_config_free(twophase_config *tp);

#endif
