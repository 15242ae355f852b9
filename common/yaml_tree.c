/* Typed, position-aware reading of a libyaml document (see yaml_tree.h). */
#include "common/yaml_tree.h"
#include "common/memory_limit.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Limits of what yt_load reads: configuration files are small and shallow. Deeper nesting or a
 * larger file is refused before libyaml builds a tree (its time grows with the square of the depth
 * of nested flow collections). */
enum { YT_MAX_DEPTH = 64 };
#define YT_MAX_BYTES (64L << 20)
/* What libyaml's tree holds per node (a list, mapping or value), beyond the value's text: the node
 * (about 100 bytes, in an array grown by doubling), its tag and value strings (at least a small
 * allocation each) and its entry in the parent's item array. Measured: a flow list of 4.2 million
 * zeros (an 8 MB file) took 1.05 GB of resident memory once loaded, 250 bytes a node. */
#define YT_BYTES_PER_NODE 320.0

/* A first pass over the events: the nesting depth, and the nodes and their text counted against the
 * memory limit (common/memory_limit.h), until the end of the first document. Syntax errors are left
 * to the loading pass, which reports them. 0, or -1 after a message. */
static int check_depth(FILE *fp, const char *path, int quiet) {
  yaml_parser_t p;
  yaml_event_t e;
  int depth = 0, rc = 0;
  double nodes = 0, text = 0;
  yaml_parser_initialize(&p);
  yaml_parser_set_input_file(&p, fp);
  while (yaml_parser_parse(&p, &e)) {
    const yaml_event_type_t type = e.type;
    if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT) {
      if (++depth > YT_MAX_DEPTH) {
        if (!quiet)
          fprintf(stderr,
                  "%s:%lu:%lu: lists and mappings nested %d deep (expected at most %d levels)\n",
                  path, (unsigned long)e.start_mark.line + 1,
                  (unsigned long)e.start_mark.column + 1, depth, YT_MAX_DEPTH);
        rc = -1;
      }
    } else if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT) {
      depth--;
    }
    if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT ||
        type == YAML_SCALAR_EVENT)
      nodes++;
    if (type == YAML_SCALAR_EVENT) text += (double)e.data.scalar.length + 1;
    yaml_event_delete(&e);
    if (rc || type == YAML_DOCUMENT_END_EVENT || type == YAML_STREAM_END_EVENT) break;
  }
  yaml_parser_delete(&p);
  rewind(fp);
  const double need = nodes * YT_BYTES_PER_NODE + text, limit = mdp_memory_limit();
  if (!rc && need > limit) {
    if (!quiet)
      fprintf(stderr,
              "%s: %.4g lists, mappings and values need about %.3g GB once parsed (%g bytes "
              "each), more than the %.3g GB this machine allows (physical memory, or "
              "MDPORE_MEMORY_LIMIT in bytes; expected a configuration file)\n",
              path, nodes, need / 1e9, YT_BYTES_PER_NODE, limit / 1e9);
    rc = -1;
  }
  return rc;
}

int yt_load(ytree_t *t, const char *path, int quiet) {
  memset(t, 0, sizeof *t);
  t->file = path;
  t->quiet = quiet;
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    if (!quiet)
      fprintf(stderr, "%s: cannot open: %s (expected a readable file)\n", path, strerror(errno));
    return -1;
  }
  long size = -1;
  if (fseek(fp, 0, SEEK_END) == 0) size = ftell(fp);
  rewind(fp);
  if (size > YT_MAX_BYTES) {
    if (!quiet)
      fprintf(stderr, "%s: %ld bytes (expected a configuration file of at most %ld bytes)\n", path,
              size, YT_MAX_BYTES);
    fclose(fp);
    return -1;
  }
  if (check_depth(fp, path, quiet)) {
    fclose(fp);
    return -1;
  }
  yaml_parser_t parser;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_file(&parser, fp);
  int ok = yaml_parser_load(&parser, &t->doc);
  if (!ok) {
    if (!quiet)
      fprintf(stderr, "%s:%lu:%lu: YAML syntax error: %s%s%s (expected well-formed YAML)\n", path,
              (unsigned long)parser.problem_mark.line + 1,
              (unsigned long)parser.problem_mark.column + 1,
              parser.problem ? parser.problem : "unknown problem", parser.context ? " " : "",
              parser.context ? parser.context : "");
  }
  yaml_parser_delete(&parser);
  fclose(fp);
  if (!ok) return -1;
  if (!yaml_document_get_root_node(&t->doc)) {
    if (!quiet) fprintf(stderr, "%s:1:1: the file is empty (expected a mapping of keys)\n", path);
    yaml_document_delete(&t->doc);
    return -1;
  }
  return 0;
}

