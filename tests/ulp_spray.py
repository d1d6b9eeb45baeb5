#!/usr/bin/python3
"""Error in ulp of three spray closed forms against mpmath, over random
ordinary and extreme arguments (exact doubles; the reference is the
closed form at high precision).  Not run by `make check`: a tool for
comparing two builds of the library.

  tab   sb_spray_tab_state y, y' (rho_l = 1000, sigma = 0.072); extreme:
        heavily overdamped (beta/w0 up to ~1e8) at t up to a few 1/|k - beta|
  tab y~0  the same with y0 ~ 0 (|y0| <= 1e-3) and t 1e-4 .. 1e-1 of the
        above, so y << y_eq (the y_eq + z cancellation)
  tab z0~0  the same as tab with y0 = y_eq = We/12 (rounded), so y' is
        mostly the free response y0' e^{-bt}(C - b S)
  hs    sb_spray_two_temp_hs T_a, T_b; extreme: n_a T_a0 and n_b T_b0
        below DBL_MIN while T_m is normal
  mx    sb_spray_two_temp_maxwell T_a, T_b; extreme: the rate
        2 B0 n m_a m_b/(m_a + m_b)^2 below DBL_MIN

Run: /usr/bin/python3 tests/ulp_spray.py [path/to/libsmolbridge.so] [N]
(default .libs/libsmolbridge.so of this tree, N = 300 draws per set, a
few seconds; docs/spray.md quotes N = 2000).  Prints the largest error
in ulp of each output per set (and of TAB's overdamped subset), with
the arguments where it is above 4 ulp.  For TAB also the largest errors
of y and y' in ulp divided by their condition numbers (/cond; tab_cond:
where y is a small difference of the data's terms y_eq g, y0 e(C + b S)
and y0' e S, or y' one of y0' e(C - b S), w0^2 y_eq e S and w0^2 y0 e S,
that many ulp are inherent).  The references are the closed forms of
tests/gen_spray_ref.py (imported), with the library's double constants.
"""
import ctypes
import math
import os
import random
import sys

from mpmath import mp, mpf, sqrt

# the closed forms as tests/gen_spray_ref.py writes them into
# tests/data/spray_extreme.csv (this directory is on the module path)
from gen_spray_ref import (tab_closed_form, tab_free, tab_oscillator,
                           tt_hs_parts, tt_hs_Ta, tt_hs_Tb, tt_maxwell_T)

HERE = os.path.dirname(os.path.abspath(__file__))
KB = mpf(1.380649e-23)  # SB_BOLTZMANN as the library has it (a double)


class Liquid(ctypes.Structure):
    _fields_ = [("sigma", ctypes.c_double), ("mu_l", ctypes.c_double)]


class Mixture(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in
                ("n_a", "n_b", "m_a", "m_b", "r_a", "r_b", "T_a0", "T_b0")]


def load(path):
    lib = ctypes.CDLL(path)
    D, P = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
    lib.sb_spray_tab_state.argtypes = [D, D, D, D, D, ctypes.POINTER(Liquid),
                                       D, D, D, P, P]
    lib.sb_spray_two_temp_hs.argtypes = [ctypes.POINTER(Mixture), D, P, P]
    lib.sb_spray_two_temp_maxwell.argtypes = [ctypes.POINTER(Mixture), D, D,
                                              P, P]
    return lib


def ulps(got, ref):
    """|got - ref| in units of the spacing of doubles at ref."""
    if not math.isfinite(got):
        return math.inf
    r = float(ref)
    sp = math.ulp(r) if r != 0 else 5e-324
    return float(abs(mpf(got) - ref) / sp)


def logu(rng, lo, hi):
    return 10 ** rng.uniform(math.log10(lo), math.log10(hi))


# ------------------------------------------------------------------ TAB
SIGMA = 0.072  # the surface tension passed to the library (a double)


def tab_ref(t, r, U, rg, mu, Cd, y0, yd0):
    with mp.workdps(120):
        return tab_closed_form(t, r, U, rg, mu, Cd, y0, yd0, SIGMA)


def tab_cond(t, r, U, rg, mu, Cd, y0, yd0):
    """Condition numbers of y and y' as sums of their data's terms,
    y = y_eq g + y0 e(C + b S) + y0' e S with g = 1 - e(C + b S) and
    y' = y0' e(C - b S) + w0^2 y_eq e S - w0^2 y0 e S (e = e^{-bt}):
    sum |term| / |y| (what a small y that is a difference of the data
    costs in ulp)"""
    with mp.workdps(60):
        t, r, U, rg, mu, Cd, y0, yd0 = [mpf(x) for x in
                                         (t, r, U, rg, mu, Cd, y0, yd0)]
        w02, b, yeq = tab_oscillator(r, U, rg, mu, Cd, mpf(SIGMA))
        e, C, S = [mp.re(x) for x in tab_free(w02, b, t)]
        P = e * (C + b * S)
        conds = []
        for terms in ((yeq * (1 - P), y0 * P, yd0 * e * S),
                      (yd0 * e * (C - b * S), w02 * yeq * e * S,
                       -w02 * y0 * e * S)):
            y = sum(terms)
            conds.append(float(sum(abs(x) for x in terms) / abs(y))
                         if y else math.inf)
        return conds


