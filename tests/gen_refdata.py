#!/usr/bin/python3
"""Reference vectors for the passage and bridge modules (smolbridge).

Run with Debian's python3-mpmath:  /usr/bin/python3 tests/gen_refdata.py
Writes tests/data/{mills,mdiff,passage_bm,passage_bes3,passage_quantile,
bridge_cross,bridge_hit,bridge_quantile,bridge_narrow,
bridge_narrow_quantile}.csv (see tests/data/README.md).

Every value is computed in arbitrary precision (mp.dps = 60 unless said
otherwise) from the closed forms written independently of the C code: the
normal CDF/erfc forms as printed in the literature (no scaling tricks),
evaluated with enough digits that their cancellations do not matter.  The
closed forms themselves are checked against quadrature of the densities
here (check_closed_forms, run first; it aborts on a mismatch) and again in
the C tests with GSL QAGS.  Inputs are exact binary doubles: each input is
written with repr() and read back as the same double, and mpmath sees the
exact value of that double.

Precision per row (the passage and bridge files; settled()).  A row's
values are computed at its base precision (60 digits; 200 for bridge_cross,
its extreme corners included; 40 for the bridge quantiles; 400 for the
extreme corners of the passage, bridge_hit and quantile files; 1000 for
the bridge_hit rows with positions near 2^1000 sqrt(sigma2 t)) and again at 40
more digits; if any value differs by more than 1e-24 relative (or falls on
the other side of the 1e-300 cut-off), the base precision is doubled and
the comparison repeated.  The values compared are those computed, before
they are written as markers (-1 below 1e-300, inf above DBL_MAX; class
Marked), and Phi keeps its far tails as values instead of an exact 0: a
value whose exponent is lost at both precisions (exp(-c^2/2) with c^2/2
~ 10^600 from 400 digits) is garbage that differs between them, whereas
its marker (-1 at both) looked settled.  The values written are those at
the first precision that passed, so each has a relative error below about
1e-24, well inside the 20 digits written: rounding errors grow by the same factor at
both precisions, so the 40 extra digits make the second value's error
1e-40 times the first's and their difference measures the first's error.
(The quantiles' bisections stop at a width of 1e-40 in log t, 1e-35 in
log s, at every precision: below the 1e-24.)  Rows that were already
right at the base precision are written with the same bytes as before.
A probability or density below 1e-300 is written as -1 (cut()); the mass
of passage_bm.csv also has its logarithm -2 d |nu| / sigma2 (logmass),
so that the exponent of a mass such as exp(-2e300) is checked too.

  /usr/bin/python3 tests/gen_refdata.py --verify [group ...]
regenerates without writing and exits with status 1, naming the rows,
if a committed file differs from what the script produces.
"""
import math
import os
import sys

import mpmath as mp

mp.mp.dps = 60
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")
TINY = mp.mpf("1e-300")  # smallest reference value kept (normal doubles)


def f17(x):
    """Inputs (Python floats, exact doubles): repr(), which round-trips.
    Reference values (mpf): 20 significant digits, more than a double."""
    if isinstance(x, Marked):
        return f17(x.mark)
    if isinstance(x, mp.mpf):
        if mp.isinf(x):
            return "inf" if x > 0 else "-inf"
        return mp.nstr(x, 20, min_fixed=1, max_fixed=0) if x != 0 else "0"
    return repr(float(x))


VERIFY = {"on": False, "failed": []}  # --verify: compare, do not write
RAISED = []  # (base, final) digits of the rows settled() raised, per file


def raised():
    """' (n rows above their base precision, up to N digits)' for the rows
    settled() raised since the last file written, or ''."""
    if not RAISED:
        return ""
    n, top = len(RAISED), max(r[1] for r in RAISED)
    del RAISED[:]
    return " (%d rows above their base precision, up to %d digits)" % (n,
                                                                        top)


def write(name, header, rows):
    path = os.path.join(DATA, name)
    lines = [",".join(header)] + [",".join(f17(v) for v in r) for r in rows]
    if VERIFY["on"]:
        with open(path) as fh:
            old = fh.read().split("\n")[:-1]
        bad = [i + 1 for i in range(max(len(old), len(lines)))
               if i >= len(old) or i >= len(lines) or old[i] != lines[i]]
        for i in bad[:20]:
            print("%s line %d differs:\n  committed %s\n  generated %s" %
                  (name, i, old[i - 1] if i <= len(old) else "(none)",
                   lines[i - 1] if i <= len(lines) else "(none)"))
        print("checked %s: %d rows, %d differ%s" % (name, len(rows), len(bad),
                                                  raised()))
        if bad:
            VERIFY["failed"].append(name)
        return
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("wrote %s: %d rows, %d bytes%s" % (name, len(rows),
                                             os.path.getsize(path), raised()))


class Marked:
    """A reference value written as a marker (mark: -1 below 1e-300, inf
    above DBL_MAX) that keeps the value computed (value), so that settled()
    compares the values and not only the markers: a value whose exponent
    is lost at both precisions (exp(-c^2/2) with c^2/2 ~ 10^600 known to
    400 digits) is garbage such as 10^(-10^230) at both, written -1 at
    both, and compared as markers it looked settled."""

    def __init__(self, value, mark):
        self.value, self.mark = value, mark


def cut(v):
    """A probability or density as written: -1 below 1e-300 (the marker
    of tests/data/README.md; such values are not normal doubles)."""
    v = v.value if isinstance(v, Marked) else v
    return v if v > TINY else Marked(v, -1)


