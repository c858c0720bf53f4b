"""AP and IE of the tibial carriage over the gait cycle, with an optional measured overlay.

usage: kinematics.py KINEMATICS.csv OUT.png [--measured FILE(.csv|.sto)]
"""
import csv
import math
import sys


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_measured(path):
    if not path.endswith(".sto"):
        return read_csv(path)
    # Grand Challenge DM .sto (data README): x = posterior (m), rotation about y = IE (rad),
    # frame turned 180 deg about y from the project's; report insert-relative AP and IE
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.strip() == "endheader") + 1
    header = lines[start].split()
    data = [list(map(float, l.split())) for l in lines[start + 1:] if l.strip()]
    col = {h: [r[i] for r in data] for i, h in enumerate(header)}
    return {
        "gait_pct": col["time"],
        "ap_mm": [-1e3 * v for v in col["knee_ant_r"]],
        "ie_deg": [math.degrees(v) for v in col["knee_add_r"]],
    }


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    args = sys.argv[1:]
    measured = None
    if "--measured" in args:
        i = args.index("--measured")
        measured = read_measured(args[i + 1])
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
    ax1.set_title("Tibial carriage kinematics")
    fig.tight_layout()
    fig.savefig(args[1], dpi=120)


if __name__ == "__main__":
    main()
