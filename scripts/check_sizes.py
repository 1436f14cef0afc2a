#!/usr/bin/env python3
"""Checks the style guide's size limits: no file over 600 lines and no function over 60 lines in src/,
include/ and tools/ (tests excepted).

    check_sizes.py [REPO] [--max-file 600] [--max-function 60]

A function is counted from the first line of its signature to its closing brace. Functions are found by
their braces: a `{` whose enclosing braces are all namespaces, classes, structs, unions or enums (or
`extern "C"`) opens a function body unless it opens one of those itself or an initializer (`= {`). Lambdas
and local classes count toward the function that holds them. Prints each violation as FILE:LINE and exits
1 if there is any.
"""
import argparse
import pathlib
import re
import sys

SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b|extern\s+\"C\"")
FOLDERS = ("src", "include", "tools")
SUFFIXES = (".h", ".hpp", ".cpp", ".cc")


def strip(text):
    """Blanks out comments, string and character literals, keeping line breaks."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """Yields (first line, last line, signature) of each function body in the stripped source."""
    text = re.sub(r"(?m)^[ \t]*#.*$", "", text)  # preprocessor lines are no part of a signature
    stack = []  # (kind, first line, head) of the open braces; kind "scope", "function" or "other"
    line = 1
    statement_start = None  # (line, offset) where the current declaration began
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
            continue
        if statement_start is None and not c.isspace():
            statement_start = (line, i)
        if c == "{":
            head = text[statement_start[1]:i] if statement_start else ""
            at_scope_level = all(entry[0] == "scope" for entry in stack)
            if SCOPE.search(head) and "(" not in head.split("{")[-1].split("=")[0] or head.rstrip().endswith("="):
                kind = "scope" if SCOPE.search(head) and not head.rstrip().endswith("=") else "other"
            elif at_scope_level and "(" in head:
                kind = "function"
            else:
                kind = "other"
            stack.append((kind, statement_start[0] if statement_start else line, head))
            statement_start = None
        elif c == "}":
            if stack:
                kind, first, head = stack.pop()
                if kind == "function":
                    yield first, line, " ".join(head.split())[:80]
            statement_start = None
        elif c == ";":
            statement_start = None


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("repo", nargs="?", default=str(pathlib.Path(__file__).resolve().parent.parent))
    parser.add_argument("--max-file", type=int, default=600)
    parser.add_argument("--max-function", type=int, default=60)
    args = parser.parse_args(argv)
    repo = pathlib.Path(args.repo)
    problems = []
    files = sorted(p for folder in FOLDERS for p in (repo / folder).rglob("*") if p.suffix in SUFFIXES)
    for path in files:
        text = path.read_text()
        name = path.relative_to(repo)
        lines = text.count("\n") + (0 if text.endswith("\n") else 1)
        if lines > args.max_file:
            problems.append(f"{name}:1: {lines} lines (limit {args.max_file})")
        for first, last, head in functions(strip(text)):
            length = last - first + 1
            if length > args.max_function:
                problems.append(f"{name}:{first}: function of {length} lines (limit {args.max_function}): {head}")
    for problem in problems:
        print(problem)
    print(f"size limits: {len(files)} files checked, {len(problems)} over the limits")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
