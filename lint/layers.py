#!/usr/bin/env python3
"""The layering check (make lint; docs/architecture.md, "Layers").

Builds two graphs between the project's source files (src/, include/, cli/,
web/) and fails on what runs against the layers:

  includes  every #include of a project file ("..." and <jumpcyl/...>);
  calls     between .c files, from the object files of a build: a file whose
            object uses a symbol (nm -P: U) that another project object
            defines calls that file. Calls made from static inline functions
            and macros of a header, which no object shows as the header's,
            are read from the header's text (an identifier followed by '('
            inside a function body or a #define that names a symbol a
            project object defines);
  declares  a header that declares a function defined in another folder
            (a prototype at file scope naming such a symbol) stands for that
            file: whoever includes the header depends on it.

A .c file and the header of the same name in the same directory (scan.c,
scan.h) are one unit: a loop between the two is no loop. Any other header
is a unit of its own. A folder's own headers may declare the functions of
every .c file of the folder; a header that declares functions of another
folder's file depends on that file, so a file that includes the header
and whose functions it declares makes a loop with it (the smell of a
header that serves several folders).

Violations:
  (a) a loop: a strongly connected component of more than one unit in the
      union of the three graphs;
  (b) an edge from a lower layer to a higher one (LAYERS below): a cli/
      folder reaching up, or the library reaching into the tool at all;
  (c) a folder of cli/ whose headers are not exactly one, named after it
      (cli/outputs/outputs.h): a second header, or none of that name.

Output: one violation per line,
  cli/design/scan.c -> cli/commands/options.c (calls cli_setup_apply)
  loop: cli/design/scan.c cli/design/solve.c
  header: cli/commands/track_input.h (cli/commands/ has one header, commands.h)
with, under a loop, the edges inside it (indented). --report lists all and
exits 0; the default (check) exits 1 on any violation not covered by the
allow-list (--allow FILE: one violation per line as printed, without the
parenthesis, then ' -- ' and the reason with the issue that removes it; a
loop is covered by an entry holding all of its files).
"""
import argparse
import os
import re
import subprocess
import sys
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The layers, top first: a file may include or call files of its own layer
# and of the layers below it, never above. Keys are path prefixes (longest
# wins); cli/main.c is the tool's top with commands/; web/
# (the page's entry point) is a client beside the tool.
LAYERS = [
    ("commands", ["cli/commands/", "cli/main.c", "web/"]),
    ("batch, design, track", ["cli/batch/", "cli/design/", "cli/track/"]),
    ("figures, films, inputs, outputs", ["cli/figures/", "cli/films/", "cli/inputs/", "cli/outputs/"]),
    ("process", ["cli/process/"]),
    ("library", ["src/", "include/"]),
]
# Folders for the "declares" relation: a header declaring functions of a
# .c file in another folder stands for that file. The library's headers
# (include/jumpcyl/jumpcyl.h, src/internal.h) are the library's own.
SOURCE_DIRS = ["src", "include", "cli", "web"]
# Where a quoted #include is looked for after the including file's own
# directory (the build's include directories, CMakeLists.txt).
INCLUDE_DIRS = ["include", "src", "cli", "cli/commands", "cli/inputs", "cli/figures", "cli/films", "cli/outputs",
                "cli/process", "cli/batch", "cli/design", "cli/track"]
DEFINED_TYPES = set("TDBRCVGSW")  # nm -P: global definitions (text, data, bss, read-only, common, weak)
SHOW_SYMBOLS = 3  # symbols named per edge


def layer_of(path):
    best, rank = -1, None
    for r, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if path.startswith(p) and len(p) > best:
                best, rank = len(p), r
    return rank  # 0 is the top


def folder_of(path):
    """The folder a file belongs to for the declares relation."""
    if path.startswith("src/") or path.startswith("include/"):
        return "library"
    return os.path.dirname(path)


def own_pair(a, b):
    """Whether a and b are a .c file and its header (x.c, x.h, one directory)."""
    sa, ea = os.path.splitext(a)
    sb, eb = os.path.splitext(b)
    return sa == sb and {ea, eb} == {".c", ".h"}


def project_files():
    files = []
    for d in SOURCE_DIRS:
        for dirpath, _, names in os.walk(os.path.join(ROOT, d)):
            for n in names:
                if n.endswith(".c") or n.endswith(".h"):
                    files.append(os.path.relpath(os.path.join(dirpath, n), ROOT))
    return sorted(files)


COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)
STRING = re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'')


def strip_code(text):
    """Comments removed (newlines kept, so that lines still count)."""
    return COMMENT.sub(lambda m: "\n" * m.group(0).count("\n") or " ", text)


INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*(?:"([^"]+)"|<([^>]+)>)', re.M)


def resolve_include(name, quoted, src, files):
    here = os.path.dirname(src)
    dirs = ([here] if quoted else []) + INCLUDE_DIRS
    for d in dirs:
        cand = os.path.normpath(os.path.join(d, name))
        if cand in files:
            return cand
    if quoted:
        raise SystemExit(f"layers.py: {src}: #include \"{name}\" is no project file I can find "
                         f"(add its directory to INCLUDE_DIRS)")
    return None  # a system header


