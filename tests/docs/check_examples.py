#!/usr/bin/env python3
"""The docs' examples, run and compared with what they quote.

Every fenced code block in README.md and docs/*.md whose first line starts
with `$ jumpcyl` is an example: each `$ COMMAND` line (continued on the
next line after a trailing backslash) is run with sh in a scratch
directory, with the built tool first on PATH as `jumpcyl`, `examples/`
of the source tree beside it and the docs' folders made empty there (so
that an example's figure never lands in the source tree). The lines after
it, up to the next `$` line, are what it prints: its standard output, then
its standard error. `echo $?` after a command prints that command's exit
status.

What the quote may leave out or let vary:

- a line `...` (or `…`) stands for any number of lines, none included;
- the time a run took is never compared: "0.03 s on 2 threads" matches any
  such time and thread count;
- an HTML comment on the line just before the block sets its tolerances,
  `<!-- example: digits=N atol=X slow -->`: numbers then compare equal
  when they agree to N significant digits, or differ by at most X (for
  residuals at rounding level, e.g. 8.9e-16), and runs of blanks count as
  one; `slow` leaves the block out unless --slow is given.

Usage:
  check_examples.py TOOL [--slow] [FILE.md ...]    check (exit 1 on a difference)
  check_examples.py TOOL --update [--slow] [FILE.md ...]
      write what the commands print into the blocks instead (`make
      docs-examples`): a block without `...` is replaced whole; in one
      with `...` each quoted stretch is replaced by the lines it stands
      for, found by their shape (the text with numbers left out).
Without files: README.md and docs/*.md of the source tree.
"""
import difflib
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ELISIONS = ("...", "\u2026")
OPTIONS = re.compile(r"^<!--\s*example:\s*(.*?)\s*-->\s*$")
NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
TIMING = re.compile(r"\b\d+(?:\.\d+)? s on \d+ threads?\b")


class Block:
    """One example: where it is in its file, its options, its commands."""

    def __init__(self, path, start, end, options, lines):
        self.path, self.start, self.end, self.options = path, start, end, options
        self.commands = []  # [command, [its source lines], [expected lines]]
        for line in lines:
            if line.startswith("$ ") and not (self.commands and self.commands[-1][0].endswith("\\")):
                self.commands.append([line[2:], [line], []])
            elif self.commands and self.commands[-1][0].endswith("\\") and not self.commands[-1][2]:
                self.commands[-1][0] = self.commands[-1][0][:-1].rstrip() + " " + line.strip()
                self.commands[-1][1].append(line)
            else:
                self.commands[-1][2].append(line)

    def where(self):
        return "%s:%d" % (os.path.relpath(self.path, ROOT), self.start + 1)


def parse_options(text):
    opts = {"digits": None, "atol": None, "slow": False}
    for word in text.split():
        key, _, value = word.partition("=")
        if key == "slow" and not value:
            opts["slow"] = True
        elif key == "digits" and value.isdigit():
            opts["digits"] = int(value)
        elif key == "atol" and value:
            opts["atol"] = float(value)
        else:
            raise SystemExit("unknown example option '%s' (allowed: digits=N, atol=X, slow)" % word)
    return opts


