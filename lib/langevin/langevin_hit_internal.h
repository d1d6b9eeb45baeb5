/* langevin_hit_internal.h — the pair first-contact sampler's workspace
 * (private to lib/langevin). */
#ifndef SB_LANGEVIN_HIT_INTERNAL_H
#define SB_LANGEVIN_HIT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <smolbridge/langevin_hit.h>

/* Gauss-Legendre nodes of the Rice integral on a sub-interval. */
#define SBI_LH_NQ 16
/* Deepest refinement level (h = dt / 2^60). */
#define SBI_LH_MAXDEPTH 60
/* Cached (tau, B, dt) triples (least recently used replaced). */
#define SBI_LH_NSLOT 8

/* Conditional law of one particle's state at a time a + xi h inside a
 * sub-interval [a, a + h] given its states at both ends, per component:
 *   E[x] = x_a + ax (x_b - x_a) + bx u_a + cx u_b + wx w,
 *   E[u] =       au (x_b - x_a) + bu u_a + cu u_b + wu w,
 * (w the fluid velocity seen; the coefficients of x_a and x_b sum to 1 for
 * x and to 0 for u: translation invariance) and covariance (vx, vu, cxu),
 * the same for every component. */
typedef struct {
  double ax, bx, cx, wx;
  double au, bu, cu, wu;
  double vx, vu, cxu;
} sbi_lh_coef;

/* Linear shear (slots with G != 0 and noise): the in-plane bridge of
 * S = (u_y, y, u_x, x) on a level (sb_langevin_shear_bridge_coefs, in
 * the caller's units): E[S] = ka S_a + kb S_b + kc (c_x, c_y), the
 * covariance cov, at the quadrature nodes and at the midpoint (with its
 * lower Cholesky factor ml); vmax and umax bound the variance of the
 * position (velocity) along any direction over the nodes (the largest
 * eigenvalue of the in-plane block, or the third component's). */
typedef struct {
  double ka[SBI_LH_NQ][4][4], kb[SBI_LH_NQ][4][4], kc[SBI_LH_NQ][4][2];
  double cov[SBI_LH_NQ][4][4];
  double mka[4][4], mkb[4][4], mkc[4][2], ml[4][4];
  double vmax, umax;
  /* for the closed-form bound: over the nodes, the largest |coefficient|
   * of the mean's deviation from the chord (rows 0, 1: x, y) and of the
   * mean velocity (rows 2, 3: u_x, u_y) on the inputs that determine
   * them, (x_b - x_a, y_b - y_a, u_x(a), u_y(a), u_x(b), u_y(b), w_x, w_y),
   * w = (c_x + G y_a, c_y) the fluid velocity at the start (translation
   * invariance: nothing else enters) */
  double km[4][8];
} sbi_lh_shear;

/* One refinement level of one (tau, B, dt): sub-intervals of length h. */
typedef struct {
  int valid;
  double h;
  sbi_lh_coef q[SBI_LH_NQ];  /* at the quadrature nodes */
  /* the same by coefficient (node index last: the node loops vectorise);
   * axr = ax - xi, the deviation of E[x] from the chord */
  double axr[SBI_LH_NQ], bx[SBI_LH_NQ], cx[SBI_LH_NQ], wx[SBI_LH_NQ];
  double au[SBI_LH_NQ], bu[SBI_LH_NQ], cu[SBI_LH_NQ], wu[SBI_LH_NQ];
  double vx[SBI_LH_NQ], vu[SBI_LH_NQ], cxu[SBI_LH_NQ];
  sbi_lh_coef mid;           /* at the midpoint */
  double l11, l21, l22;      /* Cholesky factor of the midpoint covariance */
  /* bounds over the nodes: |E[x] - chord| <= ka |x_b - x_a| + kb |u_a| +
   * kc |u_b| + kw |w| per component, |E[u]| <= the same with the u
   * coefficients (kau ...), and the largest variances */
  double ka, kb, kc, kw, vxmax;
  double kau, kbu, kcu, kwu, vumax;
  sbi_lh_shear *sh;          /* shear slots: the in-plane bridge */
} sbi_lh_level;

typedef struct {
  int used;
  double tau, B, htop;       /* key (B = 0 for free flight) */
  double G;                  /* key: linear shear rate (0: none) */
  int det;                   /* no noise: tau = inf or B = 0 */
  int shear;                 /* noise and G != 0: levels carry sh */
  uint64_t stamp;            /* last use */
  sbi_lh_level *lev[SBI_LH_MAXDEPTH + 1];  /* lazily filled */
} sbi_lh_slot;

struct sb_langevin_hitter {
  sb_langevin_hit_params par;
  double xi[SBI_LH_NQ], wq[SBI_LH_NQ];  /* nodes and weights on [0, 1] */
  sbi_lh_slot slot[SBI_LH_NSLOT];
  uint64_t clock;
  sb_langevin_hit_stats st;
  /* the entries of the last sb_langevin_hitter_sample_all call */
  sb_langevin_contact *ent;
  size_t nent, capent;
};

/* The slot of (tau, B, htop), filled or recycled; NULL on allocation
 * failure. */
sbi_lh_slot *sbi_lh_slot_get(sb_langevin_hitter *w, double tau, double B,
                             double htop, double G);
/* Level d of a slot (computed on first use); NULL on failure. */
const sbi_lh_level *sbi_lh_level_get(sb_langevin_hitter *w, sbi_lh_slot *s,
                                     unsigned d);
/* Coefficients at time s into a sub-interval of length h (0 <= s <= h) of
 * a particle (tau, B); for the contact states at a leaf.  Status. */
int sbi_lh_coef_at(double tau, double B, double h, double s, sbi_lh_coef *c);
/* The same at an interior time (0 < s < h, s and h - s >= 1e-60 tau) of
 * a noisy particle (tau, B > 0 finite), in one pass (langevin_bridge.c);
 * SB_EDOM outside that domain. */
int sbi_lh_bridge_coef(double tau, double B, double h, double s,
                       sbi_lh_coef *c);
/* Release the cached levels. */
void sbi_lh_slots_free(sb_langevin_hitter *w);

#endif /* SB_LANGEVIN_HIT_INTERNAL_H */
