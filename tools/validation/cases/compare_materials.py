"""kneesim compare at 5 Mc (rigid insert) against the materials study's deformable FE of a
Genesis II insert. UHMWPE's volume and depth are predictions (Pal 2008's wear factor); PEEK's
and CFR-PEEK's wear factors are the study's volume ratios, so their volumes are calibrated."""
TITLE = "Materials against the materials study"
LONG = False

STUDY = {"uhmwpe": (124.0, 0.31, 13.4), "peek": (300.9, 0.89, 23.6), "cfr-peek": (15.6, 0.12, 36.1)}
KEY = {"uhmwpe": "uhmwpe", "peek": "peek", "cfr-peek": "cfrpeek"}


def run(v):
    d = v.kneesim("compare", ["compare", "--materials", "uhmwpe,peek,cfr-peek", "--no-plots", "--quiet"])
    rows = {r["material"]: r for r in v.csv(d, "comparison.csv")}
    for m, k in KEY.items():
        r = rows[m]
        v.figure(f"{k}_volume_mm3", r["volume_mm3"], "mm3")
        v.figure(f"{k}_mass_mg", r["mass_mg"], "mg")
        v.figure(f"{k}_max_depth_mm", r["max_depth_mm"], "mm")
        v.figure(f"{k}_mean_peak_pressure_MPa", r["mean_peak_pressure_MPa"], "MPa")
        v.figure(f"{k}_ap_rom_mm", r["ap_rom_mm"], "mm")
        v.figure(f"{k}_ie_rom_deg", r["ie_rom_deg"], "deg")
        vol, depth, p = STUDY[m]
        v.figure(f"{k}_volume_err_pct", 100 * (r["volume_mm3"] / vol - 1), "%")
        v.figure(f"{k}_depth_err_pct", 100 * (r["max_depth_mm"] / depth - 1), "%")
        v.figure(f"{k}_pressure_err_pct", 100 * (r["mean_peak_pressure_MPa"] / p - 1), "%")
    for k, m in (("peek", "peek"), ("cfrpeek", "cfr-peek")):
        ratio = rows[m]["volume_mm3"] / rows["uhmwpe"]["volume_mm3"]
        study = STUDY[m][0] / STUDY["uhmwpe"][0]
        v.figure(f"{k}_volume_ratio", ratio, "")
        v.figure(f"{k}_volume_ratio_err_pct", 100 * (ratio / study - 1), "%")


TABLE = """
| material | volume (mm³) | mass (mg) | max depth (mm) | mean peak pressure (MPa) | AP ROM (mm) | IE ROM (deg) |
|---|---|---|---|---|---|---|
| UHMWPE | {uhmwpe_volume_mm3:.1f} | {uhmwpe_mass_mg:.1f} | {uhmwpe_max_depth_mm:.3f} | {uhmwpe_mean_peak_pressure_MPa:.1f} | {uhmwpe_ap_rom_mm:.2f} | {uhmwpe_ie_rom_deg:.2f} |
| PEEK | {peek_volume_mm3:.1f} | {peek_mass_mg:.1f} | {peek_max_depth_mm:.3f} | {peek_mean_peak_pressure_MPa:.1f} | {peek_ap_rom_mm:.2f} | {peek_ie_rom_deg:.2f} |
| CFR-PEEK | {cfrpeek_volume_mm3:.1f} | {cfrpeek_mass_mg:.1f} | {cfrpeek_max_depth_mm:.3f} | {cfrpeek_mean_peak_pressure_MPa:.1f} | {cfrpeek_ap_rom_mm:.2f} | {cfrpeek_ie_rom_deg:.2f} |

Against the materials study (deformable FE of a Genesis II insert, 5 Mc; kneesim's error in
brackets):

| quantity | UHMWPE | PEEK | CFR-PEEK | status |
|---|---|---|---|---|
| volume mm³: study / kneesim | 124.0 / {uhmwpe_volume_mm3:.1f} ({uhmwpe_volume_err_pct:+.0f} %) | 300.9 / {peek_volume_mm3:.1f} ({peek_volume_err_pct:+.0f} %) | 15.6 / {cfrpeek_volume_mm3:.1f} ({cfrpeek_volume_err_pct:+.0f} %) | UHMWPE predicted; others calibrated |
| volume ratio to UHMWPE: study / kneesim | 1 | 2.43 / {peek_volume_ratio:.2f} ({peek_volume_ratio_err_pct:+.0f} %) | 0.126 / {cfrpeek_volume_ratio:.3f} ({cfrpeek_volume_ratio_err_pct:+.0f} %) | calibrated (k ratio 2.40 / 0.130) |
| max depth mm: study / kneesim | 0.31 / {uhmwpe_max_depth_mm:.3f} ({uhmwpe_depth_err_pct:+.0f} %) | 0.89 / {peek_max_depth_mm:.3f} ({peek_depth_err_pct:+.0f} %) | 0.12 / {cfrpeek_max_depth_mm:.3f} ({cfrpeek_depth_err_pct:+.0f} %) | UHMWPE predicted; others calibrated |
| mean peak pressure MPa: study / kneesim | 13.4 / {uhmwpe_mean_peak_pressure_MPa:.1f} ({uhmwpe_pressure_err_pct:+.0f} %) | 23.6 / {peek_mean_peak_pressure_MPa:.1f} ({peek_pressure_err_pct:+.0f} %) | 36.1 / {cfrpeek_mean_peak_pressure_MPa:.1f} ({cfrpeek_pressure_err_pct:+.0f} %) | predicted |
"""
