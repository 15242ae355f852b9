/* Morphological drainage and imbibition (image_morph.c): the union of balls against brute force on
 * a random image, a slit against the one-dimensional cover of its width, an ink bottle (a wide
 * body between two narrow throats along the axis): drainage enters the body only at the throat's
 * radius, imbibition traps the body's non-wetting phase with trapping and not without; the phase
 * image nearest a target saturation. */
#include "check.h"
#include "mdpore_image.h"

#include <stdlib.h>

static uint64_t rng_state = 12345;
static double uniform(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* The curve and, per step, the phase image nearest its saturation. */
static int curve(const mdp_image_t *img, const mdp_morph_opts_t *o, mdp_morph_step_t **st, int *n) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  int rc = mdp_image_morph_curve(img, o, NULL, 0, n, err);
  CHECK(rc == 0, "%s", err);
  if (rc) return 1;
  *st = malloc((size_t)*n * sizeof **st);
  rc = mdp_image_morph_curve(img, o, *st, *n, n, err);
  CHECK(rc == 0, "%s", err);
  return rc;
}

/* Union of balls by brute force on a small random image (no connectivity rule, open faces): the
 * voxels within < R' of a centre for some R' >= R (drained stays drained), the centres at >= R'
 * from every solid voxel centre. */
static void test_brute_force(void) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_t img;
  const int N = 14;
  CHECK(mdp_image_alloc(&img, N, N, N, err) == 0, "%s", err);
  mdp_image_parse_labels("pore=0,inorganic=1", img.phase_of, err);
  for (size_t v = 0; v < mdp_image_count(&img); v++) img.label[v] = uniform() < 0.06;
  const size_t n = mdp_image_count(&img);
  long long *d4 = malloc(n * sizeof *d4);
  for (size_t v = 0; v < n; v++) {
    long long best = -1;
    const int x = (int)(v % N), y = (int)(v / N % N), z = (int)(v / (N * N));
    for (size_t u = 0; u < n; u++) {
      if (!img.label[u]) continue;
      const long long dx = x - (int)(u % N), dy = y - (int)(u / N % N), dz = z - (int)(u / (N * N));
      const long long d = 4 * (dx * dx + dy * dy + dz * dz);
      if (best < 0 || d < best) best = d;
    }
    d4[v] = best;
  }
  mdp_morph_opts_t o = {.mode = MDP_MORPH_DRAINAGE, .axis = -1};
  mdp_morph_step_t *st = NULL;
  int ns = 0;
  if (curve(&img, &o, &st, &ns)) return;
  CHECK(ns >= 4, "only %d radii", ns);
  int compared = 0;
  uint8_t *nw = calloc(n, 1); /* drained: covered at this radius or a larger one */
  for (int i = 0; i < ns; i++) {
    const long long r4 = (long long)(4 * st[i].radius * st[i].radius + 0.5);
    long long covered = 0;
    for (size_t v = 0; v < n; v++) {
      if (img.label[v]) continue;
      const int x = (int)(v % N), y = (int)(v / N % N), z = (int)(v / (N * N));
      for (size_t c = 0; c < n && !nw[v]; c++) {
        if (img.label[c] || d4[c] < r4) continue;
        const long long dx = x - (int)(c % N), dy = y - (int)(c / N % N),
                        dz = z - (int)(c / (N * N));
        nw[v] = 4 * (dx * dx + dy * dy + dz * dz) < r4;
      }
      covered += nw[v];
    }
    CHECK(covered == st[i].nw_voxels, "R %g: brute force %lld voxels, morphology %lld",
          st[i].radius, covered, st[i].nw_voxels);
    compared++;
    if (i > 0) CHECK(st[i].radius < st[i - 1].radius, "radii not descending");
  }
  printf("brute force: %d radii %.3g..%.3g, union of balls equal at each\n", compared, st[0].radius,
         st[ns - 1].radius);
  free(st), free(d4), free(nw);
  mdp_image_free(&img);
}

/* A slit of w pore layers (walls normal to y), drained along x: the centres of the balls that fit
 * lie on the pore layers p (1..w) with min(p, w + 1 - p) >= R, and they cover every layer within
 * < R of one, counted here in one dimension. */