def tab_args(rng, extreme):
    Cd = rng.choice([5.0, 10.0])
    if extreme:  # beta^2/w0^2 = Cd^2 mu^2/(32 rho_l sigma r), 1e4 .. 1e16
        r, mu = logu(rng, 1e-12, 1e-7), logu(rng, 1e-2, 1e2)
    else:
        r, mu = logu(rng, 1e-6, 1e-3), logu(rng, 1e-4, 1e-1)
    U, rg = rng.uniform(0, 100), 1.2
    y0, yd0 = rng.uniform(-0.5, 0.5), rng.uniform(-1, 1) * logu(rng, 1e-3, 1e3)
    w02 = 8 * 0.072 / (1000 * r ** 3)
    b = Cd * mu / (2000 * r * r)
    slow = w02 / (b + math.sqrt(abs(b * b - w02)) + 1e-300)
    rate = slow if b * b > w02 else math.sqrt(w02)
    t = logu(rng, 1e-3, 5.0) / rate
    return [t, r, U, rg, mu, Cd, y0, yd0]


def tab0_args(rng, extreme):
    """y near 0 while y_eq = We/12 is not: y0 ~ 0, t well below the
    oscillator's time scales (y = y_eq + z cancels there); extreme: also
    heavily overdamped"""
    a = tab_args(rng, extreme)
    a[2] = rng.uniform(30, 100)
    a[6] = rng.uniform(-1, 1) * logu(rng, 1e-12, 1e-3)
    a[7] = rng.uniform(-1, 1) * logu(rng, 1e-6, 1e-1)
    a[0] *= logu(rng, 1e-4, 1e-1)
    return a


def tabq_args(rng, extreme):
    """y0 = y_eq = We/12 rounded (z0 ~ 0): y' is y0' e^{-bt}(C - b S), the
    free response of the rate, where C - b S is a small difference of
    e^{-bt} C and b e^{-bt} S when overdamped at t ~ 1/|k - beta|"""
    a = tab_args(rng, extreme)
    with mp.workdps(40):
        a[6] = float(tab_oscillator(*[mpf(x) for x in a[1:6]],
                                    mpf(SIGMA))[2])
    return a


def tab_overdamped(a):
    """beta^2 > w0^2 (the subset where the slow rate k - beta is used)"""
    r, mu, Cd = a[1], a[4], a[5]
    return (Cd * mu / (2000 * r * r)) ** 2 > 8 * 0.072 / (1000 * r ** 3)


def tab_eval(lib, a):
    y, yd = ctypes.c_double(), ctypes.c_double()
    liq = Liquid(0.072, a[4])
    st = lib.sb_spray_tab_state(a[0], a[1], a[2], a[3], 1000.0,
                                ctypes.byref(liq), a[5], a[6], a[7],
                                ctypes.byref(y), ctypes.byref(yd))
    return (y.value, yd.value) if st == 0 else (math.nan, math.nan)


# ------------------------------------------------ two-temperature laws
def hs_ref(*a):
    """T_a, T_b of the hard-sphere closure, textbook form at 800 digits."""
    return tt_hs_Ta(a, KB), tt_hs_Tb(a, KB)


def hs_time_unit(*a):
    with mp.workdps(60):
        C, alpha = tt_hs_parts(*[mpf(x) for x in a], kb=KB)[:2]
        return 1 / (C * sqrt(alpha))


def hs_args(rng, extreme):
    ma, mb = logu(rng, 1e-27, 1e-24), logu(rng, 1e-27, 1e-24)
    if extreme:  # n T below DBL_MIN, T_m normal; r large so C is normal
        Ta0, Tb0 = logu(rng, 1e-6, 1e2), logu(rng, 1e-6, 1e2)
        na = logu(rng, 1e-318, 1e-309) / Ta0
        nb = logu(rng, 1e-318, 1e-309) / Tb0
        if rng.random() < 0.5:  # one product normal, the other subnormal
            nb = logu(rng, 1e-307, 1e-300) / Tb0
        r = logu(rng, 1e145, 1e150)
    else:
        na, nb = logu(rng, 1e18, 1e25), logu(rng, 1e18, 1e25)
        Ta0, Tb0 = logu(rng, 1.0, 1e4), logu(rng, 1.0, 1e4)
        r = logu(rng, 1e-10, 1e-9)
    t = float(logu(rng, 1e-3, 10.0) *
              hs_time_unit(na, nb, ma, mb, Ta0, Tb0, r))
    return [na, nb, ma, mb, Ta0, Tb0, r, t]


