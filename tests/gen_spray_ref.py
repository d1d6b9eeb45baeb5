#!/usr/bin/python3
"""Reference values for tests/test_spray.c, from first principles with mpmath.

Writes (into tests/data/):
  spray_bkw.csv    kind,x,K,value  kind 0: BKW density, 1: speed CDF (by
                   quadrature of 4 pi v^2 f), 4 and 6: moments E|v|^4, E|v|^6
                   (by quadrature), theta = 1.  Before writing, the script checks that BKW
                   solves the Boltzmann equation for isotropic Maxwell
                   scattering in Bobylev's Fourier form,
                     d phi/dt = lambda [ (1/2) int_{-1}^{1} phi(k sqrt((1+u)/2))
                                 phi(k sqrt((1-u)/2)) du - phi(k) ],
                   with phi(k) = exp(-K k^2/2) (1 - (1-K) k^2/2) and
                   dK/dt = lambda (1 - K)/6 (it aborts on a mismatch).
  spray_tab.csv    case,r,U,rho_g,rho_l,sigma,mu_l,Cd,y0,yd0,t,y,yd  TAB
                   equation y'' = (2/3)(rho_g/rho_l)U^2/r^2 - 8 sigma/(rho_l
                   r^3) y - Cd mu_l/(rho_l r^2) y' integrated by mpmath's
                   Taylor-series ODE solver (odefun); t = -1 rows give the
                   first time |y| = 1 (findroot on the ODE solution) in y.
  spray_reitz.csv  kind,a,U,rho_g,rho_l,sigma,mu_l,t,value  Reitz (1987)
                   fits (kind 0 Lambda, 1 Omega); kind 3: radius of the full model
                   da/dt = -(a - B0 Lambda(a)) Lambda(a) Omega(a)/(3.726 B1 a)
                   (B0 = 0.61, B1 = 10) by odefun; kind 2: the same with
                   Lambda, Omega fixed at a0.
  spray_twotemp.csv  na,nb,ma,mb,ra,rb,Ta0,Tb0,t,Ta  hard-sphere Maxwellian
                   closure dD/dt = -C D s(D) integrated by odefun.
  spray_extreme.csv  kind,a1,...,a8,value  closed forms at corners where a
                   double intermediate over/underflows but the value is a
                   normal double (arguments are exact doubles, written with
                   repr): kind 0 pair rate pi (r1 + r2)^2 g; 1 O'Rourke
                   b_cr^2/(r1 + r2)^2; 2 TAB r32; 3 Reitz blob radius; 4 BKW
                   density (theta as given); 5 BKW E|v|^6; 6 two-temperature
                   Maxwell T_a; 7 pgd delta mass rate; 8 pgd delta speed
                   (kinds 7, 8, 13, 14 are read by
                   tests/test_pgd_exact.c); 9
                   two-temperature hard-sphere T_a (r_a = r_b = a7, t =
                   a8, from the textbook form of the closed solution at
                   800 digits); 10 its rate dT_a/dt (r_a = r_b = a5);
                   11, 12 T_b of the Maxwell (as 6) and hard-sphere (as
                   9) laws, with a rare, much hotter species a (kinds 6
                   and 9 the same with a and b exchanged), then
                   hard-sphere rows with u0 far from sqrt(alpha) and
                   Maxwell rows with n T below the subnormals;
                   13, 14 pgd Riemann mass, momentum in [a, b] (rho_l,
                   u_l, rho_r, u_r, t, a, b; x0 = 0, no drag); 15 Reitz
                   full-model radius (a0, t, U, rho_g, rho_l, sigma, mu_l;
                   B0 = 0.61, B1 = 10) by odefun in scaled variables,
                   checked against the quadrature of dt = -da/rate;
                   16, 17 TAB y, y' (t, r, U, rho_g, mu_l, Cd, y0, y0';
                   rho_l = 1000, sigma = 0.072) in closed form, checked
                   against odefun in scaled variables; 18 TAB breakup time
                   (r, U, rho_g, mu_l, Cd, y0, y0', tmax); 19, 20 TAB
                   y, y' (arguments as 16, 17) heavily overdamped
                   (beta^2/w0^2 = 1e3 to 1e8) in the plain double
                   range, then overdamped rows for y' (beta/w0 = 1.5
                   to 1e4); 21, 22 two-temperature hard-sphere T_a, T_b
                   (arguments as 9) with n_a T_a0 or n_b T_b0 below
                   DBL_MIN while T_m is normal; 23, 24 two-temperature
                   Maxwell T_a, T_b (arguments as 6) with the rate
                   2 B0 n m_a m_b/(m_a + m_b)^2 below DBL_MIN.
Run: /usr/bin/python3 tests/gen_spray_ref.py   (about a minute)
"""
import os
import sys
from mpmath import mp, mpf, exp, sqrt, pi, quad, odefun, findroot, inf

mp.dps = 30
HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def s20(x):
    return mp.nstr(x, 20)


# ------------------------------------------------------------------ BKW
def bkw_pdf(v, K):
    v, K = mpf(v), mpf(K)
    return (2 * pi * K) ** mpf(-1.5) * exp(-v * v / (2 * K)) * (
        (5 * K - 3) / (2 * K) + (1 - K) * v * v / (2 * K * K))


def bkw_phi(k, K):
    return exp(-K * k * k / 2) * (1 - (1 - K) * k * k / 2)


