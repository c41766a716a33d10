#pragma once
// The plot of a sweep (error against wall time, Pareto front marked), written next to sweep.csv and run
// with python3 + matplotlib (Debian: python3-matplotlib), which draw far better than anything worth
// writing here.
namespace rift {

inline constexpr const char* kSweepPlotScript = R"PY(
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib import ticker

with open(sys.argv[1]) as f:
    reader = csv.DictReader(f)
    header = reader.fieldnames
    rows = [r for r in reader if r["status"] == "done" and r["error"] not in ("", "0")]
# The varied keys are the columns between "variant" and "status"; a point is labelled by its values (the
# key's last part when that is unambiguous).
keys = header[1:header.index("status")]
short = [k.split(".")[-1] for k in keys]
names = short if len(set(short)) == len(short) else keys
def label(r):
    return ", ".join(f"{n}={r[k]}" for n, k in zip(names, keys))

def set_scale(axis, set_log, values):
    # Log only when the values span more than a decade; then one label per decade. Within a decade a log
    # axis has no major tick, and its minor labels came out all alike: a linear axis with 3 digits instead.
    positive = [v for v in values if v > 0]
    if positive and max(positive) / min(positive) > 10:
        set_log("log")
        axis.set_major_formatter(ticker.LogFormatterSciNotation())
        axis.set_minor_formatter(ticker.NullFormatter())
    else:
        axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:.3g}"))

fig, ax = plt.subplots(figsize=(7.5, 4.8))
if rows:
    t = [float(r["wall_seconds"]) for r in rows]
    e = [float(r["error"]) for r in rows]
    ax.scatter(t, e, color="tab:blue", label="variants", zorder=3)
    for r, x, y in zip(rows, t, e):
        ax.annotate(label(r), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    front = sorted((x, y) for r, x, y in zip(rows, t, e) if r["pareto"] == "1")
    if front:
        ax.plot([p[0] for p in front], [p[1] for p in front], "-", color="tab:red", label="Pareto front", zorder=2)
    set_scale(ax.xaxis, ax.set_xscale, t)
    set_scale(ax.yaxis, ax.set_yscale, e)
    ax.margins(0.15)
ax.set_xlabel("wall time per run [s]")
ax.set_ylabel("largest relative error of the scene's metrics")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "speed-accuracy")
ax.grid(True, which="major", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
)PY";

}  // namespace rift