def hs_eval(lib, a):
    mx = Mixture(a[0], a[1], a[2], a[3], a[6], a[6], a[4], a[5])
    Ta, Tb = ctypes.c_double(), ctypes.c_double()
    st = lib.sb_spray_two_temp_hs(ctypes.byref(mx), a[7], ctypes.byref(Ta),
                                  ctypes.byref(Tb))
    return (Ta.value, Tb.value) if st == 0 else (math.nan, math.nan)


def mx_ref(*a):
    """T_a, T_b of the Maxwell law, at 100 digits."""
    return tt_maxwell_T(a, 0), tt_maxwell_T(a, 1)


def mx_args(rng, extreme):
    ma, mb = logu(rng, 1e-27, 1e-24), logu(rng, 1e-27, 1e-24)
    Ta0, Tb0 = logu(rng, 1e-12, 1e6), logu(rng, 1e-12, 1e6)
    B0 = logu(rng, 1e-18, 1e-14)
    if extreme:  # the rate between ~1e-318 and DBL_MIN
        n = logu(rng, 1e-300, 1e-293) / B0 * 1e-16
    else:
        n = logu(rng, 1e18, 1e25)
    f = rng.random()
    na, nb = n * f, n * (1 - f)
    with mp.workdps(40):
        rate = 2 * mpf(B0) * (mpf(na) + nb) * ma * mb / (mpf(ma) + mb) ** 2
        # x = rate t up to ~2 (t <= DBL_MAX)
        t = float(min(logu(rng, 1e-6, 2.0) / rate, mpf(1.7e308)))
    return [na, nb, ma, mb, Ta0, Tb0, B0, t]


def mx_eval(lib, a):
    mx = Mixture(a[0], a[1], a[2], a[3], 1e-6, 1e-6, a[4], a[5])
    Ta, Tb = ctypes.c_double(), ctypes.c_double()
    st = lib.sb_spray_two_temp_maxwell(ctypes.byref(mx), a[6], a[7],
                                       ctypes.byref(Ta), ctypes.byref(Tb))
    return (Ta.value, Tb.value) if st == 0 else (math.nan, math.nan)


# name, draw, library call, reference, outputs, a subset also reported
SETS = [("tab", tab_args, tab_eval, tab_ref, ("y", "y'"),
         ("overdamped", tab_overdamped)),
        ("tab y~0", tab0_args, tab_eval, tab_ref, ("y", "y'"), None),
        ("tab z0~0", tabq_args, tab_eval, tab_ref, ("y", "y'"), None),
        ("hs", hs_args, hs_eval, hs_ref, ("T_a", "T_b"), None),
        ("mx", mx_args, mx_eval, mx_ref, ("T_a", "T_b"), None)]


def report(label, worst, where, outs, wc=None):
    print("%-24s" % label, "  ".join("%s max %.3g ulp" % (outs[j], worst[j])
                                    for j in range(2)) +
          ("" if wc is None else "  /cond %.3g, %.3g" % tuple(wc)))
    for j in range(2):
        if worst[j] > 4:
            print("      worst %s at %r" % (outs[j], where[j]))


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        HERE, "..", ".libs", "libsmolbridge.so")
    N = int(sys.argv[2]) if len(sys.argv) > 2 else 300
    lib = load(path)
    for name, gen, ev, ref, outs, sub in SETS:
        for extreme in (False, True):
            rng = random.Random(20261130 + 7 * extreme + len(name))
            worst, where = [0.0, 0.0], [None, None]
            sworst, swhere, ns = [0.0, 0.0], [None, None], 0
            wc = [0.0, 0.0] if name.startswith("tab") else None
            for _ in range(N):
                a = gen(rng, extreme)
                got, exact = ev(lib, a), ref(*a)
                insub = sub is not None and sub[1](a)
                ns += insub
                cond = tab_cond(*a) if wc is not None else None
                for j in range(2):
                    u = ulps(got[j], exact[j])
                    if wc is not None:
                        wc[j] = max(wc[j], u / max(1.0, cond[j]))
                    if u > worst[j]:
                        worst[j], where[j] = u, a
                    if insub and u > sworst[j]:
                        sworst[j], swhere[j] = u, a
            label = "%s %s" % (name, "extreme" if extreme else "ordinary")
            report(label, worst, where, outs, wc)
            if sub is not None and not extreme:
                report("  (%d %s)" % (ns, sub[0]), sworst, swhere, outs)


if __name__ == "__main__":
    main()
