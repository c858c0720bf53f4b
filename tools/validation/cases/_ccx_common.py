"""What the CalculiX cases share (not a case: validate.py skips files starting with _)."""

BCS = (("pose", "same pose"), ("load", "same axial load"))
# (figure code, crosscheck.json name, digits in the tables)
QUANTITIES = (("peak", "peak_pressure_MPa", 2), ("mean", "mean_pressure_MPa", 2),
              ("area", "contact_area_mm2", 1), ("force", "axial_force_N", 0),
              ("share", "medial_share", 3), ("vms", "von_mises_surface_MPa", 2),
              ("vmb", "von_mises_subsurface_MPa", 2))


def key(model, pct, bc, q, code):
    """The figure name of quantity q at an instant: code k (kneesim), c (ccx) or d (%)."""
    return f"{'el' if model == 'elastic' else 'pl'}{pct}_{bc}_{q}_{code}"


def record_row(v, r):
    """One crosscheck.json row's figures (kneesim, ccx, and the difference in % of peak and mean
    pressure and area); returns (model, gait %, bc)."""
    model, pct = r["model"], int(round(r["gait_pct"]))
    bc = "pose" if r["bc"] == "same pose" else "load"
    for q, name, _ in QUANTITIES:
        for code, side in (("k", "kneesim_"), ("c", "ccx_")):
            v.figure(key(model, pct, bc, q, code), r[side + name])
        if q in ("peak", "mean", "area"):
            a, b = r["kneesim_" + name], r["ccx_" + name]
            v.figure(key(model, pct, bc, q, "d"), 100.0 * (a - b) / b, "%")
    return model, pct, bc


def row_cells(model, pct, bc):
    """The table cells "kneesim / ccx (d %)" of every quantity at an instant."""
    cells = []
    for q, _, digits in QUANTITIES:
        cell = "{%s:.%df} / {%s:.%df}" % (key(model, pct, bc, q, "k"), digits,
                                          key(model, pct, bc, q, "c"), digits)
        if q in ("peak", "mean", "area"):
            cell += " ({%s:+.1f} %%)" % key(model, pct, bc, q, "d")
        cells.append(cell)
    return " | ".join(cells)


def soft_table(pcts):
    """The table of CalculiX run with kneesim's own penalty (the figures soft<pct>_<bc>_<q>_k/c/d):
    peak and mean pressure, contact area and axial force at the instants `pcts`."""
    head = ("| gait % | CalculiX femur, penalty as kneesim's | peak pressure MPa, kneesim / ccx | "
            "mean pressure MPa | contact area mm² | axial contact force N |\n" + "|---" * 6 + "|\n")
    rows = []
    for pct in pcts:
        for bc, label in BCS:
            cells = []
            for q, digits in (("peak", 2), ("mean", 2), ("area", 1), ("force", 0)):
                k = "soft%d_%s_%s_" % (pct, bc, q)
                cell = "{%sk:.%df} / {%sc:.%df}" % (k, digits, k, digits)
                if q != "force" or bc == "pose":
                    cell += " ({%sd:+.1f} %%)" % k
                cells.append(cell)
            rows.append("| %d | %s | %s |" % (pct, label, " | ".join(cells)))
    return "\n" + head + "\n".join(rows) + "\n"
