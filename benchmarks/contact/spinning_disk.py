#!/usr/bin/env python3
"""Friction's torque on a sliding disk (spinning_disk.prm, issue 29).

Prints one CSV row per run: where friction acts (wall: the rigid wall,
on the points; face: the grid's friction face y min, on the nodes), how
the disk is seeded (lattice, or mesh N: the Gauss points of
disk_mesh.py's mesh with N cells along its core), mu, cells across the
radius, the centre's acceleration along the incline and the spin's rate
(least-squares slopes over t in [0.05, 0.4] s, from the points' momentum
and angular momentum about their centre of mass in every output frame),
the exact values (g (sin - mu cos), -2 mu g cos / R) and the relative
errors.

  spinning_disk.py --exe build/dealii-mpm --seeding lattice,32,64 --cells 5,10
  spinning_disk.py --exe ... --contact face --seeding 32 --mu 0.5 --theta 70
  spinning_disk.py --exe ... --seeding 32 --check --max-error 0.02 \\
      --max-spin-error 0.15
"""
import argparse, math, os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from scene_runner import least_squares_slope, overrides, run_scene, sweep_arguments  # noqa: E402

G, RADIUS, CENTER = 9.81, 0.1, (0.15, 0.14)


def centre_motion(points, velocity, mass):
    """Centre of mass's velocity and the spin omega_z about it."""
    m = sum(q[0] for q in mass)
    c = [sum(q[0] * p[k] for q, p in zip(mass, points)) / m for k in (0, 1)]
    v = [sum(q[0] * u[k] for q, u in zip(mass, velocity)) / m for k in (0, 1)]
    spin = inertia = 0
    for q, p, u in zip(mass, points, velocity):
        r = (p[0] - c[0], p[1] - c[1])
        spin += q[0] * (r[0] * (u[1] - v[1]) - r[1] * (u[0] - v[0]))
        inertia += q[0] * (r[0] ** 2 + r[1] ** 2)
    return v, spin / inertia


def face_scene(directory):
    """spinning_disk.prm with the grid's friction face y min at the wall's
    place instead of the wall."""
    text, out, skip = open(os.path.join(HERE, "spinning_disk.prm")).read(), [], 0
    for line in text.splitlines():
        if line.strip() == "subsection Boundary conditions":
            skip = 1
            continue
        if skip:
            skip += line.strip().startswith("subsection")
            skip -= line.strip() == "end"
            continue
        out.append(line)
    path = os.path.join(directory, "spinning_disk_face.prm")
    open(path, "w").write("\n".join(out) + "\n")
    return path


def run(a, contact, seeding, mu, per_radius, directory, extra):
    theta = math.radians(a.theta)
    args = ["-s", "Simulation/gravity=%.12g, %.12g" %
            (G * math.sin(theta), -G * math.cos(theta)),
            "-s", "Grid/cells=%d, %d" % (12 * per_radius, 3 * per_radius)]
    scene = "contact/spinning_disk.prm"
    if contact == "wall":
        args += ["-s", "Boundary conditions/Rigid wall 0/friction coefficient=%g" % mu]
    else:
        scene = face_scene(directory)
        args += ["-s", "Grid/lower corner=0, 0.04",
                 "-s", "Grid/upper corner=1.2, 0.34",
                 "-s", "Grid/boundary y min=friction",
                 "-s", "Grid/friction coefficient=%g" % mu]
    if seeding != "lattice":
        mesh = os.path.join(directory, "disk_%s.msh" % seeding)
        subprocess.run([sys.executable, os.path.join(HERE, "disk_mesh.py"),
                        "--center", "%g,%g" % CENTER, "--radius", str(RADIUS),
                        "--cells", seeding, "-o", mesh], check=True)
        args += ["-s", "Bodies/Body 0/shape=mesh",
                 "-s", "Bodies/Body 0/mesh file=" + mesh,
                 "-s", "Bodies/Body 0/mesh points=Gauss points",
                 "-s", "Bodies/Body 0/particles per cell=1"]
    r = run_scene(a.exe, scene, args + extra, frame="all",
                  fields="velocity,mass", frame_fields=("velocity", "mass"))
    along, spin = [], []
    assert len(r.rows) == len(r.points), "a frame for every statistics row"
    for row, points, values in zip(r.rows, r.points, r.fields):
        t = float(row["time"])
        if t >= 0.05 - 1e-9:
            v, omega = centre_motion(points, values["velocity"], values["mass"])
            along.append((t, v[0]))
            spin.append((t, omega))
    exact = (G * (math.sin(theta) - mu * math.cos(theta)),
             -2 * mu * G * math.cos(theta) / RADIUS)
    return least_squares_slope(along), least_squares_slope(spin), exact


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--contact", default="wall", help="wall, face")
    parser.add_argument("--seeding", default="lattice,32",
                        help="lattice, or the mesh's core cells (even)")
    parser.add_argument("--mu", default="0.1")
    parser.add_argument("--theta", type=float, default=30,
                        help="the incline (deg); the disk must slide: "
                             "mu < tan(theta) / 3")
    parser.add_argument("--cells", default="5",
                        help="cells across the disk's radius")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--max-error", type=float, default=0.02,
                        help="of the centre's acceleration")
    parser.add_argument("--max-spin-error", type=float, default=0.15)
    a = parser.parse_args()
    print("contact,seeding,mu,cells_per_radius,acceleration,exact,error,"
          "spin_rate,exact_spin_rate,spin_error")
    ok = True
    with tempfile.TemporaryDirectory() as directory:
        for contact in a.contact.split(","):
            for seeding in a.seeding.split(","):
                for mu in [float(x) for x in a.mu.split(",")]:
                    if not mu < math.tan(math.radians(a.theta)) / 3:
                        parser.error("mu = %g does not slide at theta = %g"
                                     % (mu, a.theta))
                    for n in [int(x) for x in a.cells.split(",")]:
                        acc, spin, exact = run(a, contact, seeding, mu, n,
                                               directory, overrides(a))
                        e = (acc / exact[0] - 1, spin / exact[1] - 1)
                        print("%s,%s,%g,%d,%.4f,%.4f,%.2e,%.3f,%.3f,%.2e" % (
                            contact, seeding, mu, n, acc, exact[0], e[0],
                            spin, exact[1], e[1]), flush=True)
                        ok = ok and abs(e[0]) <= a.max_error and \
                            abs(e[1]) <= a.max_spin_error
    if a.check and not ok:
        print("FAILED: the centre's acceleration is off by more than %g or "
              "the spin's rate by more than %g" % (a.max_error,
                                                   a.max_spin_error))
        sys.exit(1)


if __name__ == "__main__":
    main()
