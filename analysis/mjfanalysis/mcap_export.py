# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A run directory as an MCAP file that Foxglove opens (docs/PYTHON.md, "Runs in Foxglove").

    python -m mjfanalysis.mcap_export runs/exp2            # -> runs/exp2.mcap
    python -m mjfanalysis.mcap_export runs/exp2 -o exp2.mcap

Messages are JSON with Foxglove's well-known schema names and field layout, so Foxglove's 3D,
Plot and Log panels read them without a plugin:

    /tf                  foxglove.FrameTransforms  world -> uav<i> (0: the leader), every row
    /scene/vehicles      foxglove.SceneUpdate      a box per vehicle at its pose, every row
    /scene/formation     foxglove.SceneUpdate      the desired slots (leader + f_i) and their ring
    /metrics/sigma_f     mjformation.SigmaF        sigma_f, the formation error (Definition 2)
    /followers/sliding   mjformation.Sliding       s_x, s_y per follower (arrays, follower order)
    /events              foxglove.Log              safety events, and how the run ended

Times are the simulated time from 0 (Foxglove shows them as seconds after 1970-01-01). The run's
summary.json is the file's metadata "summary"; config.toml and scene.xml are attachments. The
schemas are JSON Schemas written here for the fields we fill. Needs the `mcap` package
(requirements.txt); uncompressed chunks, so reading needs nothing more.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

from .io import read_summary, read_timeseries_csv

ERROR, WARNING, INFO = 4, 3, 2  # foxglove.Log levels
# Events that lose a vehicle or touch another are errors; the reported-only ones are warnings.
EVENT_LEVEL = {"flip": ERROR, "ground_impact": ERROR, "collision": ERROR,
               "near_miss": WARNING, "left_region": WARNING}
VEHICLE_SIZE = {"x": 0.55, "y": 0.55, "z": 0.12}  # m: the Iris-like quadrotor's span and height
SLOT_DIAMETER = 0.3  # m


def _object(**properties) -> dict:
    return {"type": "object", "properties": properties}


_NUMBER = {"type": "number"}
_TIME = _object(sec={"type": "integer"}, nsec={"type": "integer"})
_VECTOR = _object(x=_NUMBER, y=_NUMBER, z=_NUMBER)
_QUATERNION = _object(x=_NUMBER, y=_NUMBER, z=_NUMBER, w=_NUMBER)
_POSE = _object(position=_VECTOR, orientation=_QUATERNION)
_COLOR = _object(r=_NUMBER, g=_NUMBER, b=_NUMBER, a=_NUMBER)
_PRIMITIVE = _object(pose=_POSE, size=_VECTOR, color=_COLOR)
_LINE = _object(type={"type": "integer"}, pose=_POSE, thickness=_NUMBER,
                scale_invariant={"type": "boolean"}, points={"type": "array", "items": _VECTOR},
                color=_COLOR)
_ARRAY = {"type": "array", "items": _NUMBER}

SCHEMAS = {
    "foxglove.FrameTransforms": _object(transforms={"type": "array", "items": _object(
        timestamp=_TIME, parent_frame_id={"type": "string"}, child_frame_id={"type": "string"},
        translation=_VECTOR, rotation=_QUATERNION)}),
    "foxglove.SceneUpdate": _object(
        deletions={"type": "array"},
        entities={"type": "array", "items": _object(
            timestamp=_TIME, frame_id={"type": "string"}, id={"type": "string"}, lifetime=_TIME,
            frame_locked={"type": "boolean"}, cubes={"type": "array", "items": _PRIMITIVE},
            spheres={"type": "array", "items": _PRIMITIVE},
            lines={"type": "array", "items": _LINE})}),
    "foxglove.Log": _object(timestamp=_TIME, level={"type": "integer"},
                            message={"type": "string"}, name={"type": "string"},
                            file={"type": "string"}, line={"type": "integer"}),
    "mjformation.SigmaF": _object(timestamp=_TIME, sigma_f=_NUMBER),
    "mjformation.Sliding": _object(timestamp=_TIME, sx=_ARRAY, sy=_ARRAY),
}
TOPICS = {"/tf": "foxglove.FrameTransforms", "/scene/vehicles": "foxglove.SceneUpdate",
          "/scene/formation": "foxglove.SceneUpdate", "/metrics/sigma_f": "mjformation.SigmaF",
          "/followers/sliding": "mjformation.Sliding", "/events": "foxglove.Log"}


