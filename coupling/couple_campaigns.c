/* The per-block permeability campaigns of the loop, through `mdpore permeability` (campaign/): the
 * same cache (a run folder named by the hash of its scene and binary), so a rerun or a later pass
 * only runs what is new. Launchers (no scheduler of our own):
 *   mpiexec  the campaign runs its runs on this machine (mpiexec -n NP mdpore run), campaign.jobs
 *            of them at once (--jobs; default 1: one after another);
 *   slurm    the campaign only writes its scenes (--emit-scenes); the unfinished runs of every block
 *            go into one job array (WORKDIR/pass_N/commands.txt + slurm.sh, one run per task); the
 *            next `mdpore couple` collects what finished and goes on. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "couple.h"

static int add(char **argv, int *n, const char *s) {
  argv[(*n)++] = strdup(s);
  return argv[*n - 1] ? 0 : -1;
}

/* The gradients as a --gradients LIST: the block's ladder plus the loop's extra ones. */
static void gradient_list(const couple_block *b, char *out, size_t len) {
  size_t used = 0;
  out[0] = 0;
  for (int i = 0; i < b->n_ladder + b->n_extra && used + 32 < len; i++) {
    double g = i < b->n_ladder ? b->ladder_g[i] : b->extra_g[i - b->n_ladder];
    used += (size_t)snprintf(out + used, len - used, "%s%.17g", i ? "," : "", g);
  }
}

void couple_campaign_dir(const couple_config *c, const couple_block *b, int a, char *out,
                         size_t len) {
  if (a == c->axis)
    snprintf(out, len, "%s", b->workdir);
  else /* beside the loop axis's WORKDIR/blocks/bI_J_K/campaign */
    snprintf(out, len, "%.4000s_%c", b->workdir, 'x' + a);
}

/* argv of `mdpore permeability` for block b along axis a; mode: "" (run), "--emit-scenes" or
 * "--collect". Along a cross axis the campaign is the auto ladder alone (no feedback runs). */
static int campaign_argv(const couple_config *c, const couple_block *b, int a, const char *mode,
                         char **argv) {
  int n = 0;
  char v[4096], dir[COUPLE_PATH + 8];
  couple_campaign_dir(c, b, a, dir, sizeof dir);
  int bad = add(argv, &n, c->self_exe) || add(argv, &n, "permeability");
  if (!strcmp(mode, "--collect")) {
    bad = bad || add(argv, &n, "--collect") || add(argv, &n, dir);
    argv[n] = NULL;
    return bad ? -1 : 0;
  }
  snprintf(v, sizeof v, "%c", 'x' + a);
  bad = bad || add(argv, &n, b->image) || add(argv, &n, "--axis") || add(argv, &n, v);
  bad = bad || add(argv, &n, mode[0] ? mode : "--workdir") || add(argv, &n, dir);
  if (b->n_extra > 0 && a == c->axis) {
    gradient_list(b, v, sizeof v);
    bad = bad || add(argv, &n, "--gradients") || add(argv, &n, v);
  } else {
    snprintf(v, sizeof v, "%d", c->n_gradients);
    bad = bad || add(argv, &n, "--n-gradients") || add(argv, &n, v);
    snprintf(v, sizeof v, "%.17g,%.17g", c->u_lo, c->u_hi);
    bad = bad || add(argv, &n, "--velocity-range") || add(argv, &n, v);
  }
  /* an accuracy preset sets dt, the target error and the budget; options given in the config win */
  if (c->accuracy[0]) bad = bad || add(argv, &n, "--accuracy") || add(argv, &n, c->accuracy);
  if (!c->accuracy[0] || c->target_error_given) {
    snprintf(v, sizeof v, "%.17g", c->target_error);
    bad = bad || add(argv, &n, "--target-error") || add(argv, &n, v);
  }
  if (!c->accuracy[0] || c->max_steps_given) {
    snprintf(v, sizeof v, "%lld", c->max_steps);
    bad = bad || add(argv, &n, "--max-steps") || add(argv, &n, v);
  }
  snprintf(v, sizeof v, "%d", c->np);
  bad = bad || add(argv, &n, "--np") || add(argv, &n, v);
  if (c->jobs != 1) { /* the default (1) left out: the command as it was */
    snprintf(v, sizeof v, "%d", c->jobs);
    bad = bad || add(argv, &n, "--jobs") || add(argv, &n, c->jobs ? v : "auto");
  }
  snprintf(v, sizeof v, "%lld", c->seed);
  bad = bad || add(argv, &n, "--seed") || add(argv, &n, v);
  /* The blocks share the config's voxel edge (one continuum grid): a block whose critical throat
   * is narrower than the campaign's --min-throat runs with its warning (recorded in the block's
   * permeability.json) instead of stopping the loop. */
  snprintf(v, sizeof v, "%.17g", c->rc_per_voxel);
  bad = bad || add(argv, &n, "--rc-per-voxel") || add(argv, &n, v) || add(argv, &n, "--force");
  if (c->voxel_size[0]) bad = bad || add(argv, &n, "--voxel-size") || add(argv, &n, c->voxel_size);
  if (c->viscosity > 0) {
    snprintf(v, sizeof v, "%.17g", c->viscosity);
    bad = bad || add(argv, &n, "--viscosity") || add(argv, &n, v);
  }
  if (c->mpiexec[0]) bad = bad || add(argv, &n, "--mpiexec") || add(argv, &n, c->mpiexec);
  if (c->drive_pressure) bad = bad || add(argv, &n, "--drive") || add(argv, &n, "pressure");
  /* Without campaign.boundary the campaign's own default (auto) applies: each block's faces are
   * measured (seam continuity along the axis) and mirrored where they do not continue each other,
   * the choice a single-image campaign makes. Only a given treatment is passed, so the argv (and
   * with it nothing of the cached runs) of a config without the key is what it was. */
  if (c->boundary[0]) bad = bad || add(argv, &n, "--boundary") || add(argv, &n, c->boundary);
  if (c->sides[0]) bad = bad || add(argv, &n, "--sides") || add(argv, &n, c->sides);
  snprintf(v, sizeof v, "b%d_%d_%d", b->index[0], b->index[1], b->index[2]);
  bad = bad || add(argv, &n, "--sample") || add(argv, &n, v);
  argv[n] = NULL;
  return bad ? -1 : 0;
}

