"""kneesim compare at 5 Mc (rigid insert, stanmore rig, built-in implant) beside the materials
study's deformable FE of a Genesis II insert, as a prediction of contact mechanics and
kinematics (every pressure, area and range comes from the contact model, independent of the
study and of any wear factor) and of UHMWPE's wear (Pal 2008's factor). PEEK's and CFR-PEEK's
wear is compared only through the break-even ratio (the long case materials_break_even)."""
TITLE = "Materials: contact mechanics"
LONG = False

STUDY = {"uhmwpe": (124.0, 0.31, 13.4), "peek": (300.9, 0.89, 23.6), "cfr-peek": (15.6, 0.12, 36.1)}
KEY = {"uhmwpe": "uhmwpe", "peek": "peek", "cfr-peek": "cfrpeek"}


def run(v):
    d = v.kneesim("compare", ["compare", "--materials", "uhmwpe,peek,cfr-peek", "--no-plots", "--quiet",
                              "--no-break-even"])
    rows = {r["material"]: r for r in v.csv(d, "comparison.csv")}
    u = rows["uhmwpe"]
    for m, k in KEY.items():
        r = rows[m]
        for col, unit in (("volume_mm3", "mm3"), ("max_depth_mm", "mm"),
                          ("mean_peak_pressure_MPa", "MPa"), ("peak_pressure_MPa", "MPa"),
                          ("stance_mean_pressure_MPa", "MPa"), ("contact_area_mm2", "mm2"),
                          ("sliding_distance_mm", "mm"), ("cross_shear_ratio", ""),
                          ("ap_rom_mm", "mm"), ("ie_rom_deg", "deg")):
            v.figure(f"{k}_{col}", r[col], unit)
        v.figure(f"{k}_potential_kNmm", r["wear_potential_Nmm"] * 1e-3, "kN mm")
        v.figure(f"{k}_pressure_err_pct", 100 * (r["mean_peak_pressure_MPa"] / STUDY[m][2] - 1), "%")
        v.figure(f"{k}_pressure_ratio", r["mean_peak_pressure_MPa"] / u["mean_peak_pressure_MPa"], "")
        v.figure(f"{k}_potential_ratio", r["wear_potential_Nmm"] / u["wear_potential_Nmm"], "")
        # the material's rigid law and its stance figures against the deformable insert (the
        # calibration's runs of this load case: stanmore rig, shipped gait, pristine insert)
        law = v.json(d, m, "summary.json")["contact_law_calibration"]
        pv = law["provenance"]
        v.figure(f"{k}_law_source", law["source"])
        v.figure(f"{k}_law_ratio", law["foundation_modulus_MPa"] / law["specified_modulus_MPa"], "")
        for q in ("peak", "mean"):
            dq, cq = pv[f"stance_{q}_MPa_deformable"], pv[f"stance_{q}_MPa_calibrated"]
            v.figure(f"{k}_def_stance_{q}_MPa", dq, "MPa")
            v.figure(f"{k}_cal_stance_{q}_MPa", cq, "MPa")
            v.figure(f"{k}_cal_stance_{q}_err_pct", 100 * (cq / dq - 1), "%")
    v.figure("uhmwpe_volume_err_pct", 100 * (u["volume_mm3"] / STUDY["uhmwpe"][0] - 1), "%")
    v.figure("uhmwpe_depth_err_pct", 100 * (u["max_depth_mm"] / STUDY["uhmwpe"][1] - 1), "%")
    for m, k in (("peek", "peek"), ("cfr-peek", "cfrpeek")):
        v.figure(f"{k}_study_pressure_ratio", STUDY[m][2] / STUDY["uhmwpe"][2], "")


