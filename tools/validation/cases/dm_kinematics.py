"""kneesim diagnose kinematics: the Grand Challenge DM subject's in-vivo AP and IE (fluoroscopy)
against the force-controlled stanmore rig driven by the measured flexion."""
TITLE = "Diagnosis of the DM in-vivo kinematics against the rig"
LONG = True  # 250 rig simulations: 1-5 minutes
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
        for p, val in c["params"].items():
            v.figure(f"{n}_{p}", val)


TABLE = """
| candidate | held-out RMSE (ap_mm units) | dAICc | fitted | verdict |
|---|---|---|---|---|
| measured mean (trivial) | **{trivial_heldout:.2f}** | | | |
| none (baseline, offsets only) | {none_heldout:.2f} | 0 | | reference |
| friction | {friction_heldout:.2f} | {friction_daicc:+.1f} | mu {friction_friction_coefficient:.3f} | not supported |
| restraint | {restraint_heldout:.2f} | {restraint_daicc:+.1f} | stiffness scale {restraint_restraint_stiffness_scale:.1f} (upper search bound 20), gap {restraint_restraint_gap_mm:.2f} mm | passed both gates, at a search bound: not named |
| load_convention | {load_convention_heldout:.2f} | {load_convention_daicc:+.1f} | s_AP = {load_convention_ap_force_scale:.2f}, d_AP = {load_convention_ap_force_shift_pct:.1f} %, s_IE = {load_convention_ie_torque_scale:.2f}, d_IE = {load_convention_ie_torque_shift_pct:.0f} % (lower search bound -25) | passed both gates, at a search bound: not named |

Named: `{effect}`; the baseline's gain against the measured mean is {baseline_gain_vs_trivial:.2f}.
"""
