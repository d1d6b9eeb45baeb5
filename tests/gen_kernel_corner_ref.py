#!/usr/bin/env python3
"""Reference values of the closed-form kernels at extreme arguments
(tests/test_kernel.c, test_extreme_arguments): each argument of each
kernel in turn set to 1e-320, 1e-300, 1e300 and DBL_MAX, the others at
the ordinary values of that test's table (same order, same values; the
quadrature kernel sb_kernel_shear_langevin, index 11, is left out).
Indices 19 and 20 (sb_kernel_diffusion_r2, sb_kernel_brownian_turb_r2)
come last, so that the rows of 0-18 are unchanged.

The formulas are those of lib/smolbridge/kernel.h and docs/kernel.md,
written here plainly and evaluated with mpmath at 50 digits, so that no
intermediate over- or underflows.  Inputs are exact doubles (mpmath sees
the exact value of the double, subnormals included).

Columns: f (index in the test's table), arg (which argument), x (its
value), K: the kernel to 20 digits; "inf" where it exceeds DBL_MAX (the C
code must report SB_ERANGE), 0 where it is below DBL_MIN (only checked to
be returned without error).

Run: python3 tests/gen_kernel_corner_ref.py > tests/data/kernel_corners.csv
"""
import sys

import mpmath as mp

mp.mp.dps = 50
kB = mp.mpf("1.380649e-23")
pi = mp.pi
DBL_MAX = sys.float_info.max
DBL_MIN = sys.float_info.min


def diffusivity(r, T, mu, lam):
    c = 1
    if lam > 0:
        kn = lam / r
        c = 1 + kn * (mp.mpf("1.257") + mp.mpf("0.4") * mp.exp(-mp.mpf("1.1") / kn))
    return kB * T * c / (6 * pi * mu * r)


def mass(rho, r):
    return rho * mp.mpf(4) / 3 * pi * r**3


def co(ri, rj, T, mu):
    return 4 * pi * (diffusivity(ri, T, mu, 0) + diffusivity(rj, T, mu, 0)) * (ri + rj)


def fm(ri, rj, T, rho):
    mr = 1 / (1 / mass(rho, ri) + 1 / mass(rho, rj))
    return pi * (ri + rj)**2 * mp.sqrt(8 * kB * T / (pi * mr))


def tr(ri, rj, T, mu, rho, lam):
    # Dahneke (1983) interpolation, Knudsen number K_co/(2 K_fm)
    kco = 4 * pi * (diffusivity(ri, T, mu, lam) + diffusivity(rj, T, mu, lam)) * (ri + rj)
    kfm = fm(ri, rj, T, rho)
    kn = kco / (2 * kfm)
    return kco * (1 + kn) / (1 + 2 * kn * (1 + kn))


def gh_parts(ri, rj, mi, mj, ti, tj, T):
    mr = mi * mj / (mi + mj)
    fi, fj = mi / ti, mj / tj
    fr = fi * fj / (fi + fj)
    R = ri + rj
    return mp.sqrt(kB * T * mr) / (fr * R), mr, fr, R


def ghkn(*a):
    return gh_parts(*a)[0]


def gh(*a):
    # Gopalakrishnan & Hogan (2011): beta = H f_red R^3 / m_red
    kn, mr, fr, R = gh_parts(*a)
    H = (4 * pi * kn**2 + mp.mpf("25.836") * kn**3
         + mp.sqrt(8 * pi) * mp.mpf("11.211") * kn**4) / \
        (1 + mp.mpf("3.502") * kn + mp.mpf("7.211") * kn**2 + mp.mpf("11.211") * kn**3)
    return H * fr * R**3 / mr


def kin(di, dj, mi, mj, T):
    return pi * ((di + dj) / 2)**2 * mp.sqrt(8 * kB * T / pi * (1 / mi + 1 / mj))


def kin2(di, dj, mi, mj, T):
    return (di + dj) * mp.sqrt(pi / 2 * kB * T * (1 / mi + 1 / mj))


def grav(ri, rj, rp, rf, mu, g):
    ui = 2 * (rp - rf) * g * ri**2 / (9 * mu)
    uj = 2 * (rp - rf) * g * rj**2 / (9 * mu)
    return pi * (ri + rj)**2 * abs(ui - uj)


def shear(ri, rj, G):
    return mp.mpf(4) / 3 * G * (ri + rj)**3


