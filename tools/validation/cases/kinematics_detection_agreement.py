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
import re

_spec = importlib.util.spec_from_file_location(
    "kneesim_bor_detection_agreement", os.path.join(os.path.dirname(__file__), "bor_detection_agreement.py"))
B = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(B)

TITLE = "Kinematics: reported detection limits against the hidden-effect onset"
LONG = True  # about 140 diagnoses and 4 with detection limits: 10-15 minutes
EFFECTS = ["friction", "restraint"]
RATIOS = ["0.1", "0.2", "0.3", "0.4", "0.6", "0.8", "1.0"]
RECORD = 'build/tests/diagnosis_knee/test_diagnosis_knee_long -tc="kinematics correlated sweep" --no-skip'


def tool(v, env):
    env = dict(env, KNEESIM_KIN_FAMILIES="registration")
    rec = " ".join(f"{k}={val}" for k, val in env.items())
    return v.tool("tests/diagnosis_knee/test_diagnosis_knee_long", ["-tc=kinematics correlated sweep", "--no-skip"],
                  record=rec + " " + RECORD, env=env)


def run(v):
    out = tool(v, {"KNEESIM_KIN_EFFECTS": ",".join(EFFECTS), "KNEESIM_KIN_RATIOS": ",".join(RATIOS),
                   "KNEESIM_KIN_SEEDS": "10", "KNEESIM_KIN_FIRST_SEED": "1030000"})
    fr = {}
    for eff, ratio, named, n in re.findall(r"^== registration (\S+) ratio ([0-9.]+): named (\d+) of (\d+)$", out, re.M):
        fr.setdefault(eff, []).append((float(ratio), int(named) / int(n)))
        v.figure(f"{eff}_{ratio.replace('.', 'p')}", f"{named}/{n}")
    det = tool(v, {"KNEESIM_KIN_EFFECTS": "none", "KNEESIM_KIN_SEEDS": "4",
                   "KNEESIM_KIN_FIRST_SEED": "1040000", "KNEESIM_KIN_DETECTION": "20"})
    lim = {}
    for eff, reached, ratio in re.findall(r"^\s+limit (\S+) \S+[+-]1: (at|beyond) \S+, signal \S+, ratio ([0-9.]+)", det, re.M):
        lim.setdefault(eff, []).append(float(ratio) if reached == "at" else float("inf"))
    for eff in EFFECTS:
        o = B.onset(sorted(fr.get(eff, [])))
        m = sum(lim[eff]) / len(lim[eff])
        v.figure(f"{eff}_onset", o)
        v.figure(f"{eff}_limit", m)
        v.figure(f"{eff}_limit_lo", min(lim[eff]))
        v.figure(f"{eff}_limit_hi", max(lim[eff]))
        v.figure(f"{eff}_factor", m / o if o > 0 else float("nan"))


TABLE = """
| effect | named at 0.1 / 0.2 / 0.3 / 0.4 / 0.6 / 0.8 / 1.0 x noise | onset (80 % named) | reported limit: mean (range over parameters and directions, 4 clean sets) | limit / onset |
|---|---|---|---|---|
| friction | {friction_0p10} / {friction_0p20} / {friction_0p30} / {friction_0p40} / {friction_0p60} / {friction_0p80} / {friction_1p00} | {friction_onset:.2f} | {friction_limit:.2f} ({friction_limit_lo:.2f}-{friction_limit_hi:.2f}) | {friction_factor:.2f} |
| restraint | {restraint_0p10} / {restraint_0p20} / {restraint_0p30} / {restraint_0p40} / {restraint_0p60} / {restraint_0p80} / {restraint_1p00} | {restraint_onset:.2f} | {restraint_limit:.2f} ({restraint_limit_lo:.2f}-{restraint_limit_hi:.2f}) | {restraint_factor:.2f} |
"""