def read_includes(files):
    edges = []
    fileset = set(files)
    for f in files:
        with open(os.path.join(ROOT, f), encoding="utf-8") as fh:
            text = strip_code(fh.read())
        for m in INCLUDE.finditer(text):
            target = resolve_include(m.group(1) or m.group(2), m.group(1) is not None, f, fileset)
            if target:
                edges.append((f, target, "includes", None))
    return edges


def object_source(obj, build):
    """build/CMakeFiles/TARGET.dir/cli/x/y.c.o -> cli/x/y.c"""
    rel = os.path.relpath(obj, build)
    m = re.search(r"\.dir/(.+\.c)\.o$", rel)
    return m.group(1) if m else None


def read_objects(build, files):
    """{source: (defined symbols, undefined symbols)} for the project's objects."""
    fileset = set(files)
    objs = defaultdict(list)
    for dirpath, _, names in os.walk(build):
        for n in names:
            if n.endswith(".c.o"):
                src = object_source(os.path.join(dirpath, n), build)
                if src in fileset:
                    objs[src].append(os.path.join(dirpath, n))
    if not objs:
        raise SystemExit(f"layers.py: no object files of the project's sources under {build}: "
                         f"build first (make build), or give the build directory")
    table = {}
    for src, paths in sorted(objs.items()):
        # The same source in several targets (the library, shared and
        # static): one set of symbols, the newest object's (an older one
        # may be left by a target the build no longer has).
        newest = max(paths, key=os.path.getmtime)
        out = subprocess.run(["nm", "-P", newest], check=True, capture_output=True, text=True).stdout
        defined, undefined = set(), set()
        for line in out.splitlines():
            parts = line.split()
            if len(parts) < 2:
                continue
            sym, kind = parts[0], parts[1]
            if kind in ("U", "w", "v"):
                undefined.add(sym)
            elif kind in DEFINED_TYPES:
                defined.add(sym)
        table[src] = (defined, undefined)
    return table


def definers(objects):
    where = defaultdict(set)
    for src, (defined, _) in objects.items():
        for s in defined:
            where[s].add(src)
    return where


def call_edges(objects, where):
    edges = []
    for src, (_, undefined) in objects.items():
        for sym in undefined:
            for target in where.get(sym, ()):
                if target != src:
                    edges.append((src, target, "calls", sym))
    return edges


IDENT_CALL = re.compile(r"\b([A-Za-z_]\w*)\s*\(")


def header_regions(text):
    """Splits a header (comments removed) into the text that runs (function
    bodies at file scope, #define bodies) and the text at file scope outside
    them (declarations)."""
    lines = text.split("\n")
    defines, rest = [], []
    i = 0
    while i < len(lines):
        line = lines[i]
        if re.match(r"[ \t]*#", line):
            block = [line]
            while block[-1].endswith("\\") and i + 1 < len(lines):
                i += 1
                block.append(lines[i])
            if re.match(r"[ \t]*#[ \t]*define\b", line):
                defines.append("\n".join(block))
            rest.append("")
        else:
            rest.append(line)
        i += 1
    code = STRING.sub('""', "\n".join(rest))
    bodies, outside = [], []
    depth, start, last = 0, 0, 0
    for k, ch in enumerate(code):
        if ch == "{":
            if depth == 0:
                start = k
                head = code[last:k].rstrip()
                is_function = head.endswith(")")
            depth += 1
        elif ch == "}" and depth > 0:
            depth -= 1
            if depth == 0:
                if is_function:
                    bodies.append(code[start:k + 1])
                    outside.append(code[last:start])
                else:
                    outside.append(code[last:start])  # a struct or enum: not code
                last = k + 1
    outside.append(code[last:])
    return "\n".join(bodies + defines), "\n".join(outside)


def header_edges(files, where):
    """Calls from a header's inline functions and macros; declarations of
    functions that another folder defines."""
    edges = []
    for f in files:
        if not f.endswith(".h"):
            continue
        with open(os.path.join(ROOT, f), encoding="utf-8") as fh:
            runs, outside = header_regions(strip_code(fh.read()))
        for sym in sorted(set(IDENT_CALL.findall(runs))):
            for target in where.get(sym, ()):
                if not own_pair(f, target):
                    edges.append((f, target, "calls", sym))
        for sym in sorted(set(IDENT_CALL.findall(outside))):
            for target in where.get(sym, ()):
                if folder_of(target) != folder_of(f):
                    edges.append((f, target, "declares", sym))
    return edges


def merge_edges(edges):
    """{(from, to): {kind: sorted symbols}}, files as given."""
    merged = defaultdict(lambda: defaultdict(set))
    for a, b, kind, sym in edges:
        merged[(a, b)][kind]
        if sym:
            merged[(a, b)][kind].add(sym)
    return merged


