/* shear_rk4.h — the reference of the exact shear step in the tests: one
 * non-Brownian particle in the linear field U_x = G y with a settling
 * drift w_y along y, state (X, U, Y, V), integrated by classical RK4 with
 * n equal steps over T (fine enough that its error, O((T/n)^4), is far
 * below the tests' tolerances).  Used by test_engine_physics.c and
 * test_engine_shear_noise.c. */
#ifndef SB_TESTS_SHEAR_RK4_H
#define SB_TESTS_SHEAR_RK4_H

/* d/dt (X, U, Y, V): U relaxes to G Y over tau, V to w_y */
static inline void sbt_shear_rhs(const double *s, double tau, double G,
                                 double wy, double *d)
{
  d[0] = s[1];
  d[1] = (G * s[2] - s[1]) / tau;
  d[2] = s[3];
  d[3] = (wy - s[3]) / tau;
}

static inline void sbt_shear_rk4(double *s, double tau, double G, double wy,
                                 double T, long n)
{
  double h = T / (double)n, k1[4], k2[4], k3[4], k4[4], t[4];
  for (long q = 0; q < n; q++) {
    sbt_shear_rhs(s, tau, G, wy, k1);
    for (int c = 0; c < 4; c++)
      t[c] = s[c] + 0.5 * h * k1[c];
    sbt_shear_rhs(t, tau, G, wy, k2);
    for (int c = 0; c < 4; c++)
      t[c] = s[c] + 0.5 * h * k2[c];
    sbt_shear_rhs(t, tau, G, wy, k3);
    for (int c = 0; c < 4; c++)
      t[c] = s[c] + h * k3[c];
    sbt_shear_rhs(t, tau, G, wy, k4);
    for (int c = 0; c < 4; c++)
      s[c] += h / 6.0 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
  }
}

#endif
