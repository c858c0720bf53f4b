"""The probabilistic study of the default model against Pal 2008: the 1000-trial Monte Carlo of
the kinematics, the 300-trial Monte Carlo of 5 Mc wear (10 geometry updates per trial), and the
advanced mean value method (AMV) against both."""
TITLE = "Probabilistic study against Pal 2008"
LONG = True  # 1000 kinematics trials, 300 wear trials and 24 AMV wear runs: 5-15 minutes on 2 cores
# the section's plots, copied from the runs (docs/validation.md#probabilistic-study-against-pal-2008)
IMAGES = {"docs/img/study_envelopes.png": "mc1000/envelopes.png",
          "docs/img/study_sensitivity.png": "mc1000/sensitivity.png",
          "docs/img/study_wear_envelopes.png": "mc300_wear/wear_envelopes.png"}

KIN = ("ap_rom_mm", "ie_rom_deg", "peak_pressure_MPa")
WEAR = ("max_linear_wear_mm", "gravimetric_wear_mg")
WEAR_ARGS = ["--wear", "--wear-cycles", "5000000", "--wear-updates", "10"]
INPUTS = [("friction", "contact.friction"), ("wear factor", "material.wear_factor_mm3_per_Nmm"),
          ("femoral FE axis AP", "rig.alignment.femur_fe_axis_ap_mm"),
          ("femoral FE axis IS", "rig.alignment.femur_fe_axis_is_mm"),
          ("femoral FE", "rig.alignment.femur_fe_deg"), ("femoral IE", "rig.alignment.femur_ie_deg"),
          ("femoral VV", "rig.femur_vv_deg"), ("insert tilt", "rig.alignment.insert_tilt_deg"),
          ("tibial IE axis AP", "rig.alignment.tibia_ie_axis_ap_mm"),
          ("tibial IE axis ML", "rig.alignment.tibia_ie_axis_ml_mm"),
          ("spring gap", "rig.restraint.gap_mm"), ("anterior spring", "rig.restraint.k_anterior_N_per_mm"),
          ("posterior spring", "rig.restraint.k_posterior_N_per_mm")]


def slug(label):
    return label.replace(" ", "_")


def sensitivities(v, folder, prefix, measures):
    for r in v.csv(folder, "sensitivity.csv"):
        for label, key in INPUTS:
            if r["parameter"] == key and r["measure"] in measures:
                v.figure(f"{prefix}_{slug(label)}_{r['measure']}", r["abs_corr"])


def run(v):
    mc = v.kneesim("mc1000", ["study", "--method", "mc", "--trials", "1000", "--seed", "1", "--quiet"])
    s = v.json(mc, "summary.json")
    for m in KIN:
        st = s["measures"][m]
        for k in ("mean", "sd", "p01", "p50", "p99"):
            v.figure(f"{m}_{k}", st[k])
        v.figure(f"{m}_width", st["p99"] - st["p01"])
    v.figure("trials_done", s["trials_done"])
    v.figure("trials_failed", s["trials_failed"])
    v.figure("retried", sum(1 for r in v.csv(mc, "trials.csv") if str(r["status"]).startswith("ok: step")))
    sensitivities(v, mc, "mc", KIN)

    w = v.kneesim("mc300_wear", ["study", "--method", "mc", "--trials", "300", "--seed", "2", "--quiet"] + WEAR_ARGS)
    s = v.json(w, "summary.json")
    for m in WEAR + KIN:
        st = s["measures"][m]
        for k in ("mean", "sd", "p01", "p99"):
            v.figure(f"w_{m}_{k}", st[k])
        v.figure(f"w_{m}_width", st["p99"] - st["p01"])
    v.figure("w_trials_done", s["trials_done"])
    v.figure("w_trials_failed", s["trials_failed"])
    v.figure("w_retried", sum(1 for r in v.csv(w, "trials.csv") if str(r["status"]).startswith("ok: step")))
    sensitivities(v, w, "w", WEAR)

    a = v.kneesim("amv_wear", ["study", "--method", "amv", "--quiet"] + WEAR_ARGS)
    s = v.json(a, "summary.json")
    for m in KIN + WEAR:
        st = s["measures"][m]
        v.figure(f"amv_{m}_p01", st["p01"])
        v.figure(f"amv_{m}_p99", st["p99"])
        v.figure(f"amv_{m}_p01_fo", st["p01_mean_value"])
        v.figure(f"amv_{m}_p99_fo", st["p99_mean_value"])
        v.figure(f"amv_{m}_width", st["p99"] - st["p01"])
        v.figure(f"amv_{m}_runs", st["runs"])
        mc_key = "" if m in KIN else "w_"
        for p in ("p01", "p99"):
            v.figure(f"amv_{m}_{p}_err_pct", 100 * (st[p] / v.figures[f"{mc_key}{m}_{p}"]["value"] - 1), "%")
    sensitivities(v, a, "amv", WEAR)


def _sens_rows(prefix, measures):
    return "\n".join(f"| {label} | " + " | ".join(f"{{{prefix}_{slug(label)}_{m}:.2f}}" for m in measures) + " |"
                     for label, _ in INPUTS)


