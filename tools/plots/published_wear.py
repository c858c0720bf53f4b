"""Published knee simulator wear per condition against each wear law (kneesim diagnose
published-wear): measured mean with +-SD error bars (none where the paper gives no SD), each
law's calibrated prediction and, where its coefficient is independent, its uncalibrated one.
Usage: published_wear.py PUBLISHED_WEAR_CSV OUT_PNG. The PNG is written atomically."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plotio import save_figure  # noqa: E402


def number(text):
    try:
        v = float(text)
    except ValueError:
        return math.nan
    return v


def main():
    src, dst = sys.argv[1], sys.argv[2]
    with open(src) as f:
        rows = list(csv.DictReader(f))
    labels = [r["study"] for r in rows]
    laws = [k[len("calibrated_"):-len("_mm3_per_Mc")] for k in rows[0] if k.startswith("calibrated_")]
    x = list(range(len(rows)))
    fig, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(rows) + 2), 4.8))
    meas = [number(r["measured_mm3_per_Mc"]) for r in rows]
    sd = [number(r["sd_mm3_per_Mc"]) for r in rows]
    ax.errorbar(x, meas, yerr=[0 if math.isnan(s) else s for s in sd], fmt="ks", ms=7, capsize=5,
                label="measured (mean ± SD)", zorder=5)
    markers = ["o", "^", "D", "v", "P"]
    width = 0.5 / max(1, len(laws))
    for j, law in enumerate(laws):
        dx = [i - 0.25 + (j + 0.5) * width for i in x]
        cal = [number(r[f"calibrated_{law}_mm3_per_Mc"]) for r in rows]
        ax.plot(dx, cal, markers[j % len(markers)], ms=6, label=f"{law} (calibrated)")
        ind = [number(r[f"predicted_{law}_mm3_per_Mc"]) for r in rows]
        if not all(math.isnan(v) for v in ind):
            ax.plot(dx, ind, markers[j % len(markers)], ms=6, mfc="none",
                    label=f"{law} (independent parameters)")
    triv = [number(r["trivial_mm3_per_Mc"]) for r in rows]
    ax.plot(x, triv, "_", ms=18, color="grey", label="trivial (same rate everywhere)")
    ax.set_xticks(x)
    ax.set_xticklabels([lbl.replace(":", "\n") for lbl in labels])
    ax.set_yscale("log")
    ax.set_ylabel("wear rate [mm$^3$ per million cycles]")
    ax.set_title("Published knee simulator wear against the wear laws")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    save_figure(fig, dst)


if __name__ == "__main__":
    main()