static void free_argv(char **argv) {
  for (int i = 0; argv[i]; i++) free(argv[i]);
}

static int spawn(const couple_config *c, const couple_block *b, int a, const char *mode,
                 const char *log) {
  char *argv[64] = {0};
  if (campaign_argv(c, b, a, mode, argv)) {
    free_argv(argv);
    return -1;
  }
  int st = camp_spawn(NULL, argv, log);
  free_argv(argv);
  return st;
}

int couple_read_ladder(couple_block *b) {
  campaign *m = malloc(sizeof *m);
  if (!m) return -1;
  int rc = camp_read_manifest(b->workdir, m);
  if (!rc) {
    b->n_ladder = 0;
    /* a run's G = n g with n its particles per rc^3 of pore: the template's fill (the liquid's
     * density plus what the walls adsorb) for an image, the liquid's for a scene of its own; with
     * the liquid's alone a feedback run landed a few % above the gradient it was meant for */
    b->density =
        isfinite(m->fill_density) && m->fill_density > 0 ? m->fill_density : m->fluid_density;
    camp_units u;
    camp_units_make(m->length_unit_m, m->fluid_density, m->temperature_K, &u);
    b->law.length_unit_m = m->length_unit_m;
    b->law.G_Pa_per_m = u.G_Pa_per_m;
    for (int d = 0; d < 3; d++) {
      b->boundary[d] = m->boundary[d];
      b->seam_continuity[d] = m->seam_continuity[d];
    }
    b->sides_mirror = m->sides_mirror;
    for (int i = 0; i < m->n_runs && b->n_ladder < COUPLE_MAX_GRADIENTS; i++) {
      int known = 0;
      for (int j = 0; j < b->n_extra; j++) known |= m->runs[i].g == b->extra_g[j];
      if (!known) b->ladder_g[b->n_ladder++] = m->runs[i].g;
    }
  }
  free(m);
  return rc;
}

