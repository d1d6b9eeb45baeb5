/* cases_spray.h — shared helpers and case functions of the spray
 * validation cases (V13 in cases_spray.c and cases_spray_relax.c, V14 in
 * cases_spray2.c); private to lib/validate. */
#ifndef SB_VALIDATE_CASES_SPRAY_H
#define SB_VALIDATE_CASES_SPRAY_H

#include <stddef.h>
#include <smolbridge/spray.h>
#include "cases.h"

/* Verdict level of every spray record: a run makes dozens of comparisons,
 * so a single one fails at p < 1e-3 (the table still shows the 95%
 * interval). */
#define SBV_SPRAY_ALPHA 1e-3

/* Record the mean of R >= 2 independent replica estimates x[] against
 * `ref`: 95% Student interval, two-sided t-test p-value (R - 1 degrees of
 * freedom), PASS iff p >= SBV_SPRAY_ALPHA.  Returns a status. */
int sbv_spray_add_replicas(sbv_report *rep, const char *name,
                           const double *x, size_t R, double ref);

/* Record a standard-normal statistic z (two-sided p-value). */
int sbv_spray_add_z(sbv_report *rep, const char *name, double est,
                    double ref, double z);

/* Record a deterministic comparison: PASS iff |est - ref| <= tol. */
int sbv_spray_add_tol(sbv_report *rep, const char *name, double est,
                      double ref, double tol);

/* Droplet mass 4/3 pi r^3 rho. */
double sbv_spray_mass(double r, double rho);

int sbv_spray_case_two_temp(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_engine(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_coal_const(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_coal_gravity(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_tab(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_reitz(const sbv_ctx *ctx, sbv_report *rep);

#endif /* SB_VALIDATE_CASES_SPRAY_H */
