/* registry.c — the table of validation cases, and running one case into a
 * report (the public interface of <smolbridge/validate.h>). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <smolbridge/validate.h>
#include "common/internal.h"
#include "cases.h"
#include "report.h"

/* The case tables of all modules, in the order they run. */
static const struct {
  const sbv_case *cases;
  const size_t *n;
} tables[] = {
    {sbv_cases_bridge, &sbv_ncases_bridge},
    {sbv_cases_langevin, &sbv_ncases_langevin},
    {sbv_cases_pbe, &sbv_ncases_pbe},
    {sbv_cases_engine, &sbv_ncases_engine},
    {sbv_cases_v2, &sbv_ncases_v2},
    {sbv_cases_engine2, &sbv_ncases_engine2},
    {sbv_cases_agglo, &sbv_ncases_agglo},
    {sbv_cases_v12, &sbv_ncases_v12},
    {sbv_cases_pgd, &sbv_ncases_pgd},
    {sbv_cases_pgd_jets, &sbv_ncases_pgd_jets},
    {sbv_cases_pgd_dense, &sbv_ncases_pgd_dense},
    {sbv_cases_pgd_engine, &sbv_ncases_pgd_engine},
    {sbv_cases_spray, &sbv_ncases_spray},
    {sbv_cases_v16, &sbv_ncases_v16},
    {sbv_cases_v16c, &sbv_ncases_v16c},
    {sbv_cases_v16d, &sbv_ncases_v16d},
    {sbv_cases_pair, &sbv_ncases_pair},
    {sbv_cases_transport, &sbv_ncases_transport},
};
enum { NTABLES = sizeof tables / sizeof tables[0] };

/* Case i of the concatenated tables, or NULL. */
static const sbv_case *case_at(size_t i)
{
  for (size_t t = 0; t < NTABLES; t++) {
    if (i < *tables[t].n)
      return &tables[t].cases[i];
    i -= *tables[t].n;
  }
  return NULL;
}

void sb_validate_options_init(sb_validate_options *opt)
{
  if (!opt)
    return;
  memset(opt, 0, sizeof *opt);
  opt->seed = 12345UL;
}

size_t sb_validate_ncases(void)
{
  size_t n = 0;
  for (size_t t = 0; t < NTABLES; t++)
    n += *tables[t].n;
  return n;
}

const char *sb_validate_case_name(size_t i)
{
  const sbv_case *c = case_at(i);
  if (!c)
    sbi_error(SB_EINVAL, __func__, "case index %zu out of range (%zu cases)",
              i, sb_validate_ncases());
  return c ? c->name : NULL;
}

const char *sb_validate_case_description(size_t i)
{
  const sbv_case *c = case_at(i);
  if (!c)
    sbi_error(SB_EINVAL, __func__, "case index %zu out of range (%zu cases)",
              i, sb_validate_ncases());
  return c ? c->description : NULL;
}

int sb_validate_case_index(const char *name, size_t *index)
{
  if (!name)
    return sbi_error(SB_EINVAL, __func__, "NULL name");
  size_t n = sb_validate_ncases();
  for (size_t i = 0; i < n; i++)
    if (strcmp(case_at(i)->name, name) == 0) {
      if (index)
        *index = i;
      return SB_SUCCESS;
    }
  return sbi_error(SB_EINVAL, __func__, "no case called '%s'", name);
}

/* Distinct, reproducible seeds per (base seed, stream). */
static unsigned long stream_seed(const sbv_ctx *ctx, unsigned long stream)
{
  return ctx->seed * 1000003UL + stream * 7919UL + 1UL;
}

unsigned long sbv_rng_seed(const sbv_ctx *ctx, unsigned long stream)
{
  return stream_seed(ctx, stream) & 0xffffffffUL;  /* what MT19937 keeps */
}

gsl_rng *sbv_rng_alloc(const sbv_ctx *ctx, unsigned long stream)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (r)
    gsl_rng_set(r, stream_seed(ctx, stream));
  return r;
}

void sbv_engine_params(sb_engine_params *p)
{
  sb_engine_params_default(p);
  p->rng_type = gsl_rng_mt19937;
  p->streams = 0;
}

