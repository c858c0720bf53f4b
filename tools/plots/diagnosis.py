"""Diagnosis plot from `kneesim diagnose`: measured data against the baseline and the
extended model (top row), and residuals of both (bottom row), one column per measured
quantity, one colour per condition. Usage: diagnosis.py RESIDUALS_CSV CURVES_CSV OUT_PNG
[TITLE]. The PNG is written atomically."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotio import save_figure  # noqa: E402


# axis labels in words and units for the columns the diagnoses write; any other name is
# spelled out from its unit suffix (e.g. "contact_area_mm2" -> "contact area [mm²]")
LABELS = {
    "volume_mm3": "wear volume [mm³]",
    "max_depth_mm": "maximum wear depth [mm]",
    "depth_mm": "wear depth [mm]",
    "ap_mm": "AP translation, tibia anterior [mm]",
    "ie_deg": "IE rotation, tibia internal [deg]",
    "flexion_deg": "flexion [deg]",
    "medial_force_N": "medial compartment force [N]",
    "lateral_force_N": "lateral compartment force [N]",
    "axial_force_N": "axial force [N]",
    "gait_pct": "gait cycle [%]",
    "cycles": "cycles [thousands]",
    "load_N": "load [N]",
}
UNITS = {"mm3": "mm³", "mm2": "mm²", "mm": "mm", "deg": "deg", "N": "N", "Nm": "N m",
         "MPa": "MPa", "pct": "%", "s": "s", "kN": "kN"}


def label(name):
    if name in LABELS:
        return LABELS[name]
    words, _, unit = name.rpartition("_")
    if words and unit in UNITS:
        return f"{words.replace('_', ' ')} [{UNITS[unit]}]"
    return name.replace("_", " ")


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    res, cur, dst = read(sys.argv[1]), read(sys.argv[2]), sys.argv[3]
    title = sys.argv[4] if len(sys.argv) > 4 else ""
    xname = [k for k in res[0].keys() if k not in (
        "group", "specimen", "quantity", "measured", "baseline", "extended",
        "heldout_baseline", "heldout_extended")][0]
    quantities = list(dict.fromkeys(r["quantity"] for r in res))
    groups = list(dict.fromkeys(r["group"] for r in res))
    colours = {g: c for g, c in zip(groups, plt.rcParams["axes.prop_cycle"].by_key()["color"])}
    scale = 1e3 if xname == "cycles" else 1.0
    xlabel = label(xname)
    fig, axes = plt.subplots(2, len(quantities), figsize=(max(7.0, 5.2 * len(quantities)), 7.5),
                             squeeze=False, sharex="col")
    for j, q in enumerate(quantities):
        top, bottom = axes[0][j], axes[1][j]
        for g in groups:
            rows = [r for r in res if r["quantity"] == q and r["group"] == g]
            xs = [float(r[xname]) / scale for r in rows]
            top.plot(xs, [float(r["measured"]) for r in rows], "o", ms=4, color=colours[g],
                     alpha=0.7, label=f"measured {g}")
            for model, style in (("baseline", "--"), ("extended", "-")):
                pts = [c for c in cur if c["model"] == model and c["quantity"] == q
                       and c["group"] == g]
                top.plot([float(c[xname]) / scale for c in pts], [float(c["value"]) for c in pts],
                         style, color=colours[g], lw=1.6,
                         label=f"{model} {g}")
            bottom.plot(xs, [float(r["measured"]) - float(r["baseline"]) for r in rows], "x",
                        color=colours[g], label=f"measured - baseline {g}")
            bottom.plot(xs, [float(r["measured"]) - float(r["extended"]) for r in rows], "o",
                        mfc="none", color=colours[g], label=f"measured - extended {g}")
        bottom.axhline(0.0, color="k", lw=0.8)
        top.set_ylabel(label(q))
        bottom.set_ylabel("residual (measured - model)\n" + label(q), fontsize=9)
        bottom.set_xlabel(xlabel)
        top.grid(alpha=0.3)
        bottom.grid(alpha=0.3)
        top.legend(fontsize=7)
        bottom.legend(fontsize=7)
    fig.suptitle("diagnosis" + (": " + title if title else "") +
                 "\n(dashed: baseline, solid: extended)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, dst, dpi=110)


if __name__ == "__main__":
    main()
