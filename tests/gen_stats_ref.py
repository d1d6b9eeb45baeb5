#!/usr/bin/python3
"""Reference vectors for tests/test_stats.c, computed with mpmath.

Usage:  /usr/bin/python3 tests/gen_stats_ref.py [OUTDIR]   (default tests/data)
Writes stats_*.csv (header line, 20 significant digits).  Takes about 15 CPU
minutes, mostly the Durbin matrices of the KS vectors.  Optional further
arguments select parts: intervals ks ks2 misc kslarge extreme (extreme is
not in the default set; it takes ~1 CPU minute).

Every value is computed independently of the C code and of GSL:
  - Poisson / binomial tails: mpmath's regularized incomplete gamma, exact
    binomial sums (positive terms), or tanh-sinh quadrature of the density
    (huge shapes), at 50 digits; interval ends by mpmath's root finder;
  - KS: Durbin's matrix (Durbin 1973) powered in 60-digit arithmetic (no
    rescaling), the one-sided Birnbaum-Tingey sum, the Kolmogorov series;
  - two-sample KS: exact lattice-path counts with Python integers;
  - chi-square and Student t: regularized incomplete gamma / beta (the far
    chi-square tails, down to the underflow edge, checked against a
    quadrature of the density scaled by its value at x).
"""
import os
import sys
from fractions import Fraction

import mpmath as mp

mp.mp.dps = 50
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "data")


def s(x):
    """20 significant digits (or nan/inf)."""
    if isinstance(x, (int,)) and not isinstance(x, bool):
        return str(x)
    x = mp.mpf(x)
    if mp.isnan(x):
        return "nan"
    if mp.isinf(x):
        return "inf" if x > 0 else "-inf"
    return mp.nstr(x, 20, min_fixed=-4, max_fixed=12)


def write(name, header, rows):
    path = os.path.join(OUT, name)
    with open(path, "w") as f:
        f.write(header + "\n")
        for r in rows:
            f.write(",".join(s(v) for v in r) + "\n")
    print("wrote", path, len(rows), "rows", file=sys.stderr)


def root(f, guess, scale, lo_lim, hi_lim):
    """Root of the increasing function f: bracket [guess -+ scale], widened
    by doubling within [lo_lim, hi_lim] until f changes sign, then the
    Illinois bracketed false-position method to 42 digits."""
    a, b = max(guess - scale, lo_lim), min(guess + scale, hi_lim)
    while f(a) > 0:
        scale *= 2
        a = max(guess - scale, lo_lim)
    while f(b) < 0:
        scale *= 2
        b = min(guess + scale, hi_lim)
    fa, fb = f(a), f(b)
    if fa == 0:
        return a
    if fb == 0:
        return b
    side = 0
    for _ in range(400):  # Illinois false position: superlinear, bracketed
        c = (a * fb - b * fa) / (fb - fa)
        fc = f(c)
        if fc == 0:
            return c
        if (fc < 0) == (fa < 0):
            a, fa = c, fc
            if side == -1:
                fb /= 2
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa /= 2
            side = 1
        if abs(b - a) <= mp.mpf(10)**-42 * max(abs(a), abs(b)):
            break
    else:
        raise RuntimeError("root: no convergence")
    return (a + b) / 2


# ------------------------------------------------------------------ tails
def quad_tail(logdens, x, mode, sig, lower, lo_sup, hi_sup):
    """Integral of exp(logdens) over the tail beyond x, by tanh-sinh
    quadrature split every 2 sigma (logdens includes the normalisation)."""
    L = 40
    if lower:
        a = max(lo_sup, mode - L * sig)
        if x <= a:
            return mp.mpf(0)
        n = int(mp.ceil((x - a) / (2 * sig)))
        pts = [a + (x - a) * i / n for i in range(n + 1)]
    else:
        b = min(hi_sup, mode + L * sig)
        if x >= b:
            return mp.mpf(0)
        n = int(mp.ceil((b - x) / (2 * sig)))
        pts = [x + (b - x) * i / n for i in range(n + 1)]
    return mp.quad(lambda t: mp.exp(logdens(t)), pts)


