/* Flow-table writer and reader (flowdata/): write -> read gives every double back bit for bit and
 * keeps metadata and comments; the sample tables given as arguments survive read -> write -> read;
 * the writer refuses, with a message naming the row, column or key, what the reader would refuse,
 * and leaves the target file untouched then; the reader refuses a metadata key given twice, naming
 * both lines. Usage: test_flow_table [SAMPLE.csv ...] */
#include "flowdata/flow_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int failures = 0;
#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      failures++;                                                                                  \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                              \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
    }                                                                                              \
  } while (0)

static char err[2048];

/* Same bits (so -0.0 differs from 0.0, and NAN equals the same NAN). */
static int same_bits(double a, double b) {
  return !memcmp(&a, &b, sizeof a);
}

/* Everything a table holds except its path and source lines must agree bit for bit. */
static void check_same(const flow_table *a, const flow_table *b, const char *what) {
  CHECK(!strcmp(a->sample, b->sample), "%s: sample '%s' vs '%s'", what, a->sample, b->sample);
  CHECK(!strcmp(a->axis, b->axis), "%s: axis '%s' vs '%s'", what, a->axis, b->axis);
  CHECK(!strcmp(a->length_unit, b->length_unit), "%s: length_unit", what);
  CHECK(!strcmp(a->driving_column, b->driving_column), "%s: driving column '%s' vs '%s'", what,
        a->driving_column, b->driving_column);
  CHECK(a->si == b->si, "%s: si %d vs %d", what, a->si, b->si);
  CHECK(same_bits(a->viscosity, b->viscosity), "%s: viscosity", what);
  CHECK(same_bits(a->density, b->density), "%s: density", what);
  CHECK(same_bits(a->voxel_size, b->voxel_size), "%s: voxel_size %.17g vs %.17g", what,
        a->voxel_size, b->voxel_size);
  CHECK(same_bits(a->length_unit_m, b->length_unit_m), "%s: length_unit_m %.17g vs %.17g", what,
        a->length_unit_m, b->length_unit_m);
  CHECK(a->n_comments == b->n_comments, "%s: %d vs %d comments", what, a->n_comments,
        b->n_comments);
  for (int c = 0; c < a->n_comments && c < b->n_comments; c++)
    CHECK(!strcmp(a->comments[c], b->comments[c]), "%s: comment %d '%s' vs '%s'", what, c,
          a->comments[c], b->comments[c]);
  CHECK(a->n == b->n, "%s: %d vs %d rows", what, a->n, b->n);
  for (int r = 0; r < a->n && r < b->n; r++) {
    CHECK(same_bits(a->G[r], b->G[r]), "%s: row %d G %.17g vs %.17g", what, r, a->G[r], b->G[r]);
    CHECK(same_bits(a->q[r], b->q[r]), "%s: row %d q %.17g vs %.17g", what, r, a->q[r], b->q[r]);
    CHECK(same_bits(a->sigma[r], b->sigma[r]), "%s: row %d sigma", what, r);
    CHECK(same_bits(a->run_length[r], b->run_length[r]), "%s: row %d run_length", what, r);
  }
}

static int file_exists(const char *path) {
  return access(path, F_OK) == 0;
}

/* The temporary file of an atomic write must not outlive it. */
static void check_no_temporary(const char *path) {
  char tmp[1200];
  snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
  CHECK(!file_exists(tmp), "temporary %s left behind", tmp);
}

/* A table of awkward doubles (not short in decimal, tiny, huge, negative zero) with all metadata.
 */
static void make_table(flow_table *t) {
  flow_table_init(t);
  snprintf(t->sample, sizeof t->sample, "roundtrip sample: slit h=8");
  snprintf(t->axis, sizeof t->axis, "y");
  snprintf(t->length_unit, sizeof t->length_unit, "rc");
  t->viscosity = 1.0 / 3.0;
  t->density = 6.000000000000001;
  t->voxel_size = 0.1 + 0.2;
  t->length_unit_m = 8.2e-10;
  flow_table_add_comment(t, "written by test_flow_table");
  flow_table_add_comment(t, "");
  flow_table_add_comment(t, "note: a key that is not metadata stays a comment");
  const double G[] = {-0.0, 1e-300, M_PI, 1.7976931348623157e308, 2.2250738585072014e-308};
  const double q[] = {0.0, -1e-300, 1.0 / 7.0, -123456789.123456789, 0.30000000000000004};
  for (int r = 0; r < 5; r++)
    CHECK(flow_table_add_row(t, G[r], q[r], 1e-5 * (r + 1) / 3.0, 200000 + r / 3.0) == 0,
          "add_row");
}

