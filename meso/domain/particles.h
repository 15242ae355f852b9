/* Particle storage: structure of arrays, global 64-bit ids, owned particles first, then ghosts.
 * Arrays an effect does not need are NULL (rho without a density pass, virial unless a pressure
 * profile asks for it). */
#ifndef MESO_ENGINE_PARTICLES_H
#define MESO_ENGINE_PARTICLES_H

#include <stdint.h>

typedef struct {
  int n_local;  /* owned particles: indices [0, n_local)                 */
  int n_ghost;  /* ghost copies: indices [n_local, n_local + n_ghost)    */
  int capacity; /* allocated length of every array                       */

  int64_t *id;
  int32_t *species;
  double *x[3];   /* positions (absolute box coordinates; ghosts carry periodic images) */
  double *v[3];   /* velocities                                                         */
  double *f[3];   /* total force of the last force pass                                 */
  double *rho;    /* local density (mdpd_repulsion only), ghosts synced after the density pass */
  double *virial; /* per-particle virial, 6 per particle xx yy zz xy xz yz (on request only) */
  double
      *vpred[3]; /* Groot-Warren predicted velocity v~ used by the thermostat; only allocated when
                    vv_lambda != 0.5 (at 0.5 v~ is the half-kicked v itself and v is used) */
} particles_t;

#endif
