#!/usr/bin/env python3
"""Reads a study store (DIR/study.h5, written by `seedcal calibrate`) into pandas data frames.

Usage: python3 scripts/read_store.py DIR/study.h5|DIR [--check-doc docs/store.md]

Prints the schema version and a summary of each frame: `evaluations` (one row per DEM run, the
JSON columns decoded) and one numeric table per target (`/tables/<target>`, schema 2). The
layout is docs/store.md. As a module:

    from read_store import read_store
    store = read_store("out/jinong1-quick/study.h5")
    store.evaluations, store.tables["shear"], store.stages["confirm"], store.attributes

--check-doc FILE checks the store against the layout FILE documents: every dataset and attribute
the file lists (its table rows whose first cell is a path in backticks, `/group/dataset` or
`/group/@attribute`, `<name>` standing for any one name) is in the store and was read here, and
everything in the store is listed. Exit 1 with the differences when not.

Needs h5py and pandas (Debian: python3-h5py python3-pandas).
"""
import json
import os
import re
import sys
from dataclasses import dataclass, field

import h5py
import numpy as np
import pandas as pd

# The layout this script knows (docs/store.md, "Schema version").
SCHEMA_VERSION = 2

# The fixed columns of a table (/tables/<target>/...) and of /evaluations, in frame order.
TABLE_COLUMNS = ["id", "seed", "stage", "status", "model", "cpu_seconds", "wall_seconds"]
EVALUATION_COLUMNS = ["id", "seed", "stage", "status", "cpu_seconds", "wall_seconds"]
EVALUATION_JSON = ["inputs_json", "metrics_json", "record_json"]


@dataclass
class Store:
    path: str
    attributes: dict                 # root attributes (schema_version is 1 when absent)
    evaluations: pd.DataFrame        # one row per run
    tables: dict                     # target -> numeric frame, one row per run of that target
    stages: dict                     # /stages: stage name -> its record
    read: set = field(default_factory=set)  # every HDF5 path read (attributes as /group/@name)


class _Reader:
    """Reads datasets and attributes, remembering the path of each one read."""

    def __init__(self, f):
        self.f = f
        self.read = set()

    def dataset(self, path):
        d = self.f[path]
        self.read.add(d.name)
        if h5py.check_string_dtype(d.dtype) is not None:
            return np.asarray(d.asstr()[()], dtype=object)
        return d[()]

    def attribute(self, obj, name):
        self.read.add(_attribute_path(obj.name, name))
        value = obj.attrs[name]
        if isinstance(value, bytes):
            return value.decode("utf-8")
        if isinstance(value, np.generic):
            return value.item()
        return value


def _attribute_path(obj_name, attr):
    return obj_name.rstrip("/") + "/@" + attr


def _evaluations(r):
    g = r.f["evaluations"]
    frame = pd.DataFrame({c: r.dataset(g[c].name) for c in EVALUATION_COLUMNS})
    inputs = [json.loads(t) for t in r.dataset(g["inputs_json"].name)]
    metrics = [json.loads(t) for t in r.dataset(g["metrics_json"].name)]
    records = [json.loads(t) for t in r.dataset(g["record_json"].name)]
    # The fields only the whole record holds.
    for key in ["message", "config_hash", "seedcal_version"]:
        frame[key] = [rec.get(key, "") for rec in records]
    frame["target"] = [m.get("study_target_name", "") for m in metrics]
    frame["model"] = [m.get("study_model", "") for m in metrics]
    # Parameters and metrics as columns `inputs.<path>` and `metrics.<key>` (lists and objects
    # stay Python values in their cells).
    extra = pd.DataFrame(
        [{**{"inputs." + k: v for k, v in i.items()}, **{"metrics." + k: v for k, v in m.items()}}
         for i, m in zip(inputs, metrics)],
        index=frame.index)
    return pd.concat([frame, extra], axis=1)


def _table(r, g):
    frame = pd.DataFrame({c: r.dataset(g[c].name) for c in TABLE_COLUMNS})
    for sub, prefix in [("inputs", "inputs."), ("metrics", "metrics.")]:
        for name in sorted(g[sub]):
            frame[prefix + name] = r.dataset(g[sub][name].name)
    return r.attribute(g, "target_name"), frame


def read_store(path):
    """The store at `path` (study.h5, or the study directory holding it)."""
    if os.path.isdir(path):
        path = os.path.join(path, "study.h5")
    with h5py.File(path, "r") as f:
        r = _Reader(f)
        attributes = {name: r.attribute(f, name) for name in f.attrs}
        attributes.setdefault("schema_version", 1)
        evaluations = _evaluations(r)
        stages = json.loads(r.attribute(f["stages"], "stages_json"))
        tables = {}
        if "tables" in f:
            for name in sorted(f["tables"]):
                target, frame = _table(r, f["tables"][name])
                tables[target or name] = frame
        return Store(path, attributes, evaluations, tables, stages, r.read)


