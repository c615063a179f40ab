#!/usr/bin/env python3
"""Every figure of layout_cases.py drawn as SVG by the built tool and passed
through the layout check (layout_check.py); prints each failure and
"N passed, N failed", exits 1 on a failure.

usage: test_layout.py JUMPCYL [--only NAME]... [--keep DIR] [--jobs N]
"""
import concurrent.futures
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import layout_cases  # noqa: E402
import layout_check  # noqa: E402


def run_case(jumpcyl, outdir, case):
    name, args, allow = case
    svg = os.path.join(outdir, name + ".svg")
    p = subprocess.run([jumpcyl] + args + ["--output", svg], capture_output=True, text=True)
    if p.returncode != 0:
        return name, ["%s: jumpcyl %s failed (exit %d): %s" % (name, " ".join(args), p.returncode, p.stderr.strip())]
    return name, layout_check.check(svg, name, allow)


def main(argv):
    if not argv:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    jumpcyl, only, keep, jobs, cases = argv[0], [], None, 2, list(layout_cases.CASES)
    i = 1
    while i < len(argv):
        if argv[i] == "--only":
            only.append(argv[i + 1])
            i += 2
        elif argv[i] == "--keep":
            keep = argv[i + 1]
            i += 2
        elif argv[i] == "--jobs":
            jobs = int(argv[i + 1])
            i += 2
        else:
            print("test_layout.py: unknown argument %s" % argv[i], file=sys.stderr)
            return 2
    if only:
        every = {c[0]: c for c in layout_cases.CASES}
        cases = [every[n] for n in dict.fromkeys(only) if n in every]
        if len(cases) != len(set(only)):
            print("test_layout.py: no such case among %s" % only, file=sys.stderr)
            return 2
    with tempfile.TemporaryDirectory(prefix="jc-layout-") as tmp:
        outdir = keep or tmp
        os.makedirs(outdir, exist_ok=True)
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            results = list(pool.map(lambda c: run_case(jumpcyl, outdir, c), cases))
    failed = 0
    for name, failures in results:
        for line in failures:
            print(line)
        print("%s %s" % ("FAIL" if failures else "ok  ", name))
        failed += bool(failures)
    print("%d passed, %d failed" % (len(results) - failed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
