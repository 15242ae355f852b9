/* Small text helpers shared by the line-oriented readers (raw-image sidecars, flow tables, the slip
 * fit's CSV). */
#ifndef MDPORE_COMMON_TEXT_H
#define MDPORE_COMMON_TEXT_H

/* s without its leading and trailing white space (trailing space cut in place). */
char *text_trim(char *s);

/* The whole file at path as one NUL-terminated string (malloc'd, the caller frees), or NULL when it
 * cannot be opened or memory runs out. For small text files: manifests, reports. */
char *text_read_file(const char *path);

#endif
