/* Reduced (mDPD) units -> SI, the one place that holds the formulas: `mdpore run` (a scene's
 * `units:` block, common/units_block.h) and `mdpore permeability` (campaign/campaign_units.c) both
 * call units_make. physics.md section 4; docs/permeability.md, "Conventions and units".
 *
 * The reduced units are rc (length), m (the mass of a particle of mass 1), the energy unit e (kT =
 * 1 in a scene at kT: 1) and tau = rc sqrt(m / e). Every other unit follows by dimensions:
 *   velocity rc / tau,  pressure e / rc^3,  pressure gradient (force per volume) e / rc^4,
 *   viscosity m / (rc tau),  permeability rc^2 (1 D = 9.869233e-13 m^2).
 * k = mu q / G is a length squared in any consistent units, so k in m^2 needs only rc. */
#ifndef MDPORE_COMMON_UNITS_H
#define MDPORE_COMMON_UNITS_H

#define UNITS_KB 1.380649e-23        /* J/K (exact, SI 2019) */
#define UNITS_RHO_WATER 997.0        /* kg/m^3, water at 25 C */
#define UNITS_M_WATER 2.99150711e-26 /* kg, one H2O molecule (18.015 u) */
#define UNITS_DARCY_M2 9.869233e-13  /* m^2 per darcy */
#define UNITS_NANODARCY_PER_M2 (1e9 / UNITS_DARCY_M2)
#define UNITS_WATER_VISCOSITY 8.9e-4     /* Pa s, real water at 25 C (for the statement only) */
#define UNITS_DEFAULT_TEMPERATURE 298.15 /* K */
/* mu of the standard mDPD water (A = -40, B = 25, gamma = 4.5, rd = 0.75) at n = 6.07, reverse
 * Poiseuille (validation/engine/viscosity.py): the statement of the viscosity mismatch. */
#define UNITS_MDPD_WATER_MU 5.41

/* The SI value of one reduced unit of each quantity. */
typedef struct {
  double rc_m;        /* length: metres per rc */
  double kT_J;        /* energy: joules per reduced energy unit */
  double mass_kg;     /* mass: kg per reduced mass unit */
  double tau_s;       /* time: seconds per tau = rc sqrt(m / e) */
  double q_m_per_s;   /* velocity (q, u): rc / tau */
  double p_Pa;        /* pressure: e / rc^3 */
  double G_Pa_per_m;  /* pressure gradient G = -dp/dx: e / rc^4 */
  double mu_Pa_s;     /* viscosity: m / (rc tau) */
  double k_m2;        /* permeability: rc^2 */
  double k_nD;        /* permeability: rc^2 in nanodarcy */
  double n_molecules; /* m / m_water: water molecules per particle (coarse-graining level) */
} units_si_t;

/* Length of the mDPD water mapping: a particle stands for n_molecules water molecules at n
 * particles per rc^3, so rc^3 = n_molecules n m_water / rho_water (physics.md section 4: N_m = 3,
 * n = 6.2 give rc = 0.82 nm). */
double units_water_rc(double n_molecules, double n);
/* Mass of a particle that carries the water of its volume 1/n: m = rho_water rc^3 / n. */
double units_water_mass(double rc_m, double n);
/* Every factor from rc (m), the energy unit (J) and the mass unit (kg). */
void units_make(double rc_m, double energy_J, double mass_kg, units_si_t *u);

enum { UNITS_MAPPING_WATER = 1, UNITS_MAPPING_OWN = 2 };

/* A `units:` block (common/units_block.h), read and resolved. */
typedef struct {
  int on;                                  /* 1: a block was read */
  int mapping;                             /* UNITS_MAPPING_* */
  double coarse_graining;                  /* water: N_m (NAN for own units) */
  double temperature_K;                    /* T of kT (NAN when `energy` was given) */
  int energy_given, mass_given, tau_given; /* own units: which of them the block set */
  double density;                          /* n used (NAN when none was needed) */
  char density_source[128];
  char length_source[256]; /* how rc was set, one phrase */
  units_si_t si;
} units_mapping_t;

/* One sentence that states the mapping (which one, rc, tau, m, e) and that it is dimensional, not
 * viscosity-matched (the standard mDPD water's mu = 5.41 maps to mu_SI vs real water's 8.9e-4). */
void units_mapping_describe(const units_mapping_t *m, char *out, int len);

#endif