def _agree(u, v):
    """Reference values u (base precision) and v (40 more digits) agree to
    1e-24 relative, markers included (their computed values, and the same
    marker: not on either side of the 1e-300 cut-off); exact values must
    match.  The relative comparison of mpf values is in log space in
    effect (mpmath's exponents do not overflow), so it holds at any
    magnitude."""
    if isinstance(u, Marked) or isinstance(v, Marked):
        if not (isinstance(u, Marked) and isinstance(v, Marked)) or \
                u.mark != v.mark:
            return False
        u, v = u.value, v.value
    if not isinstance(u, mp.mpf) or not isinstance(v, mp.mpf):
        return type(u) is type(v) and u == v
    if mp.isinf(u) or mp.isinf(v) or v == 0:
        return u == v
    return abs(u - v) <= mp.mpf(10) ** -24 * abs(v)


def settled(f, dps):
    """f() (a tuple of reference values) at the lowest of dps, 2 dps,
    4 dps, ... at which it agrees with f() at 40 more digits (module
    docstring); the values are rounded to that precision."""
    base = dps
    while True:
        with mp.workdps(dps):
            lo = tuple(+v if isinstance(v, mp.mpf) else v for v in f())
            lo = tuple(Marked(+v.value, v.mark) if isinstance(v, Marked)
                       else v for v in lo)
        with mp.workdps(dps + 40):
            hi = f()
        if all(_agree(u, v) for u, v in zip(lo, hi)):
            if dps > base:
                RAISED.append((base, dps))
            return lo
        if dps >= 1 << 14:
            raise ArithmeticError("no settled precision up to %d digits"
                                  % dps)
        dps *= 2


def Phi(z):
    # beyond |z| = 1e10 the tail is below 10^(-10^19) (mpmath's erfc
    # overflows for |z| ~ 1e300): its asymptotic series phi(z)/|z| (1 -
    # 1/z^2 + 3/z^4), relative error below 15/z^6, rather than 0, so that
    # a z spoiled by a lost exponent changes the value with the precision
    # (settled() then sees it; an exact 0 looked the same at both)
    if abs(z) > 1e10:
        z2 = z * z
        tail = mp.exp(-z2 / 2) / (abs(z) * mp.sqrt(2 * mp.pi)) * \
            (1 - 1 / z2 + 3 / (z2 * z2))
        return tail if z < 0 else 1 - tail
    return mp.ncdf(z)


def Q(z):
    return Phi(-z)


def M(z):
    """Q(z) exp(z^2/2); for z >= 50 by its asymptotic series (terms fall
    by (2n-1)/z^2 <= 1/2500, summed to 1e-70 relative)."""
    z = mp.mpf(z)
    if z < 50:
        return mp.erfc(z / mp.sqrt(2)) / 2 * mp.exp(z * z / 2)
    term, tot, n = mp.mpf(1), mp.mpf(1), 1
    while abs(term) > mp.mpf(10) ** -70:
        term *= -(2 * n - 1) / (z * z)
        tot += term
        n += 1
    return tot / (z * mp.sqrt(2 * mp.pi))


# ------------------------------------------------------------- numutil

def gen_mills():
    zs = [-37, -20, -5, -2, -1.5, -1, -0.5, -1e-3, 0, 1e-10, 1e-3, 0.25,
          0.5, 1, 1.5, 1.9999, 2, 2.0001, 3, 4, 5, 7.5, 10, 15, 20, 24.99,
          25, 25.01, 30, 37.5, 40, 100, 1e3, 1e5, 1e8, 1e12, 1e100]
    # the branch ends of Cody's erfcx approximations (z/sqrt 2 = 0.46875,
    # 4, 6.71e7) and their neighbours, and a grid of both signs
    for e in (0.46875, 4.0, 6.71e7):
        z = float(e * mp.sqrt(2))
        zs += [math.nextafter(z, -math.inf), z, math.nextafter(z, math.inf)]
    zs += [s * 10 ** (k / 8.0) for k in range(-24, 13) for s in (1, -1)
           if 10 ** (k / 8.0) <= 37]
    rows = [(z, M(mp.mpf(z))) for z in zs]
    write("mills.csv", ["z", "M"], rows)
    # D(z, h) = M(z - h) - M(z + h), z >= 0, z - h >= -2: both branches of
    # sbi_mills_diff (direct difference, forward and backward series)
    rows = []
    for z in [0, 1e-3, 0.3, 1, 1.9, 2, 2.1, 2.5, 3, 3.5, 4, 5, 6, 7, 8, 10,
              30, 100, 1e4, 1e8]:
        for h in [1e-12, 1e-6, 1e-3, 0.05, 0.2, 0.5, 1, 1.99, 3]:
            if z - h < -2:
                continue
            zz, hh = mp.mpf(z), mp.mpf(h)
            d = M(zz - hh) - M(zz + hh)
            lo = float(zz - hh)  # the C test passes lo = z - h rounded
            rows.append((z, h, lo, d))
    write("mdiff.csv", ["z", "h", "lo", "D"], rows)
    with mp.workdps(400):
        rows = [(x, mp.log(-mp.expm1(-mp.mpf(x))))
                for x in (1e-300, 1e-20, 1e-8, 0.01, 0.5, 0.6931, 0.6932, 1, 5,
                          30, 700)]
    write("log1mexp.csv", ["x", "log1mexp"], rows)


# ------------------------------------------------------------- passage

