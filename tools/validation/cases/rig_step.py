"""The two central-difference rig steps (solver.rig_coupling: partitioned, the default, and
coupled) at the default step (solver.dt_safety 0.8) and a quarter of it, against SUNDIALS
CVODE integrating the same equations to its tolerance: AP and IE ranges on the built-in
implant under ISO loads (stanmore and materials_study rigs) and on the JW implant under the
measured JW loads (low axial load with high AP force in early stance, condylar lift-off)."""
import math

TITLE = "Rig step: partitioned and coupled against CVODE"
LONG = True
NOISY = {"time_partitioned": math.inf, "time_coupled": math.inf}  # run times: recorded only

LOADS = {
    "iso": [],
    "ms": ["--set", "rig.preset=materials_study"],
    # the JW femoral FE axis of jw_stanmore.toml, for which a calibrated JW law ships
    "jw": ["{source}/models/examples/jw_measured_loads.toml",
           "--set", "implant.mesh.femur_origin_mm=[-3.8, 1.7, 0.0]"],
}
STEPS = {"08": "0.8", "02": "0.2"}


def run(v):
    v.require_data("gc4_jw/ngait_og3_knee_forces.csv")
    for load, base in LOADS.items():
        base = [a.format(source=v.source) for a in base]
        common = ["run"] + base + ["--no-plots", "--quiet"]
        c = v.json(v.kneesim(load + "_cvode", common + ["--set", "solver.integrator=cvode"]),
                   "summary.json")
        ref = (c["ap_rom_mm"], c["ie_rom_deg"])
        v.figure(load + "_cvode_ap", ref[0], "mm")
        v.figure(load + "_cvode_ie", ref[1], "deg")
        for scheme in ("partitioned", "coupled"):
            for tag, safety in STEPS.items():
                name = f"{load}_{scheme}_{tag}"
                s = v.json(v.kneesim(name, common + ["--set", "solver.rig_coupling=" + scheme,
                                                     "--set", "solver.dt_safety=" + safety]),
                           "summary.json")
                v.figure(name + "_ap", s["ap_rom_mm"], "mm")
                v.figure(name + "_ie", s["ie_rom_deg"], "deg")
                v.figure(name + "_ap_pct", 100.0 * (s["ap_rom_mm"] / ref[0] - 1.0), "%")
                v.figure(name + "_ie_pct", 100.0 * (s["ie_rom_deg"] / ref[1] - 1.0), "%")
                if load == "iso" and tag == "08":
                    v.figure("time_" + scheme, s["seconds_per_cycle"], "s")


def _cell(load, scheme, tag):
    n = f"{load}_{scheme}_{tag}"
    return (f"{{{n}_ap:.2f}} / {{{n}_ie:.2f}} ({{{n}_ap_pct:+.1f}} / {{{n}_ie_pct:+.1f}} %)")


_ROWS = {"iso": "built-in implant, `stanmore` rig, ISO loads",
         "ms": "built-in implant, `materials_study` rig, ISO loads",
         "jw": "JW implant, `stanmore` rig, measured JW loads"}

TABLE = ("""
AP range (mm) / IE range (deg), in brackets against CVODE:

| load case | CVODE | partitioned, dt_safety 0.8 (default) | partitioned, 0.2 | coupled, 0.8 | coupled, 0.2 |
|---|---|---|---|---|---|
""" + "".join(
    f"| {label} | {{{load}_cvode_ap:.2f}} / {{{load}_cvode_ie:.2f}} | "
    + " | ".join(_cell(load, s, t) for s in ("partitioned", "coupled") for t in ("08", "02"))
    + " |\n" for load, label in _ROWS.items()) + """
Seconds per cycle of the first row at the default step (recorded, not compared): partitioned
{time_partitioned:.3f}, coupled {time_coupled:.3f}.
""")
