#!/usr/bin/env python3
"""The slope of Griffiths and Lane (1999), example 1 (benchmarks/slope/
slope.prm): staged analysis.

--check-stages (the ctest, on a coarse grid): stage 0 (gravity loading
under local damping) ends in equilibrium before its duration; at the start
of stage 1 the displacements count from zero again; released without
damping the slope stays at rest (its kinetic energy below 1e-4 of the
strain energy, no point moving 1 mm); a restart within stage 1 and one
from the checkpoint at the end of stage 0 end where the straight run ends,
bit for bit on the same number of ranks (--np).

  python3 benchmarks/slope/slope.py --exe build/dealii-mpm --check-stages
      [--np 2] [--cells 16,6]

--factor-of-safety: stage 1 searches the factor of safety by strength
reduction (trials of --duration seconds under the scene's local damping,
bisected to --tolerance) on each grid of --ladder; prints CSV (cell size,
F, its bracket, trials, wall seconds) and, with --expect LOW,HIGH, fails
unless every F lies in [LOW, HIGH]. Limit equilibrium (Bishop's simplified
method, limit_equilibrium.py): 1.374.

  python3 benchmarks/slope/slope.py --exe build/dealii-mpm --factor-of-safety
      [--ladder "16,6;32,12;64,24"] [--duration 30] [--tolerance 0.01]
      [--set "Simulation/transfer=APIC" ...]
"""
import argparse, csv, glob, os, re, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from vtu_points import read_field  # noqa: E402


def run(a, out, extra, check=True):
    command = ([] if a.np == 1 else ["mpirun", "-np", str(a.np)]) + [
        a.exe, os.path.join(HERE, "slope.prm"),
        "-s", "Output/directory=" + out,
        "-s", "Output/progress interval=1e9",
        "-s", "Grid/cells=" + a.cells] + extra + sum(
            (["-s", x] for x in a.set), [])
    r = subprocess.run(command, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    if check and r.returncode != 0:
        raise RuntimeError(r.stderr)
    return r


def rows(directory):
    return list(csv.DictReader(open(os.path.join(directory, "statistics.csv"))))


def without_wall_time(directory):
    with open(os.path.join(directory, "statistics.csv")) as f:
        return [line.strip().rsplit(",", 1)[0] for line in f]


def largest_displacement(frame):
    return max((sum(c * c for c in u) ** 0.5
                for u in read_field(frame, "displacement")), default=0.0)


def check_stages(a):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        straight = os.path.join(tmp, "straight")
        run(a, straight, [])
        r = rows(straight)
        stage0 = [x for x in r if x["stage"] == "0"]
        stage1 = [x for x in r if x["stage"] == "1"]
        t0 = float(stage0[-1]["time"])
        balance = float(stage0[-1]["out_of_balance"])
        print("stage 0 ended at t = %.4g s, out-of-balance %.3g of the weight"
              % (t0, balance))
        if not (t0 < 60 and balance < 1e-3):
            failures.append("stage 0 did not end in equilibrium")
        strain = float(stage0[-1]["strain_energy"])
        kinetic = max(float(x["kinetic_energy"]) for x in stage1)
        print("released: largest kinetic energy %.3g J, strain energy %.4g J "
              "(ratio %.2e, bound 1e-4)" % (kinetic, strain, kinetic / strain))
        if not kinetic < 1e-4 * strain:
            failures.append("the released slope moves")
        frames = sorted(glob.glob(os.path.join(straight, "particles_*.pvtu")))
        # The frame at the end of stage 0 and the last (stage 1): the
        # displacement counts from the start of stage 1.
        n0 = len(stage0) - 1
        settled = largest_displacement(frames[n0])
        moved = largest_displacement(frames[-1])
        print("largest displacement: %.4g m at the end of gravity loading, "
              "%.3g m since the release (bound 1e-3 m)" % (settled, moved))
        if not (settled > 5e-3 and moved < 1e-3):
            failures.append("the displacements were not reset, or the "
                            "released slope moves")
        # Restarts: within stage 1, and across from the end of stage 0.
        t_end = float(r[-1]["time"])
        within = os.path.join(tmp, "within")
        run(a, within, ["-s", "Simulation/end time=%.17g" % (t0 + 1),
                        "-s", "Checkpoint/interval=0.5"])
        run(a, within, ["--restart", os.path.join(within, "checkpoint")])
        across = os.path.join(tmp, "across")
        run(a, across, ["-s", "Simulation/end time=%.17g" % (t0 + 0.3)])
        run(a, across, ["--restart", os.path.join(across, "stage_0")])
        reference = without_wall_time(straight)
        for name, directory in (("within stage 1", within),
                                ("from the end of stage 0", across)):
            same = without_wall_time(directory) == reference
            print("restart %s: %s" % (name, "bit for bit" if same else
                                       "DIFFERS"))
            if not same:
                failures.append("the restart " + name + " differs")
        del t_end
    return failures


def factor_of_safety(a):
    failures = []
    print("cell_size,factor_of_safety,holds_at,fails_at,trials,wall_seconds")
    for cells in a.ladder.split(";"):
        a.cells = cells
        with tempfile.TemporaryDirectory() as tmp:
            start = time.time()
            r = run(a, tmp, [
                "-s", "Stages/Stage 1/strength reduction=true",
                "-s", "Stages/Stage 1/end=equilibrium",
                "-s", "Stages/Stage 1/changes=",
                "-s", "Stages/Stage 1/duration=%g" % a.duration,
                "-s", "Stages/Stage 1/factor tolerance=%g" % a.tolerance,
                "-s", "Stages/Stage 1/largest factor=2"])
            seconds = time.time() - start
            trials = list(csv.DictReader(open(os.path.join(
                tmp, "factor_of_safety.csv"))))
        m = re.search(r"factor of safety: (\S+) \(holds at (\S+), fails at "
                      r"(\S+),", r.stdout)
        if m is None:
            failures.append("no factor of safety on %s cells: %s"
                            % (cells, r.stdout.splitlines()[-1]))
            continue
        f, low, high = (float(m.group(i)) for i in (1, 2, 3))
        h = 32.0 / int(cells.split(",")[0])
        print("%g,%.4f,%.4f,%.4f,%d,%.1f" % (h, f, low, high, len(trials),
                                              seconds))
        if a.expect and not (a.expect[0] <= f <= a.expect[1]):
            failures.append("F = %.4f on %g m cells outside [%g, %g]"
                            % (f, h, a.expect[0], a.expect[1]))
    return failures


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--exe", required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--cells", default="32, 12")
    p.add_argument("--check-stages", action="store_true")
    p.add_argument("--factor-of-safety", action="store_true")
    p.add_argument("--ladder", default="16,6;32,12;64,24")
    p.add_argument("--duration", type=float, default=30)
    p.add_argument("--tolerance", type=float, default=0.01)
    p.add_argument("--expect", type=lambda t: [float(x) for x in t.split(",")])
    p.add_argument("--set", action="append", default=[],
                   help="'path=value' for the scene, after the script's own "
                   "(repeatable): the numerical choices the factor of "
                   "safety must not depend on")
    a = p.parse_args()
    failures = check_stages(a) if a.check_stages else []
    if a.factor_of_safety:
        failures += factor_of_safety(a)
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