def ig_parts(t, x, a, mu, s2):
    """pdf, cdf, sf of the first passage of x + mu t + sqrt(s2) W to a."""
    t, x, a, mu, s2 = map(mp.mpf, (t, x, a, mu, s2))
    d = abs(x - a)
    nu = mu if x < a else -mu
    s = mp.sqrt(s2 * t)
    pdf = d / mp.sqrt(2 * mp.pi * s2 * t ** 3) * mp.exp(-(d - nu * t) ** 2 /
                                                        (2 * s2 * t))
    c = (nu * t - d) / s
    b = (nu * t + d) / s
    cdf = Phi(c) + mp.exp(2 * nu * d / s2) * Phi(-b)
    # log(mass) = -2 d |nu| / s2 (the mass alone reads as 0 below 1e-300)
    logmass = 0 if nu >= 0 else -2 * d * abs(nu) / s2
    mass = 1 if nu >= 0 else mp.exp(logmass)
    # the complement directly (no 1 - cdf): Q(c) - e^{2 nu d/s2} Q(b) is
    # mass-independent algebra: 1 - cdf = Q(c) - exp(2 nu d/s2) Phi(-b)
    sf = Q(c) - mp.exp(2 * nu * d / s2) * Phi(-b)
    return pdf, cdf, sf, mass, logmass


def ig_row(t, x, a, mu, s2):
    """pdf, cdf, sf, mass (-1 below 1e-300) and log(mass) of a
    passage_bm.csv row."""
    pdf, cdf, sf, mass, logmass = ig_parts(t, x, a, mu, s2)
    return cut(pdf), cut(cdf), cut(sf), cut(mass), logmass


def bes3_row(t, x, a, s2):
    """pdf, cdf (-1 below 1e-300) and sf of a passage_bes3.csv row."""
    xx, aa, ss, tt = map(mp.mpf, (x, a, s2, t))
    d = xx - aa
    z = d / mp.sqrt(2 * ss * tt)
    pdf = aa / xx * d / mp.sqrt(2 * mp.pi * ss * tt ** 3) * \
        mp.exp(-d * d / (2 * ss * tt))
    cdf = aa / xx * mp.erfc(z)
    sf = 1 - cdf
    return cut(pdf), cut(cdf), sf


def gen_passage():
    rows = []
    # (x, a, mu, s2): level below/above, drift towards/away/zero, d small,
    # scales from 1e-4 to 1e4
    pars = [(1, 0, -1, 1), (0, 1, 1, 1), (1, 0, 0, 1), (1, 0, 1, 1),
            (0, 1, -2.5, 1), (2.5, 1.5, -0.1, 0.3), (2.5, 1.5, -30, 0.3),
            (1, 1 - 2 ** -30, -1, 1), (3, 1, -1e-6, 2), (3, 1, -1e3, 2),
            (1e-4, 0, -1e-4, 1e-8), (1e4, 0, -1e2, 1e4),
            (0.7, -0.3, -0.01, 1), (-1, 2, 0.4, 5), (2, 1, 3, 1e-3),
            # 2 |nu| d / s2 from products above 2^995, finite or not
            (0, 1, -1e300, 1e300), (0, 1, -1e300, 1), (0, 1, -1e150, 1e-150)]
    for (x, a, mu, s2) in pars:
        d = abs(x - a)
        nu = mu if x < a else -mu
        tl = d * d / s2  # diffusive time
        ts = [tl * 10 ** k for k in (-8, -4, -2, -1, -0.5, 0, 0.5, 1, 2, 4,
                                     8)]
        if nu != 0:
            tm = d / abs(nu)
            ts += [tm * f for f in (1e-8, 1e-3, 0.1, 0.5, 0.9, 1, 1.1, 2, 5,
                                    10, 100, 1e3, 1e5, 1e8)]
        for t in ts:
            t = float(t)
            rows.append((t, x, a, mu, s2) +
                        settled(lambda: ig_row(t, x, a, mu, s2), 60))
    # extreme-but-representable corners (t, x, a, mu, s2): sigma2 t or
    # nu t beyond DBL_MAX or above the 2^995 where a Veltkamp split
    # overflows, exp(-E) or eps / t out of range with a normal density
    big = sys.float_info.max
    for (t, x, a, mu, s2) in [
            (1e140, 0, 1, 1, 1e160), (1e10, 0, 1, 1, 1e290),
            (1e10, 0, 1, -1e-300, 1e290), (1e300, 0, 1, 0.4, 0.8),
            (big, 0, 1, 0.4, 0.8), (big, 0, 1, -0.4, 0.8),
            (1.3, 0, 1, 0.4, 1e300), (1.3, 0, 1, -0.4, big),
            (1e-300, 0, 1e-150, 0.4, 0.8), (1e-300, 0, 1e-150, 0, 1),
            (2.0 ** -1000, 0, 1, 2.0 ** 1000, 2.0 ** 1000),
            (2.0 ** 1000 + 2.0 ** 960, 0, 2.0 ** 1000, 1, 2.0 ** 1000),
            (2.0 ** 1000 + 2.0 ** 960, 2.0 ** 1000, 0, 1, 2.0 ** 1000),
            (1e200, 0, 1e300, 1e100 * (1 + 2.0 ** -40), 1e-300),
            (1e-200, 1e-300, 0, 1e-100, 1e-300), (1e300, 0, 1e300, 0, 1e300)]:
        # 400 digits: Q(c) - exp(2 nu d/s2) Q(b) cancels down to 1e-300
        rows.append((t, x, a, mu, s2) +
                    settled(lambda: ig_row(t, x, a, mu, s2), 400))
    write("passage_bm.csv",
          ["t", "x", "a", "mu", "sigma2", "pdf", "cdf", "sf", "mass",
           "logmass"], rows)

    rows = []
    for (x, a, s2) in [(2, 1, 1), (1, 1e-6, 1), (1, 1 - 2 ** -40, 1),
                       (1e3, 1, 0.5), (3, 2.9, 1e-4), (5, 1, 1e3)]:
        xx, aa, ss = map(mp.mpf, (x, a, s2))
        d = xx - aa
        tl = float(d * d / ss)
        for k in (-8, -3, -2, -1, -0.3, 0, 0.3, 1, 2, 4, 8):
            t = tl * 10 ** k
            rows.append((t, x, a, s2) +
                        settled(lambda: bes3_row(t, x, a, s2), 60))
    # extreme corners: sigma2 t beyond DBL_MAX or above 2^995, a density
    # near 1e300 at t = 1e-300
    for (t, x, a, s2) in [(1e-300, 1e-150, 0.5e-150, 1), (1e10, 1, 0.5, 1e290),
                          (1e300, 2, 0.5, 1e300), (sys.float_info.max, 2, 0.5,
                                                   0.8),
                          (1e300, 1e300, 0.5e300, 1e300)]:
        rows.append((t, x, a, s2) +
                    settled(lambda: bes3_row(t, x, a, s2), 60))
    write("passage_bes3.csv", ["t", "x", "a", "sigma2", "pdf", "cdf", "sf"],
          rows)


