/* Apparent permeability of a straight pore with wall slip (docs/permeability.md,
 * "Slip and apparent permeability"; physics.md sections 4-5).
 *
 * A pore of size h (slit: width h between two flat walls; tube: radius R of a circular tube) in a
 * periodic sample of porosity phi has, without slip, the superficial permeability
 *
 *   slit  k_noslip = phi h^2 / 12          tube  k_noslip = phi R^2 / 8
 *
 * and with a slip length b at every wall k_app = k_noslip F(b / h). Two forms of F:
 *
 *   navier  Navier slip u_wall = b du/dn at the wall (exact for that boundary condition):
 *           u(y) = G/(2 mu) (h^2/4 - y^2 + b h)  ->  Q = G h^3/(12 mu) (1 + 6 b/h)    F = 1 + 6 b/h
 *           u(r) = G/(4 mu) (R^2 - r^2 + 2 b R)  ->  Q = pi G R^4/(8 mu) (1 + 4 b/R)  F = 1 + 4 b/R
 *   shift   no-slip walls moved out by b (the parabola of the wall validations reaches zero b
 *           beyond the wall face): slit (h + 2b)^3 / h^3 = (1 + 2 b/h)^3, tube (1 + b/R)^4.
 *
 * Both agree to first order in b/h (1 + 6 b/h, 1 + 4 b/R). The common 1 + 4 b / h_eff is the tube
 * form with h_eff = R. b > 0: slip (the flow reaches into the wall); b < 0: a layer at the wall that
 * moves less than a no-slip flow. */
#ifndef MDPORE_UPSCALE_SLIP_LAW_H
#define MDPORE_UPSCALE_SLIP_LAW_H

typedef enum { SLIP_SLIT = 0, SLIP_TUBE, SLIP_SHAPE_COUNT } slip_shape;
typedef enum { SLIP_NAVIER = 0, SLIP_SHIFT, SLIP_MODEL_COUNT } slip_model;

/* Names in enum order, NULL-terminated: "slit", "tube" and "navier", "shift". */
extern const char *const slip_shape_names[SLIP_SHAPE_COUNT + 1];
extern const char *const slip_model_names[SLIP_MODEL_COUNT + 1];
/* The enum value of a name, or -1. */
int slip_shape_from_name(const char *name);
int slip_model_from_name(const char *name);
/* What h means for a shape: "slit width h" or "tube radius R". */
const char *slip_size_meaning(slip_shape shape);

/* The no-slip superficial permeability phi h^2/12 (slit) or phi R^2/8 (tube). */
double slip_k_noslip(slip_shape shape, double h, double porosity);
/* The first-order coefficient c of F = 1 + c b / h: 6 (slit) or 4 (tube). */
double slip_coefficient(slip_shape shape);
/* F(b / h) = k_app / k_noslip of the model, and dF/db into *dfdb (when not NULL). */
double slip_factor(slip_shape shape, slip_model model, double h, double b, double *dfdb);
/* The smallest b the model allows at size h (F > 0, the flowing width positive): -h/6, -R/4
 * (navier), -h/2, -R (shift). */
double slip_b_min(slip_shape shape, slip_model model, double h);

#endif