def _amv_row(label, m, mc, fmt):
    return (f"| {label} | {{{mc}{m}_p01:{fmt}}} | {{amv_{m}_p01:{fmt}}} {{amv_{m}_p01_err_pct:+.1f}} % ({{amv_{m}_p01_fo:{fmt}}}) "
            f"| {{{mc}{m}_p99:{fmt}}} | {{amv_{m}_p99:{fmt}}} {{amv_{m}_p99_err_pct:+.1f}} % ({{amv_{m}_p99_fo:{fmt}}}) |")


TABLES = {
    "kinematics": """
| measure | kneesim mean (sd) | kneesim 1 % / 50 % / 99 % | kneesim 1-99 % width | Pal 2008 | Pal width |
|---|---|---|---|---|---|
| AP ROM (mm) | {ap_rom_mm_mean:.2f} ({ap_rom_mm_sd:.2f}) | {ap_rom_mm_p01:.2f} / {ap_rom_mm_p50:.2f} / {ap_rom_mm_p99:.2f} | {ap_rom_mm_width:.2f} | 9.68 [7.59, 12.34] | 4.75 |
| IE ROM (deg) | {ie_rom_deg_mean:.2f} ({ie_rom_deg_sd:.2f}) | {ie_rom_deg_p01:.2f} / {ie_rom_deg_p50:.2f} / {ie_rom_deg_p99:.2f} | {ie_rom_deg_width:.2f} | 10.11 [7.66, 13.85] | 6.19 |
| peak contact pressure (MPa) | {peak_pressure_MPa_mean:.2f} ({peak_pressure_MPa_sd:.2f}) | {peak_pressure_MPa_p01:.2f} / {peak_pressure_MPa_p50:.2f} / {peak_pressure_MPa_p99:.2f} | {peak_pressure_MPa_width:.2f} | 25.71 [23.94, 27.67] | 3.73 |

({trials_done:.0f} trials done, {trials_failed:.0f} failed; {retried:.0f} of them repeated once with the step the measured contact frequency allows.)
""",
    "sensitivity": "\n| input | AP ROM | IE ROM | peak pressure |\n|---|---|---|---|\n" + _sens_rows("mc", KIN) + "\n",
    "wear": """
| measure at 5 Mc | kneesim MC (300 trials) mean (sd) | 1 % / 99 % | 1-99 % width | kneesim AMV 1 % / 99 % (width) | Pal 2008 |
|---|---|---|---|---|---|
| max linear wear (mm) | {w_max_linear_wear_mm_mean:.3f} ({w_max_linear_wear_mm_sd:.3f}) | {w_max_linear_wear_mm_p01:.3f} / {w_max_linear_wear_mm_p99:.3f} | {w_max_linear_wear_mm_width:.3f} | {amv_max_linear_wear_mm_p01:.3f} / {amv_max_linear_wear_mm_p99:.3f} ({amv_max_linear_wear_mm_width:.3f}) | width 0.12, upper bound 0.37 |
| gravimetric wear (mg) | {w_gravimetric_wear_mg_mean:.1f} ({w_gravimetric_wear_mg_sd:.1f}) | {w_gravimetric_wear_mg_p01:.1f} / {w_gravimetric_wear_mg_p99:.1f} | {w_gravimetric_wear_mg_width:.1f} | {amv_gravimetric_wear_mg_p01:.1f} / {amv_gravimetric_wear_mg_p99:.1f} ({amv_gravimetric_wear_mg_width:.1f}) | width 24.8 (MC) / 20.4 (AMV); measured 78 and 97 |

({w_trials_done:.0f} trials done, {w_trials_failed:.0f} failed, {w_retried:.0f} with a shortened gait step.)
""",
    "wear_sensitivity": "\n| input | gravimetric wear, MC | max linear wear, MC | gravimetric wear, AMV | max linear wear, AMV |\n|---|---|---|---|---|\n"
    + "\n".join(f"| {label} | {{w_{slug(label)}_gravimetric_wear_mg:.2f}} | {{w_{slug(label)}_max_linear_wear_mm:.2f}} | "
                f"{{amv_{slug(label)}_gravimetric_wear_mg:.2f}} | {{amv_{slug(label)}_max_linear_wear_mm:.2f}} |" for label, _ in INPUTS) + "\n",
    "amv": "\n| measure | MC 1 % | AMV 1 % (first-order) | MC 99 % | AMV 99 % (first-order) |\n|---|---|---|---|---|\n"
    + "\n".join([_amv_row("AP ROM (mm)", "ap_rom_mm", "", ".2f"), _amv_row("IE ROM (deg)", "ie_rom_deg", "", ".2f"),
                 _amv_row("peak pressure (MPa)", "peak_pressure_MPa", "", ".2f"),
                 _amv_row("max linear wear (mm), wear MC", "max_linear_wear_mm", "w_", ".3f"),
                 _amv_row("gravimetric wear (mg), wear MC", "gravimetric_wear_mg", "w_", ".1f")])
    + "\n\nAMV runs per measure: {amv_ap_rom_mm_runs:.0f}.\n",
}
