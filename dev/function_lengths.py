#!/usr/bin/env python3
"""Lists functions in runner/ and plugins/ longer than a limit (default 60 lines): each does one job.

Usage: /usr/bin/python3 dev/function_lengths.py [LIMIT] [FOLDER...]   (exit 1 when any is longer)
FOLDER: relative to the repository root (default: runner plugins); every .cc, .hpp and .h in it.
ctest runs it (test function_lengths). A function is a block opened by a line at column 0 (or
indented inside a class) ending in '{' after a ')' and closed by the matching '}' at the same
indentation.
"""
import pathlib
import re
import sys

args = sys.argv[1:]
limit = int(args.pop(0)) if args and args[0].isdigit() else 60
folders = args or ["runner", "plugins"]
root = pathlib.Path(__file__).resolve().parent.parent
long_ones = []


def strip(line):
    """The line without strings, character literals and // comments (enough to count braces)."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def sources():
    """Every C++ source and header of the folders, in a stable order; a missing folder is an error."""
    for folder in folders:
        base = root / folder
        if not base.is_dir():
            sys.exit(f"function_lengths.py: no folder {base}")
        for path in sorted(base.rglob("*")):
            if path.suffix in (".cc", ".hpp", ".h") and path.is_file():
                yield path


for path in sources():
    lines = [strip(x) for x in path.read_text().split("\n")]
    depth, stack = 0, []  # stack of (depth before the body, start line, signature)
    signature_start = 0
    for i, line in enumerate(lines):
        code = line.strip()
        if not code:
            continue
        opens, closes = code.count("{"), code.count("}")
        is_function = (code.endswith("{") and ")" in code and not re.match(
            r"^(if|for|while|switch|else|do|catch|try|namespace|class|struct|enum)\b", code)
                       and "[" not in code.split("(")[0] and "= [" not in code and "[&" not in code
                       and "[=" not in code and "[]" not in code)
        if is_function and not stack:
            start = i
            while start > 0 and lines[start - 1].strip() and not lines[start - 1].strip().endswith(
                    (";", "}", "{")) and not lines[start - 1].strip().startswith("#"):
                start -= 1
            stack.append((depth, start, code))
        depth += opens - closes
        if stack and depth <= stack[-1][0]:
            d, start, sig = stack.pop()
            n = i - start + 1
            if n > limit:
                long_ones.append((n, f"{path.relative_to(root)}:{start + 1}", sig[:70]))
for n, where, sig in sorted(long_ones, reverse=True):
    print(f"{n:4d} lines  {where}  {sig}")
sys.exit(1 if long_ones else 0)
