#!/usr/bin/env python3
"""Checks package.xml offline, as `rosdep check` would, and against what the code uses.

    check_package.py [REPO] [--package-xml PATH]

Declared resolves: every key of package.xml (depend, build_depend, build_export_depend, buildtool_depend,
exec_depend, test_depend) is catkin or a ROS package Debian installed (/usr/share/KEY/package.xml), or a
system dependency (SYSTEM below; a python3-* key is the Debian package of that name) whose Debian packages
are installed and listed in scripts/deps.txt (what the README's commands install). Used is declared: every
package the repository uses is declared with a kind that covers the use. Build uses (C++ includes of a ROS
package or of a library in HEADERS, CMakeLists.txt's find_package and catkin COMPONENTS, setup.py's imports)
need depend, build_depend, build_export_depend or buildtool_depend; run uses (Python imports, launch files'
pkg= and $(find), ROS command-line tools in the shell scripts and the Makefile, rosrun/roslaunch's package)
need depend or exec_depend; a use in a test file (TEST_FILES, CMake inside a testing block, rostest) may
also be a test_depend. bench/ is checked too: catkin builds bench/*.cpp whenever Google Benchmark is found.
Prints each problem, each file's first use of an undeclared package as FILE:LINE, and exits 1 if any.
"""
import argparse
import ast
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

TAGS = ["depend", "build_depend", "build_export_depend", "buildtool_depend", "exec_depend", "test_depend"]
COVERS = {"build": {"depend", "build_depend", "build_export_depend", "buildtool_depend"},
          "run": {"depend", "exec_depend"}, "test": set(TAGS)}
# rosdep key -> the Debian 12 packages it installs (all of them); python3-* keys map to themselves.
SYSTEM = {
    "eigen": ["libeigen3-dev"], "boost": ["libboost-dev"], "yaml-cpp": ["libyaml-cpp-dev"],
    "geographiclib": ["libgeographiclib-dev"],  # Debian 12 has no libgeographic-dev
    "gtest": ["libgtest-dev", "googletest"],  # catkin builds gtest from googletest's /usr/src; CTest: GTestConfig
    "benchmark": ["libbenchmark-dev"], "pybind11-dev": ["pybind11-dev"],
}
HEADERS = {"Eigen": "eigen", "boost": "boost", "yaml-cpp": "yaml-cpp", "GeographicLib": "geographiclib",
           "pybind11": "pybind11-dev", "gtest": "gtest", "benchmark": "benchmark", "ros": "roscpp"}
CMAKE = {"Eigen3": "eigen", "Boost": "boost", "yaml-cpp": "yaml-cpp", "Python3": "python3-dev",
         "pybind11": "pybind11-dev", "GTest": "gtest", "benchmark": "benchmark"}
MODULES = {"yaml": "python3-yaml", "matplotlib": "python3-matplotlib", "numpy": "python3-numpy",
           "scipy": "python3-scipy", "dask": "python3-distributed", "distributed": "python3-distributed",
           "pytest": "python3-pytest", "setuptools": "python3-setuptools",
           "catkin_pkg": "catkin"}  # setup.py is read only by catkin_python_setup(); catkin brings catkin_pkg
# Command-line tool -> (key, kind); rosrun, roslaunch and rostest also use the package named after them.
TOOLS = {"rostopic": ("rostopic", "run"), "rosrun": ("rosbash", "run"), "roslaunch": ("roslaunch", "run"),
         "rosbag": ("rosbag", "run"), "rosparam": ("rosparam", "run"), "rosnode": ("rosnode", "run"),
         "rosservice": ("rosservice", "run"), "rostest": ("rostest", "test"), "rospack": ("rospack", "run"),
         "rosmsg": ("rosmsg", "run"), "catkin_make": ("catkin", "build")}
# Files only the tests use: test/, the fuzz targets, examples/ (not installed; test/python/test_examples.py
# runs them) and make test's own scripts.
TEST_FILES = re.compile(r"^(test/|fuzz/|examples/|scripts/(check_|run_all_tests|test_summary|record_golden))")
INCLUDE = re.compile(r"^\s*#\s*include\s*<([\w.+-]+)/", re.M)
TOOL = re.compile(r"(?<![\w/.$-])(" + "|".join(TOOLS) + r")(?![\w.-])((?:\s+(?:-\S+|\"[^\"]*\"|\S*\$\S*))*\s+(\w+))?")


def ros_package(name):
    return name == "catkin" or pathlib.Path(f"/usr/share/{name}/package.xml").is_file()


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def resolve(keys, repo):
    """Problems with the declared keys: each must be a ROS package or map to installed, listed Debian packages."""
    deps_txt = repo / "scripts" / "deps.txt"
    listed = {line.split("#")[0].strip() for line in deps_txt.read_text().splitlines()} - {""}
    debs = {key: SYSTEM.get(key, [key] if key.startswith("python3-") else None) for key in keys if not ros_package(key)}
    names = sorted({deb for packages in debs.values() if packages for deb in packages})
    query = subprocess.run(["dpkg-query", "-W", "-f=${Package} ${Status}\n", *names], capture_output=True, text=True)
    installed = {line.split()[0] for line in query.stdout.splitlines() if line.endswith("install ok installed")}
    problems = []
    for key, packages in sorted(debs.items()):
        if packages is None:
            problems.append(f"package.xml: {key}: neither an installed ROS package (/usr/share/{key}/package.xml) "
                            "nor a system dependency that scripts/check_package.py maps (SYSTEM)")
        for deb in packages or []:
            if deb not in installed:
                problems.append(f"package.xml: {key}: its Debian package {deb} is not installed")
            if deb not in listed:
                problems.append(f"package.xml: {key}: its Debian package {deb} is not in scripts/deps.txt")
    return problems


