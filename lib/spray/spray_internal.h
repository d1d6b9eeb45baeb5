/* spray_internal.h — the sb_spray object and helpers shared by the files of
 * the spray module (not installed). */
#ifndef SB_SPRAY_INTERNAL_H
#define SB_SPRAY_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/spray.h>

#define SBI_PI 3.14159265358979323846

struct sb_spray {
  sb_spray_params p;
  size_t n, cap;
  double *v;     /* 3 n velocities */
  double *r;     /* radii */
  double *w;     /* weights (Bird: all p.weight) */
  double *y, *yd;/* TAB deformation and its rate */
  double *shed;  /* Reitz: shed volume not yet emitted (all droplets) */
  unsigned char *formed; /* Reitz: 1 once the parcel's drops are formed
                            (the one-off B0 Lambda > a branch done, or
                            born as Reitz children): no blob branch */
  int *tag;
  double t;
  double ntc_rem;        /* NTC: fractional candidate carried over */
  sb_spray_stats st;
  sb_spray_event_fn ev;
  void *evctx;
};

/* Make room for `extra` more parcels (SB_ENOMEM on failure, recorded
 * against `func`). */
int sbi_spray_reserve(sb_spray *s, size_t extra, const char *func);

/* Append a parcel without argument checks (room must exist). */
size_t sbi_spray_push(sb_spray *s, const double v[3], double r, double w,
                      int tag);

/* Remove parcel i by moving the last parcel into its place. */
void sbi_spray_remove(sb_spray *s, size_t i);

/* Droplet mass rho 4/3 pi r^3. */
static inline double sbi_spray_mass(double rho, double r)
{
  return rho * (4.0 / 3.0) * SBI_PI * r * r * r;
}

/* Neumaier compensated sum. */
typedef struct {
  double s, c;
} sbi_ksum;
static inline void sbi_ksum_add(sbi_ksum *k, double x)
{
  double t = k->s + x;
  if (fabs(k->s) >= fabs(x))
    k->c += (k->s - t) + x;
  else
    k->c += (x - t) + k->s;
  k->s = t;
}
static inline double sbi_ksum_get(const sbi_ksum *k) { return k->s + k->c; }

/* A unit vector uniform on the circle perpendicular to the unit vector e. */
void sbi_spray_perp_dir(const double e[3], gsl_rng *rng, double n[3]);

#endif /* SB_SPRAY_INTERNAL_H */
