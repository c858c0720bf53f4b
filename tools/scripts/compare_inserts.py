#!/usr/bin/python3
"""Rigid against deformable insert: two `kneesim run` kinematics.csv files of the same rig.

    /usr/bin/python3 tools/scripts/compare_inserts.py RIGID/kinematics.csv DEFORMABLE/kinematics.csv

Prints the AP and IE RMS differences over the frames of the cycle (row by row, the same gait
percentages), and for each run the stance (gait_pct <= 60) RMS of contact axial force minus
applied axial force, the peak pressure over the cycle, the stance mean of the frame peak
pressure and the stance mean contact pressure (docs/deformable.md).
"""
import csv
import math
import sys


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    rigid, deformable = load(sys.argv[1]), load(sys.argv[2])
    n = min(len(rigid), len(deformable))

    def rms(col):
        d = [float(deformable[i][col]) - float(rigid[i][col]) for i in range(n)]
        return math.sqrt(sum(v * v for v in d) / n)

    print("AP RMS %.3f mm, IE RMS %.3f deg over %d frames" % (rms("ap_mm"), rms("ie_deg"), n))
    for name, rows in (("rigid", rigid), ("deformable", deformable)):
        stance = [r for r in rows if float(r["gait_pct"]) <= 60.0]
        balance = [float(r["contact_axial_force_N"]) - float(r["axial_force_N"]) for r in stance]
        print("%s: stance contact - applied axial force RMS %.1f N; peak pressure %.1f MPa, "
              "stance mean of the peak %.1f MPa, stance mean pressure %.1f MPa" % (
                  name, math.sqrt(sum(v * v for v in balance) / len(balance)),
                  max(float(r["peak_pressure_MPa"]) for r in rows),
                  sum(float(r["peak_pressure_MPa"]) for r in stance) / len(stance),
                  sum(float(r["mean_pressure_MPa"]) for r in stance) / len(stance)))


if __name__ == "__main__":
    main()
