#!/usr/bin/python3
"""Reference vectors for the langevin module (tests/test_langevin.c).

Run from the top of the source tree with Debian's python3 (python3-mpmath):
    /usr/bin/python3 tests/gen_langevin_ref.py
Writes tests/data/langevin_var.csv, langevin_moments.csv, langevin_bridge.csv,
langevin_extreme.csv.

Model, per component (unit-free):
    dX = U dt,  dU = (us - U)/tau dt + B dW.
Everything is computed at mp.dps = 150 from the NAIVE textbook formulas,
which cancel catastrophically for t << tau but are harmless at that
precision; the C library uses different, cancellation-free forms, so the
comparison is independent.  The conditioned (bridge) moments are computed by
a different route from the library too: Gaussian conditioning of the 4x4
joint law of (Z_s, Z_t), Z = (X, U), instead of the library's information
(precision-matrix) form.  Inputs are Python floats (exact binary doubles)
printed with repr(), so C reads exactly the values used here.
"""
import os
import sys

from mpmath import mp, mpf, exp, quad, matrix

mp.dps = 150

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")


def f17(x):
    """Text of an mpf with 20 significant digits (more than a double)."""
    return mp.nstr(x, 20, min_fixed=1, max_fixed=0) if x != 0 else "0"


def ou_moments(tau, B, us, t, x0, u0):
    """Mean and covariance of (X_t, U_t) given (x0, u0): textbook forms
    (e.g. Gardiner, Handbook of Stochastic Methods, sec. 3.8.4; Mohaupt
    2011, eqs D.1-D.6 with us = 0)."""
    tau, B, us, t, x0, u0 = map(mpf, (tau, B, us, t, x0, u0))
    e = exp(-t / tau)
    mean_x = x0 + us * t + (u0 - us) * tau * (1 - e)
    mean_u = us + (u0 - us) * e
    var_u = B**2 * tau / 2 * (1 - e**2)
    var_x = B**2 * tau**2 * (t - 2 * tau * (1 - e) + tau / 2 * (1 - e**2))
    cov = B**2 * tau**2 * (1 - e)**2 / 2
    return mean_x, mean_u, var_x, var_u, cov


def var_row(tau, B, t):
    tau_, B_, t_ = map(mpf, (tau, B, t))
    _, _, vx, vu, cv = ou_moments(tau, B, 0.0, t, 0.0, 0.0)
    e = exp(-t_ / tau_)
    # conditional variance of X given U (the x-noise of Mohaupt 2011, eq 1.16)
    vxc = B_**2 * tau_**2 * (t_ - 2 * tau_ * (1 - e) / (1 + e))
    # MSD with a Maxwellian initial velocity (Ornstein 1919; Uhlenbeck &
    # Ornstein 1930): <(X_t - X_0)^2> = B^2 tau^2 (t - tau (1 - e)).
    msd = B_**2 * tau_**2 * (t_ - tau_ * (1 - e))
    vacf = B_**2 * tau_ / 2 * e
    # self-checks of the closed forms (independent of the C code):
    # conditional variance = var_x - cov^2/var_u
    assert abs(vxc - (vx - cv**2 / vu)) <= mpf(10)**-60 * vx
    # MSD = var_x + tau^2 (1-e)^2 <u0^2>,  <u0^2> = B^2 tau/2
    assert abs(msd - (vx + tau_**2 * (1 - e)**2 * B_**2 * tau_ / 2)) \
        <= mpf(10)**-60 * msd
    return [tau, B, t, vx, vu, cv, vxc, msd, vacf]


def check_quadrature():
    """var_x = B^2 tau^2 int_0^t (1 - e^{-r/tau})^2 dr (Ito isometry)."""
    for h in (1e-3, 0.3, 1.0, 7.0):
        tau, B = mpf(1.7), mpf(0.9)
        t = mpf(h) * tau
        vx = ou_moments(tau, B, 0, t, 0, 0)[2]
        q = quad(lambda r: (B * tau * (1 - exp(-r / tau)))**2, [0, t])
        assert abs(q - vx) < mpf(10)**-40 * vx, (h, q, vx)


def bridge_row(tau, B, us, dt, s, x0, u0, x1, u1):
    """Law of Z_s given Z_0 = (x0,u0), Z_dt = (x1,u1): condition the joint
    Gaussian of (Z_s, Z_dt).  Cov(Z_s, Z_dt) = Sigma(s) Phi(dt-s)^T with
    Phi(h) = [[1, tau(1-e^{-h/tau})], [0, e^{-h/tau}]]."""
    mx_s, mu_s, vx_s, vu_s, cv_s = ou_moments(tau, B, us, s, x0, u0)
    mx_t, mu_t, vx_t, vu_t, cv_t = ou_moments(tau, B, us, dt, x0, u0)
    tau_ = mpf(tau)
    r = mpf(dt) - mpf(s)
    er = exp(-r / tau_)
    Phi = matrix([[1, tau_ * (1 - er)], [0, er]])
    Ss = matrix([[vx_s, cv_s], [cv_s, vu_s]])
    St = matrix([[vx_t, cv_t], [cv_t, vu_t]])
    C = Ss * Phi.T
    K = C * St**-1
    d = matrix([mpf(x1) - mx_t, mpf(u1) - mu_t])
    m = matrix([mx_s, mu_s]) + K * d
    S = Ss - K * C.T
    return [tau, B, us, dt, s, x0, u0, x1, u1,
            m[0], m[1], S[0, 0], S[1, 1], S[0, 1]]


