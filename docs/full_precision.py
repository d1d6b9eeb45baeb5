#!/usr/bin/env python3
"""Precision reached by `smolbridge validate --full`, per case.

usage: full_precision.py DIR...

Each DIR holds the validate.csv of one `smolbridge validate --full` run
of one case, and is named after it with the first '/' written '_'
(V1_kinetic-gases for V1/kinetic-gases); records of the other cases the
name selects as a prefix (V16/combined-shear under V16_combined) are
listed under their own case.  For every row whose verdict is interval
coverage (rule `cover`) of a ratio (reference not 0) the relative half-width of its interval is
rescaled from the row's level to 95 % with the normal quantiles
(z_95 / z_level: the Poisson and mean intervals are normal at these
sample sizes) and divided by the estimate.  Prints a Markdown table: per
case the number of such rows, the median and the largest 95 % half-width,
and the row that has the largest."""
import csv
import os
import statistics
import sys
from statistics import NormalDist


def z(level):
    return NormalDist().inv_cdf(0.5 + level / 2)


def main(dirs):
    cases = {}
    for d in dirs:
        path = os.path.join(d, "validate.csv")
        if not os.path.exists(path):
            print("skipped (no validate.csv): %s" % d, file=sys.stderr)
            continue
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                if r["rule"] != "cover":
                    continue
                est, lo, hi = (float(r[k]) for k in
                               ("estimate", "ci_low", "ci_high"))
                # differences (reference 0) have no relative width
                if not est or not float(r["reference"]) or hi != hi or lo != lo:
                    continue
                level = float(r["level"])
                w = (hi - lo) / 2 / abs(est) * z(0.95) / z(level)
                key = os.path.basename(os.path.normpath(d)).replace("_", "/", 1)
                # --case is a prefix: V16/combined also runs
                # V16/combined-shear, whose records carry their own name
                rec = "/".join(r["case"].split("/")[:2])
                if rec != key and rec.startswith(key + "-"):
                    key = rec
                cases.setdefault(key, []).append((w, r["case"]))
    print("| case | rows | median ±95 % | largest ±95 % | row with the largest |")
    print("|---|---|---|---|---|")
    for key, rows in cases.items():
        ws = [w for w, _ in rows]
        wmax, rmax = max(rows)
        print("| %s | %d | %.2f %% | %.2f %% | `%s` |"
              % (key, len(rows), 100 * statistics.median(ws), 100 * wmax,
                 rmax))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
