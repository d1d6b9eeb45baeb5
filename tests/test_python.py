"""Checks of the Python module against independent values: the closed
forms of the bridge crossing probabilities, the analytic constant-kernel
population balance, and an engine run whose answer is known (two spheres
at 45 degrees) through the library, with no command or subprocess.  Run
by tests/python.sh."""
import math
import os
import re
import subprocess
import sys
import tempfile
import warnings

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
# bad arguments are ValueErrors naming them; past gelation (multiplicative
# kernel, t_gel = 1/(K M2(0)) = 1) an error, not negative concentrations
for kw, word in [({"method": "foo"}, "method"), ({"init": "gaussian"}, "init"),
                 ({"sizes": 2.7}, "sizes"), ({"sizes": 1}, "sizes"),
                 ({"method": "sectional", "ratio": 0}, "ratio"),
                 ({"times": []}, "times")]:
    args = dict(n0=1.0, times=[1.0])
    args.update(kw)
    try:
        sb.pbe("constant", **args)
        check(False, "pbe accepted %s" % kw)
    except ValueError as e:
        check(word in str(e), "pbe %s message: %s" % (kw, e))
try:
    sb.pbe("multiplicative", n0=1.0, times=[0.5, 2.0], sizes=60)
    check(False, "pbe ran past gelation")
except ValueError as e:
    check("gelation at t = 1/(K M2(0)) = 1" in str(e),
          "pbe gelation message: %s" % e)
r = sb.pbe("multiplicative", n0=1.0, times=[0.5, 0.9], sizes=60)
check((r["moments"][:, 0] > 0).all() and (r["n"] >= -1e-12).all(),
      "pbe before gelation: positive concentrations")

# collide from a dict: the 45-degree case (one collision, known velocities),
# run by the library itself: no command on PATH, no subprocess


def no_subprocess(*args, **kw):
    raise AssertionError("collide started a subprocess")


subprocess.Popen = no_subprocess
os.environ["PATH"] = ""
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
events = []
summary, series = sb.collide(cfg, progress=events.append)
check(summary["collisions"] == 1, "collide: one collision")
check(summary["status"] == "ok" and "ncoll" in series, "collide outputs")
check(abs(series["px"][-1] - 1e-15 * 0.1) < 1e-28, "momentum conserved")
check([e["event"] for e in events] == ["begin", "step"] and
      events[-1]["fraction"] == 1.0 and events[0]["particles"] == 2 and
      events[-1]["collisions"] == 1 and events[-1]["first_contacts"] == -1,
      "collide progress: %s" % events)
# the elastic collision keeps the kinetic energy (summary kinetic_energy)
ke = summary["kinetic_energy"]
check(abs(ke["start"] / (0.5 * 1e-15 * 0.01) - 1) < 1e-12 and
      ke["rel_change"] < 1e-12,
      "collide kinetic_energy: %s" % ke)
# the mean-square displacement observer's entry comes through
summary, _ = sb.collide(dict(cfg, observe={"msd_every": 1}))
check(summary["msd"]["samples"] == 2 and summary["msd"]["particles"] == 2,
      "collide msd: %s" % summary.get("msd"))
# the batch observer's entry comes through; two region lines from a list
# of lists (both the whole box: the two spheres' mass)
summary, _ = sb.collide(dict(cfg, observe={
    "batch_steps": 1, "region": [[0, 1e-4, 0, 1e-4, 0, 1e-4]] * 2}))
b = summary.get("batches", {})
check(b.get("n") == 1 and len(b.get("regions", [])) == 2 and
      abs(b["means"]["region2"]["mean"] - 2e-15) < 1e-27 and
      b["means"]["collisions"]["mean"] == 1,
      "collide batches: %s" % b)
# an override: recorded, and it sets the step
summary, _ = sb.collide(cfg, sets=["run.dt=2e-5"])
check(summary["overrides"] == ["run.dt=2e-5"] and summary["dt"] == 2e-5,
      "collide sets recorded and applied")
# output=DIR keeps the files
with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "kept")
    sb.collide(cfg, output=out)
    check(os.path.exists(os.path.join(out, "summary.json")),
          "collide output= keeps summary.json")
# [observe] grid: its summary entry comes through, and grid.csv's frame
# holds the two spheres' mass and momentum (sum of rho h^3)
with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "grid")
    summary, _ = sb.collide(dict(cfg, observe={"grid": [4, 2, 2]}),
                            output=out)
    g = summary.get("grid", {})
    check(g.get("n") == [4, 2, 2] and g.get("frames") == 1 and
          g.get("scheme") == "ngp", "collide grid summary: %s" % g)
    rows = np.genfromtxt(os.path.join(out, "grid.csv"), delimiter=",",
                            names=True)
    hv = (1e-4 / 4) * (1e-4 / 2) * (1e-4 / 2)
    check(len(rows) == 16 and
          abs(rows["rho"].sum() * hv - 2e-15) < 1e-27 and
          abs(rows["rho_ux"].sum() * hv - 1e-15 * 0.1) < 1e-28,
          "collide grid.csv mass and momentum")
