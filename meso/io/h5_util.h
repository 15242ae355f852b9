/* Small helpers over the serial HDF5 C API: scalar/vector attributes and whole 1D/2D datasets. */
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

#endif
