#pragma once
// The plotter of `rift plot` (engine/plot/run_plot.hpp): matplotlib over a run's timeseries.csv, one PNG
// per family of columns that the run has. Written into the output folder and run with python3.
namespace rift {

inline constexpr const char* kRunPlotScript = R"PY(
import csv, math, os, re, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

csv_path, out_dir, title = sys.argv[1], sys.argv[2], sys.argv[3]
with open(csv_path) as f:
    reader = csv.DictReader(f)
    columns = reader.fieldnames
    rows = list(reader)
if not rows:
    sys.exit("rift plot: timeseries.csv has no rows")

def values(column):
    out = []
    for r in rows:
        try:
            out.append(float(r[column]))
        except ValueError:
            out.append(math.nan)
    return out

time = values("time")
span = max(time) - min(time)
scale, unit = (1e3, "ms") if span < 1.0 else (1.0, "s")
t = [v * scale for v in time]

# Each family: (file, title, rule); a column goes to the first family whose rule takes it.
def has(*words):
    return lambda c: any(w in c for w in words)
families = [
    ("energy.png", "energies [J] and the balance error", lambda c: c.startswith("solid_") and (
        c.endswith("_energy") or c.endswith("_dissipation") or c.endswith("_work") or c.endswith("_release")
        or c.endswith("balance_error"))),
    ("loads.png", "reactions and loads [N]", has("reaction", "_load")),
    ("fracture.png", "fracture", has("broken_joints", "crack_volume", "fragments")),
    ("fracture_flow.png", "fluid in the cracks (fracture flow)", lambda c: c.startswith("flow_")),
    ("coupling.png", "fluid-solid coupling", lambda c: c.startswith("fluid_solid_")),
    ("fluid.png", "fluid: pressure, speed, CFL, divergence", lambda c: c.startswith("fluid_") and not has(
        "iterations", "converged")(c)),
    ("fluid_solver.png", "fluid solver iterations", lambda c: c.startswith("fluid_")),
    ("probes.png", "probes (each probe's points on one axes)", lambda c: c.startswith("probe_")),
    ("other.png", "other series", lambda c: True),
]
taken = {"step", "time"}
written = []
for name, heading, rule in families:
    chosen = [c for c in columns if c not in taken and rule(c)]
    taken.update(chosen)
    if not chosen:
        continue
    if name == "energy.png":  # the balance error on its own axes: it is orders below the terms
        groups = [[c for c in chosen if not c.endswith("balance_error")], [c for c in chosen if c.endswith("balance_error")]]
    elif name == "probes.png":  # probe_<name> or probe_<name>_<i>: one axes per probe
        by_probe = {}
        for c in chosen:
            by_probe.setdefault(re.sub(r"_\d+$", "", c), []).append(c)
        groups = list(by_probe.values())
    else:
        groups = [[c] for c in chosen]
    groups = [g for g in groups if g][:8]
    fig, axes = plt.subplots(len(groups), 1, figsize=(8, 1.9 + 1.7 * len(groups)), sharex=True, squeeze=False)
    for ax, group in zip(axes[:, 0], groups):
        for c in group:
            ax.plot(t, values(c), label=c, linewidth=1.2)
        if len(group) > 1:
            ax.legend(fontsize=7, ncol=2)
        else:
            ax.set_ylabel(group[0], fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4), useMathText=True)
    axes[-1, 0].set_xlabel(f"time [{unit}]")
    fig.suptitle(f"{title}: {heading}", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out_dir, name)
    fig.savefig(path + ".tmp.png", dpi=110)
    os.replace(path + ".tmp.png", path)
    plt.close(fig)
    written.append(path)
for p in written:
    print(p)
)PY";

}  // namespace rift
