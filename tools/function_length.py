#!/usr/bin/env python3
"""Lines per C++ function and per file, for issue 22's structure targets.

Counts each function definition from the line its signature starts on to the
line of its closing brace (both included), the way a reader sees it; lambdas
and local classes count towards the function they are written in. A small
brace scanner, no compiler: comments, string and character literals (raw
strings too) and preprocessor lines are blanked first; then at namespace and
class level every `{` is a scope (namespace, class, struct, enum, union,
extern "C"), a brace initialiser (`x{1}`, `= {...}`), or a function body (the
signature ends with `)`, a qualifier, a trailing return type or a
constructor's initialiser list).

Usage: tools/function_length.py [--top N] [--max-function L] [--max-file L]
                                 [--exclude DIR ...] [ROOT]
Prints the N longest functions and files; exits 1 if a function is longer than
--max-function or a file longer than --max-file lines (0: no limit).
Default: the repository this script is in, without tests/, build*/ and fuzz
corpora.
"""
import argparse
import os
import re
import sys

SOURCE_SUFFIXES = (".cc", ".h", ".cpp", ".hpp")
SCOPE_KEYWORDS = {"namespace", "class", "struct", "union", "enum", "extern"}
CONTROL_KEYWORDS = {"if", "for", "while", "switch", "catch", "do", "else", "try", "return"}
QUALIFIERS = {"const", "noexcept", "override", "final", "mutable", "volatile"}


def blank_non_code(text):
    """Comments, literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            # A preprocessor line, with its backslash continuations.
            j = i
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    out.append("\n")
                    continue
                j += 1
            i = j
            continue
        if c == "\n":
            out.append(c)
            line_start = True
            i += 1
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i + m.end())
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():
                out.append(" ")  # a digit separator (1'000)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def classify(prefix):
    """'function', 'scope' or 'init' for the `{` that follows prefix."""
    p = re.sub(r"\b(public|private|protected)\s*:(?!:)", " ", prefix).strip()
    words = re.findall(r"[A-Za-z_]\w*", p)
    # A parenthesised part at top level, and what follows it.
    depth, last_close = 0, -1
    for k, ch in enumerate(p):
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
            if depth == 0:
                last_close = k
    first = words[0] if words else ""
    if first in CONTROL_KEYWORDS:
        return "init"  # not expected at this level; keep scanning as a block
    if last_close < 0:
        if any(w in SCOPE_KEYWORDS for w in words) or p.endswith('""') or p == "":
            return "scope"
        return "init"
    if any(w in ("class", "struct", "union", "enum") for w in re.findall(r"[A-Za-z_]\w*", p[:p.find("(")])):
        if "=" not in p[:p.find("(")]:
            return "scope"
    tail = p[last_close + 1:].strip()
    if tail == "" or all(w in QUALIFIERS for w in re.findall(r"[A-Za-z_]\w*", tail)) and not re.search(r"[=,.]", tail):
        return "function"
    if tail.startswith("->"):
        return "function"
    if re.match(r"^(const\s*|noexcept\s*|&+\s*)*:", tail) or re.search(r"\)\s*:[^:]", p):
        # A constructor's initialiser list: `{` ending it is the body unless it
        # is a member's brace initialiser (a name right before it).
        return "init" if re.search(r"[\w>]\s*$", p) and not p.endswith(")") else "function"
    if p.endswith("=") or p.endswith(","):
        return "init"
    return "init"


def functions_in(text):
    """(start_line, end_line, name) of every outermost function definition."""
    code = blank_non_code(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, ch in enumerate(code):
        line_of[k] = line
        if ch == "\n":
            line += 1
    line_of[len(code)] = line
    results = []
    prefix_start = 0  # where the current namespace/class-level statement starts
    i, n = 0, len(code)
    while i < n:
        ch = code[i]
        if ch in ";}":
            prefix_start = i + 1
            i += 1
            continue
        if ch != "{":
            i += 1
            continue
        prefix = code[prefix_start:i]
        kind = classify(prefix)
        if kind == "scope":
            prefix_start = i + 1
            i += 1
            continue
        # Skip to the matching brace.
        depth, j = 0, i
        while j < n:
            if code[j] == "{":
                depth += 1
            elif code[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        if kind == "function":
            stripped = re.sub(r"\b(public|private|protected)\s*:(?!:)", lambda m: " " * len(m.group(0)), prefix)
            offset = len(stripped) - len(stripped.lstrip())
            start = line_of[prefix_start + offset]
            names = re.findall(r"([~\w:]+|operator\s*\S+?)\s*\(", stripped)
            results.append((start, line_of[min(j, n)], names[0] if names else "?"))
            prefix_start = j + 1
        i = j + 1
    return results


def main():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", default=here)
    parser.add_argument("--top", type=int, default=10)
    parser.add_argument("--max-function", type=int, default=0)
    parser.add_argument("--max-file", type=int, default=0)
    parser.add_argument("--exclude", action="append", default=None,
                        help="top-level folders left out (default: tests, build*, .git, fuzz/corpus)")
    args = parser.parse_args()
    excludes = args.exclude if args.exclude is not None else ["tests"]
    funcs, files = [], []
    for dirpath, dirnames, filenames in os.walk(args.root):
        rel = os.path.relpath(dirpath, args.root)
        top = rel.split(os.sep)[0]
        if rel != "." and (top in excludes or top.startswith("build") or top.startswith(".") or "corpus" in rel):
            dirnames[:] = []
            continue
        for name in sorted(filenames):
            if not name.endswith(SOURCE_SUFFIXES):
                continue
            path = os.path.join(dirpath, name)
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            relpath = os.path.relpath(path, args.root)
            files.append((text.count("\n"), relpath))
            for start, end, fname in functions_in(text):
                funcs.append((end - start + 1, relpath, start, fname))
    funcs.sort(key=lambda f: (-f[0], f[1], f[2]))
    files.sort(key=lambda f: (-f[0], f[1]))
    print(f"{len(funcs)} functions in {len(files)} files (excluded: {', '.join(excludes)})")
    print(f"longest functions:")
    for length, path, start, fname in funcs[:args.top]:
        print(f"  {length:5d}  {path}:{start}  {fname}")
    print(f"longest files:")
    for length, path in files[:args.top]:
        print(f"  {length:5d}  {path}")
    failed = False
    if args.max_function > 0:
        over = [f for f in funcs if f[0] > args.max_function]
        for length, path, start, fname in over:
            print(f"function over {args.max_function} lines: {path}:{start} {fname} ({length})", file=sys.stderr)
        failed |= bool(over)
    if args.max_file > 0:
        over = [f for f in files if f[0] > args.max_file]
        for length, path in over:
            print(f"file over {args.max_file} lines: {path} ({length})", file=sys.stderr)
        failed |= bool(over)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