def check_bkw():
    lam = mpf(1)
    for K in [mpf("0.6"), mpf("0.7"), mpf("0.9"), mpf("0.999")]:
        dK = lam * (1 - K) / 6
        for k in [mpf("0.3"), mpf(1), mpf(2), mpf("3.5")]:
            # d phi/dt = (d phi/dK) dK/dt
            dphi = mp.diff(lambda KK: bkw_phi(k, KK), K) * dK
            gain = quad(lambda u: bkw_phi(k * sqrt((1 + u) / 2), K) *
                        bkw_phi(k * sqrt((1 - u) / 2), K), [-1, 1]) / 2
            rhs = lam * (gain - bkw_phi(k, K))
            if abs(dphi - rhs) > mpf(10) ** -20:
                sys.exit("BKW is not a solution: K=%s k=%s %s %s" %
                         (K, k, dphi, rhs))
        # the Fourier transform of the density is phi
        for k in [mpf("0.5"), mpf(2)]:
            ft = quad(lambda v: 4 * pi * v * v * bkw_pdf(v, K) *
                      (mp.sin(k * v) / (k * v)), [0, inf])
            if abs(ft - bkw_phi(k, K)) > mpf(10) ** -20:
                sys.exit("BKW Fourier transform mismatch")


def write_bkw():
    rows = ["kind,x,K,value"]
    for K in ["0.6", "0.65", "0.8", "0.95", "1"]:
        Km = mpf(K)
        for v in ["0", "0.1", "1", "1.7320508075688772", "3", "6", "12"]:
            rows.append("0,%s,%s,%s" % (v, K, s20(bkw_pdf(v, Km))))
        for s in ["0.01", "0.5", "1", "2", "4", "8"]:
            c = quad(lambda x: 4 * pi * x * x * bkw_pdf(x, Km), [0, mpf(s)])
            rows.append("1,%s,%s,%s" % (s, K, s20(c)))
        for n, name in [(4, "4"), (6, "6")]:
            m = quad(lambda x: 4 * pi * x ** (2 + n) * bkw_pdf(x, Km),
                     [0, inf])
            rows.append("%s,0,%s,%s" % (name, K, s20(m)))
    return rows


# ------------------------------------------------------------------ TAB
TAB_CASES = [
    # r, U, rho_g, rho_l, sigma, mu_l, Cd, y0, yd0, tmax
    ("1e-4", "80", "1.2", "1000", "0.072", "1e-3", "5", "0", "0", "4e-4"),
    ("1e-4", "120", "1.2", "1000", "0.072", "1e-3", "5", "0.2", "-1000",
     "4e-4"),
    ("1e-4", "59", "1.2", "1000", "0.072", "0", "5", "0", "0", "4e-4"),
    ("5e-5", "150", "20", "700", "0.025", "2e-3", "10", "-0.3", "2000",
     "2e-4"),
    ("1e-5", "50", "1.2", "1000", "0.072", "0.5", "5", "0.5", "0", "1e-4"),
]


def tab_solve(c):
    r, U, rg, rl, sg, mu, Cd, y0, yd0, tmax = [mpf(x) for x in c]
    F = mpf(2) / 3 * rg / rl * U * U / (r * r)
    w02 = 8 * sg / (rl * r ** 3)
    b2 = Cd * mu / (rl * r * r)
    sol = odefun(lambda t, y: [y[1], F - w02 * y[0] - b2 * y[1]], 0,
                 [y0, yd0])
    return sol, tmax


def write_tab():
    rows = ["case,r,U,rho_g,rho_l,sigma,mu_l,Cd,y0,yd0,t,y,yd"]
    for i, c in enumerate(TAB_CASES):
        sol, tmax = tab_solve(c)
        pre = "%d,%s" % (i, ",".join(c[:9]))
        for f in [mpf("0.01"), mpf("0.1"), mpf("0.37"), mpf("0.8"), mpf(1)]:
            t = f * tmax
            y, yd = sol(t)
            rows.append("%s,%s,%s,%s" % (pre, s20(t), s20(y), s20(yd)))
        # first |y| = 1 on a fine scan, refined by findroot
        n = 4000
        prev = sol(mpf(0))[0]
        tb = None
        for j in range(1, n + 1):
            t = tmax * j / n
            y = sol(t)[0]
            for lev in (1, -1):
                if (prev - lev) * (y - lev) <= 0 and abs(prev) < 1:
                    g = lambda s, lev=lev: sol(s)[0] - lev
                    tb = findroot(g, (tmax * (j - 1) / n, t),
                                  solver="anderson")
                    break
            if tb is not None:
                break
            prev = y
        rows.append("%s,-1,%s,0" % (pre, s20(tb) if tb is not None
                                    else "inf"))
    return rows


# ------------------------------------------------------------------ Reitz
def wave(a, U, rg, rl, sg, mu):
    We = rg * U * U * a / sg
    Z = mu / sqrt(rl * a * sg)
    T = Z * sqrt(We)
    L = a * mpf("9.02") * (1 + mpf("0.45") * sqrt(Z)) * \
        (1 + mpf("0.4") * T ** mpf("0.7")) / \
        (1 + mpf("0.87") * We ** mpf("1.67")) ** mpf("0.6")
    O = (mpf("0.34") + mpf("0.38") * We ** mpf("1.5")) / \
        ((1 + Z) * (1 + mpf("1.4") * T ** mpf("0.6"))) * \
        sqrt(sg / (rl * a ** 3))
    return L, O


