#!/usr/bin/env python3
"""Lists C++ functions longer than a limit (default 150 lines) in the source folders.

    python3 tests/check_function_length.py [ROOT] [--limit N]

A function is a brace block opened at namespace or class level by a line ending in '{' that
follows a parameter list ')' (definitions, not classes, namespaces or initializer lists);
lambdas and nested blocks count towards their enclosing function. Exits 1 if any is too long.
"""
import os
import re
import sys

FOLDERS = ["core", "energies", "geometry", "optim", "scenes", "python/src"]
# A definition's head ends in its parameter list's ')' (or a constructor's initializer list),
# maybe followed by qualifiers; a type or namespace head does not count.
OPENS_FUNCTION = re.compile(r"\)\s*(const|override|final|noexcept|mutable|->\s*[\w:<>,\s]+)*$")
DECLARES_TYPE = re.compile(r"\b(namespace|class|struct|enum|union)\b[^()]*$")


def strip(line):
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def functions(path):
    out = []
    depth = 0
    in_comment = False
    header = ""
    start = None
    start_depth = None
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.readlines()
    for no, raw in enumerate(lines, 1):
        line = raw
        if in_comment:
            if "*/" not in line:
                continue
            line = line.split("*/", 1)[1]
            in_comment = False
        if "/*" in line and "*/" not in line:
            line = line.split("/*", 1)[0]
            in_comment = True
        code = strip(line)
        if start is None:
            header = (header + " " + code.strip())[-400:]
        for ch in code:
            if ch == "{":
                before = header[: header.rfind("{")] if "{" in header else header
                if (start is None and OPENS_FUNCTION.search(before.rstrip())
                        and not DECLARES_TYPE.search(before)):
                    start, start_depth = no, depth
                depth += 1
            elif ch == "}":
                depth -= 1
                if start is not None and depth == start_depth:
                    out.append((no - start + 1, start, header.strip()[:100]))
                    start = None
                    header = ""
        if start is None and code.strip().endswith((";", "}")):
            header = ""
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    limit = 150
    if "--limit" in sys.argv:
        limit = int(sys.argv[sys.argv.index("--limit") + 1])
        if str(limit) in args:
            args.remove(str(limit))
    root = args[0] if args else "."
    long_ones = []
    for folder in FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for name in files:
                if name.endswith((".cpp", ".h")):
                    path = os.path.join(dirpath, name)
                    for n, line, head in functions(path):
                        if n > limit:
                            long_ones.append((n, os.path.relpath(path, root), line, head))
    for n, path, line, head in sorted(long_ones, reverse=True):
        print(f"{n} lines: {path}:{line}")
    print(f"function length: {len(long_ones)} over {limit} lines" if long_ones else
          f"function length: ok (none over {limit} lines)")
    return 1 if long_ones else 0


if __name__ == "__main__":
    sys.exit(main())
