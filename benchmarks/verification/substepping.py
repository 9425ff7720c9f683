#!/usr/bin/env python3
"""Substepping (issue 11, seed 003) on problems with exact answers.

convergence  At a fixed macro step Dt of about 10x the explicit limit (a
             divisor of the output interval, so that no macro step is cut
             short), the error of the 1D MMS (G = 1e-4, 64 cells) and of the
             vibrating bar (27 cells) as the substeps S grow from the fewest
             the CFL condition allows, doubling, with the wall time, beside
             the plain explicit run at the same step Dt / S. The macro step
             keeps the substeps' state, so the two must agree; the error
             converges (to the grid's) as S grows.
mismatch     How far the reconstructed grid velocity carries each point
             from its substepped position, max |x^(n+1) - x^n - Dt sum w v_k|
             in cells, as Dt grows at a fixed substep dt (S = Dt / dt), and
             the order fitted in Dt.
reconstruction  The closed form (APIC) against seed 003's least-squares
             system (Jacobi and AMG) on the 2D MMS (quadratic B-spline,
             A = 0.05, macro step 0.002 s, about 6x and 13x the explicit
             limit at 16 and 32 cells): the mismatch, and the cost of the
             macro step's own work (reconstruction, operations, the two
             relocations) per point and macro step beside a substep's.

One CSV row per run on stdout.

  substepping.py --exe build/dealii-mpm
  substepping.py --exe ... --check   fails unless each macro run matches
                                      its plain run to 1e-8 relative and the
                                      error's change with S shrinks by at
                                      least 0.6 as S doubles (first order)
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import cost, overrides, run_scene, sweep_arguments  # noqa: E402

# name: (scene, overrides, explicit step: 95 % of the CFL limit h / c, as
# the points' own speed lowers the limit a little, macro step Dt).
MMS_CELLS = 64
PROBLEMS = {
    # c = 100 m/s, CFL 0.8: dt = 0.8 h / c = 1.25e-4; Dt = 8x that.
    "mms_1d": ("verification/mms_1d.prm",
               ["Grid/cells=%d" % MMS_CELLS, "Output/interval=0.005"],
               0.95 * 0.8 / MMS_CELLS / 100, 0.001),
    # c = 10 m/s, h = 1, CFL 0.5: dt = 0.05; Dt = 10x that.
    "vibrating_bar": ("verification/vibrating_bar.prm",
                      ["Output/interval=1"], 0.95 * 0.05, 0.5),
}


def error_of(result):
    return max(float(r["error"]) for r in result.rows)


def run(exe, problem, settings, extra):
    scene, base = PROBLEMS[problem][:2]
    args = sum([["-s", s] for s in base + settings], []) + extra
    r = run_scene(exe, scene, args)
    wall, _ = cost(r)
    mismatch = float(r.rows[-1].get("macro_mismatch") or "nan")
    return error_of(r), wall, mismatch


def macro(Dt, S):
    return ["Simulation/time step=0", "Simulation/macro time step=%.12g" % Dt,
            "Simulation/substeps=%d" % S]


RECONSTRUCTIONS = {
    "APIC": ["Simulation/macro reconstruction=APIC"],
    "least squares, Jacobi": ["Simulation/macro reconstruction=least squares"],
    "least squares, AMG": ["Simulation/macro reconstruction=least squares",
                           "Simulation/least-squares preconditioner=AMG"],
}


def reconstruction_study(exe, cells, extra):
    print("# reconstruction,cells,mode,mismatch_cells,macro_ns_per_point_and_macro_step,"
          "substep_ns_per_particle_step,macro_steps")
    for n in cells:
        for name, settings in RECONSTRUCTIONS.items():
            s = ["Grid/cells=%d" % n, "Simulation/basis=quadratic B-spline",
                 "Simulation/constants=A=0.05, c=100, rho=1, mu=3846.153846153846, "
                 "lambda=5769.230769230769, px=0, py=0, pz=0",
                 "Simulation/macro time step=0.002"] + settings
            r = run_scene(exe, "verification/mms_2d.prm",
                          sum([["-s", x] for x in s], []) + extra)
            t = r.timing
            points = float(t["particles"]["seconds"])
            steps = float(t["time steps"]["seconds"])
            macro_steps = float(r.rows[-1]["macro_steps"])
            own = sum(float(t[k]["seconds"]) for k in ("macro step", "macro least squares")
                      if k in t)
            # The macro step's two relocations: relocation's calls beyond one per substep.
            per_relocation = float(t["relocate"]["seconds"]) / (steps + 2 * macro_steps)
            own += 2 * macro_steps * per_relocation
            substep = (float(t["steps"]["seconds"]) - own) / (points * steps)
            print("# reconstruction,%d,%s,%.3e,%.0f,%.0f,%d" % (
                n, name, float(r.rows[-1]["macro_mismatch"]),
                1e9 * own / (points * macro_steps), 1e9 * substep, macro_steps),
                flush=True)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--problems", default=",".join(PROBLEMS))
    parser.add_argument("--levels", type=int, default=4,
                        help="substep counts S0, 2 S0, ... at the macro step")
    parser.add_argument("--mismatch-ratios", default="2,4,8,16,32",
                        help="Dt / dt for the mismatch ladder (dt: the limit)")
    parser.add_argument("--reconstruction-cells", default="16,32",
                        help="grids of the reconstruction study ('' skips it)")
    parser.add_argument("--check", action="store_true")
    a = parser.parse_args()
    extra = overrides(a)
    print("study,problem,mode,Dt,S,dt,error,wall_seconds,macro_mismatch_cells")
    failures = []
    if a.reconstruction_cells:
        reconstruction_study(a.exe, [int(n) for n in a.reconstruction_cells.split(",")],
                             extra)
    for problem in a.problems.split(","):
        _, _, limit, Dt = PROBLEMS[problem]
        errors = []
        first = math.ceil(Dt / limit)
        for S in [first * 2 ** k for k in range(a.levels)]:
            dt = Dt / S
            e_macro, w_macro, mm = run(a.exe, problem, macro(Dt, S), extra)
            e_plain, w_plain, _ = run(a.exe, problem,
                                      ["Simulation/time step=%.12g" % dt], extra)
            print("convergence,%s,macro,%.4g,%d,%.4g,%.6e,%.2f,%.3e" % (
                problem, Dt, S, dt, e_macro, w_macro, mm), flush=True)
            print("convergence,%s,plain,,,%.4g,%.6e,%.2f," % (
                problem, dt, e_plain, w_plain), flush=True)
            print("# macro - plain, relative: %.2e" % ((e_macro - e_plain) / e_plain))
            errors.append(e_macro)
            if abs(e_macro - e_plain) > 1e-8 * e_plain:
                failures.append("%s, S = %d: macro error %g, plain %g" % (
                    problem, S, e_macro, e_plain))
        changes = [abs(b - c) for b, c in zip(errors, errors[1:])]
        print("# %s: change of the error as S doubles: %s" % (
            problem, ", ".join("%.3e" % c for c in changes)), flush=True)
        if any(later > 0.6 * earlier for earlier, later in zip(changes, changes[1:])):
            failures.append("%s: the error does not converge in S: %s" % (problem, errors))
        if a.mismatch_ratios:
            points = []
            for ratio in [int(r) for r in a.mismatch_ratios.split(",")]:
                e, w, mm = run(a.exe, problem, macro(ratio * limit, ratio), extra)
                print("mismatch,%s,macro,%.4g,%d,%.4g,%.6e,%.2f,%.3e" % (
                    problem, ratio * limit, ratio, limit, e, w, mm), flush=True)
                points.append((math.log(ratio * limit), math.log(mm)))
            order = (points[-1][1] - points[0][1]) / (points[-1][0] - points[0][0])
            print("# %s: mismatch order in Dt %.2f" % (problem, order), flush=True)
    if a.check and failures:
        for f in failures:
            print("FAILED: " + f)
        sys.exit(1)


if __name__ == "__main__":
    main()