def blocks_of(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            body = lines[i + 1:j]
            if body and body[0].startswith("$ jumpcyl"):
                k = i - 1
                while k >= 0 and not lines[k].strip():
                    k -= 1
                m = OPTIONS.match(lines[k]) if k >= 0 else None
                blocks.append(Block(path, i, j, parse_options(m.group(1) if m else ""), body))
            i = j + 1
        else:
            i += 1
    return lines, blocks


class Runner:
    """A scratch directory with examples/ and the docs' folders; the tool on PATH."""

    def __init__(self, tool):
        self.dir = tempfile.mkdtemp(prefix="jumpcyl-docs-examples-")
        os.symlink(os.path.join(ROOT, "examples"), os.path.join(self.dir, "examples"))
        for sub in glob.glob(os.path.join(ROOT, "docs", "**", ""), recursive=True):
            os.makedirs(os.path.join(self.dir, os.path.relpath(sub, ROOT)), exist_ok=True)
        os.makedirs(os.path.join(self.dir, "bin"))
        os.symlink(os.path.abspath(tool), os.path.join(self.dir, "bin", "jumpcyl"))
        self.env = dict(os.environ, PATH=os.path.join(self.dir, "bin") + os.pathsep + os.environ.get("PATH", ""))

    def run(self, block):
        """Each command's output lines (standard output, then standard error)."""
        outputs, status = [], 0
        for command, _, _ in block.commands:
            p = subprocess.run(["sh", "-c", "(exit %d); %s" % (status, command)], cwd=self.dir, env=self.env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=600)
            status = p.returncode
            text = p.stdout.decode("utf-8", "replace") + p.stderr.decode("utf-8", "replace")
            outputs.append(text.split("\n")[:-1] if text.endswith("\n") else text.split("\n"))
        return outputs

    def close(self):
        shutil.rmtree(self.dir, ignore_errors=True)


def numbers_agree(a, b, opts):
    x, y = float(a), float(b)
    if x == y:
        return True
    if opts["atol"] is not None and abs(x - y) <= opts["atol"]:
        return True
    if opts["digits"] is not None:
        scale = max(abs(x), abs(y))
        exponent = int(f"{scale:e}".split("e")[1])
        return abs(x - y) <= 10.0 ** (exponent - opts["digits"] + 1)
    return False


def same_line(expected, actual, opts):
    expected, actual = TIMING.sub("<time>", expected), TIMING.sub("<time>", actual)
    if expected == actual:
        return True
    if opts["digits"] is None and opts["atol"] is None:
        return False
    e_nums, a_nums = NUMBER.findall(expected), NUMBER.findall(actual)
    e_text = " ".join(NUMBER.sub("#", expected).split())
    a_text = " ".join(NUMBER.sub("#", actual).split())
    return (e_text == a_text and len(e_nums) == len(a_nums) and
            all(numbers_agree(x, y, opts) for x, y in zip(e_nums, a_nums)))


def shape(line):
    """The line without its numbers and with one blank between words."""
    return " ".join(NUMBER.sub("#", TIMING.sub("<time>", line)).split())


def segments(expected):
    """The quoted stretches between `...` lines, and whether the quote is
    open at its start and at its end."""
    parts, current = [], []
    for line in expected:
        if line.strip() in ELISIONS:
            parts.append(current)
            current = []
        else:
            current.append(line)
    parts.append(current)
    return parts


def place(expected, actual, equal):
    """Where each quoted stretch lies in the actual lines (start indices),
    or None: stretches in order, each on consecutive lines, the first at
    the start and the last at the end unless `...` opens or closes it."""
    parts = segments(expected)
    starts, pos = [], 0
    for k, part in enumerate(parts):
        first, last = k == 0, k == len(parts) - 1
        candidates = range(pos, len(actual) - len(part) + 1)
        if first:
            candidates = [0] if len(actual) >= len(part) else []
        if last:
            candidates = [c for c in candidates if c + len(part) == len(actual)]
        found = next((c for c in candidates if all(equal(e, a) for e, a in zip(part, actual[c:]))), None)
        if found is None:
            return None
        starts.append(found)
        pos = found + len(part)
    return starts


def check(block, outputs):
    problems = []
    for (command, _, expected), actual in zip(block.commands, outputs):
        if place(expected, actual, lambda e, a: same_line(e, a, block.options)) is None:
            diff = difflib.unified_diff(expected, actual, "quoted", "printed", lineterm="", n=1)
            problems.append("%s: $ %s\n%s" % (block.where(), command, "\n".join(diff)))
    return problems


def kept(old, new, opts):
    """The new lines, but an old one wherever it still matches (a time that
    differs only as times do is not rewritten)."""
    if len(old) != len(new):
        return new
    return [o if same_line(o, n, opts) else n for o, n in zip(old, new)]


def updated(block, outputs):
    """The block's new lines, or raises ValueError."""
    lines = []
    for (command, source, expected), actual in zip(block.commands, outputs):
        lines += source
        parts = segments(expected)
        if len(parts) == 1:
            lines += kept(expected, actual, block.options)
            continue
        starts = place(expected, actual, lambda e, a: shape(e) == shape(a))
        if starts is None:
            raise ValueError("%s: $ %s: the quoted lines no longer have the shape of the output; "
                             "edit the quote by hand" % (block.where(), command))
        for k, (part, start) in enumerate(zip(parts, starts)):
            if k > 0:
                lines.append("...")
            lines += kept(part, actual[start:start + len(part)], block.options)
    return lines


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    flags = {a for a in argv[1:] if a.startswith("--")}
    if not args or flags - {"--update", "--slow"}:
        sys.stderr.write(__doc__)
        return 2
    tool, files = args[0], args[1:] or [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    runner = Runner(tool)
    problems, checked, skipped, changed = [], 0, 0, []
    try:
        for path in files:
            lines, blocks = blocks_of(path)
            file_changed = False
            for block in reversed(blocks):  # from the end: earlier blocks keep their line numbers
                if block.options["slow"] and "--slow" not in flags:
                    skipped += 1
                    continue
                outputs = runner.run(block)
                checked += 1
                if "--update" in flags:
                    try:
                        new = updated(block, outputs)
                    except ValueError as e:
                        problems.append(str(e))
                        continue
                    if new != lines[block.start + 1:block.end]:
                        lines[block.start + 1:block.end] = new
                        changed.append(block.where())
                        file_changed = True
                else:
                    problems += check(block, outputs)
            if file_changed:
                with open(path, "w", encoding="utf-8") as f:
                    f.write("\n".join(lines))
    finally:
        runner.close()
    for p in problems:
        print(p + "\n")
    if "--update" in flags:
        print("%d example(s) run, %d rewritten%s, %d slow one(s) left out" %
              (checked, len(changed), (": " + ", ".join(sorted(changed))) if changed else "", skipped))
    else:
        print("%d example(s) checked, %d differ, %d slow one(s) left out (--slow)" % (checked, len(problems), skipped))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
