"""The deformable insert's time step against its own limit: one gait cycle of the 1.15 mm
insert (10 080 elements) with the solid's stable step raised by mass scaling to
deformable.dt_us = 10, 20 (the default), 30 and 40 us, each against the 10 us run (the
reference: a quarter of the default's added mass). What the default's step costs in accuracy,
and what a longer step (fewer steps per cycle, the cheapest way to a faster cycle) would."""
import math

TITLE = "Deformable insert: the mass-scaled time step"
LONG = True  # six deformable cycles on 10 080 elements, the 10 us ones 50-170 s: 6-15 minutes
NOISY = {f"s_{dt}": math.inf for dt in (10, 20, 30, 40)}  # run times: recorded only

STEPS_US = (10, 20, 30, 40)
MESH = ["--set", "insert=deformable", "--set", "deformable.element_size_mm=1.15",
        "--set", "solver.threads=2"]
KEYS = {"ap": "ap_rom_mm", "ie": "ie_rom_deg", "peak": "peak_pressure_MPa",
        "mpeak": "mean_peak_pressure_MPa", "area": "mean_contact_area_mm2",
        "wear": "cycle_wear_potential_Nmm"}


def _rms(a, b, col):
    n = min(len(a), len(b))
    return math.sqrt(sum((a[i][col] - b[i][col]) ** 2 for i in range(n)) / n)


def run(v):
    runs = {}
    for dt in STEPS_US:
        out = v.kneesim(f"dt{dt}", ["run", "--cycles", "1", "--no-plots", "--quiet"] + MESH
                        + ["--set", f"deformable.dt_us={dt}"])
        runs[dt] = (v.json(out, "summary.json"), v.csv(out, "kinematics.csv"))
    ref, ref_rows = runs[STEPS_US[0]]
    for dt, (s, rows) in runs.items():
        v.figure(f"steps_{dt}", s["steps_per_cycle"])
        v.figure(f"added_{dt}", s["solid_added_mass_kg"], "kg")
        v.figure(f"ke_{dt}", 100.0 * s["kinetic_to_internal_max_after_settling"], "%")
        v.figure(f"s_{dt}", s["seconds_per_cycle"], "s")
        for tag, key in KEYS.items():
            v.figure(f"{tag}_{dt}", s[key])
            v.figure(f"{tag}_{dt}_d", 100.0 * (s[key] / ref[key] - 1.0), "%")
        v.figure(f"aprms_{dt}", _rms(rows, ref_rows, "ap_mm"), "mm")
        v.figure(f"ierms_{dt}", _rms(rows, ref_rows, "ie_deg"), "deg")
    # the same two extreme steps without friction: how much of the step's effect is the scaled
    # surface mass riding the friction's stick-slip
    nofric = {}
    for dt in (STEPS_US[0], STEPS_US[-1]):
        out = v.kneesim(f"mu0_dt{dt}", ["run", "--cycles", "1", "--no-plots", "--quiet"] + MESH
                        + ["--set", f"deformable.dt_us={dt}", "--set", "contact.friction=0"])
        nofric[dt] = v.json(out, "summary.json")
    for tag, key in (("ie", "ie_rom_deg"), ("wear", "cycle_wear_potential_Nmm")):
        a, b = nofric[STEPS_US[0]][key], nofric[STEPS_US[-1]][key]
        v.figure(f"mu0_{tag}_{STEPS_US[0]}", a)
        v.figure(f"mu0_{tag}_{STEPS_US[-1]}", b)
        v.figure(f"mu0_{tag}_d", 100.0 * (b / a - 1.0), "%")


def _row(dt):
    label = f"{dt} us" + (" (default)" if dt == 20 else "")
    cells = [f"{{steps_{dt}:.0f}}", f"{{added_{dt}:.1f}}", f"{{ke_{dt}:.3f}}"]
    for tag, digits in (("ap", 2), ("ie", 2), ("peak", 1), ("mpeak", 1), ("area", 1),
                        ("wear", 0)):
        cells.append(f"{{{tag}_{dt}:.{digits}f}} ({{{tag}_{dt}_d:+.1f}} %)")
    cells.append(f"{{aprms_{dt}:.3f}} / {{ierms_{dt}:.3f}}")
    cells.append(f"{{s_{dt}:.0f}}")
    return f"| {label} | " + " | ".join(cells) + " |\n"


TABLE = ("""
| deformable.dt_us | steps per cycle | added mass (kg; the insert's own 0.035) | kinetic / internal max after settling (%) | AP range (mm) | IE range (deg) | peak pressure (MPa) | mean of the frame peak (MPa) | mean contact area (mm²) | cycle wear potential (N mm) | AP / IE RMS against 10 us (mm / deg) | s per cycle |
|---|---|---|---|---|---|---|---|---|---|---|---|
""" + "".join(_row(dt) for dt in STEPS_US) + """
(In brackets: against the 10 us row. `s per cycle` is recorded, not compared: the machine is
shared.)

Without friction (`--set contact.friction=0`), from 10 to 40 us: IE range {mu0_ie_10:.2f} ->
{mu0_ie_40:.2f} deg ({mu0_ie_d:+.1f} %), cycle wear potential {mu0_wear_10:.0f} -> {mu0_wear_40:.0f}
N mm ({mu0_wear_d:+.1f} %).
""")
