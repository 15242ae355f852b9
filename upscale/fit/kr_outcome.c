/* The result law of `mdpore fit relperm`, or none (see kr_outcome.h). */
#include "kr_outcome.h"

#include <stdio.h>
#include <string.h>

void kr_judgement_text(const kr_judgement *j, char *buf, int len) {
  int n = 0, any = 0;
  buf[0] = 0;
  for (int pass = 0; pass < 2 && !any; pass++) /* failing phases first; all when none fails */
    for (int ph = 0; ph < 2 && n < len; ph++) {
      if (!pass && j->phase[ph].verdict == KR_PHASE_PASSES) continue;
      char one[400];
      kr_phase_text(&j->phase[ph], ph, one, sizeof one);
      n += snprintf(buf + n, len - n, "%s%s", any ? "; " : "", one);
      any = 1;
    }
}

static int usable(const kr_fit_result *r) {
  return r->ok && r->converged;
}

/* "corey: not fitted: WHY" or "corey: PHASES" into buf. */
static void law_reason(const kr_fit_result *r, const kr_judgement *j, char *buf, int len) {
  char what[900];
  if (!usable(r))
    snprintf(buf, len, "%s: %s: %s", kr_law_name(r->kind), r->ok ? "no result" : "not fitted",
             r->why[0] ? r->why : "no converged fit");
  else {
    kr_judgement_text(j, what, sizeof what);
    snprintf(buf, len, "%s: %s", kr_law_name(r->kind), what);
  }
}

void kr_decide(const kr_table *t, const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
               int asked, int force, kr_outcome *out) {
  memset(out, 0, sizeof *out);
  out->law = -1;
  for (int k = 0; k < KR_LAW_COUNT; k++) kr_judge_fit(t, &fits[k], &out->judge[k]);
  char r0[1000], r1[1000];
  const kr_judgement *jc = &out->judge[KR_COREY];
  if (jc->phase[0].verdict == KR_PHASE_NO_ERRORS || jc->phase[1].verdict == KR_PHASE_NO_ERRORS) {
    int n = 0; /* no law is fitted to points without weights (cmd_fit_relperm.c) */
    for (int ph = 0; ph < 2; ph++)
      if (jc->phase[ph].verdict == KR_PHASE_NO_ERRORS && n < (int)sizeof r1) {
        kr_phase_text(&jc->phase[ph], ph, r0, sizeof r0);
        n += snprintf(r1 + n, sizeof r1 - n, "%s%s", n ? "; " : "", r0);
      }
    out->refused = asked >= 0;
    if (asked >= 0)
      snprintf(out->text, sizeof out->text,
               "--law %s refused: %s: no law is fitted without errors to weight the points%s",
               kr_law_name(asked), r1,
               force ? " (--force cannot take a law that was not fitted)" : "");
    else
      snprintf(out->text, sizeof out->text,
               "no law: %s: no law is fitted without errors to weight the points", r1);
    return;
  }
  if (asked >= 0) {
    law_reason(&fits[asked], &out->judge[asked], r0, sizeof r0);
    if (out->judge[asked].accepted) {
      out->law = asked;
      snprintf(out->text, sizeof out->text, "--law %s: accepted (%s)", kr_law_name(asked), r0);
    } else if (force && usable(&fits[asked])) {
      out->law = asked, out->forced = 1;
      snprintf(out->text, sizeof out->text,
               "--law %s --force: taken although the check refuses it (%s)", kr_law_name(asked),
               r0);
    } else {
      out->refused = 1;
      snprintf(out->text, sizeof out->text, "--law %s refused: %s%s", kr_law_name(asked), r0,
               force ? " (--force cannot take a law that was not fitted)" : "");
    }
    return;
  }
  const int first = c->chosen, other = c->chosen == KR_COREY ? KR_LET : KR_COREY;
  if (first >= 0 && out->judge[first].accepted) {
    out->law = first;
    return; /* the test's choice, accepted: kr_choice's text says it */
  }
  if (first >= 0 && out->judge[other].accepted) {
    out->law = other;
    law_reason(&fits[first], &out->judge[first], r0, sizeof r0);
    snprintf(out->text, sizeof out->text,
             "the test's choice is refused (%s); %s passes the check and is taken", r0,
             kr_law_name(other));
    return;
  }
  const int any_fit = usable(&fits[KR_COREY]) || usable(&fits[KR_LET]);
  int n = snprintf(out->text, sizeof out->text, "%s: ",
                   any_fit ? "no law fits the data within the limit" : "no law could be fitted");
  int any = 0;
  for (int k = 0; k < KR_LAW_COUNT && n < (int)sizeof out->text; k++) {
    if (!fits[k].ok && !fits[k].why[0]) continue; /* not attempted */
    law_reason(&fits[k], &out->judge[k], r1, sizeof r1);
    n += snprintf(out->text + n, sizeof out->text - n, "%s%s", any ? "; " : "", r1);
    any = 1;
  }
}
