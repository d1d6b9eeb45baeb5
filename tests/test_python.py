"""Checks of the Python module against independent values: the closed
forms of the bridge crossing probabilities, the analytic constant-kernel
population balance, and an engine run whose answer is known (two spheres
at 45 degrees).  Run by tests/python.sh."""
import math
import sys

import numpy as np

import smolbridge as sb

fails = []


def check(cond, what):
    if not cond:
        fails.append(what)
        print("FAIL:", what)


# reference functions: scalar, vectorised (broadcast), errors
check(abs(sb.bb_cross_prob(2.0, 3.0, 1.0, 4.0) - math.exp(-1)) < 1e-15,
      "bb_cross_prob scalar")
x = np.array([1.5, 2.0, 3.0])
got = sb.bes3b_cross_prob(x, 1.3, 1.0, 1.0)
want = [math.expm1(2 * (xi + 1.3 - 1)) / math.expm1(2 * xi * 1.3) for xi in x]
check(got.shape == (3,) and np.allclose(got, want, rtol=1e-13, atol=0),
      "bes3b_cross_prob vectorised")
grid = sb.bb_cross_prob(x[:, None], np.array([2.0, 3.0])[None, :], 1.0, 4.0)
check(grid.shape == (3, 2), "broadcast shape")
try:
    sb.bb_cross_prob(1.0, 1.0, 0.0, -1.0)
    check(False, "no ValueError for v < 0")
except ValueError as e:
    check("v = -1" in str(e) and "bb_cross_prob" in str(e),
          "ValueError names the argument: %s" % e)
check(np.isnan(sb.bb_cross_prob(np.array([1.0]), 1.0, 0.0, -1.0)[0]),
      "array call returns NaN on a bad argument")

# pbe: constant kernel, mono start, M0 = N0/(1 + K N0 t/2)
r = sb.pbe("constant", n0=3.0, times=[0.5, 1.0], sizes=40, K=2.0)
m0 = r["moments"][:, 0]
want = 3.0 / (1.0 + 2.0 * 3.0 * np.array([0.5, 1.0]) / 2.0)
check(np.allclose(m0, want, rtol=1e-7), "pbe M0 %s vs %s" % (m0, want))
nk = r["n"][1, :5] / 3.0
check(np.allclose(nk, [sb.pbe_const_mono_n(k, 6.0) for k in range(1, 6)],
                  rtol=1e-6), "pbe n_k vs analytic")
check(r["n"].shape == (2, 40) and r["tail_n"].shape == (2,),
      "pbe array shapes")
r = sb.pbe("diffusion", n0=1e12, v1=5.2e-19, times=[100], sizes=50, b2=1e-12)
rad = (3 * 5.2e-19 / (4 * math.pi)) ** (1 / 3)
K = 4 * math.pi * 1e-12 * 2 * rad
check(abs(r["moments"][0, 0] / (1e12 / (1 + K * 1e12 * 50)) - 1) < 1e-7,
      "pbe diffusion kernel M0")
try:
    sb.pbe("nonsense", n0=1, times=[1])
    check(False, "pbe accepted an unknown kernel")
except ValueError as e:
    check("nonsense" in str(e), "pbe error message: %s" % e)

# collide from a dict: the 45-degree case (one collision, known velocities)
c = 5e-5
r1 = 1e-6
s2 = math.sqrt(2.0)
cfg = {
    "run": {"L": 1e-4, "dt": 1e-5, "steps": 1, "sample_every": 1,
            "outcome": "elastic"},
    "species sphere": {"radius": r1, "mass": 1e-15, "tau": "inf", "T": 300,
                       "particle": [[c - s2 * r1 - 0.5 * 0.1 * 1e-5, c, c,
                                     0.1, 0, 0],
                                    [c, c - s2 * r1, c, 0, 0, 0]]},
}
summary, series = sb.collide(cfg)
check(summary["collisions"] == 1, "collide: one collision")
check(summary["status"] == "ok" and "ncoll" in series, "collide outputs")
check(abs(series["px"][-1] - 1e-15 * 0.1) < 1e-28, "momentum conserved")
summary, _ = sb.collide(cfg, sets=["run.dt=2e-5"])
check(summary["overrides"] == ["run.dt=2e-5"], "collide sets recorded")
bad = dict(cfg)
bad["run"] = dict(cfg["run"], detect="brige")
try:
    sb.collide(bad)
    check(False, "collide accepted detect = brige")
except sb.CollideError as e:
    check(e.status == 2 and "valid: ballistic, overlap" in str(e),
          "CollideError: %s" % e)

if fails:
    sys.exit(1)
print("python: all checks passed (%s)" % sb.library_version())
