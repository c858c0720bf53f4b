"""Contact-law calibration from `kneesim calibrate-contact`: frame peak pressure, mean contact
pressure and contact area over the gait cycle for the deformable insert, the rigid law as
specified and the calibrated rigid law; the fitting window (0-30 %) and the held-out window
(30-60 %) shaded. From `kneesim check-contact` (mode "check"): the same traces, the third being
the law the commands use, not fitted to this load case, and stance (0-60 %) shaded.
Usage: calibrate.py COMPARISON_CSV OUT_PNG [TITLE [MODE]]. Written atomically."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotio import read_columns, save_figure  # noqa: E402


def main():
    src, dst = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    check = len(sys.argv) > 4 and sys.argv[4] == "check"
    c = read_columns(src)
    x = c["gait_pct"]
    panels = [("peak_MPa", "frame peak pressure [MPa]"), ("mean_MPa", "mean contact pressure [MPa]"),
              ("area_mm2", "contact area [mm$^2$]")]
    runs = [("deformable", "deformable (hex8)", "k-"), ("rigid", "rigid, as specified", "r--"),
            ("calibrated", "rigid, the law the commands use" if check else "rigid, calibrated",
             "b-.")]
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for ax, (key, label) in zip(axes, panels):
        for run, name, style in runs:
            ax.plot(x, c[f"{run}_{key}"], style, label=name, lw=1.3)
        if check:
            ax.axvspan(0, 60, color="tab:blue", alpha=0.06)
        else:
            ax.axvspan(0, 30, color="tab:green", alpha=0.08)
            ax.axvspan(30, 60, color="tab:orange", alpha=0.08)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, title_fontsize=8,
                   title="shaded: stance 0-60 %, nothing fitted" if check
                   else "shaded: fitted 0-30 %, held out 30-60 %")
    axes[-1].set_xlabel("gait cycle [%]")
    fig.suptitle(("contact-law check" if check else "contact-law calibration") +
                 (": " + title if title else ""))
    fig.tight_layout()
    save_figure(fig, dst, dpi=110)


if __name__ == "__main__":
    main()
