#!/usr/bin/env python3
"""Granular column collapse: normalised runout against the experimental laws.

Runs benchmarks/granular/column_collapse.prm for each aspect ratio
a = H0 / L0 and prints one CSV row per run: a, cells across the column's
width, the normalised runout (L_inf - L0) / L0, the laws' values, whether
the front --front names (the 99 % front by default) lies inside their
envelope, the kinetic energy left at the end (over the
initial potential energy: the deposit must be at rest), and the cost.

The front L_inf is the largest x of a material point plus half a point
spacing (the body's edge). Two fronts that points thrown ahead of the
deposit cannot move come from the program's statistics ('Output/body
extents'): runout_99, the position 99 % of the points stay behind (plus
half a spacing), and runout_thick, the furthest edge where the deposit is
at least 10 % of H0 thick ('Output/front thickness'; see README.md).
The laws, for quasi-2D columns on a horizontal plane (as the issue quotes
them; see README.md for their provenance):
  Lube et al. 2005:        1.2 a for a < 1.8,   1.9 a^(2/3) above;
  Lajeunesse et al. 2005:  1.2 a for a < 3,     1.9 a^(2/3) above (glass).
The envelope at a is [min, max] of the two laws, widened by the scatter of
the experiments (--scatter, 20 % by default).

  column_collapse.py --exe build/dealii-mpm                    the sweep
  column_collapse.py --exe ... --aspect 1 --cells 8 --check    a ctest
  column_collapse.py --exe ... -s "Bodies/Body 0/density=1925" \
      -s "Bodies/Body 0/Mohr-Coulomb/friction angle=22.2" ...   another
      material: the initial stress follows its density and 1 - sin phi
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import (cost, override, overrides,  # noqa: E402
                          points_per_cell, run_scene, sweep_arguments)
L0 = 0.2


def laws(a):
    lube = 1.2 * a if a < 1.8 else 1.9 * a ** (2 / 3)
    lajeunesse = 1.2 * a if a < 3 else 1.9 * a ** (2 / 3)
    return lube, lajeunesse


def initial_stress_constants(extra):
    """The density and K0 = 1 - sin phi of the initial stress: the scene's
    (1500, 0.5) unless the overrides give the body another density or
    friction angle."""
    rho = float(override(extra, "Bodies/Body 0/density", 1500))
    phi = override(extra, "Bodies/Body 0/Mohr-Coulomb/friction angle", None)
    K0 = 0.5 if phi is None else 1 - math.sin(math.radians(float(phi)))
    return rho, K0


def run(exe, a, n, end_time, extra):
    h = L0 / n
    rho, K0 = initial_stress_constants(extra)
    # Room for the runout (a safe 1.5x the larger law) and the column.
    width = L0 * (1 + 1.5 * max(laws(a))) + 2 * h
    height = a * L0 + 2 * h
    nx, ny = round(width / h), round(height / h)
    r = run_scene(exe, "granular/column_collapse.prm", [
        "-s", "Simulation/constants=a=%g, L0=%g, rho=%.17g, g=9.81, "
              "K0=%.17g" % (a, L0, rho, K0),
        "-s", "Simulation/end time=%g" % end_time,
        "-s", "Grid/upper corner=%.17g, %.17g" % (nx * h, ny * h),
        "-s", "Grid/cells=%d, %d" % (nx, ny),
        "-s", "Bodies/Body 0/upper corner=%.17g, %.17g" % (L0, a * L0),
        "-s", "Output/interval=%g" % (end_time / 20),
        "-s", "Output/front thickness=%.17g" % (0.1 * a * L0)] + extra)
    last = r.rows[-1]
    spacing = h / points_per_cell(extra)
    front = float(last["body0_x_max"]) + spacing / 2
    front99 = float(last["body0_x_front_max"]) + spacing / 2
    thick = float(last["body0_x_deposit_max"])
    potential = float(r.rows[0]["gravitational_energy"]) - \
        float(last["gravitational_energy"])
    rest = float(last["kinetic_energy"]) / max(potential, 1e-300)
    return ((front - L0) / L0, (front99 - L0) / L0, (thick - L0) / L0,
            rest) + cost(r)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--aspect", default="0.5,1,2,4",
                        help="aspect ratios a = H0/L0, comma-separated")
    parser.add_argument("--cells", default="8,16",
                        help="cells across the column width, comma-separated")
    parser.add_argument("--scatter", type=float, default=0.2)
    parser.add_argument("--check", action="store_true",
                        help="fail unless every runout (the front --front "
                             "names) lies in the envelope and every deposit "
                             "is at rest")
    parser.add_argument("--front", default="99",
                        choices=["furthest", "99", "thick"],
                        help="the runout 'inside' and --check judge: the "
                             "furthest point, the 99 %% front (default: "
                             "stray points cannot move it) or the deposit "
                             "10 %% of H0 thick")
    a = parser.parse_args()
    extra = overrides(a)

    print("aspect,cells_per_width,runout,runout_99,runout_thick,lube,lajeunesse,"
          "envelope_low,envelope_high,inside,kinetic_over_released,"
          "wall_seconds,ns_per_particle_step")
    ok = True
    for aspect in [float(x) for x in a.aspect.split(",")]:
        # Collapse and spreading last a few sqrt(H0 / g); 8 of them, at
        # least 0.8 s, leave the deposit at rest.
        end_time = max(0.8, 8 * (aspect * L0 / 9.81) ** 0.5)
        for n in [int(x) for x in a.cells.split(",")]:
            runout, runout99, thick, rest, wall, ns = run(
                a.exe, aspect, n, end_time, extra)
            lube, lajeunesse = laws(aspect)
            low = (1 - a.scatter) * min(lube, lajeunesse)
            high = (1 + a.scatter) * max(lube, lajeunesse)
            judged = {"furthest": runout, "99": runout99,
                      "thick": thick}[a.front]
            inside = low <= judged <= high
            at_rest = rest < 1e-3
            print("%g,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%.2e,%.2f,%.1f" %
                  (aspect, n, runout, runout99, thick, lube, lajeunesse, low,
                   high,
                   inside, rest, wall, ns), flush=True)
            ok = ok and inside and at_rest
    if a.check and not ok:
        print("FAILED: a runout lies outside the envelope of the laws or a "
              "deposit is still moving")
        sys.exit(1)


if __name__ == "__main__":
    main()