/* The boundary treatment of block b's campaign along cross axis a (its campaign.txt). */
static int read_cross_manifest(const couple_config *c, couple_block *b, int a) {
  char dir[COUPLE_PATH + 8];
  couple_campaign_dir(c, b, a, dir, sizeof dir);
  campaign *m = malloc(sizeof *m);
  if (!m) return -1;
  int rc = camp_read_manifest(dir, m);
  if (!rc) {
    b->boundary[a] = m->boundary[a];
    b->seam_continuity[a] = m->seam_continuity[a];
  }
  free(m);
  return rc;
}

/* Appends the lines of DIR/commands.txt whose run folder has no summary.json to `out`. */
static int pending_commands(const char *dir_of_campaign, FILE *out, int *count) {
  char path[COUPLE_PATH + 32], line[3 * COUPLE_PATH];
  snprintf(path, sizeof path, "%.4000s/commands.txt", dir_of_campaign);
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "mdpore couple: %s: missing (the campaign's --emit-scenes should write it)\n",
            path);
    return -1;
  }
  while (fgets(line, sizeof line, f)) {
    /* "cd 'DIR' && ..." (the campaign quotes the folder) or "cd DIR && ..." */
    char dir[3 * COUPLE_PATH];
    if (strncmp(line, "cd ", 3)) continue;
    const char *p = line + 3;
    char end = ' ';
    if (*p == '\'' || *p == '"') end = *p++;
    size_t len = strcspn(p, end == ' ' ? " \n" : (end == '"' ? "\"" : "'"));
    if (len == 0 || len >= sizeof dir) continue;
    memcpy(dir, p, len);
    dir[len] = 0;
    char summary[3 * COUPLE_PATH + 32];
    snprintf(summary, sizeof summary, "%s/summary.json", dir);
    if (access(summary, R_OK)) {
      fputs(line, out);
      (*count)++;
    }
  }
  fclose(f);
  return 0;
}

static int write_slurm(const couple_config *c, int pass, const char *commands, int count) {
  char path[COUPLE_PATH + 64], tmp[COUPLE_PATH + 128];
  snprintf(path, sizeof path, "%.4000s/pass_%d/slurm.sh", c->workdir, pass);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  fprintf(f,
          "#!/bin/bash\n# mdpore couple: the unfinished pore-scale runs of pass %d, one per array "
          "task.\n# Submit: sbatch %s ; when the array is done, run mdpore couple %s again.\n"
          "#SBATCH --job-name=mdpore-couple\n#SBATCH --array=1-%d\n#SBATCH --ntasks=%d\n%s%s"
          "sed -n \"${SLURM_ARRAY_TASK_ID}p\" '%s' | bash\n",
          pass, path, c->path, count, c->np, c->slurm_header,
          c->slurm_header[0] && c->slurm_header[strlen(c->slurm_header) - 1] != '\n' ? "\n" : "",
          commands);
  return atomic_commit(f, tmp, path);
}

/* Runs (mpiexec) or emits and, when finished, collects (slurm) block b's campaign along axis a.
 * Adds its unfinished runs to *count (and b->pending). 0, or -1 with a message. */
