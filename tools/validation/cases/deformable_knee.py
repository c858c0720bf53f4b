"""The deformable hex8 insert on the contact-law calibration's reference mesh (0.5 mm surface
elements where a rigid cycle finds contact, 6 layers graded 0.15) against the rigid elastic-foundation insert on the
default implant and rig: kinematics within 1 mm / 1 deg RMS (the acceptance), and how the solid
spreads the load (Pal 2008's peak pressure: 25.7 MPa, 1-99 % 23.9-27.7)."""
import math

TITLE = "Rigid against deformable insert on the default implant"
LONG = True  # one deformable cycle on about 48 000 elements: 2-4 minutes
REFERENCE_MESH = ["deformable.element_size_mm=0.5", "deformable.layers=6", "deformable.grading=0.15",
                  "deformable.refine=contact"]


def stance_figures(rows):
    stance = [r for r in rows if r["gait_pct"] <= 60.0]
    bal = [r["contact_axial_force_N"] - r["axial_force_N"] for r in stance]
    contact = [r for r in rows if r["contact_area_mm2"] > 0]
    return {"balance_N": math.sqrt(sum(b * b for b in bal) / len(bal)),
            "peak_MPa": max(r["peak_pressure_MPa"] for r in rows),
            "stance_peak_MPa": sum(r["peak_pressure_MPa"] for r in stance) / len(stance),
            "stance_mean_MPa": sum(r["mean_pressure_MPa"] for r in stance) / len(stance),
            "area_mm2": sum(r["contact_area_mm2"] for r in contact) / len(contact)}


def run(v):
    r = v.kneesim("rigid", ["run", "--no-plots", "--quiet"])
    sets = [a for kv in REFERENCE_MESH for a in ("--set", kv)]
    d = v.kneesim("deformable", ["run", "--cycles", "1", "--set", "insert=deformable", "--set", "solver.threads=2"]
                  + sets + ["--no-plots", "--quiet"])
    kr, kd = v.csv(r, "kinematics.csv"), v.csv(d, "kinematics.csv")
    n = min(len(kr), len(kd))
    for q, unit in (("ap_mm", "mm"), ("ie_deg", "deg")):
        v.figure(f"{q}_rms", math.sqrt(sum((kd[i][q] - kr[i][q]) ** 2 for i in range(n)) / n), unit)
    for name, rows, summ in (("rigid", kr, v.json(r, "summary.json")), ("def", kd, v.json(d, "summary.json"))):
        for k, val in stance_figures(rows).items():
            v.figure(f"{name}_{k}", val)
        v.figure(f"{name}_ap_rom_mm", summ["ap_rom_mm"], "mm")
        v.figure(f"{name}_ie_rom_deg", summ["ie_rom_deg"], "deg")
        if name == "def":
            for k in ("von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa",
                      "plastic_strain_max_surface", "plastic_strain_max_subsurface"):
                v.figure(k, summ[k])
            v.figure("ke_ie_max_pct", 100 * summ["kinetic_to_internal_max"], "%")
            v.figure("ke_ie_cycle_pct", 100 * summ["kinetic_to_internal_cycle"], "%")
            v.figure("elements", summ.get("solid_elements", summ.get("deformable_elements", 0)))


TABLE = """
| | rigid (elastic foundation, calibrated law) | deformable ({elements} elements, 0.5 mm over the footprint) |
|---|---|---|
| AP / IE RMS against rigid (acceptance: 1 mm / 1 deg) | | {ap_mm_rms:.3f} mm / {ie_deg_rms:.3f} deg |
| AP ROM / IE ROM | {rigid_ap_rom_mm:.2f} mm / {rigid_ie_rom_deg:.2f} deg | {def_ap_rom_mm:.2f} mm / {def_ie_rom_deg:.2f} deg |
| stance contact - applied axial force, RMS | {rigid_balance_N:.1f} N | {def_balance_N:.1f} N |
| peak pressure over the cycle | {rigid_peak_MPa:.1f} MPa | {def_peak_MPa:.1f} MPa (Pal 2008: 25.7, 1-99 % 23.9-27.7) |
| stance (0-60 %) mean of the frame peak | {rigid_stance_peak_MPa:.1f} MPa | {def_stance_peak_MPa:.1f} MPa |
| stance mean contact pressure | {rigid_stance_mean_MPa:.1f} MPa | {def_stance_mean_MPa:.1f} MPa |
| mean contact area (frames in contact) | {rigid_area_mm2:.0f} mm² | {def_area_mm2:.0f} mm² |
| von Mises max, surface layer / subsurface | | {von_mises_max_surface_MPa:.1f} / {von_mises_max_subsurface_MPa:.1f} MPa |
| equivalent plastic strain, surface / subsurface | | {plastic_strain_max_surface:.2g} / {plastic_strain_max_subsurface:.2g} |
| kinetic / internal energy, max (IE > 10 % of its max) / cycle sums (quasi-static below 5 %) | | {ke_ie_max_pct:.3f} % / {ke_ie_cycle_pct:.4f} % |
"""
