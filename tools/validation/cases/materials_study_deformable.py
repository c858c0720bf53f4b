"""UHMWPE, PEEK and CFR-PEEK under the materials_study rig, 5 Mc, with the deformable insert
(2 mm elements, 10 updates) and the rigid insert (10 and 20 updates), on the built-in implant
and on the Grand Challenge DM implant, next to the materials study's published figures
(a Genesis II insert, deformable FE): 124.0 / 300.9 / 15.6 mm3, 0.31 / 0.89 / 0.12 mm,
13.4 / 23.6 / 36.1 MPa, AP 6.7 mm and IE 9.1 deg predicted."""
TITLE = "Materials study with the deformable insert, built-in and DM implants"
LONG = True  # two deformable comparisons of three materials: 30 minutes to several hours

MATS = (("uhmwpe", "uhmwpe"), ("peek", "peek"), ("cfr-peek", "cfr"))
STUDY_P = {"uhmwpe": 13.4, "peek": 23.6, "cfr": 36.1}
COLS = ("mean_peak_pressure_MPa", "peak_pressure_MPa", "contact_area_mm2", "ap_rom_mm", "ie_rom_deg",
        "volume_mm3", "max_depth_mm")
SOLID = ("von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa", "plastic_strain_max_surface",
         "plastic_strain_max_subsurface")


def compare(v, name, cfg, extra):
    args = ["compare"] + cfg + ["--set", "rig.preset=materials_study"] + extra + ["--no-plots", "--quiet"]
    return {r["material"]: r for r in v.csv(v.kneesim(name, args), "comparison.csv")}


def run(v):
    v.require_data("gc6_dm/femoral_component.stl")
    for imp, cfg in (("gen", []), ("dm", [v.source + "/models/examples/dm_stanmore.toml"])):
        runs = {"r250": compare(v, f"{imp}_rigid_250k", cfg, []),
                "r500": compare(v, f"{imp}_rigid_500k", cfg, ["--cycles", "5000000", "--update-every", "500000"]),
                "d500": compare(v, f"{imp}_def_500k", cfg, ["--cycles", "5000000", "--update-every", "500000",
                                                           "--set", "insert=deformable",
                                                           "--set", "deformable.element_size_mm=2"])}
        for m, k in MATS:
            for run_key, rows in runs.items():
                r = rows[m]
                for c in COLS:
                    if c in r:
                        v.figure(f"{imp}_{k}_{run_key}_{c}", r[c])
                if run_key == "d500":
                    for c in SOLID:
                        v.figure(f"{imp}_{k}_d500_{c}", r[c])
            v.figure(f"{imp}_{k}_r250_p_err_pct", 100 * (runs["r250"][m]["mean_peak_pressure_MPa"] / STUDY_P[k] - 1), "%")
            v.figure(f"{imp}_{k}_d500_p_err_pct", 100 * (runs["d500"][m]["mean_peak_pressure_MPa"] / STUDY_P[k] - 1), "%")
            v.figure(f"{imp}_{k}_d500_vol_vs_rigid_pct",
                     100 * (runs["d500"][m]["volume_mm3"] / runs["r500"][m]["volume_mm3"] - 1), "%")


def _table(imp):
    rows = []
    def add(label, study, col, fmt, extra_r250="", extra_d500=""):
        for i, (m, k) in enumerate(MATS):
            lab = label if i == 0 else ""
            st = study[i] if study else ""
            rows.append(f"| {lab} | {m.upper()} | {st} | {{{imp}_{k}_r250_{col}:{fmt}}}{extra_r250.format(imp=imp, k=k)} "
                        f"| {{{imp}_{k}_r500_{col}:{fmt}}} | {{{imp}_{k}_d500_{col}:{fmt}}}{extra_d500.format(imp=imp, k=k)} |")
    add("mean peak pressure (MPa)", ("13.4", "23.6", "36.1"), "mean_peak_pressure_MPa", ".1f",
        " ({{{imp}_{k}_r250_p_err_pct:+.0f}} %)", " ({{{imp}_{k}_d500_p_err_pct:+.0f}} %)")
    add("peak pressure (MPa)", None, "peak_pressure_MPa", ".1f")
    add("contact area, mean over frames in contact (mm²)", None, "contact_area_mm2", ".1f")
    add("AP range (mm)", ("6.7 (measured 7.1)", "", ""), "ap_rom_mm", ".2f")
    add("IE range (deg)", ("9.1 (measured 9.3)", "", ""), "ie_rom_deg", ".2f")
    add("wear volume at 5 Mc (mm³)", ("124.0", "300.9", "15.6"), "volume_mm3", ".2f", "",
        " ({{{imp}_{k}_d500_vol_vs_rigid_pct:+.1f}} %)")
    add("max depth at 5 Mc (mm)", ("0.31", "0.89", "0.12"), "max_depth_mm", ".3f")
    for i, (m, k) in enumerate(MATS):
        rows.append(f"| {'von Mises max, surface / subsurface (MPa); plastic strain, surface / subsurface' if i == 0 else ''} "
                    f"| {m.upper()} | | | | {{{imp}_{k}_d500_von_mises_max_surface_MPa:.1f}} / {{{imp}_{k}_d500_von_mises_max_subsurface_MPa:.1f}}; "
                    f"{{{imp}_{k}_d500_plastic_strain_max_surface:.2g}} / {{{imp}_{k}_d500_plastic_strain_max_subsurface:.2g}} |")
    return ("\n| quantity | material | study | rigid, 250 000 | rigid, 500 000 | deformable, 500 000 |\n"
            "|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n\n(Percentages: pressures against the study, "
            "deformable volumes against the rigid insert at the same interval.)\n")


TABLES = {"generic": _table("gen"), "dm": _table("dm")}
