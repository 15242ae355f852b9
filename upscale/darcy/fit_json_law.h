/* Reads one fitted law from a `mdpore fit` JSON file (read with libyaml: the JSON is YAML flow
 * style). */
#ifndef MDPORE_UPSCALE_FIT_JSON_LAW_H
#define MDPORE_UPSCALE_FIT_JSON_LAW_H

#include "law/flow_law.h"

/* model: "chosen" or a law name. Fills law, the fit's unit system (1 SI, 0 reduced) and fluid.
 * Returns 0, or -1 after printing "FILE:LINE:COL: key 'k': expected ... (got ...)" to stderr
 * (nothing printed when quiet). */
int fit_json_law(const char *path, const char *model, flow_law *law, int *si,
                 fluid_props *fit_fluid, int quiet);

#endif
