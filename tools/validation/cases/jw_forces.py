"""kneesim diagnose forces: the Grand Challenge JW knee's measured medial compartment force
against the stanmore rig driven by the same measured loads (two cycles, each held out)."""
import csv
import math
import os
import time

TITLE = "Diagnosis of the JW in-vivo compartment forces against the rig"
# the instrument error model's prior sds (analysis/diagnosis/forces_case.cpp, kGainCrosstalkSd):
# each cell's gain and each crosstalk fraction sd 0.02, so a gain difference sd 0.02 sqrt(2)
CROSSTALK_PRIOR_SD = 0.02
GAIN_DIFFERENCE_PRIOR_SD = 0.02 * math.sqrt(2.0)
LONG = True  # 94 rig simulations of 2 cycles, twice: 15-60 s
# a wall time on a shared machine: recorded, not compared (21-57 s between two runs of one build)
NOISY = {"wall_s": math.inf}
IMAGES = {"docs/img/forces_jw_diagnosis.png": "jw/diagnosis.png"}


def find(d, key):
    if isinstance(d, dict):
        if key in d:
            return d[key]
        for v in d.values():
            r = find(v, key)
            if r is not None:
                return r
    return None


def run(v):
    v.require_data("gc4_jw/ngait_og3_knee_forces.csv")
    t0 = time.time()
    d = v.json(v.kneesim("jw", ["diagnose", "forces"]), "diagnosis.json")
    v.figure("wall_s", time.time() - t0, "s")
    v.figure("effect", d["effect"])
    v.figure("trivial_heldout_N", d["trivial"]["heldout_rmse"], "N")
    v.figure("baseline_gain_vs_trivial", d["baseline_gain_vs_trivial"])
    for c in d["candidates"]:
        n = c["name"]
        v.figure(f"{n}_heldout_N", c["heldout_rmse"], "N")
        v.figure(f"{n}_daicc", c["delta_aicc"])
        v.figure(f"{n}_verdict", c["verdict"])
        for p, val in c["params"].items():
            v.figure(f"{n}_{p}", val)
    nz = d["candidates"][0]["noise"]
    v.figure("ell_s", nz["correlation_length"], "s")
    v.figure("white_fraction", nz["white_fraction"])
    v.figure("n_eff", nz["n_eff"])
    for name, val in d["candidates"][0]["nuisance"].items():
        v.figure(f"none_{name}", val)
    filt = d["forces"]["input_filter"]
    v.figure("cutoff_axial_Hz", filt["axial_force_N"]["cutoff_Hz"], "Hz")
    det = d["detection"]
    v.figure("noise_rms_N", det["noise_rms"], "N")
    for lim in det["limits"]:
        tag = f"lim_{lim['effect']}{'p' if lim['direction'] > 0 else 'm'}"
        v.figure(tag, f"{lim['value']:.3g}" if lim["reached"] else f"not named up to {lim['value']:.3g}")
        v.figure(tag + "_ratio", lim["ratio_to_noise"])
    shares = find(d, "medial_share") or {}
    for i, (cycle, s) in enumerate(sorted(shares.items()), 1):
        v.figure(f"cycle{i}_measured_share", s["measured"])
        v.figure(f"cycle{i}_rig_share", s["baseline"])
    # what the rig gets wrong: the measured minus the rig's medial force over phases of the cycle
    with open(os.path.join(v.dir, "jw", "residuals.csv")) as f:
        rows = [(float(r["gait_pct"]), float(r["measured"]) - float(r["baseline"]))
                for r in csv.DictReader(f)]
    v.figure("rows", len(rows))
    phase = lambda lo, hi: [e for pct, e in rows if lo <= pct < hi]
    v.figure("resid_mid_max_N", max(phase(20, 45)), "N")   # loading response and mid-stance
    v.figure("resid_hs_low_N", -min(phase(2, 6)), "N")     # just after heel strike
    v.figure("resid_po_low_N", -min(phase(63, 70)), "N")   # push-off
    cal = d["candidates"][0]["nuisance"]  # the calibration terms fitted to `none`
    ratios = [abs(cal["gain_difference"]) / GAIN_DIFFERENCE_PRIOR_SD,
              abs(cal["crosstalk_lateral_to_medial"]) / CROSSTALK_PRIOR_SD,
              abs(cal["crosstalk_medial_to_lateral"]) / CROSSTALK_PRIOR_SD]
    v.figure("calibration_prior_ratio_min", min(ratios))
    v.figure("calibration_prior_ratio_max", max(ratios))
    # the same diagnosis under independent residuals (what the error model changes)
    w = v.json(v.kneesim("jw_white", ["diagnose", "forces", "--noise-model", "white",
                                      "--detection-replicates", "0"]), "diagnosis.json")
    v.figure("white_effect", w["effect"])
    named = next((c for c in w["candidates"] if c["name"] == w["effect"]), w["candidates"][0])
    v.figure("white_param", next(iter(named["params"].values()), 0.0))
    v.figure("white_daicc", named["delta_aicc"])
    v.figure("white_none_heldout_N", w["candidates"][0]["heldout_rmse"], "N")
    v.figure("white_named_heldout_N", named["heldout_rmse"], "N")
    v.figure("white_gain_vs_trivial", w["gain_vs_trivial"])


