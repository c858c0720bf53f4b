"""Plots of a `kneesim particles` run: size histogram, mean size vs iteration, the run-in
(track and counterface roughness, particle volume), and the contact pressure map with a von
Mises section. Usage: particles.py OUT_DIR (reads its CSV/JSON)."""
import csv
import json
import os
import sys

import matplotlib
import matplotlib.pyplot as plt

from plotio import readable_log_axis, save_figure  # noqa: E402


def read_table(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in (rows[0].keys() if rows else [])}


def read_map(path):
    with open(path) as f:
        return [[float(v) for v in line.split(",")] for line in f if line.strip()]


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    parts = read_table(os.path.join(out, "particles.csv"))
    its = read_table(os.path.join(out, "iterations.csv"))
    title = f"{summary['pair']} at {summary['load_N']:g} N"

    # size histogram of the particles summary.json reports: those of the steady window
    # (iterations from steady_from_iteration on), not the run-in's
    first = summary.get("steady_from_iteration", 1)
    keep = [i for i, it in enumerate(parts.get("iteration", [])) if it >= first]
    fig, ax = plt.subplots(figsize=(6, 4))
    if keep:
        ax.hist([[parts[k][i] for i in keep] for k in ("eq_radius_nm", "length_nm", "thickness_nm")],
                bins=30, label=["equivalent radius", "length", "thickness"], histtype="step")
        ax.axvspan(100, 1000, color="0.9", zorder=0, label="0.1-1 um (most active)")
        ax.legend()
    else:
        ax.text(0.5, 0.5, "no particles in the steady window: no yielded region reaches the "
                "surface", ha="center", va="center", transform=ax.transAxes, wrap=True)
    ax.set_xlabel("size [nm]")
    ax.set_ylabel("particles")
    ax.set_title(f"{title}\n{len(keep)} particles of iterations {first}-{len(its.get('iteration', []))} "
                 f"(the steady window of summary.json; {len(parts.get('iteration', []))} in all)",
                 fontsize=9)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "size_histogram.png"))

    # mean size vs iteration
    fig, ax = plt.subplots(figsize=(6, 4))
    if its:
        ax.plot(its["iteration"], its["mean_eq_radius_nm"], "o-",
                label="mean equivalent radius (left axis)")
        ax2 = ax.twinx()
        ax2.plot(its["iteration"], its["particles"], "s--", color="tab:orange",
                 label="particles per iteration (right axis)")
        ax2.set_ylabel("particles per iteration")
        # one legend for the lines of both axes
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="best")
    ax.axvline(summary.get("steady_from_iteration", 1), color="0.5", ls=":")
    ax.set_xlabel("iteration")
    ax.set_ylabel("mean equivalent radius [nm]")
    ax.set_title(title + " (dotted: start of the reported window)")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "mean_size_vs_iteration.png"))

    # run-in: rms roughness of the worn track and of the counterface (its film flattens when
    # it flows with the disk), and the material the track loses per iteration
    if its and "track_rq_nm" in its:
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(its["iteration"], its["track_rq_nm"], "-", label="worn track Rq (left axis)")
        if "counterface_rq_nm" in its:
            ax.plot(its["iteration"], its["counterface_rq_nm"], "-",
                    label="counterface Rq (left axis)")
        ax.set_yscale("log")
        readable_log_axis(ax.yaxis)
        ax.set_xlabel("iteration")
        ax.set_ylabel("rms roughness [nm] (log scale)")
        ax2 = ax.twinx()
        ax2.plot(its["iteration"], its["particle_volume_um3"], ":", color="tab:red",
                 label="particle volume (right axis)")
        ax2.set_ylabel("particle volume per iteration [um^3]")
        ax.axvline(summary.get("steady_from_iteration", 1), color="0.5", ls=":")
        lines = ax.get_legend_handles_labels()
        lines2 = ax2.get_legend_handles_labels()
        ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="upper right")
        ax.set_title(title + ": run-in")
        fig.tight_layout()
        save_figure(fig, os.path.join(out, "run_in.png"))

    # pressure map and von Mises section
    p = read_map(os.path.join(out, "pressure_map_MPa.csv"))
    vm = read_map(os.path.join(out, "von_mises_section_MPa.csv"))
    dx = summary["dx_nm"] / 1000.0
    dz = summary["section_dz_nm"] / 1000.0
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
    nx, ny = len(p), len(p[0])
    im = a1.imshow([list(r) for r in zip(*p)], origin="lower", cmap="viridis",
                   extent=[0, nx * dx, 0, ny * dx], aspect="equal")
    fig.colorbar(im, ax=a1, label="pressure [MPa]")
    a1.set_xlabel("x (sliding) [um]")
    a1.set_ylabel("y [um]")
    a1.set_title("contact pressure (first iteration)")
    im = a2.imshow(vm, origin="upper", cmap="magma", extent=[0, nx * dx, len(vm) * dz, 0],
                   aspect="auto")
    fig.colorbar(im, ax=a2, label="von Mises [MPa]")
    sy = summary["softer"]["yield_GPa"] * 1000.0
    a2.contour([[v for v in r] for r in vm], levels=[sy], colors="cyan", origin="upper",
               extent=[0, nx * dx, len(vm) * dz, 0])
    a2.set_xlabel("x (sliding) [um]")
    a2.set_ylabel("depth [um]")
    a2.set_title(f"von Mises section at the peak pressure (cyan: yield {sy:.0f} MPa)")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "pressure_von_mises.png"))


if __name__ == "__main__":
    main(sys.argv[1])
