"""The detection limit a forces diagnosis reports against the size at which hidden effects start
being named, in the effect's own unit: fixed load-line shifts (mm), stance lever arms (mm) and
VV alignments (deg), both signs alternating by seed, 20 seeds per size, under one noise level of
the white_walk cell-noise family (white noise plus a random-walk drift, not the fit's error
model; tests/diagnosis_forces/forces_synthetic.h) at 1.5 times its unit amplitude; and the
detection limits (20 replicates) reported for 8 clean records of the same family and noise
level, as the mean of |limit| over both signs. A constant load-line shift is identified by its
size against the instrument's calibration prior rather than by its ratio to the noise
(docs/diagnosis.md, "What a load-line shift can be told from"), so sizes, not noise ratios,
are compared here."""
import importlib.util
import os
import re

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Forces: reported detection limits against the hidden-effect onset"
LONG = True  # 280 diagnoses and 8 with detection limits: about 15 minutes
VALUES = {"load_line": ["1", "1.5", "2", "3"],
          "vv_moment": ["0.5", "1", "1.5", "2", "3"],
          "vv_alignment": ["1", "2", "2.5", "3", "4"]}
NOISE = "1.5"

tool = T.sweep_tool("tests/diagnosis_forces/test_diagnosis_forces_long", "forces sweep",
                    {"KNEESIM_FORCES_FAMILIES": "white_walk", "KNEESIM_FORCES_RATIOS": NOISE})


def run(v):
    for eff, values in VALUES.items():
        fr = []
        for val in values:
            out = tool(v, {"KNEESIM_FORCES_EFFECTS": eff, "KNEESIM_FORCES_SEEDS": "20",
                           "KNEESIM_FORCES_FIRST_SEED": "1300", "KNEESIM_FORCES_VALUE": val})
            named, n = T.tally_lines(out)[0][3:]
            v.figure(f"{eff}_{val.replace('.', 'p')}", f"{named}/{n}")
            fr.append((float(val), named / n))
        v.figure(f"{eff}_onset", T.onset(fr))
    det = tool(v, {"KNEESIM_FORCES_EFFECTS": "none", "KNEESIM_FORCES_SEEDS": "8",
                   "KNEESIM_FORCES_FIRST_SEED": "1400", "KNEESIM_FORCES_VALUE": "0",
                   "KNEESIM_FORCES_DETECTION": "20"})
    lim = {}
    for eff, reached, value in re.findall(r"^\s+limit (\S+) \S+?[+-]1: (at|beyond) (\S+), signal", det, re.M):
        lim.setdefault(eff, []).append(abs(float(value)) if reached == "at" else float("inf"))
    for eff in VALUES:
        m = sum(lim[eff]) / len(lim[eff])
        v.figure(f"{eff}_limit", m)
        v.figure(f"{eff}_limit_lo", min(lim[eff]))
        v.figure(f"{eff}_limit_hi", max(lim[eff]))
        v.figure(f"{eff}_factor", m / v.figures[f"{eff}_onset"]["value"])
    named, n = T.tally_lines(det)[0][3:]
    v.figure("clean_named_none", f"{named}/{n}")


TABLE = """
| effect (unit) | named at each size (both signs) | onset (80 % named) | reported limit: mean of abs(limit) (range over signs and 8 clean records) | limit / onset |
|---|---|---|---|---|
| load_line (mm) | 1: {load_line_1} / 1.5: {load_line_1p5} / 2: {load_line_2} / 3: {load_line_3} | {load_line_onset:.2f} | {load_line_limit:.2f} ({load_line_limit_lo:.2f}-{load_line_limit_hi:.2f}) | {load_line_factor:.2f} |
| vv_moment (stance arm, mm) | 0.5: {vv_moment_0p5} / 1: {vv_moment_1} / 1.5: {vv_moment_1p5} / 2: {vv_moment_2} / 3: {vv_moment_3} | {vv_moment_onset:.2f} | {vv_moment_limit:.2f} ({vv_moment_limit_lo:.2f}-{vv_moment_limit_hi:.2f}) | {vv_moment_factor:.2f} |
| vv_alignment (deg) | 1: {vv_alignment_1} / 2: {vv_alignment_2} / 2.5: {vv_alignment_2p5} / 3: {vv_alignment_3} / 4: {vv_alignment_4} | {vv_alignment_onset:.2f} | {vv_alignment_limit:.2f} ({vv_alignment_limit_lo:.2f}-{vv_alignment_limit_hi:.2f}) | {vv_alignment_factor:.2f} |

The 8 clean records named none: {clean_named_none}.
"""
