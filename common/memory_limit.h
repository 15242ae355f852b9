/* The bytes one process may allocate for a user's input: MDPORE_MEMORY_LIMIT (bytes) when set, else
 * the machine's physical memory. Readers compare their 64-bit size estimate with it before a large
 * allocation and refuse with a message naming the file and key (image readers, darcy config). */
#ifndef COMMON_MEMORY_LIMIT_H
#define COMMON_MEMORY_LIMIT_H

double mdp_memory_limit(void);

#endif
