/* The run loop (see run_loop.h): configuration, sim_setup, sim_step + outputs, summary. */
#include "run/run_loop.h"
#include "analysis/profile.h"
#include "engine/sim.h"
#include "io/checkpoint.h"
#include "io/dump_lammps.h"
#include "populate/init_config.h"
#include "io/snapshot.h"
#include "io/thermo_log.h"
#include "analysis/penetration.h"
#include "analysis/density_guard.h"
#include "analysis/temperature_guard.h"
#include "io/stale_tmp.h"
#include "run/progress.h"
#include "run/run_balance.h"
#include "run/run_fault.h"
#include "run/run_flood.h"
#include "run/run_flux.h"
#include "run/run_stats.h"

#include <stdio.h>
#include <string.h>

static void prefix(char *path, const char *dir) {
  if (!path[0] || path[0] == '/') return;
  char tmp[SCENE_PATH_LEN];
  if (strlen(dir) + strlen(path) + 2 > sizeof tmp) return;
  snprintf(tmp, sizeof tmp, "%s/%s", dir, path);
  strcpy(path, tmp);
}

void run_apply_output_dir(scene_t *s, const char *dir) {
  prefix(s->thermo.path, dir);
  prefix(s->profile.path, dir);
  prefix(s->snapshot.path, dir);
  prefix(s->dump.path, dir);
  prefix(s->checkpoint.path, dir);
  prefix(s->flux.path, dir);
  prefix(s->summary_path, dir);
  prefix(s->flood.path, dir);
  prefix(s->flood.profile_path, dir);
  prefix(s->flood.map_path, dir);
}

static int due(const scene_output_t *o, long step) {
  return o->every > 0 && step % o->every == 0;
}

/* Outputs of one step; `first` marks the initial state of a fresh run. Collective. 0 or -1. */
static int write_outputs(sim_t *sim, long step, int fresh_start, int last, snapshot_series_t *snaps,
                         int *dump_started) {
  const scene_t *s = sim_scene(sim);
  int rc = 0;
  if (due(&s->snapshot, step)) rc |= snapshot_series_write(snaps, sim);
  if (due(&s->dump, step)) {
    rc |= dump_lammps_frame(s->dump.path, sim, fresh_start && !*dump_started);
    *dump_started = 1;
  }
  if (s->checkpoint.every > 0 && (due(&s->checkpoint, step) || last) && !(fresh_start && step == 0))
    rc |= checkpoint_write(s->checkpoint.path, sim);
  return rc;
}

/* The census of a geometry scene (collective): the penetration count into the thermo row (th; NULL
 * at a census between rows) and the summary's tally, the pore core's density into its series from
 * step core_start on; with geometry.strict a penetration stops the run, naming the particle, the
 * voxel and the step. Returns 1 to stop. */
static int penetration_sample(const penetration_map_t *m, sim_t *sim, thermo_t *th, long step,
                              run_stats_t *st, const scene_t *s, int rank) {
  if (!m->on) return 0;
  penetration_t pen;
  penetration_count(m, sim, &pen);
  if (th) {
    th->penetrations = pen.count;
    th->penetration_depth = pen.max_depth;
  }
  if (m->core_voxels > 0 && step >= st->core_start)
    series_push(&st->core_density, (double)pen.core_count / st->core_volume);
  st->penetration_samples++;
  if (pen.count == 0) return 0;
  st->penetration_bad_samples++;
  if (pen.count > st->penetration_max) st->penetration_max = pen.count;
  if (pen.max_depth > st->penetration_depth) st->penetration_depth = pen.max_depth;
  if (rank == 0 && (s->geometry.strict || st->penetration_bad_samples == 1))
    fprintf(stderr,
            "mdpore: step %ld: %ld mobile particle(s) inside solid voxels of %s; deepest: particle "
            "%lld at (%g, %g, %g), voxel (%d, %d, %d), %.3g rc deep. %s\n",
            step, pen.count, s->geometry.image, (long long)pen.id, pen.x[0], pen.x[1], pen.x[2],
            pen.voxel[0], pen.voxel[1], pen.voxel[2], pen.max_depth,
            s->geometry.strict ? "Stopping (geometry.strict). Try a boundary effect (bounce_back), "
                                 "a smaller dt, or a thicker wall."
                               : "The run goes on (geometry.strict: true stops it); the summary "
                                 "counts them.");
  return s->geometry.strict != 0;
}