REITZ_CASES = [
    # a, U, rho_g, rho_l, sigma, mu_l
    ("5e-5", "100", "10", "1000", "0.072", "1e-3"),
    ("2e-5", "300", "20", "700", "0.025", "3e-3"),
    ("1e-4", "50", "1.2", "1000", "0.072", "0"),
]


def write_reitz():
    B0, B1 = mpf("0.61"), mpf(10)
    rows = ["kind,a,U,rho_g,rho_l,sigma,mu_l,t,value"]
    for c in REITZ_CASES:
        a0, U, rg, rl, sg, mu = [mpf(x) for x in c]
        L, O = wave(a0, U, rg, rl, sg, mu)
        pre = ",".join(c)
        rows.append("0,%s,0,%s" % (pre, s20(L)))
        rows.append("1,%s,0,%s" % (pre, s20(O)))
        tau = mpf("3.726") * B1 * a0 / (L * O)
        R0 = B0 * L
        if a0 <= R0:
            continue
        c0 = L * O / (mpf("3.726") * B1)
        frozen = odefun(lambda t, a: -c0 * (a - R0) / a, 0, a0)

        def full_rhs(t, a):
            LL, OO = wave(a, U, rg, rl, sg, mu)
            return -(a - B0 * LL) * LL * OO / (mpf("3.726") * B1 * a)
        full = odefun(full_rhs, 0, a0)
        for f in ["0.1", "0.5", "1", "2", "5"]:
            t = mpf(f) * tau
            rows.append("2,%s,%s,%s" % (pre, s20(t), s20(frozen(t))))
            rows.append("3,%s,%s,%s" % (pre, s20(t), s20(full(t))))
    return rows


# ------------------------------------------------------------ two-temp
KB = mpf("1.380649e-23")
TT_CASES = [
    # na, nb, ma, mb, ra, rb, Ta0, Tb0
    ("1e9", "1e9", "4.1887902047863905e-12", "8.377580409572781e-12",
     "1e-5", "1.2599210498948732e-5", "6.0e11", "3.0e11"),
    ("2e9", "5e8", "1e-12", "1e-11", "2e-5", "5e-6", "1e11", "5e11"),
]


def write_twotemp():
    rows = ["na,nb,ma,mb,ra,rb,Ta0,Tb0,t,Ta"]
    for c in TT_CASES:
        na, nb, ma, mb, ra, rb, Ta0, Tb0 = [mpf(x) for x in c]
        n = na + nb
        M = ma + mb
        d = ra + rb
        C = mpf(16) / 3 * sqrt(2 / pi) * pi * d * d * n * ma * mb / (M * M)
        Tm = (na * Ta0 + nb * Tb0) / n

        def rhs(t, D):
            Ta = Tm + nb / n * D
            Tb = Tm - na / n * D
            return -C * D * sqrt(KB * (Ta / ma + Tb / mb))
        D0 = Ta0 - Tb0
        sol = odefun(rhs, 0, D0)
        rate = abs(rhs(0, D0) / D0)
        for f in ["0.1", "1", "3", "10"]:
            t = mpf(f) / rate
            D = sol(t)
            rows.append("%s,%s,%s" % (",".join(c), s20(t),
                                      s20(Tm + nb / n * D)))
    return rows


# kind, arguments (exact doubles; unused columns 0)
EXTREME = [
    (0, [1e160, 1e160, 1e-100]),
    (0, [1e-170, 1e-170, 1e100]),
    (1, [1e-300, 1e-300, 1e200, 1000.0, 0.072]),
    (1, [1e-100, 1e10, 1e200, 1000.0, 1e-100]),
    (2, [1e-200, 1e300, 1000.0, 0.072]),
    (3, [1e300, 1e-100, 1e250, 1e10]),
    (4, [3.7e-99, 0.8, 1e-200]),
    (5, [0.8, 1e-103]),
    (6, [1e20, 2e20, 1e-300, 5e-26, 300.0, 500.0, 1e-16, 1e270]),
    (7, [1e-320, 1e300, 1e-320, -1e300]),
    (8, [4.0, 1.7976931348623157e308, 1.0, -1e308]),
]
# two-temperature hard spheres: kind 9 T_a(t) (n_a, n_b, m_a, m_b, T_a0,
# T_b0, r_a = r_b, t), kind 10 the rate dT_a/dt (n_a, n_b, m_a, m_b,
# r_a = r_b, T_a, T_b); t = None: the time 1/(C sqrt(alpha)), rounded to
# a double, so that most rows are in the middle of the relaxation
DBL_MAX = sys.float_info.max
TT_BASE = [1e20, 2e20, 3e-26, 5e-26, 300.0, 500.0, 1e-10, None]
TT_EXT = [(0, 1e300), (0, DBL_MAX), (1, 1e300), (1, DBL_MAX),
          (2, 1e-320), (2, 1e-300), (3, 1e-320), (3, 1e-300),
          (4, 1e300), (4, DBL_MAX), (5, 1e300), (5, DBL_MAX),
          (2, 1e300, 3, 1e300), (2, DBL_MAX, 3, DBL_MAX),
          (2, 1e-320, 3, 1e-320), (4, 1e300, 5, 1e-300),
          (4, 1e-300, 5, 1e300), (0, 1e-300, 4, 1e300),
          (6, 1e300, 7, 0.0), (6, 1e-300, 7, 1e300),
          (0, 1e270, 1, 1e-90, 4, 1e-250, 5, 1e200),
          (0, 6e135, 1, 8e296, 2, 1e146, 3, 2e273, 4, 1e-38, 5, 1e-297,
           6, 1e25, 7, 0.0),
          (0, 6e135, 1, 8e296, 2, 1e146, 3, 2e273, 4, 1e-38, 5, 1e-297,
           6, 1e25),
          (0, 3e14, 1, 2e12, 2, 7e-247, 3, 3e-112, 4, 3.6e-168, 5, 3.7e-35,
           6, 7e66, 7, 1.8e-127)]
