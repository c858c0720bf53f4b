"""kneesim diagnose forces: the Grand Challenge JW knee's measured medial compartment force
against the stanmore rig driven by the same measured loads (two cycles, each held out)."""
TITLE = "Diagnosis of the JW in-vivo compartment forces against the rig"
LONG = True  # 56 rig simulations of 2 cycles: 1-3 minutes
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
    d = v.json(v.kneesim("jw", ["diagnose", "forces"]), "diagnosis.json")
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
    shares = find(d, "medial_share") or {}
    for i, (cycle, s) in enumerate(sorted(shares.items()), 1):
        v.figure(f"cycle{i}_measured_share", s["measured"])
        v.figure(f"cycle{i}_rig_share", s["baseline"])


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
"""
