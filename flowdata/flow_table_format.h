/* Names the flow-table reader and writer share (docs/flow-table.md); internal to flowdata/. */
#ifndef MDPORE_FLOWDATA_FLOW_TABLE_FORMAT_H
#define MDPORE_FLOWDATA_FLOW_TABLE_FORMAT_H

/* First line the writer puts in every table; the reader takes it as the format line, not as a free
 * comment. */
#define FLOW_TABLE_FORMAT_LINE "mdpore flow table v1"
/* Longest line the reader accepts, newline included. */
#define FLOW_TABLE_MAX_LINE 8192

enum { FLOW_COL_G, FLOW_COL_Q, FLOW_COL_SIGMA, FLOW_COL_RUN, FLOW_NCOLS };
/* Required column names, in the order the writer writes them (FLOW_COL_G may also be named
 * "body_force_density"). */
extern const char *const flow_table_columns[FLOW_NCOLS];
/* Metadata keys of "# key: value" header lines: the text ones (sample, axis, length_unit,
 * unit_system), then the numeric ones (viscosity, density, voxel_size, length_unit_m). */
extern const char *const flow_table_text_keys[4];
extern const char *const flow_table_num_keys[4];

/* printf-style message into err (errlen bytes); returns -1 (the reader's and writer's errors). */
int flow_table_fail(char *err, int errlen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