for e in TT_EXT:
    a = list(TT_BASE)
    for k in range(0, len(e), 2):
        a[e[k]] = e[k + 1]
    EXTREME.append((9, a))
RATE_BASE = [1e20, 2e20, 3e-26, 5e-26, 1e-10, 350.0, 450.0]
for e in [(2, 1e-320), (3, 1e-320), (2, 1e-320, 3, 1e-320),
          (5, 1e300, 4, 1e-200), (6, 1e300, 4, 1e-200),
          (0, DBL_MAX, 5, 1e300, 4, 1e-200), (0, 1e300, 1, 1e-100)]:
    a = list(RATE_BASE)
    for k in range(0, len(e), 2):
        a[e[k]] = e[k + 1]
    EXTREME.append((10, a))

# a rare, much hotter species (f_hot T_hot0/T_cold0 = 1e15): the colder
# species' T as T_m - f |Delta| cancels (before, a wrong or negative T_b
# with status 0).  Kinds 11 and 12: T_b of the Maxwell (arguments as kind
# 6) and hard-sphere (as kind 9) laws; kinds 6 and 9 the same with the
# roles of a and b exchanged (T_a the colder species).  Times: the given
# multiples of the relaxation time (1/rate, 1/(C sqrt(alpha))), rounded
# to doubles.
TT_COLD_FACTORS = [0.0, 1e-18, 1e-15, 1e-12, 1e-6, 1.0]
TT_COLD = []
for f in TT_COLD_FACTORS:
    TT_COLD.append((11, [1e17, 1e20, 3e-26, 5e-26, 1e6, 1e-12, 1e-16, f]))
    TT_COLD.append((6, [1e20, 1e17, 5e-26, 3e-26, 1e-12, 1e6, 1e-16, f]))
for f in TT_COLD_FACTORS:
    TT_COLD.append((12, [1e17, 1e20, 3e-26, 5e-26, 1e6, 1e-12, 1e-10, f]))
    TT_COLD.append((9, [1e20, 1e17, 5e-26, 3e-26, 1e-12, 1e6, 1e-10, f]))

# hard spheres where u0 = sqrt(alpha + beta Delta0) is far from
# sqrt(alpha): a rare hotter species (n_a/n_b = 1e-9, u0 >> sqrt(alpha):
# 1 - rho cancelled in the hotter T_a) and a heavy hot species with a
# light cold one (m_a/m_b = 1e10, u0 << sqrt(alpha): alpha + beta Delta0
# cancelled, T_b); kind 9 T_a, 12 T_b.
for f in [1e-6, 1e-3, 1.0]:
    TT_COLD.append((9, [1e14, 1e23, 3e-26, 5e-26, 1e6, 1e-12, 1e-10, f]))
for f in [1e-3, 1.0, 1e3]:
    TT_COLD.append((12, [1e20, 1e20, 1e-20, 1e-30, 300.0, 1e-3, 1e-10, f]))
    TT_COLD.append((9, [1e20, 1e20, 1e-20, 1e-30, 300.0, 1e-3, 1e-10, f]))

# Maxwell law with n_a T_a0 and n_b T_b0 below the subnormals (n = 1e-200,
# T = 1e-150): the mixture temperature T_m underflowed to 0 (before, T_b
# relaxed towards 0); kind 6 T_a, 11 T_b.
for f in [0.0, 1.0, 10.0]:
    TT_COLD.append((6, [1e-200, 1e-200, 3e-26, 5e-26, 1e-150, 3e-150, 1e-16,
                        f]))
    TT_COLD.append((11, [1e-200, 1e-200, 3e-26, 5e-26, 1e-150, 3e-150,
                         1e-16, f]))

# hard spheres with n_a T_a0 (and n_b T_b0) below DBL_MIN while T_m and
# every other intermediate of the plain form is normal (r = 1e150, so
# that C is normal): a product near 1e-318 keeps about 10 bits (T_m,
# alpha, e and u0/sqrt(alpha) lost them); kinds 21 T_a, 22 T_b.
for f in [0.1, 1.0, 10.0]:
    for a in [[3e-307, 7e-307, 3e-26, 5e-26, 1.3e-11, 2.9e-12, 1e150],
              [2e-310, 1e-300, 3e-26, 5e-26, 1.234567e-8, 3.3e-20, 1e150]]:
        TT_COLD.append((21, a + [f]))
        TT_COLD.append((22, a + [f]))

