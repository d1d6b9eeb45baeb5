#!/usr/bin/python3
"""Reference vectors for the exact bridge of a Langevin particle in a
linear shear (tests/test_langevin_shear.c; lib/langevin/langevin_shear.c).

Run from the top of the source tree with Debian's python3 (python3-mpmath):
    /usr/bin/python3 tests/gen_shear_bridge_ref.py      (~2 min)
Writes tests/data/shear_bridge.csv.

Model (units tau = B = 1; x = h/tau, g = G tau), state (u_y, y, u_x, x):
    du_y = (c_y - u_y) dt + dW_y,  dy = u_y dt,
    du_x = (g y + c_x - u_x) dt + dW_x,  dx = u_x dt,
i.e. dS = (A S + b) dt + dW, b = (c_y, 0, c_x, 0).  Phi(t) = expm(A t);
the response to the drifts, a(t) = int_0^t Phi(r) dr (b), is the top
right block of expm([[A, I], [0, 0]] t); the noise covariance Sigma(t) is
Van Loan's (1978) (tests/gen_shear_noise_ref.py).  The bridge at s given
S(0), S(x) is computed by direct conditioning of the joint Gaussian law of
(S(s), S(x)) (the gain form: K = Sigma(s) Phi(x-s)^T Sigma(x)^-1,
ka = Phi(s) - K Phi(x), kb = K, kc = a(s) - K a(x),
cov = Sigma(s) - K Phi(x-s) Sigma(s)), at mp.dps = 200 + x/2.3 (Van
Loan's exponential holds e^{+x}): the library uses
the information form instead, so the two computations are independent.
Columns: x, g, s, then ka (16, row-major), kb (16), kc (8: rows, columns
c_x then c_y), cov (10: lower triangle by rows); 25 significant digits.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpmath import mp, mpf, matrix, expm  # noqa: E402
import gen_shear_noise_ref as gn  # noqa: E402

mp.dps = 200
gn.mp.dps = 200
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "data", "shear_bridge.csv")

XS = [1e-6, 1e-3, 0.1, 1.0, 3.0, 10.0, 100.0, 1000.0]
GS = [0.0, 0.05, 0.4, 3.0]
FS = [0.00529953250417503, 0.25, 0.5, 0.9]  # s/x; the first: 16-point
                                           # Gauss-Legendre's first node


def phi(t, g):
    return expm(gn.amat(mpf(g)) * t)


def resp(t, g):
    """int_0^t Phi(r) dr, columns for b = e_ux (c_x) and e_uy (c_y)."""
    A = gn.amat(mpf(g))
    M = matrix(8, 8)
    for i in range(4):
        for j in range(4):
            M[i, j] = A[i, j] * t
        M[i, 4 + i] = t
    F = expm(M)
    a = matrix(4, 2)
    for i in range(4):
        a[i, 0] = F[i, 4 + 2]
        a[i, 1] = F[i, 4 + 0]
    return a


def f25(v):
    return mp.nstr(v, 25, min_fixed=1, max_fixed=0) if v != 0 else "0"


def row(x, g, s):
    x, s = mpf(x), mpf(s)
    r = x - s
    Ss = gn.sigma_vanloan(s, g)
    Sh = gn.sigma_vanloan(x, g)
    Ps, Pr, Ph = phi(s, g), phi(r, g), phi(x, g)
    As, Ah = resp(s, g), resp(x, g)
    K = Ss * Pr.T * Sh**-1
    ka = Ps - K * Ph
    kb = K
    kc = As - K * Ah
    cov = Ss - K * Pr * Ss
    out = [ka[i, j] for i in range(4) for j in range(4)]
    out += [kb[i, j] for i in range(4) for j in range(4)]
    out += [kc[i, j] for i in range(4) for j in range(2)]
    out += [cov[i, j] for i in range(4) for j in range(i + 1)]
    return out


def main():
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        f.write("# gen_shear_bridge_ref.py: bridge of (u_y, y, u_x, x) in "
                "the linear shear, tau = B = 1, by direct conditioning at "
                "200 digits\n")
        names = (["ka%d%d" % (i, j) for i in range(4) for j in range(4)] +
                 ["kb%d%d" % (i, j) for i in range(4) for j in range(4)] +
                 ["kc%d%d" % (i, j) for i in range(4) for j in range(2)] +
                 ["cov%d%d" % (i, j) for i in range(4) for j in range(i + 1)])
        f.write(",".join(["x", "g", "s"] + names) + "\n")
        for x in XS:
            for g in GS:
                if g * x > 100.0:
                    continue
                # Van Loan's exponential holds e^{+x}: 200 digits beyond it
                mp.dps = gn.mp.dps = 200 + int(x / 2.3)
                for fr in FS:
                    s = float(repr(x * fr)) if fr != 0.5 else x / 2
                    vals = row(x, g, s)
                    f.write(",".join([repr(x), repr(g), repr(s)] +
                                     [f25(v) for v in vals]) + "\n")


if __name__ == "__main__":
    main()
