/* Two-point flux across one face between cell centres a and b (physics.md section 6).
 * Each half has its own law and length (centre-to-face distance d_a, d_b). The flux q (Darcy
 * velocity through the face) is continuous: q = q_a(G_a) = q_b(G_b) with d_a G_a + d_b G_b = dp =
 * p_a - p_b. For Darcy halves this is the harmonic-mean transmissibility; for Darcy/Forchheimer
 * pairs a closed form; otherwise a safeguarded scalar Newton solve. */
#ifndef MDPORE_UPSCALE_FACE_FLUX_H
#define MDPORE_UPSCALE_FACE_FLUX_H

#include "flow_law.h"

typedef struct {
  double q;     /* Darcy velocity from a to b */
  double dq_dp; /* d q / d(dp) >= 0 */
  double g_a;   /* gradient in half a (so the face pressure is p_a - d_a g_a) */
} face_flux_result;

/* law_b NULL (and d_b ignored) means a boundary half-face: the face value is prescribed and the
 * flux goes through half a alone. g_lin: power-law linearisation gradient (flow_law_q). */
face_flux_result face_flux(const flow_law *law_a, double d_a, const flow_law *law_b, double d_b,
                           const fluid_props *fl, double g_lin, double dp);

#endif
