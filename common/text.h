/* Small text helpers shared by the line-oriented readers (raw-image sidecars, flow tables, the slip
 * fit's CSV). */
#ifndef MDPORE_COMMON_TEXT_H
#define MDPORE_COMMON_TEXT_H

/* s without its leading and trailing white space (trailing space cut in place). */
char *text_trim(char *s);

/* The whole file at path as one NUL-terminated string (malloc'd, the caller frees), or NULL when it
 * cannot be opened, memory runs out, or (errno EFBIG) twice its size is more than the memory limit
 * (common/memory_limit.h), checked before anything is allocated. For small text files: manifests,
 * reports. */
char *text_read_file(const char *path);

#endif
