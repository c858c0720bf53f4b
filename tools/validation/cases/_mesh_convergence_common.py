"""Shared by the mesh convergence cases (a helper, not a case: its name starts with "_"): one
deformable gait cycle per mesh, the stance figures of its kinematics.csv, the change between
successive refinements and the table rows."""

FIGS = ("peak", "stance_peak", "stance_mean", "area")
# the same stance figures measured inside the contact line (kinematics.csv's line columns):
# the area inside the line interpolated from the nodes' femoral distance, and the normal force
# over it (docs/theory.md, "Deformable insert")
LINE_FIGS = ("line_mean", "line_area")

UNIFORM_2MM = ["--set", "deformable.element_size_mm=2"]


def refined(h, layers="6", grading="0.15"):
    """The footprint-refined mesh at surface size h (mm): `layers` through the thickness graded
    `grading` towards the surface, or layers = "0": the top layer as thick as h, each layer
    below at most 1.5 times the one above."""
    args = ["--set", f"deformable.element_size_mm={h}", "--set", f"deformable.layers={layers}"]
    if layers != "0":
        args += ["--set", f"deformable.grading={grading}"]
    return args + ["--set", "deformable.refine=contact"]


def stance(rows):
    st = [r for r in rows if r["gait_pct"] <= 60.0 and r["contact_area_mm2"] > 0]
    f = {"peak": max(r["peak_pressure_MPa"] for r in st),
         "stance_peak": sum(r["peak_pressure_MPa"] for r in st) / len(st),
         "stance_mean": sum(r["mean_pressure_MPa"] for r in st) / len(st),
         "area": sum(r["contact_area_mm2"] for r in st) / len(st)}
    if "contact_line_area_mm2" in st[0]:
        f["line_mean"] = sum(r["mean_pressure_line_MPa"] for r in st) / len(st)
        f["line_area"] = sum(r["contact_line_area_mm2"] for r in st) / len(st)
    return f


def one(v, name, material, extra, config=()):
    d = v.kneesim(name, ["run"] + list(config) + ["--cycles", "1", "--set", "insert=deformable",
                                                   "--set", f"material.name={material}",
                                                   "--set", "solver.threads=2"]
                  + extra + ["--no-plots", "--quiet"])
    s = v.json(d, "summary.json")
    f = stance(v.csv(d, "kinematics.csv"))
    f["elements"] = s["solid_elements"]
    f["seconds"] = s["seconds_per_cycle"]
    f["ke_pct"] = 100 * s["kinetic_to_internal_max"]
    return f


def sequence(v, m, material, meshes, config=(), changes_from=2):
    """Runs the meshes [(key, extra args)] in order and writes figures m_key_*; the change from
    the previous mesh (m_key_*_chg, %) for the meshes from index `changes_from` on, and the
    largest change of the last refinement (m_last_max_chg)."""
    runs = [(key, one(v, f"{m}_{key}", material, extra, config)) for key, extra in meshes]
    for key, f in runs:
        for k, val in f.items():
            v.figure(f"{m}_{key}_{k}", val)
    for i in range(max(changes_from, 1), len(runs)):
        (k0, f0), (k1, f1) = runs[i - 1], runs[i]
        for k in FIGS + LINE_FIGS:
            if k in f0 and k in f1:
                v.figure(f"{m}_{k1}_{k}_chg", 100 * (f1[k] / f0[k] - 1), "%")
    v.figure(f"{m}_last_max_chg",
             max(abs(100 * (runs[-1][1][k] / runs[-2][1][k] - 1)) for k in FIGS), "%")
    return runs


LINE_HEAD = ("| elements (surface size) | stance mean pressure, nodes' area (MPa) | inside the contact line (MPa) | "
             "stance contact area, nodes (mm²) | inside the contact line (mm²) |\n"
             "|---|---|---|---|---|\n")


def line_table(m, labels, changes_from=2):
    """The stance mean pressure and contact area by both measures, labels [(key, label)]."""
    t = LINE_HEAD
    for i, (key, label) in enumerate(labels):
        c = i >= changes_from
        cell = lambda k, d: (f"{{{m}_{key}_{k}:.{d}f}}" + (f" ({{{m}_{key}_{k}_chg:+.1f}} %)" if c else ""))
        t += (f"| {{{m}_{key}_elements:.0f}} ({label}) | {cell('stance_mean', 2)} | {cell('line_mean', 2)} | "
              f"{cell('area', 1)} | {cell('line_area', 1)} |\n")
    return t


HEAD = ("| elements (surface size) | peak pressure (MPa) | stance mean of the frame peak (MPa) | "
        "stance mean pressure (MPa) | stance contact area (mm²) | s per cycle | kinetic / internal max (%) |\n"
        "|---|---|---|---|---|---|---|\n")


def row(m, key, label, change):
    if not change:
        return (f"| {{{m}_{key}_elements:.0f}} ({label}) | {{{m}_{key}_peak:.1f}} | {{{m}_{key}_stance_peak:.1f}} | "
                f"{{{m}_{key}_stance_mean:.2f}} | {{{m}_{key}_area:.1f}} | {{{m}_{key}_seconds:.0f}} | "
                f"{{{m}_{key}_ke_pct:.2f}} |\n")
    return (f"| {{{m}_{key}_elements:.0f}} ({label}) | {{{m}_{key}_peak:.1f}} ({{{m}_{key}_peak_chg:+.1f}} %) | "
            f"{{{m}_{key}_stance_peak:.1f}} ({{{m}_{key}_stance_peak_chg:+.1f}} %) | "
            f"{{{m}_{key}_stance_mean:.2f}} ({{{m}_{key}_stance_mean_chg:+.1f}} %) | "
            f"{{{m}_{key}_area:.1f}} ({{{m}_{key}_area_chg:+.1f}} %) | {{{m}_{key}_seconds:.0f}} | {{{m}_{key}_ke_pct:.2f}} |\n")


def table(m, title, labels, changes_from=2):
    """A material's table: labels [(key, label)] in the order run."""
    t = f"\n{title} (largest change between the last two refinements: {{{m}_last_max_chg:.1f}} %):\n\n" + HEAD
    for i, (key, label) in enumerate(labels):
        t += row(m, key, label, i >= changes_from)
    return t


def seconds_noisy(m, keys):
    """Timings vary with the machine's load: recorded, never compared."""
    import math
    return {f"{m}_{k}_seconds": math.inf for k in keys}
