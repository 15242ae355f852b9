/* The help of a subcommand: usage, a one-line purpose and a table of options, printed short
 * (--help, -h: the common options, within an 80 x 24 terminal) or whole (--help-all: every option
 * with its range and default, for a pager), wrapped at 80 columns, ending with the line
 * "More: docs/PAGE.md ..." (docs/architecture.md; ctest cli_help_docs checks every command). */
#ifndef MDPORE_COMMON_CLI_HELP_H
#define MDPORE_COMMON_CLI_HELP_H

#include <stdio.h>

#define CLI_HELP_WIDTH 80

/* A numeric macro as text inside a help string: "(default " CLI_HELP_STR(ROWS) ")". */
#define CLI_HELP_STR(x) CLI_HELP_STR_(x)
#define CLI_HELP_STR_(x) #x

/* One row of an options table. name NULL: a heading printed before the rows that follow it (in
 * --help-all only). A table ends with a row whose name and text are both NULL. */
typedef struct {
  const char *name; /* as the user types it, with its value: "--axis A" */
  const char *text; /* what it does, its range and default: one paragraph, wrapped when printed */
  int common;       /* 1: --help shows it too */
} cli_help_option_t;

typedef struct {
  const char *command; /* "permeability", "image drainage": named in the pointer to --help-all */
  const char *usage;   /* the usage lines, printed as they are (each within 80 columns) */
  const char *purpose; /* one line: what the command does */
  const char *about;   /* --help-all: more paragraphs ('\n' between them), or NULL */
  const cli_help_option_t *options;  /* the command's own options */
  const cli_help_option_t *options2; /* a second table (the image readers' options), or NULL */
  const char *notes;                 /* --help-all, after the options: exit status, or NULL */
  const char *more;                  /* the docs pages: "docs/permeability.md, docs/tutorial.md" */
  int name_width;                    /* columns of the option names before their text (0: 18) */
} cli_help_page_t;

enum { CLI_HELP_NONE = 0, CLI_HELP_SHORT = 1, CLI_HELP_ALL = 2 };

/* CLI_HELP_SHORT for --help and -h, CLI_HELP_ALL for --help-all, else CLI_HELP_NONE. */
int cli_help_flag(const char *arg);

/* The page, short (CLI_HELP_SHORT) or whole (CLI_HELP_ALL). */
void cli_help_print(FILE *to, const cli_help_page_t *page, int which);

#endif
