"""Shared by the plot scripts: a CSV file with a header row as columns of floats."""
import csv


def read_columns(path):
    """{column name: [float, ...]} of a CSV file whose cells are all numbers."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}
