/* Test-only fault injection for the step guards (docs/stability.md): the environment variable
 * MDPORE_TEST_FAULT=KIND:STEP:ID, read once when mdpore run starts, damages particle ID just
 * before step STEP on the rank that owns it, so that the tests can trigger guards that a healthy
 * physics run cannot reach on demand:
 *   nan_velocity  v_x = NaN            -> the non-finite check of the drift
 *   nan_position  x_x = NaN            -> the non-finite check of the drift
 *   jump          x_x += 3 box lengths -> lost: farther than a neighbour subdomain (or the box)
 *   remove        dropped from storage -> the global particle count changed
 * Unset, the run loop pays one branch per step on an integer. The value faults (nan_velocity,
 * nan_position, jump) work on both backends: they go through sim_fault_write, a device write of
 * one value on the CUDA backend (the particles live on the GPU between steps); remove works on the
 * CPU backend only (refused on CUDA). Not for users. */
#ifndef MESO_RUN_FAULT_H
#define MESO_RUN_FAULT_H

#include <stdint.h>

#include "engine/sim.h"

enum {
  RUN_FAULT_NONE = 0,
  RUN_FAULT_NAN_VELOCITY,
  RUN_FAULT_NAN_POSITION,
  RUN_FAULT_JUMP,
  RUN_FAULT_REMOVE
};

typedef struct {
  int kind; /* RUN_FAULT_*; NONE when the variable is unset */
  long step;
  int64_t id;
} run_fault_t;

/* Reads MDPORE_TEST_FAULT. 0 (also when unset), or -1 after a message on rank 0 (a bad value, or
 * a backend that cannot take it). */
int run_fault_init(run_fault_t *f, const sim_t *sim, int rank);

/* Damages the particle on the rank that owns it (call only when step == f->step). 0, or -1 when
 * the device write failed (message printed). */
int run_fault_apply(const run_fault_t *f, sim_t *sim);

#endif
