/* Streaming JSON writer (see json_out.h). Output is valid JSON and also plain YAML flow style with
 * ": " separators, so libyaml can read it back (upscale/fit/fit_json_read.c relies on that). */
#include "json_out.h"

#include <math.h>

static void indent(json_out *j) {
  for (int i = 0; i < j->depth; i++) fputs("  ", j->f);
}

static void string_literal(FILE *f, const char *s) {
  fputc('"', f);
  for (; s && *s; s++) {
    unsigned char c = (unsigned char)*s;
    if (c == '"' || c == '\\')
      fprintf(f, "\\%c", c);
    else if (c == '\n')
      fputs("\\n", f);
    else if (c == '\t')
      fputs("\\t", f);
    else if (c < 0x20)
      fprintf(f, "\\u%04x", c);
    else
      fputc(c, f);
  }
  fputc('"', f);
}

/* Writes the separator, newline, indentation and "key": for the next item. */
static void item(json_out *j, const char *key) {
  if (j->count[j->depth]++ > 0) fputc(',', j->f);
  fputc('\n', j->f);
  indent(j);
  if (key) {
    string_literal(j->f, key);
    fputs(": ", j->f);
  }
}

static void open(json_out *j, const char *key, char bracket) {
  item(j, key);
  fputc(bracket, j->f);
  if (j->depth + 1 < JSON_MAX_DEPTH) j->depth++;
  j->count[j->depth] = 0;
}

static void close(json_out *j, char bracket) {
  int had_items = j->count[j->depth] > 0;
  j->depth--;
  if (had_items) {
    fputc('\n', j->f);
    indent(j);
  }
  fputc(bracket, j->f);
}

void json_begin(json_out *j, FILE *f) {
  j->f = f;
  j->depth = 0;
  j->count[0] = 0;
  fputc('{', f);
  j->depth = 1;
  j->count[1] = 0;
}

void json_end(json_out *j) {
  close(j, '}');
  fputc('\n', j->f);
}

void json_object(json_out *j, const char *key) {
  open(j, key, '{');
}
void json_object_end(json_out *j) {
  close(j, '}');
}
void json_array(json_out *j, const char *key) {
  open(j, key, '[');
}
void json_array_end(json_out *j) {
  close(j, ']');
}

static void number_literal(FILE *f, double v) {
  if (isfinite(v))
    fprintf(f, "%.17g", v);
  else
    fputs("null", f);
}

void json_number(json_out *j, const char *key, double v) {
  item(j, key);
  number_literal(j->f, v);
}

void json_int(json_out *j, const char *key, long long v) {
  item(j, key);
  fprintf(j->f, "%lld", v);
}

void json_string(json_out *j, const char *key, const char *s) {
  item(j, key);
  string_literal(j->f, s);
}

void json_bool(json_out *j, const char *key, int v) {
  item(j, key);
  fputs(v ? "true" : "false", j->f);
}

void json_null(json_out *j, const char *key) {
  item(j, key);
  fputs("null", j->f);
}

void json_numbers(json_out *j, const char *key, const double *v, int n) {
  item(j, key);
  fputc('[', j->f);
  for (int i = 0; i < n; i++) {
    if (i) fputs(", ", j->f);
    number_literal(j->f, v[i]);
  }
  fputc(']', j->f);
}
