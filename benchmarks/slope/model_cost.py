#!/usr/bin/env python3
"""What each plastic model and each of its options costs on a flowing scene
(issue 33, item 6): the runout of benchmarks/slope/runout.prm, whose stage
1 drops the cohesion to 3 kPa and lets the slope fail and run out for 30 s
without damping. Every case keeps that stage and changes only the model or
one option; each is run --repeat times, the cases in turn, so that the
machine's load falls on all of them alike. One CSV row per case: the
medians of the failing stage's stress phase and whole step, in ns per
particle-step, and both as a ratio to the first case (plain Mohr-Coulomb).

'MC softening, nothing softens' has the softening option on with residual
values equal to the peak ones: the same flow as plain Mohr-Coulomb, so its
ratio is the option's own cost. The other cases flow differently (a softer
soil fails further and more of it is plastic), so their ratios also hold
the extra plastic work of their flow.

  python3 benchmarks/slope/model_cost.py --exe build/dealii-mpm
      [--cells 45,6] [--repeat 3]
"""
import argparse, os, re, statistics, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MC = "Bodies/Body 0/Mohr-Coulomb/"


def stage_1(changes):
    """The scene's stage 1 with its changes replaced by @p changes."""
    return ["-s", "Stages/Stage 1/changes=" + "; ".join(
        ["Simulation/local damping = 0"] + changes)]


def material(name, settings):
    """Body 0 made of model @p name with @p settings (the slope's soil)."""
    path = "Bodies/Body 0/" + name + "/"
    args = ["-s", "Bodies/Body 0/material=" + name]
    for key, value in [("Young's modulus", "1e8"),
                       ("Poisson's ratio", "0.3")] + settings:
        args += ["-s", path + key + "=" + value]
    return args


CASES = [
    ("MC", stage_1([MC + "cohesion = 3e3"])),
    ("MC softening nothing softens",
     stage_1([MC + "cohesion = 3e3", MC + "softening = linear",
              MC + "residual plastic strain = 0.05"])),
    ("MC tension cutoff 0",
     ["-s", MC + "tension cutoff=0"] + stage_1([MC + "cohesion = 3e3"])),
    ("MC softening c", stage_1([MC + "cohesion = 3e3", MC + "softening = linear",
                                MC + "residual cohesion = 0",
                                MC + "residual plastic strain = 0.05"])),
    ("MC softening c and phi",
     stage_1([MC + "cohesion = 3e3", MC + "softening = linear",
              MC + "residual cohesion = 0", MC + "residual friction angle = 12",
              MC + "residual plastic strain = 0.05"])),
    ("MC softening c and phi band 1 m",
     stage_1([MC + "cohesion = 3e3", MC + "softening = linear",
              MC + "residual cohesion = 0", MC + "residual friction angle = 12",
              MC + "residual plastic strain = 0.05",
              MC + "shear band thickness = 1"])),
    ("MC softening c and phi nonlocal 1 m (runout.prm)", []),
    ("DP plane strain",
     material("Drucker-Prager", [("cohesion", "1e4"), ("friction angle", "20"),
                                 ("cone", "plane strain")]) +
     stage_1(["Bodies/Body 0/Drucker-Prager/cohesion = 3e3"])),
    ("DP outer cone",
     material("Drucker-Prager", [("cohesion", "1e4"), ("friction angle", "20"),
                                 ("cone", "outer")]) +
     stage_1(["Bodies/Body 0/Drucker-Prager/cohesion = 3e3"])),
    ("von Mises",
     material("von Mises", [("yield stress", "6e4")]) +
     stage_1(["Bodies/Body 0/von Mises/yield stress = 2e4"])),
    ("von Mises hardening",
     material("von Mises", [("yield stress", "6e4")]) +
     stage_1(["Bodies/Body 0/von Mises/yield stress = 2e4",
              "Bodies/Body 0/von Mises/hardening modulus = 1e5"])),
]


def run(a, extra):
    with tempfile.TemporaryDirectory() as out:
        r = subprocess.run([a.exe, os.path.join(HERE, "runout.prm"),
                            "-s", "Output/directory=" + out,
                            "-s", "Output/interval=1e9",
                            "-s", "Output/progress interval=1e9",
                            "-s", "Simulation/out of grid=remove",
                            "-s", "Grid/cells=" + a.cells] + extra,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    points = int(re.search(r"(\d+) material points", r.stdout).group(1))
    stress = float(re.findall(r"^\| stress +\| +\d+ \| +([0-9.e+-]+)s",
                              r.stdout, re.M)[-1])
    steps, step_ns = re.findall(
        r"^Finished (\d+) steps .*?: ([0-9.e+-]+) ns per particle-step",
        r.stdout, re.M)[-1]
    return 1e9 * stress / (points * int(steps)), float(step_ns)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--exe", required=True)
    p.add_argument("--cells", default="45,6")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--skip", default="",
                   help="cases to leave out, comma-separated (e.g. those an "
                   "older build does not know)")
    a = p.parse_args()
    cases = [c for c in CASES if c[0] not in a.skip.split(",")]
    times = {name: [] for name, _ in cases}
    for _ in range(a.repeat):
        for name, extra in cases:
            times[name].append(run(a, extra))
    print("case,stress_ns,step_ns,stress_ratio,step_ratio")
    base = None
    for name, _ in cases:
        stress = statistics.median(t[0] for t in times[name])
        step = statistics.median(t[1] for t in times[name])
        base = base or (stress, step)
        print("%s,%.1f,%.1f,%.2f,%.2f" % (name, stress, step, stress / base[0],
                                          step / base[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