void yt_free(ytree_t *t) {
  yaml_document_delete(&t->doc);
}

yaml_node_t *yt_root(ytree_t *t) {
  return yaml_document_get_root_node(&t->doc);
}

static void vreport(const ytree_t *t, const yaml_node_t *at, const char *path, const char *kind,
                    const char *fmt, va_list ap) {
  if (t->quiet) return;
  unsigned long line = at ? (unsigned long)at->start_mark.line + 1 : 1;
  unsigned long col = at ? (unsigned long)at->start_mark.column + 1 : 1;
  fprintf(stderr, "%s:%lu:%lu: %skey '%s': ", t->file, line, col, kind,
          path && *path ? path : "(top)");
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
}

int yt_error(const ytree_t *t, const yaml_node_t *at, const char *path, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vreport(t, at, path, "", fmt, ap);
  va_end(ap);
  return -1;
}

int yt_warn(const ytree_t *t, const yaml_node_t *at, const char *path, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vreport(t, at, path, "warning: ", fmt, ap);
  va_end(ap);
  return 0;
}

const char *yt_describe(const yaml_node_t *n, char *buf, int len) {
  if (!n) return "nothing";
  if (n->type == YAML_MAPPING_NODE) return "a mapping";
  if (n->type == YAML_SEQUENCE_NODE) return "a list";
  if (yt_is_null(n)) return "an empty value";
  snprintf(buf, (size_t)len, "'%.*s'",
           (int)(n->data.scalar.length > 40 ? 40 : n->data.scalar.length),
           (const char *)n->data.scalar.value);
  return buf;
}

int yt_is_null(const yaml_node_t *n) {
  if (!n || n->type != YAML_SCALAR_NODE) return 0;
  if (n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE) return 0;
  const char *s = (const char *)n->data.scalar.value;
  return !*s || !strcmp(s, "~") || !strcasecmp(s, "null");
}

int yt_expect_map(const ytree_t *t, yaml_node_t *n, const char *path) {
  char b[64];
  if (n && n->type == YAML_MAPPING_NODE) return 0;
  return yt_error(t, n, path, "expected a mapping of keys (got %s)", yt_describe(n, b, sizeof b));
}

int yt_expect_seq(const ytree_t *t, yaml_node_t *n, const char *path) {
  char b[64];
  if (n && n->type == YAML_SEQUENCE_NODE) return 0;
  return yt_error(t, n, path, "expected a list (got %s)", yt_describe(n, b, sizeof b));
}

int yt_map_size(const yaml_node_t *map) {
  return (int)(map->data.mapping.pairs.top - map->data.mapping.pairs.start);
}

const char *yt_map_key(ytree_t *t, yaml_node_t *map, int i, yaml_node_t **key_node) {
  yaml_node_t *k = yaml_document_get_node(&t->doc, map->data.mapping.pairs.start[i].key);
  if (key_node) *key_node = k;
  return k && k->type == YAML_SCALAR_NODE ? (const char *)k->data.scalar.value : NULL;
}

yaml_node_t *yt_map_value(ytree_t *t, yaml_node_t *map, int i) {
  return yaml_document_get_node(&t->doc, map->data.mapping.pairs.start[i].value);
}

