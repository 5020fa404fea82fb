#!/usr/bin/env python3
"""The dependency half of the MSRV check (see .ci/run for the whole).

Reads `cargo metadata --format-version 1 --locked --all-features` on
standard input and fails when a package of the locked dependency graph
(every feature, every platform, dev-dependencies included) declares a
`rust-version` newer than moyo's: with that lock file, a compiler of our
MSRV could not build it. Packages that declare none cannot be judged and
are only counted.
"""

import json
import sys


def version(text):
    """`1.85` or `1.85.0` as a tuple that compares as versions do."""
    parts = [int(p) for p in text.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def main():
    meta = json.load(sys.stdin)
    packages = {p["id"]: p for p in meta["packages"]}
    root = packages[meta["resolve"]["root"]]
    ours = root["rust_version"]
    locked = [packages[node["id"]] for node in meta["resolve"]["nodes"]]
    locked = [p for p in locked if p["id"] != root["id"]]
    newer = [
        p
        for p in locked
        if p["rust_version"] and version(p["rust_version"]) > version(ours)
    ]
    undeclared = sum(1 for p in locked if not p["rust_version"])
    for p in newer:
        print(
            f"msrv: {p['name']} {p['version']} needs Rust {p['rust_version']}, "
            f"moyo's rust-version is {ours}",
            file=sys.stderr,
        )
    if newer:
        return 1
    print(
        f"msrv: {len(locked) - undeclared} locked packages declare a rust-version "
        f"of at most {ours}; {undeclared} declare none"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
