/* Command-line options shared by every command that reads an image (mdpore image, mdpore foam):
 * how to read it (--dims, --type, --labels, ...) and what to do to it (--crop, --downsample,
 * --pad). */
#ifndef MDPORE_IMAGE_CLI_H
#define MDPORE_IMAGE_CLI_H

#include "common/cli_help.h"
#include "mdpore_image.h"

#include <stdio.h>

typedef struct {
  mdp_image_read_opts_t read;
  int crop_lo[3], crop_hi[3], crop; /* half-open [lo, hi) per axis */
  int downsample;                   /* 0/1 = none */
  int pad[6], pad_label;            /* pad_label -1 = the smallest pore label */
  int mirror[3]; /* --mirror: axes followed by their reflection (mdp_image_mirror) */
} mdp_image_cli_t;

void mdp_image_cli_init(mdp_image_cli_t *c);
/* If argv[*i] is one of the shared options, consume it (and its value), advance *i and return 1;
 * return 0 when it is not one of them, -1 (with err) on a bad value. */
int mdp_image_cli_parse(int argc, char **argv, int *i, mdp_image_cli_t *c, char *err);
/* Read path and apply crop, then downsample, then pad. */
int mdp_image_cli_load(const char *path, const mdp_image_cli_t *c, mdp_image_t *img, char *err);
/* The shared options' rows for a command's help (cli_help_page_t.options2). */
extern const cli_help_option_t mdp_image_cli_options[];

/* mdpore image drainage (image_cli_drainage.c): argv[0] = "drainage". */
int cmd_image_drainage(int argc, char **argv);

#endif
