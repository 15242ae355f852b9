/* `mdpore fit relperm TABLE`: Corey and LET fits of a relative-permeability table, the law choice,
 * the JSON report, the SWOF export (docs/relperm.md section 5). Called by cmd_fit with argv[0] =
 * "relperm". */
#ifndef MDPORE_UPSCALE_CMD_FIT_RELPERM_H
#define MDPORE_UPSCALE_CMD_FIT_RELPERM_H

int cmd_fit_relperm(int argc, char **argv);

#endif