def gamma_tail(a, x, lower):
    """Regularized lower (P) or upper (Q) incomplete gamma."""
    a = mp.mpf(a)
    if a <= 10**6:
        if lower:
            return mp.gammainc(a, 0, x, regularized=True)
        return mp.gammainc(a, x, mp.inf, regularized=True)
    lg = mp.loggamma(a)
    return quad_tail(lambda t: (a - 1) * mp.log(t) - t - lg, x, a - 1,
                     mp.sqrt(a), lower, mp.mpf(0), mp.inf)


def binom_tail(k, n, p, upper):
    """P(X >= k) (upper) or P(X <= k) for X ~ Bin(n, p), exact sum of
    positive terms from k outward until negligible."""
    k, n, p = int(k), int(n), mp.mpf(p)
    q = 1 - p
    lt = (mp.loggamma(n + 1) - mp.loggamma(k + 1) - mp.loggamma(n - k + 1) +
          k * mp.log(p) + (n - k) * mp.log(q))
    t = mp.exp(lt)
    tot = t
    j = k
    eps = mp.mpf(10)**-(mp.mp.dps - 2)
    if upper:
        while j < n:
            t = t * (n - j) / (j + 1) * p / q
            j += 1
            tot += t
            if t < eps * tot and j > n * p:
                break
    else:
        while j > 0:
            t = t * j / (n - j + 1) * q / p
            j -= 1
            tot += t
            if t < eps * tot and j < n * p:
                break
    return tot


def beta_tail(a, b, x, lower):
    """Regularized incomplete beta I_x(a,b) (lower) or 1 - I_x (upper) for
    integer a, b, through the binomial identity I_x(a, b) = P(Bin(a+b-1, x)
    >= a); quadrature for a + b > 2e6."""
    a, b = int(a), int(b)
    n = a + b - 1
    if n <= 2 * 10**6:
        if lower:
            return binom_tail(a, n, x, True)
        return binom_tail(a - 1, n, x, False)
    A, B = mp.mpf(a), mp.mpf(b)
    lb = mp.loggamma(A) + mp.loggamma(B) - mp.loggamma(A + B)
    mode = (A - 1) / (A + B - 2)
    sig = mp.sqrt(mode * (1 - mode) / (A + B - 2))
    return quad_tail(lambda t: (A - 1) * mp.log(t) + (B - 1) * mp.log1p(-t)
                     - lb, x, mode, sig, lower, mp.mpf(0), mp.mpf(1))


# -------------------------------------------------------------- intervals
def wh(a, z):
    """Wilson-Hilferty guess of the gamma(a) quantile at normal deviate z."""
    a = mp.mpf(a)
    return a * (1 - 1 / (9 * a) + z / (3 * mp.sqrt(a)))**3


def garwood(k, level):
    t = (1 - mp.mpf(level)) / 2
    z = -mp.sqrt(2) * mp.erfinv(2 * t - 1)  # upper normal deviate
    k = int(k)
    tiny = mp.mpf(10)**-40
    if k == 0:
        lo = mp.mpf(0)
    else:
        g = max(wh(k, -z), tiny)
        lo = root(lambda mu: gamma_tail(k, mu, True) - t, g,
                  g / 50 + mp.mpf(10)**-3, tiny, mp.mpf(k))
    g = wh(k + 1, z)
    hi = root(lambda mu: t - gamma_tail(k + 1, mu, False), g,
              g / 1000 + mp.mpf(10)**-2, mp.mpf(k), mp.mpf(10)**20)
    return lo, hi


def clopper_pearson(k, n, level):
    t = (1 - mp.mpf(level)) / 2
    z = -mp.sqrt(2) * mp.erfinv(2 * t - 1)
    k, n = int(k), int(n)
    ph = mp.mpf(k) / n
    sd = mp.sqrt((ph * (1 - ph) + mp.mpf(1) / n) / n)
    tiny = mp.mpf(10)**-40
    if k == 0:
        lo = mp.mpf(0)
    elif k == n:
        lo = t ** (mp.mpf(1) / n)
    else:
        g = max(ph - z * sd, tiny)
        lo = root(lambda p: beta_tail(k, n - k + 1, p, True) - t, g,
                  sd / 20, tiny, ph)
    if k == n:
        hi = mp.mpf(1)
    elif k == 0:
        hi = 1 - t ** (mp.mpf(1) / n)
    else:
        g = min(ph + z * sd, 1 - tiny)
        hi = root(lambda p: t - beta_tail(k + 1, n - k, p, False), g,
                  sd / 20, ph, 1 - tiny)
    return lo, hi


