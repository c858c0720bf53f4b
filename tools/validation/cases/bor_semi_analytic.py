"""The block-on-ring semi-analytic model (KINSOL) against closed forms: the unworn Winkler
contact (bisection on F = C R^2 (theta - sin theta cos theta) w, solved here independently)
and Archard's volume k_D F S N at 200 000 cycles."""
import math

TITLE = "Block-on-ring semi-analytic model against closed forms"
LONG = False
E, NU, H, W, R, K = 690.0, 0.317, 12.0, 10.0, 17.5, 4.1e-10  # MPa, -, mm, mm, mm, mm3/(N mm)


def unworn(F):
    C = (1 - NU) * E / ((1 + NU) * (1 - 2 * NU) * H)
    lo, hi = 0.0, math.pi / 2
    for _ in range(200):
        th = 0.5 * (lo + hi)
        if C * R * R * (th - math.sin(th) * math.cos(th)) * W < F:
            lo = th
        else:
            hi = th
    half = R * math.sin(th)
    return half, F / (2 * half * W)


def run(v):
    for F in (225, 130):
        rows = v.csv(v.kneesim(f"bor_{F}", ["bor", "--load-N", str(F)]), "bor.csv")
        first, last = rows[0], rows[-1]
        half, p = unworn(F)
        v.figure(f"half_width_{F}_mm", first["contact_width_mm"] / 2, "mm")
        v.figure(f"half_width_{F}_closed_mm", half, "mm")
        v.figure(f"pressure_{F}_MPa", first["mean_pressure_MPa"], "MPa")
        v.figure(f"pressure_{F}_closed_MPa", p, "MPa")
        v.figure(f"volume_{F}_mm3", last["volume_mm3"], "mm3")
        v.figure(f"volume_{F}_closed_mm3", K * F * math.pi * 2 * R * last["cycles"], "mm3")
        v.figure(f"depth_{F}_mm", last["depth_mm"], "mm")


TABLE = """
| load | quantity | closed form | kneesim bor |
|---|---|---|---|
| 225 N | unworn contact half-width (mm) | {half_width_225_closed_mm:.3f} | {half_width_225_mm:.3f} |
| | unworn mean pressure (MPa) | {pressure_225_closed_MPa:.2f} | {pressure_225_MPa:.2f} |
| | volume at 200 000 cycles, k_D F S N (mm³) | {volume_225_closed_mm3:.4f} | {volume_225_mm3:.4f} (scar depth {depth_225_mm:.4f} mm) |
| 130 N | unworn contact half-width (mm) | {half_width_130_closed_mm:.3f} | {half_width_130_mm:.3f} |
| | unworn mean pressure (MPa) | {pressure_130_closed_MPa:.2f} | {pressure_130_MPa:.2f} |
| | volume at 200 000 cycles, k_D F S N (mm³) | {volume_130_closed_mm3:.4f} | {volume_130_mm3:.4f} (scar depth {depth_130_mm:.4f} mm) |
"""
