/* Outputs of the loop (docs/coupling.md, "Outputs"): per pass the block table (CSV, also printed)
 * and the continuum field (HDF5 + XDMF for ParaView); at the end the summary JSON and the PNG
 * (coupling/plot_couple.py, when python3 has matplotlib). Every file is written atomically. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "common/json_out.h"
#include "couple.h"

#define NANODARCY_M2 9.869233e-22

/* Where a block's gradient lies against the range its law was calibrated on. */
static const char *range_word(const couple_config *c, const couple_block *b, double G) {
  const couple_law *L = &b->law;
  if (!b->percolates) return "impermeable";
  if (G > L->g_max * 1.05) return "above";
  if (G >= L->g_min / 1.05) return "inside";
  if (G >= L->g_min * c->resolvable_fraction) return "below";
  return "linear-response";
}

/* A note on a fitted law beyond Darcy (physics.md section 4: a threshold or Forchheimer term fitted
 * at pore-scale forcing may be an artefact of the forcing). "" for Darcy. */
static const char *law_flag(const couple_law *L) {
  switch (L->chosen.kind) {
  case LAW_THRESHOLD:
    return "fit chose a threshold law: at pore-scale forcing a threshold may be an artefact";
  case LAW_FORCHHEIMER:
    return "fit chose Forchheimer: inertia at pore-scale forcing, absent at reservoir gradients";
  case LAW_POWER:
    return "fit chose a power law: check the run lengths before reading it as physics";
  default:
    return "";
  }
}

/* Who chose a block's treatment: the config, the pressure drive (always a reservoir) or the
 * campaign's auto rule on the block's own seam. */
static const char *boundary_chooser(const couple_config *c) {
  if (c->drive_pressure) return "drive: pressure";
  if (c->boundary[0] && strcmp(c->boundary, "auto")) return "campaign.boundary";
  return "auto";
}

void couple_boundary_text(const couple_config *c, const couple_block *b, char *out, size_t len) {
  couple_boundary_text_axis(c, b, c->axis, out, len);
}

void couple_boundary_text_axis(const couple_config *c, const couple_block *b, int a, char *out,
                               size_t len) {
  if (!b->boundary[a]) {
    snprintf(out, len, "block (%d,%d,%d) axis %c: no campaign (%s)", b->index[0], b->index[1],
             b->index[2], 'x' + a,
             b->spans[a] ? "not run yet" : "the pore space does not span the axis");
    return;
  }
  snprintf(out, len, "block (%d,%d,%d) axis %c: %s (seam continuity %.2f; %s%s), sides %s",
           b->index[0], b->index[1], b->index[2], 'x' + a, camp_boundary_name(b->boundary[a]),
           b->seam_continuity[a], boundary_chooser(c),
           strcmp(boundary_chooser(c), "auto") ? "" : ": periodic at >= 0.80",
           b->sides_mirror ? "mirror" : "periodic");
}

const char *couple_k_along(const couple_config *c, const couple_block *b, int a, double *k,
                           double *err) {
  const int cross = a != c->axis;
  if (cross && b->cross_state[a] == CROSS_MEASURED) {
    *k = b->cross[a].k_darcy;
    *err = b->cross[a].k_darcy_err;
    return "campaign";
  }
  if (!b->percolates || (cross && b->cross_state[a] == CROSS_NO_SPAN)) {
    *k = 0.0;
    *err = 0.0;
    return "impermeable";
  }
  *k = b->law.k_darcy;
  *err = b->law.k_darcy_err;
  return cross ? "flow axis" : "campaign";
}

/* With cross axes (campaign.axes all or auto): the block's k along every axis, as the continuum
 * uses it, into the table's extra columns and a line to print (line[len]). */
static void write_axes_k(const couple_config *c, const couple_block *B, double cross_flow, FILE *f,
                         int pass, char *line, size_t len) {
  int used = snprintf(line, len, "pass %d: block (%d,%d,%d) k along", pass, B->index[0],
                      B->index[1], B->index[2]);
  for (int a = 0; a < 3; a++) {
    double k, err;
    const char *from = couple_k_along(c, B, a, &k, &err);
    fprintf(f, ",%.9g,%.9g,%s", k, err, from);
    if (used >= 0 && (size_t)used < len)
      used += snprintf(line + used, len - used, "%s %c %.4g+-%.2g (%s)", a ? "," : "", 'x' + a, k,
                       err, from);
  }
  fprintf(f, ",%.4g", cross_flow);
  if (used >= 0 && (size_t)used < len)
    snprintf(line + used, len - used, "; flow across the axis %.3g of the flow along it",
             cross_flow);
}

