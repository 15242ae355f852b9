/* The flow laws that relate the driving gradient G = -dp/dx to the superficial (Darcy) velocity q
 * (physics.md section 5). One struct holds any law; `kind` says which parameters are used.
 *
 *   darcy        q = (k/mu) G
 *   threshold    q = (k/mu) (G - G0) for G > G0, else 0        (exact form, used by the fit)
 *                q = (k/mu) [G - G0 (1 - exp(-G/G0))]           (Swartzendruber form, continuum
 * solve) forchheimer  G = (mu/k) q + beta rho q|q| power        q = K G^n (continuum: linear below
 * g_lin)
 *
 * All laws are odd in G (flow reverses with the gradient). */
#ifndef MDPORE_UPSCALE_FLOW_LAW_H
#define MDPORE_UPSCALE_FLOW_LAW_H

typedef enum { LAW_DARCY = 0, LAW_THRESHOLD, LAW_FORCHHEIMER, LAW_POWER, LAW_COUNT } flow_law_kind;

typedef struct {
  flow_law_kind kind;
  double k;    /* permeability [length^2] (darcy, threshold, forchheimer) */
  double g0;   /* threshold gradient [pressure/length] */
  double beta; /* Forchheimer coefficient [1/length] */
  double K;    /* power-law prefactor [velocity / (pressure/length)^n] */
  double n;    /* power-law exponent */
} flow_law;

typedef struct {
  double mu;  /* dynamic viscosity */
  double rho; /* mass density (Forchheimer inertia) */
} fluid_props;

/* The law names in kind order, NULL-terminated (for keyword checks). */
extern const char *const flow_law_names[LAW_COUNT + 1];
const char *flow_law_name(flow_law_kind kind);
/* Returns the kind for a name ("darcy", "threshold", "forchheimer", "power"), or -1. */
int flow_law_from_name(const char *name);
int flow_law_nparams(flow_law_kind kind);

/* The exact law q(G) as fitted (threshold as a hinge, power law without regularisation). */
double flow_law_q_exact(const flow_law *law, const fluid_props *fl, double G);

/* The law used by the continuum solver, q(G) and dq/dG >= 0: smooth (Swartzendruber threshold) and,
 * for the power law, linear for |G| < g_lin so that dq/dG stays finite and non-zero at G = 0. */
double flow_law_q(const flow_law *law, const fluid_props *fl, double g_lin, double G, double *dqdG);

/* Inverse of the continuum law for Darcy/Forchheimer: G(q). */
double flow_law_gradient_forchheimer(const flow_law *law, const fluid_props *fl, double q);

/* Checks that the parameters make a valid law; writes a reason into why and returns -1 if not. */
int flow_law_check(const flow_law *law, char *why, int why_len);

#endif
