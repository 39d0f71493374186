#!/usr/bin/env python3
"""Lists functions longer than a limit (default 60 lines): each does one job.

Usage: /usr/bin/python3 dev/function_lengths.py [LIMIT] [FOLDER...]   (exit 1 when any is longer)
FOLDER: relative to the repository root (default: runner plugins); every .cc, .hpp, .h and .py in
it. ctest runs it (test function_lengths). A C++ function is a block opened by a line at column 0
(or indented inside a class) ending in '{' after a ')' and closed by the matching '}' at the same
indentation. A Python function is a `def` as Python's own parser reads it, from its decorators to
its last line (a nested function counts inside its parent and on its own).
"""
import ast
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
            # Hidden folders hold installed third-party code (peers/.envs, a .venv), not ours.
            hidden = any(part.startswith(".") for part in path.relative_to(base).parts[:-1])
            if path.suffix in (".cc", ".hpp", ".h", ".py") and path.is_file() and not hidden:
                yield path


def python_functions(path):
    """(lines, first line, signature) of every function and method of a Python file."""
    tree = ast.parse(path.read_text(), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = min([node.lineno] + [d.lineno for d in node.decorator_list])
            yield node.end_lineno - first + 1, first, f"def {node.name}("


for path in sources():
    if path.suffix == ".py":
        for n, first, sig in python_functions(path):
            if n > limit:
                long_ones.append((n, f"{path.relative_to(root)}:{first}", sig))
        continue
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
