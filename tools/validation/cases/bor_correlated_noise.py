"""Block-on-ring hidden-effect tallies under measurement errors that are not the fit's error
model (tests/diagnosis/hidden_effect.h: random-walk weighings, a soak-control uptake growing
with time, Student-t outliers, multiplicative lognormal errors): effects sized so that their
identifiable signal is 1.2 times the set's noise RMS, and clean sets; the hidden values, the
generator and its seeds are independent of the fits."""
import re

TITLE = "Block-on-ring hidden effects at 1.2x the noise under other noise families"
LONG = True  # about 1-3 s per diagnosis
FAMILIES = ["walk", "soak_drift", "heavy", "lognormal"]
EFFECTS = ["running_in", "incubation", "pressure_dependent_wear"]
SEEDS_EFFECT = 10
SEEDS_CLEAN = 20


def sweep(v, effects, seeds, first):
    env = {"KNEESIM_BOR_FAMILIES": ",".join(FAMILIES), "KNEESIM_BOR_EFFECTS": ",".join(effects),
           "KNEESIM_BOR_RATIOS": "1.2", "KNEESIM_BOR_SEEDS": str(seeds),
           "KNEESIM_BOR_FIRST_SEED": str(first)}
    rec = " ".join(f"{k}={val}" for k, val in env.items())
    out = v.tool("tests/diagnosis/test_diagnosis_long", ["-tc=correlated sweep", "--no-skip"],
                 record=rec + ' build/tests/diagnosis/test_diagnosis_long -tc="correlated sweep" --no-skip',
                 env=env)
    return re.findall(r"^== (\S+) (\S+) ratio [0-9.]+: named (\d+) of (\d+)$", out, re.M)


def run(v):
    for fam, eff, named, n in sweep(v, EFFECTS, SEEDS_EFFECT, 810000) + sweep(v, ["none"], SEEDS_CLEAN, 820000):
        v.figure(f"{fam}_{eff}", f"{named}/{n}")


TABLE = """
| noise family | running_in named | incubation named | pressure_dependent_wear named | clean sets named none |
|---|---|---|---|---|
| walk (random-walk weighings) | {walk_running_in} | {walk_incubation} | {walk_pressure_dependent_wear} | {walk_none} |
| soak_drift (uptake growing with time) | {soak_drift_running_in} | {soak_drift_incubation} | {soak_drift_pressure_dependent_wear} | {soak_drift_none} |
| heavy (Student-t, 3 dof) | {heavy_running_in} | {heavy_incubation} | {heavy_pressure_dependent_wear} | {heavy_none} |
| lognormal (multiplicative) | {lognormal_running_in} | {lognormal_incubation} | {lognormal_pressure_dependent_wear} | {lognormal_none} |
"""
