/* TEMPORARY until the morph branch is merged: a weak mdp_image_morph_at that says it is missing. */
#include <stdio.h>

#include "mdpore_image.h"

__attribute__((weak)) int mdp_image_morph_at(const mdp_image_t *img, const mdp_morph_opts_t *o,
                                             double target_snw, uint8_t nw_label, mdp_image_t *out,
                                             mdp_morph_step_t *achieved, char *err) {
  (void)img, (void)o, (void)target_snw, (void)nw_label, (void)out, (void)achieved;
  snprintf(err, MDP_IMAGE_ERR_LEN, "morphological drainage not built in (morph branch)");
  return -1;
}
