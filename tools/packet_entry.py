#!/usr/bin/env python3
"""One way in per node (style rule 16): HandlePacket(channel, bytes, receive time).

A node is a class deriving from PacketHandler (sources/message_source.h).
A message source feeds it through HandlePacket(std::string_view channel,
const void* data, size_t size, int64_t receive_wall_utime); the node maps
the channel name to its typed channel in its route table
(sources/channel_routes.h) and dispatches privately. This check fails when
such a class

  - declares HandlePacket more than once (a typed second entry such as
    HandlePacket(InputChannel, ...), or an overload without the receive time),
  - or has another public member function that takes raw bytes
    (`const void*` or `const uint8_t*`): a second public way in that skips
    the route table.

Covered: every C++ header and source of the repository outside tests/,
fuzz/ (harnesses, not nodes), build*/ and hidden folders. A class body is
read by brace matching; comments and string literals are ignored.

Usage: tools/packet_entry.py [ROOT]   (default: this repository)
       tools/packet_entry.py --self-test
Exits 1 and lists file:line of each finding.
"""
import re
import sys

from source_scan import blank, covered_files, run_check

EXCLUDED_DIRS = {"tests", "fuzz", "corpus", ".git"}

NODE_CLASS = re.compile(r"\b(?:class|struct)\s+(\w+)\s*(?:final\s*)?:\s*public\s+(?:\w+::)*PacketHandler\b[^{;]*\{")
ACCESS = re.compile(r"\b(public|private|protected)\s*:(?!:)")
FUNCTION = re.compile(r"\b(\w+)\s*\(([^()]*(?:\([^()]*\)[^()]*)*)\)")
RAW_BYTES = re.compile(r"\bconst\s+(?:void|u?int8_t|char|unsigned\s+char)\s*\*")


def class_members(code, start):
    """(offset, access, text) of each top-level statement of the class body opening at code[start - 1] == '{'."""
    depth, access, statement_start, members = 1, "private", start, []
    i = start
    while i < len(code) and depth > 0:
        c = code[i]
        if c == "{":
            if depth == 1:
                members.append((statement_start, access, code[statement_start:i]))
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 1:
                statement_start = i + 1
        elif c == ";" and depth == 1:
            members.append((statement_start, access, code[statement_start:i]))
            statement_start = i + 1
        elif c == ":" and depth == 1:
            m = ACCESS.search(code, statement_start, i + 1)
            if m and m.end() == i + 1:
                access = m.group(1)
                statement_start = i + 1
        i += 1
    return members


def findings(text):
    """(line, message) of every second way in of every node class in text."""
    code = blank(text)
    found = []
    for node in NODE_CLASS.finditer(code):
        entries = []
        for offset, access, statement in class_members(code, node.end()):
            m = FUNCTION.search(statement)
            if not m:
                continue
            line = code.count("\n", 0, offset + m.start()) + 1
            name, params = m.group(1), m.group(2)
            if name == "HandlePacket":
                entries.append(line)
            elif access == "public" and RAW_BYTES.search(params):
                found.append((line, "%s: public %s(...) takes raw bytes beside HandlePacket" % (node.group(1), name)))
        if len(entries) != 1:
            where = entries[1] if len(entries) > 1 else code.count("\n", 0, node.start()) + 1
            found.append((where, "%s: %d HandlePacket declarations, one way in wanted" % (node.group(1), len(entries))))
    return sorted(found)


def self_test():
    one = """class A : public PacketHandler {
     public:
      void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t t) override;
      std::vector<std::string> InputChannels() const { return routes_.Names(); }
     private:
      bool Dispatch(Channel c, const void* data, size_t size);
    };"""
    typed_second = """class B : public PacketHandler {
     public:
      void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t t) override;
      bool HandlePacket(InputChannel channel, const void* data, size_t size, int64_t t = -1);
    };"""
    raw_public = """class C : public birotor::PacketHandler {
     public:
      void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t t) override {
        if (channel == "X") OnStrain(data, size);
      }
      void OnStrain(const void* data, size_t size);
    };"""
    commented = """class D : public PacketHandler {
     public:
      // bool HandlePacket(InputChannel channel, const void* data, size_t size);
      void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t t) override;
    };"""
    bad = []
    if findings(one) or findings(commented):
        bad.append("a node with one way in was flagged")
    if not findings(typed_second):
        bad.append("a typed second HandlePacket was not flagged")
    if not findings(raw_public):
        bad.append("a public member taking raw bytes was not flagged")
    for b in bad:
        print("self-test: " + b)
    return 1 if bad else 0


def main():
    return run_check(findings, self_test, lambda root: covered_files(root, EXCLUDED_DIRS),
                     "one public HandlePacket(channel, bytes, receive time) per node, over its route table",
                     "every PacketHandler has one way in")


if __name__ == "__main__":
    sys.exit(main())
