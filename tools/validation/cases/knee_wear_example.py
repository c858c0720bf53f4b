"""kneesim diagnose knee-wear on synthetic knee-wear data with a hidden cross-shear gain g = 15
(tests/diagnosis_knee/knee_wear_example*.csv, made by the pristine-linear forward tables with
k = 2.643e-10 mm3/(N mm), 5 % specimen scatter and noise 0.2 mm3 + 2 %): the diagnosis must name
cross_shear and recover g."""
TITLE = "Knee-wear diagnosis of synthetic cross-shear data"
LONG = False
IMAGES = {"docs/img/diagnosis_knee_wear_synthetic_cross_shear.png": "kw_three/diagnosis.png"}

RUNS = [("three", "tests/diagnosis_knee/knee_wear_example.csv", []),
        ("two", "tests/diagnosis_knee/knee_wear_example_two_conditions.csv", ["--set", "implant.edge_length_mm=1"])]


def run(v):
    for key, rel, extra in RUNS:
        d = v.json(v.kneesim(f"kw_{key}", ["diagnose", "knee-wear", "--measured", v.source + "/" + rel,
                                           "--config", v.source + "/tests/diagnosis_knee/knee_conditions.toml"]
                             + extra + ["--geometry-states", "0"]), "diagnosis.json")
        ext = d["extended"]
        v.figure(f"{key}_effect", d["effect"])
        for p in ("cross_shear_gain", "k_mm3_per_Nmm"):
            v.figure(f"{key}_{p}", ext["params"][p])
            v.figure(f"{key}_{p}_lo", ext["params_ci95"][p][0])
            v.figure(f"{key}_{p}_hi", ext["params_ci95"][p][1])
        cands = {c["name"]: c["delta_aicc"] for c in d["candidates"]}
        v.figure(f"{key}_daicc", cands[d["effect"]])
        v.figure(f"{key}_pressure_daicc", cands.get("pressure_dependent_wear", float("nan")))
        v.figure(f"{key}_baseline_heldout_mm3", d["baseline"]["heldout_rmse"], "mm3")
        v.figure(f"{key}_extended_heldout_mm3", ext["heldout_rmse"], "mm3")
        v.figure(f"{key}_gain", d["gain"])


TABLE = """
| data | named | fitted g (hidden 15) [95 %] | k [95 %] (mm³/(N mm)) | dAICc | held-out RMSE baseline -> extended | gain |
|---|---|---|---|---|---|---|
| three conditions (`iso`, `low_ie`, `high_load`), 3 mm elements | `{three_effect}` | {three_cross_shear_gain:.1f} [{three_cross_shear_gain_lo:.1f}, {three_cross_shear_gain_hi:.1f}] | {three_k_mm3_per_Nmm:.4g} [{three_k_mm3_per_Nmm_lo:.3g}, {three_k_mm3_per_Nmm_hi:.3g}] | {three_daicc:.1f} (pressure {three_pressure_daicc:+.1f}) | {three_baseline_heldout_mm3:.2f} -> {three_extended_heldout_mm3:.2f} mm³ | {three_gain:.2f} |
| two conditions (`iso`, `low_ie`), 1 mm elements | `{two_effect}` | {two_cross_shear_gain:.1f} [{two_cross_shear_gain_lo:.1f}, {two_cross_shear_gain_hi:.1f}] | {two_k_mm3_per_Nmm:.4g} [{two_k_mm3_per_Nmm_lo:.3g}, {two_k_mm3_per_Nmm_hi:.3g}] | {two_daicc:.1f} | {two_baseline_heldout_mm3:.2f} -> {two_extended_heldout_mm3:.2f} mm³ | {two_gain:.2f} |
"""
