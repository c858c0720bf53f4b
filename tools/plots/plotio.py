"""Shared by the plot scripts: CSV columns in, PNG files out (written atomically)."""
import csv
import errno
import math
import os
import sys

from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter


def read_columns(path):
    """{column name: [float, ...]} of a CSV file whose cells are all numbers."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


DISK_FULL = 3  # engine/io/plot.h kPlotDiskFull


def save_figure(fig, path, dpi=120):
    """Writes the figure to path through a temporary file, so that a killed run never leaves
    a half-written PNG under the final name."""
    tmp = path + ".tmp.png"
    try:
        fig.savefig(tmp, dpi=dpi)
        os.replace(tmp, path)
    except OSError as e:
        # a full disk or another write failure: no half-written PNG, one line instead of a
        # traceback through matplotlib and PIL; a full disk exits with DISK_FULL, which kneesim
        # reports (engine/io/plot.h kPlotDiskFull)
        try:
            os.remove(tmp)
        except OSError:
            pass
        if e.errno in (errno.ENOSPC, errno.EDQUOT):
            sys.exit(DISK_FULL)
        print(f"error: cannot write {path}: {e.strerror}", file=sys.stderr)
        sys.exit(1)


def readable_log_axis(axis):
    """Plain-number labels on a log axis after the data are drawn: matplotlib labels only the
    powers of ten, so an axis spanning less than a decade or two showed one label or none.
    Ticks at 1-2-5 per decade (every 1-9 when the axis spans under a decade), labelled as
    plain numbers; whole decades only beyond six decades."""
    lo, hi = axis.get_view_interval()
    decades = math.log10(hi / lo) if lo > 0 and hi > lo else 1.0
    if decades > 6:
        subs = (1.0,)
    elif decades > 1:
        subs = (1.0, 2.0, 5.0)
    else:
        subs = tuple(float(k) for k in range(1, 10))
    axis.set_major_locator(LogLocator(base=10, subs=subs, numticks=30))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())
