#!/usr/bin/env python3
"""Records of `smolbridge validate` recomputed from the output tables of
`smolbridge collide` runs (tests/validate_ini.sh; the expect kinds are
described in docs/validation.md, "Reproducing a case with smolbridge
collide").

Input: a file of lines KIND<TAB>RECORD<TAB>OUTDIR<TAB>SPEC, one per
expect line of a run; the lines of one (KIND, RECORD) are pooled over
their runs.  Output: RECORD,VALUE per record (17 digits).

  expect-ks FILE COLUMN LAW SCALE [every=K]
      one-sample Kolmogorov-Smirnov distance of x = SCALE |COLUMN| (rows
      0, K, 2K, ... of each file) against LAW
  expect-chi2 FILE COLUMN LAW SCALE WIDTH NBINS
      Pearson's chi-square of x in the bins [k WIDTH, (k + 1) WIDTH),
      the last one open, against LAW (as sb_chi2_test)
  expect-max FIELD
      the largest summary.json FIELD (a.b: key b of object a)
  expect-diff-mean OFFSET FIELD FACTOR
      OFFSET - the mean of FIELD x FACTOR over the runs; FIELD is a
      summary.json field or anisotropy:FILE, (T_x - (T_y + T_z)/2)/T of
      a snapshot's velocities (T_k the variance of component k)
  expect-h-rises SCALE NBIN VMAX COLUMN NSNAP
      the times (the snapshots snap_000000.csv ... snap_NSNAP-1) at which the binned relative entropy
      H of x = SCALE COLUMN against Maxwell's speed law does not fall
      below its value at the time before, while that is above the
      sampling floor 10 (NBIN - 1)/(2 n)
  expect-batches STAT EXPR
      STAT (mean, min or max) over the rows of batches.csv (pooled over
      the runs, in order) of EXPR, an arithmetic expression of the
      row's columns (+ - * /, unary -, parentheses, numbers, pi, abs,
      sqrt, atan2); a division by zero gives nan
COLUMN `speed` is |(ux, uy, uz)| of a snapshot; LAW `flux-maxwell` is
1 - exp(-x^2/2), `maxwell-speed` erf(x/sqrt 2) - sqrt(2/pi) x exp(-x^2/2).
"""
import ast
import csv
import json
import math
import os
import sys


def law(name):
    if name == "flux-maxwell":
        return lambda x: 0.0 if x <= 0 else -math.expm1(-0.5 * x * x)
    if name == "maxwell-speed":
        return lambda x: 0.0 if x <= 0 else (
            math.erf(x / math.sqrt(2.0))
            - math.sqrt(2.0 / math.pi) * x * math.exp(-0.5 * x * x))
    raise SystemExit("unknown law " + name)


def column(path, col, every=1):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = []
    for i, r in enumerate(rows):
        if i % every:
            continue
        if col == "speed":
            ux, uy, uz = float(r["ux"]), float(r["uy"]), float(r["uz"])
            out.append(math.sqrt(ux * ux + uy * uy + uz * uz))
        else:
            out.append(abs(float(r[col])))
    return out


def anisotropy(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    u = [[float(r[c]) for c in ("ux", "uy", "uz")] for r in rows]
    n = len(u)
    m = [0.0, 0.0, 0.0]
    for v in u:
        for k in range(3):
            m[k] += v[k] / n
    s = [0.0, 0.0, 0.0]
    for v in u:
        for k in range(3):
            s[k] += (v[k] - m[k]) * (v[k] - m[k])
    tot = (s[0] + s[1] + s[2]) / 3.0
    return (s[0] - 0.5 * (s[1] + s[2])) / tot


def field(out, name):
    if name.startswith("anisotropy:"):
        return anisotropy(os.path.join(out, name[11:]))
    with open(os.path.join(out, "summary.json")) as f:
        o = json.load(f)
    for k in name.split("."):
        o = o[k]
    return float(o)


BATCH_FUNCS = {"abs": abs, "sqrt": math.sqrt, "atan2": math.atan2}
BATCH_OPS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
             ast.Mult: lambda a, b: a * b}


