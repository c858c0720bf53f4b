"""The detection limit a block-on-ring diagnosis reports against the size at which hidden
effects start being named: hidden effects at several multiples of the set's noise RMS under
random-walk weighings (not the fit's error model; tests/diagnosis/hidden_effect.h), 10 seeds
per size, and the detection limits (20 replicates) reported for clean sets of the same
design, as the limit's signal over the clean set's noise RMS (the measure of the hidden
effects' ratios)."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Block-on-ring: reported detection limits against the hidden-effect onset"
LONG = True  # about 200 diagnoses and 4 with detection limits: 5-15 minutes
EFFECTS = ["running_in", "incubation", "pressure_dependent_wear"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]


tool = T.sweep_tool("tests/diagnosis/test_diagnosis_long", "correlated sweep", {"KNEESIM_BOR_FAMILIES": "walk"})


def run(v):
    T.detection_agreement(v, tool, "KNEESIM_BOR_", "walk", EFFECTS, RATIOS, 830000, 840000, plus_only=True)


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | onset (80 % named) | reported limit: signal / the clean set's noise RMS (mean of 4 clean sets) | limit / onset |
|---|---|---|---|---|
| running_in | {running_in_0p10} / {running_in_0p20} / {running_in_0p30} / {running_in_0p40} / {running_in_0p60} / {running_in_0p80} / {running_in_1p00} | {running_in_onset:.2f} | {running_in_limit:.2f} | {running_in_factor:.2f} |
| incubation | {incubation_0p10} / {incubation_0p20} / {incubation_0p30} / {incubation_0p40} / {incubation_0p60} / {incubation_0p80} / {incubation_1p00} | {incubation_onset:.2f} | {incubation_limit:.2f} | {incubation_factor:.2f} |
| pressure_dependent_wear (alpha > 0) | {pressure_dependent_wear_0p10} / {pressure_dependent_wear_0p20} / {pressure_dependent_wear_0p30} / {pressure_dependent_wear_0p40} / {pressure_dependent_wear_0p60} / {pressure_dependent_wear_0p80} / {pressure_dependent_wear_1p00} | {pressure_dependent_wear_onset:.2f} | {pressure_dependent_wear_limit:.2f} | {pressure_dependent_wear_factor:.2f} |
"""
