/* Several one-rank runs at once in one process (run_replicas.h). Each replica is run_scene on its
 * own communicator (a duplicate of MPI_COMM_SELF: collectives of different threads never share
 * one) in its own thread; on a GPU each thread queues on its own default stream (the CUDA backend
 * is compiled with --default-stream per-thread), so the replicas' kernels overlap. What the
 * replicas share is made safe where it is: the HDF5 library behind one lock
 * (common/hdf5_lock.h), the comparator contexts of qsort per thread, stdout's summary blocks one
 * at a time (run_loop.c). The main thread waits and prints one progress line for all. */
#define _GNU_SOURCE
#include "run/run_replicas.h"
#include "common/same_file.h"
#include "run/run_loop.h"

#include <libgen.h>
#include <mpi.h>
#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* A replica thread's stack: run_scene keeps messages and a scene on it */
#define REPLICA_STACK_BYTES (64u << 20)

typedef struct {
  const scene_t *scene;
  MPI_Comm comm;
  int omp_threads;
  run_watch_t watch;
  int rc;
} replica_t;

/* The finished count, under its lock; the main thread waits on the condition. */
static pthread_mutex_t done_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t done_cond = PTHREAD_COND_INITIALIZER;
static int n_done;

static void *replica_main(void *arg) {
  replica_t *r = arg;
#ifdef _OPENMP
  if (r->omp_threads > 0) omp_set_num_threads(r->omp_threads); /* this thread's teams only */
#endif
  r->rc = run_scene_watched(r->scene, r->comm, &r->watch);
  pthread_mutex_lock(&done_lock);
  n_done++;
  pthread_cond_signal(&done_cond);
  pthread_mutex_unlock(&done_lock);
  return NULL;
}

int run_replicas_omp_threads(int n) {
  const char *env = getenv("OMP_NUM_THREADS");
  if (env && *env) return 0;
  cpu_set_t set;
  int cores = 1;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cores = CPU_COUNT(&set);
  const int t = n > 0 ? cores / n : 1;
  return t < 1 ? 1 : t;
}

/* The folder of a scene file ("" for the current one: paths stay as written). */
static void scene_dir(const char *file, char *out, size_t len) {
  char tmp[SCENE_PATH_LEN];
  snprintf(tmp, sizeof tmp, "%s", file);
  const char *d = dirname(tmp);
  snprintf(out, len, "%s", strcmp(d, ".") ? d : "");
}

int run_replicas_prepare(scene_t *scenes, int n) {
  for (int i = 0; i < n; i++) {
    char dir[SCENE_PATH_LEN];
    scene_dir(scenes[i].file, dir, sizeof dir);
    if (dir[0]) run_apply_output_dir(&scenes[i], dir);
    scenes[i].progress = 0;
  }
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      const scene_t *a = &scenes[i], *b = &scenes[j];
      const char *pa[] = {a->summary_path,  a->flux.path, a->thermo.path,  a->checkpoint.path,
                          a->snapshot.path, a->dump.path, a->profile.path, a->flood.path};
      const char *pb[] = {b->summary_path,  b->flux.path, b->thermo.path,  b->checkpoint.path,
                          b->snapshot.path, b->dump.path, b->profile.path, b->flood.path};
      for (size_t u = 0; u < sizeof pa / sizeof *pa; u++)
        for (size_t v = 0; v < sizeof pb / sizeof *pb; v++)
          if (pa[u][0] && pb[v][0] && mdp_same_file(pa[u], pb[v])) {
            fprintf(stderr,
                    "mdpore run --replicas: %s and %s would both write '%s': give each replica "
                    "scene its own folder (its outputs go there)\n",
                    a->file, b->file, pa[u]);
            return -1;
          }
    }
  return 0;
}

/* One line for all replicas on a terminal: steps done of all, and the time left of the slowest
 * (each replica's own rate so far: an early stop only shortens it). */
