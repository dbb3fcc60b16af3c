#!/usr/bin/env python3
"""Which room includes which, against the CMake link lines (issue 22).

For every library folder (a room with one add_library), lists the project
rooms its sources include (`#include "room/..."`) and checks that each is
reachable through its target_link_libraries, directly or through a PUBLIC /
INTERFACE dependency of a linked target. Prints the table of
docs/architecture.md ("What each room may include", project rooms only) and
every include without a matching link line (exit 1 if there is one) and
every library link to a project room none of the room's files includes.

Usage: tools/room_includes.py [ROOT]   (default: this repository)
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"', re.M)
ADD_LIBRARY = re.compile(r"add_library\(\s*(\w+)")
LINK = re.compile(r"target_link_libraries\(\s*(\w+)((?:\s+(?:PUBLIC|PRIVATE|INTERFACE|[\w:${}.+-]+))*)\s*\)", re.S)


def strip_cmake_comments(text):
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rooms = sorted(d for d in os.listdir(root) if os.path.isfile(os.path.join(root, d, "CMakeLists.txt"))
                   and d not in ("tests", "benchmarks", "fuzz", "tools", "services", "cmake")
                   and not d.startswith("build"))
    target_room, links = {}, {}
    for room in rooms:
        text = strip_cmake_comments(open(os.path.join(root, room, "CMakeLists.txt")).read())
        for name in ADD_LIBRARY.findall(text):
            target_room[name] = room
        for target, rest in LINK.findall(text):
            scope = "PUBLIC"
            for word in rest.split():
                if word in ("PUBLIC", "PRIVATE", "INTERFACE"):
                    scope = word
                    continue
                links.setdefault(target, []).append((word, scope))

    def reachable(target):
        """Targets whose headers target may use: its own links, and their PUBLIC/INTERFACE links, transitively."""
        seen, todo = set(), [dep for dep, _ in links.get(target, [])]
        while todo:
            dep = todo.pop()
            if dep in seen:
                continue
            seen.add(dep)
            todo.extend(d for d, scope in links.get(dep, []) if scope != "PRIVATE")
        return seen

    problems, unused = [], []
    print("| room | includes (project rooms) |")
    print("|---|---|")
    for room in rooms:
        targets = [t for t, r in target_room.items() if r == room]
        if not targets:
            continue
        included = {}
        for dirpath, _, files in os.walk(os.path.join(root, room)):
            for name in files:
                if not name.endswith((".h", ".cc", ".hpp", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                for other in INCLUDE.findall(open(path, encoding="utf-8", errors="replace").read()):
                    if other != room and other in rooms:
                        included.setdefault(other, set()).add(os.path.relpath(path, root))
        available = set()
        for t in targets:
            available |= {target_room.get(dep) for dep in reachable(t)}
        for other, paths in sorted(included.items()):
            if other not in available and other != "lcmtypes" or (other == "lcmtypes" and "lcmtypes" not in available):
                problems.append(f"{room}/ includes {other}/ ({', '.join(sorted(paths))}) "
                                f"without a link line from {' '.join(targets)}")
        for t in targets:
            for dep, _ in links.get(t, []):
                if target_room.get(dep) not in (None, room, "lcmtypes") and target_room[dep] not in included:
                    unused.append(f"{t} links {dep} but no file of {room}/ includes {target_room[dep]}/")
        print(f"| `{room}/` | {', '.join(sorted(included)) or '-'} |")
    for u in unused:
        print("link without include: " + u, file=sys.stderr)
    for p in problems:
        print("no link line: " + p, file=sys.stderr)
    return 1 if problems or unused else 0


if __name__ == "__main__":
    sys.exit(main())
