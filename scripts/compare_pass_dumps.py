#!/usr/bin/env python3
"""Compares two snapshots of scripts/pass_dump_snapshot.sh.

PNGs: their pixels (IHDR + the decompressed IDAT stream; tEXt provenance such as the commit is
ignored). passes.json and the render's JSON line: equal after removing what differs between any
two runs (timings, commit, command) and the keys named by --ignore-key (e.g. a new pass id).
Prints every difference and exits 1 when there is one.
    usage: compare_pass_dumps.py BEFORE AFTER [--ignore-key id ...]
"""
import json
import os
import struct
import sys
import zlib

RUN_KEYS = {"milliseconds", "frame_ms", "commit", "command", "ms", "median_ms", "timings"}


def png_pixels(path):
    data = open(path, "rb").read()
    at, header, idat = 8, b"", b""
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind = data[at + 4:at + 8]
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    return header, zlib.decompress(idat)


def strip(value, ignored):
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if k in RUN_KEYS or k in ignored:
                continue
            if k == "passes" and isinstance(v, dict):  # the JSON line: pass name -> ms
                out[k] = sorted(v.keys())
                continue
            out[k] = strip(v, ignored)
        return out
    if isinstance(value, list):
        return [strip(v, ignored) for v in value]
    return value


def first_difference(a, b, path="$"):
    """The path and the two values where two JSON values first differ."""
    if type(a) is not type(b):
        return f"{path}: {json.dumps(a)[:160]} != {json.dumps(b)[:160]}"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k}: only in {'after' if k in b else 'before'}"
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        if len(a) != len(b):
            return f"{path}: {len(a)} items before, {len(b)} after"
        return None
    return None if a == b else f"{path}: {json.dumps(a)[:160]} != {json.dumps(b)[:160]}"


def main():
    args = sys.argv[1:]
    ignored = set()
    while "--ignore-key" in args:
        i = args.index("--ignore-key")
        ignored.add(args[i + 1])
        del args[i:i + 2]
    before, after = args
    problems, files = [], 0
    for root, _, names in os.walk(before):
        for name in sorted(names):
            a = os.path.join(root, name)
            rel = os.path.relpath(a, before)
            b = os.path.join(after, rel)
            if not os.path.exists(b):
                problems.append(f"missing after: {rel}")
                continue
            files += 1
            if name.endswith(".png"):
                if png_pixels(a) != png_pixels(b):
                    problems.append(f"pixels differ: {rel}")
            elif name.endswith(".json"):
                ja, jb = (strip(json.load(open(p)), ignored) for p in (a, b))
                if ja != jb:
                    problems.append(f"json differs: {rel}: {first_difference(ja, jb)}")
            elif name == "stderr.txt":
                if open(a).read() != open(b).read():
                    problems.append(f"stderr differs: {rel}")
    for root, _, names in os.walk(after):
        for name in names:
            rel = os.path.relpath(os.path.join(root, name), after)
            if not os.path.exists(os.path.join(before, rel)):
                problems.append(f"new after: {rel}")
    for p in problems:
        print(p)
    print(f"{files} files compared, {len(problems)} differences")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
