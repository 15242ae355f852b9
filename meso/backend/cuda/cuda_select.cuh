/* Slot selection on the device with CUB, over the slot numbers: by a predicate (DeviceSelect::If:
 * the boundary slots of several ranks, cuda_halo_device.cu), a partition by a predicate
 * (DevicePartition::If: one rank's mobile slots, then the frozen ones, for the density and force
 * passes, cuda_force.cu) and by a flag array (DeviceSelect::Flagged: cuda_select_slots,
 * cuda_util.cu). Each is queued on the default stream, its count left on the device, the shared
 * scratch (g->select_tmp) grown as needed. */
#ifndef MESO_BACKEND_CUDA_SELECT_CUH
#define MESO_BACKEND_CUDA_SELECT_CUH

#include "cuda_state.cuh"

#include <cub/device/device_partition.cuh>
#include <cub/device/device_select.cuh>
#include <thrust/iterator/counting_iterator.h>

/* run(tmp, bytes): one CUB device call; first asked for its scratch size (tmp NULL), then run in
 * the shared scratch. 0 or -1. */
template <class Run> static int cuda_cub_call(struct cuda_sim *g, Run run, const char *what) {
  size_t need = 0;
  run(NULL, need);
  if (cuda_select_room(g, need)) return -1;
  size_t tmp = g->select_tmp_bytes;
  return cuda_check(run(g->select_tmp, tmp), what);
}

/* The slots i < n with pred(i) true, in slot order, into out; their count into *count_dev. */
template <class Pred>
static int cuda_select_slots_if(struct cuda_sim *g, Pred pred, int *out, int *count_dev, int n,
                                const char *what) {
  const thrust::counting_iterator<int> slots(0);
  return cuda_cub_call(
      g,
      [&](void *tmp, size_t &bytes) {
        return cub::DeviceSelect::If(tmp, bytes, slots, out, count_dev, n, pred);
      },
      what);
}

/* All n slots into out: those with pred(i) true first, in slot order, their count into *count_dev;
 * the others after them, in reverse slot order. */
template <class Pred>
static int cuda_partition_slots_if(struct cuda_sim *g, Pred pred, int *out, int *count_dev, int n,
                                   const char *what) {
  const thrust::counting_iterator<int> slots(0);
  return cuda_cub_call(
      g,
      [&](void *tmp, size_t &bytes) {
        return cub::DevicePartition::If(tmp, bytes, slots, out, count_dev, n, pred);
      },
      what);
}

#endif
