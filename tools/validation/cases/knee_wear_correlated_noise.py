"""Knee-wear hidden-effect tallies under measurement errors that are not the fit's error
model (tests/diagnosis_knee/knee_hidden_effect.h, families of tests/diagnosis/hidden_effect.h: random-walk weighings, a soak-control uptake growing
with time, Student-t outliers, multiplicative lognormal errors): effects sized so that their
identifiable signal is 1.2 times the set's noise RMS, and clean sets; the hidden values, the
generator and its seeds are independent of the fits."""
import re

TITLE = "Knee-wear hidden effects at 1.2x the noise under other noise families"
LONG = True  # about 4 s per diagnosis: 10-15 minutes
FAMILIES = ["walk", "soak_drift", "heavy", "lognormal"]
EFFECTS = ["running_in", "pressure_dependent_wear", "cross_shear"]
SEEDS_EFFECT = 10
SEEDS_CLEAN = 20


def sweep(v, effects, seeds, first):
    env = {"KNEESIM_KW_FAMILIES": ",".join(FAMILIES), "KNEESIM_KW_EFFECTS": ",".join(effects),
           "KNEESIM_KW_RATIOS": "1.2", "KNEESIM_KW_SEEDS": str(seeds),
           "KNEESIM_KW_FIRST_SEED": str(first)}
    rec = " ".join(f"{k}={val}" for k, val in env.items())
    env["KNEESIM_SOURCE_DIR"] = v.source  # the synthetic sets' conditions (knee_conditions.toml)
    out = v.tool("tests/diagnosis_knee/test_diagnosis_knee_long", ["-tc=knee wear correlated sweep", "--no-skip"],
                 record=rec + ' build/tests/diagnosis_knee/test_diagnosis_knee_long -tc="knee wear correlated sweep" --no-skip',
                 env=env)
    return re.findall(r"^== (\S+) (\S+) ratio [0-9.]+: named (\d+) of (\d+)$", out, re.M)


def run(v):
    for fam, eff, named, n in sweep(v, EFFECTS, SEEDS_EFFECT, 910000) + sweep(v, ["none"], SEEDS_CLEAN, 920000):
        v.figure(f"{fam}_{eff}", f"{named}/{n}")


TABLE = """
| noise family | running_in named | pressure_dependent_wear named | cross_shear named | clean sets named none |
|---|---|---|---|---|
| walk (random-walk weighings) | {walk_running_in} | {walk_pressure_dependent_wear} | {walk_cross_shear} | {walk_none} |
| soak_drift (uptake growing with time) | {soak_drift_running_in} | {soak_drift_pressure_dependent_wear} | {soak_drift_cross_shear} | {soak_drift_none} |
| heavy (Student-t, 3 dof) | {heavy_running_in} | {heavy_pressure_dependent_wear} | {heavy_cross_shear} | {heavy_none} |
| lognormal (multiplicative) | {lognormal_running_in} | {lognormal_pressure_dependent_wear} | {lognormal_cross_shear} | {lognormal_none} |
"""