# Maxwell law with the rate below DBL_MIN (n = 2e-297 or 2e-300, B0 =
# 1e-16: 9e-314, 9e-317), where rate t is at most ~2e-5 (t <= DBL_MAX):
# the subnormal rate kept 24 or 34 bits, and the colder species, far
# below T_m, takes f |Delta0| (1 - e) from them; kinds 23 T_a, 24 T_b
# (a the hotter species in the first rows, the colder in the last).
for a, fs in [([1e-300, 1e-300, 3e-26, 5e-26, 1e6, 1e-12, 1e-16],
               [1e-10, 1e-8]),
              ([1e-297, 1e-297, 3e-26, 5e-26, 1e6, 1e-12, 1e-16],
               [1e-7, 1e-5]),
              ([1e-297, 1e-297, 5e-26, 3e-26, 1e-12, 1e6, 1e-16],
               [1e-7, 1e-5])]:
    for f in fs:
        TT_COLD.append((23, a + [f]))
        TT_COLD.append((24, a + [f]))


def tt_cold_time(kind, a):
    """a[7] (a multiple of the relaxation time) -> t as a double."""
    with mp.workdps(60):
        x = [mpf(v) for v in a]
        if kind in (6, 11, 23, 24):
            na, nb, ma, mb = x[:4]
            rate = 2 * x[6] * (na + nb) * ma * mb / (ma + mb) ** 2
        else:
            C, alpha = tt_hs_parts(*x[:7])[:2]
            rate = C * sqrt(alpha)
        return a[:7] + [float(x[7] / rate)]


def tt_maxwell_T(a, species):
    """T_a (species 0) or T_b (1) of the Maxwell law, at 100 digits."""
    with mp.workdps(100):
        na, nb, ma, mb, Ta0, Tb0, B0, t = [mpf(x) for x in a]
        n = na + nb
        rate = 2 * B0 * n * ma * mb / (ma + mb) ** 2
        Tm = (na * Ta0 + nb * Tb0) / n
        D = (Ta0 - Tb0) * exp(-rate * t)
        return +(Tm + nb / n * D if species == 0 else Tm - na / n * D)


def tt_hs_parts(na, nb, ma, mb, Ta0, Tb0, r, kb=KB):
    """C, alpha, beta, D0, T_m and n_b/n of the hard-sphere closure
    dD/dt = -C D sqrt(alpha + beta D) (mpmath numbers; kb Boltzmann's
    constant)."""
    n = na + nb
    d = 2 * r
    C = mpf(16) / 3 * sqrt(2 / pi) * pi * d * d * n * ma * mb / (ma + mb) ** 2
    Tm = (na * Ta0 + nb * Tb0) / n
    alpha = kb * Tm * (1 / ma + 1 / mb)
    beta = kb * (nb / ma - na / mb) / n
    return C, alpha, beta, Ta0 - Tb0, Tm, nb / n


def tt_hs_time(a):
    """t = 1/(C sqrt(alpha)), as a double, where a[7] is None."""
    if a[7] is not None:
        return a
    with mp.workdps(60):
        C, alpha = tt_hs_parts(*[mpf(x) for x in a[:7]])[:2]
        return a[:7] + [float(1 / (C * sqrt(alpha)))]


def tt_hs_Ta(a, kb=KB):
    """T_a(t) from the textbook solution: with u^2 = alpha + beta D,
    (u - sqrt(alpha))/(u + sqrt(alpha)) = rho0 exp(-C sqrt(alpha) t),
    D = 4 alpha rho/(beta (1 - rho)^2) (D0 exp(-C sqrt(alpha) t) for
    beta = 0), at 800 digits (rho0 may be 1 - 1e-600)."""
    with mp.workdps(800):
        na, nb, ma, mb, Ta0, Tb0, r, t = [mpf(x) for x in a]
        C, alpha, beta, D0, Tm, fb = tt_hs_parts(na, nb, ma, mb, Ta0, Tb0, r,
                                                 kb)
        sa = sqrt(alpha)
        e = exp(-C * sa * t)
        if beta == 0:
            D = D0 * e
        else:
            u0 = sqrt(alpha + beta * D0)
            rho = (u0 - sa) / (u0 + sa) * e
            D = 4 * alpha * rho / (beta * (1 - rho) ** 2)
        return +(Tm + fb * D)


def tt_hs_Tb(a, kb=KB):
    """T_b(t) = T_a(t) - Delta(t), from the same solution."""
    with mp.workdps(800):
        na, nb, ma, mb, Ta0, Tb0, r, t = [mpf(x) for x in a]
        Ta = tt_hs_Ta(a, kb)
        return +(Ta - (Ta - (na * Ta0 + nb * Tb0) / (na + nb)) *
                 (na + nb) / nb)


def tt_hs_rate(a):
    """dT_a/dt = -C (n_b/n) s (T_a - T_b), s^2 = k (T_a/m_a + T_b/m_b)."""
    na, nb, ma, mb, r, Ta, Tb = a
    C = tt_hs_parts(na, nb, ma, mb, Ta, Tb, r)[0]
    return -C * nb / (na + nb) * sqrt(KB * (Ta / ma + Tb / mb)) * (Ta - Tb)