int couple_write_pass_table(const couple_config *c, const couple_block *blocks, int n, int pass,
                            const couple_solution *s, const int *new_runs) {
  char path[COUPLE_PATH + 64], tmp[COUPLE_PATH + 128];
  snprintf(path, sizeof path, "%.4000s/pass_%d/blocks.csv", c->workdir, pass);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  fprintf(f,
          "# mdpore couple pass %d: blocks along %c (reduced units: k rc^2, G kT/rc^4, q rc/tau;"
          " q superficial = Q / A_block)\n",
          pass, 'x' + c->axis);
  fprintf(f,
          "i,j,k,porosity,law_used,k_or_K,second_parameter,k_darcy,k_darcy_err,chosen_law,G_min,"
          "G_max,G_seen,range,q_continuum,q_continuum_err,q_mdpd_law,new_run_g,boundary,"
          "seam_continuity,note%s\n",
          c->axes == COUPLE_AXES_FLOW ? ""
                                      : ",k_x,k_x_err,k_x_from,k_y,k_y_err,k_y_from,k_z,k_z_err,"
                                        "k_z_from,cross_flow");
  printf("pass %d: %-9s %-7s %-12s %-22s %-20s %-9s %-12s %-12s %s\n", pass, "block", "law",
         "k (rc^2)", "calibrated G", "G seen", "range", "q continuum", "q law(G)", "new run");
  for (int b = 0; b < n; b++) {
    const couple_block *B = &blocks[b];
    const couple_law *L = &B->law;
    double G = fabs(s->grad[b]);
    double q_law =
        B->percolates ? flow_law_q_exact(&L->law, &(fluid_props){L->mu, L->density}, G) : 0.0;
    double second = L->law.kind == LAW_THRESHOLD     ? L->law.g0
                    : L->law.kind == LAW_FORCHHEIMER ? L->law.beta
                    : L->law.kind == LAW_POWER       ? L->law.n
                                                     : NAN;
    double first = L->law.kind == LAW_POWER ? L->law.K : L->law.k;
    double g_new = new_runs[b] ? B->extra_g[B->n_extra - 1] : NAN;
    fprintf(f,
            "%d,%d,%d,%.6g,%s,%.9g,%.9g,%.9g,%.9g,%s,%.9g,%.9g,%.9g,%s,%.9g,%.9g,%.9g,%.9g,%s,%.3g,"
            "%s",
            B->index[0], B->index[1], B->index[2], B->porosity,
            B->percolates ? flow_law_name(L->law.kind) : "none", first, second, L->k_darcy,
            L->k_darcy_err, B->percolates ? L->chosen_name : "none", L->g_min, L->g_max, G,
            range_word(c, B, G), s->flux[b], s->flux_err[b], q_law, g_new,
            B->boundary[c->axis] ? camp_boundary_name(B->boundary[c->axis]) : "none",
            B->seam_continuity[c->axis],
            B->percolates ? law_flag(L) : "pore space does not span the axis");
    double cross_flow = 0.0; /* the largest over the cross axes */
    for (int a = 0; a < 3; a++) cross_flow = fmax(cross_flow, s->cross[3 * b + a]);
    char axes_line[512] = "";
    if (c->axes != COUPLE_AXES_FLOW)
      write_axes_k(c, B, cross_flow, f, pass, axes_line, sizeof axes_line);
    fputc('\n', f);
    char blk[32], kk[48], cal[48], seen[32], newr[32];
    snprintf(blk, sizeof blk, "(%d,%d,%d)", B->index[0], B->index[1], B->index[2]);
    snprintf(kk, sizeof kk, "%.4g+-%.2g", L->k_darcy, L->k_darcy_err);
    snprintf(cal, sizeof cal, "[%.3g, %.3g]", L->g_min, L->g_max);
    snprintf(seen, sizeof seen, "%.4g", G);
    if (new_runs[b])
      snprintf(newr, sizeof newr, "g = %.4g", g_new);
    else
      snprintf(newr, sizeof newr, "-");
    printf("pass %d: %-9s %-7s %-12s %-22s %-20s %-9s %-12.5g %-12.5g %s\n", pass, blk,
           B->percolates ? flow_law_name(L->law.kind) : "none", kk, cal, seen, range_word(c, B, G),
           s->flux[b], q_law, newr);
    if (axes_line[0]) printf("%s\n", axes_line);
  }
  return atomic_commit(f, tmp, path);
}

