"""Block-on-ring: the semi-analytic and the FE model side by side (bor.csv of `kneesim bor` and
of `kneesim bor --model fe`, same columns): volume, depth, contact width and mean pressure
against cycles, one colour per load, solid lines semi-analytic, dashed with markers FE.
Usage: bor_compare.py OUT_PNG LOAD_N:ANALYTIC_CSV:FE_CSV [LOAD_N:ANALYTIC_CSV:FE_CSV ...].
The PNG is written atomically."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotio import read_columns, save_figure  # noqa: E402


def main():
    dst = sys.argv[1]
    cases = [a.split(":") for a in sys.argv[2:]]
    panels = [("volume_mm3", "worn volume [mm$^3$]"), ("depth_mm", "wear depth [mm]"),
              ("contact_width_mm", "contact width [mm]"),
              ("mean_pressure_MPa", "mean contact pressure [MPa]")]
    fig, axes = plt.subplots(2, 2, figsize=(9.5, 7), sharex=True)
    colours = ["tab:blue", "tab:red", "tab:green", "tab:purple"]
    for (load, analytic, fe), colour in zip(cases, colours):
        a, f = read_columns(analytic), read_columns(fe)
        for ax, (key, label) in zip(axes.flat, panels):
            ax.plot([c / 1e3 for c in a["cycles"]], a[key], "-", color=colour,
                    label=f"{load} N semi-analytic (Winkler)")
            ax.plot([c / 1e3 for c in f["cycles"]], f[key], "--o", color=colour, ms=3,
                    label=f"{load} N FE (hex8 block)")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("cycles [thousands]")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("block-on-ring: semi-analytic against FE, Archard k$_D$ = 4.1e-10 mm$^3$/(N mm)")
    fig.tight_layout()
    save_figure(fig, dst, dpi=110)


if __name__ == "__main__":
    main()