def ig_quantile(p, x, a, mu, s2, span=200):
    """Exact quantile by bisection-safeguarded root finding in log t
    (log t in [-span, span])."""
    p = mp.mpf(p)

    def F(lt):
        return ig_parts(mp.exp(lt), x, a, mu, s2)[1] - p

    def S(lt):  # for p > 1/2 use the complement for resolution
        return (1 - p) - ig_parts(mp.exp(lt), x, a, mu, s2)[2]
    g = F if p <= 0.5 else S
    lo, hi = mp.mpf(-span), mp.mpf(span)
    for _ in range(400):
        mid = (lo + hi) / 2
        if g(mid) < 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < mp.mpf(10) ** -40:
            break
    return mp.exp((lo + hi) / 2)


def gen_passage_quantile():
    rows = []
    pars = [(1, 0, -1, 1), (1, 0, 0, 1), (0, 1, -2.5, 0.5), (3, 1, -1e-3, 2),
            (1, 0, -100, 1), (2.5, 1.5, -0.1, 0.3)]
    ps = [1e-12, 1e-6, 0.01, 0.3, 0.5, 0.7, 0.99, 1 - 1e-6]
    for (x, a, mu, s2) in pars:
        mass = ig_parts(1, x, a, mu, s2)[3]
        for p in ps:
            if p >= mass:
                continue
            rows.append((p, x, a, mu, s2) + settled(
                lambda: (ig_quantile(p, x, a, mu, s2),), 60))
    # extreme-but-representable corners: d^2/sigma2 or d/nu beyond the
    # doubles (quantiles near 1e300 and 1e-300), tiny drifts; 400 digits,
    # log t in [-800, 800]
    for (p, x, a, mu, s2) in [
            (0.3, 0, 1e300, 0.4, 0.8), (0.3, 0, 1e154, 0.4, 0.8),
            (0.3, 0, 1e-150, 0.4, 0.8), (0.3, 0, 1e-100, 0, 1e-200),
            (0.7, 0, 1, 1e-300, 1), (0.5, 0, 1e200, 1e-100, 1e300),
            (0.9, 1e-300, 0, -1e-300, 1e-300), (0.2, 0, 1e300, 1e290, 1e-300)]:
        rows.append((p, x, a, mu, s2) + settled(
            lambda: (ig_quantile(p, x, a, mu, s2, 800),), 400))
    write("passage_quantile.csv", ["p", "x", "a", "mu", "sigma2", "q"], rows)


# -------------------------------------------------------------- bridge

def cross_ref(kind, x, y, a, v):
    """P(min <= a), log P, 1 - P from the textbook forms."""
    x, y, a, v = map(mp.mpf, (x, y, a, v))
    if kind == 0:
        # log P and 1 - P from the exponent itself: exp(-C) rounds to 1
        # at n digits when C < 10^-n
        C = 2 * (x - a) * (y - a) / v
        return mp.exp(-C), -C, -mp.expm1(-C)
    p = mp.expm1(2 * a * (x + y - a) / v) / mp.expm1(2 * x * y / v)
    return p, mp.log(p), 1 - p


def cross_row(kind, x, y, a, v):
    """p, logp, nocross (-1 below 1e-300) of a bridge_cross.csv row."""
    p, lp, nc = cross_ref(kind, x, y, a, v)
    return cut(p), lp, cut(nc)


