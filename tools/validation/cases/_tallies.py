"""Shared by the hidden-effect tally cases (a helper, not a case: its name starts with "_"):
the statistical bound that a tally of clean sets can state."""
from math import comb


def false_positive_upper95(false_positives, records):
    """One-sided 95 % upper bound (Clopper-Pearson) of a false-positive rate seen as
    false_positives of records: the rate at which seeing so few has probability 0.05
    (0 of 60 -> 4.9 %, 1 of 60 -> 7.7 %)."""
    if false_positives >= records:
        return 1.0
    lo, hi = false_positives / records, 1.0
    for _ in range(100):  # bisection on P(X <= fp | p) = 0.05, decreasing in p
        p = 0.5 * (lo + hi)
        cdf = sum(comb(records, k) * p ** k * (1 - p) ** (records - k) for k in range(false_positives + 1))
        lo, hi = (p, hi) if cdf > 0.05 else (lo, p)
    return 0.5 * (lo + hi)

