#!/usr/bin/python3
"""Independent cross-check of kneesim's deformable insert against CalculiX (ccx).

    /usr/bin/python3 tools/scripts/ccx_crosscheck.py --out DIR [CONFIG] [--set KEY=VALUE ...]
        [--materials elastic,elastoplastic] [--pcts 0,13,45] [--penalty-factor 100]
        [--submodel-mm R] [--kneesim build/tools/kneesim] [--ccx ccx] [--threads 1]
        [--tolerance-pct 10]

For each insert material model it runs `kneesim run --set insert=deformable --set
contact.friction=0 --cycles 2 --export-fe` (heel strike and the two highest axial-load peaks of
the last cycle unless --pcts), then for each exported instant writes a CalculiX deck on
kneesim's own hex mesh, runs ccx and compares. `--export FILE` takes an existing
fe_export.json instead of running kneesim (one material model, the file's).

The CalculiX model (what makes the comparison fair: docs/validation.md, "Deformable insert against CalculiX"):
- the same mesh: kneesim's hex nodes and elements as C3D8I (incompatible modes; kneesim's
  one-point element with physical hourglass stiffness bends like one), base nodes fixed;
- the same material: linear elastic, or J2 with kneesim's isotropic hardening
  (*PLASTIC: yield at 0, the cap at (cap - yield) / H, flat beyond), NLGEOM;
- the same femur: the femoral component's triangles (the mesh kneesim's distance field was
  built from) near the insert, extruded inwards into a 0.5 mm layer of C3D6 wedges made one
  *RIGID BODY, placed at kneesim's pose of the instant (X_TF) lifted clear along T's y;
- node-to-surface penalty contact, frictionless (kneesim runs with contact.friction=0: a
  static solution has no sliding history to give friction a direction), slave = the insert's
  top faces, master = the femur's outer faces; linear pressure-overclosure with a slope of
  `--penalty-factor` times kneesim's median penalty per area (lambda + 2 mu) / L_n;
- two static steps per instant: step 1 lowers the femur to kneesim's pose exactly (same pose:
  the forces may differ), step 2 frees the femur's translation along T's y and loads it with
  the y component of kneesim's contact force (same axial load: the pose may differ); the other
  five rigid-body DOFs stay at kneesim's pose.

--submodel-mm R: CalculiX solves a cut-out submodel instead of the whole insert (for meshes too
large for a direct solve of every C3D8I element: the footprint-refined reference mesh): the
elements with a node within R mm, in the insert's x-z plane, of a top node kneesim has in contact
at the instant (whole columns through the thickness), the cut nodes held at kneesim's
displacement of the instant in both steps (base nodes stay fixed). Nodes and elements keep
kneesim's numbers. Von Mises maxima are then taken over the submodel's elements for both codes;
the contact measures are unchanged (no node outside the submodel is in contact in kneesim).
tools/validation/cases/ccx_crosscheck_submodel.py compares it with the whole insert.

Contact measures, computed the same way for both codes on the same nodes (kneesim's
definitions): nodal pressure (kneesim: penalty force / tributary area; ccx: CPRESS of the
slave node from *CONTACT PRINT CSTR); contact area = the tributary areas (a quarter of each
top quad) of the top nodes with pressure > 0; mean pressure = sum(p A) / area; peak = the
largest nodal pressure; medial / lateral force = sum(p A) over nodes with z < 0 / z > 0 in T.
Von Mises: per element, of the mean of ccx's 8 integration-point Cauchy stresses (kneesim:
its one-point second Piola-Kirchhoff stress; equal at these small strains), largest in the
surface layer (the elements under the top faces) and below it.

Writes DIR/crosscheck.csv (one row per material model, instant, boundary condition),
DIR/crosscheck.md (the table) and DIR/crosscheck.json; each ccx run in
DIR/<model>/<pct>pct/. Exit status 0 when every figure ran (the acceptance is reported, not
enforced, unless --check), 1 when ccx failed, 2 for bad input, 3 when --check finds a peak or
mean pressure or contact area of the same-load step beyond --tolerance-pct.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

FEMUR_LAYER_MM = 0.5       # thickness of the rigid femur's wedge layer (at most half a facet)
CULL_MM = 4.0              # femur triangles within this of a top node are kept
MEDIAL_Z_BELOW = 0.0       # medial: z < 0 in T (kneesim's convention, engine/insert_solid.cpp)

# C3D8 faces (ccx / Abaqus numbering, 1-based local nodes)
HEX_FACES = {1: (1, 2, 3, 4), 2: (5, 8, 7, 6), 3: (1, 5, 6, 2), 4: (2, 6, 7, 3),
             5: (3, 7, 8, 4), 6: (4, 8, 5, 1)}


def fail(msg, code=2):
    print("ccx_crosscheck: " + msg, file=sys.stderr)
    sys.exit(code)


# ----------------------------------------------------------------------------- geometry

def transform(X, pts):
    X = np.asarray(X, float)
    return pts @ X[:3, :3].T + X[:3, 3]


def top_face_numbers(elements, top_faces, top_face_element):
    """the ccx face number (S1..S6) of each top quad on the element under it"""
    out = []
    for quad, e in zip(top_faces, top_face_element):
        conn = elements[e]
        want = set(quad)
        for f, local in HEX_FACES.items():
            if {conn[i - 1] for i in local} == want:
                out.append(f)
                break
        else:
            fail("top face %s is not a face of element %d" % (quad, e))
    return out


def femur_patch(export, X_TF, top_xyz):
    """the femoral triangles near the insert's top nodes, in T, facing the insert"""
    V = transform(X_TF, np.asarray(export["femur"]["vertices_F_mm"], float))
    T = np.asarray(export["femur"]["triangles"], int)
    n = np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]])
    # nearest top node of every femur vertex, in chunks
    near = np.full(len(V), np.inf)
    for a in range(0, len(V), 2000):
        d = V[a:a + 2000, None, :] - top_xyz[None, :, :]
        near[a:a + 2000] = np.sqrt((d * d).sum(-1)).min(1)
    keep = (near[T] < CULL_MM).any(1) & (n[:, 1] < 0.0)
    T = T[keep]
    used = np.unique(T)
    index = -np.ones(len(V), int)
    index[used] = np.arange(len(used))
    # area-weighted vertex normals (outward) of the kept triangles
    nv = np.zeros((len(used), 3))
    for c in range(3):
        np.add.at(nv, index[T[:, c]], n[keep])
    nv /= np.linalg.norm(nv, axis=1)[:, None]
    return V[used], index[T], nv