static void test_roundtrip(void) {
  flow_table t, back;
  make_table(&t);
  const char *path = "roundtrip.csv";
  remove(path);
  CHECK(flow_table_write(path, &t, err, sizeof err) == 0, "%s", err);
  check_no_temporary(path);
  CHECK(flow_table_read(path, &back, err, sizeof err) == 0, "%s", err);
  check_same(&t, &back, "write -> read");
  CHECK(back.line[0] == 14,
        "first row on line %d (14 expected: format line, 8 metadata lines, 3 "
        "comments, column line)",
        back.line[0]);
  flow_table_free(&back);

  /* reduced -> SI, optional metadata left out, body force as the driving column */
  t.si = 1;
  t.voxel_size = NAN;
  t.length_unit_m = NAN;
  snprintf(t.length_unit, sizeof t.length_unit, "m");
  snprintf(t.driving_column, sizeof t.driving_column, "body_force_density");
  CHECK(flow_table_write(path, &t, err, sizeof err) == 0, "%s", err);
  CHECK(flow_table_read(path, &back, err, sizeof err) == 0, "%s", err);
  check_same(&t, &back, "SI, no optional metadata, body force");
  flow_table_free(&back);
  flow_table_free(&t);
  CHECK(t.n == 0 && t.n_comments == 0 && !t.G && !t.comments, "free leaves an empty table");
}

/* A table from the repository: read, write, read again; the two reads must agree. */
static void test_sample(const char *sample) {
  flow_table a, b;
  if (flow_table_read(sample, &a, err, sizeof err)) {
    CHECK(0, "%s", err);
    return;
  }
  CHECK(a.n > 0, "%s: no rows", sample);
  CHECK(a.n_comments > 0, "%s: free comments expected in the sample table", sample);
  const char *path = "sample_rewritten.csv";
  CHECK(flow_table_write(path, &a, err, sizeof err) == 0, "%s", err);
  CHECK(flow_table_read(path, &b, err, sizeof err) == 0, "%s", err);
  check_same(&a, &b, sample);
  printf("%s: %d rows, %d comments: read -> write -> read identical\n", sample, a.n, a.n_comments);
  flow_table_free(&a);
  flow_table_free(&b);
}

/* The writer must refuse, with all `texts` in the message, and leave `path` as it was. */
static void check_refused(const flow_table *t, const char *what, const char *const *texts) {
  const char *path = "refused.csv";
  FILE *f = fopen(path, "w");
  fputs("old content\n", f);
  fclose(f);
  err[0] = 0;
  CHECK(flow_table_write(path, t, err, sizeof err) != 0, "%s: the writer accepted it", what);
  for (const char *const *s = texts; *s; s++)
    CHECK(strstr(err, *s), "%s: message '%s' lacks '%s'", what, err, *s);
  char buf[64] = "";
  f = fopen(path, "r");
  CHECK(f && fgets(buf, sizeof buf, f) && !strcmp(buf, "old content\n"),
        "%s: target changed to '%s'", what, buf);
  if (f) fclose(f);
  check_no_temporary(path);
  printf("refused (%s): %s\n", what, err);
}

