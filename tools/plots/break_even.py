"""The break-even plot of `kneesim compare`: per material, the volume at the end of the run
against the wear-factor ratio to the reference material (each point a whole wear run with
geometry updates), the reference's volume, the break-even ratios (equal volume, equal maximum
depth), the ratio of the material's own factor (marked as the materials study's implied ratio
when it is not independent), and below it the published ranges of the ratio with citations.

usage: break_even.py COMPARISON_JSON OUT_PNG
"""
import json
import sys

from plotio import save_figure

X_LO, X_HI = 1e-3, 1e3
BAND_COLOURS = ["#4c72b0", "#dd8452", "#55a868", "#c44e52", "#8172b3", "#937860"]


def jump_text(m, target):
    """' (jumps by X % between a and b)' when the solve found the break-even as a jump of the
    result across the reference's inside a bracket narrower than its tolerance"""
    pct = m.get(f"{target}_jump_pct")
    if pct is None:
        return ""
    return (f" (jumps by {pct:.2g} % between {m[target + '_ratio_low']:.5g} and "
            f"{m[target + '_ratio_high']:.5g})")


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(sys.argv[1]) as f:
        data = json.load(f)["break_even"]
    ref = data["reference"]
    v_ref = data["reference_volume_mm3"]
    mc = data["cycles"] * 1e-6
    names = data.get("order") or list(data["materials"])
    bands = data.get("literature", [])
    rows = max([1] + [sum(1 for b in bands if b["material"] == m) for m in names])

    fig, axes = plt.subplots(2, len(names), figsize=(7.2 * len(names), 7.0 + 0.8 * rows),
                             sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": [3.0, 0.4 + 0.75 * rows]})
    for col, name in enumerate(names):
        m = data["materials"][name]
        ax, bx = axes[0][col], axes[1][col]
        done = [r for r in m["runs"] if r["complete"]]
        stopped = [r for r in m["runs"] if not r["complete"]]
        ax.plot([r["ratio"] for r in done], [r["volume_mm3"] for r in done], "o-", color="k",
                label=f"{name}: volume after {mc:g} Mc (each point a wear run)")
        ymax = max([v_ref] + [r["volume_mm3"] for r in done]) * 60.0  # room for the legend
        ymin = min([v_ref] + [r["volume_mm3"] for r in done if r["volume_mm3"] > 0]) / 3.0
        for r in stopped:
            top = max([v_ref] + [r["volume_mm3"] for r in done]) * 2.0
            ax.plot([r["ratio"]], [top], "x", color="crimson", ms=10, mew=2)
            when = (f"after {r['cycles'] * 1e-6:.2g} Mc" if r["cycles"] > 0
                    else "in the first update")
            ax.annotate(f"stopped {when}:\nworn through", (r["ratio"], top),
                        textcoords="offset points", xytext=(0, -30), ha="center", fontsize=8,
                        color="crimson")
        ax.axhline(v_ref, color="0.4", ls="--", lw=1,
                   label=f"{ref}: {v_ref:.1f} mm³ after {mc:g} Mc")
        lines = [(m["volume_ratio"], "-", "tab:green", "break-even, equal volume"
                  + jump_text(m, "volume")),
                 (m["max_depth_ratio"], ":", "tab:green", "break-even, equal max depth"
                  + jump_text(m, "max_depth"))]
        own = m["own_ratio"]
        own_label = (f"materials study's implied ratio {own:.3g} (back-calculated from its "
                     "volumes: not independent)" if not m["own_factor_independent"]
                     else f"{name}'s own wear factor, ratio {own:.3g}")
        for x, ls, colour, label in lines:
            if x is None:
                continue
            for a in (ax, bx):
                a.axvline(x, color=colour, ls=ls, lw=2)
            ax.plot([], [], color=colour, ls=ls, lw=2, label=f"{label}: {x:.3g}")
        for a in (ax, bx):
            a.axvline(own, color="tab:purple", ls="-.", lw=1.5)
        ax.plot([], [], color="tab:purple", ls="-.", lw=1.5, label=own_label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(X_LO, X_HI)
        ax.set_ylim(ymin, ymax)
        ax.set_ylabel(f"volume after {mc:g} Mc (mm³)")
        ax.set_title(f"{name}: wear against its wear-factor ratio to {ref}")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="upper left", framealpha=0.95)

        # published ranges, one row each, with the citation and what was read
        own_bands = [b for b in bands if b["material"] == name]
        for i, b in enumerate(own_bands):
            lo = X_LO if b["open_end"] == "low" else b["ratio_low"]
            hi = X_HI if b["open_end"] == "high" else b["ratio_high"]
            y = rows - 1 - i
            colour = BAND_COLOURS[i % len(BAND_COLOURS)]
            bx.barh(y, hi - lo, left=lo, height=0.3, color=colour, alpha=0.45,
                    edgecolor=colour)
            if b["open_end"] == "high":
                bx.annotate("", (X_HI, y), (b["ratio_low"] * 3, y),
                            arrowprops={"arrowstyle": "->", "color": colour})
            if b["open_end"] == "low":
                bx.annotate("", (X_LO, y), (b["ratio_high"] / 3, y),
                            arrowprops={"arrowstyle": "->", "color": colour})
            rng = ("≤ %g" % b["ratio_high"] if b["open_end"] == "low" else
                   "≥ %g" % b["ratio_low"] if b["open_end"] == "high" else
                   "%g-%g" % (b["ratio_low"], b["ratio_high"]))
            bx.text(1.3 * X_LO, y + 0.2, f"{b['citation']}: ratio {rng}", fontsize=8.5,
                    va="bottom", fontweight="bold", color=colour)
            bx.text(1.3 * X_LO, y - 0.2, b["conditions"][:100], fontsize=6.5, va="top",
                    color="0.25")
            for a in (ax,):
                a.axvspan(lo, hi, color=colour, alpha=0.07)
        if not own_bands:
            bx.text(1.3 * X_LO, 0, "no published range read for this material", fontsize=9)
        bx.set_ylim(-0.7, rows - 0.25)
        bx.set_yticks([])
        bx.set_xscale("log")
        bx.set_xlim(X_LO, X_HI)
        bx.set_xlabel(f"wear-factor ratio k_{name} / k_{ref}")
        bx.set_title("published ranges of the ratio (what the readable text states)", fontsize=9)
        bx.grid(alpha=0.3, axis="x", which="major")
    fig.suptitle("Break-even: below the green line the material wears less than "
                 f"{ref} on this implant and rig; the published ranges say where its factor may be",
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, sys.argv[2])


if __name__ == "__main__":
    main()