# ----------------------------------------------------------------------------- the deck

def fmt(v):
    return "%.10g" % v


def submodel_elements(export, instant, radius_mm):
    """the elements of the cut-out submodel: every element with a node within radius_mm (in the
    insert's x-z plane, undeformed) of a top node kneesim has in contact at the instant, so the
    submodel keeps whole columns through the thickness under and around the patch; and the cut
    nodes (on a kept and a dropped element, not on the base), which CalculiX holds at kneesim's
    displacement of the instant"""
    mesh = export["mesh"]
    nodes = np.asarray(mesh["nodes_mm"], float)
    elements = np.asarray(mesh["elements"], int)
    top = np.asarray(export["contact"]["top_nodes"], int)
    touching = top[np.asarray(instant["top_node_pressure_MPa"], float) > 0.0]
    xz = nodes[:, [0, 2]]
    near = np.full(len(nodes), np.inf)
    for a in range(0, len(nodes), 4000):
        d = xz[a:a + 4000, None, :] - xz[touching][None, :, :]
        near[a:a + 4000] = np.sqrt((d * d).sum(-1)).min(1)
    keep = (near[elements] <= radius_mm).any(1)
    kept_nodes = np.zeros(len(nodes), bool)
    kept_nodes[elements[keep].ravel()] = True
    dropped_nodes = np.zeros(len(nodes), bool)
    dropped_nodes[elements[~keep].ravel()] = True
    cut = kept_nodes & dropped_nodes
    cut[np.asarray(mesh["base_nodes"], int)] = False
    return keep, np.flatnonzero(cut)


