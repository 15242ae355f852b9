/* sim_explain: the phase lists of a scene's plan in words (mdpore run --explain). It prints the
 * plan's own lists (effects/plan.h), the ones engine/step.c runs, with the chosen backend's remark
 * on each phase (backend.h phase_note: where a fused phase runs), so a phase that is not printed is
 * not run. */
#include "domain/decomp.h"
#include "effects/effect.h"
#include "common/memory_limit.h"
#include "engine/memory_plan.h"
#include "engine/sim_internal.h"

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

/* The memory plan of the largest rank from the scene alone (engine/memory_plan.h; the run checks
 * it again with the particles counted) and the memory available now. */
static void print_memory(const scene_t *s, const plan_t *plan, const backend_ops_t *ops, int nranks,
                         const int dims[3], FILE *out) {
  memory_inputs_t in;
  memory_inputs_from_scene(s, dims, &in);
  if (ops && ops->device_bytes_per_particle)
    in.device_bytes_per_particle = ops->device_bytes_per_particle(plan, nranks, s->gpu_memory);
  memory_plan_t mp;
  memory_plan_build(s, plan, &in, &mp);
  memory_plan_print(&mp, out);
  char from[64], b[32];
  const double avail = mdp_memory_available(from, sizeof from);
  fprintf(out, "  %-48s %s (%s)\n", "available now (the node)",
          memory_bytes_text(avail, b, sizeof b), from);
  if (s->init.kind == INIT_LAMMPS_DATA || s->init.kind == INIT_SNAPSHOT)
    fprintf(out,
            "  (the particles of %s are counted when it is read; the run checks the plan then)\n",
            s->init.path);
  else if (s->init.kind == INIT_GEOMETRY)
    fprintf(out, "  (a geometry at its largest density over the whole box, an upper bound: the run "
                 "counts the image's particles and checks the plan then)\n");
}

/* The named effects that need `need` (enum effect_need), comma-separated; then, with describe,
 * one indented line each. */
static void list_effects(const scene_t *s, const plan_t *plan, unsigned need, FILE *out,
                         int describe) {
  const char *sep = "";
  for (int e = 0; e < EFFECT_COUNT; e++)
    if (plan->named[e] && (effect_get(e)->needs & need)) {
      if (describe) {
        fprintf(out, "\n      ");
        effect_get(e)->describe(s, out);
      } else {
        fprintf(out, "%s%s", sep, effect_name(e));
        sep = ", ";
      }
    }
}

static void describe_phase(const scene_t *s, const plan_t *plan, int phase, int setup, FILE *out) {
  switch (phase) {
  case PHASE_KICK_DRIFT:
    fprintf(out, "first half kick v += dt/2 f/m + drift x += dt v (mobile species: ");
    list_species(s, out, 0);
    fprintf(out, "; frozen, never integrated: ");
    list_species(s, out, 1);
    for (int a = 0; a < s->n_species; a++) /* moving walls (species[].velocity) */
      if (plan->moving[a])
        fprintf(out, "; %s moves at the fixed velocity [%g, %g, %g]", s->species[a].name,
                plan->wall_u[a][0], plan->wall_u[a][1], plan->wall_u[a][2]);
    fprintf(out, ")");
    break;
  case PHASE_AFTER_DRIFT:
    fprintf(out, "position constraints: ");
    list_effects(s, plan, NEED_AFTER_DRIFT, out, 0);
    list_effects(s, plan, NEED_AFTER_DRIFT, out, 1);
    break;
  case PHASE_CHECK_DRIFT:
    fprintf(out,
            "collective check: NaN/Inf in x, v; displacement > %g (half the cutoff) in one step; "
            "then the step index advances",
            plan->max_disp);
    break;
  case PHASE_MIGRATE:
    fprintf(out, "periodic wrap; particles to the rank that owns them");
    break;
  case PHASE_SORT:
    fprintf(out, "owned particles in cell order");
    break;
  case PHASE_PREDICT:
    if (setup)
      fprintf(out, "v~ = v (the first forces use the current velocities)");
    else
      fprintf(out, "predicted velocity v~ = v + (lambda - 1/2) dt f/m, lambda = %g (Groot-Warren)",
              plan->vv_lambda);
    break;
  case PHASE_GHOSTS:
    fprintf(out, "ghost exchange in 3 stages x, y, z, width %g (fields: id, species, x%s)",
            plan->rcut, plan->ghost_v ? (plan->use_vpred ? ", v~" : ", v") : "");
    break;
  case PHASE_NEIGHBOURS:
    fprintf(out, "cell lists of width >= %g and neighbour lists", plan->rcut);
    break;
  case PHASE_DENSITY:
    fprintf(out, "density pass (%s kernel, rd = ", s->density_kernel == 1 ? "Lucy" : "Warren");
    effect_print_pair_param(s, out, offsetof(scene_pair_t, rd));
    fprintf(out, "; self term excluded)");
    if (plan->density_cache)
      fprintf(out,
              "; static frozen particles: the part from other static frozen particles computed "
              "once, each step only the mobile and moving neighbours (CPU; MDPORE_DENSITY_CACHE=0: "
              "off; the GPU only with MDPORE_DENSITY_CACHE=1)");
    break;
  case PHASE_RHO_SYNC:
    fprintf(out, "ghost sync: rho");
    break;
  case PHASE_WALL_FIELD:
    fprintf(out, "wall fraction phi and grad phi of each mobile particle from the frozen ones (");
    list_effects(s, plan, NEED_WALL_FIELD, out, 0);
    fprintf(out, "%s)",
            (plan->pair_terms & PAIR_TERM_WALL_NO_SLIP)
                ? "; phi scales the wall pairs' thermostat"
                : "; read by the reflection after the next drift");
    break;
  case PHASE_PAIR_FORCES:
    if (!plan->pair_terms) {
      fprintf(out, "no pair effect named: forces start at 0");
      break;
    }
    fprintf(out, "force pass: ");
    list_effects(s, plan, NEED_PAIR, out, 0);
    if (plan->pair_terms & PAIR_TERM_WALL_NO_SLIP)
      fprintf(out, " (wall pairs' thermostat x ratio(phi_i): wall_boundary)");
    if (!setup) list_effects(s, plan, NEED_PAIR, out, 1);
    break;
  case PHASE_PARTICLE_FORCES:
    fprintf(out, "particle forces: ");
    list_effects(s, plan, NEED_PARTICLE, out, 0);
    if (!setup) list_effects(s, plan, NEED_PARTICLE, out, 1);
    break;
  case PHASE_KICK:
    fprintf(out, "second half kick v += dt/2 f/m");
    break;
  case PHASE_CHECK:
    fprintf(out, "collective check: NaN/Inf in f%s (all ranks stop together)",
            setup ? "" : "; particle count");
    break;
  default:
    break;
  }
}

