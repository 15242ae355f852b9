/* Shared by the fuzz entries of tests/fuzz (docs/fuzzing.md). Each entry defines
 * LLVMFuzzerTestOneInput: it writes the input to a file in a private temporary folder, calls one
 * reader, and checks the outcome with fuzz_outcome(): either the reader accepted the input, or it
 * refused it with a message that names the file. Anything else (a crash, a hang, a sanitizer report,
 * a refusal without a message naming the file) is a finding. The same entries run under libFuzzer
 * (MDPORE_FUZZ builds) and under replay_main.c (every build: the corpus replay ctests). */
#ifndef MDPORE_TESTS_FUZZ_UTIL_H
#define MDPORE_TESTS_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Called once by LLVMFuzzerInitialize, before any input: an entry that needs a process-wide start
 * (MPI) defines it; the default does nothing. */
void fuzz_target_init(void);

/* The private folder (created on first use, removed at exit) and a file in it holding bytes. */
const char *fuzz_dir(void);
void fuzz_path(const char *name, char *out, size_t len);
void fuzz_write(const char *path, const void *data, size_t size);

/* Split the input into argv tokens, one a line (a NUL ends a token too; a last token without a
 * newline counts), after argv[0] = argv0: at most max - 1 entries (the rest of the input is
 * ignored), argv[argc] = NULL. The tokens live in a buffer kept until the next call. Returns argc. */
int fuzz_argv(const uint8_t *data, size_t size, const char *argv0, char **argv, int max);

/* Capture what the reader prints on stderr between begin and end (end returns the text, kept until
 * the next begin). */
void fuzz_capture_begin(void);
const char *fuzz_capture_end(void);

/* Record the outcome of one input: rc 0 accepted; otherwise `message` must be non-empty and name
 * `path` (else the input is reported and the process aborts, which libFuzzer records as a crash).
 * In replay mode the message is printed, so the ctest log shows every refusal. */
void fuzz_outcome(int rc, const char *message, const char *path);

/* Set by fuzz_outcome: 1 accepted, 0 refused (read by replay_main.c). */
extern int fuzz_last_accepted;
/* 1 under replay_main.c. */
extern int fuzz_replay_mode;

#endif
