"""5 Mc of the default wear run: volume, rate, depth and the volume bookkeeping."""
TITLE = "Default 5 Mc wear"
LONG = False


def run(v):
    s = v.json(v.kneesim("wear", ["wear", "--no-plots", "--no-depth-maps", "--quiet"]), "summary.json")
    v.figure("volume_mm3", s["volume_mm3"], "mm3")
    v.figure("mass_mg", s["mass_mg"], "mg")
    v.figure("rate_mm3_per_Mc", s["wear_rate_mm3_per_Mc"], "mm3/Mc")
    v.figure("max_depth_mm", s["max_depth_mm"], "mm")
    v.figure("bookkeeping_pct", 100 * s["volume_bookkeeping_rel_diff"], "%")


TABLE = """
| quantity | reference | kneesim |
|---|---|---|
| volume / rate / max depth at 5 Mc | Pal 2008, measured: 78 and 97 mg (two samples, NexGen CR); the materials study: 124.0 mm³, 0.31 mm (Genesis II) | {volume_mm3:.1f} mm³ ({mass_mg:.1f} mg), {rate_mm3_per_Mc:.2f} mm³/Mc, {max_depth_mm:.3f} mm |
| enclosed-volume loss against the depth integral | equal within 1 % (the area-weighted spreading keeps the Archard volume exactly) | {bookkeeping_pct:.2f} % (`volume_bookkeeping_rel_diff`) |
"""
