# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""pyproject.toml pins what requirements.txt pins, at the same versions: requirements.txt stays
the one place a PyPI version is chosen."""

import re
import tomllib


def pins(lines) -> dict:
    out = {}
    for line in lines:
        match = re.fullmatch(r"\s*([A-Za-z0-9_.-]+)==([0-9A-Za-z.]+)\s*", line.split("#")[0])
        if match:
            out[match.group(1).lower().replace("_", "-")] = match.group(2)
    return out


def test_pyproject_pins_are_requirements_pins(source):
    required = pins((source / "requirements.txt").read_text().splitlines())
    project = tomllib.loads((source / "pyproject.toml").read_text())
    listed = project["build-system"]["requires"] + project["project"]["dependencies"]
    for extra in project["project"].get("optional-dependencies", {}).values():
        listed = listed + extra
    assert all("==" in item for item in listed), listed
    given = pins(listed)
    assert given and len(given) == len(listed)
    for name, version in given.items():
        assert required.get(name) == version, f"{name}=={version} is not requirements.txt's pin"
