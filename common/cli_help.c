/* The short and the full help of a subcommand from one table of options (cli_help.h). */
#include "cli_help.h"

#include <string.h>

enum { DEFAULT_NAME_WIDTH = 18, NAME_INDENT = 2 };

int cli_help_flag(const char *arg) {
  if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) return CLI_HELP_SHORT;
  if (!strcmp(arg, "--help-all")) return CLI_HELP_ALL;
  return CLI_HELP_NONE;
}

/* The words of text from column col (where the cursor is), a line broken before a word that would
 * pass CLI_HELP_WIDTH, continuation lines starting at column indent; a '\n' in text breaks the
 * line there. Ends the line. */
static void wrap(FILE *to, const char *text, int col, int indent) {
  int words_on_line = 0;
  for (const char *p = text; *p;) {
    if (*p == ' ') {
      p++;
      continue;
    }
    if (*p == '\n') {
      fprintf(to, "\n%*s", indent, "");
      col = indent, words_on_line = 0, p++;
      continue;
    }
    const int len = (int)strcspn(p, " \n");
    if (words_on_line && col + 1 + len > CLI_HELP_WIDTH) {
      fprintf(to, "\n%*s", indent, "");
      col = indent, words_on_line = 0;
    }
    if (words_on_line) fputc(' ', to), col++;
    fwrite(p, 1, (size_t)len, to);
    col += len, words_on_line++, p += len;
  }
  fputc('\n', to);
}

/* "  NAME  text...": the text from column NAME_INDENT + width + 2, or after the name when the name
 * is wider. */
static void print_option(FILE *to, const cli_help_option_t *o, int width) {
  const int text_col = NAME_INDENT + width + 2;
  int col = fprintf(to, "%*s%s", NAME_INDENT, "", o->name);
  col += fprintf(to, "%*s", col + 2 > text_col ? 2 : text_col - col, "");
  wrap(to, o->text, col, text_col);
}

static int is_end(const cli_help_option_t *o) {
  return !o->name && !o->text;
}

/* Prints the rows of a table that `which` shows; returns how many options it holds. */
static int print_table(FILE *to, const cli_help_option_t *table, int width, int which, int *shown) {
  int n = 0;
  for (const cli_help_option_t *o = table; o && !is_end(o); o++) {
    if (!o->name) {
      if (which == CLI_HELP_ALL) wrap(to, o->text, 0, 0);
      continue;
    }
    n += o->name[0] == '-'; /* an option, not an operand such as INPUT */
    if (which == CLI_HELP_ALL || o->common) print_option(to, o, width), (*shown)++;
  }
  return n;
}

void cli_help_print(FILE *to, const cli_help_page_t *page, int which) {
  const int width = page->name_width > 0 ? page->name_width : DEFAULT_NAME_WIDTH;
  fputs(page->usage, to);
  wrap(to, page->purpose, 0, 0);
  if (which == CLI_HELP_ALL && page->about) wrap(to, page->about, 0, 0);
  int shown = 0;
  const int n = print_table(to, page->options, width, which, &shown) +
                print_table(to, page->options2, width, which, &shown);
  if (which == CLI_HELP_ALL && page->notes) wrap(to, page->notes, 0, 0);
  /* the short form says where the rest is, when there is more */
  if (which != CLI_HELP_ALL && n > shown)
    fprintf(to, "All %d options and the details: mdpore %s --help-all\n", n, page->command);
  else if (which != CLI_HELP_ALL && (page->about || page->notes))
    fprintf(to, "The details: mdpore %s --help-all\n", page->command);
  /* the pointer to the docs, with the pointer to the list of commands where it fits */
  static const char *const list = " (mdpore --help lists every command)";
  if (strlen("More: ") + strlen(page->more) + strlen(list) <= CLI_HELP_WIDTH)
    fprintf(to, "More: %s%s\n", page->more, list);
  else
    fprintf(to, "More: %s\n", page->more);
}