def gen_intervals():
    levels = ["0.5", "0.6827", "0.9", "0.95", "0.99", "0.999", "0.999999",
              "0.999999999", "0.999999999999"]
    rows = []
    for k in [0, 1, 2, 3, 5, 10, 20, 50, 100, 1000, 10**4, 10**5, 10**5 + 1,
              10**6, 10**7, 10**9, 10**12]:
        for lv in levels:
            lvd = float(lv)
            lo, hi = garwood(k, mp.mpf(lvd))
            rows.append((k, lvd, lo, hi))
    write("stats_poisson_ci.csv", "k,level,lo,hi", rows)

    # Cross-check of the two independent tail methods at a shape where both
    # apply (gammainc vs quadrature; binomial sum vs quadrature).
    a = mp.mpf(10**6)
    x = a - 2 * mp.sqrt(a)
    lg = mp.loggamma(a)
    q1 = mp.gammainc(a, 0, x, regularized=True)
    q2 = quad_tail(lambda t: (a - 1) * mp.log(t) - t - lg, x, a - 1,
                   mp.sqrt(a), True, mp.mpf(0), mp.inf)
    assert abs(q1 / q2 - 1) < mp.mpf(10)**-30, (q1, q2)

    rows = []
    cases = [(0, 1), (1, 1), (0, 10), (1, 10), (3, 10), (5, 10), (9, 10),
             (10, 10), (1, 100), (50, 100), (99, 100), (7, 1000),
             (500, 1000), (1, 10**6), (10, 10**9), (1000, 10**4),
             (10**5, 10**6), (10**6, 10**7), (3, 10**15)]
    for k, n in cases:
        for lv in ["0.5", "0.9", "0.95", "0.99", "0.999999",
                   "0.999999999999"]:
            lvd = float(lv)
            lo, hi = clopper_pearson(k, n, mp.mpf(lvd))
            rows.append((k, n, lvd, lo, hi))
    write("stats_binomial_ci.csv", "k,n,level,lo,hi", rows)


# ---------------------------------------------------------------- KS
def durbin_cdf(n, d):
    """P(D_n < d), Durbin's matrix powered in high precision."""
    d = mp.mpf(d)
    nd = n * d
    k = int(mp.floor(nd)) + 1
    m = 2 * k - 1
    h = k - nd
    H = mp.matrix(m, m)
    for i in range(m):
        for j in range(m):
            r = i - j + 1
            if r >= 0:
                H[i, j] = 1 / mp.factorial(r)
    for i in range(m):
        H[i, 0] -= h**(i + 1) / mp.factorial(i + 1)
        H[m - 1, i] -= h**(m - i) / mp.factorial(m - i)
    if 2 * h - 1 > 0:
        H[m - 1, 0] += (2 * h - 1)**m / mp.factorial(m)
    R, B, e = None, H, n
    while e:
        if e & 1:
            R = B if R is None else R * B
        e >>= 1
        if e:
            B = B * B
    return R[k - 1, k - 1] * mp.factorial(n) / mp.mpf(n)**n


def ks_sf(n, d):
    """P(D_n >= d) = 1 - Durbin CDF, with the working precision raised by
    the number of digits the subtraction cancels."""
    p = 1 - durbin_cdf(n, d)
    lost = -int(mp.floor(mp.log10(p))) if p > 0 else mp.mp.dps
    if lost > 5:
        with mp.workdps(mp.mp.dps + lost + 5):
            p = 1 - durbin_cdf(n, d)
    return p


