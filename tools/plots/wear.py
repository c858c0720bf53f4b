"""Wear against cycles, and a top view of the final wear depth on the insert.

usage: wear.py WEAR.csv FINAL_DEPTH.csv WEAR.png DEPTH_MAP.png [MATERIAL]
(the titles name the material and the cycles of the last row of WEAR.csv)
"""
from plotio import read_columns as read_csv, save_figure
import sys


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri

    wear_csv, depth_csv, wear_png, map_png = sys.argv[1:5]
    material = sys.argv[5] if len(sys.argv) > 5 else "insert"
    w = read_csv(wear_csv)
    mc = [c * 1e-6 for c in w["cycles"]]
    cycles = "{:,.0f}".format(w["cycles"][-1]).replace(",", " ")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.plot(mc, w["volume_mm3"], "o-", label="total (enclosed volume)")
    ax1.plot(mc, w["medial_volume_mm3"], "s--", label="medial")
    ax1.plot(mc, w["lateral_volume_mm3"], "^--", label="lateral")
    ax1.set_xlabel("cycles (millions)")
    ax1.set_ylabel("volumetric wear (mm$^3$)")
    ax1.grid(alpha=0.3)
    ax1.legend()
    ax2.plot(mc, w["max_depth_mm"], "o-")
    ax2.set_xlabel("cycles (millions)")
    ax2.set_ylabel("maximum linear wear (mm)")
    ax2.grid(alpha=0.3)
    fig.suptitle("Wear of the %s insert over %s cycles" % (material, cycles), fontsize=11)
    fig.tight_layout()
    save_figure(fig, wear_png)

    d = read_csv(depth_csv)
    fig, ax = plt.subplots(figsize=(7, 5))
    tri = mtri.Triangulation(d["z_mm"], d["x_mm"])
    cs = ax.tricontourf(tri, d["depth_mm"], levels=20, cmap="viridis")
    fig.colorbar(cs, ax=ax, label="wear depth (mm)")
    ax.set_xlabel("medial  <-  z (mm)  ->  lateral")
    ax.set_ylabel("posterior  <-  x (mm)  ->  anterior")
    ax.set_aspect("equal")
    ax.set_title("Wear depth of the %s insert after %s cycles (worn), top view" % (material, cycles),
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, map_png)


if __name__ == "__main__":
    main()
