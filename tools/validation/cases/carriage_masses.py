"""Sensitivity of the default run's ranges of motion to the carriage masses, inertias and dampers
(this project's assumptions: the papers give none), to the time step, and the same rig integrated
by CVODE (the accurate solution of the same equations)."""
TITLE = "Carriage masses"
LONG = False
NOISY = {}

# key, default (models/config.h), label
KEYS = [("rig.ap_mass_kg", 0.06, "AP mass 0.06 kg"),
        ("rig.ml_mass_kg", 0.25, "ML mass 0.25 kg"),
        ("rig.is_mass_kg", 8.0, "IS (axial) mass 8 kg, sets the step"),
        ("rig.vv_inertia_kgm2", 0.01, "VV inertia 0.01 kg m²"),
        ("rig.ie_inertia_kgm2", 3e-5, "IE inertia 3e-5 kg m²"),
        ("rig.ap_damping_Ns_per_m", 1.0, "AP damper 1 N s/m"),
        ("rig.ml_damping_Ns_per_m", 5.0, "ML damper 5 N s/m"),
        ("rig.vv_damping_Nms_per_rad", 0.01, "VV damper 0.01 N m s/rad"),
        ("rig.ie_damping_Nms_per_rad", 0.003, "IE damper 0.003 N m s/rad")]


def _name(key):
    return key.split(".")[1]


def run(v):
    def ranges(name, sets):
        args = ["run", "--no-plots", "--quiet"]
        for s in sets:
            args += ["--set", s]
        s = v.json(v.kneesim(name, args), "summary.json")
        return s["ap_rom_mm"], s["ie_rom_deg"], s["steps_per_cycle"]

    ap0, ie0, steps0 = ranges("default", [])
    v.figure("default_ap_rom_mm", ap0, "mm")
    v.figure("default_ie_rom_deg", ie0, "deg")
    v.figure("default_steps", steps0, "")
    worst = 0.0
    for key, value, _ in KEYS:
        for tag, f in (("half", 0.5), ("double", 2.0)):
            ap, ie, _ = ranges(f"{_name(key)}_{tag}", [f"{key}={value * f:g}"])
            d_ap, d_ie = 100 * (ap / ap0 - 1), 100 * (ie / ie0 - 1)
            v.figure(f"{_name(key)}_{tag}_ap_pct", d_ap, "%")
            v.figure(f"{_name(key)}_{tag}_ie_pct", d_ie, "%")
            if key != "rig.is_mass_kg":
                worst = max(worst, abs(d_ap), abs(d_ie))
    v.figure("worst_pct", worst, "%")
    for tag, f in (("half", 0.5), ("quarter", 0.25)):
        ap, ie, steps = ranges(f"step_{tag}", [f"solver.dt_safety={0.8 * f:g}"])
        v.figure(f"step_{tag}_ap_pct", 100 * (ap / ap0 - 1), "%")
        v.figure(f"step_{tag}_ie_pct", 100 * (ie / ie0 - 1), "%")
    ap, ie, _ = ranges("cvode", ["solver.integrator=cvode"])
    v.figure("cvode_ap_rom_mm", ap, "mm")
    v.figure("cvode_ie_rom_deg", ie, "deg")
    v.figure("cvode_ap_pct", 100 * (ap / ap0 - 1), "%")
    v.figure("cvode_ie_pct", 100 * (ie / ie0 - 1), "%")


_rows = "\n".join(
    f"| {label} | {{{_name(k)}_half_ap_pct:+.1f}} % / {{{_name(k)}_half_ie_pct:+.1f}} % | "
    f"{{{_name(k)}_double_ap_pct:+.1f}} % / {{{_name(k)}_double_ie_pct:+.1f}} % |"
    for k, _, label in KEYS)

TABLE = """
Default run: AP range {default_ap_rom_mm:.2f} mm, IE range {default_ie_rom_deg:.2f} deg,
{default_steps:.0f} steps per cycle. Change of the AP / IE range when one value is halved or
doubled:

| parameter (default) | halved | doubled |
|---|---|---|
""" + _rows + """
| time step (solver.dt_safety 0.8) | {step_half_ap_pct:+.1f} % / {step_half_ie_pct:+.1f} % | quartered: {step_quarter_ap_pct:+.1f} % / {step_quarter_ie_pct:+.1f} % |

Largest change over the masses, inertias and dampers (the axial mass aside, which acts through
the step): {worst_pct:.1f} %. CVODE on the same rig: AP {cvode_ap_rom_mm:.2f} mm
({cvode_ap_pct:+.1f} %), IE {cvode_ie_rom_deg:.2f} deg ({cvode_ie_pct:+.1f} %).
"""
