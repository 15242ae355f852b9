/* The flow-data table: the contract between pore-scale campaigns and `mdpore fit`
 * (format documented in docs/flow-table.md). */
#ifndef MDPORE_UPSCALE_FLOW_TABLE_H
#define MDPORE_UPSCALE_FLOW_TABLE_H

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
  double *G;            /* driving gradient (pressure gradient -dp/dx or body force per volume) */
  double *q;            /* superficial (Darcy) velocity */
  double *sigma;        /* standard error of q (block-averaged) */
  double *run_length;   /* length of the run that produced the row (steps or time) */
  int *line;            /* file line of each row, for messages */
} flow_table;

/* Reads and validates a table. On error writes "FILE:LINE: column ...: expected ..., got ..." (or a
 * whole-file reason) into err and returns -1. */
int flow_table_read(const char *path, flow_table *t, char *err, int errlen);
void flow_table_free(flow_table *t);

#endif
