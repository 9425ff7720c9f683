#!/usr/bin/env python3
"""The hard cases: scenes that must run to the end without an instability,
with the numerics they ship with and with the program's defaults (USL,
linear basis, FLIP 0.99, CFL 0.5). Prints one CSV row per run: case,
numerics, whether it finished, the kinetic energy at the end over the
largest seen, and the wall time; a stopped run names its diagnosis.

  hard_cases.py --exe build/dealii-mpm [--only taylor_bar,...]
"""
import argparse, time

from scene_runner import run_scene
DEFAULTS = ["-s", "Simulation/basis=linear", "-s", "Simulation/update scheme=USL",
            "-s", "Simulation/transfer=FLIP", "-s", "Simulation/FLIP fraction=0.99",
            "-s", "Simulation/PIC relaxation time=0",
            "-s", "Simulation/CFL number=0.5"]

# name: (scene, overrides of the coarse version)
CASES = {
    "taylor_bar": ("impact/taylor_bar.prm", []),
    "column_collapse_a4": ("granular/column_collapse.prm",
                           ["-s", "Simulation/constants=a=4, L0=0.2, rho=1500, g=9.81, K0=0.5",
                            "-s", "Grid/upper corner=1.85, 0.85", "-s", "Grid/cells=74, 34",
                            "-s", "Bodies/Body 0/upper corner=0.2, 0.8",
                            "-s", "Simulation/end time=2.3"]),
    "bui2008_collapse": ("granular/bui2008.prm", []),
    "strip_footing": ("plasticity/strip_footing.prm",
                      ["-s", "Grid/cells=50, 35", "-s", "Simulation/end time=2"]),
    "thick_cylinder_to_0.99_pL": ("plasticity/thick_cylinder.prm", []),
    "footing_mohr_coulomb_softening": (
        "plasticity/strip_footing.prm",
        ["-s", "Grid/cells=20,14", "-s", "Simulation/end time=2",
         "-s", "Bodies/Body 0/material=Mohr-Coulomb",
         "-s", "Bodies/Body 0/Mohr-Coulomb/Young's modulus=1e7",
         "-s", "Bodies/Body 0/Mohr-Coulomb/cohesion=1e4",
         "-s", "Bodies/Body 0/Mohr-Coulomb/softening=linear",
         "-s", "Bodies/Body 0/Mohr-Coulomb/residual cohesion=5e3",
         "-s", "Bodies/Body 0/Mohr-Coulomb/residual friction angle=20"]),
}


def run(exe, scene, overrides):
    start = time.time()
    r = run_scene(exe, scene, overrides, check=False)
    kinetic = [float(row["kinetic_energy"]) for row in r.rows]
    left = kinetic[-1] / max(max(kinetic), 1e-300)
    return r.returncode == 0, left, time.time() - start, \
        r.stderr.replace(",", ";")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--only", default="")
    a = parser.parse_args()
    names = a.only.split(",") if a.only else list(CASES)
    print("case,numerics,finished,kinetic_end_over_max,wall_seconds,diagnosis")
    for name in names:
        scene, overrides = CASES[name]
        for numerics, extra in (("shipped", []), ("defaults", DEFAULTS)):
            ok, left, wall, why = run(a.exe, scene, overrides + extra)
            print("%s,%s,%d,%.2e,%.1f,%s" % (name, numerics, ok, left, wall,
                                            why[:200]), flush=True)


if __name__ == "__main__":
    main()