static int dataset(hid_t f, const char *name, const int n[3], const double *v, const char *unit,
                   const char *what) {
  hsize_t dims[3] = {(hsize_t)n[2], (hsize_t)n[1], (hsize_t)n[0]};
  hid_t sp = H5Screate_simple(3, dims, NULL);
  hid_t d = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  int rc = d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0;
  const char *keys[3] = {"unit", "description", "axis_order"};
  const char *vals[3] = {unit, what, "zyx"};
  for (int a = 0; d >= 0 && a < 3; a++) {
    hid_t ts = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
    H5Tset_size(ty, strlen(vals[a]) + 1);
    hid_t at = H5Acreate2(d, keys[a], ty, ts, H5P_DEFAULT, H5P_DEFAULT);
    rc |= at < 0 || H5Awrite(at, ty, vals[a]) < 0;
    if (at >= 0) H5Aclose(at);
    H5Tclose(ty);
    H5Sclose(ts);
  }
  if (d >= 0) H5Dclose(d);
  H5Sclose(sp);
  return rc ? -1 : 0;
}

int couple_write_field(const couple_config *c, const couple_block *blocks, int pass,
                       const double size[3], const couple_solution *s) {
  int n = c->blocks[0] * c->blocks[1] * c->blocks[2];
  char path[COUPLE_PATH + 64], tmp[COUPLE_PATH + 128], name[64];
  snprintf(name, sizeof name, "field.h5");
  snprintf(path, sizeof path, "%.4000s/pass_%d/%s", c->workdir, pass, name);
  double *k = malloc((size_t)n * sizeof(double)), *phi = malloc((size_t)n * sizeof(double));
  if (!k || !phi) {
    free(k);
    free(phi);
    return -1;
  }
  for (int b = 0; b < n; b++) {
    k[b] = blocks[b].percolates ? blocks[b].law.k_darcy : 0.0;
    phi[b] = blocks[b].porosity;
  }
  atomic_tmp_name(path, tmp, sizeof tmp);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  int rc = f < 0;
  if (!rc) {
    rc |= dataset(f, "pressure", c->blocks, s->pressure, "kT/rc^3", "block pressure");
    rc |= dataset(f, "gradient", c->blocks, s->grad, "kT/rc^4",
                  "mean gradient -dp/dx of the block along the loop's axis");
    rc |= dataset(f, "flux", c->blocks, s->flux, "rc/tau",
                  "superficial velocity through the block along the loop's axis");
    rc |= dataset(f, "flux_err", c->blocks, s->flux_err, "rc/tau",
                  "standard error of flux from the fits' parameter covariances");
    rc |= dataset(f, "k_darcy", c->blocks, k, "rc^2", "Darcy permeability of the block's campaign");
    rc |= dataset(f, "porosity", c->blocks, phi, "1", "pore voxels / voxels of the block");
    H5Fclose(f);
    rc = rc || atomic_rename(tmp, path);
  }
  free(k);
  free(phi);
  if (rc) {
    fprintf(stderr, "mdpore couple: cannot write %s\n", path);
    remove(tmp);
    return -1;
  }
  /* XDMF: cell data on a uniform grid of (blocks + 1) nodes per axis, origin 0, block spacing */
  snprintf(path, sizeof path, "%.4000s/pass_%d/field.xmf", c->workdir, pass);
  FILE *x = atomic_open(path, tmp, sizeof tmp);
  if (!x) return -1;
  const int *nb = c->blocks;
  fprintf(x,
          "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n<Grid Name=\"blocks\" "
          "GridType=\"Uniform\">\n<Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"%d %d "
          "%d\"/>\n<Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n<DataItem Dimensions=\"3\" "
          "Format=\"XML\">0 0 0</DataItem>\n<DataItem Dimensions=\"3\" Format=\"XML\">%.17g %.17g "
          "%.17g</DataItem>\n</Geometry>\n",
          nb[2] + 1, nb[1] + 1, nb[0] + 1, size[2], size[1], size[0]);
  const char *sets[] = {"pressure", "gradient", "flux", "flux_err", "k_darcy", "porosity"};
  for (int i = 0; i < 6; i++)
    fprintf(x,
            "<Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n<DataItem "
            "Dimensions=\"%d %d %d\" NumberType=\"Float\" Precision=\"8\" "
            "Format=\"HDF\">%s:/%s</DataItem>\n</Attribute>\n",
            sets[i], nb[2], nb[1], nb[0], name, sets[i]);
  fprintf(x, "</Grid>\n</Domain>\n</Xdmf>\n");
  return atomic_commit(x, tmp, path);
}

