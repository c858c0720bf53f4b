"""The materials_study preset on the built-in implant against the materials study's
Genesis II (predicted and measured ranges)."""
TITLE = "materials_study preset against the materials study"
LONG = False


def run(v):
    s = v.json(v.kneesim("materials_study", ["run", "--set", "rig.preset=materials_study",
                                             "--set", "implant.edge_length_mm=2", "--no-plots", "--quiet"]),
               "summary.json")
    v.figure("ap_rom_mm", s["ap_rom_mm"], "mm")
    v.figure("ie_rom_deg", s["ie_rom_deg"], "deg")
    v.figure("medial_share_pct", 100 * s["medial_fraction_stance"], "%")
    v.figure("ap_ratio", s["ap_rom_mm"] / 6.7, "")


TABLE = """
| quantity | materials study (predicted / measured) | kneesim |
|---|---|---|
| AP range (mm) | 6.7 / 7.1 | {ap_rom_mm:.2f} |
| IE range (deg) | 9.1 / 9.3 | {ie_rom_deg:.2f} |
| medial share over stance | 60 % (the study's axial load offset) | {medial_share_pct:.1f} % |

With the femoral AP free the AP force is carried by the restraint alone and the joint AP follows
the implant's geometry; the generic implant is not the Genesis II, and its AP range is
{ap_ratio:.1f}x the study's.
"""