def smirnov_plus(n, d):
    """P(D_n^+ >= d), Birnbaum-Tingey sum (positive terms)."""
    d = mp.mpf(d)
    tot = mp.mpf(0)
    j = 0
    while j < n * (1 - d):
        tot += (mp.binomial(n, j) * (1 - d - mp.mpf(j) / n)**(n - j) *
                (d + mp.mpf(j) / n)**(j - 1))
        j += 1
    return d * tot


def smirnov_plus_window(n, d, cut=80):
    """P(D_n^+ >= d) for large n: the Birnbaum-Tingey sum over the terms
    within e^-cut of the largest (the terms are unimodal in j), each from
    log-gamma at 30 digits.  Minutes per value at n = 1e7."""
    with mp.workdps(30):
        d, N = mp.mpf(d), mp.mpf(n)
        lgn = mp.loggamma(N + 1)

        def lt(j):
            j = mp.mpf(j)
            return (lgn - mp.loggamma(j + 1) - mp.loggamma(N - j + 1) +
                    (N - j) * mp.log(1 - d - j / N) +
                    (j - 1) * mp.log(d + j / N))
        J = int(mp.ceil(N * (1 - d))) - 1
        lo, hi = 0, J
        while hi - lo > 2:  # ternary search for the largest term
            m1, m2 = lo + (hi - lo) // 3, hi - (hi - lo) // 3
            if lt(m1) < lt(m2):
                lo = m1
            else:
                hi = m2
        jm = max(range(lo, hi + 1), key=lt)
        top, tot = lt(jm), mp.mpf(0)
        for j0, step in ((jm, 1), (jm - 1, -1)):
            j = j0
            while 0 <= j <= J:
                term = lt(j) - top
                if term < -cut:
                    break
                tot += mp.exp(term)
                j += step
        return d * tot * mp.exp(top)


def gen_ks_large():
    """n > 1e6, small p: the one-sided tail, which the C code takes from
    the integral of the continued terms there."""
    rows = []
    print("ks: n = 2e6 and 1e7 (~10 minutes)", file=sys.stderr)
    for n, z in [(2 * 10**6, 3.0), (2 * 10**6, 6.0), (10**7, 10.0),
                 (10**7, 13.0)]:
        d = z / n**0.5
        rows.append((n, d, smirnov_plus_window(n, d)))
    write("stats_ks_large.csv", "n,d,pplus", rows)


def gen_ks():
    mp.mp.dps = 60
    rows = []
    small = [1, 2, 3, 5, 10, 20, 50, 100, 140]
    print("ks: n <= 140", file=sys.stderr)
    for n in small:
        ds = set()
        for nd in [0.3, 0.5, 0.75, 1.0, 1.5, 2.2, 3.0, 4.5]:
            if nd / n < 1:
                ds.add(nd / n)
        for z in [0.3, 0.5, 0.7, 0.9, 1.1, 1.36, 1.63, 2.0, 2.5, 3.0]:
            d = z / n**0.5
            if d < 1:
                ds.add(d)
        for d in [0.5, 0.6, 0.9, 1 - 1.0 / n + 1e-3 if n > 1 else 0.5]:
            if d < 1:
                ds.add(d)
        for d in sorted(ds):
            pp = smirnov_plus(n, d)
            if n * d <= 0.5:
                p = mp.mpf(1)
            elif d >= 0.5:  # the two one-sided events are disjoint
                p = 2 * pp
            else:
                p = ks_sf(n, d)
            rows.append((n, d, p, pp))
    # beyond n = 140: Durbin region (n d^1.5 <= 1.4) and Pelz-Good region
    print("ks: n = 141 ... 1000 (several minutes)", file=sys.stderr)
    for n in [141, 300, 1000]:
        for z in [0.4, 0.55, 0.8, 1.0, 1.36, 1.63, 2.0]:
            d = z / n**0.5
            rows.append((n, d, ks_sf(n, d), smirnov_plus(n, d)))
    for n in [10**4, 10**5]:
        d = 1.1 * (1.4 / n)**(2 / 3.0)  # Durbin still cheap (m small)
        for f in [0.5, 0.8]:
            rows.append((n, f * d, ks_sf(n, f * d), mp.nan))
    # small p at large n: only the one-sided sum is available (p = nan)
    for n, z in [(10**4, 3.0), (10**5, 4.0)]:
        d = z / n**0.5
        rows.append((n, d, mp.nan, smirnov_plus(n, d)))
    write("stats_ks.csv", "n,d,p,pplus", rows)

    rows = []
    for t in [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8280, 0.9, 1.0, 1.2239,
              1.3581, 1.5, 1.6276, 2.0, 3.0, 5.0, 10.0, 20.0]:
        t = mp.mpf(t)
        tot = mp.mpf(0)
        j = 1
        while True:
            term = mp.exp(-2 * j * j * t * t)
            tot += term if j % 2 else -term
            if term < mp.mpf(10)**-400 or j > 5000:
                break
            j += 1
        rows.append((t, 2 * tot))
    write("stats_kolmogorov.csv", "t,q", rows)
    mp.mp.dps = 50


