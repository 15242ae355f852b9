/* Host/device qualifiers and the floating-point type of the shared pair physics.
 * Every header in meso/physics is plain C99 that compiles unchanged as CUDA device code:
 * no globals, no allocation, no I/O, no host-only library calls. */
#ifndef MESO_PHYSICS_HD_H
#define MESO_PHYSICS_HD_H

#ifdef __CUDACC__
#define MESO_HD static __host__ __device__ __forceinline__
#else
#define MESO_HD static inline
#endif

/* meso_real: the type of the pair math. The CPU path uses double; the CUDA path defines
 * MESO_REAL_FLOAT (single precision, the default there) unless built with MDPORE_DOUBLE. */
#include <float.h>
#ifdef MESO_REAL_FLOAT
typedef float meso_real;
#define MESO_R(x) x##f
#define meso_sqrt sqrtf
#define MESO_R_MIN_NORMAL FLT_MIN /* the smallest normal meso_real */
#else
typedef double meso_real;
#define MESO_R(x) x
#define meso_sqrt sqrt
#define MESO_R_MIN_NORMAL DBL_MIN
#endif

#define MESO_PI 3.14159265358979323846

/* Most species a scene may declare (sizes the per-species tables of the plan and the device). */
#define MESO_MAX_SPECIES 8

#endif