def quaternion_zyx(roll: float, pitch: float, yaw: float) -> dict:
    """The unit quaternion of ZYX Euler angles (timeseries.csv's roll, pitch, yaw):
    q = q_z(yaw) q_y(pitch) q_x(roll)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return {"x": sr * cp * cy - cr * sp * sy, "y": cr * sp * cy + sr * cp * sy,
            "z": cr * cp * sy - sr * sp * cy, "w": cr * cp * cy + sr * sp * sy}


def _nanoseconds(t: float) -> int:
    return int(round(t * 1e9))


def _stamp(ns: int) -> dict:
    return {"sec": ns // 1_000_000_000, "nsec": ns % 1_000_000_000}


def _vehicles(columns: dict) -> int:
    """Number of vehicles (leader included) in the timeseries' columns."""
    n = 0
    while f"uav{n}_px" in columns:
        n += 1
    return n


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


class _Row:
    """The messages of one timeseries.csv row."""

    def __init__(self, columns: dict, row: int, vehicles: int, altitude: float):
        self.c, self.k, self.n, self.altitude = columns, row, vehicles, altitude
        self.ns = _nanoseconds(float(columns["t"][row]))

    def value(self, vehicle: int, name: str) -> float:
        return float(self.c[f"uav{vehicle}_{name}"][self.k])

    def position(self, i: int) -> dict:
        return {"x": self.value(i, "px"), "y": self.value(i, "py"), "z": self.value(i, "pz")}

    def rotation(self, i: int) -> dict:
        return quaternion_zyx(self.value(i, "roll"), self.value(i, "pitch"), self.value(i, "yaw"))

    def transforms(self) -> dict:
        return {"transforms": [
            {"timestamp": _stamp(self.ns), "parent_frame_id": "world", "child_frame_id": f"uav{i}",
             "translation": self.position(i), "rotation": self.rotation(i)}
            for i in range(self.n)]}

    def _entity(self, name: str, **primitives) -> dict:
        return {"timestamp": _stamp(self.ns), "frame_id": "world", "id": name,
                "lifetime": _stamp(0), "frame_locked": False, **primitives}

    def vehicles(self) -> dict:
        cubes = [{"pose": {"position": self.position(i), "orientation": self.rotation(i)},
                  "size": VEHICLE_SIZE,
                  "color": {"r": 0.85, "g": 0.2, "b": 0.2, "a": 1.0} if i == 0
                  else {"r": 0.15, "g": 0.4, "b": 0.85, "a": 1.0}}
                 for i in range(self.n)]
        return {"deletions": [], "entities": [self._entity("vehicles", cubes=cubes)]}

    def formation(self) -> dict:
        slots = [{"x": self.value(i, "slot_x"), "y": self.value(i, "slot_y"), "z": self.altitude}
                 for i in range(1, self.n)]
        slots = [s for s in slots if math.isfinite(s["x"]) and math.isfinite(s["y"])]
        identity = {"position": {"x": 0, "y": 0, "z": 0}, "orientation": quaternion_zyx(0, 0, 0)}
        green = {"r": 0.1, "g": 0.75, "b": 0.3, "a": 0.8}
        spheres = [{"pose": {"position": s, "orientation": identity["orientation"]},
                    "size": {"x": SLOT_DIAMETER, "y": SLOT_DIAMETER, "z": SLOT_DIAMETER},
                    "color": green} for s in slots]
        ring = {"type": 1, "pose": identity, "thickness": 2.0, "scale_invariant": True,
                "points": slots, "color": green}  # type 1: LINE_LOOP
        return {"deletions": [],
                "entities": [self._entity("formation", spheres=spheres, lines=[ring])]}

    def sigma_f(self) -> dict:
        return {"timestamp": _stamp(self.ns), "sigma_f": _finite(float(self.c["sigma_f"][self.k]))}

    def sliding(self) -> dict:
        return {"timestamp": _stamp(self.ns),
                "sx": [_finite(self.value(i, "sx")) for i in range(1, self.n)],
                "sy": [_finite(self.value(i, "sy")) for i in range(1, self.n)]}


