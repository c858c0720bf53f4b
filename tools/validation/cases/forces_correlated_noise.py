"""Forces hidden-effect tallies on a four-cell synthetic instrumented tray
(tests/diagnosis_forces/forces_synthetic.h) whose cell errors are not the fit's error model:
white noise plus a random-walk drift, crosstalk between non-neighbouring cells with gain
errors, 1/f-like noise; hidden effects sized so that their identifiable signal is 1.2 times
the record's noise RMS, and clean records."""
import re

TITLE = "Forces hidden effects at 1.2x the noise under other cell-noise families"
LONG = True  # about 10-30 s per diagnosis
FAMILIES = ["white_walk", "crosstalk", "pink"]
EFFECTS = ["load_line", "vv_moment", "vv_alignment"]
SEEDS_EFFECT = 5
SEEDS_CLEAN = 5


def sweep(v, effects, seeds, first):
    env = {"KNEESIM_FORCES_FAMILIES": ",".join(FAMILIES), "KNEESIM_FORCES_EFFECTS": ",".join(effects),
           "KNEESIM_FORCES_RATIOS": "1.2", "KNEESIM_FORCES_SEEDS": str(seeds),
           "KNEESIM_FORCES_FIRST_SEED": str(first)}
    rec = " ".join(f"{k}={val}" for k, val in env.items())
    out = v.tool("tests/diagnosis_forces/test_diagnosis_forces_long", ["-tc=forces sweep", "--no-skip"],
                 record=rec + ' build/tests/diagnosis_forces/test_diagnosis_forces_long -tc="forces sweep" --no-skip',
                 env=env)
    return re.findall(r"^== (\S+) (\S+) ratio [0-9.]+: named (\d+) of (\d+)$", out, re.M)


def run(v):
    for fam, eff, named, n in sweep(v, EFFECTS, SEEDS_EFFECT, 1100) + sweep(v, ["none"], SEEDS_CLEAN, 1200):
        v.figure(f"{fam}_{eff}", f"{named}/{n}")


TABLE = """
| cell-noise family | load_line named | vv_moment named | vv_alignment named | clean records named none |
|---|---|---|---|---|
| white_walk (white + random-walk drift) | {white_walk_load_line} | {white_walk_vv_moment} | {white_walk_vv_alignment} | {white_walk_none} |
| crosstalk (non-neighbouring cells, gain errors) | {crosstalk_load_line} | {crosstalk_vv_moment} | {crosstalk_vv_alignment} | {crosstalk_none} |
| pink (1/f-like) | {pink_load_line} | {pink_vv_moment} | {pink_vv_alignment} | {pink_none} |
"""
