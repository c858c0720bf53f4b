#!/usr/bin/python3
"""tools/validation/cases/_tallies.py's statistics against closed forms:
- false_positive_upper95: with no false positive in n records the Clopper-Pearson bound solves
  (1 - p)^n = 0.05, p = 1 - 0.05^(1/n) (4.87 % for 60, 3.68 % for 80);
- logistic_x80: grouped outcomes whose named fractions are exactly a logistic curve in ln x are
  that curve's maximum-likelihood fit (the score equations hold term by term). With b0 = 0 and
  b1 = ln 3 the curve is 1/4, 1/2, 3/4 at ln x = -1, 0, 1 (1, 2, 3 of 4 named) and names 80 % at
  ln x = ln 4 / ln 3 (to 1e-4: the fit's 1e-6 ridge, which keeps separable data finite, moves
  it by about 1e-5); all named or none named has no crossing (nan);
- onset: linear interpolation of the named fraction to 0.8 between the sizes that bracket it.
Run by ctest (tests/CMakeLists.txt) with the source tree as the first argument."""
import importlib.util
import math
import os
import sys

SOURCE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
spec = importlib.util.spec_from_file_location(
    "kneesim_tallies", os.path.join(SOURCE, "tools", "validation", "cases", "_tallies.py"))
T = importlib.util.module_from_spec(spec)
spec.loader.exec_module(T)


def check(name, got, want, tol):
    ok = (math.isnan(want) and math.isnan(got)) or abs(got - want) <= tol
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {got:.6g} (expected {want:.6g} +- {tol:g})")
    return ok


def main():
    ok = True
    for n in (60, 80):
        ok &= check(f"upper bound, 0 of {n}", T.false_positive_upper95(0, n), 1 - 0.05 ** (1 / n), 1e-9)
    x, named = [], []
    for z, k in ((-1.0, 1), (0.0, 2), (1.0, 3)):
        x += [math.exp(z)] * 4
        named += [1.0] * k + [0.0] * (4 - k)
    ok &= check("x80 of an exact logistic", T.logistic_x80(x, named), math.exp(math.log(4) / math.log(3)), 1e-4)
    ok &= check("x80 with every set named", T.logistic_x80(x, [1.0] * len(x)), float("nan"), 0)
    ok &= check("onset between 0.3 (5/10) and 0.4 (9/10)",
                T.onset([(0.2, 0.1), (0.3, 0.5), (0.4, 0.9)]), 0.3 + 0.3 / 0.4 * 0.1, 1e-12)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