int couple_write_summary(const couple_config *c, const couple_block *blocks, int n,
                         const double size[3], const couple_solution *s, const couple_history *h) {
  char path[COUPLE_PATH + 64], tmp[COUPLE_PATH + 128];
  snprintf(path, sizeof path, "%.4000s/couple.json", c->workdir);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  double rc_m = NAN, G_SI = NAN;
  for (int b = 0; b < n; b++)
    if (blocks[b].percolates && blocks[b].law.length_unit_m > 0) {
      rc_m = blocks[b].law.length_unit_m;
      G_SI = blocks[b].law.G_Pa_per_m;
      break;
    }
  json_out j;
  json_begin(&j, f);
  json_string(&j, "format", "mdpore-couple");
  json_int(&j, "version", 1);
  json_string(&j, "config", c->path);
  json_string(&j, "axis", (const char[]){(char)('x' + c->axis), 0});
  json_numbers(&j, "blocks", (const double[]){c->blocks[0], c->blocks[1], c->blocks[2]}, 3);
  json_numbers(&j, "block_size_rc", size, 3);
  json_string(&j, "law", c->law_choice == COUPLE_LAW_CHOSEN ? "chosen" : "darcy");
  if (c->axes != COUPLE_AXES_FLOW)
    json_string(&j, "campaign_axes", c->axes == COUPLE_AXES_ALL ? "all" : "auto");
  json_string(&j, "convention",
              "superficial (Darcy) velocity q = Q / A_total over the whole cross-section; k = mu q "
              "/ G with G = -dp/dx; reduced units (rc, kT, tau) unless stated");
  json_string(&j, "linear_response",
              "the pore-scale runs are driven at gradients far above reservoir ones (~1e-11 "
              "reduced); the continuum solve uses the laws fitted on the runs' range, extrapolated "
              "in linear response below it; a fitted threshold, Forchheimer or power-law term may "
              "be a forcing artefact (physics.md section 4)");
  json_int(&j, "passes", h->passes);
  json_bool(&j, "converged", h->converged);
  json_bool(&j, "pending", h->pending);
  json_string(&j, "stop_reason", h->stop_reason);
  json_number(&j, "gradient",
              s && s->pressure ? s->dp / (c->blocks[c->axis] * size[c->axis]) : NAN);
  json_number(&j, "gradient_Pa_per_m",
              s && s->pressure ? s->dp / (c->blocks[c->axis] * size[c->axis]) * G_SI : NAN);
  json_object(&j, "effective_permeability");
  double k = s && s->pressure ? s->keff : NAN, ke = s && s->pressure ? s->keff_err : NAN;
  json_number(&j, "k_rc2", k);
  json_number(&j, "k_rc2_err", ke);
  json_number(&j, "k_m2", k * rc_m * rc_m);
  json_number(&j, "k_m2_err", ke * rc_m * rc_m);
  json_number(&j, "k_nD", k * rc_m * rc_m / NANODARCY_M2);
  json_number(&j, "k_nD_err", ke * rc_m * rc_m / NANODARCY_M2);
  json_number(&j, "rc_m", rc_m);
  json_int(&j, "error_samples", s ? s->samples_ok : 0);
  json_object_end(&j);
  json_array(&j, "history");
  for (int p = 0; p < h->passes; p++) {
    json_object(&j, NULL);
    json_int(&j, "pass", p + 1);
    json_number(&j, "k_rc2", h->keff[p]);
    json_number(&j, "k_rc2_err", h->keff_err[p]);
    json_number(&j, "max_flux_change_sigma", h->max_dq_sigma[p]);
    json_int(&j, "new_runs", h->new_runs[p]);
    json_int(&j, "blocks_with_left_out_run", h->left_out[p]);
    if (c->axes == COUPLE_AXES_AUTO) json_int(&j, "new_cross_axes", h->new_cross[p]);
    json_object_end(&j);
  }
  json_array_end(&j);
  /* written with or without a solution: a pending slurm pass already knows its treatments */
  json_array(&j, "block_boundaries");
  for (int b = 0; b < n; b++) {
    const couple_block *B = &blocks[b];
    char text[256];
    couple_boundary_text(c, B, text, sizeof text);
    json_object(&j, NULL);
    json_numbers(&j, "index", (const double[]){B->index[0], B->index[1], B->index[2]}, 3);
    json_string(&j, "faces",
                B->boundary[c->axis] ? camp_boundary_name(B->boundary[c->axis]) : "none");
    json_number(&j, "seam_continuity", B->seam_continuity[c->axis]);
    json_string(&j, "sides", B->sides_mirror ? "mirror" : "periodic");
    json_string(&j, "chosen_by", boundary_chooser(c));
    json_string(&j, "text", text);
    json_object_end(&j);
  }
  json_array_end(&j);
  json_array(&j, "blocks_final");
  for (int b = 0; s && s->pressure && b < n; b++) {
    const couple_block *B = &blocks[b];
    json_object(&j, NULL);
    json_numbers(&j, "index", (const double[]){B->index[0], B->index[1], B->index[2]}, 3);
    json_string(&j, "image", B->image);
    json_number(&j, "porosity", B->porosity);
    json_bool(&j, "percolates", B->percolates);
    json_string(&j, "boundary",
                B->boundary[c->axis] ? camp_boundary_name(B->boundary[c->axis]) : "none");
    json_string(&j, "law", B->percolates ? flow_law_name(B->law.law.kind) : "none");
    json_string(&j, "chosen_law", B->percolates ? B->law.chosen_name : "none");
    json_number(&j, "k_darcy_rc2", B->law.k_darcy);
    json_number(&j, "k_darcy_rc2_err", B->law.k_darcy_err);
    json_numbers(&j, "calibrated_G", (const double[]){B->law.g_min, B->law.g_max}, 2);
    json_number(&j, "G_seen", fabs(s->grad[b]));
    json_string(&j, "range", range_word(c, B, fabs(s->grad[b])));
    json_number(&j, "q_continuum", s->flux[b]);
    json_number(&j, "q_continuum_err", s->flux_err[b]);
    json_string(&j, "note", B->percolates ? law_flag(&B->law) : "does not span the axis");
    if (c->axes != COUPLE_AXES_FLOW) { /* the diagonal the continuum used */
      double k[3], err[3];
      json_array(&j, "k_axes_from");
      for (int a = 0; a < 3; a++) json_string(&j, NULL, couple_k_along(c, B, a, &k[a], &err[a]));
      json_array_end(&j);
      json_numbers(&j, "k_axes_rc2", k, 3);
      json_numbers(&j, "k_axes_rc2_err", err, 3);
      json_numbers(&j, "cross_flow", &s->cross[3 * b], 3);
    }
    json_object_end(&j);
  }
  json_array_end(&j);
  json_end(&j);
  return atomic_commit(f, tmp, path);
}

void couple_plot(const couple_config *c) {
  char summary[COUPLE_PATH + 32], png[COUPLE_PATH + 32];
  snprintf(summary, sizeof summary, "%.4000s/couple.json", c->workdir);
  snprintf(png, sizeof png, "%.4000s/couple.png", c->workdir);
  char *argv[] = {MDPORE_PYTHON_EXE, COUPLE_PLOT_SCRIPT, summary, png, NULL};
  int st = camp_spawn(NULL, argv, NULL);
  if (st == 0)
    printf("wrote %s (block permeability map and the loop's convergence)\n", png);
  else
    printf("no PNG: %s %s exited %d (python3 with matplotlib needed)\n", MDPORE_PYTHON_EXE,
           COUPLE_PLOT_SCRIPT, st);
}
