"""Block-on-ring wear curves from `kneesim bor`: volume, depth, contact width and mean pressure
against cycles. Usage: bor.py BOR_CSV OUT_PNG [TITLE]. The PNG is written atomically."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotio import save_figure  # noqa: E402


def main():
    src, dst = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    cyc = [float(r["cycles"]) / 1e3 for r in rows]
    panels = [("volume_mm3", "worn volume [mm$^3$]"), ("depth_mm", "depth [mm]"),
              ("contact_width_mm", "contact width [mm]"),
              ("mean_pressure_MPa", "mean contact pressure [MPa]")]
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), sharex=True)
    for ax, (key, label) in zip(axes.flat, panels):
        ax.plot(cyc, [float(r[key]) for r in rows], "-", color="tab:blue")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("cycles [thousands]")
    fig.suptitle("block-on-ring semi-analytic model" + (": " + title if title else ""))
    fig.tight_layout()
    save_figure(fig, dst, dpi=110)


if __name__ == "__main__":
    main()
