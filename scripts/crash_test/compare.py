#!/usr/bin/env python3
"""Compares the outputs of a run that was killed and redone with those of the uninterrupted run
(scripts/crash_test.sh). Prints one line per difference and exits 1 if there is any.

  compare.py [--loose GLOB]... [--timed GLOB]... REFERENCE RUN

Every file of REFERENCE must be in RUN and RUN must hold no other (a `*.tmp-*` file left by a
killed writer is reported as such; lock files, `.lock` and `.FILE.lock`, are not outputs). Files are compared by what they hold, not by their bytes
where bytes may honestly differ:
  *.pt     LibTorch archives (zip): the tensors they hold, byte for byte
  *.csv    metrics: every column but timings (`seconds`)
  *.json   every key but `seconds`
  *.h5     HDF5: bytes, else every dataset and attribute (h5py)
  other    bytes
--timed GLOB: archives (path relative to REFERENCE) that keep the run's seconds as one float64
tensor (GAIL's checkpoint): every tensor equal but one of 8 bytes.
--loose GLOB: files that need only be complete, the outputs of a job whose resumed run is not
the uninterrupted one: CSVs with the same header and first column (one row per iteration or
epoch, in order), archives with tensors of the same sizes, JSON with the same keys."""
import argparse
import collections
import csv
import fnmatch
import json
import os
import sys
import zipfile

TIMING_KEYS = {"seconds"}


def is_lock(name):
    # A writer's flock file (`.lock`, `.FILE.lock`), which a killed writer leaves: not an output.
    return name.startswith(".") and name.endswith(".lock")


def files_under(root):
    found = set()
    for folder, _, names in os.walk(root):
        for name in names:
            if not is_lock(name):
                found.add(os.path.relpath(os.path.join(folder, name), root))
    return found


def archive_tensors(path):
    """The archive's tensor storages (entries data/N), as a sorted list. Their numbering and the rest of the
    archive are not compared: LibTorch keys an optimiser's state by parameter addresses and
    numbers the classes it writes per process, so one state saved by two processes differs there."""
    with zipfile.ZipFile(path) as z:
        return sorted(z.read(name) for name in z.namelist() if name.split("/", 1)[-1].startswith("data/"))


def csv_rows(path, complete_only):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return rows
    keep = [i for i, column in enumerate(rows[0]) if column not in TIMING_KEYS]
    if complete_only:
        keep = keep[:1]
    return [rows[0]] + [[row[i] if i < len(row) else None for i in keep] for row in rows[1:]]


def json_without_timings(path, complete_only):
    with open(path) as f:
        value = json.load(f)
    if isinstance(value, dict):
        value = {k: v for k, v in value.items() if k not in TIMING_KEYS}
        if complete_only:
            value = sorted(value)
    return value


def hdf5_contents(path):
    import h5py  # only where bytes differ
    import numpy

    def values(dataset):
        data = numpy.asarray(dataset[()])
        return repr(data.tolist()) if data.dtype.kind == "O" else data.tobytes()  # strings by value

    contents = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            attrs = {k: repr(v) for k, v in obj.attrs.items()}
            contents[name] = (attrs, values(obj) if isinstance(obj, h5py.Dataset) else None)
        contents["/"] = ({k: repr(v) for k, v in f.attrs.items()}, None)
        f.visititems(visit)
    return contents


def difference(reference, run, complete_only, timed):
    """None when `run` holds what `reference` holds, else why not."""
    extension = os.path.splitext(reference)[1]
    if extension == ".pt":
        a, b = archive_tensors(reference), archive_tensors(run)
        if complete_only:
            a, b = sorted(map(len, a)), sorted(map(len, b))
        if len(a) != len(b):
            return "%d tensors, the reference %d" % (len(b), len(a))
        only_a = collections.Counter(a) - collections.Counter(b)
        if timed and sorted(map(len, only_a.elements())) == [8]:
            return None  # the one float64 scalar that holds the run's seconds
        differing = sum(only_a.values())
        return "%d of %d tensors differ" % (differing, len(a)) if differing else None
    if extension == ".csv":
        a, b = csv_rows(reference, complete_only), csv_rows(run, complete_only)
        if len(a) != len(b):
            return "%d lines, the reference %d" % (len(b), len(a))
        for number, (x, y) in enumerate(zip(a, b), 1):
            if x != y:
                return "line %d: %s, the reference %s" % (number, ",".join(map(str, y)), ",".join(map(str, x)))
        return None
    if extension == ".json":
        a, b = json_without_timings(reference, complete_only), json_without_timings(run, complete_only)
        return None if a == b else "JSON differs (timings aside)"
    with open(reference, "rb") as f:
        a = f.read()
    with open(run, "rb") as f:
        b = f.read()
    if a == b:
        return None
    if extension == ".h5":
        return None if hdf5_contents(reference) == hdf5_contents(run) else "HDF5 datasets or attributes differ"
    return "bytes differ"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reference")
    parser.add_argument("run")
    parser.add_argument("--loose", action="append", default=[], metavar="GLOB")
    parser.add_argument("--timed", action="append", default=[], metavar="GLOB")
    args = parser.parse_args()
    expected, found = files_under(args.reference), files_under(args.run)
    problems = []
    for name in sorted(found - expected):
        problems.append("%s: %s" % (name, "temporary file left" if ".tmp-" in name else "not in the reference"))
    for name in sorted(expected - found):
        problems.append("%s: missing" % name)
    for name in sorted(expected & found):
        loose = any(fnmatch.fnmatch(name, glob) for glob in args.loose)
        timed = any(fnmatch.fnmatch(name, glob) for glob in args.timed)
        why = difference(os.path.join(args.reference, name), os.path.join(args.run, name), loose, timed)
        if why:
            problems.append("%s: %s" % (name, why))
    for line in problems:
        print(line)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
