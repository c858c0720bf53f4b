"""The detection limit a knee-wear diagnosis reports against the size at which hidden effects
start being named: running-in, a pressure-dependent wear factor and cross-shear at several
multiples of the set's noise RMS under random-walk weighings (not the fit's error model;
tests/diagnosis_knee/knee_hidden_effect.h), 10 seeds per size, and the detection limits (20
replicates) reported for clean sets of the same design (volume only), as the limit's signal
over the clean set's noise RMS (the measure of the hidden effects' ratios), in the direction the hidden effects take (more wear early, wear rising with pressure:
the sized generator's pressure exponent is positive, more wear under cross-shear)."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Knee wear: reported detection limits against the hidden-effect onset"
LONG = True  # about 210 diagnoses and 4 with detection limits: 15-20 minutes
EFFECTS = ["running_in", "pressure_dependent_wear", "cross_shear"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]


# KNEESIM_SOURCE_DIR: the synthetic sets' conditions (knee_conditions.toml)
tool = T.sweep_tool("tests/diagnosis_knee/test_diagnosis_knee_long", "knee wear correlated sweep",
                    {"KNEESIM_KW_FAMILIES": "walk"}, source_dir=True)


def run(v):
    T.detection_agreement(v, tool, "KNEESIM_KW_", "walk", EFFECTS, RATIOS, 930000, 940000, plus_only=True)


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | onset (80 % named) | reported limit: signal / the clean set's noise RMS (mean of 4 clean sets) | limit / onset |
|---|---|---|---|---|
| running_in | {running_in_0p10} / {running_in_0p20} / {running_in_0p30} / {running_in_0p40} / {running_in_0p60} / {running_in_0p80} / {running_in_1p00} | {running_in_onset:.2f} | {running_in_limit:.2f} | {running_in_factor:.2f} |
| pressure_dependent_wear (exponent > 0) | {pressure_dependent_wear_0p10} / {pressure_dependent_wear_0p20} / {pressure_dependent_wear_0p30} / {pressure_dependent_wear_0p40} / {pressure_dependent_wear_0p60} / {pressure_dependent_wear_0p80} / {pressure_dependent_wear_1p00} | {pressure_dependent_wear_onset:.2f} | {pressure_dependent_wear_limit:.2f} | {pressure_dependent_wear_factor:.2f} |
| cross_shear | {cross_shear_0p10} / {cross_shear_0p20} / {cross_shear_0p30} / {cross_shear_0p40} / {cross_shear_0p60} / {cross_shear_0p80} / {cross_shear_1p00} | {cross_shear_onset:.2f} | {cross_shear_limit:.2f} | {cross_shear_factor:.2f} |
"""
