"""kneesim calibrate-contact: the rigid elastic-foundation law p = K_eff g^n fitted to the
deformable insert (the converged footprint-refined reference mesh) on 0-30 % of the cycle and
judged held out on 30-60 %, per material on the built-in and DM implants (default stanmore rig),
and UHMWPE's fit with the exponent fixed at 1 (the modulus alone) against the same deformable
run."""
import os

TITLE = "Calibrated rigid contact law, every material, generic and DM implants"
LONG = True  # seven fits of about 200 short rigid runs each (10-20 minutes) against the deformable
# runs tools/scripts/calibrate_contact_laws.sh left in build/contact_laws, and gen_cfr's own
# deformable cycle (the script's CFR-PEEK run lies on finer surfaces); without the script's runs
# five deformable cycles on about 50 000 elements more (30-60 minutes)
IMAGES = {"docs/img/contact_calibration_uhmwpe.png": "gen_uhmwpe/calibration.png",
          "docs/img/contact_calibration_dm_uhmwpe.png": "dm_uhmwpe/calibration.png"}

DM = "models/examples/dm_stanmore.toml"
# (key, config, material, the calibrate_contact_laws.sh run of the same law, extra arguments);
# gen_cfr is the built-in implant's CFR-PEEK fitted against a reference on the default surfaces,
# which the shipped law is not (contact_calibration_cfr: its reference lies on finer ones)
RUNS = [("gen_uhmwpe", [], "uhmwpe", "generic_uhmwpe", []),
        ("gen_uhmwpe_n1", [], "uhmwpe", "generic_uhmwpe", ["--exponent", "1"]),
        ("gen_peek", [], "peek", "generic_peek", []), ("gen_cfr", [], "cfr-peek", None, []),
        ("dm_uhmwpe", [DM], "uhmwpe", "dm_uhmwpe", []), ("dm_peek", [DM], "peek", "dm_peek", []),
        ("dm_cfr", [DM], "cfr-peek", "dm_cfr-peek", [])]


def deformable_run(v, key, script_run):
    """The deformable reference run to fit against: the one tools/scripts/calibrate_contact_laws.sh
    made for the shipped law (build/contact_laws/<implant>_<material>/deformable) when it is there
    (calibrate-contact --deformable-from refuses a run of other settings; a deformable run is
    deterministic, so it is the run this case would make), else the case's own first fit of this
    law (gen_uhmwpe_n1 reuses gen_uhmwpe's), else none: calibrate-contact runs it."""
    shipped = os.path.join(v.build, "contact_laws", script_run or "", "deformable")
    if script_run and os.path.isfile(os.path.join(shipped, "summary.json")):
        return ["--deformable-from", shipped]
    own = {"gen_uhmwpe_n1": "gen_uhmwpe"}.get(key)
    if own:
        return ["--deformable-from", os.path.join(own, "deformable")]
    return []


def record_fit(v, key, d):
    """The figures of one calibrate-contact run in folder d, named after key."""
    s = v.json(d, "summary.json")
    v.figure(f"{key}_ratio", s["modulus_ratio"])
    v.figure(f"{key}_exponent", s["calibrated_exponent"])
    v.figure(f"{key}_elements", s["deformable_elements"])
    v.figure(f"{key}_at_bound", "yes" if s["fit_at_search_bound"] else "no")
    for w, wk in (("fit", "fit_window_0_30pct"), ("held", "held_out_30_60pct"), ("stance", "stance_0_60pct")):
        for q in ("peak_pressure_rms", "mean_pressure_rms", "contact_area_rms"):
            v.figure(f"{key}_{w}_{q}_spec_pct", 100 * s[wk]["rigid_as_specified"][q], "%")
            v.figure(f"{key}_{w}_{q}_cal_pct", 100 * s[wk]["rigid_calibrated"][q], "%")
    # the stance (0-60 %) figures over the frames in contact, as calibrate-contact and compare
    # compute them (a frame out of contact would pull a mean towards zero)
    for src, sk in (("rigid", "rigid_as_specified"), ("calibrated", "rigid_calibrated"),
                    ("deformable", "deformable")):
        f = s["stance_figures"][sk]
        v.figure(f"{key}_{src}_stance_peak_MPa", f["mean_peak_MPa"], "MPa")
        v.figure(f"{key}_{src}_stance_mean_MPa", f["mean_MPa"], "MPa")
        v.figure(f"{key}_{src}_stance_area_mm2", f["area_mm2"], "mm2")
        v.figure(f"{key}_{src}_peak_MPa", f["peak_MPa"], "MPa")
    v.figure(f"{key}_k_spec_MPa", s["specified_modulus_MPa"], "MPa")
    v.figure(f"{key}_k_cal_MPa", s["calibrated_modulus_MPa"], "MPa")


def run(v):
    v.require_data("gc6_dm/femoral_component.stl")
    for key, cfg, material, script_run, extra in RUNS:
        args = (["calibrate-contact"] + [v.source + "/" + c for c in cfg] + ["--material", material] + extra)
        # the footer shows the command without the reused deformable run (the same run: see
        # deformable_run), so that it does not depend on what build/ already holds
        d = v.kneesim(key, args + deformable_run(v, key, script_run), record=args)
        record_fit(v, key, d)