int yt_seq_size(const yaml_node_t *seq) {
  return (int)(seq->data.sequence.items.top - seq->data.sequence.items.start);
}

yaml_node_t *yt_seq_item(ytree_t *t, yaml_node_t *seq, int i) {
  return yaml_document_get_node(&t->doc, seq->data.sequence.items.start[i]);
}

/* 1 when key i of a mapping equals an earlier key of it. */
static int repeats_earlier_key(ytree_t *t, yaml_node_t *map, int i, const char *key) {
  for (int j = 0; j < i; j++) {
    const char *other = yt_map_key(t, map, j, NULL);
    if (other && !strcmp(other, key)) return 1;
  }
  return 0;
}

void yt_record_keys(const char *path, const char *const *allowed, int any_other) {
  const char *log = getenv("MDPORE_KEY_LOG");
  if (!log || !*log) return;
  FILE *f = fopen(log, "a");
  if (!f) return;
  fprintf(f, "%s\t", path);
  for (int a = 0; allowed && allowed[a]; a++) fprintf(f, "%s%s", a ? " " : "", allowed[a]);
  fprintf(f, "%s%s\n", allowed && allowed[0] && any_other ? " " : "", any_other ? "*" : "");
  fclose(f);
}

int yt_check_keys(const ytree_t *t, yaml_node_t *map, const char *path,
                  const char *const *allowed) {
  ytree_t *tm = (ytree_t *)t;
  yt_record_keys(path, allowed, !allowed);
  if (yt_expect_map(t, map, path)) return -1;
  const int n = yt_map_size(map);
  for (int i = 0; i < n; i++) {
    yaml_node_t *kn;
    const char *key = yt_map_key(tm, map, i, &kn);
    char sub[512];
    if (!key)
      return yt_error(t, kn, path, "expected plain text keys (got a mapping or list as a key)");
    snprintf(sub, sizeof sub, "%s%s%s", path, *path ? "." : "", key);
    int known = !allowed; /* NULL: any key */
    for (int a = 0; allowed && allowed[a]; a++) known |= !strcmp(allowed[a], key);
    if (!known) {
      char list[512] = "";
      for (int a = 0; allowed[a]; a++) {
        strncat(list, a ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, allowed[a], sizeof list - strlen(list) - 1);
      }
      return yt_error(t, kn, sub, "unknown key (expected one of: %s)", list);
    }
    if (repeats_earlier_key(tm, map, i, key))
      return yt_error(t, kn, sub, "expected each key once (got a duplicate)");
  }
  return 0;
}

yaml_node_t *yt_get(ytree_t *t, yaml_node_t *map, const char *key) {
  if (!map || map->type != YAML_MAPPING_NODE) return NULL;
  const int n = yt_map_size(map);
  for (int i = 0; i < n; i++) {
    const char *k = yt_map_key(t, map, i, NULL);
    if (k && !strcmp(k, key)) return yt_map_value(t, map, i);
  }
  return NULL;
}

yaml_node_t *yt_need(ytree_t *t, yaml_node_t *map, const char *key, const char *path,
                     const char *what) {
  yaml_node_t *v = yt_get(t, map, key);
  if (!v) yt_error(t, map, path, "expected %s (the key is missing)", what);
  return v;
}

