"""Top views of the insert's contact pressure maps of `kneesim run` (one panel per gait % of
output.map_pcts, one colour scale), read from the run's own pressure_<pct>pct.vtp files.

usage: pressure_maps.py OUT.png TITLE MAP.vtp [MAP.vtp ...]
"""
from plotio import save_figure
import os
import re
import sys
import xml.etree.ElementTree as ET


def read_vtp(path):
    """(points [(x, y, z)], triangles [(a, b, c)], pressure_MPa per triangle) of a kneesim .vtp"""
    root = ET.parse(path).getroot()
    piece = root.find("PolyData/Piece")
    nums = piece.find("Points/DataArray").text.split()
    pts = [tuple(float(v) for v in nums[i:i + 3]) for i in range(0, len(nums), 3)]
    conn = [int(v) for v in piece.find("Polys/DataArray[@Name='connectivity']").text.split()]
    tris = [tuple(conn[i:i + 3]) for i in range(0, len(conn), 3)]
    p = None
    for a in piece.findall("CellData/DataArray"):
        if a.get("Name") == "pressure_MPa":
            p = [float(v) for v in a.text.split()]
    return pts, tris, p


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri

    out, title, files = sys.argv[1], sys.argv[2], sys.argv[3:]
    maps = []
    for f in files:
        pts, tris, p = read_vtp(f)
        if p is None or len(p) != len(tris):
            print("pressure_maps.py: %s has no pressure_MPa per triangle" % f, file=sys.stderr)
            return 1
        m = re.search(r"pressure_(\d+)pct", os.path.basename(f))
        maps.append((int(m.group(1)) if m else 0, pts, tris, p))
    vmax = max(max(p) for _, _, _, p in maps) or 1.0
    n = len(maps)
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 2.8 * rows + 0.6), squeeze=False)
    im = None
    for ax, (pct, pts, tris, p) in zip(axes.flat, maps):
        # top view: medial-lateral (z) across, anterior-posterior (x) up
        tri = mtri.Triangulation([q[2] for q in pts], [q[0] for q in pts], tris)
        im = ax.tripcolor(tri, facecolors=p, cmap="inferno_r", vmin=0.0, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_title("gait %d %%, peak %.1f MPa" % (pct, max(p)), fontsize=9)
        ax.set_xlabel("z (mm), lateral +", fontsize=8)
        ax.set_ylabel("x (mm), anterior +", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0, 0.9, 0.95))
    cax = fig.add_axes((0.91, 0.15, 0.015, 0.7))
    fig.colorbar(im, cax=cax, label="contact pressure (MPa)")
    save_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
