#!/usr/bin/env python3
"""The birotor's rotor count has a name: kBirotorRotors (samples/rotor_count.h).

A per-rotor (per-arm, per-gauge) array or loop of the birotor is sized by
kBirotorRotors, never by a literal 2, so that a reader sees which twos are
rotors and a vehicle with another count (a VehicleDescription on the N-arm
types) finds every place that assumes two. This check fails when a C++ source
declares an array of two whose name says it holds one value per rotor, arm or
gauge, or loops `for (int rotor|arm = 0; ... < 2; ...)`:

  double force_n[2]          double (&omega_cmd_rad_s)[2]
  for (int arm = 0; arm < 2; ++arm)

Names that hold a per-rotor value: they start with (or are) one of
PER_ROTOR_PREFIXES below (force, omega, deflection, thrust_scale, gauge,
efficiency, ...). An array of two of anything else (x and z, a 2-d
innovation's components, nominal and force feedback) keeps its literal 2.

Covered: every C++ file of the repository except lcmtypes/ (the wire types'
fixed arrays are the contract, ../shared/spec/interface.md), tests/ and fuzz
corpora, build*/. Not covered: a loop over an index named i (review catches
those; the sweep that introduced the name converted them file by file).

Usage: tools/rotor_count.py [ROOT]   (default: this repository)
       tools/rotor_count.py --self-test
Exits 1 and lists file:line of each literal it finds.
"""
import re
import sys

from source_scan import blank, covered_files, line_of, run_check

EXCLUDED_DIRS = {"lcmtypes", "tests", "corpus", ".git"}
PER_ROTOR_PREFIXES = ("deflection", "omega", "force", "thrust_scale", "gauge", "rotor", "arm", "efficiency",
                      "max_force", "mu_", "strain_scale", "offset_rad", "command_rad_s", "weak")
ARRAY_OF_TWO = re.compile(r"\b([A-Za-z_]\w*)\)?\[2\]")
LOOP_OF_TWO = re.compile(r"for\s*\(\s*int\s+(rotor|arm)\s*=\s*0\s*;\s*\1\s*<\s*2\s*;")


def is_per_rotor(name):
    bare = name.lstrip("&").rstrip("_")
    if bare.startswith("k"):  # kOmegaIndex, kRotorColor: drop the constant's k
        bare = re.sub(r"(?<!^)([A-Z])", r"_\1", bare[1:]).lower()
    return bare.startswith(PER_ROTOR_PREFIXES)


def findings(text):
    """(line, message) of every per-rotor literal two in one source text."""
    code = blank(text)
    out = []
    for match in ARRAY_OF_TWO.finditer(code):
        if is_per_rotor(match.group(1)):
            out.append((line_of(code, match.start()), "per-rotor literal 2: " + match.group(0)))
    for match in LOOP_OF_TWO.finditer(code):
        out.append((line_of(code, match.start()), "per-rotor literal 2: " + match.group(0)))
    return sorted(out)


def self_test():
    flagged = [
        "double force_n[2] = {0, 0};",
        "void F(const double (&omega_cmd_rad_s)[2]);",
        "constexpr EkfIndex kOmegaIndex[2] = {kOmega1, kOmega2};",
        "for (int arm = 0; arm < 2; ++arm) {}",
        "double efficiency_[2];",
    ]
    passed = [
        "double force_n[kBirotorRotors] = {0, 0};",
        "double start_position_m[2] = {0.0, 0.0};  // x, z",
        "double bias[2];  // innovation components",
        "// double force_n[2] in a comment",
        'const char* text = "force_n[2]";',
        "for (int axis = 0; axis < 2; ++axis) {}",
        "x = force_n[1];",
    ]
    bad = [s for s in flagged if not findings(s)] + [s for s in passed if findings(s)]
    for s in bad:
        print("self-test: wrong verdict on:", s)
    return 1 if bad else 0


def main():
    return run_check(findings, self_test, lambda root: covered_files(root, EXCLUDED_DIRS),
                     "size them by kBirotorRotors (samples/rotor_count.h)",
                     "rotor count: every per-rotor array and rotor/arm loop is sized by kBirotorRotors")


if __name__ == "__main__":
    sys.exit(main())
