"""kneesim's deformable insert against CalculiX (ccx, an independent implicit FE code) on the
contact-law calibration's reference mesh (0.5 mm surface elements over the footprint, 6 layers
graded 0.15: the mesh on which UHMWPE pressures converge), linear elastic and J2 elastoplastic, at
heel strike and the two axial-load peaks of the second gait cycle, same pose and same axial load;
then CalculiX with kneesim's own penalty at the first peak (the penalty's share of the
difference). CalculiX solves a cut-out submodel: the elements within
6 mm (x-z) of kneesim's contact nodes at the instant, full thickness, the cut held at kneesim's
displacement (ccx_crosscheck_submodel checks the cut against whole-insert solutions)."""
import importlib.util
import math
import os
import shutil

_spec = importlib.util.spec_from_file_location(
    "kneesim_ccx_common", os.path.join(os.path.dirname(__file__), "_ccx_common.py"))
C = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(C)

TITLE = "Deformable insert against CalculiX, reference mesh"
LONG = True  # two kneesim runs of two cycles on ~49 000 elements, seven ccx submodel solutions: ~2.5 h
# run times on a shared machine: recorded, not compared (the 1 mm CalculiX instant took
# 1001 s and 383 s on two days)
NOISY = {"kneesim_s_per_cycle": math.inf, "ccx_s_mean": math.inf}

REFERENCE_MESH = ["deformable.element_size_mm=0.5", "deformable.layers=6",
                  "deformable.grading=0.15", "deformable.refine=contact"]
SUBMODEL_MM = 6.0
# the instants of the second cycle: the first cycle's 0 % is the start of the run, not a heel
# strike (the femur lowered onto the insert from rest)
CYCLES = 2
MODELS = ("elastic", "elastoplastic")
PCTS = (0, 13, 45)
SOFT_PCTS = (13,)  # CalculiX with kneesim's penalty: the first load peak only (time)
BCS = C.BCS
QUANTITIES = C.QUANTITIES
key = C.key


def _args():
    sets = [a for kv in REFERENCE_MESH + ["solver.threads=2"] for a in ("--set", kv)]
    return sets + ["--cycles", str(CYCLES), "--materials", ",".join(MODELS),
                   "--pcts", ",".join(str(p) for p in PCTS), "--submodel-mm", "%g" % SUBMODEL_MM]


def run(v):
    if shutil.which("ccx") is None:
        raise v.skip("needs CalculiX (ccx); tools/scripts/setup.sh installs calculix-ccx")
    out = os.path.join(v.dir, "crosscheck")
    script = os.path.join(v.source, "tools", "scripts", "ccx_crosscheck.py")
    v.tool("/usr/bin/python3", [script, "--out", out, "--kneesim",
                                os.path.join(v.build, "tools", "kneesim")] + _args(),
           record="/usr/bin/python3 tools/scripts/ccx_crosscheck.py --out DIR " + " ".join(_args()))
    result = v.json(out, "crosscheck.json")
    seconds = []
    for r in result["rows"]:
        model, pct, bc = C.record_row(v, r)
        v.figure(key(model, pct, "ccx", "elements", "n"), r["ccx_elements"])
        if bc == "pose":
            seconds.append(r["ccx_seconds"])
    # the penalty's share: CalculiX with kneesim's own penalty (the surface element's stiffness
    # per area) on the same export and submodel
    soft = os.path.join(v.dir, "crosscheck_kneesim_penalty")
    soft_args = ["--penalty-factor", "1", "--pcts", ",".join(str(p) for p in SOFT_PCTS),
                 "--submodel-mm", "%g" % SUBMODEL_MM]
    v.tool("/usr/bin/python3", [script, "--out", soft, "--export",
                                os.path.join(out, "kneesim_elastic", "fe_export.json")]
           + soft_args,
           record="/usr/bin/python3 tools/scripts/ccx_crosscheck.py --out DIR1 --export "
                  "DIR/kneesim_elastic/fe_export.json " + " ".join(soft_args))
    for r in v.json(soft, "crosscheck.json")["rows"]:
        pct = int(round(r["gait_pct"]))
        bc = "pose" if r["bc"] == "same pose" else "load"
        for q, name, _ in QUANTITIES[:4]:
            for code, side in (("k", "kneesim_"), ("c", "ccx_")):
                v.figure(f"soft{pct}_{bc}_{q}_{code}", r[side + name])
            a, b = r["kneesim_" + name], r["ccx_" + name]
            v.figure(f"soft{pct}_{bc}_{q}_d", 100.0 * (a - b) / b, "%")
    run0 = result["runs"][0]
    v.figure("elements", run0["elements"])
    v.figure("penalty_factor", result["penalty_factor"])
    v.figure("kneesim_penalty_MPa_per_mm", run0["kneesim_penalty_median_MPa_per_mm"], "MPa/mm")
    v.figure("kneesim_s_per_cycle", sum(x["kneesim_seconds"] for x in result["runs"])
             / (CYCLES * len(result["runs"])), "s")
    v.figure("ccx_s_mean", sum(seconds) / len(seconds), "s")


def _table():
    head = ("| insert material | gait % | CalculiX femur | CalculiX elements | peak pressure MPa, "
            "kneesim / ccx | mean pressure MPa | contact area mm² | axial contact force N | "
            "medial share | von Mises surface layer MPa | von Mises subsurface MPa |\n"
            + "|---" * 11 + "|\n")
    rows = []
    for model in MODELS:
        for pct in PCTS:
            for bc, label in BCS:
                rows.append("| %s | %d | %s | {%s:.0f} | %s |" % (
                    model, pct, label, key(model, pct, "ccx", "elements", "n"),
                    C.row_cells(model, pct, bc)))
    tail = ("\nkneesim's insert: the reference mesh ({elements:.0f} hex8 elements), linear "
            "elastic and J2 elastoplastic, heel strike and the load peaks of its second gait "
            "cycle; CalculiX: the submodel within %g mm "
            "of kneesim's contact nodes (its elements in the fourth column), C3D8I, penalty slope "
            "{penalty_factor:.0f} x the surface element's stiffness per area (kneesim's median "
            "{kneesim_penalty_MPa_per_mm:.0f} MPa/mm); run time on this machine: kneesim "
            "{kneesim_s_per_cycle:.0f} s per gait cycle, ccx {ccx_s_mean:.0f} s per instant (two "
            "static steps).\n" % SUBMODEL_MM)
    return "\n" + head + "\n".join(rows) + "\n" + tail


TABLE = _table()


TABLES = {"penalty": C.soft_table(SOFT_PCTS)}
