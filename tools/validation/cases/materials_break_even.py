"""The break-even wear-factor ratio to UHMWPE of PEEK and CFR-PEEK at 5 Mc on the built-in
implant and the stanmore rig (kneesim compare: whole wear runs with geometry updates, solved to
0.1 %, or to a bracket of ratios 0.1 % wide across which the result jumps), set beside the
materials study's implied ratio (its own volume ratios, not independent) and the published ranges
(models/wear_literature.toml). The break-even depends on the contact model only; no wear factor
of PEEK or CFR-PEEK enters it."""
TITLE = "Materials: the break-even wear-factor ratio"
LONG = True
IMAGES = {"docs/img/compare_break_even.png": "compare_archard/compare_break_even.png"}

def run(v):
    for name, extra in (("archard", []),):
        d = v.kneesim(f"compare_{name}", ["compare", "--materials", "uhmwpe,peek,cfr-peek",
                                          "--quiet"] + extra)
        be = {r["material"]: r for r in v.csv(d, "break_even.csv")}
        for m, k in (("peek", "peek"), ("cfr-peek", "cfrpeek")):
            v.figure(f"{name}_{k}_volume", be[m]["break_even_volume_ratio"], "")
            v.figure(f"{name}_{k}_depth", be[m]["break_even_max_depth_ratio"], "")
            v.figure(f"{k}_own", be[m]["own_ratio"], "")
            for target, short in (("volume", "volume"), ("max_depth", "depth")):
                v.figure(f"{name}_{k}_{short}_how", how_found(be[m], target), "")


def how_found(row, target):
    """how the solve found the ratio: a run within its tolerance, or (the result is not smooth
    in the ratio: analysis/run/break_even.h) the step of the result inside a bracket narrower
    than the tolerance"""
    lo, hi = row[f"{target}_ratio_low"], row[f"{target}_ratio_high"]
    jump = row[f"{target}_jump_pct"]
    if lo == hi:
        return "a run within 0.1 %"
    if isinstance(jump, float) and jump == jump:
        return f"jumps by {jump:.2g} % between {lo:.5g} and {hi:.5g}"
    return f"between {lo:.5g} and {hi:.5g} (not converged)"


TABLE = """
| quantity | PEEK | CFR-PEEK |
|---|---|---|
| break-even ratio, equal volume, constant factors | {archard_peek_volume:.3f} | {archard_cfrpeek_volume:.3f} |
| break-even ratio, equal max depth, constant factors | {archard_peek_depth:.3f} | {archard_cfrpeek_depth:.3f} |
| how the volume ratio was found | {archard_peek_volume_how} | {archard_cfrpeek_volume_how} |
| how the depth ratio was found | {archard_peek_depth_how} | {archard_cfrpeek_depth_how} |
| the materials study's implied ratio (back-calculated from its volumes) | {peek_own:.2f} | {cfrpeek_own:.3f} |
| published ranges of the ratio | ≥ 1 (Brockett 2016); 30-100 (Brockett 2017) | 30-100 (Brockett 2017, knee simulator, CoCr); 0.01-0.1 below 6 MPa (Evans 2014, ceramic); ≤ 1 (Scholes & Unsworth 2009) |
"""
