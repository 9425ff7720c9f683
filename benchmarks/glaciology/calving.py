#!/usr/bin/env python3
"""The failing ice cliff demonstration (calving.prm): runs the scene (or reads the
output directory of a run with --output) and draws the points coloured by
damage at a few instants into a PNG. No exact answer: the scene must run
stably to its end.

  calving.py --exe build/dealii-mpm --png doc/calving.png
  calving.py --output /tmp/calving --png doc/calving.png
"""
import argparse, glob, os, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from vtu_points import read_field, read_points  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def draw(directory, png, count, level):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    frames = sorted(glob.glob(os.path.join(directory, "particles_*.pvtu")))
    chosen = [frames[round(i * (len(frames) - 1) / (count - 1))]
              for i in range(count)]
    fig, axes = plt.subplots(count, 1, figsize=(8, 1.9 * count), sharex=True)
    times = {}
    pvd = os.path.join(directory, "particles.pvd")
    for line in open(pvd):
        if "timestep" in line:
            t = float(line.split('timestep="')[1].split('"')[0])
            name = line.split('file="')[1].split('"')[0]
            times[os.path.basename(name)] = t
    for ax, frame in zip(axes, chosen):
        x = read_points(frame)
        d = [v[0] for v in read_field(frame, "damage")]
        sc = ax.scatter([p[0] for p in x], [p[1] for p in x], c=d, s=1.5,
                        cmap="inferno_r", vmin=0, vmax=1)
        ax.axhline(level, color="tab:blue", lw=0.8)
        ax.set_aspect("equal")
        ax.set_xlim(200, 640)
        ax.set_ylim(0, 120)
        ax.set_title("t = %.0f s" % times.get(os.path.basename(frame), 0),
                     fontsize=9)
    fig.colorbar(sc, ax=axes, label="damage", shrink=0.6)
    axes[-1].set_xlabel("x (m); the blue line is the sea level")
    fig.savefig(png, dpi=90)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe")
    parser.add_argument("--output", help="an existing output directory")
    parser.add_argument("--png", required=True)
    parser.add_argument("--frames", type=int, default=4)
    parser.add_argument("--level", type=float, default=30,
                        help="sea level drawn (the scene's fluid level)")
    a = parser.parse_args()
    if a.output:
        draw(a.output, a.png, a.frames, a.level)
        return
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([a.exe, os.path.join(HERE, "calving.prm"),
                        "-s", "Output/directory=" + out], check=True,
                       stdout=subprocess.DEVNULL)
        draw(out, a.png, a.frames, a.level)


if __name__ == "__main__":
    main()