TABLE = """
| candidate | held-out RMSE [N] | dAICc vs none | fitted | verdict |
|---|---|---|---|---|
| none (the rig) | {none_heldout_N:.1f} | 0 | | reference |
| trivial predictor (mean measured share x measured total) | {trivial_heldout_N:.1f} | | share from the training cycle | |
| load_line | {load_line_heldout_N:.1f} | {load_line_daicc:+.1f} | d = {load_line_load_line_shift_mm:.2f} mm | {load_line_verdict} |
| vv_moment | {vv_moment_heldout_N:.1f} | {vv_moment_daicc:+.1f} | A = {vv_moment_vv_stance_arm_mm:.2f} mm | {vv_moment_verdict} |
| vv_alignment | {vv_alignment_heldout_N:.1f} | {vv_alignment_daicc:+.1f} | a = {vv_alignment_femur_vv_deg:.2f} deg | {vv_alignment_verdict} |

Named: `{effect}`; the rig's gain against the trivial predictor is {baseline_gain_vs_trivial:.3f}.

| medial share in stance (total above 20 % of peak) | measured | rig |
|---|---|---|
| cycle 1 | {cycle1_measured_share:.3f} | {cycle1_rig_share:.3f} |
| cycle 2 | {cycle2_measured_share:.3f} | {cycle2_rig_share:.3f} |

Error model of `none` (`instrument`): correlation length {ell_s:.3f} s, white fraction
{white_fraction:.2f}, n_eff {n_eff:.1f}; medial reading offset {none_offset_N:.1f} N, drift
{none_drift_N_per_s:.1f} N/s, gain difference medial - lateral {none_gain_difference:+.3f},
crosstalk lateral to medial {none_crosstalk_lateral_to_medial:+.3f}, medial to lateral
{none_crosstalk_medial_to_lateral:+.3f}; the rig's axial input filtered at {cutoff_axial_Hz:.2f} Hz.

| candidate | detection limit + | signal / noise | detection limit - | signal / noise |
|---|---|---|---|---|
| load_line (d, mm) | {lim_load_linep} | {lim_load_linep_ratio:.1f} | {lim_load_linem} | {lim_load_linem_ratio:.1f} |
| vv_moment (A, mm) | {lim_vv_momentp} | {lim_vv_momentp_ratio:.1f} | {lim_vv_momentm} | {lim_vv_momentm_ratio:.1f} |
| vv_alignment (a, deg) | {lim_vv_alignmentp} | {lim_vv_alignmentp_ratio:.1f} | {lim_vv_alignmentm} | {lim_vv_alignmentm_ratio:.1f} |

Fitted noise RMS of the error model {noise_rms_N:.1f} N; the command's wall time {wall_s:.0f} s
(model build, rig simulations and detection limits included; on the shared 2-core machine).
"""

TABLES = {
    "residual": """
What the simulation gets wrong (the residual panel, `residuals.csv` of the command above):
the rig holds the load line where its tibial VV axis is, so its medial share is nearly
constant through stance; the measured medial force is up to {resid_mid_max_N:.0f} N higher in
loading response and mid-stance (20-45 % of the cycle) and up to {resid_hs_low_N:.0f} N
lower just after heel strike (2-6 %) and up to {resid_po_low_N:.0f} N lower at push-off
(63-70 %). The error is a time course, not a level: the mean share is nearly right.
""",
    "why": """
Why nothing is named, and what that means. Under the `instrument` error model the rig's
residual, a smooth curve over the cycle, is fitted as correlated error: a correlation length
of {ell_s:.2f} s over a 2.3 s record leaves an effective sample size of {n_eff:.1f}, and no
candidate lowers AICc. Under independent residuals (the second command) `{white_effect}` is
named: A = {white_param:.2f} mm, dAICc {white_daicc:.1f}, held-out {white_none_heldout_N:.1f} ->
{white_named_heldout_N:.1f} N, gain {white_gain_vs_trivial:.3f} against the trivial predictor;
under the error model the same lever does not lower AICc ({vv_moment_daicc:+.1f}, although it
predicts the held-out cycle better, {vv_moment_heldout_N:.1f} against {none_heldout_N:.1f} N):
once the residuals may be correlated over about {ell_s:.1f} s, its improvement of the fit no
longer pays for its parameter. The default is the error model: with correlated errors,
independent residuals overstate the evidence (AICc then counts {rows:.0f} correlated rows as
independent measurements, where they carry about as much information on a smooth effect as
n_eff). The calibration terms fitted to `none` are {calibration_prior_ratio_min:.1f}-{calibration_prior_ratio_max:.1f}
times their prior sd (gain difference 0.028, crosstalk 0.02): the record's medial share
differs from the rig's by about what the instrument's specification allows.
""",
}