# ---- --check-doc ------------------------------------------------------------------------------

def documented_paths(doc_text):
    """The paths of the documented datasets and attributes: the first cell of every Markdown table
    row, when it is one path in backticks (groups, ending in '/', are left out)."""
    paths = []
    for line in doc_text.splitlines():
        m = re.match(r"^\|\s*`(/[^`]*)`\s*\|", line)
        if m and not m.group(1).endswith("/"):
            paths.append(m.group(1))
    return paths


def _pattern(doc_path):
    parts = re.split(r"(<[^>]+>)", doc_path)
    return re.compile("^" + "".join("[^/]+" if p.startswith("<") else re.escape(p) for p in parts) + "$")


def store_paths(path):
    """Every dataset and attribute in the store: /a/b and /a/@name."""
    found = set()
    with h5py.File(path, "r") as f:
        found.update(_attribute_path("/", a) for a in f.attrs)

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                found.add("/" + name)
            found.update(_attribute_path("/" + name, a) for a in obj.attrs)
        f.visititems(visit)
    return found


def check_doc(store, doc_text):
    """The differences between the store and the layout doc_text documents, as lines; none when
    every documented path is in the store and was read, and every path in the store is
    documented."""
    documented = documented_paths(doc_text)
    if not documented:
        return ["the document lists no dataset or attribute (rows whose first cell is `/path`)"]
    patterns = [(d, _pattern(d)) for d in documented]
    present = store_paths(store.path)
    problems = []
    for d, p in patterns:
        hits = [x for x in present if p.match(x)]
        if not hits:
            problems.append(f"documented but not in the store: {d}")
        for x in sorted(hits):
            if x not in store.read:
                problems.append(f"in the store but not read by read_store.py: {x} (documented as {d})")
    for x in sorted(present):
        if not any(p.match(x) for _, p in patterns):
            problems.append(f"in the store but not documented: {x}")
    return problems


# ---- the command line -------------------------------------------------------------------------

def summary(store):
    lines = [f"{store.path}: schema version {store.attributes['schema_version']}, "
             f"{len(store.evaluations)} runs, stages: {', '.join(sorted(store.stages)) or 'none'}"]
    frames = [("evaluations", store.evaluations)] + [(f"tables[{t!r}]", fr) for t, fr in store.tables.items()]
    for name, frame in frames:
        lines.append(f"\n{name}: {frame.shape[0]} rows x {frame.shape[1]} columns")
        lines.append("  columns: " + ", ".join(map(str, frame.columns)))
        if "status" in frame:
            counts = frame["status"].value_counts()
            lines.append("  status: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
        numeric = frame.select_dtypes(include="number")
        if not numeric.empty and name != "evaluations":
            lines.append(numeric.describe().loc[["count", "mean", "min", "max"]].T.to_string())
    if store.attributes["schema_version"] < 2:
        lines.append("\nno numeric tables (schema 1): resuming the study with seedcal adds them")
    return "\n".join(lines)


def main(argv):
    args = list(argv)
    doc = None
    if "--check-doc" in args:
        i = args.index("--check-doc")
        if i + 1 >= len(args):
            print("read_store.py: --check-doc needs a file (docs/store.md)", file=sys.stderr)
            return 2
        doc = args[i + 1]
        del args[i:i + 2]
    if len(args) != 1 or args[0].startswith("-"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    path = args[0]
    if not os.path.exists(path):
        print(f"read_store.py: {path}: no such file or directory", file=sys.stderr)
        return 2
    try:
        store = read_store(path)
    except (OSError, KeyError) as e:
        print(f"read_store.py: {path}: not a readable study store ({e})", file=sys.stderr)
        return 1
    if store.attributes["schema_version"] > SCHEMA_VERSION:
        print(f"read_store.py: {path} has schema {store.attributes['schema_version']}, newer than this "
              f"script's {SCHEMA_VERSION}: what it added is not read", file=sys.stderr)
    print(summary(store))
    if doc:
        with open(doc, encoding="utf-8") as f:
            problems = check_doc(store, f.read())
        if problems:
            print(f"\n{doc} and {store.path} differ:", file=sys.stderr)
            for p in problems:
                print("  " + p, file=sys.stderr)
            return 1
        print(f"\n{doc}: every documented dataset and attribute is in the store and was read; "
              "everything in the store is documented")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
