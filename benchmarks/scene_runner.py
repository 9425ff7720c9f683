"""Run a dealii-mpm scene with overrides into a temporary directory and
return what the benchmark scripts read: the rows of statistics.csv, the
phases of timing.csv, and optionally the points of one output frame.

    from scene_runner import run_scene
    result = run_scene(exe, "plasticity/thick_cylinder.prm", ["-s", "..."],
                       frame=0)
    result.rows[-1]["kinetic_energy"], result.timing["steps"], result.points

frame=-1 reads the last frame; frame_fields=("stress",) also reads those
point fields of it (result.fields["stress"], in the order of the points).
frame="all" reads every frame: result.points and result.fields are lists.
"""
import csv, glob, os, subprocess, tempfile
from collections import namedtuple

from vtu_points import read_field, read_points

HERE = os.path.dirname(os.path.abspath(__file__))
Result = namedtuple("Result", "rows timing points fields returncode stderr")


def cost(result):
    """Wall seconds of the run and ns per particle-step of its steps."""
    return float(result.rows[-1]["wall_seconds"]), \
        float(result.timing["steps"]["ns_per_particle_step"])


def run_scene(exe, scene, overrides=(), frame=None, fields="J", check=True,
              frame_fields=()):
    """@p scene is relative to benchmarks/; a failed run raises unless
    @p check is False (then returncode and stderr say why)."""
    with tempfile.TemporaryDirectory() as out:
        r = subprocess.run([exe, os.path.join(HERE, scene),
                            "-s", "Output/directory=" + out,
                            "-s", "Output/fields=" + fields,
                            "-s", "Output/progress interval=1e9"] + list(overrides),
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
        if check and r.returncode != 0:
            raise RuntimeError(r.stderr)
        rows = list(csv.DictReader(open(os.path.join(out, "statistics.csv"))))
        timing_file = os.path.join(out, "timing.csv")
        timing = {t["phase"]: t for t in csv.DictReader(open(timing_file))} \
            if os.path.exists(timing_file) else {}
        points, values = None, {}
        frames = sorted(glob.glob(os.path.join(out, "particles_*.pvtu")))
        if frame == "all":
            points = [read_points(name) for name in frames]
            values = [{f: read_field(name, f) for f in frame_fields}
                      for name in frames]
        elif frame is not None:
            name = frames[-1] if frame == -1 else \
                os.path.join(out, "particles_%05d.pvtu" % frame)
            points = read_points(name)
            values = {f: read_field(name, f) for f in frame_fields}
    return Result(rows, timing, points, values, r.returncode, r.stderr.strip())


def least_squares_slope(samples):
    """Slope of the least-squares line through (t, v) samples."""
    mean_t = sum(t for t, _ in samples) / len(samples)
    mean_v = sum(v for _, v in samples) / len(samples)
    return sum((t - mean_t) * (v - mean_v) for t, v in samples) / \
        sum((t - mean_t) ** 2 for t, _ in samples)


def override(extra, path, default):
    """The value the overrides @p extra ('-s', 'path=value', ...) give the
    entry @p path (the last one wins), else @p default."""
    value = default
    for a, b in zip(extra, extra[1:]):
        if a == "-s" and b.startswith(path + "="):
            value = b.split("=", 1)[1]
    return value


def points_per_cell(extra):
    """Points per cell and direction: the scene's 2 unless overridden."""
    return int(override(extra, "Bodies/Body 0/particles per cell", 2))


def sweep_arguments(parser):
    """The arguments every driver takes: the executable, and overrides."""
    parser.add_argument("--exe", required=True, help="the dealii-mpm binary")
    parser.add_argument("-s", action="append", default=[],
                        help="a parameter override passed on to dealii-mpm")


def overrides(args):
    return sum([["-s", s] for s in args.s], [])
