/* libyaml document helpers (see yaml_doc.h). */
#include "yaml_doc.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ydoc_line(const yaml_node_t *n) {
  return n ? (int)n->start_mark.line + 1 : 0;
}

int ydoc_fail(ydoc *y, const yaml_node_t *at, const char *fmt, ...) {
  if (y->failed) return -1; /* keep the first error */
  char msg[768];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (at)
    snprintf(y->err, y->errlen, "%s:%d: %s", y->path, ydoc_line(at), msg);
  else
    snprintf(y->err, y->errlen, "%s: %s", y->path, msg);
  y->failed = 1;
  return -1;
}

yaml_node_t *ydoc_load(ydoc *y, const char *path, char *err, int errlen) {
  memset(y, 0, sizeof *y);
  y->path = path;
  y->err = err;
  y->errlen = errlen;
  FILE *f = fopen(path, "rb");
  if (!f) {
    ydoc_fail(y, NULL, "cannot open: %s", strerror(errno));
    return NULL;
  }
  yaml_parser_t parser;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_file(&parser, f);
  int ok = yaml_parser_load(&parser, &y->doc);
  if (!ok)
    ydoc_fail(y, NULL, "line %d: YAML syntax error: %s", (int)parser.problem_mark.line + 1,
              parser.problem ? parser.problem : "?");
  yaml_parser_delete(&parser);
  fclose(f);
  if (!ok) return NULL;
  yaml_node_t *root = yaml_document_get_root_node(&y->doc);
  if (!root || root->type != YAML_MAPPING_NODE) {
    ydoc_fail(y, root, "expected a mapping (key: value) at the top level");
    return NULL;
  }
  return root;
}

void ydoc_free(ydoc *y) {
  yaml_document_delete(&y->doc);
}

int ydoc_is_map(const yaml_node_t *n) {
  return n && n->type == YAML_MAPPING_NODE;
}
int ydoc_is_seq(const yaml_node_t *n) {
  return n && n->type == YAML_SEQUENCE_NODE;
}
int ydoc_seq_len(const yaml_node_t *n) {
  return ydoc_is_seq(n) ? (int)(n->data.sequence.items.top - n->data.sequence.items.start) : 0;
}
yaml_node_t *ydoc_seq_item(ydoc *y, const yaml_node_t *seq, int i) {
  return yaml_document_get_node(&y->doc, seq->data.sequence.items.start[i]);
}

static const char *scalar(const yaml_node_t *n) {
  return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

yaml_node_t *ydoc_get(ydoc *y, const yaml_node_t *map, const char *key) {
  if (!ydoc_is_map(map)) return NULL;
  for (yaml_node_pair_t *pr = map->data.mapping.pairs.start; pr < map->data.mapping.pairs.top;
       pr++) {
    const char *k = scalar(yaml_document_get_node(&y->doc, pr->key));
    if (k && !strcmp(k, key)) return yaml_document_get_node(&y->doc, pr->value);
  }
  return NULL;
}

int ydoc_only_keys(ydoc *y, const yaml_node_t *map, const char *what, const char *const *keys) {
  if (!ydoc_is_map(map)) return ydoc_fail(y, map, "%s: expected a mapping", what);
  for (yaml_node_pair_t *pr = map->data.mapping.pairs.start; pr < map->data.mapping.pairs.top;
       pr++) {
    yaml_node_t *kn = yaml_document_get_node(&y->doc, pr->key);
    const char *k = scalar(kn);
    int known = 0;
    for (int i = 0; k && keys[i]; i++) known |= !strcmp(k, keys[i]);
    if (!known) {
      char list[512] = "";
      int len = 0;
      for (int i = 0; keys[i]; i++)
        len += snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", keys[i]);
      return ydoc_fail(y, kn, "%s: unknown key '%s' (expected one of: %s)", what, k ? k : "?",
                       list);
    }
  }
  return 0;
}

int ydoc_node_number(ydoc *y, const yaml_node_t *n, const char *what, double *v) {
  const char *s = scalar(n);
  char *end = NULL;
  if (s) {
    errno = 0;
    *v = strtod(s, &end);
  }
  if (!s || !*s || *end || errno == ERANGE || !isfinite(*v))
    return ydoc_fail(y, n, "%s: expected a number, got '%s'", what, s ? s : "(not a scalar)");
  return 0;
}

int ydoc_number(ydoc *y, const yaml_node_t *map, const char *key, double *v) {
  yaml_node_t *n = ydoc_get(y, map, key);
  if (!n) return ydoc_fail(y, map, "missing key '%s' (a number)", key);
  char what[128];
  snprintf(what, sizeof what, "key '%s'", key);
  return ydoc_node_number(y, n, what, v);
}

int ydoc_int(ydoc *y, const yaml_node_t *map, const char *key, long *v) {
  double d;
  if (ydoc_number(y, map, key, &d)) return -1;
  if (d != floor(d))
    return ydoc_fail(y, ydoc_get(y, map, key), "key '%s': expected an integer", key);
  *v = (long)d;
  return 0;
}

const char *ydoc_string(ydoc *y, const yaml_node_t *map, const char *key) {
  yaml_node_t *n = ydoc_get(y, map, key);
  const char *s = scalar(n);
  if (!n)
    ydoc_fail(y, map, "missing key '%s' (a string)", key);
  else if (!s)
    ydoc_fail(y, n, "key '%s': expected a string", key);
  return s;
}