def extreme_row(tau, B, t):
    """var_row plus the exact-step coefficients at an extreme corner
    (t/tau down to 1e-620 or up to 1e620, B^2 or tau^3 beyond the double
    range).  The naive forms cancel to O(h^3) of their O(h) terms, so the
    working precision is raised to 3 |log10 h| + 60 digits."""
    import math
    h = abs(math.log10(t) - math.log10(tau))
    with mp.workdps(int(3 * h) + 60):
        row = var_row(tau, B, t)
        vx, vu, cv, vxc = (mpf(v) for v in row[3:7])
        tau_, t_ = mpf(tau), mpf(t)
        gain = tau_ * (1 - exp(-t_ / tau_))
        s_u = vu**0.5
        # s_xu = cov/s_u, s_xc = sqrt(var_x|u) (langevin.h, exact step)
        # the means from (x0, u0) = (1.5, -0.8) with us = 0.37
        mx, mu = ou_moments(tau, B, 0.37, t, 1.5, -0.8)[:2]
        row = row + [gain, s_u, cv / s_u, vxc**0.5, mx, mu]
        # below half the smallest subnormal the double is 0 (vacf =
        # B^2 tau/2 e^{-1e300}): write 0, not a 10^(-4e299) literal
        return [v if isinstance(v, float) else
                (+v if abs(v) >= mpf(2)**-1075 else mpf(0)) for v in row]


def write(name, header, rows, dps=None):
    path = os.path.join(DATA, name)
    with open(path, "w") as f:
        f.write("# generated by tests/gen_langevin_ref.py (mpmath, dps=%s)\n"
                % (dps or mp.dps))
        f.write(",".join(header) + "\n")
        for row in rows:
            f.write(",".join(repr(v) if isinstance(v, float) else f17(v)
                             for v in row) + "\n")
    print("wrote", path, len(rows), "rows", file=sys.stderr)


def main():
    check_quadrature()

    # ---------------------------------------------------- variances
    hs = [1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.3, 0.5, 0.9, 1.0,
          1.1, 1.9, 2.0, 2.1, 3.0, 5.0, 10.0, 30.0, 100.0, 1e3, 1e4, 1e6,
          1e8, 1e10]
    rows = []
    for tau, B in ((1.0, 1.0), (3e-6, 2.27), (2.5, 0.3)):
        for h in hs:
            rows.append(var_row(tau, B, h * tau))
    write("langevin_var.csv",
          ["tau", "B", "t", "var_x", "var_u", "cov_xu", "var_x_cond", "msd",
           "vacf"], rows)

    # ---------------------------------------------------- moments
    rows = []
    for tau, B, us, x0, u0 in ((1.0, 1.0, 0.0, 0.0, 0.0),
                               (3e-6, 2.27, 0.0, 1e-6, 0.8),
                               (2.5, 0.3, -0.7, 12.5, 1.3),
                               (0.01, 5.0, 2.0, -3.0, -4.0)):
        for h in (1e-8, 1e-4, 0.2, 1.0, 4.0, 1e4, 1e8):
            t = h * tau
            rows.append([tau, B, us, t, x0, u0]
                        + list(ou_moments(tau, B, us, t, x0, u0)))
    write("langevin_moments.csv",
          ["tau", "B", "us", "t", "x0", "u0", "mean_x", "mean_u", "var_x",
           "var_u", "cov_xu"], rows)

    # ---------------------------------------------------- bridge
    rows = []
    for tau, B, us, x0, u0 in ((1.0, 1.0, 0.0, 0.0, 0.0),
                               (3e-6, 2.27, 0.0, 0.0, 1.5),
                               (2.5, 0.3, -0.7, 12.5, 1.3)):
        for h in (1e-8, 1e-4, 0.05, 1.0, 6.0, 1e3, 1e6):
            dt = h * tau
            mx, mu, vx, vu, cv = ou_moments(tau, B, us, dt, x0, u0)
            # an end state about one standard deviation from its mean
            x1 = float(mx + mpf("0.7") * vx**0.5)
            u1 = float(mu - mpf("1.1") * vu**0.5)
            for frac in (1e-3, 0.25, 0.5, 0.8, 0.999):
                s = frac * dt
                rows.append(bridge_row(tau, B, us, dt, s, x0, u0, x1, u1))
    write("langevin_bridge.csv",
          ["tau", "B", "us", "dt", "s", "x0", "u0", "x1", "u1", "mean_x",
           "mean_u", "var_x", "var_u", "cov_xu"], rows)

    # ---------------------------------------------------- extreme corners
    # (tau, B, t) where t/tau, B^2 or tau^k leave the double range while
    # every value is a normal double (or 0 where it underflows)
    rows = [extreme_row(tau, B, t) for tau, B, t in (
        (1e300, 1.0, 1.0), (1e300, 1e-150, 1e100), (1.0, 1e150, 1e-100),
        (1e-300, 1e150, 1.0), (1e-300, 1e150, 1e300), (1e-320, 1e300, 1.0),
        (1e300, 1e-300, 1e300), (1.7976931348623157e308, 1.0, 1.0),
        (1e100, 1e-160, 1e100), (1e-200, 1e200, 3e-200))]
    write("langevin_extreme.csv",
          ["tau", "B", "t", "var_x", "var_u", "cov_xu", "var_x_cond", "msd",
           "vacf", "gain", "s_u", "s_xu", "s_xc", "mean_x", "mean_u"], rows,
          dps="3|log10 t/tau|+60")


if __name__ == "__main__":
    main()
