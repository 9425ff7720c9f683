#!/usr/bin/env python3
"""A disk at rest in a V-shaped notch of two rigid walls (v_notch.prm):
each wall's mean force over the last output interval against
(-+ m g / 2, -m g / 2), and their sum against (0, -m g). Prints the four
components over m g / 2 and the largest errors. With friction the split
between the walls is statically indeterminate (--sum-only checks the sum).

  v_notch.py --exe build/dealii-mpm
  v_notch.py --exe ... -s "Boundary conditions/Rigid wall 0/friction coefficient=0.3" \\
                       --sum-only --check --max-error 0.01
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", type=float, default=0.01)
    parser.add_argument("--sum-only", action="store_true")
    a = parser.parse_args()
    last = run_scene(a.exe, "contact/v_notch.prm", overrides(a)).rows[-1]
    half_weight = float(last["mass"]) * 9.81 / 2
    measured = [float(last[c]) / half_weight for c in
                ("wall0_force_x", "wall0_force_y", "wall1_force_x", "wall1_force_y")]
    exact = [-1, -1, 1, -1]
    error = max(abs(m - e) for m, e in zip(measured, exact))
    sum_error = max(abs(measured[0] + measured[2]),
                    abs(measured[1] + measured[3] + 2)) / 2
    print("wall0_x,wall0_y,wall1_x,wall1_y,max_error,sum_error")
    print("%.6f,%.6f,%.6f,%.6f,%.2e,%.2e" % (*measured, error, sum_error))
    if a.sum_only:
        error = sum_error
    if a.check and not error <= a.max_error:
        print("FAILED: a wall force is off by more than %g of m g / 2" % a.max_error)
        sys.exit(1)


if __name__ == "__main__":
    main()
