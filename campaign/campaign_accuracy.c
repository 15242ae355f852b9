/* `mdpore permeability --accuracy fast|balanced|precise`: presets of the run settings that trade
 * accuracy for time, taken from the measured error-against-time table of validation/accuracy
 * (docs/accuracy.md: one knob at a time on a 107,741-particle sphere array, H100, against a
 * reference kappa = 0.02927 +- 0.37%). Options given explicitly (--dt, --target-error,
 * --max-steps) win over a preset. */
#include <stdio.h>
#include <string.h>

#include "campaign.h"

typedef struct {
  const char *name;
  double dt;           /* run.dt */
  double target_error; /* run.target_error: the averaging window, stopped by the flux's error */
  long long max_steps; /* run.steps: the budget */
  const char *measured;
} accuracy_preset;

/* The cheapest settings found for each target (docs/accuracy.md, "Results", the paragraph
 * "Cheapest settings found"):
 *   10%: dt 0.01 with a 10 tau window met it (1.5 s on the H100); the preset allows 50 tau;
 *    3%: dt 0.01 with a 40 tau window met it (2.5 s); the preset allows 200 tau and asks 3%;
 *    1%: dt 0.005 with a 640 tau window met it (-0.11 +- 0.79% against the reference, 38.7 s on
 *        the H100; seed 12, so not the reference's own draw): its flux error bar was 0.70%, which
 *        the preset asks as its target error, within a budget of 2000 tau. */
static const accuracy_preset presets[] = {
    {"fast", 0.01, 0.10, 5000, "10% target: met by a 10 tau window at dt 0.01"},
    {"balanced", 0.01, 0.03, 20000, "3% target: met by a 40 tau window at dt 0.01"},
    {"precise", 0.005, 0.007, 400000,
     "1% target: met by dt 0.005 with a 640 tau window, whose flux error bar was 0.70%"},
};

int camp_accuracy_preset(const char *name, camp_opts *o, int dt_given, int error_given,
                         int steps_given) {
  for (size_t i = 0; i < sizeof presets / sizeof *presets; i++) {
    const accuracy_preset *p = &presets[i];
    if (strcmp(name, p->name)) continue;
    if (!dt_given) o->dt = p->dt;
    if (!error_given) o->target_error = p->target_error;
    if (!steps_given) o->max_steps = p->max_steps;
    fprintf(stderr,
            "mdpore permeability: --accuracy %s: dt %g, target error %g, at most %lld steps per "
            "run (%s; docs/accuracy.md)\n",
            p->name, o->dt, o->target_error, o->max_steps, p->measured);
    return 0;
  }
  fprintf(stderr, "mdpore permeability: --accuracy: expected fast, balanced or precise, got '%s'\n",
          name);
  return -1;
}
