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
  fuzz_parameters.py --exe ... --match 'taylor_bar.*density = 1$'
                                                        one case again
  fuzz_parameters.py --exe ... --report                 also list the
      input errors that name another parameter than the bad one, and the
      stopped runs, for review (they are not failures)
"""
import argparse, concurrent.futures, glob, os, random, re, signal, subprocess
import sys
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


# Seconds a run that outlived --timeout is watched for one more step.
GRACE = 5


def last_step(log):
    """(step, line) of the last progress line in @p log, or None."""
    found = None
    for line in open(log, errors="replace"):
        m = re.match(r"\s*step\s+(\d+)\s", line)
        if m:
            found = (int(m.group(1)), line.strip())
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
    parser.add_argument("--match", default="",
                        help="only the cases whose 'scene: path = value' "
                        "matches this regular expression (to rerun one)")
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
    if a.match:
        cases = [c for c in cases if re.search(
            a.match, "%s: %s = %s" % (os.path.relpath(c[0], TOP), c[1], c[2]))]
    if a.sample:
        random.seed(a.seed)
        cases = random.sample(cases, min(a.sample, len(cases)))
    cases = cases[part - 1::parts]
    def run(case):
        """Run one case in a directory of its own; (case, exit code, or
        None for a hang, or the last progress line of a run that was still
        advancing when the time was up; stderr)."""
        scene, path, value = case
        with tempfile.TemporaryDirectory() as out:
            # Short runs: a few steps of each scene, then the bad value.
            # Progress lines every second tell a slow run from a hang.
            command = [a.exe, scene, "-s", "Output/directory=" + out,
                       "-s", "Output/progress interval=1",
                       "-s", "Simulation/end time=1e-4",
                       "-s", "%s=%s" % (path, value)]
            if a.np > 1:
                command = ["mpirun", "-np", str(a.np)] + command
            log = os.path.join(out, "stdout.log")
            with open(log, "w") as stdout:
                process = subprocess.Popen(command, stdout=stdout,
                                           stderr=subprocess.PIPE,
                                           text=True,
                                           start_new_session=True)
                try:
                    _, stderr = process.communicate(timeout=a.timeout)
                    return case, process.returncode, stderr
                except subprocess.TimeoutExpired:
                    before = last_step(log)
                    try:
                        _, stderr = process.communicate(timeout=GRACE)
                        return case, process.returncode, stderr
                    except subprocess.TimeoutExpired:
                        pass
                    after = last_step(log)
                    os.killpg(process.pid, signal.SIGKILL)
                    process.communicate()
                    if after and (not before or after[0] > before[0]):
                        return case, "slow", after[1]
                    return case, None, ""

    failures = 0
    counts = {0: 0, 1: 0, 2: 0}
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for (scene, path, value), code, stderr in pool.map(run, cases):
            if code is None:
                problem = "no answer within %g s and no step in the %g s " \
                    "after (a hang)" % (a.timeout, GRACE)
            elif code == "slow":
                # Not a failure: the run tells its user how long it will
                # take, and the refusal bound is 1e9 steps.
                counts["slow"] = counts.get("slow", 0) + 1
                print("SLOW %s: %s = '%s': still advancing after %g s: %s"
                      % (os.path.relpath(scene, TOP), path, value,
                         a.timeout, stderr), flush=True)
                continue
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
          "runs, %d slow runs still advancing, %d failures"
          % (len(cases), counts.get(0, 0), counts.get(1, 0), counts.get(2, 0),
             counts.get("slow", 0), failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
