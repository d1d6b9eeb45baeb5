#!/usr/bin/python3
"""Reference vectors for tests/test_dlvo.c (mpmath, 60 digits).

Independent of lib/dlvo/dlvo.c: the van der Waals energy is the Hamaker (1937)
expression written with the centre distance r = D + r1 + r2 (as in
Hamaker's paper), evaluated at 60 digits
(its cancellation at large D costs < 20 of them); forces are numerical
derivatives (mpmath.diff) of the energies, not the analytic forms; the
barrier is located by a fine scan of dW/dD and mpmath.findroot; the
relative-kinetic-energy laws are mpmath's regularised incomplete gamma
functions.

Usage: /usr/bin/python3 tests/gen_dlvo_ref.py   (writes tests/data/dlvo_*.csv)
"""
import os
from mpmath import mp, mpf, log, exp, tanh, pi, diff, findroot, gammainc, \
    gamma, inf, isinf

mp.dps = 60
kB = mpf('1.380649e-23')
ECH = mpf('1.602176634e-19')
EPS0 = mpf('8.8541878128e-12')
HERE = os.path.dirname(os.path.abspath(__file__))


def reff(r1, r2):
    return r1 if isinf(r2) else r1 * r2 / (r1 + r2)


def vdw_ham(A, r1, r2, D):
    if isinf(r2):  # sphere-plane
        R = r1
        return -A / 6 * (R / D + R / (D + 2 * R) + log(D / (D + 2 * R)))
    r = D + r1 + r2
    p = (r1 + r2) ** 2
    m = (r1 - r2) ** 2
    return -A / 6 * (2 * r1 * r2 / (r * r - p) + 2 * r1 * r2 / (r * r - m)
                     + log((r * r - p) / (r * r - m)))


def vdw_der(A, r1, r2, D):
    return -A * reff(r1, r2) / (6 * D)


def edl_lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2):
    # Israelachvili ch. 14, weak overlap (flat plates, per unit area):
    #   w(D) = 64 kT n0 g1 g2 exp(-kappa D)/kappa
    # Derjaguin: W = 2 pi R int_D^inf w = 2 pi R w(D)/kappa, and
    # n0 = eps kT kappa^2/(2 z^2 e^2) from kappa's definition.
    eps = eps_r * EPS0
    n0 = eps * kB * T * kappa ** 2 / (2 * z * z * ECH * ECH)
    g1 = tanh(z * ECH * psi1 / (4 * kB * T))
    g2 = tanh(z * ECH * psi2 / (4 * kB * T))
    w = 64 * kB * T * n0 * g1 * g2 * exp(-kappa * D) / kappa
    return 2 * pi * reff(r1, r2) * w / kappa


def edl_hhf(D, r1, r2, kappa, eps_r, psi1, psi2):
    # Hogg, Healy & Fuerstenau (1966), their eq. in the product form
    #   V = pi eps a1 a2 (psi1^2 + psi2^2)/(a1 + a2) *
    #       [2 psi1 psi2/(psi1^2 + psi2^2) ln((1 + e)/(1 - e)) + ln(1 - e^2)]
    eps = eps_r * EPS0
    e = exp(-kappa * D)
    s = psi1 ** 2 + psi2 ** 2
    if s == 0:
        return mpf(0)
    return pi * eps * reff(r1, r2) * s * (
        2 * psi1 * psi2 / s * log((1 + e) / (1 - e)) + log(1 - e * e))


def fmt(x):
    if isinf(x):
        return 'inf' if x > 0 else '-inf'
    return mp.nstr(x, 20, min_fixed=1, max_fixed=0)


def write(name, header, rows):
    with open(os.path.join(HERE, 'data', name), 'w') as f:
        f.write(header + '\n')
        for r in rows:
            f.write(','.join(fmt(mpf(x)) if not isinstance(x, str) else x
                             for x in r) + '\n')