# pgd Riemann integral (x0 = 0, no drag), kinds 13 mass, 14 momentum:
# rho u length overflows, b - a overflows, rho u underflows
RIEMANN_EXTREME = [
    (13, [1e200, 1e200, 1e200, 1e200, 1e-300, -1e-200, 1e-200]),
    (14, [1e200, 1e200, 1e200, 1e200, 1e-300, -1e-200, 1e-200]),
    (13, [1e-10, 2.0, 0.0, 1.0, 8e307, -1e308, 1.5e308]),
    (14, [1e-10, 2.0, 0.0, 1.0, 8e307, -1e308, 1.5e308]),
    (13, [1e-200, -1e-200, 3e-200, 1e-200, 1.0, -1e200, 1e200]),
    (14, [1e-200, -1e-200, 3e-200, 1e-200, 1.0, -1e200, 1e200]),
]
# wave positions beyond DBL_MAX (|u| t > 1e308) outside [a, b], which they
# only clamp: vacuum (x_r ~ 1e310), contacts (x ~ +-1e600), a delta at
# ~ -3e309 whose mass (~4e310) is beyond DBL_MAX too; a delta at ~5e9
# with a mass of ~1e310 outside [a, b]; a delta inside [a, b] whose mass
# rate (2e310) overflows while the mass (2e290) does not
for r in ([2.0, 5.0, 3.0, 1e300, 1e10, -1e10, 1e10],
          [3.0, 1e300, 0.0, 0.0, 1e300, -5.0, 7.0],
          [0.0, 0.0, 0.5, -1e300, 1e300, -5.0, 7.0],
          [1.0, 1e300, 4.0, -1e300, 1e10, 0.0, 1.0],
          [1e300, 1e10, 1e300, -1.0, 1.0, 1e10, 1e10 + 0.5]):
    RIEMANN_EXTREME += [(13, r), (14, r)]
RIEMANN_EXTREME.append((13, [1e300, 1e10, 1e300, -1e10, 1e-20, -1.0, 1.0]))


# Reitz full-model radius (kind 15) where the plain fits leave the range
# (a^3 underflows, We^1.67 overflows, a^3 overflows): (a0, U, rho_g,
# rho_l, sigma, mu_l) at t = f tau(a0) rounded to a double
REITZ_EXTREME = [
    (("1e-150", "1e80", "10", "1000", "0.072", "0"), ["0.5"]),
    (("1e-4", "1e100", "1.2", "1000", "0.072", "1e-3"), ["0.5"]),
    (("1e120", "1", "1.2", "1000", "0.072", "1e-3"), ["0.5"]),
]


# TAB at corners (kinds 16 y, 17 y', 18 breakup time; rho_l = 1000,
# sigma = 0.072): r ~ 1e-100 (beta^2 overflows), r ~ 1e103 (r^3
# overflows), y0 or y0' near DBL_MAX.  16, 17: t, r, U, rho_g, mu_l, Cd,
# y0, y0'; 18: r, U, rho_g, mu_l, Cd, y0, y0', tmax.
TAB_EXTREME = [
    [1e-194, 1e-100, 50.0, 1.2, 1e-3, 5.0, 0.1, 20.0],
    [1e-102, 1e-100, 50.0, 1.2, 1e-3, 5.0, 0.1, 20.0],
    [1e154, 1e103, 1e-52, 1.2, 1e-3, 5.0, 0.1, 1e-160],
    [1e-12, 1e-4, 50.0, 1.2, 1e-3, 5.0, 1e308, 0.0],
    [1e-5, 1e-4, 50.0, 1.2, 1e-3, 5.0, 0.1, -1e308],
    # y << y_eq = We/12 at t << 1/w0 (y_eq + z cancelled): underdamped,
    # heavily overdamped, and y0 ~ -1e-13 (ulp_spray.py, 1e13 ulp before)
    [1e-9, 1e-4, 50.0, 1.2, 1e-3, 5.0, 0.0, 1e-3],
    [1e-10, 1e-6, 50.0, 1.2, 0.1, 5.0, 0.0, 1e-3],
    [5.527545495057997e-12, 1.1930638517458016e-05, 46.207994046804735, 1.2,
     0.056405058012653185, 5.0, -2.2977937136290926e-13,
     0.009254831758485611],
]
TAB_TB_EXTREME = [
    [1e103, 1e-49, 1.2, 1e-3, 5.0, 0.1, 0.0, 1e160],
]
# TAB heavily overdamped with every scale a normal double (kinds 19 y,
# 20 y'; arguments as 16, 17): beta^2/w0^2 = Cd^2 mu_l^2/(32 rho_l sigma
# r) = 1e3 to 1e8, t of order 1/|k - beta|, where the slow rate k - beta
# cancels (relative error ~ DBL_EPSILON beta^2/w0^2)
TAB_OVERDAMPED = [
    [1e-9, 1e-10, 50.0, 1.2, 1.0, 5.0, 0.1, 20.0],
    [3e-9, 1e-10, 50.0, 1.2, 1.0, 5.0, -0.3, -1e3],
    [2e-5, 1e-7, 50.0, 1.2, 10.0, 10.0, 0.1, 20.0],
    [1e-4, 1e-5, 50.0, 1.2, 1.0, 5.0, 0.1, 20.0],
    # y' where the free response of the rate, y0' e^{-bt}(C - b S), is
    # all of it (U = 0, y0 = 0): C - b S as e^{-bt} C - b e^{-bt} S
    # cancelled by ~(b/w0)^2 (y' wrong in the ninth and the thirteenth
    # digit); and at small kt (2kt < 1e-4, y0 = 0), where e^{-bt}
    # sinh(kt)/k as (e^{(k-b)t} - e^{-(k+b)t})/(2k) cancelled (y' wrong
    # in the thirteenth digit, ulp_spray.py 'tab y~0')
    [1e-9, 1e-10, 0.0, 1.2, 1.0, 5.0, 0.0, 1.0],
    [1e-4, 1e-5, 0.0, 1.2, 1.0, 5.0, 0.0, 1.0],
    [1e-11, 1e-5, 50.0, 1.2, 0.1, 5.0, 0.0, 1e-3],
    [2e-11, 1.2e-5, 50.0, 1.2, 0.05, 5.0, 0.0, -1e-4],
]