def st(ri, rj, eps, nu):
    return mp.sqrt(8 * pi * eps / (15 * nu)) * (ri + rj)**3


def ab(ri, rj, u1, u2):
    return mp.sqrt(8 * pi * (u1 + u2)) * (ri + rj)**2


def dif(ri, rj, b1, b2):
    return 2 * pi * (b1 + b2) * (ri + rj)


def b2(r, T, mu):
    return kB * T / (3 * pi * mu * r)


def tb2(r, eps, nu):
    return mp.sqrt(2 / (15 * pi)) * mp.sqrt(eps / nu) * r**2


def bt(ri, rj, T, mu, eps, nu):
    return dif(ri, rj, b2(ri, T, mu) + b2(rj, T, mu), tb2(ri + rj, eps, nu))


def dr2(R, b0, b2):
    # steady rate with b2(r) = b0 + b2 (r/R)^2: 2 pi b2 R/g(t), t^2 = b0/b2,
    # g(t) = (t - atan t)/t^3; t - atan t ~ t^3/3 cancels at small t, so
    # the working precision grows with -log10 t (t down to ~1e-170 here)
    if b2 == 0:
        return 2 * pi * b0 * R
    if b0 == 0:
        return 6 * pi * b2 * R
    t = mp.sqrt(b0 / b2)
    extra = max(0, int(-2 * mp.log10(t))) + 20
    with mp.extradps(extra):
        g = (t - mp.atan(t)) / t**3
        return 2 * pi * b2 * R / g


def btr2(ri, rj, T, mu, eps, nu):
    return dr2(ri + rj, b2(ri, T, mu) + b2(rj, T, mu), tb2(ri + rj, eps, nu))


def const(vi, vj, K):
    return K


def additive(vi, vj, K):
    return K * (vi + vj)


def mult(vi, vj, K):
    return K * vi * vj


# index in test_extreme_arguments' table, function, ordinary arguments
KERNELS = [
    (0, co, [1e-6, 2e-6, 300, 1e-3]),
    (1, fm, [1e-8, 2e-8, 300, 1000]),
    (2, tr, [1e-7, 2e-7, 300, 1.8e-5, 1000, 6.8e-8]),
    (3, gh, [1e-7, 2e-7, 4e-18, 3e-17, 1e-7, 3e-7, 300]),
    (4, ghkn, [1e-7, 2e-7, 4e-18, 3e-17, 1e-7, 3e-7, 300]),
    (5, kin, [1e-9, 2e-9, 1e-25, 2e-25, 300]),
    (6, kin2, [1e-9, 2e-9, 1e-25, 2e-25, 300]),
    (7, grav, [1e-6, 2e-6, 2000, 1000, 1e-3, 9.81]),
    (8, shear, [1e-6, 2e-6, 10]),
    (9, st, [1e-6, 2e-6, 1e-3, 1e-6]),
    (10, ab, [1e-6, 2e-6, 1e-4, 2e-4]),
    (12, dif, [1e-6, 2e-6, 1e-12, 2e-12]),
    (13, b2, [1e-6, 300, 1e-3]),
    (14, tb2, [1e-6, 1e-3, 1e-6]),
    (15, bt, [1e-6, 2e-6, 300, 1e-3, 1e-3, 1e-6]),
    (16, const, [1e-18, 2e-18, 1e-9]),
    (17, additive, [1e-18, 2e-18, 1e-9]),
    (18, mult, [1e-18, 2e-18, 1e-9]),
    (19, dr2, [2e-6, 1e-12, 2e-12]),
    (20, btr2, [1e-6, 2e-6, 300, 1e-3, 1e-3, 1e-6]),
]
EXTREMES = [1e-320, 1e-300, 1e300, DBL_MAX]


def main():
    print("f,arg,x,K")
    for f, fn, base in KERNELS:
        for i in range(len(base)):
            for x in EXTREMES:
                a = [mp.mpf(v) for v in base]
                a[i] = mp.mpf(x)
                K = fn(*a)
                if K > DBL_MAX:
                    ks = "inf"
                elif K < DBL_MIN:
                    ks = "0"
                else:
                    ks = mp.nstr(K, 20, min_fixed=1, max_fixed=0)
                print("%d,%d,%r,%s" % (f, i, x, ks))


if __name__ == "__main__":
    main()
