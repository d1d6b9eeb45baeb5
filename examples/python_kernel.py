#!/usr/bin/env python3
"""Engine kernel vs the continuum Brownian kernel from Python (docs/python.md):
first-contact counting with the Bessel-3 bridge detector for three
diameters; writes kernel.png."""
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import smolbridge as sb

T, mu, rho = 296.15, 1.83245e-5, 1000.0      # air, Mohaupt (2011) Table 5.2
K_co = sb.kernel_brownian_co(0.5e-6, 0.5e-6, T, mu)   # 8 k_B T/(3 mu)

rows = []
for d in [0.75e-6, 1e-6, 2e-6]:
    tau = sb.stokes_tau(rho, d, mu, 1.0)
    cfg = {
        "run": {"seed": 7, "L": 1e-4, "dt": 100 * tau, "steps": 300,
                "detect": "bridge", "outcome": "count",
                "placement": "uniform"},
        "observe": {"first_hit": True},
        "species p": {"diameter": d, "density": rho, "mu": mu, "T": T,
                      "count": 3000},
    }
    summary, series = sb.collide(cfg)
    fh = summary["first_hit"]
    rows.append((d, fh["K"] / K_co, fh["ci95"][0] / K_co,
                 fh["ci95"][1] / K_co, fh["hits"]))
    print("d = %.2f um: %d first contacts, K/K_co = %.3f [%.3f, %.3f]"
          % (d * 1e6, fh["hits"], *rows[-1][1:4]))

d, r, lo, hi, n = np.array(rows).T
plt.errorbar(d * 1e6, r, yerr=[r - lo, hi - r], fmt="o", label="engine (bridge)")
plt.axhline(1.0, color="k", label="continuum 8kT/3mu")
plt.xlabel("diameter (um)")
plt.ylabel("K / K_co")
plt.legend()
plt.savefig("kernel.png", dpi=100)
