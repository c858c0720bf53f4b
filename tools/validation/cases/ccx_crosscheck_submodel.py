"""The cut-out submodel of the CalculiX cross-check against CalculiX's whole insert, on the 2 mm
mesh where the whole insert is cheap: the same kneesim export (linear elastic, heel strike and
the two axial-load peaks) solved by ccx once on every element and once on the elements within
6 mm (x-z) of kneesim's contact nodes with the cut held at kneesim's displacement. What the cut
changes is what ccx_crosscheck_reference_mesh's submodel can be trusted to."""
import os
import shutil

TITLE = "CalculiX submodel against CalculiX's whole insert"
LONG = True  # one kneesim run of 2 cycles on the 2 mm mesh and six ccx solutions: ~10 min

ELEMENT_SIZE_MM = 2.0
SUBMODEL_MM = 6.0
PCTS = (0, 13, 45)
BCS = (("pose", "same pose"), ("load", "same axial load"))
QUANTITIES = (("peak", "peak_pressure_MPa", 2), ("mean", "mean_pressure_MPa", 2),
              ("area", "contact_area_mm2", 1), ("force", "axial_force_N", 0))


def run(v):
    if shutil.which("ccx") is None:
        raise v.skip("needs CalculiX (ccx); tools/scripts/setup.sh installs calculix-ccx")
    script = os.path.join(v.source, "tools", "scripts", "ccx_crosscheck.py")
    whole = os.path.join(v.dir, "whole")
    sub = os.path.join(v.dir, "submodel")
    mesh = "deformable.element_size_mm=%g" % ELEMENT_SIZE_MM
    pcts = ",".join(str(p) for p in PCTS)
    v.tool("/usr/bin/python3", [script, "--out", whole, "--kneesim",
                                os.path.join(v.build, "tools", "kneesim"), "--set", mesh,
                                "--materials", "elastic", "--pcts", pcts],
           record="/usr/bin/python3 tools/scripts/ccx_crosscheck.py --out DIR --set %s "
                  "--materials elastic --pcts %s" % (mesh, pcts))
    v.tool("/usr/bin/python3", [script, "--out", sub, "--export",
                                os.path.join(whole, "kneesim_elastic", "fe_export.json"),
                                "--pcts", pcts, "--submodel-mm", "%g" % SUBMODEL_MM],
           record="/usr/bin/python3 tools/scripts/ccx_crosscheck.py --out DIR1 --export "
                  "DIR/kneesim_elastic/fe_export.json --pcts %s --submodel-mm %g"
                  % (pcts, SUBMODEL_MM))
    rows_w = {(round(r["gait_pct"]), r["bc"]): r for r in v.json(whole, "crosscheck.json")["rows"]}
    rows_s = {(round(r["gait_pct"]), r["bc"]): r for r in v.json(sub, "crosscheck.json")["rows"]}
    for pct in PCTS:
        for bc, label in BCS:
            w, s = rows_w[(pct, label)], rows_s[(pct, label)]
            for q, name, _ in QUANTITIES:
                v.figure(f"p{pct}_{bc}_{q}_w", w["ccx_" + name])
                v.figure(f"p{pct}_{bc}_{q}_s", s["ccx_" + name])
                v.figure(f"p{pct}_{bc}_{q}_d", 100.0 * (s["ccx_" + name] - w["ccx_" + name])
                         / w["ccx_" + name], "%")
        v.figure(f"p{pct}_elements_s", rows_s[(pct, "same pose")]["ccx_elements"])
    v.figure("elements", v.json(whole, "crosscheck.json")["runs"][0]["elements"])


def _table():
    head = ("| gait % | CalculiX femur | submodel elements | peak pressure MPa, whole / submodel | "
            "mean pressure MPa | contact area mm² | axial contact force N |\n" + "|---" * 7 + "|\n")
    rows = []
    for pct in PCTS:
        for bc, label in BCS:
            cells = []
            for q, _, digits in QUANTITIES:
                k = "p%d_%s_%s_" % (pct, bc, q)
                cells.append("{%sw:.%df} / {%ss:.%df} ({%sd:+.2f} %%)" % (k, digits, k, digits, k))
            rows.append("| %d | %s | {p%d_elements_s:.0f} | %s |" % (pct, label, pct,
                                                                   " | ".join(cells)))
    tail = ("\nThe 2 mm insert ({elements:.0f} hex8 elements), linear elastic, the same kneesim "
            "export for both; submodel: the elements within %g mm of kneesim's contact nodes, "
            "the cut at kneesim's displacement.\n" % SUBMODEL_MM)
    return "\n" + head + "\n".join(rows) + "\n" + tail


TABLE = _table()