static void progress_line(const replica_t *r, int n, double t0, int running) {
  double now = MPI_Wtime(), eta = 0;
  long done = 0, total = 0;
  for (int i = 0; i < n; i++) {
    const long first = __atomic_load_n(&r[i].watch.first, __ATOMIC_RELAXED);
    const long last = __atomic_load_n(&r[i].watch.last, __ATOMIC_RELAXED);
    const long step = __atomic_load_n(&r[i].watch.step, __ATOMIC_RELAXED);
    double since;
    __atomic_load(&r[i].watch.t_loop, &since, __ATOMIC_RELAXED);
    if (last <= first) continue;
    total += last - first;
    done += step - first;
    if (step > first && step < last && since > 0) {
      const double left = (now - since) * (double)(last - step) / (double)(step - first);
      if (left > eta) eta = left;
    }
  }
  fprintf(
      stderr,
      "\rreplicas: %d running, steps %ld / %ld (%3.0f%%)  elapsed %.0f s  ETA %02d:%02d:%02d   ",
      running, done, total, total > 0 ? 100.0 * (double)done / (double)total : 0.0, now - t0,
      (int)(eta / 3600), (int)(eta / 60) % 60, (int)eta % 60);
  fflush(stderr);
}

/* Open MPI opens some of its frameworks at their first use, and that first use is not thread-safe
 * (Open MPI 4.1: the topology framework at the first MPI_Cart_create, a crash in
 * mca_base_var_register when two threads race to it). The calls the engine makes on a replica's
 * communicator are made once here, before the threads start. */
static void mpi_first_uses(void) {
  MPI_Comm cart = MPI_COMM_NULL, node = MPI_COMM_NULL;
  int dims[3] = {1, 1, 1}, periodic[3] = {1, 1, 1}, from, to;
  MPI_Cart_create(MPI_COMM_SELF, 3, dims, periodic, 0, &cart);
  if (cart != MPI_COMM_NULL) {
    MPI_Cart_shift(cart, 0, 1, &from, &to);
    MPI_Comm_split_type(cart, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    if (node != MPI_COMM_NULL) MPI_Comm_free(&node);
    MPI_Comm_free(&cart);
  }
}

int run_replicas(scene_t *scenes, int n, int omp_threads) {
  replica_t *r = calloc((size_t)n, sizeof *r);
  pthread_t *tid = calloc((size_t)n, sizeof *tid);
  if (!r || !tid) {
    fprintf(stderr, "mdpore run --replicas: out of memory\n");
    free(r);
    free(tid);
    return 1;
  }
  const int show = isatty(fileno(stderr)); /* (each replica's own line is off: prepare) */
  const double t0 = MPI_Wtime();
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, REPLICA_STACK_BYTES);
  n_done = 0;
  int rc = 0;
  mpi_first_uses();
  for (int i = 0; i < n; i++) {
    r[i].scene = &scenes[i];
    r[i].omp_threads = omp_threads;
    r[i].rc = 1;
    MPI_Comm_dup(MPI_COMM_SELF, &r[i].comm); /* collective: here, before the threads */
  }
  for (int i = 0; i < n; i++) {
    if (pthread_create(&tid[i], &attr, replica_main, &r[i])) {
      fprintf(stderr, "mdpore run --replicas: cannot start the thread of %s\n", scenes[i].file);
      pthread_mutex_lock(&done_lock);
      n_done++; /* counted as ended: it never ran */
      pthread_mutex_unlock(&done_lock);
      tid[i] = 0;
    }
  }
  pthread_attr_destroy(&attr);
  pthread_mutex_lock(&done_lock);
  while (n_done < n) {
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += 2;
    pthread_cond_timedwait(&done_cond, &done_lock, &until);
    if (show && n_done < n) {
      const int running = n - n_done;
      pthread_mutex_unlock(&done_lock);
      progress_line(r, n, t0, running);
      pthread_mutex_lock(&done_lock);
    }
  }
  pthread_mutex_unlock(&done_lock);
  if (show) fputc('\n', stderr);
  int failed = 0;
  for (int i = 0; i < n; i++) {
    if (tid[i]) pthread_join(tid[i], NULL);
    MPI_Comm_free(&r[i].comm);
    if (r[i].rc) {
      failed++;
      fprintf(stderr,
              "mdpore run --replicas: replica %d of %d (%s) failed: see its messages above\n",
              i + 1, n, scenes[i].file);
    }
  }
  if (failed) {
    fprintf(stderr, "mdpore run --replicas: %d of %d replicas failed; the others finished\n",
            failed, n);
    rc = 1;
  }
  free(r);
  free(tid);
  return rc;
}
