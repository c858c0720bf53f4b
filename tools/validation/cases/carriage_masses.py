"""Sensitivity of the default run's ranges of motion to the fictitious carriage masses."""
TITLE = "Carriage masses"
LONG = False

CASES = [("default", []), ("tibia_1kg", ["rig.tibia_mass_kg=1"]), ("tibia_4kg", ["rig.tibia_mass_kg=4"]),
         ("femur_4kg", ["rig.femur_mass_kg=4"])]


def run(v):
    base = None
    for name, sets in CASES:
        args = ["run", "--no-plots", "--quiet"]
        for s in sets:
            args += ["--set", s]
        s = v.json(v.kneesim(name, args), "summary.json")
        v.figure(f"{name}_ap_rom_mm", s["ap_rom_mm"], "mm")
        v.figure(f"{name}_ie_rom_deg", s["ie_rom_deg"], "deg")
        if base is None:
            base = s["ap_rom_mm"]
        else:
            v.figure(f"{name}_ap_change_pct", 100 * (s["ap_rom_mm"] / base - 1), "%")


TABLE = """
| change | AP ROM (mm) | IE ROM (deg) | AP ROM change |
|---|---|---|---|
| default (tibia 2 kg, femur 8 kg) | {default_ap_rom_mm:.2f} | {default_ie_rom_deg:.2f} | |
| tibia 1 kg | {tibia_1kg_ap_rom_mm:.2f} | {tibia_1kg_ie_rom_deg:.2f} | {tibia_1kg_ap_change_pct:+.1f} % |
| tibia 4 kg | {tibia_4kg_ap_rom_mm:.2f} | {tibia_4kg_ie_rom_deg:.2f} | {tibia_4kg_ap_change_pct:+.1f} % |
| femur 4 kg | {femur_4kg_ap_rom_mm:.2f} | {femur_4kg_ie_rom_deg:.2f} | {femur_4kg_ap_change_pct:+.1f} % |
"""
