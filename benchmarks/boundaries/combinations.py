#!/usr/bin/env python3
"""Issue 9's pieces with every basis, update scheme and transfer.

Runs six coarse scenes, one for each piece, over the 5 bases x 3 schemes x 2
transfers, and prints one CSV row per run: whether it finished, and the
scene's measure:

  loaded_column  RMS stress error of the column under a top traction
                 (tests/loaded_column.prm; linear USL 0.032)
  absorbing      energy left at t = 0.06 s over the initial (2D square,
                 32 cells: the pulse is only 1.6 cells wide, a rough measure)
  floating       draft of the floating block at 16 cells (exact 0.125)
  two_disks      energy kept by two disks with a field each
  v_notch        force on wall 0 over m g / 2 (exact 1)
  sliding_disk   acceleration of a disk on a frictionless rigid incline
                 (exact 4.905)

  combinations.py --exe build/dealii-mpm > combinations.csv
"""
import argparse, itertools, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402

BASES = ["linear", "uGIMP", "cpGIMP", "quadratic B-spline", "cubic B-spline"]
SCHEMES = ["USL", "USF", "MUSL"]
TRANSFERS = ["FLIP", "APIC"]


def ratio(rows, column):
    return float(rows[-1][column]) / float(rows[0][column])


SCENES = {
    "loaded_column": ("../tests/loaded_column.prm",
                      ["-s", "Verification/error bound=0"],
                      lambda rows: float(rows[-1]["error"])),
    "absorbing": ("boundaries/absorbing_square.prm",
                  ["-s", "Grid/cells=32", "-s", "Simulation/end time=0.06"],
                  lambda rows: ratio(rows, "total_energy")),
    "floating": ("boundaries/floating_block.prm",
                 ["-s", "Grid/cells=16", "-s", "Simulation/end time=2"],
                 lambda rows: 0.5 - (float(rows[-1]["body0_y_min"]) - 1 / 64)),
    "two_disks": ("../tests/two_disks.prm",
                  ["-s", "Contact/bodies=0, 1",
                   "-s", "Verification/energy change bound=0"],
                  lambda rows: ratio(rows, "total_energy")),
    "v_notch": ("contact/v_notch.prm", [],
                lambda rows: -float(rows[-1]["wall0_force_y"]) /
                (float(rows[-1]["mass"]) * 9.81 / 2)),
    "sliding_disk": ("contact/rolling_disk.prm",
                     ["-s", "Contact/friction coefficient=0",
                      "-s", "Simulation/end time=0.2"],
                     lambda rows: float(rows[-1]["momentum_x"]) /
                     (float(rows[-1]["mass"]) - 48) / float(rows[-1]["time"])),
}


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--scenes", default=",".join(SCENES))
    a = parser.parse_args()
    print("scene,basis,scheme,transfer,finished,measure,message")
    for name in a.scenes.split(","):
        scene, arguments, measure = SCENES[name]
        for basis, scheme, transfer in itertools.product(BASES, SCHEMES, TRANSFERS):
            r = run_scene(a.exe, scene, arguments + [
                "-s", "Simulation/basis=" + basis,
                "-s", "Simulation/update scheme=" + scheme,
                "-s", "Simulation/transfer=" + transfer] + overrides(a),
                check=False)
            value = "%.4g" % measure(r.rows) if r.returncode == 0 else ""
            print('%s,%s,%s,%s,%s,%s,"%s"' % (name, basis, scheme, transfer,
                                              r.returncode == 0, value,
                                              r.stderr[:100]), flush=True)


if __name__ == "__main__":
    main()
