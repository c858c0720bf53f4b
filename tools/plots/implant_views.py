"""Three orthogonal views of the femoral component over the insert as `kneesim run` starts
(kneesim implant check): front (from anterior), side (from lateral) and top, shaded, drawn back
to front, with the project axes and the flexion-extension axis.

usage: implant_views.py OUT.png TITLE FEMUR.stl INSERT.stl AXIS_Y_MM
(binary STL in metres, project frame: +x anterior, +y superior, +z lateral)
"""
from plotio import save_figure
import struct
import sys


def read_stl(path):
    """triangles (n, 3, 3) in mm of a binary STL in metres"""
    import numpy as np
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack("<I", data[80:84])[0]
    rec = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    return np.frombuffer(data[84:84 + 50 * n], dtype=rec)["v"].astype(float) * 1e3


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    import numpy as np

    out, title, femur_path, insert_path, axis_y = sys.argv[1:6]
    axis_y = float(axis_y)
    parts = [(read_stl(femur_path), np.array([0.62, 0.68, 0.78])),
             (read_stl(insert_path), np.array([0.93, 0.85, 0.62]))]
    # (name, horizontal axis, vertical axis, viewing direction towards the viewer)
    views = [("front (from anterior)", 2, 1, np.array([1.0, 0, 0]), "z lateral [mm]",
              "y superior [mm]"),
             ("side (from lateral)", 0, 1, np.array([0, 0, 1.0]), "x anterior [mm]",
              "y superior [mm]"),
             ("top (from superior)", 2, 0, np.array([0, 1.0, 0]), "z lateral [mm]",
              "x anterior [mm]")]
    light = np.array([0.4, 0.8, 0.45])
    light /= np.linalg.norm(light)
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.4))
    for ax, (name, h, v, toward, hl, vl) in zip(axes, views):
        polys, colours, depth = [], [], []
        for tris, base in parts:
            nrm = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
            nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-12)[:, None]
            facing = nrm @ toward > 0.0  # back faces are hidden by the front ones
            t = tris[facing]
            shade = 0.35 + 0.65 * np.clip(np.abs(nrm[facing] @ light), 0, 1)
            polys.append(t[:, :, [h, v]])
            colours.append(np.clip(base[None, :] * shade[:, None], 0, 1))
            depth.append(t.mean(axis=1) @ toward)
        polys = np.concatenate(polys)
        colours = np.concatenate(colours)
        order = np.argsort(np.concatenate(depth))  # far first
        ax.add_collection(PolyCollection(polys[order], facecolors=colours[order],
                                         edgecolors="none", antialiased=False))
        ax.autoscale_view()
        ax.set_aspect("equal")
        ax.set_title(name)
        ax.set_xlabel(hl)
        ax.set_ylabel(vl)
        ax.axhline(0.0, color="0.7", lw=0.5)
        ax.axvline(0.0, color="0.7", lw=0.5)
        # the flexion-extension axis: along z through (0, axis_y)
        if h == 0 and v == 1:
            ax.plot([0.0], [axis_y], "r+", ms=14, mew=2, label="flexion axis (along z)")
            ax.legend(loc="lower right", fontsize=8)
        elif v == 1:
            ax.axhline(axis_y, color="r", lw=1.2, label="flexion axis")
            ax.legend(loc="lower right", fontsize=8)
        else:
            ax.axhline(0.0, color="r", lw=1.2, label="flexion axis (x = 0)")
            ax.legend(loc="lower right", fontsize=8)
    fig.suptitle(title + ": femoral component (blue) over the insert (yellow) as the run starts")
    fig.tight_layout()
    save_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
