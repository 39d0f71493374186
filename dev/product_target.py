#!/usr/bin/env python3
"""Checks that the target scripts/reproduce.sh builds covers what the README's commands use.

Usage: /usr/bin/python3 dev/product_target.py BUILD_DIR   (exit 1 with the missing targets)

The README's first command builds one target (MJF_BUILD_TARGET in scripts/reproduce.sh); after
it, `mjformation plugins` must list every plugin family and `cmake --install` must find every
file it installs. So that target's dependency closure, read from the build system of BUILD_DIR
(Unix Makefiles: CMakeFiles/Makefile2; Ninja: `ninja -t inputs`), must hold every plugin family
(`mjformation_add_plugin` without NO_INSTALL in plugins/) and every target the source tree
installs (`install(TARGETS ...)` outside tests/ and examples/) that this build configured.
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def reproduce_target():
    """The target scripts/reproduce.sh asks scripts/build.sh for."""
    text = (ROOT / "scripts" / "reproduce.sh").read_text()
    found = re.search(r"MJF_BUILD_TARGET=(\S+)", text)
    if not found:
        sys.exit("product_target: scripts/reproduce.sh sets no MJF_BUILD_TARGET; "
                 "it must build one target that covers the README's commands")
    return found.group(1)


def wanted_targets():
    """Every plugin family and every installed target named in the source tree's CMakeLists."""
    wanted = set()
    for path in ROOT.rglob("CMakeLists.txt"):
        relative = path.relative_to(ROOT).parts
        if relative[0] in ("tests", "examples", "build") or relative[0].startswith("build"):
            continue
        text = path.read_text()
        for name, rest in re.findall(r"mjformation_add_plugin\((\S+)([^)]*)\)", text):
            if "NO_INSTALL" not in rest:
                wanted.add(name)
        for names in re.findall(r"install\(TARGETS ([^)]*?)(?:\s+[A-Z]+\b|\))", text):
            wanted.update(n for n in names.split() if not n.startswith("$"))
    return wanted


def makefile_closure(build, target):
    """Targets reached from `target` in a Unix Makefiles tree, and every target it configured."""
    edges, known = {}, set()
    rule = re.compile(r"^(?:\S*/)?CMakeFiles/([^/\s]+)\.dir/all:(?: (?:\S*/)?CMakeFiles/([^/\s]+)\.dir/all)?$")
    for line in (build / "CMakeFiles" / "Makefile2").read_text().splitlines():
        found = rule.match(line)
        if found:
            known.add(found.group(1))
            if found.group(2):
                edges.setdefault(found.group(1), set()).add(found.group(2))
    reached, todo = set(), [target]
    while todo:
        name = todo.pop()
        if name not in reached:
            reached.add(name)
            todo.extend(edges.get(name, ()))
    return reached, known


def ninja_closure(build, target):
    """The same for a Ninja tree: the file names of the transitive inputs."""
    inputs = subprocess.run(["ninja", "-C", str(build), "-t", "inputs", target], check=True,
                            capture_output=True, text=True).stdout
    targets = subprocess.run(["ninja", "-C", str(build), "-t", "targets", "all"], check=True,
                             capture_output=True, text=True).stdout
    stem = lambda p: re.sub(r"^lib|\.so.*$", "", pathlib.Path(p).name)
    return ({stem(p) for p in inputs.split()},
            {stem(line.split(":")[0]) for line in targets.splitlines()})


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    build = pathlib.Path(sys.argv[1])
    target = reproduce_target()
    if (build / "CMakeFiles" / "Makefile2").exists():
        reached, known = makefile_closure(build, target)
    else:
        reached, known = ninja_closure(build, target)
    if target not in known:
        sys.exit(f"product_target: scripts/reproduce.sh builds '{target}', which {build} "
                 "does not define; name a target of the top-level CMakeLists.txt")
    missing = sorted((wanted_targets() & known) - reached)
    if missing:
        sys.exit(f"product_target: scripts/reproduce.sh builds '{target}', which does not build "
                 f"{', '.join(missing)}; add them to its dependencies (top-level CMakeLists.txt)")
    print(f"product_target: '{target}' builds {len(wanted_targets() & known)} installed targets")


if __name__ == "__main__":
    main()