TABLE = """
Contact mechanics and kinematics, the pristine insert's settled cycle (predicted: independent of
any wear factor and of the study):

| quantity | UHMWPE | PEEK | CFR-PEEK |
|---|---|---|---|
| mean peak pressure MPa: study / kneesim | 13.4 / {uhmwpe_mean_peak_pressure_MPa:.1f} ({uhmwpe_pressure_err_pct:+.0f} %) | 23.6 / {peek_mean_peak_pressure_MPa:.1f} ({peek_pressure_err_pct:+.0f} %) | 36.1 / {cfrpeek_mean_peak_pressure_MPa:.1f} ({cfrpeek_pressure_err_pct:+.0f} %) |
| mean peak pressure ratio to UHMWPE: study / kneesim | 1 | {peek_study_pressure_ratio:.2f} / {peek_pressure_ratio:.2f} | {cfrpeek_study_pressure_ratio:.2f} / {cfrpeek_pressure_ratio:.2f} |
| peak pressure (MPa) | {uhmwpe_peak_pressure_MPa:.1f} | {peek_peak_pressure_MPa:.1f} | {cfrpeek_peak_pressure_MPa:.1f} |
| stance mean pressure, 0-60 % (MPa) | {uhmwpe_stance_mean_pressure_MPa:.1f} | {peek_stance_mean_pressure_MPa:.1f} | {cfrpeek_stance_mean_pressure_MPa:.1f} |
| contact area, mean over the cycle (mm²) | {uhmwpe_contact_area_mm2:.1f} | {peek_contact_area_mm2:.1f} | {cfrpeek_contact_area_mm2:.1f} |
| sliding distance per cycle (mm) | {uhmwpe_sliding_distance_mm:.1f} | {peek_sliding_distance_mm:.1f} | {cfrpeek_sliding_distance_mm:.1f} |
| cross-shear ratio | {uhmwpe_cross_shear_ratio:.3f} | {peek_cross_shear_ratio:.3f} | {cfrpeek_cross_shear_ratio:.3f} |
| AP / IE range (mm / deg) | {uhmwpe_ap_rom_mm:.2f} / {uhmwpe_ie_rom_deg:.2f} | {peek_ap_rom_mm:.2f} / {peek_ie_rom_deg:.2f} | {cfrpeek_ap_rom_mm:.2f} / {cfrpeek_ie_rom_deg:.2f} |
| rigid contact law (models/contact_laws/generic_*.toml): source, K_eff / K | {uhmwpe_law_source}, {uhmwpe_law_ratio:.3f} | {peek_law_source}, {peek_law_ratio:.3f} | {cfrpeek_law_source}, {cfrpeek_law_ratio:.3f} |
| stance (0-60 %) peak pressure MPa: deformable insert / calibrated rigid (the law's calibration runs) | {uhmwpe_def_stance_peak_MPa:.1f} / {uhmwpe_cal_stance_peak_MPa:.1f} ({uhmwpe_cal_stance_peak_err_pct:+.1f} %) | {peek_def_stance_peak_MPa:.1f} / {peek_cal_stance_peak_MPa:.1f} ({peek_cal_stance_peak_err_pct:+.1f} %) | {cfrpeek_def_stance_peak_MPa:.1f} / {cfrpeek_cal_stance_peak_MPa:.1f} ({cfrpeek_cal_stance_peak_err_pct:+.1f} %) |
| stance (0-60 %) mean pressure MPa: deformable / calibrated rigid | {uhmwpe_def_stance_mean_MPa:.2f} / {uhmwpe_cal_stance_mean_MPa:.2f} ({uhmwpe_cal_stance_mean_err_pct:+.1f} %) | {peek_def_stance_mean_MPa:.2f} / {peek_cal_stance_mean_MPa:.2f} ({peek_cal_stance_mean_err_pct:+.1f} %) | {cfrpeek_def_stance_mean_MPa:.2f} / {cfrpeek_cal_stance_mean_MPa:.2f} ({cfrpeek_cal_stance_mean_err_pct:+.1f} %) |
| wear potential per cycle (kN mm) and its ratio to UHMWPE | {uhmwpe_potential_kNmm:.1f} | {peek_potential_kNmm:.1f} ({peek_potential_ratio:.3f}) | {cfrpeek_potential_kNmm:.1f} ({cfrpeek_potential_ratio:.3f}) |

UHMWPE's wear, a prediction from Pal 2008's factor (PEEK's and CFR-PEEK's shipped factors are
the study's own volume ratios: their volumes are not predictions, see the break-even below):

| quantity | study | kneesim |
|---|---|---|
| UHMWPE volume at 5 Mc (mm³) | 124.0 | {uhmwpe_volume_mm3:.1f} ({uhmwpe_volume_err_pct:+.0f} %) |
| UHMWPE max depth at 5 Mc (mm) | 0.31 | {uhmwpe_max_depth_mm:.3f} ({uhmwpe_depth_err_pct:+.0f} %) |
"""
