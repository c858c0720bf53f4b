"""Plots of `kneesim compare`: wear against cycles, AP and IE over the gait cycle, and contact
area and peak pressure over the gait cycle, one line per material.

usage: compare.py OUT_DIR MATERIAL [MATERIAL ...]
"""
from plotio import read_columns as read_csv, save_figure
import os
import sys


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out, materials = sys.argv[1], sys.argv[2:]
    wear = {m: read_csv(os.path.join(out, m, "wear.csv")) for m in materials}
    kin = {m: read_csv(os.path.join(out, m, "kinematics.csv")) for m in materials}

    cycles = "{:,.0f}".format(wear[materials[0]]["cycles"][-1]).replace(",", " ")
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.set_title("Wear over %s cycles" % cycles, fontsize=10)
    for m in materials:
        ax.plot([c * 1e-6 for c in wear[m]["cycles"]], wear[m]["volume_mm3"], "o-", label=m)
    ax.set_xlabel("cycles (millions)")
    ax.set_ylabel("volumetric wear (mm$^3$)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "compare_wear.png"))

    # kinematics.csv of each material is the gait cycle simulated on its final (worn) geometry;
    # comparison.md's pressures and areas are the new insert's
    worn = "final cycle on each worn insert after %s cycles" % cycles
    for name, keys, labels, title in [
        ("compare_kinematics.png", ("ap_mm", "ie_deg"), ("AP, tibia anterior (mm)", "IE, tibia internal (deg)"),
         "Joint coordinates (tibia relative to femur), " + worn),
        ("compare_contact.png", ("contact_area_mm2", "peak_pressure_MPa"), ("contact area (mm$^2$)", "peak pressure (MPa)"),
         "Contact, " + worn),
    ]:
        fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
        axes[0].set_title(title, fontsize=10)
        for ax, key, label in zip(axes, keys, labels):
            for m in materials:
                ax.plot(kin[m]["gait_pct"], kin[m][key], label=m)
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
            ax.legend()
        axes[1].set_xlabel("gait cycle (%)")
        fig.tight_layout()
        save_figure(fig, os.path.join(out, name))


if __name__ == "__main__":
    main()