def write_deck(path, export, instant, penalty, lift_mm, axial_load_N, keep=None, cut=()):
    """keep: the elements of a cut-out submodel (None: the whole insert); cut: its cut nodes,
    held at kneesim's displacement of the instant in both steps"""
    mesh = export["mesh"]
    mat = export["material"]
    nodes = np.asarray(mesh["nodes_mm"], float)
    elements = mesh["elements"]
    if keep is None:
        keep = np.ones(len(elements), bool)
    used = np.zeros(len(nodes), bool)
    used[np.asarray(elements, int)[keep].ravel()] = True
    top_nodes = [t for t in export["contact"]["top_nodes"] if used[t]]
    faces = top_face_numbers(elements, mesh["top_faces"], mesh["top_face_element"])
    u_cut = (np.asarray(instant["node_position_mm"], float)[cut] - nodes[cut]) if len(cut) else []
    X = np.asarray(instant["X_TF_mm"], float)
    X[1, 3] += lift_mm
    fv, ft, fn = femur_patch(export, X, nodes[top_nodes])
    n_ins, e_ins = len(nodes), len(elements)
    # the rigid layer no thicker than half a facet: offset along the vertex normals by more
    # than a fine triangulation's curvature radius at the femur's rounded edges, it inverts
    edges = np.linalg.norm(fv[ft[:, 1]] - fv[ft[:, 0]], axis=1)
    inner = fv - min(FEMUR_LAYER_MM, 0.5 * float(np.median(edges))) * fn
    outer_id = n_ins + 1 + np.arange(len(fv))
    inner_id = n_ins + 1 + len(fv) + np.arange(len(fv))
    ref, rot = n_ins + 2 * len(fv) + 1, n_ins + 2 * len(fv) + 2
    L = []
    w = L.append
    w("*HEADING")
    w("kneesim deformable insert cross-check, gait %.2f %%" % instant["gait_pct"])
    w("** units mm, N, MPa; frame T of kneesim (y up, z < 0 medial)")
    w("*NODE, NSET=NINSERT")
    for i, p in enumerate(nodes):
        if used[i]:
            w("%d, %s, %s, %s" % (i + 1, fmt(p[0]), fmt(p[1]), fmt(p[2])))
    w("*NODE, NSET=NFEMUR")
    for k in range(len(fv)):
        w("%d, %s, %s, %s" % (outer_id[k], fmt(fv[k, 0]), fmt(fv[k, 1]), fmt(fv[k, 2])))
        w("%d, %s, %s, %s" % (inner_id[k], fmt(inner[k, 0]), fmt(inner[k, 1]), fmt(inner[k, 2])))
    w("*NODE, NSET=NREF")
    w("%d, %s, %s, %s" % (ref, fmt(X[0, 3]), fmt(X[1, 3]), fmt(X[2, 3])))
    w("*NODE, NSET=NROT")
    w("%d, %s, %s, %s" % (rot, fmt(X[0, 3]), fmt(X[1, 3]), fmt(X[2, 3])))
    w("*ELEMENT, TYPE=C3D8I, ELSET=EINSERT")
    for e, conn in enumerate(elements):
        if keep[e]:
            w("%d, %s" % (e + 1, ", ".join(str(c + 1) for c in conn)))
    # wedges: inner triangle (1-2-3) below the outer one (4-5-6), both counter-clockwise seen
    # from outside, so the element's volume is positive and face S2 is the outer surface
    w("*ELEMENT, TYPE=C3D6, ELSET=EFEMUR")
    for k, t in enumerate(ft):
        w("%d, %d, %d, %d, %d, %d, %d" % (e_ins + 1 + k, inner_id[t[0]], inner_id[t[1]],
                                          inner_id[t[2]], outer_id[t[0]], outer_id[t[1]],
                                          outer_id[t[2]]))
    w("*NSET, NSET=NBASE")
    base = [b + 1 for b in mesh["base_nodes"] if used[b]]
    for a in range(0, len(base), 16):
        w(", ".join(str(b) for b in base[a:a + 16]))
    w("*ELSET, ELSET=ESURFACE")
    surf = sorted({e + 1 for e in mesh["top_face_element"] if keep[e]})
    for a in range(0, len(surf), 16):
        w(", ".join(str(b) for b in surf[a:a + 16]))
    w("*MATERIAL, NAME=INSERT")
    w("*ELASTIC")
    w("%s, %s" % (fmt(mat["youngs_modulus_MPa"]), fmt(mat["poisson"])))
    if mat["model"] == "j2":
        y, H, cap = mat["yield_MPa"], mat["hardening_MPa"], mat["yield_cap_MPa"]
        w("*PLASTIC")
        w("%s, 0" % fmt(y))
        if H > 0.0:
            if cap > y:
                w("%s, %s" % (fmt(cap), fmt((cap - y) / H)))
            else:
                w("%s, 1" % fmt(y + H))
    w("*SOLID SECTION, ELSET=EINSERT, MATERIAL=INSERT")
    w("*MATERIAL, NAME=RIGID")
    w("*ELASTIC")
    w("210000, 0.3")
    w("*SOLID SECTION, ELSET=EFEMUR, MATERIAL=RIGID")
    w("*RIGID BODY, ELSET=EFEMUR, REF NODE=%d, ROT NODE=%d" % (ref, rot))
    w("*SURFACE, NAME=SINSERT, TYPE=ELEMENT")
    for e, f in zip(mesh["top_face_element"], faces):
        if keep[e]:
            w("%d, S%d" % (e + 1, f))
    w("*SURFACE, NAME=SFEMUR, TYPE=ELEMENT")
    for k in range(len(ft)):
        w("%d, S2" % (e_ins + 1 + k))
    w("*SURFACE INTERACTION, NAME=SI")
    w("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR")
    # slope, tension at large clearance (a thousandth of a MPa: negligible against the
    # contact pressures of tens of MPa)
    w("%s, 0.001" % fmt(penalty))
    w("*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE")
    w("SINSERT, SFEMUR")
    w("*AMPLITUDE, NAME=HOLD")
    w("0, 1, 1, 1")
    w("*BOUNDARY")
    w("NBASE, 1, 3")
    w("NROT, 1, 3")
    w("NREF, 1, 1")
    w("NREF, 3, 3")
    # printed at the end of each step only
    outputs = ["*NODE PRINT, NSET=NREF, FREQUENCY=10000", "U, RF",
               "*EL PRINT, ELSET=EINSERT, FREQUENCY=10000", "S",
               "*CONTACT PRINT, FREQUENCY=10000", "CSTR, CDIS"]
    if mat["model"] == "j2":
        outputs[3] = "S, PEEQ"
    # step 1: the femur lowered to kneesim's pose
    w("*STEP, NLGEOM, INC=400")
    w("*STATIC")
    w("0.2, 1.0, 1e-6, 0.25")
    w("*BOUNDARY")
    w("NREF, 2, 2, %s" % fmt(-lift_mm))
    cut_lines = ["%d, %d, %d, %s" % (n + 1, c + 1, c + 1, fmt(u[c]))
                 for n, u in zip(cut, u_cut) for c in range(3)]
    L.extend(cut_lines)
    L.extend(outputs)
    w("*END STEP")
    # step 2: the femur's y translation free under kneesim's axial contact force
    w("*STEP, NLGEOM, INC=400")
    w("*STATIC")
    w("0.25, 1.0, 1e-6, 1.0")
    w("*BOUNDARY, OP=NEW")
    w("NBASE, 1, 3")
    w("NROT, 1, 3")
    w("NREF, 1, 1")
    w("NREF, 3, 3")
    L.extend(cut_lines)
    w("*CLOAD, AMPLITUDE=HOLD")
    w("%d, 2, %s" % (ref, fmt(-axial_load_N)))
    L.extend(outputs)
    w("*END STEP")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")
    return {"femur_triangles": len(ft), "femur_nodes": len(fv), "ref_node": ref,
            "elements": int(keep.sum()), "cut_nodes": len(cut)}