static void test_refusals(void) {
  flow_table t;
  make_table(&t);
  t.q[2] = NAN;
  check_refused(&t, "NaN velocity", (const char *const[]){"row 3", "'darcy_velocity'", NULL});
  t.q[2] = 0.5;
  t.G[4] = -INFINITY;
  check_refused(&t, "infinite gradient",
                (const char *const[]){"row 5", "'pressure_gradient'", NULL});
  t.G[4] = 1;
  t.run_length[0] = 0;
  check_refused(&t, "zero run length", (const char *const[]){"row 1", "'run_length'", NULL});
  t.run_length[0] = 1;
  t.sigma[1] = 4e-320;
  check_refused(&t, "subnormal stderr",
                (const char *const[]){"row 2", "'darcy_velocity_stderr'", "subnormal", NULL});
  t.sigma[1] = 1e-5;
  t.viscosity = INFINITY;
  check_refused(&t, "infinite viscosity", (const char *const[]){"'viscosity'", NULL});
  t.viscosity = 1;
  t.voxel_size = 0;
  check_refused(&t, "zero voxel size", (const char *const[]){"'voxel_size'", "positive", NULL});
  t.voxel_size = NAN;
  snprintf(t.axis, sizeof t.axis, "w");
  check_refused(&t, "bad axis", (const char *const[]){"'axis'", "'w'", NULL});
  snprintf(t.axis, sizeof t.axis, "x");
  t.sample[0] = 0;
  check_refused(&t, "no sample", (const char *const[]){"'sample'", "empty", NULL});
  snprintf(t.sample, sizeof t.sample, "s");
  flow_table_add_comment(&t, "density: 7");
  check_refused(&t, "comment that is metadata",
                (const char *const[]){"comment 4", "metadata 'density'", NULL});
  free(t.comments[--t.n_comments]);
  CHECK(flow_table_write("refused_ok.csv", &t, err, sizeof err) == 0, "repaired table: %s", err);
  int n = t.n;
  t.n = 0;
  check_refused(&t, "zero rows", (const char *const[]){"no data rows", NULL});
  t.n = n;
  flow_table_free(&t);

  flow_table empty;
  flow_table_init(&empty);
  check_refused(&empty, "empty table", (const char *const[]){"no data rows", NULL});
}

/* The reader must refuse `content` with all `texts` in its message. */
static void check_read_refused(const char *path, const char *content, const char *const *texts) {
  FILE *f = fopen(path, "w");
  fputs(content, f);
  fclose(f);
  flow_table t;
  err[0] = 0;
  CHECK(flow_table_read(path, &t, err, sizeof err) != 0, "%s: the reader accepted it", path);
  for (const char *const *s = texts; *s; s++)
    CHECK(strstr(err, *s), "%s: message '%s' lacks '%s'", path, err, *s);
  printf("read refused (%s): %s\n", path, err);
}

/* A metadata key given twice is an error naming both lines, whether the values differ or not, in
 * the header or between the rows (a later line must never override an earlier one silently). */
static void test_duplicate_keys(void) {
#define HEAD_A "# mdpore flow table v1\n# sample: s\n# axis: x\n# unit_system: reduced\n"
#define HEAD_B "# length_unit: rc\n# viscosity: 1.2\n# density: 6\n"
#define COLS_ROWS                                                                                  \
  "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n0.1,0.004,1e-4,1\n"
  check_read_refused("dup_viscosity.csv", HEAD_A HEAD_B "# viscosity: 4.8\n" COLS_ROWS,
                     (const char *const[]){"dup_viscosity.csv:8: key 'viscosity' given again "
                                           "(first at line 6)",
                                           NULL});
  check_read_refused("dup_sample_same.csv", HEAD_A "#   sample :  s\n" HEAD_B COLS_ROWS,
                     (const char *const[]){"dup_sample_same.csv:5: key 'sample' given again "
                                           "(first at line 2)",
                                           NULL});
  check_read_refused("dup_between_rows.csv",
                     HEAD_A HEAD_B COLS_ROWS "# unit_system: SI\n0.2,0.008,1e-4,1\n",
                     (const char *const[]){"dup_between_rows.csv:10: key 'unit_system' given "
                                           "again (first at line 4)",
                                           NULL});
  /* keys that are not metadata may repeat: they are free comments */
  FILE *f = fopen("repeated_comment.csv", "w");
  fputs(HEAD_A "# note: a\n# note: b\n" HEAD_B COLS_ROWS, f);
  fclose(f);
  flow_table t;
  CHECK(flow_table_read("repeated_comment.csv", &t, err, sizeof err) == 0, "%s", err);
  CHECK(t.n_comments == 2, "two free comments expected, got %d", t.n_comments);
  flow_table_free(&t);
#undef HEAD_A
#undef HEAD_B
#undef COLS_ROWS
}

int main(int argc, char **argv) {
  test_roundtrip();
  test_duplicate_keys();
  for (int i = 1; i < argc; i++) test_sample(argv[i]);
  test_refusals();
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("flow table writer/reader: all checks passed\n");
  return 0;
}
