"""Shared by the plot scripts: CSV columns in, PNG files out (written atomically)."""
import csv
import os


def read_columns(path):
    """{column name: [float, ...]} of a CSV file whose cells are all numbers."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def save_figure(fig, path, dpi=120):
    """Writes the figure to path through a temporary file, so that a killed run never leaves
    a half-written PNG under the final name."""
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, path)
