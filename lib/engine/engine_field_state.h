/* engine_field_state.h — the state of the random fluid fields
 * (engine_field.c draws and evaluates them, engine_field_io.c saves and
 * restores them). */
#ifndef SBI_ENGINE_FIELD_STATE_H
#define SBI_ENGINE_FIELD_STATE_H

#include <stddef.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine_field.h>

struct sb_field_ou {
  size_t n;      /* particles */
  double *U;     /* 3 n, the velocities handed out at the next step */
  double u2, TL, dt;
  double b, q;   /* exp(-dt/TL), sd of the update noise */
  const gsl_rng *r;  /* generator (owned by the caller) */
};

/* The parameters of f and what follows from them (not U). */
void sbi_field_ou_set(sb_field_ou *f, size_t n, double u2, double TL,
                      double dt, const gsl_rng *r);

struct sb_field_kraichnan {
  double L, s2;
  double eps_nu, omega;      /* as given to sb_field_kraichnan_alloc */
  int M;
  size_t nm;                 /* modes */
  int m[SB_FIELD_KRAICHNAN_MAXMODES][3];
  double a[SB_FIELD_KRAICHNAN_MAXMODES][3], b[SB_FIELD_KRAICHNAN_MAXMODES][3];
  double w[SB_FIELD_KRAICHNAN_MAXMODES];
  const sb_engine *e;        /* attached engine (its time) */
};

#endif
