"""Wear on the deformable insert: the hex mesh's volume loss against the depth integral on the
coarse insert of the default suite, and the deformable against the rigid insert at 5 Mc in two
updates (same sliding work, so the same Archard volume within a few per cent)."""
TITLE = "Deformable insert wear"
LONG = True  # four deformable wear runs: 10-40 minutes

COARSE = ["--cycles", "1000000", "--update-every", "500000", "--set", "insert=deformable",
          "--set", "deformable.element_size_mm=3", "--set", "deformable.layers=3",
          "--set", "implant.edge_length_mm=2", "--set", "gait.period_s=0.2"]
TWO = ["--cycles", "5000000", "--update-every", "2500000"]
DEF = ["--set", "insert=deformable", "--set", "deformable.element_size_mm=2"]


def run(v):
    s = v.json(v.kneesim("coarse", ["wear"] + COARSE + ["--no-plots", "--no-depth-maps", "--quiet"]), "summary.json")
    v.figure("coarse_volume_mm3", s["volume_mm3"], "mm3")
    v.figure("coarse_depth_volume_mm3", s["volume_depth_mm3"], "mm3")
    v.figure("coarse_bookkeeping_pct", 100 * (s["volume_mm3"] / s["volume_depth_mm3"] - 1), "%")
    for k in ("kinetic_to_internal_max", "kinetic_to_internal_cycle", "final_kinetic_to_internal_max",
              "final_kinetic_to_internal_cycle", "kinetic_to_internal_max_all_cycles"):
        v.figure(f"coarse_{k}_pct", 100 * s[k], "%")
    r = v.json(v.kneesim("stanmore_rigid", ["wear"] + TWO + ["--no-plots", "--no-depth-maps", "--quiet"]), "summary.json")
    d = v.json(v.kneesim("stanmore_def", ["wear"] + TWO + DEF + ["--no-plots", "--no-depth-maps", "--quiet"]), "summary.json")
    v.figure("stanmore_rigid_mm3", r["volume_mm3"], "mm3")
    v.figure("stanmore_def_mm3", d["volume_mm3"], "mm3")
    v.figure("stanmore_diff_pct", 100 * (d["volume_mm3"] / r["volume_mm3"] - 1), "%")
    v.figure("stanmore_def_bookkeeping_pct", 100 * d["volume_bookkeeping_rel_diff"], "%")
    for k in ("kinetic_to_internal_max", "kinetic_to_internal_cycle", "kinetic_to_internal_max_all_cycles"):
        v.figure(f"stanmore_def_{k}_pct", 100 * d[k], "%")
    ms = ["--set", "rig.preset=materials_study", "--no-plots", "--quiet"]
    cr = {x["material"]: x for x in v.csv(v.kneesim("ms_rigid", ["compare"] + TWO + ms), "comparison.csv")}
    cd = {x["material"]: x for x in v.csv(v.kneesim("ms_def", ["compare"] + TWO + DEF + ms), "comparison.csv")}
    for m, k in (("uhmwpe", "uhmwpe"), ("peek", "peek"), ("cfr-peek", "cfr")):
        v.figure(f"ms_{k}_rigid_mm3", cr[m]["volume_mm3"], "mm3")
        v.figure(f"ms_{k}_def_mm3", cd[m]["volume_mm3"], "mm3")
        v.figure(f"ms_{k}_diff_pct", 100 * (cd[m]["volume_mm3"] / cr[m]["volume_mm3"] - 1), "%")


TABLES = {
    "coarse": """
| check | reference | result |
|---|---|---|
| 1 080 elements, 0.2 s cycle, 1 Mc in 2 updates | hex volume loss vs depth integral within 1 % | {coarse_volume_mm3:.3f} / {coarse_depth_volume_mm3:.3f} mm³ ({coarse_bookkeeping_pct:+.2f} %) |
| kinetic / internal energy of the solid at this 0.2 s cycle (5 times the gait's speed, for economy): pristine cycle max / sum, last geometry max / sum, every cycle max | none: the check above needs no quasi-statics; kinetic energy grows with the speed squared | {coarse_kinetic_to_internal_max_pct:.2f} / {coarse_kinetic_to_internal_cycle_pct:.3f} %, {coarse_final_kinetic_to_internal_max_pct:.2f} / {coarse_final_kinetic_to_internal_cycle_pct:.3f} %, {coarse_kinetic_to_internal_max_all_cycles_pct:.2f} % |
| the same at the gait's 1 s cycle (stanmore, UHMWPE, 2 mm elements, 5 Mc in 2 updates, below): pristine cycle max / sum, every cycle max | quasi-static: below 5 % | {stanmore_def_kinetic_to_internal_max_pct:.3f} / {stanmore_def_kinetic_to_internal_cycle_pct:.4f} %, {stanmore_def_kinetic_to_internal_max_all_cycles_pct:.3f} % |
""",
    "two_updates": """
| rig, material | rigid (mm³) | deformable (mm³) |
|---|---|---|
| stanmore, UHMWPE | {stanmore_rigid_mm3:.1f} | {stanmore_def_mm3:.1f} ({stanmore_diff_pct:+.1f} %; bookkeeping {stanmore_def_bookkeeping_pct:+.2f} %) |
| materials_study, UHMWPE | {ms_uhmwpe_rigid_mm3:.1f} | {ms_uhmwpe_def_mm3:.1f} ({ms_uhmwpe_diff_pct:+.1f} %) |
| materials_study, PEEK | {ms_peek_rigid_mm3:.1f} | {ms_peek_def_mm3:.1f} ({ms_peek_diff_pct:+.1f} %) |
| materials_study, CFR-PEEK | {ms_cfr_rigid_mm3:.2f} | {ms_cfr_def_mm3:.2f} ({ms_cfr_diff_pct:+.1f} %) |
""",
}
