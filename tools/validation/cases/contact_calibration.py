"""kneesim calibrate-contact: the rigid elastic-foundation law fitted to the deformable insert on
0-30 % of the cycle and judged held out on 30-60 %, per material and implant (default stanmore
rig), with the mesh refinement that shows whether the deformable reference is converged."""
TITLE = "Calibrated rigid contact law, every material, generic and DM implants"
LONG = True  # nine deformable cycles and about 150 rigid runs: 20-60 minutes
IMAGES = {"docs/img/contact_calibration_uhmwpe.png": "gen_uhmwpe/calibration.png",
          "docs/img/contact_calibration_dm_uhmwpe.png": "dm_uhmwpe/calibration.png"}

DM = "models/examples/dm_stanmore.toml"
RUNS = [("gen_uhmwpe", [], "uhmwpe", None), ("dm_uhmwpe", [DM], "uhmwpe", None),
        ("gen_peek", [], "peek", None), ("dm_peek", [DM], "peek", None),
        ("gen_cfr", [], "cfr-peek", None), ("gen_cfr_15", [], "cfr-peek", "1.5"),
        ("dm_cfr", [DM], "cfr-peek", None), ("dm_cfr_15", [DM], "cfr-peek", "1.5"),
        ("dm_cfr_10", [DM], "cfr-peek", "1.0")]


def stance_mean(rows, col):
    s = [r[col] for r in rows if r["gait_pct"] <= 60.0]
    return sum(s) / len(s)


def run(v):
    v.require_data("gc6_dm/femoral_component.stl")
    for key, cfg, material, element in RUNS:
        args = ["calibrate-contact"] + [v.source + "/" + c for c in cfg] + ["--material", material]
        if element:
            args += ["--element-mm", element]
        d = v.kneesim(key, args)
        s = v.json(d, "summary.json")
        v.figure(f"{key}_ratio", s["modulus_ratio"])
        v.figure(f"{key}_at_bound", "yes" if s["fit_at_search_bound"] else "no")
        for w, wk in (("fit", "fit_window_0_30pct"), ("held", "held_out_30_60pct"), ("stance", "stance_0_60pct")):
            for q in ("peak_pressure_rms", "mean_pressure_rms", "contact_area_rms"):
                v.figure(f"{key}_{w}_{q}_spec_pct", 100 * s[wk]["rigid_as_specified"][q], "%")
                v.figure(f"{key}_{w}_{q}_cal_pct", 100 * s[wk]["rigid_calibrated"][q], "%")
        rows = v.csv(d, "comparison.csv")
        for src in ("rigid", "calibrated", "deformable"):
            v.figure(f"{key}_{src}_stance_peak_MPa", stance_mean(rows, f"{src}_peak_MPa"), "MPa")
            v.figure(f"{key}_{src}_stance_mean_MPa", stance_mean(rows, f"{src}_mean_MPa"), "MPa")
            v.figure(f"{key}_{src}_stance_area_mm2", stance_mean(rows, f"{src}_area_mm2"), "mm2")
            v.figure(f"{key}_{src}_peak_MPa", max(r[f"{src}_peak_MPa"] for r in rows), "MPa")
        v.figure(f"{key}_k_spec_MPa", s["specified_modulus_MPa"], "MPa")
        v.figure(f"{key}_k_cal_MPa", s["calibrated_modulus_MPa"], "MPa")


def _row(label, key):
    return (f"| {label} | {{{key}_ratio:.3f}} | {{{key}_held_peak_pressure_rms_spec_pct:.1f}} -> "
            f"{{{key}_held_peak_pressure_rms_cal_pct:.1f}} % | {{{key}_held_mean_pressure_rms_spec_pct:.1f}} -> "
            f"{{{key}_held_mean_pressure_rms_cal_pct:.1f}} % | {{{key}_held_contact_area_rms_spec_pct:.1f}} -> "
            f"{{{key}_held_contact_area_rms_cal_pct:.1f}} % | {{{key}_rigid_stance_peak_MPa:.1f}} / "
            f"{{{key}_calibrated_stance_peak_MPa:.1f}} / {{{key}_deformable_stance_peak_MPa:.1f}} | {{{key}_at_bound}} |")