# ----------------------------------------------------------------------------- ccx output

def parse_dat(path):
    """the .dat file's blocks as (title, total time, rows of numbers)"""
    blocks = []
    cur = None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            if " and time " in s:
                cur = {"title": s.lower(), "time": float(s.split()[-1]), "rows": []}
                blocks.append(cur)
            elif cur is not None and (s[0].isdigit() or s[0] == "-"):
                cur["rows"].append([float(x) for x in s.split()])
    return blocks


# ----------------------------------------------------------------------------- measures

def contact_measures(pressure, area, top_z):
    p = np.asarray(pressure, float)
    on = p > 0.0
    A = np.asarray(area, float)
    f = p * A
    total_area = A[on].sum()
    med = on & (top_z < MEDIAL_Z_BELOW)
    lat = on & ~(top_z < MEDIAL_Z_BELOW)
    return {
        "peak_pressure_MPa": float(p.max()) if on.any() else 0.0,
        "mean_pressure_MPa": float(f[on].sum() / total_area) if total_area > 0 else 0.0,
        "contact_area_mm2": float(total_area),
        "medial_force_N": float(f[med].sum()),
        "lateral_force_N": float(f[lat].sum()),
        "nodes_in_contact": int(on.sum()),
    }


def von_mises(s):
    sxx, syy, szz, sxy, sxz, syz = s
    return math.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                     + 3.0 * (sxy ** 2 + sxz ** 2 + syz ** 2))


