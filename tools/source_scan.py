"""What the source checks share (status_owner.py, packet_entry.py, rotor_count.py).

The C++ files of a tree a check covers, a source text with its comments and
literals blanked (line numbers kept), and the one main: --self-test, or scan
ROOT, print file:line of each finding, a summary, exit 1 if any.
"""
import os
import re
import sys

SOURCE_SUFFIXES = (".cc", ".h", ".cpp", ".hpp")
# Comments, then string and character literals (their text is not code).
BLANKED = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)


def blank(text):
    """Comments and literals replaced by spaces, newlines kept (line numbers stay)."""
    return BLANKED.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def line_of(code, offset):
    """1-based line of a character offset."""
    return code.count("\n", 0, offset) + 1


def covered_files(root, excluded_dirs, excluded_files=()):
    """Relative paths of the C++ files below root, outside excluded_dirs, build*/ and hidden top folders."""
    for folder, dirs, files in os.walk(root):
        rel_folder = os.path.relpath(folder, root)
        dirs[:] = sorted(d for d in dirs if d not in excluded_dirs and not d.startswith("build")
                         and not (rel_folder == "." and d.startswith(".")))
        for name in sorted(files):
            rel = os.path.normpath(os.path.join(rel_folder, name))
            if name.endswith(SOURCE_SUFFIXES) and rel not in excluded_files:
                yield rel


def run_check(findings, self_test, covered, what_to_do, all_clear):
    """The checks' main: findings(text) -> [(line, message)], covered(root) -> relative paths."""
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    failures = 0
    for rel in covered(root):
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for line, message in findings(f.read()):
                print("%s:%d: %s" % (rel, line, message))
                failures += 1
    if failures:
        print("%d finding(s): %s" % (failures, what_to_do))
        return 1
    print(all_clear)
    return 0