def describe(kinds):
    parts = []
    for kind in ("calls", "declares", "includes"):
        if kind not in kinds:
            continue
        syms = sorted(kinds[kind])
        if not syms:
            parts.append(kind)
            continue
        more = f" and {len(syms) - SHOW_SYMBOLS} more" if len(syms) > SHOW_SYMBOLS else ""
        parts.append(f"{kind} {', '.join(syms[:SHOW_SYMBOLS])}{more}")
    return "; ".join(parts)


def strongly_connected(nodes, succ):
    """Tarjan's algorithm, iterative: the components, each sorted."""
    index, low, on, stack, comps = {}, {}, set(), [], []
    counter = 0
    for root in sorted(nodes):
        if root in index:
            continue
        work = [(root, iter(sorted(succ[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(succ[w]))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                comps.append(sorted(comp))
    return comps


def violations(build):
    files = project_files()
    objects = read_objects(build, files)
    where = definers(objects)
    edges = read_includes(files) + call_edges(objects, where) + header_edges(files, where)
    merged = merge_edges(edges)

    found = []  # (key, line, details)
    # (b) against the layers.
    for (a, b), kinds in sorted(merged.items()):
        la, lb = layer_of(a), layer_of(b)
        if lb >= la and "declares" not in kinds:
            continue
        key = f"{a} -> {b}"
        found.append((key, f"{key} ({describe(kinds)})", []))
    # (a) loops, through calls and includes (a declaration is reported above).
    succ = defaultdict(set)
    for (a, b), kinds in merged.items():
        if set(kinds) != {"declares"} and not own_pair(a, b):
            succ[a].add(b)
            succ[b]
    for comp in strongly_connected(set(succ), succ):
        if len(comp) < 2:
            continue
        members = set(comp)
        details = [f"  {a} -> {b} ({describe(merged[(a, b)])})" for a in comp for b in sorted(succ[a] & members)]
        key = "loop: " + " ".join(comp)
        found.append((key, key, details))
    found += header_violations(files)
    return found


def header_violations(files):
    """(c): each folder of cli/ has one header, named after it."""
    headers = defaultdict(set)
    for f in files:
        folder = os.path.dirname(f)
        if os.path.dirname(folder) == "cli":
            headers[folder]
            if f.endswith(".h"):
                headers[folder].add(f)
    found = []
    for folder, hs in sorted(headers.items()):
        own = f"{os.path.basename(folder)}.h"
        for h in sorted(hs - {f"{folder}/{own}"}):
            key = f"header: {h}"
            found.append((key, f"{key} ({folder}/ has one header, {own})", []))
        if f"{folder}/{own}" not in hs:
            key = f"header: {folder}/{own}"
            found.append((key, f"{key} is missing (each folder of cli/ has one header named after it)", []))
    return found


def read_allow(path):
    """[(key, loop members or None)]; every entry must give a reason naming an issue."""
    entries = []
    with open(path, encoding="utf-8") as fh:
        for n, line in enumerate(fh, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            key, sep, reason = line.partition(" -- ")
            key = key.strip()
            if not sep or not re.search(r"\bissue \d+", reason):
                raise SystemExit(f"{path}:{n}: an entry is 'VIOLATION -- reason (issue N: what removes it)'")
            members = set(key[len("loop: "):].split()) if key.startswith("loop: ") else None
            entries.append((key, members))
    return entries


def allowed(key, entries):
    if key.startswith("loop: "):
        members = set(key[len("loop: "):].split())
        return any(m is not None and members <= m for _, m in entries)
    return any(k == key for k, _ in entries)


def main():
    ap = argparse.ArgumentParser(description="The layering check: loops and upward calls or includes "
                                 "between source files (docs/architecture.md, Layers).")
    ap.add_argument("build", nargs="?", default="build", help="the build directory with the objects (build/)")
    ap.add_argument("--report", action="store_true", help="list every violation and exit 0")
    ap.add_argument("--allow", metavar="FILE", help="known violations, each with its reason and issue")
    args = ap.parse_args()
    build = args.build if os.path.isabs(args.build) else os.path.join(os.getcwd(), args.build)

    found = violations(build)
    if args.report:
        for _, line, details in found:
            print(line)
            for d in details:
                print(d)
        print(f"layers: {len(found)} violation(s)", file=sys.stderr)
        return 0

    entries = read_allow(args.allow) if args.allow else []
    new = [(line, details) for key, line, details in found if not allowed(key, entries)]
    for line, details in new:
        print(line)
        for d in details:
            print(d)
    keys = [k for k, _, _ in found]
    for key, members in entries:
        if members is None and key not in keys or members is not None and not any(
                k.startswith("loop: ") and set(k[6:].split()) & members for k in keys):
            print(f"layers: note: the allow-list's '{key}' is gone: remove it", file=sys.stderr)
    known = len(found) - len(new)
    if new:
        print(f"layers: {len(new)} violation(s) of the layers (docs/architecture.md, Layers)"
              + (f"; {known} more allowed by {args.allow}" if known else ""), file=sys.stderr)
        return 1
    print(f"layers: no new violation ({known} allowed by {args.allow})" if known else "layers: no violation",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