def paths_inside(nx, ny, c):
    """Number of monotone lattice paths (0,0) -> (nx,ny) with
    |i ny - j nx| < c at every point (Python integers: exact)."""
    row = [0] * (ny + 1)
    for i in range(nx + 1):
        for j in range(ny + 1):
            if abs(i * ny - j * nx) >= c:
                row[j] = 0
            elif i == 0 and j == 0:
                row[j] = 1
            else:
                row[j] = (row[j] if i else 0) + (row[j - 1] if j else 0)
    return row[ny]


def gen_ks2():
    from math import comb
    rows = []
    for nx, ny in [(1, 1), (2, 3), (3, 5), (5, 7), (10, 15), (13, 29),
                   (20, 30), (40, 60), (100, 100), (50, 70), (7, 300)]:
        L = nx * ny
        tot = comb(nx + ny, nx)
        vals = sorted({abs(i * ny - j * nx) for i in range(nx + 1)
                       for j in range(ny + 1)} - {0})
        pick = vals if len(vals) <= 12 else [vals[int(f * (len(vals) - 1))]
                                             for f in (0, .1, .2, .3, .4, .5,
                                                       .6, .7, .8, .9, 1)]
        for c in pick:
            p = Fraction(tot - paths_inside(nx, ny, c), tot)
            rows.append((nx, ny, c, mp.mpf(p.numerator) / p.denominator))
    write("stats_ks2.csv", "nx,ny,c,p", rows)


# --------------------------------------------------------- chi2, t, z
def check_far_tail(a, y, q):
    """Abort unless q agrees with an independent evaluation of the upper
    tail Q(a, y), y beyond the mode: the density at y (loggamma) times the
    integral of f(t)/f(y) over t > y, by tanh-sinh quadrature split on the
    local decay scale."""
    def lf(t):
        return (a - 1) * mp.log(t) - t
    h = 1 / max((y - a + 1) / y, 1 / mp.sqrt(a - 1))
    pts = [y + k * h for k in (0, 1, 2, 4, 8, 16, 32, 64, 128)] + [mp.inf]
    i = mp.quad(lambda t: mp.exp(lf(t) - lf(y)), pts)
    q2 = mp.exp(lf(y) - mp.loggamma(a)) * i
    if abs(q2 / q - 1) > mp.mpf(10)**-30:
        raise RuntimeError("chi2 far tail: gammainc %s, quadrature %s"
                           % (mp.nstr(q, 25), mp.nstr(q2, 25)))


