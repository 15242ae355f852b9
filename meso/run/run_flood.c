/* The flood in the run loop (run_flood.h). */
#include "run/run_flood.h"

#include <math.h>
#include <string.h>

/* The injection side [sink.lo, sample.lo) along the flow (+axis), across the periodic face. */
static int recolor_injection_side(run_flood_t *r, sim_t *sim) {
  const scene_t *s = sim_scene(sim);
  const scene_flood_t *o = &s->flood;
  const int a = o->axis;
  const double blo = s->box_lo[a], bhi = s->box_hi[a], L = bhi - blo;
  const double from = o->sink_lo;
  double to = o->sample_lo;
  if (to <= from) to += L;
  long n1 = 0, n2 = 0;
  if (sim_recolor(sim, a, from, fmin(to, bhi), o->defending, o->invading, &n1)) return -1;
  if (to > bhi && sim_recolor(sim, a, blo, to - L, o->defending, o->invading, &n2)) return -1;
  r->recolored += n1 + n2;
  return 0;
}

static int census(run_flood_t *r, sim_t *sim, long step) {
  const scene_t *s = sim_scene(sim);
  if (flood_census(&r->f, sim)) return -1;
  flood_update(&r->f, s, step);
  flood_log_row(&r->log, &r->f, r->recolored);
  if (s->flood.map_every > 0 && step % s->flood.map_every == 0)
    return flood_log_map(&r->log, s, &r->f, sim, r->rank);
  return 0;
}

int run_flood_open(run_flood_t *r, sim_t *sim, long first, int rank) {
  memset(r, 0, sizeof *r);
  const scene_t *s = sim_scene(sim);
  r->rank = rank;
  if (!s->flood.on) return 0;
  r->on = 1;
  int err = flood_init(&r->f, s, sim);
  if (!err) err = flood_log_open(&r->log, s, &r->f, rank);
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MIN, sim_comm(sim));
  if (err) return -1;
  if (first == s->flood.start && recolor_injection_side(r, sim)) return -1;
  return census(r, sim, first);
}

int run_flood_step(run_flood_t *r, sim_t *sim, long step) {
  if (!r->on) return 0;
  const scene_flood_t *o = &sim_scene(sim)->flood;
  if (step == o->start) {
    if (recolor_injection_side(r, sim)) return -1;
  } else if (step > o->start) {
    long n = 0;
    if (sim_recolor(sim, o->axis, o->sink_lo, o->sink_hi, o->defending, o->invading, &n)) return -1;
    r->recolored += n;
  }
  if (step % o->every == 0 || step == o->start) return census(r, sim, step);
  return 0;
}

/* The capillary number Ca = mu q_t / gamma of the injection, q_t the mean total superficial
 * velocity in the sample after the start (NaN without flood.viscosity and flood.tension). */
static double capillary_number(const run_flood_t *r, const scene_t *s) {
  const scene_flood_t *o = &s->flood;
  if (!(o->viscosity > 0 && o->tension > 0) || r->f.q_n < 1) return NAN;
  return o->viscosity * (r->f.q_sum / r->f.q_n) / o->tension;
}

void run_flood_text(FILE *out, const run_flood_t *r, const scene_t *s) {
  if (!r->on) return;
  const flood_t *f = &r->f;
  const scene_flood_t *o = &s->flood;
  const char ax = "xyz"[f->axis];
  fprintf(out,
          "flood along %c: %s displacing %s from the sample [%g, %g) from step %ld; at step %ld: "
          "S_%s = %.4f, recovery = %.4f, %.3g pore volumes injected, front at %.3g of %.3g\n",
          ax, s->species[f->inv].name, s->species[f->def].name, f->lo, f->hi, o->start, f->step,
          s->species[f->inv].name, f->s_inv, f->recovery, f->pvi, f->front, f->length);
  if (!f->started)
    fprintf(out, "  the injection had not started (flood.start %ld is after the last step)\n",
            o->start);
  else if (f->broke_through)
    fprintf(out,
            "  breakthrough (S_%s of the last of %d bins >= %g) at step %ld, %.6g time units "
            "after the start, %.3g pore volumes injected, recovery %.4f\n",
            s->species[f->inv].name, f->nbins, o->breakthrough, f->bt_step, f->bt_time, f->bt_pvi,
            f->bt_recovery);
  else
    fprintf(out, "  no breakthrough yet (S_%s of the sample's last bin stayed below %g)\n",
            s->species[f->inv].name, o->breakthrough);
  fprintf(out, "  q_%s = %.4g, q_%s = %.4g (superficial, last census; n = %.4g from %s)",
          s->species[f->inv].name, f->q_inv, s->species[f->def].name, f->q_def, f->n_fluid,
          f->density_source);
  const double ca = capillary_number(r, s);
  if (isfinite(ca))
    fprintf(out, "; Ca = mu q_t / gamma = %.3g (mu %g, gamma %g)", ca, o->viscosity, o->tension);
  fprintf(out, "\n  series %s%s%s\n", o->path, o->profile_path[0] ? ", profiles " : "",
          o->profile_path);
}

static void num(FILE *fp, const char *before, double v) {
  fputs(before, fp);
  if (isfinite(v))
    fprintf(fp, "%.10g", v);
  else
    fputs("null", fp);
}

void run_flood_json(FILE *fp, const run_flood_t *r, const scene_t *s) {
  if (!r->on) return;
  const flood_t *f = &r->f;
  const scene_flood_t *o = &s->flood;
  fprintf(fp,
          "  \"flood\": {\"axis\": \"%c\", \"invading\": \"%s\", \"defending\": \"%s\", "
          "\"start_step\": %ld, \"last_census_step\": %ld",
          "xyz"[f->axis], s -> species[f->inv].name, s->species[f->def].name, o->start, f->step);
  num(fp, ", \"sample\": [", f->lo);
  num(fp, ", ", f->hi);
  num(fp, "], \"saturation_invading\": ", f->s_inv);
  num(fp, ", \"recovery\": ", f->recovery);
  num(fp, ", \"pore_volumes_injected\": ", f->pvi);
  num(fp, ", \"front\": ", f->front);
  num(fp, ", \"q_invading\": ", f->q_inv);
  num(fp, ", \"q_defending\": ", f->q_def);
  num(fp, ", \"density\": ", f->n_fluid);
  num(fp, ", \"capillary_number\": ", capillary_number(r, s));
  fprintf(fp, ", \"recolored\": %ld, \"breakthrough\": ", r->recolored);
  if (f->broke_through) {
    fprintf(fp, "{\"step\": %ld", f->bt_step);
    num(fp, ", \"time_after_start\": ", f->bt_time);
    num(fp, ", \"pore_volumes_injected\": ", f->bt_pvi);
    num(fp, ", \"recovery\": ", f->bt_recovery);
    num(fp, ", \"saturation_invading\": ", f->bt_s_inv);
    num(fp, ", \"threshold\": ", o->breakthrough);
    fputs("}", fp);
  } else {
    fputs("null", fp);
  }
  fprintf(fp, ", \"series\": \"%s\"},\n", o->path);
}

void run_flood_close(run_flood_t *r) {
  flood_log_close(&r->log);
  flood_free(&r->f);
}
