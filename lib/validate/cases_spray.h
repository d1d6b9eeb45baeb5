/* cases_spray.h — shared helpers and case functions of the spray
 * validation cases (V13 in cases_spray.c and cases_spray_relax.c, V14 in
 * cases_spray2.c); private to lib/validate. */
#ifndef SB_VALIDATE_CASES_SPRAY_H
#define SB_VALIDATE_CASES_SPRAY_H

#include <stddef.h>
#include <smolbridge/spray.h>
#include "cases.h"

/* Test level of the spray records (each row states it: intervals at
 * 1 - 1e-3 invert the test behind the row). */
#define SBV_SPRAY_ALPHA 1e-3

/* Record the mean of R >= 2 independent replica estimates x[] against
 * `ref`: Student interval at 1 - SBV_SPRAY_ALPHA and the two-sided t test
 * it inverts (R - 1 degrees of freedom): rule cover.  Returns a status. */
int sbv_spray_add_replicas(sbv_report *rep, const char *name,
                           const double *x, size_t R, double ref);

/* Record an estimate whose standard-normal statistic against ref is z:
 * acceptance region ref -+ z_{1-alpha/2} se (se = |est - ref|/|z|) and the
 * two-sided normal p-value: rule accept. */
int sbv_spray_add_z(sbv_report *rep, const char *name, double est,
                    double ref, double z);

/* Record a deterministic comparison: PASS iff |est - ref| <= tol (rule
 * band). */
int sbv_spray_add_tol(sbv_report *rep, const char *name, double est,
                      double ref, double tol);

/* Set-up of a validation spray: the fields that differ from
 * sb_spray_params_default.  Zero means the default (V = 1 m^3,
 * rho_l = 1000 kg/m^3, theta_cr = 0, capacity 1024). */
typedef struct {
  sb_spray_method method;
  double B0;          /* > 0: Maxwell-type kernel B0 (m^3/s); 0: hard spheres */
  double volume;      /* m^3 */
  double rho_l;       /* kg/m^3 */
  double theta_cr;    /* rad */
  size_t capacity;
  const sb_spray_settling *settling; /* non-NULL: merged drops take the
                                        Stokes settling velocity */
} sbv_spray_setup;

/* Allocate the spray of `u` (NULL on error, as sb_spray_alloc). */
sb_spray *sbv_spray_new(const sbv_spray_setup *u);

/* Droplet mass 4/3 pi r^3 rho. */
double sbv_spray_mass(double r, double rho);

int sbv_spray_case_two_temp(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_engine(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_coal_const(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_coal_gravity(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_tab(const sbv_ctx *ctx, sbv_report *rep);
int sbv_spray_case_reitz(const sbv_ctx *ctx, sbv_report *rep);

#endif /* SB_VALIDATE_CASES_SPRAY_H */
