"""Sensitivity of the AP and IE ranges of motion (and the medial share) to every rig parameter
that is this project's assumption or that the sources give two ways (Pal 2008's spring gap:
3.0 mm in its table, 2.5 mm in its text)."""
TITLE = "Rig parameters: sensitivity of the ranges to the assumed ones"
LONG = False

# (figure name, preset, --set values, label)
CASES = [
    ("stan_base", "stanmore", [], "stanmore as shipped"),
    ("stan_gap25", "stanmore", ["rig.restraint.gap_mm=2.5"], "spring gap 2.5 mm (Pal's text)"),
    ("stan_gap35", "stanmore", ["rig.restraint.gap_mm=3.5"], "spring gap 3.5 mm (table mean + 1 SD)"),
    ("stan_arm25", "stanmore", ["rig.restraint.spring_arm_mm=25"], "spring lever arm 25 mm"),
    ("stan_arm45", "stanmore", ["rig.restraint.spring_arm_mm=45"], "spring lever arm 45 mm"),
    ("stan_pivot0", "stanmore", ["rig.tibia_pivot_medial_mm=0"], "tibial VV/IE pivot central"),
    ("stan_pivot10", "stanmore", ["rig.tibia_pivot_medial_mm=10"], "tibial VV/IE pivot 10 mm medial"),
    ("stan_offset0", "stanmore", ["rig.axial_offset_mm=0"], "axial load line central"),
    ("stan_offset10", "stanmore", ["rig.axial_offset_mm=10"], "axial load line 10 mm medial"),
    ("ms_base", "materials_study", [], "materials_study as shipped"),
    ("ms_offset3", "materials_study", ["rig.axial_offset_mm=3"], "axial load line 3 mm medial"),
    ("ms_offset7", "materials_study", ["rig.axial_offset_mm=7"], "axial load line 7 mm medial"),
    ("ms_pivot5", "materials_study", ["rig.tibia_pivot_medial_mm=5"], "tibial IE axis 5 mm medial"),
    ("iso_base", "iso", [], "iso as shipped"),
    ("iso_gap2", "iso", ["rig.restraint.gap_mm=2"], "AP gap 2 mm"),
    ("iso_gap3", "iso", ["rig.restraint.gap_mm=3"], "AP gap 3 mm"),
    ("iso_kin", "iso", ["rig.restraint.k_inside_N_per_mm=4.65"], "AP stiffness inside the gap halved"),
    ("iso_iegap4", "iso", ["rig.restraint.ie_gap_deg=4"], "IE gap 4 deg"),
    ("iso_iegap8", "iso", ["rig.restraint.ie_gap_deg=8"], "IE gap 8 deg"),
]


def run(v):
    base = {}
    for name, preset, sets, _ in CASES:
        args = ["run", "--no-plots", "--quiet", "--set", f"rig.preset={preset}"]
        for s in sets:
            args += ["--set", s]
        s = v.json(v.kneesim(name, args), "summary.json")
        ap, ie, med = s["ap_rom_mm"], s["ie_rom_deg"], 100 * s["medial_fraction_stance"]
        v.figure(f"{name}_ap", ap, "mm")
        v.figure(f"{name}_ie", ie, "deg")
        v.figure(f"{name}_med", med, "%")
        if name.endswith("_base"):
            base[preset] = (ap, ie)
        b = base[preset]
        v.figure(f"{name}_dap", 100 * (ap / b[0] - 1), "%")
        v.figure(f"{name}_die", 100 * (ie / b[1] - 1), "%")


TABLE = """
| preset | change | AP range (mm) | IE range (deg) | medial share | AP / IE change |
|---|---|---|---|---|---|
""" + "\n".join(
    f"| `{preset}` | {label} | {{{n}_ap:.2f}} | {{{n}_ie:.2f}} | {{{n}_med:.1f}} % | "
    + ("" if n.endswith("_base") else f"{{{n}_dap:+.1f}} % / {{{n}_die:+.1f}} %") + " |"
    for n, preset, _, label in CASES) + "\n"
