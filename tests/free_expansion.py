#!/usr/bin/env python3
"""APIC on a body whose stress stays zero (tests/free_expansion.prm): the
median J of its points at t = 1 against the ballistic (1 + a t)^2 = 4, for
every basis and update scheme, and the output fields 'strain' (log strain
of the points' deformation gradient, exact ln(1 + a t) = ln 2 on xx and yy,
0 on xy) and 'deviatoric strain' (plane strain: 2/3 ln 2). Prints one line
per run; exits 1 if an error exceeds --tolerance.

Measured (relative error of the median J): below 1e-6 with USL, 1e-5 to
5e-5 with MUSL (its second transfer uses the step's first stencils); before
APIC's affine velocity moved with the material, 2.3e-3 (linear) to 9.5e-3
(cubic B-spline).

  free_expansion.py --exe build/dealii-mpm --scene tests/free_expansion.prm
"""
import argparse, math, os, sys
from statistics import median

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "benchmarks"))
from scene_runner import run_scene  # noqa: E402

BASES = ["linear", "uGIMP", "cpGIMP", "quadratic B-spline", "cubic B-spline"]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--tolerance", type=float, default=1e-3)
    a = parser.parse_args()
    ok = True
    for basis in BASES:
        for scheme in ("USL", "MUSL"):
            r = run_scene(a.exe, os.path.abspath(a.scene), [
                "-s", "Simulation/basis=" + basis,
                "-s", "Simulation/update scheme=" + scheme],
                frame=-1, fields="J, strain, deviatoric strain",
                frame_fields=("J", "strain", "deviatoric_strain"))
            J = sorted(j[0] for j in r.fields["J"])
            error = J[len(J) // 2] / 4 - 1
            # The strain: median of each component against the exact one
            # (VTU writes a tensor as 3 x 3: xx, xy, yy at 0, 1, 4).
            strain = r.fields["strain"]
            exact = {0: math.log(2), 4: math.log(2), 1: 0.0}
            strain_error = max(
                abs(median([e[k] for e in strain]) - v) / math.log(2)
                for k, v in exact.items())
            shear = median([e[0] for e in r.fields["deviatoric_strain"]])
            shear_error = shear / (2 / 3 * math.log(2)) - 1
            print("%-20s %-5s median J %.6f, error %.1e; strain error %.1e, "
                  "deviatoric strain error %.1e" %
                  (basis, scheme, J[len(J) // 2], error, strain_error,
                   shear_error), flush=True)
            ok = ok and max(abs(error), strain_error,
                            abs(shear_error)) <= a.tolerance
    if not ok:
        print("FAILED: an error exceeds %g" % a.tolerance)
        sys.exit(1)


if __name__ == "__main__":
    main()