def gen_bridge_cross():
    rows = []
    base = []
    for (x, y, a) in [(1.5, 1.3, 1.0), (2.0, 3.0, 1.0), (1.0, 1.0, 0.5),
                      (1 + 1e-8, 1.7, 1.0), (1 + 2 ** -40, 1 + 2 ** -45, 1.0),
                      (3.0, 2.0, 1e-10), (3.0, 2.0, 1e-100), (10.0, 0.5, 0.25),
                      (1e4, 2e4, 5e3), (1e-4, 3e-4, 0.5e-4)]:
        L = min(x - a, y - a)
        for k in (-8, -4, -2, -1, 0, 1, 2, 4, 8):
            base.append((x, y, a, float(L * L * 10 ** k)))
        scale = max(x, y)
        for k in (-8, -3, 0, 3, 8):
            base.append((x, y, a, float(scale * scale * 10 ** k)))
    # deep tails: log P from -1e3 to -1e300 (P itself underflows)
    for v in (1e-3, 1e-10, 1e-100, 1e-300):
        base.append((2.0, 3.0, 1.0, v))
    # magnitudes near the overflow (x - a, v above 2^995) and a Bessel-3
    # exponent A = 2a(x+y-a)/v below the normal doubles
    base += [(1.0, 1.0, 1e-5, 2e300), (1.0, 1.0, 0.5, 1.4e300),
             (1e301, 1e-10, 1e-20, 1e300),
             (1.0, 1.000000000001, 0.999999999999999, 1e300),
             (1.0, 1.0, 0.999999, 1e300), (1.0, 0.5, 0.4999995, 1e300),
             (1.0, 1e-6, 1e-306, 1e8), (1e8, 100.0, 1e-298, 1e24)]
    for kind in (0, 1):
        for (x, y, a, v) in base:
            rows.append((kind, x, y, a, v) +
                        settled(lambda: cross_row(kind, x, y, a, v), 200))
    # extreme corners: (x - a)(y - a) above DBL_MAX or below DBL_MIN with
    # C = 2(x - a)(y - a)/v a normal double, log P near -DBL_MAX
    for (kind, x, y, a, v) in [
            (0, 1e200, 1e200, 0.0, 1e300), (0, 1e-200, 1e-200, 0.0, 1e-300),
            (0, 1.0, 0.5, -1e300, 1e300), (0, 1e300, 0.5, 0.0, 1e-8),
            (1, 1e200, 1e200, 0.5, 1e300), (1, 3e-200, 2e-200, 1e-200, 1e-300),
            (1, 1e300, 1.5, 1.0, 1e-8)]:
        rows.append((kind, x, y, a, v) +
                    settled(lambda: cross_row(kind, x, y, a, v), 200))
    # Bessel-3 ratio r = expm1(-A)/expm1(-B) a normal double where its
    # factors a/x, (x+y-a)/y or a(x+y-a) leave the doubles (A < 1e-290,
    # or B < 1e-280: r ~ A/B)
    for (kind, x, y, a, v) in [
            (1, sys.float_info.max, 0.5, 1e-300, sys.float_info.max),
            (1, 1e300, 0.5, 1e-300, 1e300), (1, 1e-48, 1e-199, 1e-304, 1e194)]:
        rows.append((kind, x, y, a, v) +
                    settled(lambda: cross_row(kind, x, y, a, v), 200))
    write("bridge_cross.csv",
          ["kind", "x", "y", "a", "v", "p", "logp", "nocross"], rows)


def g(v, z):
    return mp.exp(-z * z / (2 * v)) / mp.sqrt(2 * mp.pi * v)


def flevy(d, s2, t):
    return d / mp.sqrt(2 * mp.pi * s2 * t ** 3) * mp.exp(-d * d / (2 * s2 * t))


def bb_law(u, al, L, s2, t, w):
    """cdf, sf of the BB hitting time (IG form), any precision."""
    r = mp.sqrt(s2 * u * t * w)
    c = (L * u - al * w) / r
    b = (L * u + al * w) / r
    k = mp.exp(2 * al * L / (s2 * t))
    return Phi(c) + k * Phi(-b), Q(c) - k * Phi(-b)


def hit_ref(kind, u, x, y, a, s2, t, w=None):
    """pdf, cdf, sf of T_a | T_a <= t for BB (kind 0) or B3B (kind 1);
    w = t - u may be given separately (quantile search near u = t)."""
    if kind == 1 and y == 0:
        # the B3B law is continuous in y: y = 0 is its limit, taken at
        # y = 1e-45 with 120 more digits (error O(y))
        with mp.workdps(mp.mp.dps + 120):
            r = hit_ref(1, u, x, mp.mpf("1e-45"), a, s2, t, w)
        return tuple(+v for v in r)
    u, x, y, a, s2, t = map(mp.mpf, (u, x, y, a, s2, t))
    w = t - u if w is None else mp.mpf(w)
    al, L1, L2, v = x - a, abs(y - a), y + a, s2 * t
    if kind == 0:
        pdf = flevy(al, s2, u) * g(s2 * w, L1) / g(v, al + L1)
        cdf, sf = bb_law(u, al, L1, s2, t, w)
        return pdf, cdf, sf
    # extra digits for the cancellations of order 1 - rho below (positions
    # ~1e-270 sqrt(v): 1 - rho ~ 1e-540, all digits of 400 lost)
    extra = int(-mp.log10(-mp.expm1(-(L2 - L1) * (2 * al + L1 + L2) /
                                      (2 * v)))) + 10
    with mp.workdps(mp.mp.dps + max(extra, 0)):
        # first-principles density: n_{x,a}(u) q_{t-u}(a, y) / P(hit, end
        # y); both differences cancel like 1 - rho
        z = g(v, al + L1) - g(v, al + L2)
        pdf = flevy(al, s2, u) * (g(s2 * w, L1) - g(s2 * w, L2)) / z
    # signed mixture, the same extra digits
    with mp.workdps(mp.mp.dps + max(extra, 0)):
        rho = g(v, al + L2) / g(v, al + L1)
        c1, s1 = bb_law(u, al, L1, s2, t, w)
        c2, s2_ = bb_law(u, al, L2, s2, t, w)
        cdf = (c1 - rho * c2) / (1 - rho)
        sf = (s1 - rho * s2_) / (1 - rho)
    return +pdf, +cdf, +sf


