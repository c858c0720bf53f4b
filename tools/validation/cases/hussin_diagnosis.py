"""kneesim diagnose bor on the Hussin 2024 block-on-ring points reconstructed under both readings
of the paper's error sign (analysis/diagnosis/data)."""
TITLE = "Diagnosis of the Hussin 2024 block-on-ring data"
LONG = False
IMAGES = {"docs/img/diagnosis_bor_hussin2024.png": "hussin_primary/diagnosis.png"}

FILES = {"primary": "analysis/diagnosis/data/hussin2024_bor.csv",
         "alt": "analysis/diagnosis/data/hussin2024_bor_underprediction.csv"}


def run(v):
    for key, rel in FILES.items():
        d = v.json(v.kneesim(f"hussin_{key}", ["diagnose", "bor", "--measured", v.source + "/" + rel]),
                   "diagnosis.json")
        v.figure(f"{key}_effect", d["effect"])
        ext = d["extended"]
        for p, val in ext["params"].items():
            v.figure(f"{key}_{p}", val)
            lo, hi = ext["params_ci95"][p]
            v.figure(f"{key}_{p}_lo", lo)
            v.figure(f"{key}_{p}_hi", hi)
        cands = {c["name"]: c for c in d["candidates"]}
        v.figure(f"{key}_daicc", cands[d["effect"]]["delta_aicc"])
        for name, c in cands.items():
            if name != "none":
                v.figure(f"{key}_{name}_daicc", c["delta_aicc"])
        rows = [r for r in v.csv(v.source, rel) if r["cycles"] == 200000]
        for load in (225, 130):
            vols = [r["volume_mm3"] for r in rows if r["load_N"] == load]
            v.figure(f"{key}_measured_200k_{load}_mm3", sum(vols) / len(vols), "mm3")
        v.figure(f"{key}_baseline_heldout_mm3", d["baseline"]["heldout_rmse"], "mm3")
        v.figure(f"{key}_extended_heldout_mm3", ext["heldout_rmse"], "mm3")
        v.figure(f"{key}_gain", d["gain"])
        v.figure(f"{key}_gain_vs_trivial", d["gain_vs_trivial"])
        det = d["detection"]
        v.figure(f"{key}_noise_rms_mm3", det["noise_rms"], "mm3")
        for lim in det["limits"]:
            tag = f"{key}_lim_{lim['effect']}{'p' if lim['direction'] > 0 else 'm'}"
            v.figure(tag, f"{lim['value']:.3g}" if lim["reached"] else f"not named up to {lim['value']:.3g}")
            v.figure(tag + "_ratio", lim["ratio_to_noise"])


TABLE = """
| file | reading | measured at 200k (225 / 130 N) | named | evidence | gain (vs baseline / vs measured mean) |
|---|---|---|---|---|---|
| `hussin2024_bor.csv` (**primary**) | the paper's: model above the measurement, measured = model / (1 + error) | {primary_measured_200k_225_mm3:.3f} / {primary_measured_200k_130_mm3:.3f} mm³ | **`{primary_effect}`**: N_i = {primary_incubation_cycles:.0f} [{primary_incubation_cycles_lo:.0f}, {primary_incubation_cycles_hi:.0f}] cycles, k = {primary_k_mm3_per_Nmm:.3g} [{primary_k_mm3_per_Nmm_lo:.3g}, {primary_k_mm3_per_Nmm_hi:.3g}] | dAICc {primary_daicc:.1f} (`running_in` {primary_running_in_daicc:+.1f}, at its lower bound; pressure {primary_pressure_dependent_wear_daicc:+.1f}) | {primary_gain:.3f} ({primary_baseline_heldout_mm3:.3f} -> {primary_extended_heldout_mm3:.3f} mm³) / {primary_gain_vs_trivial:.3f} |
| `hussin2024_bor_underprediction.csv` (alternative) | contrary to the sentence: model below, measured = model / (1 - error) | {alt_measured_200k_225_mm3:.3f} / {alt_measured_200k_130_mm3:.3f} mm³ | `{alt_effect}`: a = {alt_running_in_excess:.2f} [{alt_running_in_excess_lo:.2f}, {alt_running_in_excess_hi:.2f}] (N_r fixed), k = {alt_k_mm3_per_Nmm:.3g} [{alt_k_mm3_per_Nmm_lo:.3g}, {alt_k_mm3_per_Nmm_hi:.3g}] | dAICc {alt_daicc:.1f} (`incubation` {alt_incubation_daicc:+.1f}, pressure {alt_pressure_dependent_wear_daicc:+.1f}) | {alt_gain:.3f} ({alt_baseline_heldout_mm3:.3f} -> {alt_extended_heldout_mm3:.3f} mm³) / {alt_gain_vs_trivial:.3f} |

Detection limits (the smallest size named in 80 % of 20 data sets simulated with the fitted
error model, `detection` in diagnosis.json; signal / noise: the part of the effect the baseline
cannot absorb, RMS, over the fitted noise RMS, {primary_noise_rms_mm3:.4f} and {alt_noise_rms_mm3:.4f} mm³):

| candidate | parameter | primary | signal / noise | alternative | signal / noise |
|---|---|---|---|---|---|
| running_in | excess a | {primary_lim_running_inp} | {primary_lim_running_inp_ratio:.1f} | {alt_lim_running_inp} | {alt_lim_running_inp_ratio:.1f} |
| incubation | N_i [cycles] | {primary_lim_incubationp} | {primary_lim_incubationp_ratio:.1f} | {alt_lim_incubationp} | {alt_lim_incubationp_ratio:.1f} |
| pressure_dependent_wear | alpha > 0 | {primary_lim_pressure_dependent_wearp} | {primary_lim_pressure_dependent_wearp_ratio:.1f} | {alt_lim_pressure_dependent_wearp} | {alt_lim_pressure_dependent_wearp_ratio:.1f} |
| pressure_dependent_wear | alpha < 0 | {primary_lim_pressure_dependent_wearm} | {primary_lim_pressure_dependent_wearm_ratio:.1f} | {alt_lim_pressure_dependent_wearm} | {alt_lim_pressure_dependent_wearm_ratio:.1f} |
"""
