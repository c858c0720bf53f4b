"""Convergence of the 5 Mc wear prediction in the geometry-update interval
(kneesim wear --convergence; the finest interval is the reference)."""
TITLE = "Wear update interval"
LONG = True  # 185 geometry updates in all: about 2 minutes on 2 idle cores

INTERVALS = [1000000, 500000, 250000, 100000, 50000]


def run(v):
    d = v.kneesim("convergence", ["wear", "--convergence", ",".join(map(str, INTERVALS)),
                                  "--no-plots", "--no-depth-maps", "--quiet"])
    rows = {int(r["update_every"]): r for r in v.csv(d, "convergence.csv")}
    ref = rows[INTERVALS[-1]]
    for n in INTERVALS:
        r = rows[n]
        v.figure(f"volume_{n}_mm3", r["volume_mm3"], "mm3")
        v.figure(f"depth_{n}_mm", r["max_depth_mm"], "mm")
        v.figure(f"volume_{n}_pct", 100 * (r["volume_mm3"] / ref["volume_mm3"] - 1), "%")
        v.figure(f"depth_{n}_pct", 100 * (r["max_depth_mm"] / ref["max_depth_mm"] - 1), "%")


TABLE = """
| cycles per update | updates | volume (mm³) | max depth (mm) | volume vs 50k | depth vs 50k |
|---|---|---|---|---|---|
| 1 000 000 | 5 | {volume_1000000_mm3:.2f} | {depth_1000000_mm:.4f} | {volume_1000000_pct:+.2f} % | {depth_1000000_pct:+.2f} % |
| 500 000 | 10 | {volume_500000_mm3:.2f} | {depth_500000_mm:.4f} | {volume_500000_pct:+.2f} % | {depth_500000_pct:+.2f} % |
| 250 000 (default) | 20 | {volume_250000_mm3:.2f} | {depth_250000_mm:.4f} | {volume_250000_pct:+.2f} % | {depth_250000_pct:+.2f} % |
| 100 000 | 50 | {volume_100000_mm3:.2f} | {depth_100000_mm:.4f} | {volume_100000_pct:+.2f} % | {depth_100000_pct:+.2f} % |
| 50 000 | 100 | {volume_50000_mm3:.2f} | {depth_50000_mm:.4f} | reference | reference |
"""
