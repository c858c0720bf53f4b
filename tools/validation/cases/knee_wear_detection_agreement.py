"""The detection limit a knee-wear diagnosis reports against the size at which hidden effects
start being named: running-in, a pressure-dependent wear factor and cross-shear at several
multiples of the set's noise RMS under random-walk weighings (not the fit's error model;
tests/diagnosis_knee/knee_hidden_effect.h), 10 seeds per size, and the detection limits (20
replicates) reported for clean sets of the same design (volume only), as signal / noise
ratios, in the direction the hidden effects take (more wear early, wear rising with pressure:
the sized generator's pressure exponent is positive, more wear under cross-shear)."""
import importlib.util
import os
import re

_spec = importlib.util.spec_from_file_location(
    "kneesim_bor_detection_agreement", os.path.join(os.path.dirname(__file__), "bor_detection_agreement.py"))
B = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(B)

TITLE = "Knee wear: reported detection limits against the hidden-effect onset"
LONG = True  # about 210 diagnoses and 4 with detection limits: 15-20 minutes
EFFECTS = ["running_in", "pressure_dependent_wear", "cross_shear"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]
RECORD = 'build/tests/diagnosis_knee/test_diagnosis_knee_long -tc="knee wear correlated sweep" --no-skip'


def tool(v, env):
    env = dict(env, KNEESIM_KW_FAMILIES="walk")
    rec = " ".join(f"{k}={val}" for k, val in env.items())
    env["KNEESIM_SOURCE_DIR"] = v.source  # the synthetic sets' conditions (knee_conditions.toml)
    return v.tool("tests/diagnosis_knee/test_diagnosis_knee_long", ["-tc=knee wear correlated sweep", "--no-skip"],
                  record=rec + " " + RECORD, env=env)


def run(v):
    out = tool(v, {"KNEESIM_KW_EFFECTS": ",".join(EFFECTS), "KNEESIM_KW_RATIOS": ",".join(RATIOS),
                   "KNEESIM_KW_SEEDS": "10", "KNEESIM_KW_FIRST_SEED": "930000"})
    fr = {}
    for eff, ratio, named, n in re.findall(r"^== walk (\S+) ratio ([0-9.]+): named (\d+) of (\d+)$", out, re.M):
        fr.setdefault(eff, []).append((float(ratio), int(named) / int(n)))
        v.figure(f"{eff}_{ratio.replace('.', 'p')}", f"{named}/{n}")
    det = tool(v, {"KNEESIM_KW_EFFECTS": "none", "KNEESIM_KW_SEEDS": "4",
                   "KNEESIM_KW_FIRST_SEED": "940000", "KNEESIM_KW_DETECTION": "20"})
    lim = {}
    for eff, d, reached, ratio in re.findall(r"^\s+limit (\S+) \S+?([+-])1: (at|beyond) \S+, signal \S+, ratio ([0-9.]+)", det, re.M):
        if d == "+":
            lim.setdefault(eff, []).append(float(ratio) if reached == "at" else float("inf"))
    for eff in EFFECTS:
        o = B.onset(sorted(fr.get(eff, [])))
        m = sum(lim[eff]) / len(lim[eff])
        v.figure(f"{eff}_onset", o)
        v.figure(f"{eff}_limit", m)
        v.figure(f"{eff}_factor", m / o if o > 0 else float("nan"))


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | onset (80 % named) | reported limit (mean of 4 clean sets) | limit / onset |
|---|---|---|---|---|
| running_in | {running_in_0p10} / {running_in_0p20} / {running_in_0p30} / {running_in_0p40} / {running_in_0p60} / {running_in_0p80} / {running_in_1p00} | {running_in_onset:.2f} | {running_in_limit:.2f} | {running_in_factor:.2f} |
| pressure_dependent_wear (exponent > 0) | {pressure_dependent_wear_0p10} / {pressure_dependent_wear_0p20} / {pressure_dependent_wear_0p30} / {pressure_dependent_wear_0p40} / {pressure_dependent_wear_0p60} / {pressure_dependent_wear_0p80} / {pressure_dependent_wear_1p00} | {pressure_dependent_wear_onset:.2f} | {pressure_dependent_wear_limit:.2f} | {pressure_dependent_wear_factor:.2f} |
| cross_shear | {cross_shear_0p10} / {cross_shear_0p20} / {cross_shear_0p30} / {cross_shear_0p40} / {cross_shear_0p60} / {cross_shear_0p80} / {cross_shear_1p00} | {cross_shear_onset:.2f} | {cross_shear_limit:.2f} | {cross_shear_factor:.2f} |
"""
