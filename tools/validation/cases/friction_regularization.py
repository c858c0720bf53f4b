"""Default 5 Mc wear and ranges of motion against the friction regularization's slip speed eps
(convergence as eps falls below the slip speeds that matter)."""
TITLE = "Friction regularization"
LONG = False
NOISY = {}

EPS = [("5", 5.0), ("1", 1.0), ("0p3", 0.3), ("0p1", 0.1), ("0p03", 0.03)]


def run(v):
    vols = {}
    for tag, eps in EPS:
        s = v.json(v.kneesim(f"eps_{tag}", ["wear", "--no-plots", "--no-depth-maps", "--quiet",
                                            "--set", f"contact.friction_regularization_mm_per_s={eps:g}"]),
                   "summary.json")
        v.figure(f"vol_{tag}", s["volume_mm3"], "mm3")
        v.figure(f"ap_{tag}", s["ap_rom_mm"], "mm")
        v.figure(f"ie_{tag}", s["ie_rom_deg"], "deg")
        v.figure(f"steps_{tag}", s["steps_per_cycle"], "")
        vols[tag] = s["volume_mm3"]
    for tag, _ in EPS:
        v.figure(f"dvol_{tag}", 100 * (vols[tag] / vols["0p1"] - 1), "%")


TABLE = """
| eps (mm/s) | 5 Mc volume (mm³) | against 0.1 mm/s | AP range (mm) | IE range (deg) | steps per cycle |
|---|---|---|---|---|---|
""" + "\n".join(f"| {eps:g}{' (default)' if tag == '0p1' else ''} | {{vol_{tag}:.2f}} | {{dvol_{tag}:+.1f}} % | {{ap_{tag}:.2f}} | {{ie_{tag}:.2f}} | {{steps_{tag}:.0f}} |"
                for tag, eps in EPS) + "\n"
