#!/usr/bin/env python3
"""docs/figures.md's timing table, measured and written (make docs-timing).

usage: figures_timing.py JUMPCYL [--runs N] [--check]

Each job runs N times (3) in a scratch directory; its CPU time (user and
system, of the tool and its gnuplot or ffmpeg: the children's rusage) is the
least of the runs. The table between the markers `<!-- timing: begin -->`
and `<!-- timing: end -->` of docs/figures.md is replaced, with the machine's
load average at the time; --check prints it without writing.
"""
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "figures.md")
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cpu_of(argv, cwd):
    """CPU seconds (user + system) of one run of argv and its children."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(argv, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def least(argv, runs, cwd, clean=None):
    best = float("inf")
    for _ in range(runs):
        if clean:
            shutil.rmtree(os.path.join(cwd, clean), ignore_errors=True)
        best = min(best, cpu_of(argv, cwd))
    return best


def frames_in(cwd, name):
    return len([f for f in os.listdir(os.path.join(cwd, name)) if f.endswith(".png")])


def measure(tool, runs, cwd):
    rows = []
    kinds = ["paper-criterion", "forces", "gap", "energy"]
    times = [least([tool, "plot", "--incline", "45", "--what", k, "--output", k + ".png"], runs, cwd) for k in kinds]
    rows.append(("one figure (`paper-criterion`, `forces`, `gap`, `energy`), PNG",
                 "%.2f–%.2f s" % (min(times), max(times))))
    for kind in ("trajectory", "overview"):
        t = least([tool, "plot", "--incline", "45", "--what", kind, "--output", kind + ".png"], runs, cwd)
        rows.append(("`%s`" % kind, "%.2f s" % t))
    for size in ("960x540", "640x360"):
        t = least([tool, "animate", "--incline", "45", "--size", size, "--output", "frames/"], runs, cwd, "frames")
        n = frames_in(cwd, "frames")
        w, h = size.split("x")
        rows.append(("animation frames, %s × %s (PNG, no ffmpeg)" % (w, h),
                     "%.1f ms per frame (the 45° film: %d frames, %.1f s)" % (1000 * t / n, n, t)))
    t = least([tool, "animate", "--incline", "45", "--size", "640x360", "--fps", "25", "--slowmo", "6",
               "--output", "jump-45.gif"], runs, cwd)
    rows.append(("45° film, 640 × 360, 25 fps, 6× slow motion, GIF (`make run`)", "%.1f s" % t))
    t = least([tool, "animate", "--incline", "45", "--output", "jump45.mp4"], runs, cwd)
    rows.append(("45° film, 960 × 540, 30 fps, 8× slow motion, MP4", "%.1f s" % t))
    build = os.path.dirname(os.path.abspath(tool))
    t = least(["make", "-s", "-C", REPO, "-o", "build", "-o", "configure", "run",
               "BUILD=" + os.path.relpath(build, REPO)], runs, cwd)
    rows.append(("`make run` after a build (Table 1, three overviews, four trajectories, two GIFs)", "%.1f s" % t))
    return rows


def table(rows, runs):
    load = os.getloadavg()[0]
    lines = ["Measured on the development machine (%d cores) by `make docs-timing`" % os.cpu_count(),
             "(tests/docs/figures_timing.py), paper's cylinder on 45°, at a load average",
             "of %.1f: CPU time, user and system, of the tool with its gnuplot or ffmpeg," % load,
             "the least of %d runs. Sharing the machine inflates it less than the wall" % runs,
             "time, which on an idle machine is close to it (the figures and frames are",
             "drawn on one core).",
             "",
             "| job | CPU time |",
             "|---|---|"]
    lines += ["| %s | %s |" % r for r in rows]
    return "\n".join(lines) + "\n"


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    tool = os.path.abspath(args[0])
    runs = int(args[args.index("--runs") + 1]) if "--runs" in args else 3
    with tempfile.TemporaryDirectory(prefix="jc-timing-") as cwd:
        text = table(measure(tool, runs, cwd), runs)
    if "--check" in args:
        print(text, end="")
        return
    with open(DOC, encoding="utf-8") as f:
        doc = f.read()
    pattern = re.compile(r"(<!-- timing: begin -->\n).*?(<!-- timing: end -->)", re.S)
    if not pattern.search(doc):
        sys.exit("figures_timing.py: no timing markers in " + DOC)
    doc = pattern.sub(lambda m: m.group(1) + text + m.group(2), doc)
    with open(DOC, "w", encoding="utf-8") as f:
        f.write(doc)
    print(text, end="")


if __name__ == "__main__":
    main()
