"""What the CalculiX cases share (not a case: validate.py skips files starting with _)."""

BCS = (("pose", "same pose"), ("load", "same axial load"))


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
