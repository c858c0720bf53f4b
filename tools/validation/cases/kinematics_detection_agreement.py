"""The detection limit a kinematics diagnosis reports against the size at which hidden effects
start being named: a friction or restraint change at several multiples of the set's noise RMS
under rotation-centre registration errors (not the fit's error model;
tests/diagnosis_knee/knee_hidden_effect.h), 10 seeds per size. The noise of this family is
scaled to size each set (the rotation-centre offset with it, against the error model's fixed
prior), so clean sets of one scale are not the regime of the effect sets: each set is compared
with the limit reported for its clean twin (the same noise without the effect, 20 replicates),
x = the set's identifiable signal / the twin's limit in the effect's direction, and the x at
which the sets start being named (80 %, logistic in ln x) is the onset in units of the
reported limit (1 if the limits are exact)."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Kinematics: reported detection limits against the hidden-effect onset"
LONG = True  # 140 diagnoses, each with its twin's detection limits: 20-30 minutes
EFFECTS = ["friction", "restraint"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]


tool = T.sweep_tool("tests/diagnosis_knee/test_diagnosis_knee_long", "kinematics correlated sweep",
                    {"KNEESIM_KIN_FAMILIES": "registration"})


def run(v):
    T.twin_agreement(v, tool, "KNEESIM_KIN_", "registration", EFFECTS, RATIOS, 1030000, 10)
    for eff in EFFECTS:
        v.figure(f"{eff}_factor", 1.0 / v.figures[f"{eff}_x80"]["value"])


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | named with the effect below / at or above its twin's reported limit | onset in units of the reported limit (80 % named; 95 % bootstrap interval) | limit / onset |
|---|---|---|---|---|
| friction | {friction_0p10} / {friction_0p20} / {friction_0p30} / {friction_0p40} / {friction_0p60} / {friction_0p80} / {friction_1p00} | {friction_below} / {friction_above} | {friction_x80:.2f} ({friction_x80_lo:.2f}-{friction_x80_hi:.2f}) | {friction_factor:.2f} |
| restraint | {restraint_0p10} / {restraint_0p20} / {restraint_0p30} / {restraint_0p40} / {restraint_0p60} / {restraint_0p80} / {restraint_1p00} | {restraint_below} / {restraint_above} | {restraint_x80:.2f} ({restraint_x80_lo:.2f}-{restraint_x80_hi:.2f}) | {restraint_factor:.2f} |

Clean twins named an effect: {twins_named:.0f} of {twins:.0f}.
"""
