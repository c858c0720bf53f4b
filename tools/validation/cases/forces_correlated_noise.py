"""Forces hidden-effect tallies on a four-cell synthetic instrumented tray
(tests/diagnosis_forces/forces_synthetic.h) whose cell errors are not the fit's error model:
white noise plus a random-walk drift, crosstalk between non-neighbouring cells with gain
errors, 1/f-like noise; hidden effects sized so that their identifiable signal is 1.2 times
the record's noise RMS, and clean records; and load-line shifts of fixed size under one noise
level (white_walk at 1.5 times its unit amplitude, the medial reading's noise 25-81 N RMS) against
the detection limit the diagnosis reports for a clean record of that family."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(os.path.dirname(__file__), "_tallies.py"))
T = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(T)

TITLE = "Forces hidden effects at 1.2x the noise under other cell-noise families"
LONG = True  # 2-5 s per diagnosis, 160 diagnoses: about 7 minutes
FAMILIES = ["white_walk", "crosstalk", "pink"]
EFFECTS = ["load_line", "vv_moment", "vv_alignment"]
SEEDS_EFFECT = 10
SEEDS_CLEAN = 20  # 60 clean records: enough that none named bounds the false-positive rate below 5 %
ONSET_MM = ["1", "1.5", "2", "3"]
SEEDS_ONSET = 10


tool = T.sweep_tool("tests/diagnosis_forces/test_diagnosis_forces_long", "forces sweep")


def onset(v, mm):
    out = tool(v, {"KNEESIM_FORCES_FAMILIES": "white_walk", "KNEESIM_FORCES_EFFECTS": "load_line",
                   "KNEESIM_FORCES_RATIOS": "1.5", "KNEESIM_FORCES_SEEDS": str(SEEDS_ONSET),
                   "KNEESIM_FORCES_FIRST_SEED": "1300", "KNEESIM_FORCES_VALUE": mm})
    named, n = T.tally_lines(out)[0][3:]
    return f"{named}/{n}"


def run(v):
    T.tallies_at_1_2(v, tool, "KNEESIM_FORCES_", FAMILIES, EFFECTS, SEEDS_EFFECT, 1100, SEEDS_CLEAN, 1200)
    for mm in ONSET_MM:
        v.figure(f"onset_{mm.replace('.', '_')}mm", onset(v, mm))


TABLE = """
| cell-noise family | load_line named | vv_moment named | vv_alignment named | clean records named none |
|---|---|---|---|---|
| white_walk (white + random-walk drift) | {white_walk_load_line} | {white_walk_vv_moment} | {white_walk_vv_alignment} | {white_walk_none} |
| crosstalk (non-neighbouring cells, gain errors) | {crosstalk_load_line} | {crosstalk_vv_moment} | {crosstalk_vv_alignment} | {crosstalk_none} |
| pink (1/f-like) | {pink_load_line} | {pink_vv_moment} | {pink_vv_alignment} | {pink_none} |

| load-line shift (white_walk, noise scale 1.5, both signs) | 1 mm | 1.5 mm | 2 mm | 3 mm |
|---|---|---|---|---|
| named | {onset_1mm} | {onset_1_5mm} | {onset_2mm} | {onset_3mm} |

False positives: {false_positives:.0f} of {clean_records:.0f} clean records; the rate's one-sided 95 % upper bound (Clopper-Pearson) {false_positive_upper95_pct:.1f} %.
"""