static void test_slit(int w) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_t img;
  CHECK(mdp_make_slit(&img, w, 2, 24, 5, err) == 0, "%s", err);
  mdp_morph_opts_t o = {.mode = MDP_MORPH_DRAINAGE, .axis = 0, .trapping = 1};
  mdp_morph_step_t *st = NULL;
  int ns = 0;
  if (curve(&img, &o, &st, &ns)) return;
  const double rmax = (w + 1) / 2; /* the largest distance of a layer to a wall centre */
  CHECK_CLOSE(st[0].radius, rmax, 1e-12);
  for (int i = 0; i < ns; i++) {
    const double R = st[i].radius;
    int covered = 0;
    for (int p = 1; p <= w; p++) {
      int hit = 0;
      for (int c = 1; c <= w; c++)
        if ((c < w + 1 - c ? c : w + 1 - c) >= R && abs(p - c) < R) hit = 1;
      covered += hit;
    }
    CHECK_CLOSE(st[i].snw, (double)covered / w, 1e-12);
  }
  printf("slit w = %d: first invasion at R = %g voxels (w/2 = %g), Snw %.4f there; %d radii\n", w,
         st[0].radius, 0.5 * w, st[0].snw, ns);
  if (w % 2 == 0) CHECK_CLOSE(st[0].radius, 0.5 * w, 1e-12);
  free(st);
  mdp_image_free(&img);
}

/* Along x: inlet throat [0, 12), body [12, 30), outlet throat [30, 42); square cross-sections of
 * side t (throats) and b (body) centred in a 24 x 24 section. */
static void make_ink_bottle(mdp_image_t *img, int t, int b, long long *body_voxels) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  CHECK(mdp_image_alloc(img, 42, 24, 24, err) == 0, "%s", err);
  mdp_image_parse_labels("pore=0,inorganic=1", img->phase_of, err);
  *body_voxels = 0;
  for (int k = 0; k < 24; k++)
    for (int j = 0; j < 24; j++)
      for (int i = 0; i < 42; i++) {
        const int side = i >= 12 && i < 30 ? b : t, lo = 12 - side / 2;
        const int pore = j >= lo && j < lo + side && k >= lo && k < lo + side;
        img->label[mdp_image_index(img, i, j, k)] = pore ? 0 : 1;
        *body_voxels += pore && side == b;
      }
}

