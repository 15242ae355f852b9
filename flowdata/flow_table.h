/* The flow-data table: the contract between pore-scale campaigns, `mdpore fit` and coupling/
 * (format documented in docs/flow-table.md). One reader and one writer, shared by all of them. */
#ifndef MDPORE_FLOWDATA_FLOW_TABLE_H
#define MDPORE_FLOWDATA_FLOW_TABLE_H

typedef struct {
  char path[1024];
  char sample[256];
  char axis[16];
  char length_unit[64];
  char driving_column[32]; /* "pressure_gradient" or "body_force_density" (same quantity: G =
                              -dp/dx) */
  int si;                  /* 1: SI units, 0: reduced (DPD) units */
  double viscosity, density;
  double voxel_size;    /* NAN when not given */
  double length_unit_m; /* metres per length unit (reduced tables), NAN when not given */
  int n;                /* number of data rows */
  int capacity;         /* rows allocated in G, q, sigma, run_length and line */
  double *G;            /* driving gradient (pressure gradient -dp/dx or body force per volume) */
  double *q;            /* superficial (Darcy) velocity */
  double *sigma;        /* standard error of q (block-averaged) */
  double *run_length;   /* length of the run that produced the row (steps or time) */
  int *line;            /* file line of each row, for messages (0 for rows added in memory) */
  int n_comments;       /* free header comments (provenance notes), in file order */
  char **comments;      /* their text without the leading '#', trimmed; "key: value" lines with
                           keys that are not metadata are kept here too */
} flow_table;

/* Reads and validates a table. On error writes "FILE:LINE: column ...: expected ..., got ..." (or a
 * whole-file reason) into err and returns -1. */
int flow_table_read(const char *path, flow_table *t, char *err, int errlen);

/* An empty table to fill in memory: no rows, no metadata, driving column "pressure_gradient",
 * reduced units, voxel_size and length_unit_m NAN (not given). */
void flow_table_init(flow_table *t);
/* Appends one data row (line 0). Returns -1 when out of memory. */
int flow_table_add_row(flow_table *t, double G, double q, double sigma, double run_length);
/* Appends one free header comment (copied). Returns -1 when out of memory. */
int flow_table_add_comment(flow_table *t, const char *text);

/* Writes the table to `path` in the format flow_table_read reads, atomically (temporary file in the
 * same folder, then rename): the format line, every metadata line (optional ones only when given),
 * the free comments, the column line and the rows, numbers as %.17g so that reading the file back
 * gives the same doubles bit for bit. Refuses (returns -1, err names the row, column or key, and
 * `path` is left untouched) a table the reader would refuse: no rows, a non-finite or subnormal
 * value, a non-positive standard error or run length, missing or invalid metadata. */
int flow_table_write(const char *path, const flow_table *t, char *err, int errlen);

/* Frees the rows and comments; the table is empty afterwards. */
void flow_table_free(flow_table *t);

#endif