static void print_list(const scene_t *s, const plan_t *plan, const backend_ops_t *ops, int setup,
                       FILE *out) {
  const unsigned char *list = setup ? plan->setup : plan->step;
  const int n = setup ? plan->n_setup : plan->n_step;
  for (int k = 0; k < n; k++) {
    fprintf(out, "%2d. %s: ", k + 1, step_phase_names[list[k]]);
    describe_phase(s, plan, list[k], setup, out);
    const char *note = ops && ops->phase_note ? ops->phase_note(plan, list[k]) : NULL;
    if (note)
      fprintf(out, "\n      [%s: %s]", ops->name, note);
    else if (ops && !ops->phase[list[k]])
      fprintf(out, "\n      [%s: nothing to do here]", ops->name);
    fprintf(out, "\n");
  }
}

void sim_explain(const scene_t *s, int nranks, FILE *out) {
  plan_t plan;
  char err[512];
  int dims[3];
  if (plan_build(&plan, s, err, sizeof err)) {
    fprintf(out, "cannot plan this scene: %s\n", err);
    return;
  }
  if (decomp_dims(s, nranks, dims, err, sizeof err)) {
    fprintf(out, "cannot plan this scene: %s\n", err);
    plan_release(&plan);
    return;
  }
  const backend_ops_t *ops = sim_backend_ops(s->backend, nranks);
  fprintf(out, "Step plan for scene '%s' (%s)\n", s->name, s->file);
  fprintf(out,
          "decomposition: %d MPI rank(s) as %d x %d x %d subdomains of %g x %g x %g%s; ghost "
          "cutoff %g\n",
          nranks, dims[0], dims[1], dims[2], (s->box_hi[0] - s->box_lo[0]) / dims[0],
          (s->box_hi[1] - s->box_lo[1]) / dims[1], (s->box_hi[2] - s->box_lo[2]) / dims[2],
          s->balance.cuts == SCENE_CUTS_COST ? " on average" : "", plan.rcut);
  if (nranks > 1 && s->balance.cuts == SCENE_CUTS_COST) {
    fprintf(out,
            "load balancing: cuts placed by particle weight before the set-up (frozen particle "
            "weight %g; a restart keeps its checkpoint's cuts)",
            scene_frozen_weight(s));
    if (s->balance.every > 0)
      fprintf(out,
              "; every %ld steps the busy-time imbalance is measured and the cuts move above %g%s",
              s->balance.every, s->balance.threshold,
              s->backend == SCENE_BACKEND_CUDA ? " (not on the GPU backend: not measured)" : "");
    fprintf(out, "\n");
  }
  fprintf(out, "periodic: x %s, y %s, z %s; dt = %g; backend: %s\n", s->periodic[0] ? "yes" : "no",
          s->periodic[1] ? "yes" : "no", s->periodic[2] ? "yes" : "no", s->dt,
          ops ? ops->name : "cuda (not in this build)");
  fprintf(out, "set-up (forces of the first configuration), %d phases:\n", plan.n_setup);
  print_list(s, &plan, ops, 1, out);
  fprintf(out, "every step, %d phases:\n", plan.n_step);
  print_list(s, &plan, ops, 0, out);
  if (s->flood.on) {
    const scene_flood_t *f = &s->flood;
    const char ax = (char)('x' + f->axis);
    fprintf(out,
            "after the step (flood, run/run_flood.c): at step %ld the %s on the injection side "
            "(%c from %g round to %g) becomes %s; after every later step the %s in the sink %c in "
            "[%g, %g) does (%s); census of the sample %c in [%g, %g) every %ld steps (particles "
            "read on the host)%s\n",
            f->start, s->species[f->defending].name, ax, f->sink_lo, f->sample_lo,
            s->species[f->invading].name, s->species[f->defending].name, ax, f->sink_lo, f->sink_hi,
            ops && ops->recolor ? "on the device" : "on the host particles", ax, f->sample_lo,
            f->sample_hi, f->every, f->map_every > 0 ? "; saturation maps" : "");
  }
  print_memory(s, &plan, ops, nranks, dims, out);
  plan_release(&plan);
}
