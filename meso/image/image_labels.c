/* Label maps: which label values are pore, organic and inorganic solid. */
#include "mdpore_image.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int phase_by_name(const char *s, size_t len) {
  static const char *names[] = {"pore", "organic", "inorganic"};
  for (int p = 0; p < 3; p++)
    if (strlen(names[p]) == len && !strncmp(s, names[p], len)) return p;
  return -1;
}

/* Grammar: item (',' | ';' item)*, item = [phase '='] value ['-' value]; a value without "phase="
 * keeps the phase named last, so "pore=0,organic=2,inorganic=1,3-5" maps 1, 3, 4 and 5 to
 * inorganic. */
int mdp_image_parse_labels(const char *text, uint8_t phase_of[256], char *err) {
  memset(phase_of, MDP_PHASE_UNSET, 256);
  int phase = -1;
  const char *s = text;
  while (*s) {
    while (*s == ' ' || *s == ',' || *s == ';') s++;
    if (!*s) break;
    const char *eq = s;
    while (*eq && isalpha((unsigned char)*eq)) eq++;
    if (eq != s) {
      if (*eq != '=') {
        snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': expected 'phase=value' at '%s'", text, s);
        return 1;
      }
      phase = phase_by_name(s, (size_t)(eq - s));
      if (phase < 0) {
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "label map '%s': unknown phase '%.*s' (expected pore, organic or inorganic)", text,
                 (int)(eq - s), s);
        return 1;
      }
      s = eq + 1;
    }
    if (phase < 0) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': a value before any 'phase=' at '%s'", text,
               s);
      return 1;
    }
    char *end;
    long lo = strtol(s, &end, 10), hi = lo;
    if (end == s) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': expected a label value at '%s'", text, s);
      return 1;
    }
    s = end;
    if (*s == '-') {
      hi = strtol(s + 1, &end, 10);
      if (end == s + 1) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': expected a range end at '%s'", text, s);
        return 1;
      }
      s = end;
    }
    if (lo < 0 || hi > 255 || lo > hi) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': value %ld-%ld outside 0..255", text, lo,
               hi);
      return 1;
    }
    for (long v = lo; v <= hi; v++) {
      if (phase_of[v] != MDP_PHASE_UNSET && phase_of[v] != phase) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': value %ld is given to both %s and %s",
                 text, v, mdp_phase_name(phase_of[v]), mdp_phase_name(phase));
        return 1;
      }
      phase_of[v] = (uint8_t)phase;
    }
    if (*s && *s != ',' && *s != ';' && *s != ' ') {
      snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': unexpected '%c'", text, *s);
      return 1;
    }
  }
  int any_pore = 0;
  for (int v = 0; v < 256; v++) any_pore |= phase_of[v] == MDP_PHASE_PORE;
  if (!any_pore) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "label map '%s': no value is mapped to pore", text);
    return 1;
  }
  return 0;
}

void mdp_image_format_labels(const uint8_t phase_of[256], char *out, size_t len) {
  size_t n = 0;
  out[0] = 0;
  for (int p = 0; p < 3; p++) {
    int first = 1;
    for (int v = 0; v < 256; v++) {
      if (phase_of[v] != p) continue;
      int hi = v;
      while (hi + 1 < 256 && phase_of[hi + 1] == p) hi++;
      int w;
      if (first)
        w = snprintf(out + n, len - n, "%s%s=", n ? ";" : "", mdp_phase_name(p));
      else
        w = snprintf(out + n, len - n, ",");
      if (w < 0 || (size_t)w >= len - n) return;
      n += (size_t)w;
      w = hi > v ? snprintf(out + n, len - n, "%d-%d", v, hi) : snprintf(out + n, len - n, "%d", v);
      if (w < 0 || (size_t)w >= len - n) return;
      n += (size_t)w;
      first = 0;
      v = hi;
    }
  }
}

int mdp_image_check_labels(const mdp_image_t *img, const char *source, char *err) {
  size_t n = mdp_image_count(img);
  for (size_t idx = 0; idx < n; idx++) {
    if (img->phase_of[img->label[idx]] != MDP_PHASE_UNSET) continue;
    int i = (int)(idx % (size_t)img->nx), j = (int)(idx / (size_t)img->nx % (size_t)img->ny);
    int k = (int)(idx / ((size_t)img->nx * (size_t)img->ny));
    char map[512];
    mdp_image_format_labels(img->phase_of, map, sizeof map);
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: voxel (%d,%d,%d) has label %d, which the label map '%s' does not name "
             "(give it with --labels, e.g. --labels pore=0,inorganic=1,%d)",
             source, i, j, k, img->label[idx], map, img->label[idx]);
    return 1;
  }
  return 0;
}