int run_scene(const scene_t *scene, MPI_Comm comm) {
  return run_scene_watched(scene, comm, NULL);
}

int run_scene_watched(const scene_t *scene, MPI_Comm comm, run_watch_t *watch) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const double t_start = MPI_Wtime();
  if (rank == 0) { /* temporary files of writes a killed run did not finish */
    const char *const paths[] = {
        scene->thermo.path,     scene->profile.path,      scene->snapshot.path, scene->dump.path,
        scene->checkpoint.path, scene->flux.path,         scene->summary_path,  scene->restart_from,
        scene->flood.path,      scene->flood.profile_path};
    for (size_t k = 0; k < sizeof paths / sizeof *paths; k++) stale_tmp_cleanup(paths[k]);
  }
  sim_t *sim = sim_create(scene, comm);
  if (!sim) return 1;
  const scene_t *s = sim_scene(sim);
  const int restart = s->restart_from[0] != 0;
  int rc = restart ? checkpoint_read(s->restart_from, sim) : init_configuration(sim, s);
  run_balance_t rbal;
  if (rc || run_balance_start(&rbal, sim, restart, rank) || sim_setup(sim)) {
    sim_destroy(sim);
    return 1;
  }
  const long first = sim_step_index(sim), last = first + s->steps;
  comm = sim_comm(sim);
  run_fault_t fault; /* MDPORE_TEST_FAULT (tests only; the same on every rank) */
  if (run_fault_init(&fault, sim, rank)) {
    sim_destroy(sim);
    return 1;
  }

  thermo_log_t log;
  profile_t prof;
  memset(&prof, 0, sizeof prof);
  run_stats_t st;
  snapshot_series_t snaps;
  progress_t pr;
  int dump_started = 0, err = thermo_log_open(&log, s, s->thermo.path, restart ? first : -1, rank);
  if (restart && rank == 0 && !err) { /* cut the series a killed run wrote past the checkpoint */
    if (s->dump.every > 0 && dump_lammps_trim(s->dump.path, first)) err = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm);
  if (err) {
    sim_destroy(sim);
    return 1;
  }
  if (s->profile.nbins > 0 && profile_init(&prof, s, first, last, comm)) {
    fprintf(stderr, "mdpore: out of memory for the profile\n");
    sim_destroy(sim);
    return 1;
  }
  run_stats_init(&st, s, first, last, size);
  penetration_map_t pmap;
  char perr[1024] = "";
  err = penetration_map_create(&pmap, s, perr, sizeof perr);
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm);
  if (err) {
    if (rank == 0) fprintf(stderr, "mdpore: %s\n", perr[0] ? perr : "penetration map failed");
    sim_destroy(sim);
    return 1;
  }
  st.penetration_on = pmap.on;
  st.core_voxels = pmap.core_voxels;
  st.core_rc = pmap.core_rc;
  st.core_volume = (double)pmap.core_voxels * pmap.h * pmap.h * pmap.h;
  /* The pore core's density settles within a few hundred steps; flux runs may stop early, before
   * the thermo window, so its samples start after min(1000 steps, half the run). */
  st.core_start = first + (last - first < 2000 ? (last - first) / 2 : 1000);
  temperature_guard_t tguard;
  density_guard_t dguard;
  err = temperature_guard_init(&tguard, sim) | density_guard_init(&dguard, sim, &pmap);
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm);
  run_flux_t rf;
  if (err || run_flux_open(&rf, sim, restart, first, rank)) {
    if (err) memset(&rf, 0, sizeof rf);
    temperature_guard_free(&tguard);
    density_guard_free(&dguard);
    run_flux_close(&rf);
    thermo_log_close(&log);
    run_stats_free(&st);
    penetration_map_free(&pmap);
    if (s->profile.nbins > 0) profile_free(&prof);
    sim_destroy(sim);
    return 1;
  }
  st.flux = &rf;
  run_flood_t rfl;
  memset(&rfl, 0, sizeof rfl);
  if (!err) err = run_flood_open(&rfl, sim, first, rank) != 0;
  st.flood = &rfl;
  snapshot_series_init(&snaps, s->snapshot.path);
  if (!err && restart && rank == 0 && s->snapshot.every > 0)
    err = snapshot_series_resume(&snaps, s, first);
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm);
  progress_start(&pr, s->progress, rank, first, last);
  char gmsg[2048] = "";

  thermo_t th;
  sim_thermo(sim, &th);
  if (!err) err = penetration_sample(&pmap, sim, &th, first, &st, s, rank);
  if (!err) err = density_guard_check(&dguard, sim, first, gmsg, sizeof gmsg); /* reference */
  st.n_total = th.n_total;
  if (!restart && !err) {
    if (due(&s->thermo, first)) thermo_log_row(&log, &th);
    if (run_flux_due(&rf, first) && run_flux_sample(&rf, sim, first, rank) < 0) err = 1;
    err = write_outputs(sim, first, 1, first == last, &snaps, &dump_started);
  }
  double loop = 0;
  if (watch) {
    __atomic_store_n(&watch->first, first, __ATOMIC_RELAXED);
    __atomic_store_n(&watch->step, first, __ATOMIC_RELAXED);
    __atomic_store_n(&watch->last, last, __ATOMIC_RELAXED);
    const double now = MPI_Wtime();
    __atomic_store(&watch->t_loop, &now, __ATOMIC_RELAXED);
  }
  for (long step = first + 1; step <= last && !err; step++) {
    const int sample = s->profile.nbins > 0 && profile_wants(&prof, step);
    const int virial_for_flux = run_flux_wants_virial(&rf, step); /* measured pressure drop */
    if (sample || virial_for_flux) sim_request_virial(sim, 1);
    const int log_row = due(&s->thermo, step), stat = run_stats_wants(&st, step);
    sim_announce_thermo(sim, log_row || stat);
    /* A checkpoint after this step: build the neighbour lists in this step, as a restart from it
     * will, so that the restarted run sums the forces in the same order (bitwise restarts). */
    if (s->checkpoint.every > 0 &&
        (due(&s->checkpoint, step) || step == last || run_flux_check_at(&rf, step)))
      sim_rebuild_lists(sim);
    /* Not a branch on the result: stopping one rank here would leave the others waiting in the
     * step's collectives. A failed device write has printed its CUDA error; a device fault stays
     * pending, and the step's own device calls then fail and stop the run collectively. */
    if (fault.kind && step == fault.step) (void)run_fault_apply(&fault, sim);
    MPI_Barrier(comm);
    const double t0 = MPI_Wtime();
    if (sim_step(sim)) {
      /* The engine printed its message (NaN, particle lost, ...). */
      if (rank == 0) fprintf(stderr, "mdpore: run stopped at step %ld\n", step);
      err = 1;
      break;
    }
    loop += MPI_Wtime() - t0;
    if (run_balance_step(&rbal, sim, step, last, rank)) {
      err = 1;
      break;
    }
    if (sample) {
      profile_sample(&prof, sim);
      if (!profile_wants(&prof, step + 1)) sim_request_virial(sim, 0);
    }
    /* sim_thermo is collective: only on steps every rank knows (the progress line on rank 0 shows
     * the latest sample rather than asking for one). The geometry's census (penetrations, the pore
     * core's density) runs at thermo rows and every MESO_GEOMETRY_SAMPLE_EVERY steps, not at every
     * statistics sample: on the GPU each census copies the particles to the host. */
    const int census = pmap.on && (log_row || step % MESO_GEOMETRY_SAMPLE_EVERY == 0);
    if (log_row || stat) sim_thermo(sim, &th);
    if (census && penetration_sample(&pmap, sim, log_row ? &th : NULL, step, &st, s, rank)) {
      if (rank == 0) fprintf(stderr, "mdpore: run stopped at step %ld\n", step);
      err = 1;
      break;
    }
    if (log_row || stat) {
      if (temperature_guard_sample(&tguard, &th, gmsg, sizeof gmsg)) {
        if (rank == 0) fprintf(stderr, "%s\nmdpore: run stopped at step %ld\n", gmsg, step);
        err = 1;
        break;
      }
      if (log_row) thermo_log_row(&log, &th);
      if (stat && rank == 0) run_stats_add(&st, &th);
    }
    if (density_guard_check(&dguard, sim, step, gmsg, sizeof gmsg)) {
      if (rank == 0) fprintf(stderr, "%s\nmdpore: run stopped at step %ld\n", gmsg, step);
      err = 1;
      break;
    }
    if (watch) __atomic_store_n(&watch->step, step, __ATOMIC_RELAXED);
    progress_update(&pr, step, th.step, th.temperature,
                    (th.pressure[0] + th.pressure[1] + th.pressure[2]) / 3);
    /* The flux sample; with run.target_error it may end the run here (every rank together; the
     * outputs of a last step, the checkpoint included, are written first). */
    int stop = 0;
    if (run_flux_due(&rf, step) && (stop = run_flux_sample(&rf, sim, step, rank)) < 0) {
      err = 1;
      break;
    }
    if (run_flood_step(&rfl, sim, step)) {
      if (rank == 0) fprintf(stderr, "mdpore: run stopped at step %ld (flood)\n", step);
      err = 1;
      break;
    }
    if (virial_for_flux && !(s->profile.nbins > 0 && profile_wants(&prof, step + 1)))
      sim_request_virial(sim, 0);
    err = write_outputs(sim, step, !restart, step == last || stop, &snaps, &dump_started);
    if (!err && s->profile.nbins > 0 && s->checkpoint.every > 0 && due(&s->checkpoint, step) &&
        rank == 0)
      profile_write(&prof, s->profile.path);
    if (stop) break;
  }
  progress_end(&pr);
  if (watch) __atomic_store_n(&watch->step, last, __ATOMIC_RELAXED); /* done (or stopped early) */
  thermo_log_close(&log);
  if (dguard.on && rank == 0)
    fprintf(stderr,
            "mdpore: density guard: %ld checks (every %ld steps, %ld of %ld bins watched), %.3g s "
            "= %.2g%% of the step loop\n",
            dguard.checks, dguard.every, dguard.watched, dguard.nbins, dguard.seconds,
            loop > 0 ? 100.0 * dguard.seconds / loop : 0.0);
  if (!err) {
    st.steps_done = sim_step_index(sim) - first;
    st.last_step = sim_step_index(sim); /* earlier than planned after an early stop */
    if (rank == 0) run_stats_finish(&st, st.last_step);
    run_flux_finish(&rf, s, rank);
    run_balance_finish(&rbal, sim, &st);
    st.loop_seconds = loop;
    st.total_seconds = MPI_Wtime() - t_start;
    if (rank == 0) {
      if (s->profile.nbins > 0 && profile_write(&prof, s->profile.path)) err = 1;
      flockfile(stdout); /* one block: replicas (run_replicas.c) write theirs at once */
      if (run_summary_write(&st, s, s->profile.nbins > 0 ? &prof : NULL, stdout, s->summary_path))
        err = 1;
      funlockfile(stdout);
    }
    MPI_Bcast(&err, 1, MPI_INT, 0, comm);
  }
  run_flux_close(&rf);
  run_flood_close(&rfl);
  run_stats_free(&st);
  temperature_guard_free(&tguard);
  density_guard_free(&dguard);
  penetration_map_free(&pmap);
  snapshot_series_free(&snaps);
  if (s->profile.nbins > 0) profile_free(&prof);
  sim_destroy(sim);
  return err ? 1 : 0;
}