def batch_eval(node, row):
    """EXPR of expect-batches on one row: only the documented forms."""
    if isinstance(node, ast.Expression):
        return batch_eval(node.body, row)
    if isinstance(node, ast.Constant) and isinstance(node.value,
                                                     (int, float)):
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id == "pi":
            return math.pi
        return float(row[node.id])
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return -batch_eval(node.operand, row)
    if isinstance(node, ast.BinOp):
        a, b = batch_eval(node.left, row), batch_eval(node.right, row)
        if isinstance(node.op, ast.Div):
            return a / b if b != 0 else math.nan
        if type(node.op) in BATCH_OPS:
            return BATCH_OPS[type(node.op)](a, b)
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
            and node.func.id in BATCH_FUNCS and not node.keywords):
        return BATCH_FUNCS[node.func.id](*[batch_eval(a, row)
                                           for a in node.args])
    raise SystemExit("expect-batches: not allowed: " + ast.dump(node))


def batches(runs):
    s = runs[0][1]
    stat, expr = s[0], ast.parse(" ".join(s[1:]), mode="eval")
    x = []
    for out, _ in runs:
        with open(os.path.join(out, "batches.csv")) as f:
            x += [batch_eval(expr, r) for r in csv.DictReader(f)]
    if stat == "mean":
        return sum(x) / len(x)
    if stat in ("min", "max"):
        return (min if stat == "min" else max)(x)
    raise SystemExit("expect-batches: unknown statistic " + stat)


def ks(x, F):
    x = sorted(x)
    n = float(len(x))
    d, prev = 0.0, 0.0
    for i, v in enumerate(x):
        f = max(F(v), prev)
        prev = f
        d = max(d, (i + 1) / n - f, f - i / n)
    return d


def chi2(x, F, width, nbins):
    edges = [k * width for k in range(nbins)] + [math.inf]
    Fe = [F(e) if e < math.inf else 1.0 for e in edges]
    obs = [0] * nbins
    for v in x:
        if v < 0:
            continue
        k = min(int(v / width), nbins - 1)
        while k > 0 and v < edges[k]:  # the C search: edges[k] <= v
            k -= 1
        while k < nbins - 1 and v >= edges[k + 1]:
            k += 1
        obs[k] += 1
    nin = sum(obs)
    mass = Fe[nbins] - Fe[0]
    c2 = 0.0
    for k in range(nbins):
        e = nin * (Fe[k + 1] - Fe[k]) / mass
        if e > 0:
            c2 += (obs[k] - e) ** 2 / e
    return c2


def h_rel(v, nbin, vmax, F):
    w = vmax / (nbin - 1)
    cnt = [0] * nbin
    for s in v:
        cnt[min(int(s / w), nbin - 1)] += 1
    h = 0.0
    for b in range(nbin):
        lo = b * w
        Q = (F(lo + w) if b < nbin - 1 else 1.0) - F(lo)
        P = cnt[b] / len(v)
        if P > 0:
            h += P * math.log(P / Q)
    return h


def main():
    groups = {}
    with open(sys.argv[1]) as f:
        for line in f:
            kind, rec, out, spec = line.rstrip("\n").split("\t")
            groups.setdefault((kind, rec), []).append((out, spec.split()))
    for (kind, rec), runs in groups.items():
        if kind == "expect-ks":
            x = []
            for out, s in runs:
                every = int(s[4][6:]) if len(s) > 4 else 1
                x += [float(s[3]) * v for v in
                      column(os.path.join(out, s[0]), s[1], every)]
            val = ks(x, law(runs[0][1][2]))
        elif kind == "expect-chi2":
            x = []
            for out, s in runs:
                x += [float(s[3]) * v for v in
                      column(os.path.join(out, s[0]), s[1])]
            s = runs[0][1]
            val = chi2(x, law(s[2]), float(s[4]), int(s[5]))
        elif kind == "expect-max":
            val = max(field(out, s[0]) for out, s in runs)
        elif kind == "expect-diff-mean":
            s = runs[0][1]
            val = float(s[0]) - sum(field(out, t[1]) * float(t[2])
                                    for out, t in runs) / len(runs)
        elif kind == "expect-h-rises":
            s = runs[0][1]
            scale, nbin, vmax, col = float(s[0]), int(s[1]), float(s[2]), s[3]
            files = ["snap_%06d.csv" % k for k in range(int(s[4]))]
            F = law("maxwell-speed")
            h = []
            for fn in files:
                v = []
                for out, _ in runs:
                    v += [scale * u for u in column(os.path.join(out, fn),
                                                      col)]
                h.append(h_rel(v, nbin, vmax, F))
                floor_h = 10.0 * (nbin - 1) / (2.0 * len(v))
            val = sum(1 for k in range(1, len(h))
                      if h[k - 1] > floor_h and h[k] >= h[k - 1])
        elif kind == "expect-batches":
            val = batches(runs)
        else:
            raise SystemExit("unknown kind " + kind)
        print("%s,%.17g" % (rec, val))


main()