def gen_vdw():
    rows = []
    A = mpf('1e-20')
    for (r1, r2) in [('1e-7', '1e-7'), ('5e-7', '2e-8'), ('1e-6', inf),
                     ('3e-9', '7e-6'), ('2e-8', inf)]:
        r1 = mpf(r1)
        r2 = inf if isinf(r2) else mpf(r2)
        for lg in range(-26, 13, 2):  # D/r1 = 10^(lg/4)
            D = r1 * mpf(10) ** (mpf(lg) / 4)
            W = vdw_ham(A, r1, r2, D)
            F = -diff(lambda d: vdw_ham(A, r1, r2, d), D)
            rows.append((A, r1, r2, D, W, F))
    write('dlvo_vdw.csv', 'A,r1,r2,D,W,F', rows)


EDL_CASES = [  # r1, r2, kappa, eps_r, T, z, psi1, psi2
    ('1e-7', '1e-7', '1.04e8', '78.4', '298.15', '1', '0.05', '0.05'),
    ('5e-7', '2e-7', '3.3e8', '78.4', '298.15', '2', '-0.03', '-0.08'),
    ('1e-6', 'inf', '1.0e7', '80.1', '293.15', '1', '0.02', '0.015'),
    ('2e-8', '3e-6', '1.04e9', '78.4', '310', '1', '0.1', '-0.02'),
]


def gen_edl():
    rows = []
    for c in EDL_CASES:
        r1, r2, kappa, eps_r, T, z, psi1, psi2 = [
            inf if v == 'inf' else mpf(v) for v in c]
        for x in ['1e-3', '0.01', '0.1', '0.5', '1', '2', '5', '10', '30',
                  '100']:
            D = mpf(x) / kappa
            for model in (0, 1):
                if model == 0:
                    f = lambda d: edl_lsa(d, r1, r2, kappa, eps_r, T, z,
                                          psi1, psi2)
                else:
                    f = lambda d: edl_hhf(d, r1, r2, kappa, eps_r, psi1,
                                          psi2)
                rows.append((model, D, r1, r2, kappa, eps_r, T, z, psi1,
                             psi2, f(D), -diff(f, D)))
    write('dlvo_edl.csv', 'model,D,r1,r2,kappa,eps_r,T,z,psi1,psi2,W,F',
          rows)


BAR_CASES = [  # vdw, edl, r1, r2, A, T, eps_r, z, kappa, psi1, psi2, d0
    (0, 0, '5e-7', '5e-7', '1e-20', '298.15', '78.4', '1', '1.04e8',
     '0.05', '0.05', '2e-10'),
    (1, 0, '5e-8', '2e-7', '2e-20', '298.15', '78.4', '1', '2.0e8',
     '0.04', '0.03', '2e-10'),
    (0, 1, '1e-6', 'inf', '1e-20', '298.15', '78.4', '1', '1.04e8',
     '0.025', '0.025', '3e-10'),
    (1, 1, '3e-8', '3e-8', '5e-21', '298.15', '78.4', '1', '5.0e7',
     '0.02', '0.02', '1e-10'),
    (1, 0, '1e-6', 'inf', '1e-20', '298.15', '78.4', '2', '3.29e8',
     '-0.04', '-0.06', '4e-10'),
    # weak double layer: no barrier
    (0, 0, '5e-7', '5e-7', '1e-20', '298.15', '78.4', '1', '1.04e9',
     '0.01', '0.01', '2e-10'),
    # maximum below d_contact, W(d0) > 0: barrier at contact
    (0, 0, '5e-7', '5e-7', '1e-20', '298.15', '78.4', '1', '1.04e8',
     '0.05', '0.05', '1.5e-9'),
]


def barrier(c):
    vdw, edl = c[0], c[1]
    r1, r2, A, T, eps_r, z, kappa, psi1, psi2, d0 = [
        inf if v == 'inf' else mpf(v) for v in c[2:]]

    def W(d):
        v = (vdw_ham if vdw else vdw_der)(A, r1, r2, d)
        if edl == 0:
            return v + edl_lsa(d, r1, r2, kappa, eps_r, T, z, psi1, psi2)
        return v + edl_hhf(d, r1, r2, kappa, eps_r, psi1, psi2)

    def dW(d):
        return diff(W, d)

    # stationary points: dW changes sign on a fine log grid up to 200/kappa
    hi = d0 + 200 / kappa
    n = 2000
    q = (hi / d0) ** (mpf(1) / n)
    pts = []
    dp, sp = d0, dW(d0)
    for i in range(1, n + 1):
        d = d0 * q ** i
        s = dW(d)
        if (sp > 0) != (s > 0):
            r = findroot(dW, (dp, d), solver='anderson')
            pts.append((r, 'max' if sp > 0 else 'min'))
        dp, sp = d, s
    kind, wmax, dmax = 0, mpf(0), inf
    if W(d0) > 0:
        kind, wmax, dmax = 2, W(d0), d0
    for r, t in pts:
        if t == 'max' and W(r) > wmax:
            kind, wmax, dmax = 1, W(r), r
    mins = [(W(r), r) for r, t in pts if t == 'min' and (kind == 0 or
                                                          r > dmax)]
    wmin, dmin = min(mins) if mins else (mp.nan, mp.nan)
    return kind, dmax, wmax, dmin, wmin