def tab_oscillator(r, U, rg, mu, Cd, sg):
    """w0^2 = 8 sigma/(rho_l r^3), beta = 1/t_d = Cd mu_l/(2 rho_l r^2) and
    y_eq = We/12 of the TAB equation (spray_tab.csv), rho_l = 1000, at
    the current precision (mpmath arguments)."""
    rl = mpf(1000)
    w02 = 8 * sg / (rl * r ** 3)
    b = Cd * mu / (2 * rl * r * r)
    yeq = mpf(2) / 3 * rg / rl * U * U / (r * r) / w02
    return w02, b, yeq


def tab_free(w02, b, t):
    """e^{-beta t}, C(t) = cos wt and S(t) = sin(wt)/w, w^2 = w0^2 -
    beta^2 (complex w: cosh and sinh overdamped; C, S have zero imaginary
    part)."""
    w = mp.sqrt(mp.mpc(w02 - b * b))
    return exp(-b * t), mp.cos(w * t), mp.sin(w * t) / w


def tab_closed_form(t, r, U, rg, mu, Cd, y0, yd0, sg):
    """y(t), y'(t) of the TAB equation in closed form at the current
    precision (arguments converted exactly; sg the surface tension):
    y = y_eq + e^{-beta t}[z0 C + (y0' + beta z0) S],
    y' = e^{-beta t}[y0' C - (beta y0' + w0^2 z0) S], z0 = y0 - y_eq."""
    t, r, U, rg, mu, Cd, y0, yd0 = [mpf(x) for x in
                                     (t, r, U, rg, mu, Cd, y0, yd0)]
    w02, b, yeq = tab_oscillator(r, U, rg, mu, Cd, mpf(sg))
    z0 = y0 - yeq
    e, C, S = tab_free(w02, b, t)
    y = mp.re(yeq + e * (z0 * C + (yd0 + b * z0) * S))
    yd = mp.re(e * (yd0 * C - (b * yd0 + w02 * z0) * S))
    return y, yd


def tab_closed(t, r, U, rg, mu, Cd, y0, yd0):
    """y(t), y'(t) of the TAB equation (spray_tab.csv) in closed form at
    250 digits (the overdamped slow rate cancels to ~100 digits at r =
    1e-100), sigma = 0.072.  Where t max(beta, w0) <= 100 it is checked
    against odefun in the variables s = t max(beta, w0), z/A."""
    with mp.workdps(250):
        y, yd = tab_closed_form(t, r, U, rg, mu, Cd, y0, yd0, mpf("0.072"))
        t, r, U, rg, mu, Cd, y0, yd0 = [mpf(x) for x in
                                         (t, r, U, rg, mu, Cd, y0, yd0)]
        w02, b, yeq = tab_oscillator(r, U, rg, mu, Cd, mpf("0.072"))
        z0 = y0 - yeq
        Om = max(b, sqrt(w02))
        if t * Om <= 100:
            A = max(abs(z0), abs(yd0) / Om)
            B, W = b / Om, w02 / Om ** 2
            with mp.workdps(30):
                sol = odefun(lambda s_, u: [u[1], -W * u[0] - 2 * B * u[1]],
                             0, [z0 / A, yd0 / (Om * A)])
                u = sol(t * Om)
            for got, ref in ((yeq + A * u[0], y), (A * Om * u[1], yd)):
                if abs(got - ref) > mpf(10) ** -20 * (abs(ref) + A * 1e-5):
                    sys.exit("TAB closed form vs odefun: %s %s" % (got, ref))
        return y, yd


def tab_tb(r, U, rg, mu, Cd, y0, yd0, tmax):
    """First |y| = 1 in (0, tmax] of tab_closed: a scan of 4000 points,
    then findroot (the rows have y rising through 1)."""
    f = lambda t: tab_closed(t, r, U, rg, mu, Cd, y0, yd0)[0]
    tmax = mpf(tmax)
    prev = mpf(0)
    for j in range(1, 4001):
        t = tmax * j / 4000
        if f(t) >= 1:
            return findroot(lambda x: f(x) - 1, (prev, t),
                            solver="anderson")
        prev = t
    return mpf("inf")


def reitz_radius_scaled(a0, t, U, rg, rl, sg, mu):
    """Full Reitz model a(t) (B0 = 0.61, B1 = 10) by odefun in the
    variables y = a/a0, s = t/tau(a0) (odefun's tolerance is absolute),
    checked against s = int_y^1 dy'/(tau0/a0 rate(a0 y')) by quad."""
    B0, B1, C = mpf("0.61"), mpf(10), mpf("3.726")
    L0, O0 = wave(a0, U, rg, rl, sg, mu)
    if a0 <= B0 * L0 or t == 0:
        return a0
    tau0 = C * B1 * a0 / (L0 * O0)

    def rate(a):  # -da/dt
        LL, OO = wave(a, U, rg, rl, sg, mu)
        return (a - B0 * LL) * LL * OO / (C * B1 * a)
    s = t / tau0
    sol = odefun(lambda s_, y: -tau0 / a0 * rate(a0 * y), 0, mpf(1))
    y = mp.re(sol(s))
    # (quad's tolerance is absolute too: integrate in y)
    back = quad(lambda u: a0 / (tau0 * rate(a0 * u)), [y, 1])
    if abs(back / s - 1) > mpf(10) ** -25:
        sys.exit("Reitz radius: odefun and quad disagree (%s)" % (back / s))
    return a0 * y


