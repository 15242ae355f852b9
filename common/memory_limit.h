/* How much memory a process may use. mdp_memory_limit: the bytes one process may allocate for a
 * user's input (MDPORE_MEMORY_LIMIT when set, else the machine's physical memory); readers compare
 * their 64-bit size estimate with it before a large allocation and refuse with a message naming the
 * file and key (image readers, darcy config). mdp_memory_available: the memory free for a run now
 * (the memory plan of mdpore run, meso/engine/memory_plan.h). */
#ifndef COMMON_MEMORY_LIMIT_H
#define COMMON_MEMORY_LIMIT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

double mdp_memory_limit(void);

/* A byte count: a number with an optional suffix K, M, G or T (powers of 1024; "64M", "1.5G",
 * "100000000"). -1 when it is not a finite number > 0 with nothing after it. */
double mdp_parse_bytes(const char *text);

/* The memory a run can count on now, in bytes: the smallest of MemAvailable (/proc/meminfo), the
 * cgroup's limit less what the cgroup uses beyond its inactive file cache (cgroup v2 memory.max,
 * v1 memory.limit_in_bytes; where one is set) and MDPORE_MEMORY_LIMIT. `from` (len bytes) names
 * the one that set it ("MemAvailable", "cgroup memory.max", "MDPORE_MEMORY_LIMIT"). 1e18 and
 * "unknown" when none could be read. */
double mdp_memory_available(char *from, size_t len);

#ifdef __cplusplus
}
#endif

#endif