TABLES = {
    "uhmwpe": """
Default implant and rig, UHMWPE, deformable insert of 2 mm elements: K {gen_uhmwpe_k_spec_MPa:.0f} MPa as
specified, K_eff = {gen_uhmwpe_k_cal_MPa:.0f} MPa ({gen_uhmwpe_ratio:.3f} K; at a search bound: {gen_uhmwpe_at_bound}).

| | rigid as specified | rigid calibrated | deformable |
|---|---|---|---|
| stance (0-60 %) mean of the frame peak pressure | {gen_uhmwpe_rigid_stance_peak_MPa:.1f} MPa | {gen_uhmwpe_calibrated_stance_peak_MPa:.1f} MPa | {gen_uhmwpe_deformable_stance_peak_MPa:.1f} MPa |
| peak pressure over the cycle | {gen_uhmwpe_rigid_peak_MPa:.1f} MPa | {gen_uhmwpe_calibrated_peak_MPa:.1f} MPa | {gen_uhmwpe_deformable_peak_MPa:.1f} MPa |
| stance mean contact pressure | {gen_uhmwpe_rigid_stance_mean_MPa:.1f} MPa | {gen_uhmwpe_calibrated_stance_mean_MPa:.1f} MPa | {gen_uhmwpe_deformable_stance_mean_MPa:.1f} MPa |
| stance mean contact area | {gen_uhmwpe_rigid_stance_area_mm2:.0f} mm² | {gen_uhmwpe_calibrated_stance_area_mm2:.0f} mm² | {gen_uhmwpe_deformable_stance_area_mm2:.0f} mm² |
| peak pressure error, fitted 0-30 % / held out 30-60 % / stance | {gen_uhmwpe_fit_peak_pressure_rms_spec_pct:.1f} / {gen_uhmwpe_held_peak_pressure_rms_spec_pct:.1f} / {gen_uhmwpe_stance_peak_pressure_rms_spec_pct:.1f} % | {gen_uhmwpe_fit_peak_pressure_rms_cal_pct:.1f} / {gen_uhmwpe_held_peak_pressure_rms_cal_pct:.1f} / {gen_uhmwpe_stance_peak_pressure_rms_cal_pct:.1f} % | |
| mean pressure error, fitted / held out / stance | {gen_uhmwpe_fit_mean_pressure_rms_spec_pct:.1f} / {gen_uhmwpe_held_mean_pressure_rms_spec_pct:.1f} / {gen_uhmwpe_stance_mean_pressure_rms_spec_pct:.1f} % | {gen_uhmwpe_fit_mean_pressure_rms_cal_pct:.1f} / {gen_uhmwpe_held_mean_pressure_rms_cal_pct:.1f} / {gen_uhmwpe_stance_mean_pressure_rms_cal_pct:.1f} % | |
| contact area error, fitted / held out / stance | {gen_uhmwpe_fit_contact_area_rms_spec_pct:.1f} / {gen_uhmwpe_held_contact_area_rms_spec_pct:.1f} / {gen_uhmwpe_stance_contact_area_rms_spec_pct:.1f} % | {gen_uhmwpe_fit_contact_area_rms_cal_pct:.1f} / {gen_uhmwpe_held_contact_area_rms_cal_pct:.1f} / {gen_uhmwpe_stance_contact_area_rms_cal_pct:.1f} % | |
""",
    "all": "\n| implant, material, elements | K_eff / K | peak pressure, held out: specified -> calibrated | mean pressure, held out | contact area, held out | stance mean of the frame peak: specified / calibrated / deformable (MPa) | fit at a search bound |\n|---|---|---|---|---|---|---|\n"
    + "\n".join(_row(label, key) for label, key in (
        ("generic, UHMWPE, 2 mm", "gen_uhmwpe"), ("DM, UHMWPE, 2 mm", "dm_uhmwpe"),
        ("generic, PEEK, 2 mm", "gen_peek"), ("DM, PEEK, 2 mm", "dm_peek"),
        ("generic, CFR-PEEK, 2 mm", "gen_cfr"), ("generic, CFR-PEEK, 1.5 mm", "gen_cfr_15"),
        ("DM, CFR-PEEK, 2 mm", "dm_cfr"), ("DM, CFR-PEEK, 1.5 mm", "dm_cfr_15"),
        ("DM, CFR-PEEK, 1.0 mm", "dm_cfr_10"))) + "\n",
}
