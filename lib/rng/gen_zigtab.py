#!/usr/bin/env python3
"""Write lib/rng/rng_zigtab.c: the tables of the 128-layer ziggurat for the
standard normal (Marsaglia & Tsang 2000, "The ziggurat method for generating
random variables", J. Stat. Softw. 5(8), section 2), computed with mpmath
at 60 digits and rounded once to double.

Layers of equal area v under f(x) = exp(-x^2/2), x >= 0:
  base: [0, r] x [0, f(r)] plus the tail beyond r, area v = r f(r) + T(r),
        T(r) = sqrt(pi/2) erfc(r/sqrt(2));
  X[0] = v/f(r) (the base's virtual width), X[1] = r,
  X[i+1] = f^-1(f(X[i]) + v/X[i]),  X[128] = 0;
r solves X[127] (1 - f(X[127])) = v (the top layer reaches f(0) = 1).
A 32-bit word gives the layer i (7 bits), the sign (1 bit) and j (24 bits);
x = j W[i], W[i] = X[i]/2^24, accepted at once when j < K[i] =
floor(2^24 X[i+1]/X[i]).  F[i] = f(X[i]) for the wedge test (F[0] unused,
F[128] = 1).  tests/test_rng.c recomputes the tables with GSL.

Run: python3 lib/rng/gen_zigtab.py > lib/rng/rng_zigtab.c
"""
import mpmath as mp

mp.mp.dps = 60
N = 128


def f(x):
    return mp.exp(-x * x / 2)


def finv(y):
    return mp.sqrt(-2 * mp.log(y))


def layers(r):
    v = r * f(r) + mp.sqrt(mp.pi / 2) * mp.erfc(r / mp.sqrt(2))
    X = [v / f(r), r]
    for i in range(1, N - 1):
        y = f(X[i]) + v / X[i]
        if y >= 1:
            return v, X, mp.mpf(-1)
        X.append(finv(y))
    return v, X, X[N - 1] * (1 - f(X[N - 1])) - v


def closure(r):
    return layers(r)[2]


# bisection on the closure (its sign changes once near r = 3.44)
lo, hi = mp.mpf("3.3"), mp.mpf("3.6")
for _ in range(250):
    mid = (lo + hi) / 2
    if closure(mid) < 0:
        lo = mid
    else:
        hi = mid
r = (lo + hi) / 2
v, X, _ = layers(r)
X.append(mp.mpf(0))
two24 = mp.mpf(2) ** 24

print("/* rng_zigtab.c -- written by lib/rng/gen_zigtab.py (do not edit):")
print(" * 128-layer ziggurat tables for N(0,1) (Marsaglia & Tsang 2000).")
print(" * r = %s, v = %s */" % (mp.nstr(r, 25), mp.nstr(v, 25)))
print('#include "rng/rng_internal.h"\n')
print("const double sbi_zig_r = %s;" % float(r).hex())
print("const double sbi_zig_v = %s;\n" % float(v).hex())
print("const double sbi_zig_w[128] = {")
for i in range(N):
    print("  %s," % float(X[i] / two24).hex())
print("};\n")
print("const uint32_t sbi_zig_k[128] = {")
for i in range(N):
    print("  %du," % int(mp.floor(two24 * X[i + 1] / X[i])))
print("};\n")
print("const double sbi_zig_f[129] = {")
print("  0.0,")
for i in range(1, N):
    print("  %s," % float(f(X[i])).hex())
print("  1.0,")
print("};")
