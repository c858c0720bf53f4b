"""The 1000-trial Monte Carlo kinematics study of the default model against Pal 2008."""
TITLE = "Probabilistic study against Pal 2008 (1000-trial Monte Carlo)"
LONG = True  # 1000 trials: 1.5-3 minutes on 2 cores


def run(v):
    d = v.kneesim("mc1000", ["study", "--method", "mc", "--trials", "1000", "--seed", "1", "--quiet"])
    s = v.json(d, "summary.json")
    for m in ("ap_rom_mm", "ie_rom_deg", "peak_pressure_MPa"):
        st = s["measures"][m]
        for k in ("mean", "sd", "p01", "p50", "p99"):
            v.figure(f"{m}_{k}", st[k])
        v.figure(f"{m}_width", st["p99"] - st["p01"])
    v.figure("trials_done", s["trials_done"])
    v.figure("trials_failed", s["trials_failed"])


TABLE = """
| measure | kneesim mean (sd) | kneesim 1 % / 50 % / 99 % | kneesim 1-99 % width | Pal 2008 | Pal width |
|---|---|---|---|---|---|
| AP ROM (mm) | {ap_rom_mm_mean:.2f} ({ap_rom_mm_sd:.2f}) | {ap_rom_mm_p01:.2f} / {ap_rom_mm_p50:.2f} / {ap_rom_mm_p99:.2f} | {ap_rom_mm_width:.2f} | 9.68 [7.59, 12.34] | 4.75 |
| IE ROM (deg) | {ie_rom_deg_mean:.2f} ({ie_rom_deg_sd:.2f}) | {ie_rom_deg_p01:.2f} / {ie_rom_deg_p50:.2f} / {ie_rom_deg_p99:.2f} | {ie_rom_deg_width:.2f} | 10.11 [7.66, 13.85] | 6.19 |
| peak contact pressure (MPa) | {peak_pressure_MPa_mean:.2f} ({peak_pressure_MPa_sd:.2f}) | {peak_pressure_MPa_p01:.2f} / {peak_pressure_MPa_p50:.2f} / {peak_pressure_MPa_p99:.2f} | {peak_pressure_MPa_width:.2f} | 25.71 [23.94, 27.67] | 3.73 |

({trials_done:.0f} trials done, {trials_failed:.0f} failed.)
"""
