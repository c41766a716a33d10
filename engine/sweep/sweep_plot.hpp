#pragma once
// The plot of a sweep (error against wall time, Pareto front marked), written next to sweep.csv and run
// with python3 + matplotlib (Debian: python3-matplotlib), which draw far better than anything worth
// writing here.
namespace rift {

inline constexpr const char* kSweepPlotScript = R"PY(
import csv, math, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "done" and r["error"] not in ("", "0")]
fig, ax = plt.subplots(figsize=(7, 4.5))
if rows:
    t = [float(r["wall_seconds"]) for r in rows]
    e = [float(r["error"]) for r in rows]
    ax.scatter(t, e, color="tab:blue", label="variants")
    for r, x, y in zip(rows, t, e):
        ax.annotate(r["variant"], (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    front = sorted((x, y) for r, x, y in zip(rows, t, e) if r["pareto"] == "1")
    if front:
        ax.plot([p[0] for p in front], [p[1] for p in front], "-o", color="tab:red", label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
ax.set_xlabel("wall time per run [s]")
ax.set_ylabel("largest relative error of the scene's metrics")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "speed-accuracy")
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
)PY";

}  // namespace rift