def riemann_integral(rl, ul, rr, ur, t, a, b):
    """Mass and momentum in [a, b] of the drag-free Riemann problem at
    x0 = 0 (contact, vacuum or delta-shock; docs/pgd.md)."""
    dm = dq = mpf(0)
    if rl == 0 and rr == 0:
        xl = xr = mpf(0)
    elif rl == 0 or rr == 0 or ul == ur:
        xl = xr = (ul if rl > 0 else ur) * t
    elif ul < ur:
        xl, xr = ul * t, ur * t
    else:
        sig = (sqrt(rl) * ul + sqrt(rr) * ur) / (sqrt(rl) + sqrt(rr))
        xl = xr = sig * t
        if a <= xl < b:
            dm = sqrt(rl * rr) * (ul - ur) * t
            dq = dm * sig
    ll = max(mpf(0), min(b, xl) - a)
    lr = max(mpf(0), b - max(a, xr))
    return (rl * ll + rr * lr + dm, rl * ul * ll + rr * ur * lr + dq)


def extreme_value(kind, a):
    a = [mpf(x) for x in a]  # exact binary values
    if kind == 0:
        return pi * (a[0] + a[1]) ** 2 * a[2]
    if kind == 1:
        r1, r2, g, rho, sg = a[:5]
        rs = min(r1, r2)
        gam = max(r1, r2) / rs
        f = gam ** 3 - mpf("2.4") * gam ** 2 + mpf("2.7") * gam
        return min(mpf(1), mpf("2.4") * f * sg / (rho * g * g * rs))
    if kind == 2:
        r, yd, rho, sg = a[:4]
        return r / (mpf(7) / 3 + rho * r ** 3 * yd ** 2 / (8 * sg))
    if kind == 3:
        A, U, L, O = a[:4]
        return min(mp.cbrt(3 * pi * A * A * U / (2 * O)),
                   mp.cbrt(mpf(3) / 4 * A * A * L))
    if kind == 4:
        v, K, th = a[:3]
        kt = K * th
        x = v * v / (2 * kt)
        return (2 * pi * kt) ** mpf(-1.5) * exp(-x) * (
            (5 * K - 3) / (2 * K) + (1 - K) / K * x)
    if kind == 5:
        K, th = a[:2]
        return th ** 3 * K * K * (315 - 210 * K)
    if kind == 6:
        return tt_maxwell_T(a, 0)
    if kind == 7:
        return sqrt(a[0]) * sqrt(a[2]) * (a[1] - a[3])
    if kind == 8:
        return (sqrt(a[0]) * a[1] + sqrt(a[2]) * a[3]) / (sqrt(a[0]) +
                                                         sqrt(a[2]))
    if kind == 9:
        return tt_hs_Ta(a)
    if kind == 10:
        return tt_hs_rate(a)
    if kind == 11:
        return tt_maxwell_T(a, 1)
    if kind == 12:
        return tt_hs_Tb(a)
    if kind in (13, 14):
        return riemann_integral(*a[:7])[kind - 13]
    if kind == 15:
        return reitz_radius_scaled(*a[:7])
    if kind in (16, 17):
        return tab_closed(*a)[kind - 16]
    if kind == 18:
        return tab_tb(*a)
    if kind in (19, 20):
        return tab_closed(*a)[kind - 19]
    if kind == 21:
        return tt_hs_Ta(a)
    if kind == 22:
        return tt_hs_Tb(a)
    if kind in (23, 24):
        return tt_maxwell_T(a, kind - 23)
    raise ValueError(kind)


def write_extreme():
    rows = ["kind,a1,a2,a3,a4,a5,a6,a7,a8,value"]
    B1, C = mpf(10), mpf("3.726")
    rows_in = EXTREME + [(k, tt_cold_time(k, a)) for k, a in TT_COLD]
    rows_in += RIEMANN_EXTREME
    for c, fs in REITZ_EXTREME:
        a0, U, rg, rl, sg, mu = [mpf(x) for x in c]
        L0, O0 = wave(a0, U, rg, rl, sg, mu)
        for f in fs:
            t = float(mpf(f) * C * B1 * a0 / (L0 * O0))
            rows_in.append((15, [float(a0), t] + [float(x) for x in c[1:]]))
    for a in TAB_EXTREME:
        rows_in += [(16, a), (17, a)]
    rows_in += [(18, a) for a in TAB_TB_EXTREME]
    for a in TAB_OVERDAMPED:
        rows_in += [(19, a), (20, a)]
    for kind, a in rows_in:
        if kind == 9:
            a = tt_hs_time(a)
        args = [repr(float(x)) for x in a] + ["0"] * (8 - len(a))
        rows.append("%d,%s,%s" % (kind, ",".join(args),
                                  s20(extreme_value(kind, a))))
    return rows


def main():
    check_bkw()
    for name, fn in [("spray_bkw.csv", write_bkw), ("spray_tab.csv", write_tab),
                     ("spray_reitz.csv", write_reitz),
                     ("spray_twotemp.csv", write_twotemp),
                     ("spray_extreme.csv", write_extreme)]:
        rows = fn()
        with open(os.path.join(HERE, name), "w") as f:
            f.write("\n".join(rows) + "\n")
        print("wrote", name, len(rows) - 1, "rows")


if __name__ == "__main__":
    main()
