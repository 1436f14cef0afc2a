#!/usr/bin/env python3
"""Checks the style guide's size limits over every folder of code (src/, include/, tools/, test/, bench/,
fuzz/, scripts/, examples/, python/; C++ and Python): no file over 600 lines, no production function over 60 lines, no test
function over 80 (test/ and fuzz/), and no class over 600 lines across its files (its body in the header
plus its member functions defined out of line; PENDING_CLASSES are reported, not counted).

    check_sizes.py [REPO] [--max-file 600] [--max-function 60] [--max-test-function 80] [--max-class 600]

A C++ function is counted from the first line of its signature to its closing brace. Functions are found by
their braces: a `{` whose enclosing braces are all namespaces, classes, structs, unions or enums (or
`extern "C"`) opens a function body unless it opens one of those itself or an initializer (`= {`). Lambdas
and local classes count toward the function that holds them. A Python function (a .py file, or a script
whose first line names python) is counted from its `def` to its last line, nested functions toward the one
that holds them. Prints each violation as FILE:LINE and exits 1 if there is any.
"""
import argparse
import ast
import collections
import pathlib
import re
import sys

SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b|extern\s+\"C\"")
CLASS = re.compile(r"\bclass\s+(\w+)\s*(?::[^{]*)?$")
MEMBER = re.compile(r"\b(\w+)::~?\w+\s*\(")
FOLDERS = ("src", "include", "tools", "test", "bench", "fuzz", "scripts", "examples", "python")
TEST_FOLDERS = ("test", "fuzz")
# Classes over the limit whose split is an open, named piece of work: reported, not counted. Remove an
# entry when its work lands (the check then holds the class to the limit).
PENDING_CLASSES = {}
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
                    yield "function", first, line, " ".join(head.split())[:80]
                elif kind == "scope" and CLASS.search(" ".join(head.split())):
                    yield "class", first, line, CLASS.search(" ".join(head.split())).group(1)
            statement_start = None
        elif c == ";":
            statement_start = None


def is_python(path):
    if path.suffix == ".py":
        return True
    if path.suffix or not path.is_file():
        return False
    with open(path, "rb") as f:
        first = f.readline()
    return first.startswith(b"#!") and b"python" in first


def python_functions(text):
    """Yields (first line, last line, name) of each outermost function in Python source."""
    tree = ast.parse(text)

    def walk(node):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                first = min([child.lineno] + [d.lineno for d in child.decorator_list])
                yield first, child.end_lineno, child.name
            elif isinstance(child, ast.ClassDef):
                yield from walk(child)

    yield from walk(tree)


def code_files(repo):
    for folder in FOLDERS:
        for p in sorted((repo / folder).rglob("*")):
            if "corpus" in p.parts or "golden" in p.parts:
                continue
            if p.suffix in SUFFIXES or is_python(p):
                yield p


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("repo", nargs="?", default=str(pathlib.Path(__file__).resolve().parent.parent))
    parser.add_argument("--max-file", type=int, default=600)
    parser.add_argument("--max-function", type=int, default=60)
    parser.add_argument("--max-test-function", type=int, default=80)
    parser.add_argument("--max-class", type=int, default=600)
    args = parser.parse_args(argv)
    repo = pathlib.Path(args.repo)
    problems = []
    classes = collections.defaultdict(int)  # lines of each class across its files
    class_site = {}
    files = list(code_files(repo))
    for path in files:
        text = path.read_text()
        name = path.relative_to(repo)
        limit = args.max_test_function if name.parts[0] in TEST_FOLDERS else args.max_function
        lines = text.count("\n") + (0 if text.endswith("\n") else 1)
        if lines > args.max_file:
            problems.append(f"{name}:1: {lines} lines (limit {args.max_file})")
        if path.suffix not in SUFFIXES:
            for first, last, head in python_functions(text):
                if last - first + 1 > limit:
                    problems.append(f"{name}:{first}: function of {last - first + 1} lines (limit {limit}): {head}")
            continue
        for kind, first, last, head in functions(strip(text)):
            length = last - first + 1
            if kind == "class":
                classes[head] += length
                class_site.setdefault(head, f"{name}:{first}")
                continue
            member = MEMBER.search(head)
            if member:
                classes[member.group(1)] += length
            if length > limit:
                problems.append(f"{name}:{first}: function of {length} lines (limit {limit}): {head}")
    for cls, length in sorted(classes.items()):
        if length > args.max_class and cls in class_site:
            message = f"{class_site[cls]}: class {cls} of {length} lines across its files (limit {args.max_class})"
            if cls in PENDING_CLASSES:
                print(f"{message}: pending, {PENDING_CLASSES[cls]}")
            else:
                problems.append(message)
    for problem in problems:
        print(problem)
    print(f"size limits: {len(files)} files checked, {len(problems)} over the limits")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