def stress_measures(vm_element, surface_mask, keep):
    """the largest element von Mises stress in the surface layer and below it, over the
    elements CalculiX has (keep: the whole insert, or the submodel's elements)"""
    vm = np.asarray(vm_element, float)
    return {"von_mises_surface_MPa": float(vm[surface_mask & keep].max()),
            "von_mises_subsurface_MPa": float(vm[~surface_mask & keep].max())}


def run_ccx(ccx, deck_dir, threads, log):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads),
               CCX_NPROC_EQUATION_SOLVER=str(threads), CCX_NPROC_RESULTS=str(threads))
    t0 = time.time()
    with open(os.path.join(deck_dir, "ccx.log"), "w") as out:
        r = subprocess.run(["nice", "-n", "10", ccx, "-i", "insert"], cwd=deck_dir, env=env,
                           stdout=out, stderr=subprocess.STDOUT)
    seconds = time.time() - t0
    with open(os.path.join(deck_dir, "ccx.log")) as f:
        text = f.read()
    if r.returncode != 0 or "Job finished" not in text:
        tail = "\n".join(text.strip().splitlines()[-8:])
        fail("ccx failed in %s (exit %d):\n%s" % (deck_dir, r.returncode, tail), 1)
    log("  ccx %.1f s" % seconds)
    return seconds


def read_results(deck_dir, export, n_elements, steps=2):
    """per step (its end, total time k for step k): CPRESS of the top nodes (MPa, 0 where not
    in contact), the femur's U and RF, element von Mises and plastic strain"""
    blocks = parse_dat(os.path.join(deck_dir, "insert.dat"))
    index = {n + 1: i for i, n in enumerate(export["contact"]["top_nodes"])}
    out = []
    for k in range(1, steps + 1):
        mine = [b for b in blocks if abs(b["time"] - k) < 1e-6]
        r = {"u": None, "rf": None, "cpress": np.zeros(len(index)),
             "von_mises": np.zeros(n_elements), "von_mises_ip": np.zeros(n_elements),
             "peeq": np.zeros(n_elements)}
        stress = {}
        for b in mine:
            t = b["title"]
            if t.startswith("displacements"):
                r["u"] = b["rows"][0][1:4]
            elif t.startswith("forces"):
                r["rf"] = b["rows"][0][1:4]
            elif t.startswith("stresses"):
                for row in b["rows"]:
                    stress.setdefault(int(row[0]), []).append(row[2:8])
            elif t.startswith("equivalent plastic strain"):
                for row in b["rows"]:
                    e = int(row[0]) - 1
                    r["peeq"][e] = max(r["peeq"][e], row[2])
            elif t.startswith("contact stress"):
                for row in b["rows"]:
                    if int(row[0]) in index:
                        r["cpress"][index[int(row[0])]] = row[1]
        if r["u"] is None or not stress:
            fail("%s: no results at the end of step %d (ccx stopped early?)" % (deck_dir, k), 1)
        for e, ips in stress.items():
            a = np.asarray(ips, float)
            r["von_mises"][e - 1] = von_mises(a.mean(0))
            r["von_mises_ip"][e - 1] = max(von_mises(x) for x in a)
        out.append(r)
    return out


# ----------------------------------------------------------------------------- driver