def cmake_uses(text):
    """(line, key, kind) of CMakeLists.txt's find_package calls; inside an if() that tests TESTING or
    calls enable_testing() they are test uses."""
    blocks, test_lines = [], set()
    for number, line in enumerate(text.splitlines(), 1):
        if re.match(r"\s*if\s*\(", line):
            blocks.append("TESTING" in line)
        elif re.match(r"\s*endif\s*\(", line) and blocks:
            blocks.pop()
        elif re.match(r"\s*enable_testing\s*\(", line) and blocks:
            blocks[-1] = True
        if any(blocks):
            test_lines.add(number)
    for call in re.finditer(r"find_package\s*\(\s*([\w-]+)([^)]*)\)", text):
        name, args, start = call.group(1), call.group(2), line_of(text, call.start())
        kind = "test" if start in test_lines else "build"
        if name == "catkin" and "COMPONENTS" in args:
            after = call.start(2) + args.index("COMPONENTS") + len("COMPONENTS")
            for token in re.finditer(r"[\w-]+", text[after:call.end() - 1]):
                yield line_of(text, after + token.start()), token.group(), kind
        yield start, CMAKE.get(name, name), kind


def python_uses(text, own):
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            names = [node.module]
        else:
            continue
        for name in names:
            top = name.split(".")[0]
            if top not in sys.stdlib_module_names and top not in own:
                yield node.lineno, MODULES.get(top, top)


def shell_uses(text):
    for number, line in enumerate(text.splitlines(), 1):
        line = re.sub(r"(^|\s)#.*", "", line)  # comments
        for match in TOOL.finditer(line):
            key, kind = TOOLS[match.group(1)]
            yield number, key, kind
            if match.group(1) in ("rosrun", "roslaunch", "rostest") and match.group(3):
                yield number, match.group(3), kind


def uses(repo, name):
    """(file, line, key, kind) of every use of another package."""
    def files(folders, suffixes):
        return sorted(p for f in folders for p in (repo / f).rglob("*") if p.is_file() and p.suffix in suffixes)

    def found(path, items, kind=None):
        rel = str(path.relative_to(repo))
        test = bool(TEST_FILES.match(rel))
        for line, key, *use_kind in items:
            yield rel, line, key, "test" if test else (use_kind[0] if use_kind else kind)

    for path in files(["src", "include", "tools", "test", "bench", "fuzz"], {".h", ".hpp", ".cpp"}):
        text = path.read_text()
        includes = [(line_of(text, m.start()), m.group(1)) for m in INCLUDE.finditer(text)]
        yield from found(path, [(line, HEADERS.get(pkg, pkg)) for line, pkg in includes
                                if pkg in HEADERS or (pkg != name and ros_package(pkg))], "build")
    yield from found(repo / "CMakeLists.txt", cmake_uses((repo / "CMakeLists.txt").read_text()))
    python = files(["scripts", "python", "examples", "test", "tools", "bench"], {".py"})
    own = {name} | {p.stem for p in python}  # the package and the repository's own modules
    scripts = [p for p in (repo / "scripts").iterdir() if p.is_file() and not p.suffix]
    python += [p for p in scripts if "python" in p.read_text().partition("\n")[0]]
    for path in python:
        yield from found(path, python_uses(path.read_text(), own), "run")
    yield from found(repo / "setup.py", python_uses((repo / "setup.py").read_text(), own), "build")
    for path in files(["launch", "test"], {".launch", ".test", ".xml"}):
        text = path.read_text()
        refs = [(line_of(text, m.start()), m.group(1) or m.group(2))
                for m in re.finditer(r'\bpkg="([^"$]+)"|\$\(find ([\w-]+)\)', text)]
        tool = "rostest" if path.suffix == ".test" else "roslaunch"  # what runs the file
        yield from found(path, [(1, tool)] + [(line, pkg) for line, pkg in refs if pkg != name], "run")
    shell = [p for p in scripts + files(["scripts", ".ci"], {".sh"}) + files([".ci"], {""})
             if "sh" in p.read_text().partition("\n")[0]]
    for path in sorted(set(shell)) + [repo / "Makefile"]:
        yield from found(path, [(n, key, kind) for n, key, kind in shell_uses(path.read_text()) if key != name])


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("repo", nargs="?", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent)
    parser.add_argument("--package-xml", type=pathlib.Path, metavar="PATH",
                        help="check this package.xml instead of REPO's")
    args = parser.parse_args(argv)
    root = ET.parse(args.package_xml or args.repo / "package.xml").getroot()
    declared = {}  # key -> the tags that declare it
    for element in root:
        if element.tag in TAGS:
            declared.setdefault(element.text.strip(), set()).add(element.tag)
    problems = resolve(declared, args.repo)
    seen, used = set(), 0
    for rel, line, key, kind in uses(args.repo, root.findtext("name")):
        if (rel, key, kind) in seen:
            continue  # each file's first use of a package
        seen.add((rel, key, kind))
        if declared.get(key, set()) & COVERS[kind]:
            used += 1
            continue
        tags = ", ".join(sorted(declared.get(key, ())))
        why = f" as a {kind} use (only {tags})" if tags else ""
        problems.append(f"{rel}:{line}: uses {key}, not declared in package.xml{why}")
    for problem in problems:
        print(problem)
    resolving = len(declared) - len({p.split(":")[1].strip() for p in problems if p.startswith("package.xml:")})
    print(f"package: {resolving} keys resolve, {used} uses declared")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
