"""Grid convergence of the particle model (build/tools/bench_particles): the same 24.5 um window
on 80^2 to 320^2 grids, at first contact (16 levels of 95 nm refined x4; 240h: 32 levels of
47.5 nm) and through the run-in wear loop; criterion: R, L, W, T change by less than 10 % from
240^2 to 320^2."""
TITLE = "Wear particles: grid convergence"
LONG = True  # bench_particles 1: 2-10 minutes on 2 threads


def run(v):
    out = v.tool("tools/bench_particles", ["1"])
    section = None
    for line in out.splitlines():
        if line.startswith("grid convergence"):
            section = "first"
        elif line.startswith("wear-loop grid convergence"):
            section = "loop"
        w = line.split()
        if section and w and w[0].rstrip("h").isdigit():
            n = w[0]
            if section == "first":
                keys = ("dx", "contact", "capped", "maxvm", "particles", "R", "L", "W", "T")
                vals = w[1:10]
            else:
                keys = ("dx", "iterations", "particles", "R", "L", "W", "T")
                vals = w[1:8]
            for k, val in zip(keys, vals):
                v.figure(f"{section}_{n}_{k}", float(val))
    for section in ("first", "loop"):
        for q in "RLWT":
            for a, b in (("160", "240"), ("240", "320")):
                v.figure(f"{section}_{q}_{a}_{b}_pct",
                         100 * (v.figures[f"{section}_{b}_{q}"]["value"] / v.figures[f"{section}_{a}_{q}"]["value"] - 1), "%")


FIRST = ["80", "120", "160", "240", "240h", "320"]
LOOP = ["80", "120", "160", "240", "320"]

TABLES = {
    "first": "\n| n | dx nm | contact | capped | max von Mises MPa | particles | R nm | L nm | W nm | T nm |\n|---|---|---|---|---|---|---|---|---|---|\n"
    + "\n".join(f"| {n} | {{first_{n}_dx:.1f}} | {{first_{n}_contact:.4f}} | {{first_{n}_capped:.4f}} | {{first_{n}_maxvm:.0f}} | "
                f"{{first_{n}_particles:.0f}} | {{first_{n}_R:.0f}} | {{first_{n}_L:.0f}} | {{first_{n}_W:.0f}} | {{first_{n}_T:.0f}} |" for n in FIRST)
    + "\n\n240² -> 320²: R {first_R_240_320_pct:+.1f} %, L {first_L_240_320_pct:+.1f} %, W {first_W_240_320_pct:+.1f} %, T {first_T_240_320_pct:+.1f} %.\n",
    "loop": "\n| n | dx nm | iterations | particles | R nm | L nm | W nm | T nm |\n|---|---|---|---|---|---|---|---|\n"
    + "\n".join(f"| {n} | {{loop_{n}_dx:.1f}} | {{loop_{n}_iterations:.0f}} | {{loop_{n}_particles:.0f}} | {{loop_{n}_R:.0f}} | "
                f"{{loop_{n}_L:.0f}} | {{loop_{n}_W:.0f}} | {{loop_{n}_T:.0f}} |" for n in LOOP)
    + "\n\n160² -> 240²: R {loop_R_160_240_pct:+.1f} %, L {loop_L_160_240_pct:+.1f} %, W {loop_W_160_240_pct:+.1f} %, T {loop_T_160_240_pct:+.1f} %; "
      "240² -> 320²: R {loop_R_240_320_pct:+.1f} %, L {loop_L_240_320_pct:+.1f} %, W {loop_W_240_320_pct:+.1f} %, T {loop_T_240_320_pct:+.1f} % (criterion 10 %).\n",
}