def gen_misc():
    rows = []
    for dof in [1, 2, 3, 10, 100, 1000, 10**5, 199999, 200001, 3 * 10**5,
                10**6]:
        for z in [-3, 0, 2, 5, 10]:
            x = dof + z * (2.0 * dof)**0.5
            if x <= 0:
                continue
            x = float(x)
            q = gamma_tail(mp.mpf(dof) / 2, mp.mpf(x) / 2, False)
            rows.append((dof, x, q))
        if dof <= 10:
            for x in [1e-3, 0.5, 1.6, 40.0, 200.0]:
                rows.append((dof, x, gamma_tail(mp.mpf(dof) / 2,
                                                mp.mpf(x) / 2, False)))
    # Far upper tails at large dof, down to and past the underflow edge:
    # x solving Q = target, rounded to a double, Q recomputed there.
    # Targets below DBL_TRUE_MIN / 2 (~2.5e-324) must come out as 0.
    for dof in [401, 12000, 10**5, 10**6]:
        a = mp.mpf(dof) / 2
        for e in [-40, -60, -100, -150, -200, -250, -300, -305, -310, -320,
                  mp.log10(4) - 324, -325]:
            lt = mp.mpf(e) * mp.log(10)
            z0 = mp.sqrt(-2 * lt)
            x = root(lambda x: lt - mp.log(gamma_tail(a, x / 2, False)),
                     dof + z0 * mp.sqrt(2 * dof), mp.sqrt(2 * dof),
                     mp.mpf(dof), mp.mpf(100) * dof)
            x = float(x)
            q = gamma_tail(a, mp.mpf(x) / 2, False)
            check_far_tail(a, mp.mpf(x) / 2, q)
            rows.append((dof, x, q))
    write("stats_chi2.csv", "dof,x,q", rows)

    rows = []
    for nu in [1, 2, 3, 4, 10, 30, 100, 10**4]:
        for lv in [0.5, 0.95, 0.99, 0.999998, 0.999999999998]:
            qq = (1 - mp.mpf(lv)) / 2  # what the C code forms from level
            nn = mp.mpf(nu)

            def upper(t):  # P(T > t) for t > 0
                return mp.betainc(nn / 2, mp.mpf(1) / 2, 0, nn / (nn + t * t),
                                  regularized=True) / 2
            t = root(lambda t: qq - upper(t), mp.mpf(2), mp.mpf(1),
                     mp.mpf(0), mp.mpf(10)**14)
            rows.append((nu, lv, t))
    write("stats_tquant.csv", "nu,level,t", rows)

    rows = []
    for z in [0.0, 0.1, 0.5, 1.0, 1.959963984540054, 2.5758293035489, 3.0,
              5.0, 8.0, 10.0, 20.0, 30.0, 37.5]:
        rows.append((z, mp.erfc(mp.mpf(z) / mp.sqrt(2))))
    write("stats_zpvalue.csv", "z,p", rows)


# ------------------------------------------------- extreme arguments
def binom_le(k, n, q):
    """P(X <= k), X ~ binomial(n, q), k small: the terms from (1-q)^n by
    their exact ratios (n - f)/(f + 1) q/(1 - q)."""
    q = mp.mpf(q)
    t = mp.exp(n * mp.log1p(-q))
    tot = t
    for f in range(k):
        t *= mp.mpf(n - f) / (f + 1) * q / (1 - q)
        tot += t
    return tot


def cp_small(k, n, level):
    """Clopper-Pearson interval for a small count k of n >= 1 trials, from
    the finite sums (no incomplete beta): P(X >= k | lo) = t,
    P(X <= k | hi) = t."""
    t = (1 - mp.mpf(level)) / 2
    ph = mp.mpf(k) / n
    sd = mp.sqrt((ph + mp.mpf(1) / n) / n)
    tiny = mp.mpf(10)**-60
    lo = mp.mpf(0) if k == 0 else root(
        lambda p: (1 - binom_le(k - 1, n, p)) - t, max(ph - 2 * sd, tiny),
        sd, tiny, ph)
    hi = root(lambda p: t - binom_le(k, n, p), ph + 2 * sd, sd, ph,
              mp.mpf(1) / 2)
    return lo, hi


def ks2_equal_sum(n, d):
    """P(D >= d), equal sizes n: the threshold h as the C code forms it
    from the double d, then the Gnedenko-Korolyuk sum with 50-digit
    log-gamma ratios."""
    L = float(n) * float(n)
    c = d * L
    cr = float(round(c))
    ci = cr if abs(c - cr) <= 1e-9 * c else float(mp.ceil(c))
    h = int(mp.ceil(mp.mpf(ci) / n))
    lg = 2 * mp.loggamma(n + 1)
    s, j = mp.mpf(0), 1
    while j * h <= n:
        term = mp.exp(lg - mp.loggamma(n - j * h + 1) -
                      mp.loggamma(n + j * h + 1))
        s += term if j % 2 else -term
        if term < mp.mpf(10)**-40 * s:
            break
        j += 1
    return 2 * s


