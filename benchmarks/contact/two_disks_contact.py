#!/usr/bin/env python3
"""Two elastic disks colliding (Sulsky et al. 1994, tests/two_disks.prm),
with the single velocity field and with frictionless multi-body contact
(each disk its own field).

Prints one CSV row per run: the energy left at the end over the initial
energy, the smallest distance between points of different disks over all
output frames in units of the point spacing (their point domains overlap
below 1), and each disk's mean velocity along the line of centres at the
end (separated: the first negative, the second positive).

  two_disks_contact.py --exe build/dealii-mpm
  two_disks_contact.py --exe ... --check
      contact: closest >= --min-gap spacings, separated, and more energy
      kept than with the single field
  two_disks_contact.py --exe ... --check --max-over-single 0.01 -s ...
      the same, but the energy kept at most 0.01 (of the initial energy)
      above the single field's: for USF and MUSL, whose single field
      itself gains energy with FLIP (a scheme's error the contact must not
      add to)
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_runner import overrides, run_scene, sweep_arguments  # noqa: E402

SPACING = 0.05 / 2  # h = 1/20, 2 points per cell and direction
LINE = (1 / math.sqrt(2), 1 / math.sqrt(2))  # from disk 0 to disk 1


def closest_approach(points, bodies):
    """Smallest distance between a point of disk 0 and one of disk 1 (only
    points near the line x + y = 1, where they meet, can be closest)."""
    a = [p for p, b in zip(points, bodies) if b[0] == 0 and p[0] + p[1] > 0.8]
    b = [p for p, c in zip(points, bodies) if c[0] == 1 and p[0] + p[1] < 1.2]
    return min((math.dist(p, q) for p in a for q in b), default=float("inf"))


def run(exe, contact, extra):
    arguments = ["-s", "Output/interval=0.05",
                 "-s", "Verification/energy change bound=0"] + extra
    if contact:
        arguments += ["-s", "Contact/bodies=0, 1"]
    r = run_scene(exe, "../tests/two_disks.prm", arguments, frame="all",
                  fields="body, velocity", frame_fields=("body", "velocity"))
    closest = min(closest_approach(points, fields["body"])
                  for points, fields in zip(r.points, r.fields))
    bodies, velocities = r.fields[-1]["body"], r.fields[-1]["velocity"]
    speed = []
    for disk in (0, 1):
        v = [w for w, b in zip(velocities, bodies) if b[0] == disk]
        speed.append(sum(w[0] * LINE[0] + w[1] * LINE[1] for w in v) / len(v))
    energy = float(r.rows[-1]["total_energy"]) / float(r.rows[0]["total_energy"])
    return energy, closest / SPACING, speed


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sweep_arguments(parser)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--min-gap", type=float, default=0.9)
    parser.add_argument("--max-over-single", type=float, default=None)
    a = parser.parse_args()
    print("field,energy_kept,closest_over_spacing,speed_0,speed_1")
    results = {}
    for name, contact in (("single", False), ("contact", True)):
        energy, closest, speed = run(a.exe, contact, overrides(a))
        results[name] = (energy, closest, speed)
        print("%s,%.4f,%.3f,%.4f,%.4f" % (name, energy, closest, *speed),
              flush=True)
    energy, closest, speed = results["contact"]
    single = results["single"][0]
    if a.max_over_single is None:
        energy_ok, energy_rule = energy > single, "less energy than"
    else:
        energy_ok = energy <= single + a.max_over_single
        energy_rule = "more than %g above the energy of" % a.max_over_single
    ok = closest >= a.min_gap and speed[0] < 0 < speed[1] and energy_ok
    if a.check and not ok:
        print("FAILED: with contact the disks came closer than %g spacings, "
              "did not separate, or kept %s one field" % (a.min_gap,
                                                          energy_rule))
        sys.exit(1)


if __name__ == "__main__":
    main()
