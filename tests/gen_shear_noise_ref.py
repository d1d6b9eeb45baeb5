#!/usr/bin/python3
"""Reference vectors for the exact shear noise of the engine's Langevin step
(tests/test_engine_shear_noise.c; lib/engine/engine_lees.c).

Run from the top of the source tree with Debian's python3 (python3-mpmath):
    /usr/bin/python3 tests/gen_shear_noise_ref.py
Writes tests/data/shear_noise_cov.csv and tests/data/shear_noise_chol.csv.

Model (units tau = B = 1; x = h/tau, g = G tau), state (u_y, y, u_x, x):
    du_y = -u_y dt + dW_y,  dy = u_y dt,
    du_x = (g y - u_x) dt + dW_x,  dx = u_x dt,
i.e. ds = A s dt + dW with Q = diag(1, 0, 1, 0).  The covariance of the
noise over a step x is Sigma(x) = int_0^x Phi(s) Q Phi(s)^T ds,
Phi = expm(A s).  It is computed here by Van Loan's method (C. F. Van Loan
1978, "Computing integrals involving the matrix exponential", IEEE Trans.
Automat. Control 23:395, Theorem 1): expm([[-A, Q], [0, A^T]] x) =
[[F11, F12], [0, F22]], Sigma = F22^T F12, at mp.dps = 80 (the entries
cancel as x^7 at small x; 80 digits leave > 40).  Independent of the C
code, which integrates closed-form kernels.  As a self-check the script
compares Sigma with mp.quad of Phi Q Phi^T at a few points and aborts on a
mismatch.  The Cholesky factor (lower, in the order above) is mpmath's.
Inputs are exact doubles (repr()), 20 significant digits out.
"""
import os
import sys

from mpmath import mp, mpf, matrix, expm, quad, cholesky

mp.dps = 80
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")

XS = [1e-3, 3e-3, 0.01, 0.1, 0.5, 1.0, 1.4999999, 1.5, 2.0, 5.0, 10.0,
      30.0, 100.0]
GS = [1e-3, 0.01, 0.04, 0.1, 0.4, 1.0, 3.0, 10.0]


def f20(v):
    return mp.nstr(v, 20, min_fixed=1, max_fixed=0) if v != 0 else "0"


def amat(g):
    A = matrix(4, 4)
    A[0, 0] = -1
    A[1, 0] = 1
    A[2, 2] = -1
    A[2, 1] = g
    A[3, 2] = 1
    return A


QD = [1, 0, 1, 0]


def sigma_vanloan(x, g):
    A = amat(mpf(g))
    M = matrix(8, 8)
    for i in range(4):
        for j in range(4):
            M[i, j] = -A[i, j] * x
            M[4 + i, 4 + j] = A[j, i] * x
        M[i, 4 + i] = QD[i] * x
    F = expm(M)
    F12 = matrix(4, 4)
    F22 = matrix(4, 4)
    for i in range(4):
        for j in range(4):
            F12[i, j] = F[i, 4 + j]
            F22[i, j] = F[4 + i, 4 + j]
    return F22.T * F12


def sigma_quad(x, g):
    A = amat(mpf(g))

    def ent(i, j):
        def f(s):
            P = expm(A * s)
            return sum(P[i, k] * QD[k] * P[j, k] for k in range(4))
        return quad(f, [0, x])
    return [[ent(i, j) for j in range(4)] for i in range(4)]


def main():
    os.makedirs(DATA, exist_ok=True)
    old = mp.dps
    mp.dps = 40
    for x, g in [(0.5, 1.0), (3.0, 0.3), (0.01, 10.0)]:
        S = sigma_vanloan(mpf(x), g)
        T = sigma_quad(mpf(x), g)
        for i in range(4):
            for j in range(i + 1):
                if abs(S[i, j] - T[i][j]) > mpf(10)**-30 * abs(T[i][j]):
                    sys.exit("Van Loan vs quad mismatch at x=%r g=%r (%d,%d)"
                             % (x, g, i, j))
    mp.dps = old
    names = ["uy_uy", "y_uy", "y_y", "ux_uy", "ux_y", "ux_ux", "x_uy",
             "x_y", "x_ux", "x_x"]
    lnames = ["L31", "L32", "L33", "L41", "L42", "L43", "L44"]
    with open(os.path.join(DATA, "shear_noise_cov.csv"), "w") as fc, \
            open(os.path.join(DATA, "shear_noise_chol.csv"), "w") as fl:
        fc.write("# gen_shear_noise_ref.py: Sigma(x) of (u_y, y, u_x, x), "
                 "tau = B = 1, x = h/tau, g = G tau (Van Loan 1978)\n")
        fc.write(",".join(["x", "g"] + names) + "\n")
        fl.write("# gen_shear_noise_ref.py: x rows of the lower Cholesky "
                 "factor of Sigma in the order (u_y, y, u_x, x)\n")
        fl.write(",".join(["x", "g"] + lnames) + "\n")
        for x in XS:
            for g in GS:
                S = sigma_vanloan(mpf(x), g)
                L = cholesky(S)
                row = [S[i, j] for i in range(4) for j in range(i + 1)]
                fc.write(",".join([repr(x), repr(g)] + [f20(v) for v in row])
                         + "\n")
                lr = [L[2, 0], L[2, 1], L[2, 2], L[3, 0], L[3, 1], L[3, 2],
                      L[3, 3]]
                fl.write(",".join([repr(x), repr(g)] + [f20(v) for v in lr])
                         + "\n")


if __name__ == "__main__":
    main()
