#!/usr/bin/env python3
"""A block on a rigid floor body at 30 degrees with mu = 0.7 (sticking_block.prm):
prints the slide of the block between t = 0.5 s and the end (mm), and the
rigid floor's force on the block over m g (sin, cos): both components
should be 1 when it sticks.

  sticking_block.py --exe build/dealii-mpm
  sticking_block.py --exe ... --check --max-slide-mm 0.1 --max-error 0.01
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402

G, THETA, MASS = 9.81, math.pi / 6, 2000 * 0.2 * 0.1


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-slide-mm", type=float, default=0.1)
    parser.add_argument("--max-error", type=float, default=0.01)
    a = parser.parse_args()
    rows = run_scene(a.exe, "contact/sticking_block.prm", overrides(a)).rows
    at = {round(float(r["time"]), 6): r for r in rows}
    slide = 1e3 * (float(rows[-1]["body0_x_min"]) - float(at[0.5]["body0_x_min"]))
    # The floor's force on the material opposes the weight's components.
    along = -float(rows[-1]["rigid1_force_x"]) / (MASS * G * math.sin(THETA))
    normal = float(rows[-1]["rigid1_force_y"]) / (MASS * G * math.cos(THETA))
    print("slide_mm,force_along_over_weight,force_normal_over_weight")
    print("%.4f,%.5f,%.5f" % (slide, along, normal))
    ok = abs(slide) <= a.max_slide_mm and abs(along - 1) <= a.max_error \
        and abs(normal - 1) <= a.max_error
    if a.check and not ok:
        print("FAILED: the block slid more than %g mm, or the floor does not "
              "carry its weight within %g" % (a.max_slide_mm, a.max_error))
        sys.exit(1)


if __name__ == "__main__":
    main()