# a key without effect: a CollideWarning naming it
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    sb.collide(dict(cfg, bridge={"tol": 1e-6}))
check(len(w) == 1 and issubclass(w[0].category, sb.CollideWarning) and
      "[bridge] ignored" in str(w[0].message),
      "collide warning: %s" % [str(x.message) for x in w])
# input errors: status 2, the line of the INI text and the key
bad = dict(cfg)
bad["run"] = dict(cfg["run"], detect="brige")
try:
    sb.collide(bad)
    check(False, "collide accepted detect = brige")
except sb.CollideError as e:
    check(e.status == 2 and
          re.match(r"config:\d+: \[run\] detect = brige: unknown; valid: "
                   r"ballistic, overlap", str(e)),
          "CollideError: %s" % e)
try:
    sb.collide(cfg, sets=["run.dt=-1"])
    check(False, "collide accepted run.dt=-1")
except sb.CollideError as e:
    check(e.status == 2 and str(e).startswith("--set run.dt=-1: [run] dt"),
          "CollideError of --set: %s" % e)
# a run stopped by its progress callback: a run error (status 1); an
# exception in the callback stops the run and comes back
long_cfg = dict(cfg, run=dict(cfg["run"], steps=40))
try:
    sb.collide(long_cfg, progress=lambda p: p["event"] == "step")
    check(False, "the progress callback did not stop the run")
except sb.CollideError as e:
    check(e.status == 1 and "stopped by the progress callback" in str(e),
          "stopped run: %s" % e)


def interrupt(p):
    if p["event"] == "step":
        raise KeyboardInterrupt


try:
    sb.collide(long_cfg, progress=interrupt)
    check(False, "the callback's exception was lost")
except KeyboardInterrupt:
    pass

# first-contact counting of a mixture: the summary dict carries one
# kernel per species pair (first_hit.pairs), whose counts add up to the
# totals, each K = hits / expected_per_K
mix = {
    "run": {"L": 2e-6, "dt": 1e-7, "steps": 100, "detect": "exact",
            "outcome": "count", "placement": "uniform", "seed": 3},
    "observe": {"first_hit": True},
    "species a": {"radius": 5e-8, "mass": 1e-18, "tau": 1e-9, "b2": 2e-10,
                  "count": 60},
    "species b": {"radius": 1e-7, "mass": 1e-18, "tau": 1e-9, "b2": 2e-11,
                  "count": 40},
}
summary, _ = sb.collide(mix)
fh = summary["first_hit"]
pairs = fh["pairs"]
check([p["species"] for p in pairs] == [["a", "a"], ["a", "b"], ["b", "b"]]
      and fh["K"] is None and sum(p["hits"] for p in pairs) == fh["hits"]
      and fh["hits"] > 0 and
      sum(p["pairs_apart"] for p in pairs) == fh["pairs_apart"] and
      all(abs(p["K"] - p["hits"] / p["expected_per_K"]) <= 1e-12 * p["K"]
          for p in pairs) and
      abs(pairs[1]["radius"] - 1.5e-7) < 1e-20 and
      abs(pairs[1]["D"] - 1.1e-10) < 1e-22,
      "collide first_hit pairs: %s" % fh)

# deposition on absorbing walls without particle-particle detection: the
# series carries the cumulative deposits (total and per absorbing face),
# the last row the summary's per-face counts
dep = {
    "run": {"Lx": 4e-4, "Ly": 2e-5, "Lz": 4e-4, "dt": 0.0225, "steps": 8,
            "sample_every": 1, "detect": "none", "placement": "uniform",
            "seed": 5},
    "walls": {"y_lo": "absorb", "y_hi": "absorb"},
    "species a": {"radius": 5e-8, "mass": 5e-19, "tau": 1e-9,
                  "b2": 8.8e-12, "count": 2000, "profile": "parabolic"},
}
summary, series = sb.collide(dep)
d = summary["deposits"]
check(summary["detect"] == "none" and len(series["deposits"]) == 8 and
      series["deposits"][-1] == d[2] + d[3] > 0 and
      series["deposits_y_lo"][-1] == d[2] and
      all(series["deposits"][1:] >= series["deposits"][:-1]),
      "collide deposits series: %s, %s" % (d, series.get("deposits")))

if fails:
    sys.exit(1)
print("python: all checks passed (%s)" % sb.library_version())
