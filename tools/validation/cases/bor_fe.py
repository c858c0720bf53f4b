"""The block-on-ring FE model (rigid ring on the hex8 block) against the semi-analytic Winkler
model, both under Archard at Hussin 2024's k_D: volumes must agree (5 %, the FE model's load
balance, wear integration and geometry update); depth, width and pressure are where a Winkler
foundation and an elastic solid differ."""
TITLE = "Block-on-ring: semi-analytic against FE"
LONG = True  # two FE runs of about 4 minutes each


def run(v):
    for F in (225, 130):
        an = {int(r["cycles"]): r for r in v.csv(v.kneesim(f"an{F}", ["bor", "--load-N", str(F)]), "bor.csv")}
        fe = {int(r["cycles"]): r for r in v.csv(v.kneesim(f"fe{F}", ["bor", "--model", "fe", "--load-N", str(F)]), "bor.csv")}
        for n in (0, 50000, 100000, 150000, 200000):
            a, f = an[n], fe[n]
            for src, r in (("an", a), ("fe", f)):
                v.figure(f"{src}{F}_{n}_volume_mm3", r["volume_mm3"], "mm3")
                v.figure(f"{src}{F}_{n}_depth_mm", r["depth_mm"], "mm")
                v.figure(f"{src}{F}_{n}_half_width_mm", r["contact_width_mm"] / 2, "mm")
                v.figure(f"{src}{F}_{n}_pressure_MPa", r["mean_pressure_MPa"], "MPa")
            if n:
                v.figure(f"diff{F}_{n}_pct", 100 * (f["volume_mm3"] / a["volume_mm3"] - 1), "%")


def _rows(F):
    out = []
    for n in (0, 50000, 100000, 150000, 200000):
        diff = f"{{diff{F}_{n}_pct:+.2f}} %" if n else ""
        cells = [f"{{an{F}_{n}_volume_mm3:.4f}}", f"{{fe{F}_{n}_volume_mm3:.4f}}", diff,
                 f"{{an{F}_{n}_depth_mm:.4f}}", f"{{fe{F}_{n}_depth_mm:.4f}}",
                 f"{{an{F}_{n}_half_width_mm:.3f}}", f"{{fe{F}_{n}_half_width_mm:.3f}}",
                 f"{{an{F}_{n}_pressure_MPa:.2f}}", f"{{fe{F}_{n}_pressure_MPa:.2f}}"]
        out.append(f"| {F} | {n} | " + " | ".join(cells) + " |")
    return "\n".join(out)


TABLE = ("| load N | cycles | volume mm³ semi-analytic | FE | FE - semi-analytic | depth mm semi-analytic | FE "
         "| half-width mm semi-analytic | FE | mean pressure MPa semi-analytic | FE |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|\n" + _rows(225) + "\n" + _rows(130) + "\n")
