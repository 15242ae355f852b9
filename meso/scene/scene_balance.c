/* The `balance:` block (scene_balance.h). */
#include "scene/scene_balance.h"

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

void scene_balance_defaults(scene_t *s) {
  s->balance.cuts = SCENE_CUTS_UNIFORM;
  s->balance.frozen_weight = SCENE_FROZEN_WEIGHT_CPU; /* the GPU's: engine/sim.c */
  s->balance.frozen_weight_given = 0;
  s->balance.every = 0;
  s->balance.threshold = 1.05;
}

int scene_parse_balance(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"cuts", "frozen_weight", "every", "threshold", NULL};
  TRY(yt_check_keys(t, n, "balance", keys));
  scene_balance_t *b = &s->balance;
  yaml_node_t *v;
  if ((v = yt_get(t, n, "cuts"))) {
    static const char *const words[] = {"uniform", "cost", NULL};
    const int k = yt_enum(t, v, "balance.cuts", words);
    if (k < 0) return -1;
    b->cuts = k == 1 ? SCENE_CUTS_COST : SCENE_CUTS_UNIFORM;
  }
  if ((v = yt_get(t, n, "frozen_weight"))) {
    TRY(yt_double(t, v, "balance.frozen_weight", &b->frozen_weight));
    b->frozen_weight_given = 1;
    if (!(b->frozen_weight >= 0 && b->frozen_weight <= 10))
      return yt_error(t, v, "balance.frozen_weight",
                      "expected the cost of a frozen (wall) particle relative to a mobile one, "
                      "0 to 10 (got %g)",
                      b->frozen_weight);
  }
  if ((v = yt_get(t, n, "every"))) {
    TRY(yt_long(t, v, "balance.every", &b->every));
    if (b->every < 0)
      return yt_error(t, v, "balance.every",
                      "expected steps >= 0 between checks of the measured imbalance (0: the cuts "
                      "never move after the start) (got %ld)",
                      b->every);
  }
  if ((v = yt_get(t, n, "threshold"))) {
    TRY(yt_double(t, v, "balance.threshold", &b->threshold));
    if (!(b->threshold >= 1.0 && b->threshold <= 100))
      return yt_error(t, v, "balance.threshold",
                      "expected an imbalance factor (max / mean busy time over the ranks) of 1 to "
                      "100 above which the cuts move (got %g)",
                      b->threshold);
  }
  if (b->every > 0 && b->cuts != SCENE_CUTS_COST)
    return yt_error(
        t, n, "balance.every",
        "expected balance.cuts: cost as well (moving cuts are placed by measured cost)");
  return 0;
}