def gen_barrier():
    rows = []
    for c in BAR_CASES:
        kind, dmax, wmax, dmin, wmin = barrier(c)
        rows.append(tuple(str(v) for v in c) + (str(kind),) +
                    (dmax, wmax, dmin, wmin))
    write('dlvo_barrier.csv', 'vdw,edl,r1,r2,A,T,eps_r,z,kappa,psi1,psi2,'
          'd_contact,kind,D_max,W_max,D_min2,W_min2', rows)


def gen_erel():
    rows = []
    for k2 in (1, 2, 3, 4):
        k = mpf(k2) / 2
        for x in ['0', '1e-8', '1e-3', '0.1', '0.5', '1', '1.5', '1.999',
                  '2', '3', '7.5', '20', '50', '200', '650']:
            x = mpf(x)
            P = gammainc(k, 0, x, regularized=True)
            Q = gammainc(k, x, inf, regularized=True)
            pdf = x ** (k - 1) * exp(-x) / gamma(k) if x > 0 else (
                inf if k2 == 1 else (1 if k2 == 2 else 0))
            rows.append((k2, x, P, Q, pdf, log(Q)))
    write('dlvo_erel.csv', 'k2,x,P,Q,pdf,logQ', rows)


# ------------------------------------------------------------ sweep
# tests/test_dlvo.c, test_extreme_arguments: each argument of each
# function in turn at an extreme value, the others ordinary (the same
# table, same order).  Evaluated at 1000 digits: the centre-distance form
# of the Hamaker energy cancels by up to ~650 digits there (D = 1e-320
# against r ~ 1e-6, or r = DBL_MAX against D); forces are numerical
# derivatives with a step relative to D.  Values "inf" (|value| above
# DBL_MAX: SB_ERANGE expected), "-inf" (the Hamaker energy where t = R/D
# exceeds DBL_MAX: -inf by the documented convention, though |W| may be
# below DBL_MAX there) and 0 (below DBL_MIN) are markers.
DBL_MAX = mpf(1.7976931348623157e308)
DBL_MIN = mpf(2.2250738585072014e-308)


def dforce(f, D):
    return -diff(f, D, h=D * mpf('1e-40'))


def pair_w(a, force):
    r1, r2, A, T, eps_r, z, kappa, psi1, psi2, d0, D, vdw, edl = a

    def w(d):
        v = vdw_ham(A, r1, r2, d) if vdw else vdw_der(A, r1, r2, d)
        e = edl_hhf(d, r1, r2, kappa, eps_r, psi1, psi2) if edl else \
            edl_lsa(d, r1, r2, kappa, eps_r, T, z, psi1, psi2)
        return v + e
    return dforce(w, D) if force else w(D)