void sbv_progress(const sbv_ctx *ctx, const char *fmt, ...)
{
  const sb_validate_options *o = ctx->opt;
  if (!o || !o->progress)
    return;
  char line[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  o->progress(line, o->progress_data);
}

static double wall_seconds(void)
{
  struct timespec ts;
  if (timespec_get(&ts, TIME_UTC) != TIME_UTC)
    return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sb_validate_run(size_t index, const sb_validate_options *opt,
                    sb_validate_report *rep)
{
  const sbv_case *c = case_at(index);
  if (!c)
    return sbi_error(SB_EINVAL, __func__,
                     "case index %zu out of range (%zu cases)", index,
                     sb_validate_ncases());
  if (!opt || !rep)
    return sbi_error(SB_EINVAL, __func__, "NULL options or report");
  if (sbv_report_begin_case(rep, c->name) != SB_SUCCESS)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  sbv_ctx ctx = {opt->full != 0, opt->seed, opt->outdir, opt, NULL, NULL};
  double t0 = wall_seconds();
  sb_clear_error();  /* a failed case reports its own message */
  int st = c->run(&ctx, rep);
  sbv_report_end_case(rep, st, wall_seconds() - t0);
  return st;
}

/* Cases with engine runs that `smolbridge collide` reproduces (all or
 * some of them: the others are listed in NOT-WRITTEN.txt, sbv_ini_skip). */
static const char *const INI_CASES[] = {
    "V1/kinetic-gases", "V1/dense-long-steps", "V1/kinetic-mixture",
    "V9/two-spheres-45", "V9/crossing-jets", "V2/brownian-ballistic",
    "V4/bridge-brownian", "V5/constant-B", "V7/brownian-turb",
    "V3/diffusive-fail", "V6/correction-step", "VX/exact-detection",
    "V8/agglo-dlvo", "V8/agglo-constant", "V8/agglo-brownian",
    "V12/langevin-detector", "V16/shear", "V16/settling",
    "V16/abrahamson", "V16/saffman-turner", "V16/combined",
    "V16/combined-shear-diffusive", "V16/deposition",
    "V16/deposition-langevin", "V16/combined-shear", "V15/engine-jets",
    "V18/self-diffusion", "V18/maxwell-relaxation", "V13/spray-vs-engine",
    "V15/dense-jets", NULL};

/* Cases whose engine runs `smolbridge collide` does not reproduce, and
 * why: written to NOT-WRITTEN.txt, so that no engine run goes unlisted. */
static const struct {
  const char *name, *why;
} NO_FILES[] = {
    {NULL, NULL},  /* none at present: every engine case has its files */
};

int sb_validate_write_ini(size_t index, const sb_validate_options *opt,
                          const char *dir, size_t *nfiles)
{
  if (nfiles)
    *nfiles = 0;
  const sbv_case *c = case_at(index);
  if (!c || !opt || !dir)
    return sbi_error(SB_EINVAL, __func__, "bad case index, options or "
                     "directory");
  for (size_t i = 0; NO_FILES[i].name; i++)
    if (!strcmp(NO_FILES[i].name, c->name)) {
      char path[1100];
      snprintf(path, sizeof path, "%s/NOT-WRITTEN.txt", dir);
      FILE *f = fopen(path, "a");
      int bad = !f;
      if (f) {
        bad = fprintf(f, "%s: no file: %s\n", c->name, NO_FILES[i].why) < 0;
        bad |= fclose(f) != 0;
      }
      return bad ? sbi_error(SB_EIO, __func__, "cannot write '%s'", path)
                 : SB_SUCCESS;
    }
  int ok = 0;
  for (int i = 0; INI_CASES[i]; i++)
    ok |= !strcmp(INI_CASES[i], c->name);
  if (!ok)
    return sbi_error(SB_EINVAL, __func__, "case %s has no engine run (the "
                     "engine cases: docs/validation.md, 'Reproducing a "
                     "case with smolbridge collide')", c->name);
  sb_validate_report *rep = sb_validate_report_alloc();
  if (!rep)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  sb_validate_options o = *opt;
  o.outdir = NULL;
  o.progress = NULL;
  sbv_report_begin_case(rep, c->name);
  sbv_ctx ctx = {opt->full != 0, opt->seed, NULL, &o, dir, rep};
  int st = c->run(&ctx, rep);
  sbv_report_end_case(rep, st, 0.0);
  if (!st && rep->ini_skipped[0]) {
    char path[1100];
    snprintf(path, sizeof path, "%s/NOT-WRITTEN.txt", dir);
    FILE *f = fopen(path, "a");
    if (f) {
      fprintf(f, "%s: runs without a collide configuration:\n%s", c->name,
              rep->ini_skipped);
      fclose(f);
    }
  }
  if (nfiles)
    *nfiles = rep->nini;
  sb_validate_report_free(rep);
  return st;
}