def cap(v):
    """A density as written: inf above DBL_MAX (the C function returns
    SB_ERANGE there; tests/data/README.md)."""
    if isinstance(v, Marked):
        return v
    return Marked(v, mp.inf) if v > sys.float_info.max else v


def hit_row(kind, u, x, y, a, s2, t):
    """pdf, cdf, sf (-1 below 1e-300, inf above DBL_MAX) of a
    bridge_hit.csv row."""
    return tuple(cap(cut(v)) for v in hit_ref(kind, u, x, y, a, s2, t))


HIT_BB = [(1.5, 1.3, 1.0, 1.0, 1.0), (2.0, 3.0, 1.0, 0.5, 2.0),
          (1.5, 0.4, 1.0, 0.7, 2.0), (1.5, 1.0, 1.0, 1.0, 1.0),
          (1 + 1e-6, 1.5, 1.0, 1.0, 1.0), (1.5, 1.3, 1.0, 1e6, 1.0),
          (1.5, 1.3, 1.0, 1e-3, 1.0), (1.5, 1.3, 1.0, 1.0, 1e-6),
          (30.0, 20.0, 1.0, 1.0, 10.0), (1.2, 1.0 + 2 ** -30, 1.0, 0.3, 4.0)]
HIT_B3 = [(1.5, 1.3, 1.0, 1.0, 1.0), (1.1, 1.05, 1.0, 5.0, 3.0),
          (3.0, 2.0, 0.1, 1.3, 0.5), (1.5, 0.4, 1.0, 0.7, 2.0),
          (1.5, 0.0, 1.0, 1.0, 1.0), (2.0, 3.0, 1e-6, 1.0, 1.0),
          (1.5, 1.3, 1.0, 1e4, 1.0), (1.5, 1.3, 1.0, 1e-3, 1.0),
          (1.5, 1e-9, 1.0, 1.0, 1.0), (1.5, 1.0 + 1e-9, 1.0, 1.0, 1.0),
          (1.0 + 1e-7, 2.0, 1.0, 1.0, 1.0), (2.0, 2.5, 0.01, 100.0, 1.0),
          (4.0, 3.0, 1.0, 2.0, 1.0)]
UFRAC = [1e-8, 1e-4, 1e-2, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8,
         0.9, 0.95, 0.99, 1 - 1e-4, 1 - 1e-8]


