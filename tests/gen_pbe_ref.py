#!/usr/bin/python3
"""Reference values of the analytic Smoluchowski solutions (tests/test_pbe.c).

Writes tests/data/pbe_analytic.csv: kind,k_or_x,tau,logn with logn =
log(n/N0) computed with mpmath at 50 digits directly from the defining
products (factorials as exact integers, Bessel I1 by mpmath), so large k
that underflow in double precision are covered; the inputs are the
binary doubles the test reads (mpf(float(...))).  Kinds: const_mono,
add_mono, mult_mono (k integer), const_exp, add_exp (x = v/v0).
Run: /usr/bin/python3 tests/gen_pbe_ref.py > tests/data/pbe_analytic.csv
"""
import sys

from mpmath import mp, mpf, log, exp, factorial, besseli, sqrt, expm1

mp.dps = 50


def const_mono(k, tau):
    t = mpf(tau) / 2
    return log(t ** (k - 1) / (1 + t) ** (k + 1))


def add_mono(k, tau):
    phi = -expm1(-mpf(tau))
    return log((1 - phi) * (k * phi) ** (k - 1) * exp(-k * phi) / factorial(k))


def mult_mono(k, tau):
    tau = mpf(tau)
    return log(mpf(k) ** (k - 3) * tau ** (k - 1) * exp(-k * tau) / factorial(k - 1))


def const_exp(x, tau):
    s = 1 + mpf(tau) / 2
    return log(exp(-mpf(x) / s) / s ** 2)


def add_exp(x, tau):
    x = mpf(x)
    T = -expm1(-mpf(tau))
    return log((1 - T) * exp(-(1 + T) * x) * besseli(1, 2 * x * sqrt(T)) / (x * sqrt(T)))


print("kind,a,tau,logn")
for k in [1, 2, 3, 7, 50, 400, 10000, 1000000, 10 ** 9, 10 ** 15]:
    for tau in ["0.001", "0.1", "1", "10", "1000", "1e300"]:
        print("const_mono,%d,%s,%s" % (k, tau, mp.nstr(const_mono(k, mpf(float(tau))), 25)))
    for tau in ["0.001", "0.1", "1", "10", "30"]:
        print("add_mono,%d,%s,%s" % (k, tau, mp.nstr(add_mono(k, mpf(float(tau))), 25)))
    for tau in ["0.001", "0.1", "0.5", "0.9", "0.999", "0.999999"]:
        print("mult_mono,%d,%s,%s" % (k, tau, mp.nstr(mult_mono(k, mpf(float(tau))), 25)))
for x in ["1e-6", "0.01", "1", "10", "300", "1e5"]:
    for tau in ["0", "0.1", "1", "10", "1000"]:
        print("const_exp,%s,%s,%s" % (x, tau, mp.nstr(const_exp(mpf(float(x)), mpf(float(tau))), 25)))
    for tau in ["1e-12", "0.1", "1", "10"]:
        print("add_exp,%s,%s,%s" % (x, tau, mp.nstr(add_exp(mpf(float(x)), mpf(float(tau))), 25)))
# multiplicative kernel at small tau: tau - 1 rounds away tau's bits (and
# is -1 below 2^-54, outside GSL's log_1plusx_mx)
for k in [2, 7, 400, 10 ** 9]:
    for tau in ["0.05", "1e-10", "1e-20", "1e-300"]:
        print("mult_mono,%d,%s,%s" % (k, tau, mp.nstr(mult_mono(k, mpf(float(tau))), 25)))
# additive kernel, exponential start, at x near DBL_MAX: 2 x sqrt(T)
# overflows (inf * 0 at tau = 0 gave NaN)
for (x, tau) in [(1e300, "1"), (sys.float_info.max, "1"),
                 (sys.float_info.max, "1e-300"), (sys.float_info.max, "1e-20")]:
    print("add_exp,%r,%s,%s" % (x, tau, mp.nstr(add_exp(mpf(x), mpf(float(tau))), 25)))
# additive kernel, monodisperse, at k ~ 1e308 and tau in ~[0.1, 0.7]:
# (k-1) log phi leaves the doubles while log n ~ -0.2 k ... -1.5 k does not
# (it was -inf with status 0); k are the doubles 1e308 and DBL_MAX
for (k, tau) in [(1e308, "0.1"), (1e308, "0.3"), (sys.float_info.max, "0.2"),
                 (sys.float_info.max, "0.3"), (sys.float_info.max, "0.45")]:
    print("add_mono,%r,%s,%s" % (k, tau, mp.nstr(add_mono(int(k), mpf(float(tau))), 25)))
# constant kernel, monodisperse, at subnormal tau: 2/tau overflows (log1p
# of it was inf, log n -inf with status 0 although it is a double)
for (k, tau) in [(2.0, 1e-320), (7.0, 1e-320), (1e150, 1e-320),
                 (1e300, 5e-324)]:
    print("const_mono,%r,%r,%s" % (k, tau, mp.nstr(const_mono(int(k), mpf(tau)), 25)))
