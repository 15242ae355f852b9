/* Loading a scene file with the registered effects (the scene parser is generic; the effects'
 * names, option parsers and checks come from the registry). */
#ifndef MESO_EFFECTS_SCENE_LOAD_H
#define MESO_EFFECTS_SCENE_LOAD_H

#include "scene/scene.h"

/* Parse and validate a scene file. On error prints "FILE:LINE:COL: key 'K': expected ..." to
 * stderr and returns non-zero. Every rank may call it (the file is small). */
int scene_load(const char *path, scene_t *scene);

#endif