def gen_bridge_hit():
    rows = []
    for kind, sets in ((0, HIT_BB), (1, HIT_B3)):
        for (x, y, a, s2, t) in sets:
            for f in UFRAC:
                u = t * f
                rows.append((kind, u, x, y, a, s2, t) + settled(
                    lambda: hit_row(kind, u, x, y, a, s2, t), 60))
    # extreme-but-representable corners (400 digits: with v ~ 1e300 the
    # B3B density and mixture cancel to 1e-300): u = 1e-300 with a
    # normal density near 1e280 (B3B: y/x = 1e-31, the y -> 0 law),
    # t = 1e300 and DBL_MAX, t = 1e-300 (rescaled), and B3B at u = 1e-300
    # with min(a, y) ~ 1e-149
    big = sys.float_info.max
    for (kind, u, x, y, a, s2, t) in [
            (0, 1e-300, 1e-149, 0.5, 0.0, 1.0, 1.0),
            (0, 0.3, 1.0, 0.5, 0.0, 1.0, 1e300),
            (0, 0.3, 1.0, 0.5, 0.0, 1.0, big),
            (0, 0.3e-300, 1e-150, 0.5e-150, 0.0, 1.0, 1e-300),
            (1, 1e-300, 2e-149, 1e-180, 1e-149, 1.0, 1.0),
            (1, 0.3, 2.0, 1.0, 0.5, 1.0, 1e300),
            (1, 0.3e-300, 2e-150, 1e-150, 0.5e-150, 1.0, 1e-300),
            # B3B, u = 1e-300 with min(a, y) ~ 1e-149 (1 - rho ~ 1e-298):
            # the expansion of the mixture, whose products L u and
            # 2 dl ex g0 underflow
            (1, 1e-300, 2e-149, 1e-149, 1e-149, 1.0, 1.0),
            (1, 1e-300, 2e-149, 1e-149, 0.5e-149, 1.0, 1.0),
            # B3B, min(a, y) = 1e-305 with v = 1e-30 (not rescaled):
            # 1 - rho ~ 1e-289 is a normal double but min(a, y) times
            # 2(alpha + max(a, y)) and 2 a y are subnormal
            (1, 0.5, 3e-15, 2e-15, 1e-305, 1e-30, 1.0),
            (1, 0.5, 3e-15, 1e-305, 2e-15, 1e-30, 1.0),
            # B3B, a = 1e-320 the negligible min(a, y) (k below DBL_MIN):
            # the limit law, whose density factor is max(a, y) t /
            # ((alpha + max(a, y)) w)
            (1, 0.5, 1e5, 0.5e5, 1e-320, 1e10, 1.0),
            (1, 0.5, 1e-10, 1e-10, 1e-320, 1e-6, 1.0),
            # B3B with every position 1e-200 to 3e-272 sqrt(v) (k = 1 - rho
            # ~ 1e-400 below DBL_MIN, min(a, y) comparable to the others): the
            # mixture with its extended normaliser, not the limit law
            # (cdf 0.419 for 0.540 in the last row).  sqrt(v) = 1e-100,
            # positions 1e-300: early hits at u ~ 1e-300 (cdf 0.35-0.63),
            # the plateau at u = t/2 (0.722); y < a; x -> a
            (1, 0.5e-300, 1.5e-300, 1.3e-300, 1e-300, 1e-300, 1e100),
            (1, 2e-300, 1.5e-300, 1.3e-300, 1e-300, 1e-300, 1e100),
            (1, 1e-299, 1.5e-300, 1.3e-300, 1e-300, 1e-300, 1e100),
            (1, 0.5e100, 1.5e-300, 1.3e-300, 1e-300, 1e-300, 1e100),
            (1, 2e-300, 3e-300, 0.5e-300, 1e-300, 1e-300, 1e100),
            (1, 0.5e100, 3e-300, 0.5e-300, 1e-300, 1e-300, 1e100),
            (1, 2e-300, 1e-300 * (1 + 2 ** -30), 2e-300, 1e-300, 1e-300,
             1e100),
            (1, 0.3, 1.5e-200, 1.3e-200, 1e-200, 1.0, 1.0),
            (1, 4.405338698603621e-108, 2.5656389575526504e-198,
             2.0745494702725768e-198, 7.987425390623592e-199,
             1.962483298637378e255, 4.40534153809633e-108)]:
        rows.append((kind, u, x, y, a, s2, t) + settled(
            lambda: hit_row(kind, u, x, y, a, s2, t), 400))
    # positions beyond ~2^990 sqrt(sigma2 t), where bridge_hit.c's
    # rescaling overflowed them (SB_EDOM) or its evaluation read
    # sigma2 u t (t - u) below DBL_MIN as a law without mass below u; 1000
    # digits: (alpha + L)^2/(2v) ~ 2^2100 has 632 digits before the point,
    # and at 400 digits both precisions of settled() dropped the same
    # exp(-c^2/2) from the density.  With a = 2^-51 (2^-350) the
    # numerator L u - alpha (t - u) = a t/2 is all that is left of
    # products near 2^1200: c = 1/sqrt 3 (2/sqrt 3), a normal cdf; the
    # second set's density exceeds DBL_MAX (inf: SB_ERANGE).  x = 1e-300,
    # y = 1e300, u = 1e-310: the law sits at u ~ 1e-600, cdf 1
    for kind in (0, 1):
        for (u, x, y, a, s2, t) in [
                (2.0 ** 198, 2.0 ** 1000, 3 * 2.0 ** 1000, 2.0 ** -51,
                 2.0 ** -300, 2.0 ** 200),
                (0.25, 2.0 ** 1000, 3 * 2.0 ** 1000, 2.0 ** -350,
                 2.0 ** -700, 1.0),
                (1e-310, 1e-300, 1e300, 1e-301 if kind else 0.0, 1.0,
                 1.0)]:
            rows.append((kind, u, x, y, a, s2, t) + settled(
                lambda: hit_row(kind, u, x, y, a, s2, t), 1000))
    write("bridge_hit.csv",
          ["kind", "u", "x", "y", "a", "sigma2", "t", "pdf", "cdf", "sf"],
          rows)


def hit_quantile(kind, p, x, y, a, s2, t, span=300):
    """Exact quantile: bisection in log s, s = u t/(t - u), log s in
    [-span, span]."""
    p = mp.mpf(p)
    t_ = mp.mpf(t)
    lo, hi = mp.mpf(-span), mp.mpf(span)
    for _ in range(500):
        mid = (lo + hi) / 2
        s = mp.exp(mid)
        u = t_ * s / (t_ + s)
        _, cdf, sf = hit_ref(kind, u, x, y, a, s2, t, t_ * t_ / (t_ + s))
        gv = cdf - p if p <= 0.5 else (1 - p) - sf
        if gv < 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < mp.mpf(10) ** -35:
            break
    s = mp.exp((lo + hi) / 2)
    return t_ * s / (t_ + s)


def gen_bridge_quantile():
    rows = []
    ps = [1e-12, 1e-6, 0.01, 0.3, 0.5, 0.7, 0.99, 1 - 1e-6]
    sets = [(0, HIT_BB[0]), (0, HIT_BB[1]), (0, HIT_BB[2]), (0, HIT_BB[8]),
            (1, HIT_B3[0]), (1, HIT_B3[3]), (1, HIT_B3[5]), (1, HIT_B3[6]),
            (1, HIT_B3[12])]
    for kind, (x, y, a, s2, t) in sets:
        for p in ps:
            rows.append((kind, p, x, y, a, s2, t) + settled(
                lambda: (hit_quantile(kind, p, x, y, a, s2, t),), 40))
    # extreme corners (the iteration in log s failed there): laws
    # narrower than one ulp (sigma2 = 1e-154, a = -1e300), u ~ 1e-300
    # (sigma2 = 1e300), t = 1e300; 400 digits, log s in [-800, 800]
    for (kind, p, x, y, a, s2, t) in [
            (0, 0.3, 1.0, 0.5, 0.0, 1e-154, 1.0),
            (0, 0.3, 1.0, 0.5, 0.0, 1e300, 1.0),
            (0, 0.3, 1.0, 0.5, 0.0, 1.0, 1e300),
            (0, 0.3, 1.0, 0.5, -1e300, 1.0, 1.0),
            (1, 0.3, 2.0, 1.0, 0.5, 1e300, 1.0),
            (1, 0.3, 2.0, 1.0, 0.5, 1.0, 1e300),
            (1, 0.3, 2.0, 1.0, 0.5, 1e-154, 1.0)]:
        rows.append((kind, p, x, y, a, s2, t) + settled(
            lambda: (hit_quantile(kind, p, x, y, a, s2, t, 800),), 400))
    write("bridge_quantile.csv",
          ["kind", "p", "x", "y", "a", "sigma2", "t", "q"], rows)


