"""5 Mc of wear on the Grand Challenge DM implant under the stanmore rig."""
TITLE = "DM implant 5 Mc wear"
LONG = False


def run(v):
    v.require_data("gc6_dm/femoral_component.stl")
    s = v.json(v.kneesim("wear_dm", ["wear", v.source + "/models/examples/dm_stanmore.toml",
                                     "--no-plots", "--no-depth-maps", "--quiet"]), "summary.json")
    v.figure("volume_mm3", s["volume_mm3"], "mm3")
    v.figure("mass_mg", s["mass_mg"], "mg")
    v.figure("rate_mm3_per_Mc", s["wear_rate_mm3_per_Mc"], "mm3/Mc")
    v.figure("max_depth_mm", s["max_depth_mm"], "mm")
    v.figure("bookkeeping_pct", 100 * s["volume_bookkeeping_rel_diff"], "%")


TABLE = """
| quantity | reference | kneesim |
|---|---|---|
| volume / rate / max depth at 5 Mc | none measured for this implant in a simulator | {volume_mm3:.1f} mm³ ({mass_mg:.1f} mg), {rate_mm3_per_Mc:.2f} mm³/Mc, {max_depth_mm:.3f} mm |
| enclosed-volume loss against the depth integral | equal within 1 % | {bookkeeping_pct:.2f} % |
"""