SWEEP = [  # function index, number of swept arguments, ordinary arguments
    (0, 4, [1e-20, 1e-6, 2e-6, 1e-8]),
    (1, 4, [1e-20, 1e-6, 2e-6, 1e-8]),
    (2, 4, [1e-20, 1e-6, 2e-6, 1e-8]),
    (3, 4, [1e-20, 1e-6, 2e-6, 1e-8]),
    (4, 9, [1e-8, 1e-6, 2e-6, 1e8, 78.4, 298.0, 1.0, 0.03, 0.02]),
    (5, 9, [1e-8, 1e-6, 2e-6, 1e8, 78.4, 298.0, 1.0, 0.03, 0.02]),
    (6, 7, [1e-8, 1e-6, 2e-6, 1e8, 78.4, 0.03, 0.02]),
    (7, 7, [1e-8, 1e-6, 2e-6, 1e8, 78.4, 0.03, 0.02]),
    (8, 4, [6e23, 1.0, 78.4, 298.0]),
    # pairs: r1, r2, A, T, eps_r, z, kappa, psi1, psi2, d_contact, D,
    # then the models (not swept)
    (9, 11, [1e-6, 2e-6, 1e-20, 298.0, 78.4, 1.0, 1e8, 0.03, 0.02, 4e-10,
             1e-8, 1, 1]),
    (10, 11, [1e-6, 2e-6, 1e-20, 298.0, 78.4, 1.0, 1e8, 0.03, 0.02, 4e-10,
              1e-8, 0, 0]),
    (11, 11, [1e-6, 2e-6, 1e-20, 298.0, 78.4, 1.0, 1e8, 0.03, 0.02, 4e-10,
              1e-8, 1, 1]),
    (12, 11, [1e-6, 2e-6, 1e-20, 298.0, 78.4, 1.0, 1e8, 0.03, 0.02, 4e-10,
              1e-8, 0, 0]),
]
# which arguments may be negative (A, psi1, psi2) and which infinite (r2)
SIGNED = {0: [0], 1: [0], 2: [0], 3: [0], 4: [7, 8], 5: [7, 8], 6: [5, 6],
          7: [5, 6], 8: [], 9: [2, 7, 8], 10: [2, 7, 8], 11: [2, 7, 8],
          12: [2, 7, 8]}


def ham_t(a, f):
    """t = 2 r1 r2/(D (D + 2 r1 + 2 r2)) of the Hamaker energy (r1/D for a
    plane): the energy is -inf by convention where t exceeds DBL_MAX."""
    r1, r2, D = (a[1], a[2], a[3]) if f == 0 else (a[0], a[1], a[10])
    if isinf(r2):
        return r1 / D
    return 2 * r1 * r2 / (D * (D + 2 * r1 + 2 * r2))


def sweep_value(f, a):
    if f == 0:
        return vdw_ham(*a)
    if f == 1:
        return dforce(lambda d: vdw_ham(a[0], a[1], a[2], d), a[3])
    if f == 2:
        return vdw_der(*a)
    if f == 3:
        return dforce(lambda d: vdw_der(a[0], a[1], a[2], d), a[3])
    if f == 4:
        return edl_lsa(*a)
    if f == 5:
        return dforce(lambda d: edl_lsa(d, *a[1:]), a[0])
    if f == 6:
        return edl_hhf(*a)
    if f == 7:
        return dforce(lambda d: edl_hhf(d, *a[1:]), a[0])
    if f == 8:
        n0, z, eps_r, T = a
        return (2 * n0 * (z * ECH) ** 2 / (eps_r * EPS0 * kB * T)) ** 0.5
    return pair_w(a, f in (11, 12))


def gen_sweep():
    rows = []
    with mp.workdps(1000):
        for f, n, base in SWEEP:
            for i in range(n):
                xs = [1e-320, 1e-300, 1e300, 1.7976931348623157e308]
                if i in SIGNED[f]:
                    xs += [-1e-320, -1e300, -1.7976931348623157e308]
                for x in xs:
                    a = [mpf(v) for v in base]
                    a[i] = mpf(x)
                    v = sweep_value(f, a)
                    if f in (0, 9) and ham_t(a, f) > DBL_MAX:
                        vs = '-inf'  # the documented convention, A > 0
                    elif abs(v) > DBL_MAX:
                        vs = 'inf'
                    elif abs(v) < DBL_MIN:
                        vs = '0'
                    else:
                        vs = mp.nstr(v, 20, min_fixed=1, max_fixed=0)
                    rows.append('%d,%d,%r,%s' % (f, i, x, vs))
    with open(os.path.join(HERE, 'data', 'dlvo_sweep.csv'), 'w') as fh:
        fh.write('f,arg,x,value\n')
        fh.write('\n'.join(rows) + '\n')


if __name__ == '__main__':
    gen_vdw()
    gen_edl()
    gen_erel()
    gen_barrier()
    gen_sweep()
