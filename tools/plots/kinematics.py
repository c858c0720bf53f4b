"""AP and IE over the gait cycle as joint coordinates (the tibia relative to the femur), with an
optional measured overlay.

usage: kinematics.py KINEMATICS.csv OUT.png [--measured MEASURED.csv] [--context TEXT]
(TEXT, e.g. "UHMWPE, new insert, last of 2 cycles", completes the title)
(the measured CSV has gait_pct, ap_mm, ie_deg in the project convention; `kneesim run`
writes it from a CSV or .sto input)
"""
from plotio import read_columns as read_csv, save_figure
import sys


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    args = sys.argv[1:]
    measured = None
    if "--measured" in args:
        i = args.index("--measured")
        measured = read_csv(args[i + 1])
        del args[i:i + 2]
    context = ""
    if "--context" in args:
        i = args.index("--context")
        context = args[i + 1]
        del args[i:i + 2]
    sim = read_csv(args[0])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax1.plot(sim["gait_pct"], sim["ap_mm"], label="kneesim")
    ax2.plot(sim["gait_pct"], sim["ie_deg"], label="kneesim")
    if measured:
        ax1.plot(measured["gait_pct"], measured["ap_mm"], "k--", label="measured")
        ax2.plot(measured["gait_pct"], measured["ie_deg"], "k--", label="measured")
    ax1.set_ylabel("AP, tibia anterior (mm)")
    ax2.set_ylabel("IE, tibia internal (deg)")
    ax2.set_xlabel("gait cycle (%)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend()
    ax1.set_title("Joint coordinates, tibia relative to femur" + (": " + context if context else ""),
                  fontsize=10)
    fig.tight_layout()
    save_figure(fig, args[1])


if __name__ == "__main__":
    main()