def run_kneesim(args, model_name, out_dir):
    cmd = [args.kneesim, "run", "--out", out_dir, "--cycles", str(args.cycles), "--no-plots",
           "--quiet", "--set", "insert=\"deformable\"", "--set", "contact.friction=0",
           "--set", "deformable.material=\"%s\"" % model_name]
    if args.config:
        cmd.insert(2, args.config)
    for s in args.set or []:
        cmd += ["--set", s]
    cmd += ["--export-fe-pcts", args.pcts] if args.pcts else ["--export-fe"]
    print("kneesim: " + " ".join(cmd), flush=True)
    t0 = time.time()
    r = subprocess.run(["nice", "-n", "10"] + cmd)
    if r.returncode != 0:
        fail("kneesim run failed (exit %d)" % r.returncode, 1)
    summary = json.load(open(os.path.join(out_dir, "summary.json")))
    return os.path.join(out_dir, "fe_export.json"), time.time() - t0, summary


def pct_diff(a, b):
    return 100.0 * (a - b) / b if b != 0 else float("nan")


def crosscheck(args, export_path, model_label, kneesim_seconds, rows, details):
    export = json.load(open(export_path))
    mesh = export["mesh"]
    nodes = np.asarray(mesh["nodes_mm"], float)
    top = export["contact"]["top_nodes"]
    area = np.asarray(export["contact"]["tributary_area_mm2"], float)
    top_z = nodes[top, 2]
    n_el = len(mesh["elements"])
    surface = np.zeros(n_el, bool)
    surface[mesh["top_face_element"]] = True
    # kneesim's penalty per area: the surface element's own stiffness, (lambda + 2 mu) / L_n
    k_per_area = np.asarray(export["contact"]["penalty_N_per_mm"]) / area
    penalty = args.penalty_factor * float(np.median(k_per_area))
    print("%s: %d elements, %d top nodes; kneesim penalty per area %.0f-%.0f MPa/mm "
          "(median %.0f), ccx slope %.0f MPa/mm" % (
              model_label, n_el, len(top), k_per_area.min(), k_per_area.max(),
              np.median(k_per_area), penalty), flush=True)
    wanted = [float(v) for v in args.pcts.split(",")] if args.pcts else None
    for inst in export["instants"]:
        pct = inst["gait_pct_requested"]
        if wanted is not None and not any(abs(pct - v) < 1e-9 for v in wanted):
            continue
        d = os.path.join(args.out, model_label, "%03.0fpct" % pct)
        os.makedirs(d, exist_ok=True)
        x = np.asarray(inst["node_position_mm"], float)
        p_k = np.asarray(inst["top_node_pressure_MPa"], float)
        # the femur starts clear of the undeformed insert: deformation plus penalty overlap
        pen = p_k * area / np.asarray(export["contact"]["penalty_N_per_mm"])
        lift = 1.2 * (np.linalg.norm(x[top] - nodes[top], axis=1).max() + pen.max()) + 0.02
        axial = -inst["contact_force_on_insert_T_N"][1]
        kn = contact_measures(p_k, area, top_z)
        if args.submodel_mm is not None and kn["nodes_in_contact"] > 0:
            keep, cut = submodel_elements(export, inst, args.submodel_mm)
        else:
            keep, cut = np.ones(n_el, bool), np.zeros(0, int)
        kn.update(stress_measures(inst["element_von_mises_MPa"], surface, keep))
        kn["plastic_strain_max"] = float(max(inst["element_plastic_strain"]))
        kn["axial_force_N"] = axial
        info = write_deck(os.path.join(d, "insert.inp"), export, inst, penalty, lift, axial,
                          keep, cut)
        print("%s %.1f %%: axial contact force %.0f N, lift %.3f mm, %d femur triangles, "
              "%d of %d elements in CalculiX, %d cut nodes at kneesim's displacement" % (
                  model_label, inst["gait_pct"], axial, lift, info["femur_triangles"],
                  info["elements"], n_el, info["cut_nodes"]), flush=True)
        if kn["nodes_in_contact"] == 0:
            print("  kneesim has no contact at this instant: skipped", flush=True)
            continue
        seconds = run_ccx(args.ccx, d, args.threads, print)
        results = read_results(d, export, n_el)
        for step, bc in zip(results, ("same pose", "same axial load")):
            cx = contact_measures(step["cpress"], area, top_z)
            cx.update(stress_measures(step["von_mises"], surface, keep))
            cx["von_mises_ip_max_MPa"] = float(step["von_mises_ip"].max())
            cx["plastic_strain_max"] = float(step["peeq"].max())
            # RF: the force the prescribed DOF needs, opposite to the insert's push on the femur
            cx["axial_force_N"] = -float(step["rf"][1]) if step["rf"] else float("nan")
            cx["femur_y_mm"] = float(step["u"][1]) + lift if step["u"] else float("nan")
            row = {"model": model_label, "gait_pct": round(inst["gait_pct"], 2), "bc": bc,
                   "ccx_seconds": round(seconds, 1), "ccx_elements": info["elements"],
                   "ccx_cut_nodes": info["cut_nodes"]}
            for key in ("peak_pressure_MPa", "mean_pressure_MPa", "contact_area_mm2",
                        "medial_force_N", "lateral_force_N", "von_mises_surface_MPa",
                        "von_mises_subsurface_MPa", "axial_force_N", "plastic_strain_max"):
                row["kneesim_" + key] = kn[key]
                row["ccx_" + key] = cx[key]
            row["ccx_femur_y_mm"] = cx["femur_y_mm"]
            row["ccx_contact_force_sum_N"] = cx["medial_force_N"] + cx["lateral_force_N"]
            row["kneesim_medial_share"] = kn["medial_force_N"] / max(
                1e-9, kn["medial_force_N"] + kn["lateral_force_N"])
            row["ccx_medial_share"] = cx["medial_force_N"] / max(
                1e-9, cx["medial_force_N"] + cx["lateral_force_N"])
            row["kneesim_nodes_in_contact"] = kn["nodes_in_contact"]
            row["ccx_nodes_in_contact"] = cx["nodes_in_contact"]
            rows.append(row)
            print("  %-16s peak %.2f / %.2f MPa (%+.1f %%), mean %.2f / %.2f (%+.1f %%), area "
                  "%.1f / %.1f mm2 (%+.1f %%), axial %.0f / %.0f N, medial share %.3f / %.3f, "
                  "von Mises surface %.2f / %.2f, subsurface %.2f / %.2f MPa" % (
                      bc, kn["peak_pressure_MPa"], cx["peak_pressure_MPa"],
                      pct_diff(kn["peak_pressure_MPa"], cx["peak_pressure_MPa"]),
                      kn["mean_pressure_MPa"], cx["mean_pressure_MPa"],
                      pct_diff(kn["mean_pressure_MPa"], cx["mean_pressure_MPa"]),
                      kn["contact_area_mm2"], cx["contact_area_mm2"],
                      pct_diff(kn["contact_area_mm2"], cx["contact_area_mm2"]),
                      kn["axial_force_N"], cx["axial_force_N"], row["kneesim_medial_share"],
                      row["ccx_medial_share"], kn["von_mises_surface_MPa"],
                      cx["von_mises_surface_MPa"], kn["von_mises_subsurface_MPa"],
                      cx["von_mises_subsurface_MPa"]), flush=True)
    details.append({"model": model_label, "export": export_path,
                    "kneesim_seconds": kneesim_seconds, "elements": n_el,
                    "top_nodes": len(top), "ccx_penalty_MPa_per_mm": penalty,
                    "kneesim_penalty_median_MPa_per_mm": float(np.median(k_per_area))})


