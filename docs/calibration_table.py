#!/usr/bin/env python3
"""Write the calibration table of docs/validation.md from calibration.csv
(smolbridge validate --seeds N): one row per case, pooling its records.

usage: calibration_table.py CALIBRATION.csv VALIDATION.md NSEEDS
(the per-case KS p-value is read from calibration.md beside the csv)

       calibration_table.py --splice NEW.csv SUITE.csv VALIDATION.md NSEEDS
replaces the records of the cases in NEW.csv (a calibration of a few
cases, `--case X --seeds N`) in SUITE.csv (docs/calibration-quick.csv)
and their lines in the table, keeping every other case's line as it is.
"""
import os
import csv
import math
import sys


def splice(new, suite, md, nseeds):
    """Replace the cases of NEW.csv in SUITE.csv and in the table."""
    with open(new, newline="") as f:
        rd = csv.DictReader(f)
        fields = rd.fieldnames
        fresh = list(rd)
    cases = {r["case"] for r in fresh}
    with open(suite, newline="") as f:
        old = list(csv.DictReader(f))
    out, done = [], False
    for r in old:  # the new records where the case's old ones were
        if r["case"] in cases:
            if not done:
                out.extend(fresh)
                done = True
        else:
            out.append(r)
    if not done:
        out.extend(fresh)
    with open(suite, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(out)
    lines = table_lines(new, nseeds)
    text = open(md).read()
    for c in cases:
        line = [x for x in lines if x.startswith(f"| {c} |")][0]
        a = text.index(f"| {c} |")
        b = text.index("\n", a)
        text = text[:a] + line + text[b:]
    open(md, "w").write(text)


def main():
    if sys.argv[1] == "--splice":
        splice(sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]))
        return
    cal, md, nseeds = sys.argv[1], sys.argv[2], int(sys.argv[3])
    lines = table_lines(cal, nseeds)
    text = open(md).read()
    a = text.index("<!-- calibration:begin -->")
    b = text.index("<!-- calibration:end -->")
    text = (text[:a] + "<!-- calibration:begin -->\n" + "\n".join(lines)
            + "\n" + text[b:])
    open(md, "w").write(text)


def table_lines(cal, nseeds):
    """The table's lines (header and one per case) for CALIBRATION.csv."""
    ks = {}
    calmd = os.path.join(os.path.dirname(cal), "calibration.md")
    if os.path.exists(calmd):
        for line in open(calmd):
            f = [x.strip() for x in line.split("|")]
            if len(f) > 8 and f[1].startswith("V"):
                ks[f[1]] = f[7]
    cases = {}
    order = []
    with open(cal, newline="") as f:
        for r in csv.DictReader(f):
            c = r["case"]
            if c not in cases:
                cases[c] = []
                order.append(c)
            cases[c].append(r)
    lines = [
        f"Quick mode, {nseeds} seeds (12345 onwards).  Per case: records "
        "(stochastic ones, i.e. tests and intervals), the largest pooled "
        "bias |z| among them and the record it belongs to with its pooled "
        "estimate/reference, the fraction of p-values below 0.05 over "
        "all records and the KS p-value of all of them against the uniform "
        "law (per record: calibration-quick.csv), and the records failing "
        "calibration.",
        "",
        "| case | records (stochastic) | max \\|z\\| | at (pooled est/ref [95%]) "
        "| p < 0.05 | KS p | records failing | verdict |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for c in order:
        rows = cases[c]
        stoch = [r for r in rows if r["rule"] in ("cover", "accept")
                 and r["kind"] != "deterministic"]
        worst, wz = None, -1.0
        for r in stoch:
            try:
                z = abs(float(r["bias_z"]))
            except ValueError:
                continue
            if not math.isnan(z) and z > wz:
                worst, wz = r, z
        nfail = sum(r["verdict"] == "fail" for r in rows)
        # fraction of p < 0.05 over all records with p-values
        num = den = 0.0
        for r in rows:
            try:
                n, f5 = int(r["npvalues"]), float(r["frac_p05"])
            except ValueError:
                continue
            if n and not math.isnan(f5):
                num += f5 * n
                den += n
        at = "-"
        if worst is not None:
            kind = "" if worst["kind"] == "est/ref" else "d "
            at = (f"{worst['record']}: {kind}{float(worst['pooled']):.4f} "
                  f"[{float(worst['pooled_lo']):.4f}, "
                  f"{float(worst['pooled_hi']):.4f}]")
        lines.append(
            f"| {c} | {len(rows)} ({len(stoch)}) | "
            f"{wz:.2f} | {at} | "
            f"{(num / den if den else float('nan')):.3f} | "
            f"{ks.get(c, '-')} | {nfail} | "
            f"{'fail' if nfail else 'pass'} |"
            if worst is not None else
            f"| {c} | {len(rows)} ({len(stoch)}) | - | - | "
            f"{(num / den if den else float('nan')):.3f} | "
            f"{ks.get(c, '-')} | {nfail} | "
            f"{'fail' if nfail else 'pass'} |")
    return lines


if __name__ == "__main__":
    main()
