#!/usr/bin/env python3
"""Lists references in tracked files to places outside the repository.

Usage: /usr/bin/python3 dev/outside_references.py   (exit 1 when any is found)

A user's clone holds only the repository, so no tracked file may send the reader (or a program)
to a file beside or above it. Flagged, in every text file `git ls-files` names:
- a relative path that climbs (`../x/y`) and names nothing inside the repository, whether read
  from the file's own folder or from any top-level folder (experiment files name models
  relative to themselves, so `../examples/...` written in the README is read from
  experiments/);
- an absolute path into a home, work or shared folder (`/work/...`, `/home/...`, `/shared/...`,
  `/Users/...`, `/mnt/...`, `/root/...`, `/scratch/...`), which exists on one machine only.
A test that feeds the runner such a path on purpose is listed in ALLOWED, with its reason; this
file, which spells the patterns out, is not read.
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
CLIMBING = re.compile(r"(?<![\w/$}.-])((?:\.\./)+[A-Za-z_][\w./-]*)")
ABSOLUTE = re.compile(r"(?<![\w.$}/-])(/(?:work|home|shared|Users|mnt|root|scratch)/[\w./-]*)")
ALLOWED = {
    ("tests/runner/config/paths_test.cc", "../q.xml"): "input of a path-joining unit test",
    ("tests/runner/input_corpus.sh", "../../escaped"): "a run name the runner must refuse",
    ("tests/runner/record/output_test.cc", "/home/someone/experiments/exp2.toml"):
        "a source path the config echo must shorten to its file name",
}


def tracked_files():
    """The repository's tracked text files, as paths relative to its root."""
    names = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], check=True,
                           capture_output=True).stdout.decode().split("\0")
    for name in filter(None, names):
        path = ROOT / name
        if path == pathlib.Path(__file__).resolve():
            continue
        if not path.is_file():
            continue
        data = path.read_bytes()
        if b"\0" not in data[:8192]:
            yield name, data.decode("utf-8", errors="replace")


def resolves_inside(name, reference):
    """Whether `reference` names an existing path in the repository from some plausible folder."""
    bases = [(ROOT / name).parent] + [p for p in ROOT.iterdir() if p.is_dir()]
    for base in bases:
        target = (base / reference.rstrip(".")).resolve()
        if target.is_relative_to(ROOT) and target.exists():
            return True
    return False


def findings(name, text):
    """(line number, reference) for each outside reference in one file."""
    for number, line in enumerate(text.splitlines(), 1):
        for reference in CLIMBING.findall(line):
            if (name, reference) not in ALLOWED and not resolves_inside(name, reference):
                yield number, reference
        for reference in ABSOLUTE.findall(line):
            if (name, reference) not in ALLOWED:
                yield number, reference


def main():
    found = [(name, number, reference) for name, text in tracked_files()
             for number, reference in findings(name, text)]
    for name, number, reference in found:
        print(f"{name}:{number}: '{reference}' points outside the repository; point at a file "
              "inside it (the paper's equations: docs/EQUATIONS.md; the design: "
              "docs/ARCHITECTURE.md) or write the path relative to the repository")
    if found:
        sys.exit(1)
    print("outside_references: no tracked file points outside the repository")


if __name__ == "__main__":
    main()
