"""The error contract: each class of bad input is refused with exit 2 and one sentence naming
the file, key or option, the value and the allowed range, before any simulation; two
acceptable inputs (a 3-column measured CSV, the same with a UTF-8 byte-order mark) run.
The meshes are the DM implant's, written as ASCII STL with one vertex broken or every
coordinate scaled."""
import os
import struct
import subprocess

TITLE = "Bad input: exit codes and messages"
LONG = False
FOOTER_COMMANDS = False

COMMANDS = [
    "diagnose bor --measured bor_falling.csv --out o_diag",
    "run ins_nan.toml --cycles 1 --out o_insnan --quiet",
    "wear ins_nan.toml --cycles 2 --update-every 1 --out o_insnan_w --quiet",
    "wear ins_huge.toml --cycles 2 --update-every 1 --out o_inshuge_w --quiet",
    "run fem_huge.toml --cycles 1 --out o_femhuge --quiet",
    "run fem_mm_as_m.toml --cycles 1 --out o_femmm --quiet",
    "run ins_mm_as_m.toml --cycles 1 --out o_insmm --quiet",
    "run both_m_as_mm.toml --cycles 1 --out o_masmm --quiet",
    "run --cycles 1 --set implant.edge_length_mm=3 --measured three.csv --out o_meas --quiet",
    "run --cycles 1 --set implant.edge_length_mm=3 --measured bom.csv --out o_bom --quiet",
    "particles --load-N -10 --out o_p1",
    "particles --load-N nan --out o_p2",
    "particles --max-iterations 0 --out o_p3",
    "compare --jobs 0 --out o_c1",
    "run --set gait.ap_sign=0.3 --out o_aps",
    "wear --cycles 99999999999999999999 --out o_w1",
    "wear --update-every 1 --out o_w2",
    "run --set contact.sdf_spacing_mm=0.05 --out o_sdf",
    "run --cycles 1 --set implant.edge_length_mm=3 --out afile --quiet",
    "run --cycles 1 --set implant.edge_length_mm=3 --out imm/sub --quiet",
    "wear --cycles 2 --update-every 1 --set implant.edge_length_mm=3 --out afile --quiet",
    "compare --cycles 2 --update-every 1 --set implant.edge_length_mm=3 --out afile --quiet",
    "particles --out afile",
    "bor --out afile",
    "diagnose bor --measured bor_good.csv --out afile",
    "study --out afile",
    "run --cycles 0",
    "bogus",
    "run --nope",
    "run --cycles 1 --set implant.edge_length_mm=3 --out imm --quiet",
    "wear --cycles 2 --update-every 1 --set implant.edge_length_mm=3 --out imm/sub --quiet",
    "study --out imm/sub",
    "wear no_law.toml --out o_law1",
    "compare foreign_param.toml --out o_law2",
    "run gain_range.toml --out o_law3",
    "study creep_zero.toml --wear --out o_law4",
]

# wear-law keys in a config file: a law that does not exist, a parameter the law does not
# have, one out of its range, creep with a zero time constant
LAW_CONFIGS = {
    "no_law.toml": '[wear]\nlaw = "magic"\n',
    "foreign_param.toml": '[wear]\nlaw = "running_in"\ncross_shear_gain = 2.0\n',
    "gain_range.toml": '[wear]\nlaw = "cross_shear"\ncross_shear_gain = -1.0\n',
    "creep_zero.toml": '[wear]\nlaw = "cross_shear"\ncreep = true\ncreep_time_s = 0.0\n',
}


def read_stl(path):
    data = open(path, "rb").read()
    if data[:5] == b"solid" and b"facet" in data[:400]:
        tris, cur = [], []
        for line in data.decode().splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                cur.append(tuple(float(x) for x in w[1:4]))
                if len(cur) == 3:
                    tris.append(cur)
                    cur = []
        return tris
    n = struct.unpack_from("<I", data, 80)[0]
    return [[struct.unpack_from("<3f", data, 84 + 50 * i + 12 + 12 * k) for k in range(3)] for i in range(n)]


