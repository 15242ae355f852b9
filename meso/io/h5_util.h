/* Small helpers over the serial HDF5 C API: scalar/vector attributes, whole 1D/2D datasets and
 * appendable time-series tables (thermo and flux logs). */
#ifndef MESO_IO_H5_UTIL_H
#define MESO_IO_H5_UTIL_H

#include <hdf5.h>
#include <stddef.h>

void h5_attr_double(hid_t loc, const char *name, const double *v, hsize_t n);
void h5_attr_long(hid_t loc, const char *name, long v);
void h5_attr_u64(hid_t loc, const char *name, unsigned long long v);
void h5_attr_string(hid_t loc, const char *name, const char *v);
int h5_read_attr_double(hid_t loc, const char *name, double *v, hsize_t n);
int h5_read_attr_long(hid_t loc, const char *name, long *v);
int h5_read_attr_u64(hid_t loc, const char *name, unsigned long long *v);
int h5_read_attr_string(hid_t loc, const char *name, char *v, size_t len);
/* Dataset of n rows x m columns (m == 1: 1D). 0 or -1. */
int h5_write_dataset(hid_t loc, const char *name, hid_t type, const void *data, hsize_t n,
                     hsize_t m);
/* Read a dataset that must have n x m values; messages name `file` and the dataset. 0 or -1. */
int h5_read_dataset(hid_t loc, const char *name, hid_t type, void *data, hsize_t n, hsize_t m,
                    const char *file);
/* Rows of a 1D or 2D dataset, or -1 when absent. */
long h5_dataset_rows(hid_t loc, const char *name);
/* A time-series table: an empty, extendible 0 x ncol double dataset (chunks of 256 rows), or -1. */
hid_t h5_create_row_table(hid_t loc, const char *name, hsize_t ncol);
/* Append one row of ncol doubles at row index `rows` (the table's current length) and flush the
 * file, so that a killed run keeps every row written so far. */
void h5_append_row(hid_t file, hid_t dset, long rows, hsize_t ncol, const double *row);

#endif