def gen_extreme():
    """Rows case,a,b,c,w1,w2 for test_extreme_arguments (integers exact,
    doubles as given to the C code; w2 nan where unused):
      1 binomial p-value  (k, n, p)         w1 = p-value
      2 binomial CI       (k, n, level)     w1, w2 = lo, hi
      3 Poisson ratio CI  (k1, k2, level), t1 = t2 = 1: w1, w2 = lo, hi
      4 two-sample KS, equal sizes (n, n, d)  w1 = P(D >= d)
      5 Poisson ratio CI  (k1, k2, t2) with t1 = 1e-300, level 0.95
      6 mean CI of x = (1e308, 1.2e308, 1.1e308) at level a: w1, w2
      7 pair-count variance (H, sqa, na) with S2 = H, P = 1e12, nb = 0."""
    rows = []
    N = 2**64 - 1
    q = mp.mpf(2)**-53
    p = 1 - q  # the double 1 - 2^-53
    # failures F = n - X ~ binomial(n, q): P(X <= k) = P(F >= n - k)
    for k in [N - 2000, N - 2048, N - 2100]:
        f = N - k
        ge = binom_le(f, N, q)           # P(X >= k) = P(F <= f)
        le = 1 - binom_le(f - 1, N, q)   # P(X <= k) = P(F >= f)
        rows.append((1, k, N, p, min(1, 2 * min(ge, le)), "nan"))
        rows.append((1, N - k, N, q, min(1, 2 * min(ge, le)), "nan"))
    for n in [2**54 + 1, N]:
        for k in [2, 3, 10]:
            for lv in ["0.95", "0.999999"]:
                lo, hi = cp_small(k, n, float(lv))
                rows.append((2, k, n, float(lv), lo, hi))
                rows.append((2, n - k, n, float(lv), 1 - hi, 1 - lo))
                rows.append((3, k, n - k, float(lv), lo / (1 - lo),
                             hi / (1 - hi)))
    for n, d in [(30000001, 9000 / 30000001), (30000001, 3e-4),
                 (10**13, 3e-7), (N, 1e-9)]:
        rows.append((4, n, n, d, ks2_equal_sum(n, d), "nan"))
    for k2, t2 in [(10**6, 1e10), (10**6, 1e300)]:
        lo, hi = cp_small(1, k2 + 1, 0.95)
        f = mp.mpf(t2) / mp.mpf(1e-300)
        rows.append((5, 1, k2, t2, f * lo / (1 - lo), f * hi / (1 - hi)))
    x = [mp.mpf(1e308), mp.mpf(1.2e308), mp.mpf(1.1e308)]
    m = sum(x) / 3
    sd = mp.sqrt(sum((v - m)**2 for v in x) / 2 / 3)
    for lv in [0.5, 0.95]:
        qq = (1 - mp.mpf(lv)) / 2
        # Student t with 2 degrees of freedom: Q(t) = (1 - t/sqrt(2+t^2))/2
        t = (1 - 2 * qq) * mp.sqrt(2 / (1 - (1 - 2 * qq)**2))
        rows.append((6, lv, 3, 0, m - t * sd, m + t * sd))
    for H, sqa, na in [(1e155, 1e306, 1e6), (1e160, 1.5e308, 1e15)]:
        H, sqa, na, P = mp.mpf(H), mp.mpf(sqa), mp.mpf(na), mp.mpf(1e12)
        v = sqa - 4 * H * H / na - H + H * H / P
        f = 1 - 4 / na + 1 / P
        rows.append((7, H, sqa, na, v / f, "nan"))
    write("stats_extreme.csv", "case,a,b,c,w1,w2", rows)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    what = sys.argv[2:] or ["intervals", "ks", "ks2", "misc", "kslarge"]
    if "misc" in what:
        gen_misc()
    if "ks2" in what:
        gen_ks2()
    if "intervals" in what:
        gen_intervals()
    if "ks" in what:
        gen_ks()
    if "kslarge" in what:
        gen_ks_large()
    if "extreme" in what:
        gen_extreme()
