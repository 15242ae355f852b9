/* scene_load: the generic scene parser with the effects of the registry. */
#include "effects/scene_load.h"
#include "effects/effect.h"

int scene_load(const char *path, scene_t *scene) {
  return scene_parse_file(path, effect_catalog(), scene);
}
