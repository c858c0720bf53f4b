"""The default run against its equilibrium and the rig's intent, and Pal 2008's ranges."""
TITLE = "Default run: ranges of motion, force balance, medial share, pressures"
LONG = False


def run(v):
    out = v.kneesim("run", ["run", "--no-plots", "--quiet"])
    s = v.json(out, "summary.json")
    v.figure("ap_rom_mm", s["ap_rom_mm"], "mm")
    v.figure("ie_rom_deg", s["ie_rom_deg"], "deg")
    v.figure("peak_axial_load_N", s["peak_axial_load_N"], "N")
    v.figure("contact_axial_force_N", s["contact_axial_force_at_peak_load_N"], "N")
    v.figure("force_balance_pct", 100 * (s["contact_axial_force_at_peak_load_N"] / s["peak_axial_load_N"] - 1), "%")
    v.figure("medial_share_pct", 100 * s["medial_fraction_stance"], "%")
    v.figure("mean_peak_pressure_MPa", s["mean_peak_pressure_MPa"], "MPa")
    v.figure("peak_pressure_MPa", s["peak_pressure_MPa"], "MPa")
    # the rigid law against the deformable insert over stance (0-60 %): this run's frames and
    # the deformable run of the same load case that the shipped law was calibrated on
    law = s["contact_law_calibration"]
    v.figure("law_source", law["source"])
    v.figure("law_ratio", law["foundation_modulus_MPa"] / law["specified_modulus_MPa"])
    v.figure("law_exponent", law["exponent"])
    rows = [r for r in v.csv(out, "kinematics.csv") if r["gait_pct"] <= 60.0 and r["contact_area_mm2"] > 0.0]
    p = law["provenance"]
    peak = max(r["peak_pressure_MPa"] for r in rows)
    mean = sum(r["mean_pressure_MPa"] for r in rows) / len(rows)
    v.figure("stance_peak_MPa", peak, "MPa")
    v.figure("stance_mean_MPa", mean, "MPa")
    v.figure("deformable_mesh", "%s; %d elements" % (p["deformable_mesh"], p["deformable_elements"]))
    v.figure("deformable_stance_peak_MPa", p["stance_peak_MPa_deformable"], "MPa")
    v.figure("deformable_stance_mean_MPa", p["stance_mean_MPa_deformable"], "MPa")
    v.figure("stance_peak_err_pct", 100 * (peak / p["stance_peak_MPa_deformable"] - 1), "%")
    v.figure("stance_mean_err_pct", 100 * (mean / p["stance_mean_MPa_deformable"] - 1), "%")


TABLE = """
| quantity | reference | kneesim | summary.json key |
|---|---|---|---|
| AP / IE range of motion (joint coordinates) | Pal 2008 (NexGen CR, 1000-trial MC): 9.68 [7.59, 12.34] mm / 10.11 [7.66, 13.85] deg | {ap_rom_mm:.2f} mm / {ie_rom_deg:.2f} deg | `ap_rom_mm`, `ie_rom_deg` |
| axial contact force at the peak load vs the applied axial force | {peak_axial_load_N:.1f} N (equilibrium) | {contact_axial_force_N:.1f} N ({force_balance_pct:+.2f} %) | `contact_axial_force_at_peak_load_N`, `peak_axial_load_N` |
| medial share of the contact force over stance (0-60 %) | about 60 % (5 mm medial IE/VV axis, the rig's intent) | {medial_share_pct:.1f} % | `medial_fraction_stance` |
| mean peak pressure / peak pressure | Pal 2008: peak 25.71 [23.94, 27.67] MPa | {mean_peak_pressure_MPa:.1f} / {peak_pressure_MPa:.1f} MPa | `mean_peak_pressure_MPa`, `peak_pressure_MPa` |
| rigid contact law | the law calibrated against the deformable insert (models/contact_laws/generic_uhmwpe.toml) | source {law_source}, p = K_eff g^n with K_eff = {law_ratio:.3f} K, n = {law_exponent:.3f} | `contact_law_calibration` |
| stance (0-60 %) peak / mean contact pressure against the deformable insert ({deformable_mesh}) of the same load case | deformable: {deformable_stance_peak_MPa:.1f} / {deformable_stance_mean_MPa:.1f} MPa; acceptance within 15 % | {stance_peak_MPa:.1f} / {stance_mean_MPa:.1f} MPa ({stance_peak_err_pct:+.1f} / {stance_mean_err_pct:+.1f} %) | `kinematics.csv`, law provenance |
"""