static int run_campaign(const couple_config *c, couple_block *b, int a, int pass, FILE *array,
                        int *count) {
  char dir[COUPLE_PATH + 8], log[COUPLE_PATH + 64], cross[48] = "";
  int st;
  couple_campaign_dir(c, b, a, dir, sizeof dir);
  snprintf(log, sizeof log, "%.4000s/campaign.log", dir);
  if (a != c->axis) snprintf(cross, sizeof cross, " along %c", 'x' + a);
  if (make_dirs(dir)) return -1;
  if (a == c->axis)
    fprintf(stderr, "mdpore couple: pass %d: block (%d,%d,%d): campaign %s (%d gradients%s)\n",
            pass, b->index[0], b->index[1], b->index[2], dir,
            b->n_extra ? b->n_ladder + b->n_extra : c->n_gradients,
            b->n_extra ? ", with the loop's" : ", auto ladder");
  else
    fprintf(stderr,
            "mdpore couple: pass %d: block (%d,%d,%d): campaign along %c %s (%d gradients, auto "
            "ladder: the block's k along a cross axis)\n",
            pass, b->index[0], b->index[1], b->index[2], 'x' + a, dir, c->n_gradients);
  if (c->launcher == COUPLE_LAUNCH_SLURM) {
    int before = *count;
    if (spawn(c, b, a, "--emit-scenes", log) != 0 || pending_commands(dir, array, count)) {
      fprintf(stderr, "mdpore couple: the campaign%s of block (%d,%d,%d) failed: see %s\n", cross,
              b->index[0], b->index[1], b->index[2], log);
      return -1;
    }
    b->pending += *count - before;
    if (*count == before && (st = spawn(c, b, a, "--collect", log)) != 0) {
      fprintf(stderr, "mdpore couple: collecting block (%d,%d,%d)%s %s: see %s\n", b->index[0],
              b->index[1], b->index[2], cross,
              st == CAMP_EXIT_NO_DARCY_RANGE ? "found no Darcy range (its k is not defined)"
                                             : "failed",
              log);
      return -1;
    }
  } else if ((st = spawn(c, b, a, "", log)) != 0) {
    if (st == CAMP_EXIT_NO_DARCY_RANGE)
      fprintf(stderr,
              "mdpore couple: the runs of block (%d,%d,%d)%s define no Darcy range: its k is not "
              "defined, so neither is the sample's (the reasons and what to try: %s)\n",
              b->index[0], b->index[1], b->index[2], cross, log);
    else
      fprintf(stderr, "mdpore couple: the campaign%s of block (%d,%d,%d) failed: see %s\n", cross,
              b->index[0], b->index[1], b->index[2], log);
    return -1;
  }
  if (a == c->axis ? couple_read_ladder(b) : read_cross_manifest(c, b, a)) return -1;
  char text[256];
  couple_boundary_text_axis(c, b, a, text, sizeof text);
  printf("mdpore couple: pass %d: %s\n", pass, text);
  /* the campaign warns in its own log; a forced periodic seam across a crop's mismatched faces
   * can read k many times too low (docs/permeability.md, "Boundaries"), so say it here too */
  if (b->boundary[a] == CAMP_BOUNDARY_PERIODIC &&
      b->seam_continuity[a] < MDP_SEAM_PERIODIC_CONTINUITY)
    fprintf(stderr,
            "mdpore couple: warning: block (%d,%d,%d) runs periodic along %c, but its end slices "
            "do not continue each other (seam continuity %.2f < %.2f): the seam closes or "
            "invents flow paths; campaign.boundary auto or mirror treats a cut block's faces\n",
            b->index[0], b->index[1], b->index[2], 'x' + a, b->seam_continuity[a],
            MDP_SEAM_PERIODIC_CONTINUITY);
  fflush(stdout);
  return 0;
}

int couple_run_campaigns(const couple_config *c, couple_block *blocks, int n, int pass,
                         int *pending) {
  *pending = 0;
  char passdir[COUPLE_PATH + 32], cmds[COUPLE_PATH + 64], tmp[COUPLE_PATH + 128];
  snprintf(passdir, sizeof passdir, "%.4000s/pass_%d", c->workdir, pass);
  if (make_dirs(passdir)) return -1;
  FILE *array = NULL;
  int count = 0;
  if (c->launcher == COUPLE_LAUNCH_SLURM) {
    snprintf(cmds, sizeof cmds, "%s/commands.txt", passdir);
    if (!(array = atomic_open(cmds, tmp, sizeof tmp))) return -1;
  }
  for (int i = 0; i < n; i++) {
    couple_block *b = &blocks[i];
    b->pending = 0;
    /* along the loop's axis: a block without a new gradient keeps its runs and fit */
    if (b->percolates && b->n_extra_run != b->n_extra) {
      if (run_campaign(c, b, c->axis, pass, array, &count)) goto fail;
      if (!b->pending) b->n_extra_run = b->n_extra;
    }
    /* along the cross axes wanted: once per loop (the auto ladder, cached) */
    for (int a = 0; a < 3; a++) {
      if (b->cross_state[a] != CROSS_WANTED || b->cross_run[a]) continue;
      const int before = b->pending;
      if (run_campaign(c, b, a, pass, array, &count)) goto fail;
      if (b->pending == before) b->cross_run[a] = 1;
    }
  }
  if (array) {
    if (atomic_commit(array, tmp, cmds)) return -1;
    if (count && write_slurm(c, pass, cmds, count)) return -1;
    if (!count) remove(cmds);
    *pending = count;
  }
  return 0;
fail:
  if (array) {
    fclose(array);
    remove(tmp);
  }
  return -1;
}
