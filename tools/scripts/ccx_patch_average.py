#!/usr/bin/env python3
"""Whether kneesim's and CalculiX's peak contact pressures differ at one node or over the patch:
for each instant and CalculiX step of a ccx_crosscheck.py output folder, the peak nodal pressure
of both codes, where it sits (an interior node of the patch, or one with a node out of contact
within 0.8 mm), and the peak of the pressure averaged (tributary-area weighted) over every top
node within R mm of each node. Reads the folder's fe_export.json and CalculiX .dat files; runs
nothing.

Usage: ccx_patch_average.py CROSSCHECK_DIR [--radius-mm 0.6,1,1.5]
(CROSSCHECK_DIR holds kneesim_<model>/fe_export.json and <model>/<pct>pct/insert.dat.)"""
import argparse
import glob
import importlib.util
import json
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("ccx_crosscheck", os.path.join(HERE, "ccx_crosscheck.py"))
cc = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cc)


def averaged_peak(p, xz, area, radius):
    best = 0.0
    for i in np.nonzero(p > 0)[0]:
        m = np.linalg.norm(xz - xz[i], axis=1) <= radius
        best = max(best, float((p[m] * area[m]).sum() / area[m].sum()))
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--radius-mm", default="0.6,1,1.5")
    a = ap.parse_args()
    radii = [float(r) for r in a.radius_mm.split(",")]
    exports = sorted(glob.glob(os.path.join(a.dir, "kneesim_*", "fe_export.json")))
    if not exports:
        raise SystemExit("%s: no kneesim_*/fe_export.json (a ccx_crosscheck.py --out folder)" % a.dir)
    for path in exports:
        model = os.path.basename(os.path.dirname(path))[len("kneesim_"):]
        export = json.load(open(path))
        nodes = np.asarray(export["mesh"]["nodes_mm"], float)
        top = np.asarray(export["contact"]["top_nodes"])
        area = np.asarray(export["contact"]["tributary_area_mm2"], float)
        xz = nodes[top][:, [0, 2]]
        for inst in export["instants"]:
            d = os.path.join(a.dir, model, "%03.0fpct" % inst["gait_pct_requested"])
            if not os.path.exists(os.path.join(d, "insert.dat")):
                continue
            pk = np.asarray(inst["top_node_pressure_MPa"], float)
            for step, bc in zip(cc.read_results(d, export, len(export["mesh"]["elements"])),
                                ("same pose", "same axial load")):
                pc = step["cpress"]
                ik, ic = int(pk.argmax()), int(pc.argmax())
                where = lambda i: ("edge" if (pc[np.linalg.norm(xz - xz[i], axis=1) < 0.8] == 0).any()
                                   or (pk[np.linalg.norm(xz - xz[i], axis=1) < 0.8] == 0).any()
                                   else "interior")
                print("%s %.0f %% %s: peak kneesim %.2f (%s node), ccx %.2f (%s node), %.2f mm apart" % (
                    model, inst["gait_pct"], bc, pk[ik], where(ik), pc[ic], where(ic),
                    np.linalg.norm(xz[ik] - xz[ic])))
                for r in radii:
                    k, c = averaged_peak(pk, xz, area, r), averaged_peak(pc, xz, area, r)
                    print("    averaged within %.2g mm: kneesim %.2f, ccx %.2f MPa (%+.1f %%)" % (
                        r, k, c, 100 * (k / c - 1)))


if __name__ == "__main__":
    main()
