#!/usr/bin/env python3
"""A fuzzer over the parameters of the shipped scenes (issue 12).

Every 'set' line of every scene (tests/*.prm, benchmarks/*/*.prm) is given
bad values, one at a time, in a short run; each run must end in one of:
  - a clean run (exit 0),
  - an input error (exit 1) of exactly one line that names a parameter,
    the scene or the option,
  - a stopped run (exit 2) with its diagnosis,
and never in a crash (a signal, another exit code) or a hang (--timeout).

  fuzz_parameters.py --exe build/dealii-mpm             every case
  fuzz_parameters.py --exe ... --jobs 2                 in 2 processes
  fuzz_parameters.py --exe ... --sample 60 --seed 1     a random sample
  fuzz_parameters.py --exe ... --np 2 --sample 20       each case on 2
      MPI ranks (collective failures must stop every rank: a rank left
      waiting is a hang)
  fuzz_parameters.py --exe ... --part 2/4               the second
      quarter of the sweep (every 4th case from the 2nd)
  fuzz_parameters.py --exe ... --report                 also list the
      input errors that name another parameter than the bad one, and the
      stopped runs, for review (they are not failures)
"""
import argparse, concurrent.futures, glob, os, random, re, subprocess, sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(HERE)
# Beyond the malformed: values a scene may hold by mistake or at the edge
# of what makes sense (1e-30, 1e12, 1 in the wrong unit; issue 32).
BAD_VALUES = ["", "-1", "0", "1e308", "-1e308", "nan", "inf", "abc",
              "1, 2, 3, 4", "1e-308", "1e-30", "1e12", "1"]


def parameters(scene):
    """(path, value) of every 'set' line of @p scene."""
    stack, found = [], []
    for line in open(scene):
        line = line.split("#")[0].strip()
        if line.startswith("subsection "):
            stack.append(line[len("subsection "):].strip())
        elif line == "end" and stack:
            stack.pop()
        elif line.startswith("set ") and "=" in line:
            name = line[4:line.index("=")].strip()
            found.append("/".join(stack + [name]))
    return found


def verdict(returncode, stderr, np=1):
    """None if acceptable, else what went wrong."""
    message = stderr.strip()
    if returncode == 0 or returncode == 2:
        return None
    if returncode == 1:
        lines = [l for l in message.splitlines() if l.strip()]
        # mpirun adds its own report of the non-zero exit after ours; a
        # stack trace must still not be there.
        if np > 1:
            if re.search("Stacktrace|An error occurred in line", message):
                return "input error with a stack trace"
            lines = [l for l in lines if l.startswith("dealii-mpm")]
        if len(lines) != 1:
            return "input error of %d lines" % len(lines)
        if not re.search(r"parameters? '|section '|scene|option", lines[0]):
            return "input error naming no parameter: " + lines[0]
        return None
    return "exit code %d (crash): %s" % (returncode, message[-300:])


def report(path, value, returncode, message, scene):
    """Print an input error that names another parameter than @p path,
    and a stopped run, for review."""
    if returncode == 1:
        if "'%s'" % path not in message:
            print("OTHER %s: %s = '%s': %s" % (scene, path, value, message),
                  flush=True)
    elif returncode == 2:
        print("STOPPED %s: %s = '%s': %s" % (scene, path, value,
                                             message[:300]), flush=True)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--sample", type=int, default=0,
                        help="run this many random cases (0: all)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--report", action="store_true")
    parser.add_argument("--jobs", type=int, default=1,
                        help="cases run at once")
    parser.add_argument("--np", type=int, default=1,
                        help="MPI ranks per case")
    parser.add_argument("--part", default="1/1",
                        help="K/N: run every N-th case from the K-th, so "
                        "that the full sweep can be run in N pieces")
    a = parser.parse_args()
    try:
        part, parts = (int(x) for x in a.part.split("/"))
    except ValueError:
        part, parts = 0, 0
    if not 1 <= part <= parts:
        parser.error("--part '%s': needs K/N with 1 <= K <= N" % a.part)
    # The scenes that are malformed on purpose (their own tests) are left
    # out.
    malformed = ("malformed.prm", "empty.prm", "duplicate_parameter.prm",
                 "duplicate_section.prm")
    scenes = sorted(s for s in
                    glob.glob(os.path.join(HERE, "*.prm")) +
                    glob.glob(os.path.join(TOP, "benchmarks", "*", "*.prm"))
                    if os.path.basename(s) not in malformed)
    cases = [(scene, path, value) for scene in scenes
             for path in parameters(scene) for value in BAD_VALUES]
    if a.sample:
        random.seed(a.seed)
        cases = random.sample(cases, min(a.sample, len(cases)))
    cases = cases[part - 1::parts]
    def run(case):
        """Run one case in a directory of its own; (case, exit code or
        None for a timeout, stderr)."""
        scene, path, value = case
        with tempfile.TemporaryDirectory() as out:
            # Short runs: a few steps of each scene, then the bad value.
            command = [a.exe, scene, "-s", "Output/directory=" + out,
                       "-s", "Output/progress interval=1e9",
                       "-s", "Simulation/end time=1e-4",
                       "-s", "%s=%s" % (path, value)]
            if a.np > 1:
                command = ["mpirun", "-np", str(a.np)] + command
            try:
                r = subprocess.run(command, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, text=True,
                                   timeout=a.timeout)
                return case, r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                return case, None, ""

    failures = 0
    counts = {0: 0, 1: 0, 2: 0}
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for (scene, path, value), code, stderr in pool.map(run, cases):
            if code is None:
                problem = "no answer within %g s (a hang?)" % a.timeout
            else:
                problem = verdict(code, stderr, a.np)
                counts[code] = counts.get(code, 0) + 1
            if a.report and not problem:
                report(path, value, code, stderr.strip(),
                       os.path.relpath(scene, TOP))
            if problem:
                failures += 1
                print("FAIL %s: %s = '%s': %s" % (
                    os.path.relpath(scene, TOP), path, value, problem),
                    flush=True)
    print("%d cases: %d clean runs, %d one-line input errors, %d stopped "
          "runs, %d failures" % (len(cases), counts.get(0, 0),
                                 counts.get(1, 0), counts.get(2, 0), failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
