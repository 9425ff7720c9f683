#!/usr/bin/env python3
"""Damage in a bar (issue 10): damage_bar.prm, a bar whose halves are
thrown apart, so that a tensile wave 1.5 times the strength starts in its
middle. The dissipated energy

  D = initial kinetic energy - kinetic energy - strain energy  (at the end)

is measured under grid refinement with local damage and with a nonlocal
length l = 0.05. Local: the softening zone is one cell wide, D falls with
h (mesh dependence). Nonlocal: the zone keeps the width l sets, D
converges. 'zone' is the length over which d > 0.5.

  damage_bar.py --exe build/dealii-mpm
  damage_bar.py --exe ... --cells 32,64,128 --check

--check asserts that the local D falls by at least 20 % per halving of h
and that the nonlocal D of the two finest grids differs by under 10 %.
"""
import argparse, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402


def bar(exe, cells, length, extra):
    result = run_scene(exe, "damage/damage_bar.prm", [
        "-s", "Grid/cells=%d" % cells,
        "-s", "Bodies/Body 0/Hencky elastic/Damage/nonlocal length=%g" % length]
        + extra, frame=-1, fields="damage, volume",
        frame_fields=("damage", "volume"))
    first, last = result.rows[0], result.rows[-1]
    dissipated = float(first["total_energy"]) - float(last["kinetic_energy"]) \
        - float(last["strain_energy"])
    zone = sum(v[0] for d, v in zip(result.fields["damage"],
                                    result.fields["volume"]) if d[0] > 0.5)
    return dissipated, zone, cost(result)[0]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--cells", default="32,64,128,256")
    parser.add_argument("--length", type=float, default=0.05)
    parser.add_argument("--check", action="store_true")
    a = parser.parse_args()
    print("damage,cells,dissipated,zone,wall_seconds")
    ladders = {}
    for name, length in (("local", 0.0), ("nonlocal", a.length)):
        for cells in [int(c) for c in a.cells.split(",")]:
            d, zone, wall = bar(a.exe, cells, length, overrides(a))
            ladders.setdefault(name, []).append(d)
            print("%s,%d,%.4e,%.4f,%.2f" % (name, cells, d, zone, wall), flush=True)
    local, nonlocal_ = ladders["local"], ladders["nonlocal"]
    falls = all(fine < 0.8 * coarse for coarse, fine in zip(local, local[1:]))
    spread = abs(nonlocal_[-1] / nonlocal_[-2] - 1)
    print("# local D falls by >= 20 %% per halving: %s; nonlocal spread of "
          "the two finest: %.3f" % (falls, spread))
    if a.check and not (falls and spread < 0.1):
        print("FAILED")
        sys.exit(1)


if __name__ == "__main__":
    main()