def _logs(summary: dict, end_ns: int) -> list[tuple[int, dict]]:
    """(time, foxglove.Log) for each safety event, then one for how the run ended."""
    logs = []
    for e in summary.get("events", {}).get("list", []):
        ns = _nanoseconds(float(e["time_s"]))
        logs.append((ns, {"timestamp": _stamp(ns), "level": EVENT_LEVEL.get(e["kind"], WARNING),
                          "message": e["what"], "name": e["kind"], "file": "summary.json",
                          "line": 0}))
    complete = summary.get("complete", False)
    ending = "run complete" if complete else f"run stopped early: {summary.get('error', '')}"
    logs.append((end_ns, {"timestamp": _stamp(end_ns), "level": INFO if complete else ERROR,
                          "message": ending, "name": "run", "file": "summary.json", "line": 0}))
    return sorted(logs, key=lambda item: item[0])


def _altitude(run_dir: Path) -> float:
    """[vehicles] altitude of the run's config.toml (m), where the slots are drawn."""
    try:
        import tomllib
        with open(run_dir / "config.toml", "rb") as f:
            return float(tomllib.load(f).get("vehicles", {}).get("altitude", 5.0))
    except (OSError, ValueError):
        return 5.0


def _register(writer) -> dict[str, int]:
    schema_ids = {name: writer.register_schema(name=name, encoding="jsonschema",
                                               data=json.dumps(schema).encode())
                  for name, schema in SCHEMAS.items()}
    return {topic: writer.register_channel(topic=topic, message_encoding="json",
                                           schema_id=schema_ids[schema])
            for topic, schema in TOPICS.items()}


def _attach(writer, run_dir: Path, summary: dict) -> None:
    writer.add_metadata("summary", {"summary.json": json.dumps(summary)})
    for name, media in (("config.toml", "application/toml"), ("scene.xml", "application/xml")):
        if (run_dir / name).is_file():
            writer.add_attachment(create_time=0, log_time=0, name=name, media_type=media,
                                  data=(run_dir / name).read_bytes())


def write_mcap(run_dir, out=None, *, overwrite: bool = False) -> Path:
    """Writes the run directory `run_dir` as MCAP (default: beside it, RUN_DIR.mcap, so the run
    directory keeps only the runner's files); returns the path. An existing file is refused
    unless `overwrite`."""
    from mcap.writer import CompressionType, Writer

    run_dir = Path(run_dir)
    out = Path(out) if out is not None else run_dir.parent / (run_dir.name + ".mcap")
    if out.exists() and not overwrite:
        raise FileExistsError(f"{out}: exists; pass overwrite=True (--overwrite) to replace it")
    columns = read_timeseries_csv(run_dir / "timeseries.csv")
    summary = read_summary(run_dir / "summary.json")
    vehicles, altitude, rows = _vehicles(columns), _altitude(run_dir), len(columns["t"])
    with open(out, "wb") as stream:
        writer = Writer(stream, compression=CompressionType.NONE)
        writer.start(profile="", library="mjformation")
        channels = _register(writer)
        logs = _logs(summary, _nanoseconds(float(columns["t"][-1])) if rows else 0)
        for k in range(rows):
            row = _Row(columns, k, vehicles, altitude)
            while logs and logs[0][0] <= row.ns:
                _add(writer, channels["/events"], *logs.pop(0))
            for topic, message in (("/tf", row.transforms()), ("/scene/vehicles", row.vehicles()),
                                   ("/scene/formation", row.formation()),
                                   ("/metrics/sigma_f", row.sigma_f()),
                                   ("/followers/sliding", row.sliding())):
                _add(writer, channels[topic], row.ns, message)
        for ns, message in logs:
            _add(writer, channels["/events"], ns, message)
        _attach(writer, run_dir, summary)
        writer.finish()
    return out


def _add(writer, channel: int, ns: int, message: dict) -> None:
    writer.add_message(channel_id=channel, log_time=ns, publish_time=ns,
                       data=json.dumps(message, allow_nan=False).encode())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Write a run directory as MCAP for Foxglove")
    parser.add_argument("run_dir", help="a run directory (timeseries.csv, summary.json)")
    parser.add_argument("-o", "--out", help="the .mcap file (default RUN_DIR.mcap)")
    parser.add_argument("--overwrite", action="store_true", help="replace an existing file")
    args = parser.parse_args(argv)
    try:
        print(write_mcap(args.run_dir, args.out, overwrite=args.overwrite))
    except (FileExistsError, FileNotFoundError, KeyError) as e:
        parser.exit(1, f"mcap_export: error: {e}\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
