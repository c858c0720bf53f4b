"""kneesim particles against the particle-size study's model: steel-steel at 10 N and 2.5 N
(L / W / T 442 / 245 / 197 nm and 267 / 161 / 151 nm; criterion a factor of 2) and the
steel-brass pair with and without the brass transfer film (the study: smaller with the film)."""
TITLE = "Wear particles against the particle-size study"
LONG = True  # four wear loops to the run-in steady state: 5-10 minutes on 2 threads

STUDY = {"n10": (442, 245, 197), "n2p5": (267, 161, 151)}
RUNS = [("n10", ["--pair", "steel-steel", "--load-N", "10"]),
        ("n2p5", ["--pair", "steel-steel", "--load-N", "2.5"]),
        ("sb", ["--pair", "steel-brass"]),
        ("sb0", ["--pair", "steel-brass", "--no-film"])]
SIZES = (("L", "mean_length_nm"), ("W", "mean_width_nm"), ("T", "mean_thickness_nm"), ("R", "mean_eq_radius_nm"))


def run(v):
    for key, args in RUNS:
        s = v.json(v.kneesim(f"particles_{key}", ["particles"] + args), "summary.json")
        for q, k in SIZES:
            v.figure(f"{key}_{q}_nm", s[k], "nm")
        v.figure(f"{key}_iterations", s["iterations"])
        v.figure(f"{key}_vw_R_nm", s["volume_weighted_eq_radius_nm"], "nm")
        v.figure(f"{key}_active_pct", 100 * s["volume_fraction_eq_diameter_0p1_to_1um"], "%")
        if key in STUDY:
            for (q, k), ref in zip(SIZES, STUDY[key]):
                v.figure(f"{key}_{q}_ratio", s[k] / ref)
        if key == "sb":
            c = s["counterface_particles"]
            v.figure("sb_film_particles", c["particles"])
            v.figure("sb_film_R_nm", c["mean_eq_radius_nm"], "nm")
    v.figure("layered_change_pct", 100 * (v.figures["sb_R_nm"]["value"] / v.figures["sb0_R_nm"]["value"] - 1), "%")


TABLE = """
| case | quantity | predicted | study's model | ratio | study's AFM |
|---|---|---|---|---|---|
| steel-steel 10 N | length nm | {n10_L_nm:.0f} | 442 | {n10_L_ratio:.2f} | 747 |
| | width nm | {n10_W_nm:.0f} | 245 | {n10_W_ratio:.2f} | 541 |
| | thickness nm | {n10_T_nm:.0f} | 197 | {n10_T_ratio:.2f} | 145 |
| | eq. radius nm | {n10_R_nm:.0f} (volume-weighted {n10_vw_R_nm:.0f}; {n10_active_pct:.0f} % of the volume at diameters 0.1-1 µm) | | | |
| steel-steel 2.5 N | length nm | {n2p5_L_nm:.0f} | 267 | {n2p5_L_ratio:.2f} | |
| | width nm | {n2p5_W_nm:.0f} | 161 | {n2p5_W_ratio:.2f} | |
| | thickness nm | {n2p5_T_nm:.0f} | 151 | {n2p5_T_ratio:.2f} | |
| | eq. radius nm | {n2p5_R_nm:.0f} | | | |
| steel-brass 10 N, layered (0.5 µm brass film on the cylinder, the preset; flowing with the disk; disk and film particles) | L / W / T / R nm | {sb_L_nm:.0f} / {sb_W_nm:.0f} / {sb_T_nm:.0f} / {sb_R_nm:.1f} (film's own: {sb_film_particles:.0f} particles, R {sb_film_R_nm:.1f}) | smaller than homogeneous: {layered_change_pct:+.0f} % in R | | |
| steel-brass 10 N, homogeneous (`--no-film`) | L / W / T / R nm | {sb0_L_nm:.0f} / {sb0_W_nm:.0f} / {sb0_T_nm:.0f} / {sb0_R_nm:.1f} | | | |

Iterations to the run-in steady state: {n10_iterations:.0f}, {n2p5_iterations:.0f}, {sb_iterations:.0f} and {sb0_iterations:.0f}.
"""
