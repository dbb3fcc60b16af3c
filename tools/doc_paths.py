#!/usr/bin/env python3
"""Every repository path a document names exists (docs/architecture.md's walk
of one strain sample, its rooms and their files): a renamed or removed file
shows here, not in a reader's failed search.

A path is a backticked span that starts with one of the repository's top-level
folders and has no spaces, e.g. `estimator/force_status.cc` or `controller/`;
a `name.h` alone or an absolute path (`/etc/birotor`) is not checked.

Usage: tools/doc_paths.py [--root DIR] FILE.md [FILE.md ...]
Exit 1 with one line per missing path; 0 when every named path exists.
"""
import argparse
import os
import re
import sys

SPAN = re.compile(r"`([^`\s]+)`")


def named_paths(text, folders):
    """Backticked spans that start with a top-level folder of the repository."""
    for span in SPAN.findall(text):
        path = re.sub(r":\d+$", "", span.split("::")[0]).rstrip(".,:;")
        if "<" in path or "*" in path:
            continue  # a pattern (`fuzz/corpus/<harness>/`), not a path
        head = path.split("/", 1)[0]
        if "/" in path and head in folders:
            yield path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("documents", nargs="+")
    args = parser.parse_args()
    folders = {d for d in os.listdir(args.root)
               if os.path.isdir(os.path.join(args.root, d)) and not d.startswith((".", "build", "out"))}
    missing, checked = [], 0
    for document in args.documents:
        with open(os.path.join(args.root, document), encoding="utf-8") as f:
            text = f.read()
        for path in sorted(set(named_paths(text, folders))):
            checked += 1
            if not os.path.exists(os.path.join(args.root, path)):
                missing.append(f"{document}: `{path}` does not exist")
    for line in missing:
        print(line)
    print(f"doc_paths: {checked} paths named, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
