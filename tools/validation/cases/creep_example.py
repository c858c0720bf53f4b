"""kneesim diagnose bor on synthetic block-on-ring data with depth and a hidden creep effect
(the hidden-effect generator of tests/diagnosis, seed 42: phi 0.75, tau 8 570 s, k 4.67e-10
mm3/(N mm); 6 specimens x 2 loads x 4 cycle counts): the diagnosis must name creep and its
intervals hold the hidden values."""
import os

TITLE = "Block-on-ring diagnosis of synthetic creep data"
LONG = False
IMAGES = {"docs/img/diagnosis_bor_synthetic_creep.png": "creep42/diagnosis.png"}


def run(v):
    csv = os.path.join(v.dir, "creep42.csv")
    v.tool("tests/diagnosis/test_diagnosis_long", ["-tc=write example", "--no-skip"],
           record='KNEESIM_EXAMPLE_CSV=creep42.csv build/tests/diagnosis/test_diagnosis_long -tc="write example" --no-skip',
           env={"KNEESIM_EXAMPLE_CSV": csv})
    d = v.json(v.kneesim("creep42", ["diagnose", "bor", "--measured", csv]), "diagnosis.json")
    v.commands[-1] = v.commands[-1].replace(v.dir + "/", "")
    v.figure("effect", d["effect"])
    ext = d["extended"]
    for p, val in ext["params"].items():
        v.figure(p, val)
        v.figure(p + "_lo", ext["params_ci95"][p][0])
        v.figure(p + "_hi", ext["params_ci95"][p][1])
    v.figure("daicc", {c["name"]: c["delta_aicc"] for c in d["candidates"]}[d["effect"]])
    v.figure("gain", d["gain"])
    v.figure("measurements", len(v.csv(csv)))


TABLE = """
| hidden | named | phi (hidden 0.75) [95 %] | tau s (hidden 8 570) [95 %] | k mm³/(N mm) (hidden 4.67e-10) [95 %] | dAICc | gain |
|---|---|---|---|---|---|---|
| creep, seed 42 | `{effect}` | {creep_ratio:.2f} [{creep_ratio_lo:.2f}, {creep_ratio_hi:.2f}] | {creep_time_s:.0f} [{creep_time_s_lo:.0f}, {creep_time_s_hi:.0f}] | {k_mm3_per_Nmm:.3g} [{k_mm3_per_Nmm_lo:.3g}, {k_mm3_per_Nmm_hi:.3g}] | {daicc:.0f} | {gain:.2f} |
"""
