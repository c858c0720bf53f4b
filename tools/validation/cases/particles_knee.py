"""kneesim particles for the knee inserts against polished CoCr: the cylinder is sized so that
its Hertz peak equals the insert's mean peak pressure, kneesim's own (rigid insert, `kneesim run
--set material.name=...`) and the materials study's (13.4 / 23.6 / 36.1 MPa)."""
TITLE = "Wear particles of the knee inserts against CoCr"
LONG = True  # six wear loops to the run-in steady state: 10-30 minutes

PAIRS = [("uhmwpe", "uhmwpe-cocr", "13.4"), ("peek", "peek-cocr", "23.6"), ("cfr", "cfrpeek-cocr", "36.1")]


def result(s):
    if s["particles"] == 0:
        return (f"none in {s['iterations']} iterations (steady: {'yes' if s['steady_state'] else 'no'}; "
                f"track Rq {s['track_rq_nm']['initial']:.0f} -> {s['track_rq_nm']['final']:.0f} nm)",
                "no yielded region reaches the surface")
    return (f"{s['particles']} in the reported iterations ({s['iterations']} iterations, steady: "
            f"{'yes' if s['steady_state'] else 'no'}; track Rq {s['track_rq_nm']['initial']:.0f} -> "
            f"{s['track_rq_nm']['final']:.0f} nm)",
            f"{s['mean_length_nm']:.0f} / {s['mean_width_nm']:.0f} / {s['mean_thickness_nm']:.0f} / "
            f"{s['mean_eq_radius_nm']:.0f} (volume-weighted R {s['volume_weighted_eq_radius_nm']:.0f} nm; "
            f"{100 * s['volume_fraction_eq_diameter_0p1_to_1um']:.0f} % of the volume at diameters 0.1-1 µm)")


def run(v):
    for key, pair, study in PAIRS:
        for src, extra in (("own", []), ("study", ["--contact-pressure-MPa", study])):
            s = v.json(v.kneesim(f"{key}_{src}", ["particles", "--pair", pair] + extra), "summary.json")
            v.figure(f"{key}_{src}_pressure_MPa", s["contact_pressure_MPa"], "MPa")
            v.figure(f"{key}_{src}_load_N", s["load_N"], "N")
            count, sizes = result(s)
            v.figure(f"{key}_{src}_count", count)
            v.figure(f"{key}_{src}_sizes", sizes)


TABLE = """
| insert | source of the contact pressure | contact pressure MPa | cylinder load N | particles | mean L / W / T / R nm |
|---|---|---|---|---|---|
| UHMWPE | kneesim (`kneesim run`) | {uhmwpe_own_pressure_MPa:.2f} | {uhmwpe_own_load_N:.2f} | {uhmwpe_own_count} | {uhmwpe_own_sizes} |
| | materials study | {uhmwpe_study_pressure_MPa:.1f} | {uhmwpe_study_load_N:.2f} | {uhmwpe_study_count} | {uhmwpe_study_sizes} |
| PEEK | kneesim | {peek_own_pressure_MPa:.2f} | {peek_own_load_N:.2f} | {peek_own_count} | {peek_own_sizes} |
| | materials study | {peek_study_pressure_MPa:.1f} | {peek_study_load_N:.2f} | {peek_study_count} | {peek_study_sizes} |
| CFR-PEEK | kneesim | {cfr_own_pressure_MPa:.2f} | {cfr_own_load_N:.2f} | {cfr_own_count} | {cfr_own_sizes} |
| | materials study | {cfr_study_pressure_MPa:.1f} | {cfr_study_load_N:.2f} | {cfr_study_count} | {cfr_study_sizes} |
"""
