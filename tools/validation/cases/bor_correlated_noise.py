"""Block-on-ring hidden-effect tallies under measurement errors that are not the fit's error
model (tests/diagnosis/hidden_effect.h: random-walk weighings, a soak-control uptake growing
with time, Student-t outliers, multiplicative lognormal errors): effects sized so that their
identifiable signal is 1.2 times the set's noise RMS, and clean sets; the hidden values, the
generator and its seeds are independent of the fits."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Block-on-ring hidden effects at 1.2x the noise under other noise families"
LONG = True  # about 1-3 s per diagnosis
FAMILIES = ["walk", "soak_drift", "heavy", "lognormal"]
EFFECTS = ["running_in", "incubation", "pressure_dependent_wear"]
SEEDS_EFFECT = 10
SEEDS_CLEAN = 20


tool = T.sweep_tool("tests/diagnosis/test_diagnosis_long", "correlated sweep")


def run(v):
    T.tallies_at_1_2(v, tool, "KNEESIM_BOR_", FAMILIES, EFFECTS, SEEDS_EFFECT, 810000, SEEDS_CLEAN, 820000)


TABLE = """
| noise family | running_in named | incubation named | pressure_dependent_wear named | clean sets named none |
|---|---|---|---|---|
| walk (random-walk weighings) | {walk_running_in} | {walk_incubation} | {walk_pressure_dependent_wear} | {walk_none} |
| soak_drift (uptake growing with time) | {soak_drift_running_in} | {soak_drift_incubation} | {soak_drift_pressure_dependent_wear} | {soak_drift_none} |
| heavy (Student-t, 3 dof) | {heavy_running_in} | {heavy_incubation} | {heavy_pressure_dependent_wear} | {heavy_none} |
| lognormal (multiplicative) | {lognormal_running_in} | {lognormal_incubation} | {lognormal_pressure_dependent_wear} | {lognormal_none} |

False positives: {false_positives:.0f} of {clean_records:.0f} clean sets; the rate's one-sided 95 % upper bound (Clopper-Pearson) {false_positive_upper95_pct:.1f} %.
"""