def write_stl(path, tris, scale=1.0, first_x=None):
    with open(path, "w") as f:
        f.write("solid kneesim\n")
        for i, t in enumerate(tris):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for k, (x, y, z) in enumerate(t):
                if i == 0 and k == 0 and first_x is not None:
                    f.write(f"   vertex {first_x} {y * scale:.9g} {z * scale:.9g}\n")
                else:
                    f.write(f"   vertex {x * scale:.9g} {y * scale:.9g} {z * scale:.9g}\n")
            f.write("  endloop\n endfacet\n")
        f.write("endsolid kneesim\n")


def config(path, femur, insert, units):
    with open(path, "w") as f:
        f.write(f'[implant]\nkind = "mesh"\n[implant.mesh]\nfemur = "{femur}"\ninsert = "{insert}"\n'
                f'units = "{units}"\nrotation_deg = [0.0, 180.0, 0.0]\nfemur_origin_mm = [-5.5, 0.6, 0.0]\n')


def run(v):
    dm = v.require_data("gc6_dm")
    os.chdir(v.dir)
    fem, ins = read_stl(os.path.join(dm, "femoral_component.stl")), read_stl(os.path.join(dm, "tibial_insert.stl"))
    fem_orig, ins_orig = os.path.join(dm, "femoral_component.stl"), os.path.join(dm, "tibial_insert.stl")
    write_stl("insert_nan.stl", ins, first_x="nan")
    write_stl("insert_huge.stl", ins, first_x="1e30")
    write_stl("femur_huge.stl", fem, first_x="1e30")
    write_stl("femur_mm.stl", fem, scale=1000.0)
    write_stl("insert_mm.stl", ins, scale=1000.0)
    config("ins_nan.toml", fem_orig, "insert_nan.stl", "m")
    config("ins_huge.toml", fem_orig, "insert_huge.stl", "m")
    config("fem_huge.toml", "femur_huge.stl", ins_orig, "m")
    config("fem_mm_as_m.toml", "femur_mm.stl", ins_orig, "m")
    config("ins_mm_as_m.toml", fem_orig, "insert_mm.stl", "m")
    config("both_m_as_mm.toml", fem_orig, ins_orig, "mm")
    with open("bor_falling.csv", "w") as f:
        f.write("load_N,cycles,volume_mm3\n225,50000,0.5\n225,100000,0.4\n225,150000,0.3\n225,200000,0.2\n"
                "130,50000,0.3\n130,100000,0.6\n130,150000,0.9\n130,200000,1.2\n")
    with open("bor_good.csv", "w") as f:
        f.write("load_N,cycles,volume_mm3\n225,50000,0.5\n225,100000,1.0\n225,150000,1.5\n225,200000,2.0\n"
                "130,50000,0.3\n130,100000,0.6\n130,150000,0.9\n130,200000,1.2\n")
    rows = "gait_pct,ap_mm,ie_deg\n" + "".join(f"{p},{0.01 * p:.2f},{0.02 * p:.2f}\n" for p in range(0, 101, 10))
    open("three.csv", "w").write(rows)
    open("bom.csv", "w", encoding="utf-8-sig").write(rows)
    open("afile", "w").write("a file, not a folder\n")
    for name, text in LAW_CONFIGS.items():
        open(name, "w").write(text)
    os.makedirs("imm", exist_ok=True)
    subprocess.run(["chattr", "-i", "imm"], capture_output=True)
    if subprocess.run(["chattr", "+i", "imm"], capture_output=True).returncode != 0:
        raise v.skip("needs chattr +i (root) for the unwritable-folder rows")
    try:
        for i, c in enumerate(COMMANDS):
            rc, out, err = v.kneesim_status(c.split())
            lines = [l for l in err.strip().splitlines() if l.strip()]
            v.figure(f"c{i}_exit", str(rc))
            v.figure(f"c{i}_stderr", lines[-1].replace(v.dir + "/", "").replace(dm + "/", "") if lines else "")
    finally:
        subprocess.run(["chattr", "-i", "imm"], capture_output=True)


TABLE = "\n| command | exit | stderr |\n|---|---|---|\n" + "\n".join(
    f"| `kneesim {c}` | {{c{i}_exit}} | {{c{i}_stderr}} |" for i, c in enumerate(COMMANDS)) + "\n"
