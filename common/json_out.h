/* A small streaming JSON writer: enough for mdpore's summaries (objects, arrays, numbers, strings).
 * Commas and indentation are handled here so callers only name keys and values. */
#ifndef MDPORE_UPSCALE_JSON_OUT_H
#define MDPORE_UPSCALE_JSON_OUT_H

#include <stdio.h>

#define JSON_MAX_DEPTH 32

typedef struct {
  FILE *f;
  int depth;
  int count[JSON_MAX_DEPTH]; /* items written so far at each nesting level */
} json_out;

void json_begin(json_out *j, FILE *f);          /* opens the top-level object */
void json_end(json_out *j);                     /* closes it and writes a newline */
void json_object(json_out *j, const char *key); /* key NULL inside arrays */
void json_object_end(json_out *j);
void json_array(json_out *j, const char *key);
void json_array_end(json_out *j);
void json_number(json_out *j, const char *key, double v); /* non-finite values become null */
void json_int(json_out *j, const char *key, long long v);
void json_string(json_out *j, const char *key, const char *s);
void json_bool(json_out *j, const char *key, int v);
void json_null(json_out *j, const char *key);
/* A compact one-line array of numbers. */
void json_numbers(json_out *j, const char *key, const double *v, int n);

#endif
