"""kneesim diagnose kinematics: the Grand Challenge DM subject's in-vivo AP and IE (fluoroscopy)
against the force-controlled stanmore rig driven by the measured flexion."""
import math

TITLE = "Diagnosis of the DM in-vivo kinematics against the rig"
LONG = True  # about 380 rig simulations (detection limits included): 2-6 minutes
# a wall time on a shared machine: recorded, not compared (119-406 s between two runs of one build)
NOISY = {"seconds": math.inf}
IMAGES = {"docs/img/diagnosis_kinematics_dm.png": "dm/diagnosis.png"}


def run(v):
    sto = v.require_data("gc6_dm/fluoroscopic_gait.sto")
    d = v.json(v.kneesim("dm", ["diagnose", "kinematics", "--measured", sto, "--config",
                                v.source + "/models/examples/dm_stanmore.toml"]), "diagnosis.json")
    v.commands[-1] = v.commands[-1].replace(sto, "$KNEESIM_DATA/gc6_dm/fluoroscopic_gait.sto")
    v.figure("effect", d["effect"])
    v.figure("trivial_heldout", d["trivial"]["heldout_rmse"], "mm")
    v.figure("baseline_gain_vs_trivial", d["baseline_gain_vs_trivial"])
    for c in d["candidates"]:
        n = c["name"]
        v.figure(f"{n}_heldout", c["heldout_rmse"], "mm")
        v.figure(f"{n}_daicc", c["delta_aicc"])
        v.figure(f"{n}_verdict", c["verdict"])
        for p, val in c["params"].items():
            v.figure(f"{n}_{p}", val)
    nz = d["candidates"][0]["noise"]
    v.figure("ell_pct", nz["correlation_length"], "% of the gait cycle")
    v.figure("white_fraction", nz["white_fraction"])
    v.figure("n_eff", nz["n_eff"])
    for name, val in d["candidates"][0]["nuisance"].items():
        v.figure(f"none_{name}", val, "mm")
    v.figure("seconds", d["seconds"], "s")
    det = d["detection"]
    v.figure("noise_rms", det["noise_rms"], "mm")
    for lim in det["limits"]:
        tag = f"lim_{lim['effect']}_{lim['param']}{'p' if lim['direction'] > 0 else 'm'}"
        v.figure(tag, f"{lim['value']:.3g}" if lim["reached"] else f"not named up to {lim['value']:.3g}")
        v.figure(tag + "_ratio", lim["ratio_to_noise"])


TABLE = """
| candidate | held-out RMSE (ap_mm units) | dAICc | fitted | verdict |
|---|---|---|---|---|
| measured mean (trivial) | **{trivial_heldout:.2f}** | | | |
| none (baseline, offsets only) | {none_heldout:.2f} | 0 | | reference |
| friction | {friction_heldout:.2f} | {friction_daicc:+.1f} | mu {friction_friction_coefficient:.3f} | {friction_verdict} |
| restraint | {restraint_heldout:.2f} | {restraint_daicc:+.1f} | stiffness scale {restraint_restraint_stiffness_scale:.1f} (search bounds 0.05-20), gap {restraint_restraint_gap_mm:.2f} mm | {restraint_verdict} |
| load_convention | {load_convention_heldout:.2f} | {load_convention_daicc:+.1f} | s_AP = {load_convention_ap_force_scale:.2f}, d_AP = {load_convention_ap_force_shift_pct:.1f} %, s_IE = {load_convention_ie_torque_scale:.2f}, d_IE = {load_convention_ie_torque_shift_pct:.0f} % (search bounds +-25 %) | {load_convention_verdict} |

Named: `{effect}`; the baseline's gain against the measured mean is {baseline_gain_vs_trivial:.2f}.

Error model of `none` (`instrument`): correlation length {ell_pct:.1f} % of the cycle, white
fraction {white_fraction:.2f}, n_eff {n_eff:.1f}, rotation-centre offset {none_rotation_centre_mm:+.2f} mm;
fitted noise RMS {noise_rms:.3f} (ap_mm units). Detection limits (the parameter's value at the
limit; null values: the model's friction and gap, scales 1, delays 0):

| candidate parameter | limit above the null value | signal / noise | limit below | signal / noise |
|---|---|---|---|---|
| friction mu | {lim_friction_friction_coefficientp} | {lim_friction_friction_coefficientp_ratio:.1f} | {lim_friction_friction_coefficientm} | {lim_friction_friction_coefficientm_ratio:.1f} |
| restraint stiffness scale | {lim_restraint_restraint_stiffness_scalep} | {lim_restraint_restraint_stiffness_scalep_ratio:.1f} | {lim_restraint_restraint_stiffness_scalem} | {lim_restraint_restraint_stiffness_scalem_ratio:.1f} |
| restraint gap [mm] | {lim_restraint_restraint_gap_mmp} | {lim_restraint_restraint_gap_mmp_ratio:.1f} | {lim_restraint_restraint_gap_mmm} | {lim_restraint_restraint_gap_mmm_ratio:.1f} |
| load_convention s_AP | {lim_load_convention_ap_force_scalep} | {lim_load_convention_ap_force_scalep_ratio:.1f} | {lim_load_convention_ap_force_scalem} | {lim_load_convention_ap_force_scalem_ratio:.1f} |
| load_convention d_AP [%] | {lim_load_convention_ap_force_shift_pctp} | {lim_load_convention_ap_force_shift_pctp_ratio:.1f} | {lim_load_convention_ap_force_shift_pctm} | {lim_load_convention_ap_force_shift_pctm_ratio:.1f} |
| load_convention s_IE | {lim_load_convention_ie_torque_scalep} | {lim_load_convention_ie_torque_scalep_ratio:.1f} | {lim_load_convention_ie_torque_scalem} | {lim_load_convention_ie_torque_scalem_ratio:.1f} |
| load_convention d_IE [%] | {lim_load_convention_ie_torque_shift_pctp} | {lim_load_convention_ie_torque_shift_pctp_ratio:.1f} | {lim_load_convention_ie_torque_shift_pctm} | {lim_load_convention_ie_torque_shift_pctm_ratio:.1f} |

Diagnosis run time {seconds:.0f} s (detection limits included).
"""
