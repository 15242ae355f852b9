/* Fuzz entry: the command line of `mdpore permeability` (camp_parse_args) or, when the first token
 * is "relperm", of `mdpore relperm` (rp_parse_args). The input is the argv tokens, one a line (a
 * NUL ends a token too). Only the parser runs: nothing is planned, run or written (it checks that
 * an IMAGE, SCENE or --template can be read, no more). The argv must be accepted, or refused with
 * a message that starts with the command's name and names what is at fault: an option or a value
 * as given, or the missing IMAGE, --axis or WORKDIR (else abort: a finding). An accepted argv must
 * hold what the campaign indexes with (axes 0..2, 1..64 gradients, ranks and jobs in range). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "fuzz_util.h"
#include "relperm.h"

#define MAX_ARGS 64

static rp_opts ro; /* large: not on the stack */
static camp_opts co;

/* The message names an argument as given (an option or value of two or more characters, a shorter
 * one quoted or as the message's subject), or what is missing. */
static int names_argument(const char *msg, int argc, char **argv) {
  if (strstr(msg, "IMAGE") || strstr(msg, "--axis") || strstr(msg, "WORKDIR")) return 1;
  for (int i = 1; i < argc; i++) {
    char quoted[4200], subject[4200];
    snprintf(quoted, sizeof quoted, "'%.4096s'", argv[i]);
    snprintf(subject, sizeof subject, ": %.4096s:", argv[i]); /* "mdpore X: TOKEN: ..." */
    if ((strlen(argv[i]) >= 2 && strstr(msg, argv[i])) || strstr(msg, quoted) ||
        strstr(msg, subject))
      return 1;
  }
  return 0;
}

static void check_relperm(const rp_opts *r) {
  int ok = r->axis >= 0 && r->axis <= 2 && r->n_sw >= 1 && r->n_sw <= RP_MAX_SATURATIONS &&
           (r->ratio == 1 || r->ratio == 2 || r->ratio == 5);
  for (int i = 0; i < r->n_sw && ok; i++)
    ok = r->sw[i] > 0 && r->sw[i] < 1 && (i == 0 || r->sw[i] > r->sw[i - 1]);
  if (!ok) {
    fprintf(stderr, "fuzz: mdpore relperm accepted axis %d, %d saturations, ratio %d\n", r->axis,
            r->n_sw, r->ratio);
    abort();
  }
}

static void check_accepted(const camp_opts *o, const char *cmd) {
  int ok = o->n_axes >= 1 && o->n_axes <= 3 && o->np >= 1 && o->jobs >= 0 &&
           o->jobs <= CAMP_MAX_JOBS && o->flux_every >= 1 && o->input[0] && o->workdir[0];
  for (int a = 0; a < o->n_axes && ok; a++) ok = o->axes[a] >= 0 && o->axes[a] <= 2;
  if (ok && !o->grad_auto && o->n_grads) /* relperm: one gradient, from the image */
    ok = o->n_grads >= 1 && o->n_grads <= CAMP_MAX_GRADIENTS;
  if (ok && o->grad_auto) ok = o->n_grads >= 5 && o->n_grads <= CAMP_MAX_GRADIENTS;
  if (ok && o->target_error_k > 0) ok = o->round_steps >= 1 && o->round_steps <= o->max_steps;
  if (!ok) {
    fprintf(stderr,
            "fuzz: %s accepted options out of range: %d axes, %d gradients (auto %d), np %d, "
            "jobs %d, flux_every %d, round_steps %lld of %lld, input '%s', workdir '%s'\n",
            cmd, o->n_axes, o->n_grads, o->grad_auto, o->np, o->jobs, o->flux_every, o->round_steps,
            o->max_steps, o->input, o->workdir);
    abort();
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *argv[MAX_ARGS + 1];
  const int relperm = size >= 8 && !memcmp(data, "relperm\n", 8);
  const char *cmd = relperm ? "mdpore relperm" : "mdpore permeability";
  int argc = relperm ? fuzz_argv(data + 8, size - 8, "relperm", argv, MAX_ARGS)
                     : fuzz_argv(data, size, "permeability", argv, MAX_ARGS);
  fuzz_capture_begin();
  const int rc = relperm ? rp_parse_args(argc, argv, &ro) : camp_parse_args(argc, argv, &co);
  const char *msg = fuzz_capture_end();
  if (rc < 0 && !names_argument(msg, argc, argv)) {
    fprintf(stderr, "fuzz: %s refused its arguments without naming the one at fault: '%s'\n", cmd,
            msg);
    abort();
  }
  /* 1: --help (the usage is printed by the caller) */
  if (rc == 0 && !(relperm ? ro.co.collect_dir[0] : co.collect_dir[0])) {
    check_accepted(relperm ? &ro.co : &co, cmd);
    if (relperm) check_relperm(&ro);
  }
  fuzz_outcome(rc < 0 ? rc : 0, msg, cmd);
  return 0;
}
