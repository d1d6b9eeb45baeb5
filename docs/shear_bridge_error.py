#!/usr/bin/python3
"""How far the Langevin detector's conditional law is from the exact one in
a linear shear (docs/engine_langevin.md, "Shear").  Run from the top of
the source tree: /usr/bin/python3 docs/shear_bridge_error.py (~5 s).

One particle, state (u_y, y, u_x, x), units tau = B = 1, shear g = G tau
(the model of tests/gen_shear_noise_ref.py, whose Van Loan covariance is
reused).  Given the step's end states S_0, S_h the state at m = h/2 is
Gaussian: exact mean Phi(m) S_0 + K (S_h - Phi(h) S_0), K = Sigma(m)
Phi(h-m)^T Sigma(h)^-1, covariance Sigma(m) - K Phi(h-m) Sigma(m).  The
detector uses the same with g = 0 (independent per-component OU bridges;
a constant fluid velocity does not change them).  Printed: the rms over
the ends (velocities at S_0 ~ N(0, 1/2), S_h from the exact step) of the
difference of the two conditional means of x and of y, in units of the
exact conditional standard deviation; the exact conditional correlation of
x and y (the detector's is 0); the relative error of the conditional
variance of x.  mp.dps = 150 (Van Loan's exponential holds e^{+h}).
"""
import sys
import os
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from mpmath import mp, mpf, matrix, expm, sqrt
import gen_shear_noise_ref as g
g.mp.dps = 150
mp.dps = 150

def phi(x, gg):
    return expm(g.amat(mpf(gg)) * x)

def sig(x, gg):
    return g.sigma_vanloan(mpf(x), gg)

def bridge(h, gg, m):
    Sm, Sh, Pr = sig(m, gg), sig(h, gg), phi(h - m, gg)
    K = Sm * Pr.T * Sh**-1
    P = Sm - K * Pr * Sm
    return K, P, phi(m, gg), phi(h, gg), Sh

def row(h, Gh):
    gg = Gh / h
    m = h / 2
    K, P, Pm, Ph, Sh = bridge(h, gg, m)
    K0, P0, Pm0, Ph0, _ = bridge(h, 0, m)
    M = Pm - Pm0 - K0 * (Ph - Ph0)
    C0 = matrix(4, 4); C0[0, 0] = C0[2, 2] = mpf(1) / 2
    D = M * C0 * M.T + (K - K0) * Sh * (K - K0).T
    # order (u_y, y, u_x, x)
    sx = sqrt(D[3, 3] / P[3, 3]); sy = sqrt(D[1, 1] / P[1, 1])
    corr = P[3, 1] / sqrt(P[3, 3] * P[1, 1])
    dv = P[3, 3] / P0[3, 3] - 1
    return sx, sy, corr, dv

print("h/tau  G h   rms dmean_x/sd  rms dmean_y/sd  corr(x,y|ends)  var_x/var0_x-1")
for h in [0.05, 1.0, 10.0, 100.0]:
    for Gh in [0.01, 0.1, 0.4]:
        sx, sy, c, dv = row(h, Gh)
        print("%6g %5g %14.3g %14.3g %14.3g %14.3g" % (h, Gh, sx, sy, c, dv))
