#!/usr/bin/env python3
"""Reference values of sb_kernel_shear_langevin (tests/test_kernel.c):
the pass-through flux of two identical Langevin spheres in the linear
shear U_x = G y,

  K = R^2 int dOmega [s phi(m/s) - m Phi(-m/s)],  m = G R n_x n_y,
  s^2 = n.S.n,  S = 2 u2 [[1 + (G tau)^2/2, -G tau/2, 0],
                          [-G tau/2, 1, 0], [0, 0, 1]],

R = r_i + r_j, by two nested tanh-sinh quadratures of mpmath at 30
digits (phi split at the quarter turns, where n_x n_y changes sign).
Columns: r_i, r_j (m), u2 (m^2/s^2), tau (s), G (1/s), K (m^3/s).

Run: python3 tests/gen_kernel_shear_langevin_ref.py > tests/data/kernel_shear_langevin.csv
"""
import mpmath as mp

mp.mp.dps = 30


def flux(ri, rj, u2, tau, G):
    ri, rj, u2, tau, G = (mp.mpf(v) for v in (ri, rj, u2, tau, G))
    R = ri + rj
    gt = G * tau

    def integrand(th, ph):
        nx = mp.sin(th) * mp.cos(ph)
        ny = mp.sin(th) * mp.sin(ph)
        nz = mp.cos(th)
        m = G * R * nx * ny
        var = 2 * u2 * ((1 + gt * gt / 2) * nx * nx - gt * nx * ny + ny * ny
                        + nz * nz)
        s = mp.sqrt(var)
        z = m / s
        val = (s * mp.exp(-z * z / 2) / mp.sqrt(2 * mp.pi)
               - m * mp.erfc(z / mp.sqrt(2)) / 2)
        return val * mp.sin(th)

    q = mp.pi / 2
    total = mp.quad(integrand, [0, mp.pi / 2, mp.pi],
                    [0, q, 2 * q, 3 * q, 4 * q])
    return R * R * total


def main():
    rows = []
    r = 5e-6
    R = 2 * r
    for pk in (0.3, 1.0, 3.0):
        for gt in (0.01, 0.5):
            u2 = 0.5 * (1000.0 * R / pk) ** 2
            rows.append((r, r, u2, gt / 1000.0, 1000.0))
    rows.append((r, r, 0.5 * (1000.0 * R) ** 2, 1e-5, 0.0))
    rows.append((1e-6, 3e-6, 2e-3, 2e-4, 150.0))
    # large G tau, where the integrand has a kink of width 1/(G tau) at
    # n_x = 0 (phi = pi/2, a breakpoint here) and K -> R^2 sqrt(2 pi u2) G tau
    rows.append((1e-6, 1e-6, 1e-6, 1e3, 1.0))
    rows.append((1e-6, 1e-6, 1e-6, 1e6, 1.0))
    print("# sb_kernel_shear_langevin: pass-through flux of identical "
          "Langevin spheres in shear")
    print("# (tests/gen_kernel_shear_langevin_ref.py, mpmath 30 digits)")
    print("r_i,r_j,u2,tau,G,K")
    for ri, rj, u2, tau, G in rows:
        K = flux(ri, rj, u2, tau, G)
        print("%r,%r,%r,%r,%r,%s" % (ri, rj, u2, tau, G,
                                     mp.nstr(K, 20, min_fixed=1,
                                             max_fixed=0)))


if __name__ == "__main__":
    main()