static const char *scalar(const yaml_node_t *n) {
  return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

int yt_double(const ytree_t *t, yaml_node_t *n, const char *path, double *out) {
  char b[64];
  const char *s = scalar(n);
  if (s && *s && n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) {
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (!*end && !errno && isfinite(v)) {
      *out = v;
      return 0;
    }
  }
  return yt_error(t, n, path, "expected a number (got %s)", yt_describe(n, b, sizeof b));
}

int yt_long(const ytree_t *t, yaml_node_t *n, const char *path, long *out) {
  char b[64];
  const char *s = scalar(n);
  if (s && *s && n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) {
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (!*end && !errno) {
      *out = v;
      return 0;
    }
    /* Accept integral numbers written as 1e5. */
    double d = strtod(s, &end);
    if (!*end && isfinite(d) && d == floor(d) && fabs(d) < 9e18) {
      *out = (long)d;
      return 0;
    }
  }
  return yt_error(t, n, path, "expected an integer (got %s)", yt_describe(n, b, sizeof b));
}

int yt_bool(const ytree_t *t, yaml_node_t *n, const char *path, int *out) {
  char b[64];
  const char *s = scalar(n);
  if (s && n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) {
    static const char *yes[] = {"true", "yes", "on"}, *no[] = {"false", "no", "off"};
    for (int i = 0; i < 3; i++) {
      if (!strcasecmp(s, yes[i])) return (*out = 1), 0;
      if (!strcasecmp(s, no[i])) return (*out = 0), 0;
    }
  }
  return yt_error(t, n, path, "expected true or false (got %s)", yt_describe(n, b, sizeof b));
}

int yt_string(const ytree_t *t, yaml_node_t *n, const char *path, char *out, int len) {
  char b[64];
  const char *s = scalar(n);
  if (!s || yt_is_null(n))
    return yt_error(t, n, path, "expected a text value (got %s)", yt_describe(n, b, sizeof b));
  if ((int)strlen(s) >= len)
    return yt_error(t, n, path, "expected at most %d characters (got %d)", len - 1, (int)strlen(s));
  strcpy(out, s);
  return 0;
}

static int seq3(ytree_t *t, yaml_node_t *n, const char *path, const char *what) {
  char b[64];
  if (n && n->type == YAML_SEQUENCE_NODE && yt_seq_size(n) == 3) return 0;
  if (n && n->type == YAML_SEQUENCE_NODE)
    return yt_error(t, n, path, "expected a list of 3 %s (got a list of %d)", what, yt_seq_size(n));
  return yt_error(t, n, path, "expected a list of 3 %s (got %s)", what,
                  yt_describe(n, b, sizeof b));
}

int yt_vec3(ytree_t *t, yaml_node_t *n, const char *path, double out[3]) {
  if (seq3(t, n, path, "numbers")) return -1;
  for (int i = 0; i < 3; i++) {
    char sub[512];
    snprintf(sub, sizeof sub, "%s[%d]", path, i);
    if (yt_double(t, yt_seq_item(t, n, i), sub, &out[i])) return -1;
  }
  return 0;
}

int yt_bool3(ytree_t *t, yaml_node_t *n, const char *path, int out[3]) {
  if (seq3(t, n, path, "true/false values")) return -1;
  for (int i = 0; i < 3; i++) {
    char sub[512];
    snprintf(sub, sizeof sub, "%s[%d]", path, i);
    if (yt_bool(t, yt_seq_item(t, n, i), sub, &out[i])) return -1;
  }
  return 0;
}

int yt_int3(ytree_t *t, yaml_node_t *n, const char *path, int out[3]) {
  if (seq3(t, n, path, "integers")) return -1;
  for (int i = 0; i < 3; i++) {
    char sub[512];
    long v = 0;
    snprintf(sub, sizeof sub, "%s[%d]", path, i);
    if (yt_long(t, yt_seq_item(t, n, i), sub, &v)) return -1;
    if (v < INT_MIN || v > INT_MAX)
      return yt_error(t, yt_seq_item(t, n, i), sub,
                      "expected an integer of at most %d in size (got %ld)", INT_MAX, v);
    out[i] = (int)v;
  }
  return 0;
}

int yt_enum(const ytree_t *t, yaml_node_t *n, const char *path, const char *const *words) {
  char b[64];
  const char *s = scalar(n);
  if (s)
    for (int i = 0; words[i]; i++)
      if (!strcmp(s, words[i])) return i;
  char list[256] = "";
  for (int i = 0; words[i]; i++) {
    strncat(list, i ? " | " : "", sizeof list - strlen(list) - 1);
    strncat(list, words[i], sizeof list - strlen(list) - 1);
  }
  yt_error(t, n, path, "expected %s (got %s)", list, yt_describe(n, b, sizeof b));
  return -1;
}
