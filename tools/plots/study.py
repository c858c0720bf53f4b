"""Plots of a probabilistic study (`kneesim study`): AP and IE 1/50/99 % envelopes over the
gait cycle with the nominal trace (and the measured one when DIR/measured_kinematics.csv is
there), |Pearson r| sensitivity bars per measure, and with --wear the wear envelopes against
cycles.

usage: study.py DIR   (reads DIR/envelopes.csv, DIR/sensitivity.csv, DIR/wear_envelopes.csv,
DIR/measured_kinematics.csv; writes DIR/envelopes.png, DIR/sensitivity.png,
DIR/wear_envelopes.png)
"""
import csv
import os
import sys

from plotio import save_figure


def envelope_axes(ax, cols, x_name, name, ylabel, measured=None):
    x = cols[x_name]
    ax.fill_between(x, cols[name + "_p01"], cols[name + "_p99"], alpha=0.3,
                    label="1-99 %")
    ax.plot(x, cols[name + "_p50"], label="50 %")
    nominal = cols.get(name + "_nominal")
    if nominal:
        ax.plot(x, nominal, "k--", label="nominal")
    if measured and name in measured:
        ax.plot(measured["gait_pct"], measured[name], "r-", lw=1.2, label="measured")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8)


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = sys.argv[1]
    env = os.path.join(d, "envelopes.csv")
    if os.path.exists(env) and "ap_mm_p01" in read_columns_blank(env):
        cols = read_columns_blank(env)
        meas_path = os.path.join(d, "measured_kinematics.csv")
        measured = read_columns_blank(meas_path) if os.path.exists(meas_path) else None
        fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
        envelope_axes(ax1, cols, "gait_pct", "ap_mm", "AP, tibia anterior (mm)", measured)
        envelope_axes(ax2, cols, "gait_pct", "ie_deg", "IE, tibia internal (deg)", measured)
        ax2.set_xlabel("gait cycle (%)")
        fig.tight_layout()
        save_figure(fig, os.path.join(d, "envelopes.png"))
    wear = os.path.join(d, "wear_envelopes.csv")
    if os.path.exists(wear) and "max_linear_wear_mm_p01" in read_columns_blank(wear):
        cols = read_columns_blank(wear)
        fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
        envelope_axes(ax1, cols, "cycles", "max_linear_wear_mm", "max linear wear (mm)")
        envelope_axes(ax2, cols, "cycles", "gravimetric_wear_mg", "gravimetric wear (mg)")
        ax2.set_xlabel("cycles")
        fig.tight_layout()
        save_figure(fig, os.path.join(d, "wear_envelopes.png"))
    sens = os.path.join(d, "sensitivity.csv")
    if os.path.exists(sens):
        with open(sens) as f:
            rows = list(csv.DictReader(f))
        measures = sorted({r["measure"] for r in rows}, key=lambda m: [r["measure"] for r in rows].index(m))
        fig, axes = plt.subplots(len(measures), 1, figsize=(8, 2.2 * len(measures)), squeeze=False)
        for ax, m in zip(axes[:, 0], measures):
            sel = [r for r in rows if r["measure"] == m]
            sel.sort(key=lambda r: -float(r["abs_corr"]))
            ax.barh([r["parameter"].split(".")[-1] for r in sel],
                    [float(r["abs_corr"]) for r in sel])
            ax.invert_yaxis()
            ax.set_xlim(0, 1)
            ax.set_title(m, fontsize=9)
            ax.tick_params(labelsize=7)
        axes[-1, 0].set_xlabel("|Pearson r|")
        fig.tight_layout()
        save_figure(fig, os.path.join(d, "sensitivity.png"))


def read_columns_blank(path):
    """Like read_columns, but blank cells (a failed nominal) are dropped columns."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = {}
    for k in rows[0]:
        if all(r[k] != "" for r in rows):
            out[k] = [float(r[k]) for r in rows]
    return out


if __name__ == "__main__":
    main()
