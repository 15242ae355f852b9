/* sim_explain: the step plan of a scene in words (mdpore run --explain). Built from the same plan
 * the engine runs, so a pass that is not printed is not run. */
#include "decomp.h"
#include "effects/effect.h"
#include "plan.h"
#include "sim.h"

#include <stddef.h>

static void list_species(const scene_t *s, FILE *out, int frozen) {
  const char *sep = "";
  int any = 0;
  for (int a = 0; a < s->n_species; a++)
    if ((s->species[a].frozen != 0) == frozen) {
      fprintf(out, "%s%s", sep, s->species[a].name);
      sep = ", ";
      any = 1;
    }
  if (!any) fprintf(out, "none");
}

void sim_explain(const scene_t *s, int nranks, FILE *out) {
  plan_t plan;
  char err[512];
  int dims[3];
  if (plan_build(&plan, s, err, sizeof err) || decomp_dims(s, nranks, dims, err, sizeof err)) {
    fprintf(out, "cannot plan this scene: %s\n", err);
    return;
  }
  fprintf(out, "Step plan for scene '%s' (%s)\n", s->name, s->file);
  fprintf(
      out,
      "decomposition: %d MPI rank(s) as %d x %d x %d subdomains of %g x %g x %g; ghost cutoff %g\n",
      nranks, dims[0], dims[1], dims[2], (s->box_hi[0] - s->box_lo[0]) / dims[0],
      (s->box_hi[1] - s->box_lo[1]) / dims[1], (s->box_hi[2] - s->box_lo[2]) / dims[2], plan.rcut);
  fprintf(out, "periodic: x %s, y %s, z %s; dt = %g\n", s->periodic[0] ? "yes" : "no",
          s->periodic[1] ? "yes" : "no", s->periodic[2] ? "yes" : "no", s->dt);
  int k = 1;
  fprintf(out,
          "%d. integrate: first half kick v += dt/2 f/m + drift x += dt v (mobile species: ", k++);
  list_species(s, out, 0);
  fprintf(out, "; frozen, never moved: ");
  list_species(s, out, 1);
  fprintf(out, ")\n");
  if (plan.walls) {
    fprintf(out, "   ");
    effect_box_walls.describe(s, out);
    fprintf(out, "\n");
  }
  if (plan.use_vpred)
    fprintf(out,
            "   predicted velocity v~ = v + (lambda - 1/2) dt f/m, lambda = %g (Groot-Warren)\n",
            s->vv_lambda);
  else if (plan.ghost_v)
    fprintf(
        out,
        "   lambda = 0.5: the thermostat uses the half-kicked velocity (plain velocity Verlet)\n");
  if (plan.pair_terms)
    fprintf(out, "%d. migrate + ghost exchange in 3 stages x, y, z (fields: id, species, x%s)\n",
            k++, plan.ghost_v ? (plan.use_vpred ? ", v~" : ", v") : "");
  else
    fprintf(out, "%d. migrate (no pair effect named: no ghosts, no neighbour search)\n", k++);
  if (plan.density) {
    fprintf(out, "%d. density pass (%s kernel, rd = ", k++,
            s->density_kernel == 1 ? "Lucy" : "Warren");
    effect_print_pair_param(s, out, offsetof(scene_pair_t, rd));
    fprintf(out, "; self term excluded)\n");
    fprintf(out, "%d. ghost sync: rho\n", k++);
  }
  if (plan.pair_terms) {
    fprintf(out, "%d. force pass:", k++);
    const char *sep = " ";
    for (int e = 0; e < EFFECT_COUNT; e++)
      if (plan.named[e] && (effect_get(e)->needs & NEED_PAIR)) {
        fprintf(out, "%s%s", sep, effect_get(e)->name);
        sep = ", ";
      }
    fprintf(out, " (full neighbour traversal, cell lists of width >= %g)\n", plan.rcut);
    for (int e = 0; e < EFFECT_COUNT; e++)
      if (plan.named[e] && (effect_get(e)->needs & NEED_PAIR)) {
        fprintf(out, "   ");
        effect_get(e)->describe(s, out);
        fprintf(out, "\n");
      }
  }
  if (plan.particle_forces) {
    fprintf(out, "%d. particle forces: ", k++);
    const char *sep = "";
    for (int e = 0; e < EFFECT_COUNT; e++)
      if (plan.named[e] && (effect_get(e)->needs & NEED_PARTICLE)) {
        fprintf(out, "%s%s", sep, effect_get(e)->name);
        sep = ", ";
      }
    fprintf(out, "\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
      if (plan.named[e] && (effect_get(e)->needs & NEED_PARTICLE)) {
        fprintf(out, "   ");
        effect_get(e)->describe(s, out);
        fprintf(out, "\n");
      }
  }
  fprintf(out, "%d. second half kick v += dt/2 f/m\n", k++);
  fprintf(out,
          "checks every step (all ranks stop together): NaN/Inf in x, v, f; displacement > %g "
          "(half the cutoff) in one step; particle count\n",
          plan.max_disp);
}
