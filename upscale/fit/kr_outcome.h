/* Which law `mdpore fit relperm` gives as its result (docs/relperm.md section 5, "When no law
 * fits"): the law the selection test chose (kr_select.h) if the per-phase check of kr_judge.h
 * accepts it, else the other law if that one is accepted, else none, and the SWOF export is then
 * the measured points themselves. With --law L only L is considered: when the check refuses it (or
 * it cannot be fitted or judged) the command exits KR_EXIT_LAW_REFUSED, unless --force, which takes
 * L anyway, flagged in the report and the SWOF header. */
#ifndef MDPORE_UPSCALE_KR_OUTCOME_H
#define MDPORE_UPSCALE_KR_OUTCOME_H

#include "kr_judge.h"
#include "kr_select.h"

/* Exit status when the law asked for with --law is refused by the data (as `mdpore permeability`
 * exits 3 when its runs define no Darcy range; 1: an error, 2: bad usage). */
#define KR_EXIT_LAW_REFUSED 3

typedef struct {
  int law;                          /* the result: KR_COREY, KR_LET, or -1 (no law) */
  int forced;                       /* --force: `law` fails the check and is taken anyway */
  int refused;                      /* --law L without --force, L not accepted: exit 3 */
  kr_judgement judge[KR_LAW_COUNT]; /* per law */
  char text[2400];                  /* the outcome in words, with the numbers */
} kr_outcome;

/* fits and c as kr_choose left them; asked: the --law (-1: auto); force: --force. */
void kr_decide(const kr_table *t, const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
               int asked, int force, kr_outcome *out);

/* The failing (or unjudged) phases of one law in words: "kro: chi2/dof = ...; ..." (every phase
 * when all pass). */
void kr_judgement_text(const kr_judgement *j, char *buf, int len);

#endif
