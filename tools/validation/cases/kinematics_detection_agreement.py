"""The detection limit a kinematics diagnosis reports against the size at which hidden effects
start being named: a friction or restraint change at several multiples of the set's noise RMS
under rotation-centre registration errors (not the fit's error model;
tests/diagnosis_knee/knee_hidden_effect.h), 10 seeds per size, and the detection limits (20
replicates) reported for clean sets of the same design, as signal / noise ratios. The hidden
changes go either way (friction lower or higher, the restraint softer or stiffer with its gap
changed too), so the reported limit is the mean over the candidate's parameters and both
directions."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Kinematics: reported detection limits against the hidden-effect onset"
LONG = True  # about 140 diagnoses and 4 with detection limits: 10-15 minutes
EFFECTS = ["friction", "restraint"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]


tool = T.sweep_tool("tests/diagnosis_knee/test_diagnosis_knee_long", "kinematics correlated sweep",
                    {"KNEESIM_KIN_FAMILIES": "registration"})


def run(v):
    T.detection_agreement(v, tool, "KNEESIM_KIN_", "registration", EFFECTS, RATIOS, 1030000, 1040000, plus_only=False)


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | onset (80 % named) | reported limit: mean (range over parameters and directions, 4 clean sets) | limit / onset |
|---|---|---|---|---|
| friction | {friction_0p10} / {friction_0p20} / {friction_0p30} / {friction_0p40} / {friction_0p60} / {friction_0p80} / {friction_1p00} | {friction_onset:.2f} | {friction_limit:.2f} ({friction_limit_lo:.2f}-{friction_limit_hi:.2f}) | {friction_factor:.2f} |
| restraint | {restraint_0p10} / {restraint_0p20} / {restraint_0p30} / {restraint_0p40} / {restraint_0p60} / {restraint_0p80} / {restraint_1p00} | {restraint_onset:.2f} | {restraint_limit:.2f} ({restraint_limit_lo:.2f}-{restraint_limit_hi:.2f}) | {restraint_factor:.2f} |
"""
