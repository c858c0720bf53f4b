"""The particle-size study's roughness trend at the run-in steady state (steel-steel, 10 N): the
softer surface's roughness barely changes the particle size, the harder surface's does; three
seed pairs, each surface's Rq doubled in turn."""
import os

TITLE = "Wear particles: roughness trends"
LONG = True  # nine wear loops to the run-in steady state: 15-60 minutes

VARIANTS = (("base", ""), ("softer", "[softer]\nrq_nm = 1220\n"), ("harder", "[harder]\nrq_nm = 100\n"))


def run(v):
    means = {k: [] for k, _ in VARIANTS}
    for off in (0, 100, 200):
        for key, extra in VARIANTS:
            path = os.path.join(v.dir, f"{key}_{off}.toml")
            body = f'pair = "steel-steel"\nload_N = 10\n'
            soft = f"seed = {23 + off}\n"
            hard = f"seed = {11 + off}\n"
            if key == "softer":
                soft += "rq_nm = 1220\n"
            if key == "harder":
                hard += "rq_nm = 100\n"
            with open(path, "w") as f:
                f.write(body + "[softer]\n" + soft + "[harder]\n" + hard)
            s = v.json(v.kneesim(f"{key}_{off}", ["particles", path]), "summary.json")
            v.commands[-1] = v.commands[-1].replace(v.dir + "/", "")
            v.figure(f"{key}_{off}_R_nm", s["mean_eq_radius_nm"], "nm")
            v.figure(f"{key}_{off}_iterations", s["iterations"])
            means[key].append(s["mean_eq_radius_nm"])
    for key, vals in means.items():
        v.figure(f"{key}_mean_R_nm", sum(vals) / len(vals), "nm")
    for key in ("softer", "harder"):
        v.figure(f"{key}_change_pct", 100 * (v.figures[f"{key}_mean_R_nm"]["value"] / v.figures["base_mean_R_nm"]["value"] - 1), "%")


TABLE = """
| seeds (offset) | R base nm | softer Rq x2 (1220 nm) | harder Rq x2 (100 nm) |
|---|---|---|---|
""" + "\n".join(f"| +{o} | {{base_{o}_R_nm:.1f}} ({{base_{o}_iterations:.0f}} iterations) | {{softer_{o}_R_nm:.1f}} ({{softer_{o}_iterations:.0f}}) | "
                f"{{harder_{o}_R_nm:.1f}} ({{harder_{o}_iterations:.0f}}) |" for o in (0, 100, 200)) + """
| mean | {base_mean_R_nm:.1f} | {softer_mean_R_nm:.1f} ({softer_change_pct:+.1f} %) | {harder_mean_R_nm:.1f} ({harder_change_pct:+.1f} %) |

The configs are `pair = "steel-steel"`, `load_N = 10`, `[softer] seed = 23 + offset`, `[harder] seed = 11 + offset`, with `[softer] rq_nm = 1220` or `[harder] rq_nm = 100`.
"""