def _row(label, key):
    return (f"| {label} | {{{key}_elements}} | {{{key}_ratio:.3f}} | {{{key}_exponent:.3f}} | "
            f"{{{key}_held_peak_pressure_rms_spec_pct:.1f}} -> {{{key}_held_peak_pressure_rms_cal_pct:.1f}} % | "
            f"{{{key}_held_mean_pressure_rms_spec_pct:.1f}} -> {{{key}_held_mean_pressure_rms_cal_pct:.1f}} % | "
            f"{{{key}_held_contact_area_rms_spec_pct:.1f}} -> {{{key}_held_contact_area_rms_cal_pct:.1f}} % | "
            f"{{{key}_rigid_peak_MPa:.1f}} / {{{key}_calibrated_peak_MPa:.1f}} / {{{key}_deformable_peak_MPa:.1f}} | "
            f"{{{key}_rigid_stance_mean_MPa:.2f}} / {{{key}_calibrated_stance_mean_MPa:.2f}} / {{{key}_deformable_stance_mean_MPa:.2f}} | "
            f"{{{key}_at_bound}} |")


# the head of the one-row-per-law table (contact_calibration_cfr's too)
ALL_HEAD = ("\n| implant, material | reference elements | K_eff / K | n | peak pressure, held out: "
            "specified -> calibrated | mean pressure, held out | contact area, held out | stance "
            "peak pressure: specified / calibrated / deformable (MPa) | stance mean pressure: "
            "specified / calibrated / deformable (MPa) | fit at a search bound |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n")


def _detail(key):
    k = key
    return f"""
| | rigid as specified | rigid calibrated | deformable |
|---|---|---|---|
| stance (0-60 %) peak pressure | {{{k}_rigid_peak_MPa:.1f}} MPa | {{{k}_calibrated_peak_MPa:.1f}} MPa | {{{k}_deformable_peak_MPa:.1f}} MPa |
| stance mean of the frame peak pressure | {{{k}_rigid_stance_peak_MPa:.1f}} MPa | {{{k}_calibrated_stance_peak_MPa:.1f}} MPa | {{{k}_deformable_stance_peak_MPa:.1f}} MPa |
| stance mean contact pressure | {{{k}_rigid_stance_mean_MPa:.2f}} MPa | {{{k}_calibrated_stance_mean_MPa:.2f}} MPa | {{{k}_deformable_stance_mean_MPa:.2f}} MPa |
| stance mean contact area | {{{k}_rigid_stance_area_mm2:.0f}} mm² | {{{k}_calibrated_stance_area_mm2:.0f}} mm² | {{{k}_deformable_stance_area_mm2:.0f}} mm² |
| peak pressure error, fitted 0-30 % / held out 30-60 % / stance | {{{k}_fit_peak_pressure_rms_spec_pct:.1f}} / {{{k}_held_peak_pressure_rms_spec_pct:.1f}} / {{{k}_stance_peak_pressure_rms_spec_pct:.1f}} % | {{{k}_fit_peak_pressure_rms_cal_pct:.1f}} / {{{k}_held_peak_pressure_rms_cal_pct:.1f}} / {{{k}_stance_peak_pressure_rms_cal_pct:.1f}} % | |
| mean pressure error, fitted / held out / stance | {{{k}_fit_mean_pressure_rms_spec_pct:.1f}} / {{{k}_held_mean_pressure_rms_spec_pct:.1f}} / {{{k}_stance_mean_pressure_rms_spec_pct:.1f}} % | {{{k}_fit_mean_pressure_rms_cal_pct:.1f}} / {{{k}_held_mean_pressure_rms_cal_pct:.1f}} / {{{k}_stance_mean_pressure_rms_cal_pct:.1f}} % | |
| contact area error, fitted / held out / stance | {{{k}_fit_contact_area_rms_spec_pct:.1f}} / {{{k}_held_contact_area_rms_spec_pct:.1f}} / {{{k}_stance_contact_area_rms_spec_pct:.1f}} % | {{{k}_fit_contact_area_rms_cal_pct:.1f}} / {{{k}_held_contact_area_rms_cal_pct:.1f}} / {{{k}_stance_contact_area_rms_cal_pct:.1f}} % | |
"""


TABLES = {
    "uhmwpe": """
Default implant and rig, UHMWPE, the reference mesh ({gen_uhmwpe_elements} elements): K {gen_uhmwpe_k_spec_MPa:.0f} MPa
and n = 1 as specified; calibrated K_eff = {gen_uhmwpe_k_cal_MPa:.0f} MPa ({gen_uhmwpe_ratio:.3f} K) and
n = {gen_uhmwpe_exponent:.3f} (at a search bound: {gen_uhmwpe_at_bound}).
""" + _detail("gen_uhmwpe") + """
The same deformable run fitted with the exponent fixed at 1 (`--exponent 1`, the modulus alone):
K_eff = {gen_uhmwpe_n1_ratio:.3f} K.
""" + _detail("gen_uhmwpe_n1"),
    "all": ALL_HEAD + "\n".join(_row(label, key) for label, key in (
        ("generic, UHMWPE", "gen_uhmwpe"), ("generic, UHMWPE, n fixed at 1", "gen_uhmwpe_n1"),
        ("generic, PEEK", "gen_peek"),
        ("generic, CFR-PEEK, reference on the default 1 mm facets (not the shipped law)", "gen_cfr"),
        ("DM, UHMWPE", "dm_uhmwpe"), ("DM, PEEK", "dm_peek"), ("DM, CFR-PEEK", "dm_cfr"))) + "\n",
}