# Bessel-3 bridges whose mixture range is short (1 - rho small), where
# bridge_hit.c expands (2) about its mid L: 1 - rho ~ 1e-2, 1e-4, 1e-6,
# 1e-9 (a = (1 - rho)/(2(x + y)) with v = 1), both sides of the switch from
# (1) at rho = 0.95 (rho = 0.95005, 0.94995), the benchmark's regime
# (a = 0.01, v = 2), y < a, x -> a, a flat law (sigma2 = 1e3); u up to
# 1 - 1e-4 of t, where the expansion needs panels or the quadrature.
HIT_NARROW = [(1.5, 1.3, 1.7857142857142857e-3, 1.0, 1.0),
              (1.5, 1.3, 1.7857142857142857e-5, 1.0, 1.0),
              (1.5, 1.3, 1.7857142857142857e-7, 1.0, 1.0),
              (1.5, 1.3, 1.7857142857142857e-10, 1.0, 1.0),
              (1.5, 1.3, 9.18e-3, 1.0, 1.0),
              (1.5, 1.3, 9.20e-3, 1.0, 1.0),
              (1.4, 2.1, 0.01, 2.0, 1.0),
              (1.2, 0.5e-4, 1e-4, 0.8, 1.0),
              (1e-6 + 1e-9, 0.7, 1e-6, 1.0, 1.0),
              (3.0, 2.0, 1e-3, 1e3, 0.5)]
UNARROW = [1e-3, 0.05, 0.2, 0.4, 0.5, 0.6, 0.8, 0.9, 0.99, 0.999, 1 - 1e-4]
PNARROW = [1e-9, 0.01, 0.3, 0.5, 0.7, 0.99, 1 - 1e-9]


def gen_bridge_narrow():
    rows = []
    for (x, y, a, s2, t) in HIT_NARROW:
        for f in UNARROW:
            u = t * f
            rows.append((1, u, x, y, a, s2, t) + settled(
                lambda: hit_row(1, u, x, y, a, s2, t), 60))
    write("bridge_narrow.csv",
          ["kind", "u", "x", "y", "a", "sigma2", "t", "pdf", "cdf", "sf"],
          rows)
    rows = []
    for (x, y, a, s2, t) in HIT_NARROW:
        for p in PNARROW:
            rows.append((1, p, x, y, a, s2, t) + settled(
                lambda: (hit_quantile(1, p, x, y, a, s2, t),), 40))
    write("bridge_narrow_quantile.csv",
          ["kind", "p", "x", "y", "a", "sigma2", "t", "q"], rows)


def check_closed_forms():
    """Closed forms vs mp.quad of the densities (aborts on mismatch)."""
    mp.mp.dps = 30
    for (t, x, a, mu, s2) in [(0.7, 1, 0, -1, 1), (3, 0, 1, -0.5, 2),
                              (0.2, 2, 1.5, 0, 0.3)]:
        pdf, cdf, sf = ig_parts(t, x, a, mu, s2)[:3]
        q = mp.quad(lambda s: ig_parts(s, x, a, mu, s2)[0], [0, t])
        assert abs(q - cdf) < 1e-20, (q, cdf)
        assert abs(sf - (1 - cdf)) < 1e-20
    # hitting-time CDFs (IG form, signed mixture) vs quadrature of the
    # first-principles densities
    for kind, (x, y, a, s2, t) in [(0, HIT_BB[0]), (0, HIT_BB[2]),
                                   (1, HIT_B3[0]), (1, HIT_B3[3]),
                                   (1, HIT_B3[2])]:
        for f in (0.2, 0.6):
            u = t * f
            q = mp.quad(lambda s: hit_ref(kind, s, x, y, a, s2, t)[0],
                        [0, u / 2, u])
            q2 = mp.quad(lambda s: hit_ref(kind, s, x, y, a, s2, t)[0],
                         [0, t / 2, t])
            _, cdf, sf = hit_ref(kind, u, x, y, a, s2, t)
            assert abs(q - cdf) < 1e-18 and abs(q2 - 1) < 1e-18, (q, cdf)
    mp.mp.dps = 60


if __name__ == "__main__":
    os.makedirs(DATA, exist_ok=True)
    check_closed_forms()
    args = sys.argv[1:]
    if args[:1] == ["--verify"]:
        VERIFY["on"] = True
        args = args[1:]
    which = args or ["mills", "passage", "passage_quantile",
                             "bridge_cross", "bridge_hit", "bridge_quantile",
                             "bridge_narrow"]
    if "mills" in which:
        gen_mills()
    if "passage" in which:
        gen_passage()
    if "passage_quantile" in which:
        gen_passage_quantile()
    if "bridge_cross" in which:
        gen_bridge_cross()
    if "bridge_hit" in which:
        gen_bridge_hit()
    if "bridge_quantile" in which:
        gen_bridge_quantile()
    if "bridge_narrow" in which:
        gen_bridge_narrow()
    if VERIFY["failed"]:
        sys.exit("differ from the generator: " + ", ".join(VERIFY["failed"]))
