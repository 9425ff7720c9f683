#!/usr/bin/env python3
"""Output that survives a kill, and a directory with an earlier run in it
(issue 12).

1. A run killed with SIGKILL at random moments while it writes a frame
   every step leaves only complete files: every .vtu and .pvtu in the
   directory parses as XML (with all the raw data its header names), and
   every frame the .pvd lists exists.
2. A new run into that directory replaces the old frames ('existing
   output = replace', the default): no frame of the first run stays.
3. With 'existing output = refuse' it stops with a one-line error naming
   the parameter.

  output_robustness.py --exe build/dealii-mpm --scene tests/two_disks.prm
"""
import argparse, glob, os, random, re, struct, subprocess, sys, tempfile, time
import xml.etree.ElementTree as ET


def check_vtu(name):
    """Parse a .vtu or .pvtu; one with raw appended data (not XML there)
    must hold every array its header names, each with its byte count,
    and end with the closing tags right after the last one."""
    raw = open(name, "rb").read()
    marker = raw.find(b"<AppendedData")
    if marker < 0:
        ET.parse(name)
        return
    start = raw.index(b"_", marker) + 1
    head = raw[:start - 1].decode()
    ET.fromstring(head + "</AppendedData></VTKFile>")
    tail = b"\n  </AppendedData>\n</VTKFile>\n"
    if not raw.endswith(tail):
        raise ET.ParseError("the appended data are not closed")
    data = raw[start:len(raw) - len(tail)]
    compressed = "compressor=" in head
    end = 0
    for offset in sorted(int(o) for o in re.findall(r'offset="(\d+)"', head)):
        if offset != end or offset + 8 > len(data):
            raise ET.ParseError("array at %d: data end at %d" % (offset, end))
        n = struct.unpack("<Q", data[offset:offset + 8])[0]
        if compressed:  # n blocks: 3 + n sizes, then the blocks
            sizes = struct.unpack("<%dQ" % n,
                                  data[offset + 24:offset + 24 + 8 * n])
            end = offset + 8 * (3 + n) + sum(sizes)
        else:
            end = offset + 8 + n
    if end != len(data):
        raise ET.ParseError("%d bytes of data, the arrays need %d"
                            % (len(data), end))


def complete(directory):
    """Diagnoses of incomplete or missing files (empty if consistent)."""
    problems = []
    for name in glob.glob(os.path.join(directory, "*.vtu")) + \
            glob.glob(os.path.join(directory, "*.pvtu")):
        try:
            check_vtu(name)
        except (ET.ParseError, struct.error, UnicodeDecodeError) as e:
            problems.append("%s: %s" % (os.path.basename(name), e))
    pvd = os.path.join(directory, "particles.pvd")
    if os.path.exists(pvd):
        for ds in ET.parse(pvd).getroot().iter("DataSet"):
            if not os.path.exists(os.path.join(directory, ds.get("file"))):
                problems.append("listed but missing: " + ds.get("file"))
    return problems


def frame_times(out):
    """The frames in @p out and when each was last written."""
    times = {}
    for f in glob.glob(os.path.join(out, "particles_*.pvtu")):
        try:
            times[f] = os.path.getmtime(f)
        except OSError:  # replaced while we looked
            pass
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--kills", type=int, default=8)
    a = parser.parse_args()
    random.seed(1)
    ok = True
    # Open MPI's 'sharedfp sm' left a named semaphore per killed .vtu write
    # in /dev/shm, and later writes of that file name hung; the program
    # excludes that component, so kills must leave none.
    def semaphores():
        return set(glob.glob("/dev/shm/sem.OMPIO_*"))
    semaphores_before = semaphores()
    with tempfile.TemporaryDirectory() as out:
        base = [a.exe, a.scene, "-s", "Output/directory=" + out,
                "-s", "Output/interval=0", "-s", "Output/progress interval=1e9"]
        frames_seen = 0
        for k in range(a.kills):
            p = subprocess.Popen(base, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
            # Kill once the run writes frames (a frame every step, so the
            # kill lands in or between writes): a fixed delay found a
            # loaded machine, or a Debug build, still setting up.
            started = time.time()
            before = frame_times(out)
            while p.poll() is None and time.time() - started < 120 and \
                    frame_times(out) == before:
                time.sleep(0.01)
            time.sleep(random.uniform(0, 0.5))
            p.kill()
            p.wait()
            problems = complete(out)
            frames = len(glob.glob(os.path.join(out, "particles_*.pvtu")))
            frames_seen = max(frames_seen, frames)
            print("kill %d: %d complete frames, %s" %
                  (k, frames, "consistent" if not problems else problems[:3]))
            ok = ok and not problems
        ok = ok and frames_seen > 0
        stale = semaphores() - semaphores_before
        print("stale MPI-IO semaphores left by the kills: %d" % len(stale))
        ok = ok and not stale

        # A short run into the same directory replaces the old frames.
        subprocess.run(base + ["-s", "Simulation/end time=1e-9"], check=True,
                       stdout=subprocess.DEVNULL)
        left = len(glob.glob(os.path.join(out, "particles_*.pvtu")))
        print("after a new run: %d frames (its own)" % left)
        ok = ok and 1 <= left <= 2 and not complete(out)

        r = subprocess.run(base + ["-s", "Output/existing output=refuse"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
        message = r.stderr.strip()
        print("refuse: exit %d, %s" % (r.returncode, message))
        ok = ok and r.returncode == 1 and "\n" not in message and \
            "parameter 'Output/existing output' = 'refuse'" in message
    print("passed" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