static void test_ink_bottle(void) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_t img;
  long long body = 0;
  const int t = 4, b = 16;
  make_ink_bottle(&img, t, b, &body);
  /* drainage: nothing until R reaches the throat's largest inscribed radius (t/2 = 2 voxels:
   * the distance of the middle layers to the wall centres), then the body at once */
  mdp_morph_opts_t o = {.mode = MDP_MORPH_DRAINAGE, .axis = 0, .trapping = 1};
  mdp_morph_step_t *st = NULL;
  int ns = 0;
  if (curve(&img, &o, &st, &ns)) return;
  const double r_throat = 0.5 * t;
  int entry = -1;
  for (int i = 0; i < ns; i++) {
    if (st[i].radius > r_throat + 1e-9)
      CHECK(st[i].nw_voxels == 0, "R %g > throat %g: %lld voxels invaded", st[i].radius, r_throat,
            st[i].nw_voxels);
    else if (entry < 0)
      entry = i;
  }
  CHECK(entry > 0, "no step at or below the throat radius (entry %d)", entry);
  if (entry > 0) {
    CHECK_CLOSE(st[entry].radius, r_throat, 1e-12);
    CHECK(st[entry].nw_spans == 1 && st[entry - 1].nw_spans == 0,
          "spans %d at the entry, %d "
          "before",
          st[entry].nw_spans, st[entry - 1].nw_spans);
    CHECK(st[entry].nw_voxels >= 0.9 * body, "at the throat radius %lld voxels invaded, body %lld",
          st[entry].nw_voxels, body);
    printf("ink bottle drainage: Snw 0 for R > %g (%d radii), Snw %.4f at R = %g (body %.4f of the "
           "pore space)\n",
           r_throat, entry, st[entry].snw, st[entry].radius,
           (double)body / (double)st[entry].pore_voxels);
  }
  /* morph_at: the step nearest a target between two steps, its voxels labelled */
  const double target = entry > 0 ? st[entry].snw - 0.2 : 0.3;
  mdp_image_t out;
  mdp_morph_step_t got;
  CHECK(mdp_image_morph_at(&img, &o, target, 7, &out, &got, err) == 0, "%s", err);
  int best = 0;
  for (int i = 1; i < ns; i++)
    if (fabs(st[i].snw - target) < fabs(st[best].snw - target)) best = i;
  CHECK_CLOSE(got.snw, st[best].snw, 1e-15);
  CHECK_CLOSE(got.radius, st[best].radius, 1e-15);
  long long labelled = 0;
  for (size_t v = 0; v < mdp_image_count(&out); v++) labelled += out.label[v] == 7;
  CHECK(labelled == got.nw_voxels, "%lld voxels labelled 7, step has %lld", labelled,
        got.nw_voxels);
  CHECK(out.phase_of[7] == MDP_PHASE_PORE, "label 7 maps to %d", out.phase_of[7]);
  printf("morph_at %.4f: step %d, Snw %.4f, R %g, %lld voxels labelled\n", target, best, got.snw,
         got.radius, labelled);
  mdp_image_t again;
  CHECK_ERR_HAS(mdp_image_morph_at(&out, &o, 0.5, 7, &again, &got, err), err, "label 7");
  CHECK_ERR_HAS(mdp_image_morph_at(&img, &o, 1.5, 7, &again, &got, err), err, "[0, 1]");
  mdp_image_free(&out);
  free(st);
  /* imbibition: once R exceeds the throats the body's non-wetting phase is cut off from the
   * outlet; with trapping it stays, without it leaves with the opening */
  /* the opening by the largest ball (the first step of a drainage without connectivity rule) */
  mdp_morph_opts_t open_o = {.mode = MDP_MORPH_DRAINAGE, .axis = -1};
  if (curve(&img, &open_o, &st, &ns)) return;
  const long long opening = st[0].nw_voxels;
  const double r_max = st[0].radius;
  free(st);
  long long trapped_end = 0;
  for (int trapping = 1; trapping >= 0; trapping--) {
    mdp_morph_opts_t im = {.mode = MDP_MORPH_IMBIBITION, .axis = 0, .trapping = trapping};
    if (curve(&img, &im, &st, &ns)) return;
    CHECK_CLOSE(st[0].snw, 1.0, 1e-15);
    for (int i = 1; i < ns; i++) CHECK(st[i].snw <= st[i - 1].snw, "imbibition Snw rises");
    const mdp_morph_step_t *end = &st[ns - 1];
    /* with trapping: the body as it was when R passed the throats (its edges, within about
     * a voxel of the walls, already gave way at that radius); without: at most the opening by
     * the largest ball (less: a voxel imbibed once stays wetting) */
    if (trapping)
      CHECK(end->trapped_voxels >= 0.85 * body && end->nw_voxels >= end->trapped_voxels,
            "with trapping: %lld trapped, %lld non-wetting, body %lld", end->trapped_voxels,
            end->nw_voxels, body);
    else
      CHECK(end->trapped_voxels == 0 && end->nw_voxels <= opening && end->radius == r_max &&
                end->nw_voxels < trapped_end,
            "without trapping: %lld trapped, %lld non-wetting at R %g, the opening by R %g %lld, "
            "trapped with trapping %lld",
            end->trapped_voxels, end->nw_voxels, end->radius, r_max, opening, trapped_end);
    trapped_end = end->trapped_voxels;
    printf("ink bottle imbibition %s trapping: residual Snw %.4f (trapped %.4f) at R = %g\n",
           trapping ? "with" : "without", end->snw,
           (double)end->trapped_voxels / (double)end->pore_voxels, end->radius);
    free(st);
  }
  mdp_image_free(&img);
}

int main(void) {
  test_brute_force();
  test_slit(10);
  test_slit(7);
  test_ink_bottle();
  if (check_failures) fprintf(stderr, "%d checks failed\n", check_failures);
  return check_failures ? 1 : 0;
}
