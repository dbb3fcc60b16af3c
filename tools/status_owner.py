#!/usr/bin/env python3
"""One writer of FORCE's status bits: estimator/force_status.{h,cc}.

The status of a force estimate (force_estimate_t / ForceEstimate, and the
ESTIMATOR_STATUS status, which repeats the newest FORCE's) is composed in one
place, ComposeForceStatus, from the facts the parts return (the method, the
pipeline, the model-consistency monitor, the service). This check fails when
a C++ source outside the composer's files ORs or ANDs bits into a `status`:

  status |= ...        status &= ...
  status = <expression with |, &, ~ or a kStatus* / STATUS_* constant>

(`x.status`, `x->status` and a local `status` alike; comments and string
literals are ignored; a statement may span lines). A plain copy
(`message->status = health.last_status`, `m.status = e.status`) and the
composer's result (`status = ComposeForceStatus(facts)`) pass.

Covered: every C++ file of the repository except
  - estimator/force_status.h and .cc (the composer),
  - controller/: MOTOR_COMMAND's own status (kCommand* bits, composed in
    vehicle_controller.cc) is not FORCE's,
  - transport/counted_messages.cc: it translates the same bits between the
    birotor and the N-arm wire layouts (rotor bits 16/32 <-> rotor_fault_bits),
    it composes nothing,
  - tests/ (fixtures set a status as their input), build*/ and fuzz corpora.
Not covered: bits built in a variable of another name and then assigned
(`int32_t bits = kStatusValid; e.status = bits;`); review catches those.

Usage: tools/status_owner.py [ROOT]   (default: this repository)
       tools/status_owner.py --self-test
Exits 1 and lists file:line of each write it finds.
"""
import os
import re
import sys

from source_scan import blank, covered_files, line_of, run_check

COMPOSER_FILES = {os.path.join("estimator", "force_status.h"), os.path.join("estimator", "force_status.cc"),
                  os.path.join("transport", "counted_messages.cc")}  # the wire translation (docstring)
EXCLUDED_DIRS = {"controller", "tests", "corpus", ".git"}

COMPOUND = re.compile(r"\bstatus\s*(\|=|&=)")
ASSIGN = re.compile(r"\bstatus\s*=(?!=)([^;{}]*)")
COMPOSED_RHS = re.compile(r"[|&~]|\bkStatus\w*|\bSTATUS_\w+")
def status_writes(text):
    """(line, statement) of every composed write to a `status` in text."""
    code = blank(text)
    found = []
    for m in COMPOUND.finditer(code):
        found.append((line_of(code, m.start()), "status bits set outside estimator/force_status: " + m.group(0)))
    for m in ASSIGN.finditer(code):
        if COMPOSED_RHS.search(m.group(1)):
            found.append((line_of(code, m.start()), "status bits set outside estimator/force_status: " + " ".join(m.group(0).split())))
    return sorted(found)


def self_test():
    flagged = [
        "estimate->status |= kStatusNoMotorInput;",
        "e.status &= ~kStatusValid;",
        "m.status = (m.status | kStatusInputConflict) & ~kStatusValid;",
        "status = *converged ? kStatusValid : kStatusConverging;",
        "estimate->status =\n    status | kStatusValid;",
        "message->status = force_estimate_t::STATUS_VALID;",
    ]
    passed = [
        "message->status = health.last_status;",
        "force_message_.status = ComposeForceStatus(facts);",
        "if (e.status == kStatusValid) return;",
        "// estimate->status |= kStatusValid;",
        'log("status |= x");',
        "const int32_t status = ComposeForceStatus(f);",
    ]
    bad = [s for s in flagged if not status_writes(s)] + [s for s in passed if status_writes(s)]
    for s in bad:
        print("self-test: wrongly judged: %r" % s)
    return 1 if bad else 0


def main():
    return run_check(status_writes, self_test, lambda root: covered_files(root, EXCLUDED_DIRS, COMPOSER_FILES),
                     "fill the part's facts (estimator/force_status.h) and let ComposeForceStatus decide",
                     "FORCE status: composed in estimator/force_status.cc only")


if __name__ == "__main__":
    sys.exit(main())