def write_tables(args, rows, details):
    import csv
    keys = list(rows[0].keys()) if rows else []
    with open(os.path.join(args.out, "crosscheck.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=keys)
        wr.writeheader()
        for r in rows:
            wr.writerow(r)
    def strict(v):  # JSON has no NaN (strict readers such as nlohmann refuse it): null
        if isinstance(v, float) and not math.isfinite(v):
            return None
        if isinstance(v, dict):
            return {k: strict(x) for k, x in v.items()}
        if isinstance(v, list):
            return [strict(x) for x in v]
        return v
    with open(os.path.join(args.out, "crosscheck.json"), "w") as f:
        json.dump(strict({"rows": rows, "runs": details, "penalty_factor": args.penalty_factor,
                          "submodel_mm": args.submodel_mm}),
                  f, indent=1, allow_nan=False)
    lines = ["| material | gait % | CalculiX BC | peak pressure MPa kneesim / ccx | mean pressure "
             "MPa | contact area mm² | axial force N | medial share | von Mises surface MPa | "
             "von Mises subsurface MPa |", "|" + "---|" * 10]
    for r in rows:
        def pair(k, digits=2, pct=True):
            a, b = r["kneesim_" + k], r["ccx_" + k]
            s = ("%." + str(digits) + "f / %." + str(digits) + "f") % (a, b)
            return s + (" (%+.1f %%)" % pct_diff(a, b) if pct else "")
        lines.append("| %s | %.1f | %s | %s | %s | %s | %s | %.3f / %.3f | %s | %s |" % (
            r["model"], r["gait_pct"], r["bc"], pair("peak_pressure_MPa"),
            pair("mean_pressure_MPa"), pair("contact_area_mm2", 1),
            pair("axial_force_N", 0), r["kneesim_medial_share"], r["ccx_medial_share"],
            pair("von_mises_surface_MPa"), pair("von_mises_subsurface_MPa")))
    with open(os.path.join(args.out, "crosscheck.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("config", nargs="?", help="kneesim TOML config (default: built-in)")
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--set", action="append", help="kneesim --set override (repeatable)")
    ap.add_argument("--materials", default="elastic,elastoplastic",
                    help="insert material models (deformable.material), comma-separated")
    ap.add_argument("--pcts", help="gait %% to compare, comma-separated (default: heel strike "
                    "and the two highest axial-load peaks)")
    ap.add_argument("--cycles", type=int, default=2, help="kneesim cycles (instants of the last)")
    ap.add_argument("--export", help="an existing fe_export.json (no kneesim run; --pcts picks "
                    "among its instants)")
    ap.add_argument("--penalty-factor", type=float, default=100.0,
                    help="ccx penalty slope over the median surface element stiffness per area "
                    "(lambda + 2 mu) / L_n (kneesim's penalty)")
    ap.add_argument("--submodel-mm", type=float,
                    help="CalculiX solves a cut-out submodel: the elements within this distance "
                    "(x-z) of kneesim's contact nodes at the instant, full thickness, the cut "
                    "held at kneesim's displacement (default: the whole insert)")
    ap.add_argument("--kneesim", default="build/tools/kneesim")
    ap.add_argument("--ccx", default="ccx")
    ap.add_argument("--threads", type=int, default=1, help="ccx threads")
    ap.add_argument("--tolerance-pct", type=float, default=10.0)
    ap.add_argument("--check", action="store_true",
                    help="exit 3 when a same-load peak, mean pressure or area is beyond tolerance")
    args = ap.parse_args()
    if shutil.which(args.ccx) is None:
        fail("ccx (%s) not found; tools/scripts/setup.sh installs calculix-ccx" % args.ccx)
    if not (args.penalty_factor > 0):
        fail("--penalty-factor %g is out of range (must be > 0)" % args.penalty_factor)
    if args.submodel_mm is not None and not (args.submodel_mm > 0):
        fail("--submodel-mm %g is out of range (must be > 0)" % args.submodel_mm)
    os.makedirs(args.out, exist_ok=True)
    rows, details = [], []
    if args.export:
        if not os.path.isfile(args.export):
            fail("--export %s: no such file" % args.export)
        model = json.load(open(args.export))["material"]["model"]
        crosscheck(args, args.export, "elastic" if model == "elastic" else "elastoplastic",
                   float("nan"), rows, details)
    else:
        if not os.path.isfile(args.kneesim):
            fail("--kneesim %s: no such file (build kneesim first)" % args.kneesim)
        for m in args.materials.split(","):
            if m not in ("elastic", "elastoplastic"):
                fail("--materials: '%s' is not one of elastic, elastoplastic" % m)
            path, seconds, _ = run_kneesim(args, m, os.path.join(args.out, "kneesim_" + m))
            crosscheck(args, path, m, seconds, rows, details)
    write_tables(args, rows, details)
    if args.check:
        bad = [r for r in rows if r["bc"] == "same axial load" and any(
            abs(pct_diff(r["kneesim_" + k], r["ccx_" + k])) > args.tolerance_pct
            for k in ("peak_pressure_MPa", "mean_pressure_MPa", "contact_area_mm2"))]
        if bad:
            print("beyond %.0f %%: %s" % (args.tolerance_pct, ", ".join(
                "%s %.1f %%" % (r["model"], r["gait_pct"]) for r in bad)))
            sys.exit(3)


if __name__ == "__main__":
    main()
