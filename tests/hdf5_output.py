#!/usr/bin/env python3
"""HDF5 + XDMF particle output (issue 13): a scene written as HDF5 on --np
ranks holds the same points and fields as the same run written as VTU,
frame by frame: positions to the VTU's single precision (1e-6 relative to
the largest coordinate), fields exactly (deal.II's patches hold floats in
both); every frame's .xdmf names its .h5 and its number of points, and
particles.xdmf includes every frame in order. A frame without points
has an .xdmf of no points and no .h5; a rank without points does not
stop the others writing (deal.II 9.4 hangs in HDF5 there).

  hdf5_output.py --exe build/dealii-mpm --scene tests/two_disks.prm [--np 2]
      [--dim 3] [--empty-frames N]   (assert that N frames have no points)
"""
import argparse, os, re, subprocess, sys, tempfile

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "benchmarks"))
from vtu_points import read_field, read_points  # noqa: E402


def run(exe, scene, out, np, fmt, extra):
    cmd = ([exe] if np == 1 else ["mpirun", "-np", str(np), exe]) + [
        scene, "-s", "Output/directory=" + out, "-s", "Output/particle format=" + fmt,
        "-s", "Output/fields=velocity, stress, mass, J"] + extra
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                       text=True, timeout=300)
    if r.returncode != 0:
        raise SystemExit("FAILED: %s: %s" % (" ".join(cmd), r.stderr))


def rows_of_vtu(pvtu, dim):
    """Per point: position, velocity, stress xx, yy, xy (VTU pads a tensor
    to 3 x 3), mass, J."""
    x = read_points(pvtu)
    v = read_field(pvtu, "velocity")
    s = read_field(pvtu, "stress")
    m = read_field(pvtu, "mass")
    J = read_field(pvtu, "J")
    return [tuple(x[i][:dim]) + tuple(v[i][:dim]) +
            (s[i][0], s[i][4], s[i][1]) + (m[i][0], J[i][0]) for i in range(len(x))]


def rows_of_h5(path, dim):
    f = h5py.File(path, "r")
    x, v = f["nodes"][:], f["velocity"][:]
    cols = [f[k][:, 0] for k in ("stress_xx", "stress_yy", "stress_xy", "mass", "J")]
    return [tuple(x[i][:dim]) + tuple(v[i][:dim]) + tuple(c[i] for c in cols)
            for i in range(len(x))]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--empty-frames", type=int, default=0)
    ap.add_argument("-s", action="append", default=[])
    a = ap.parse_args()
    extra = sum([["-s", s] for s in a.s], [])
    dim = a.dim
    empty = 0
    with tempfile.TemporaryDirectory() as work:
        vtu, h5 = os.path.join(work, "vtu"), os.path.join(work, "h5")
        run(a.exe, a.scene, vtu, a.np, "VTU", extra)
        run(a.exe, a.scene, h5, a.np, "HDF5", extra)
        frames = sorted(f for f in os.listdir(vtu) if f.endswith(".pvtu"))
        collection = open(os.path.join(h5, "particles.xdmf")).read()
        included = re.findall(r'href="([^"]+)"', collection)
        ok = len(frames) > 1 and included == [f.replace(".pvtu", ".xdmf") for f in frames]
        print("%d frames; particles.xdmf includes %d" % (len(frames), len(included)))
        worst_x, fields_equal = 0, True
        # Points in order of their position, rounded to the VTU's precision
        # (in double, points of one lattice column differ in the last bits).
        def key(r):
            return tuple(round(c, 5) for c in r[:dim])

        for frame in frames:
            a_rows = sorted(rows_of_vtu(os.path.join(vtu, frame), dim), key=key)
            name = frame.replace(".pvtu", "")
            xdmf = open(os.path.join(h5, name + ".xdmf")).read()
            ok = ok and ('NumberOfElements="%d"' % len(a_rows)) in xdmf
            if not a_rows:
                empty += 1
                ok = ok and not os.path.exists(os.path.join(h5, name + ".h5"))
                continue
            b_rows = sorted(rows_of_h5(os.path.join(h5, name + ".h5"), dim), key=key)
            ok = ok and (name + ".h5:/nodes") in xdmf
            if len(a_rows) != len(b_rows):
                ok = False
                print("%s: %d points in VTU, %d in HDF5" % (name, len(a_rows), len(b_rows)))
                continue
            scale = max(max(abs(c) for c in r[:dim]) for r in a_rows)
            for r, q in zip(a_rows, b_rows):
                worst_x = max([worst_x] + [abs(r[c] - q[c]) / scale for c in range(dim)])
                fields_equal = fields_equal and r[dim:] == q[dim:]
        print("positions: largest difference HDF5 - VTU %.2e of the largest "
              "coordinate (bound 1e-6); fields equal: %s" % (worst_x, fields_equal))
        print("frames without points: %d (expected %d)" % (empty, a.empty_frames))
        ok = ok and worst_x <= 1e-6 and fields_equal and empty == a.empty_frames
    print("passed" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
