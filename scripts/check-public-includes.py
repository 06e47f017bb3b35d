#!/usr/bin/env python3
"""Checks that the apps, their tests and the public headers use only the engine's public API.

  scripts/check-public-includes.py [ROOT]   check ROOT (default: the repository holding this script)
  scripts/check-public-includes.py --self-test

The public API is engine/include/weft/ (docs/layout.md); engine/weft/ holds the engine's private
headers. Checked sources:
  - app/**, tests/app/**, tests/editor/**, tests/support/** (and python/**): every `#include <weft/...>` names a
    public header (engine/include/) or the task library's (bench/); no quoted include reaches
    into engine/; the editor does not include the `weft` tool's own files (app/weft/).
  - engine/include/** and bench/**/*.h (headers the apps include): every `#include <weft/...>`
    names a public header (and the engine's never the task library's).
Each violation is printed as `<file>:<line>: <include>: <why>`. Exit status: 0 when there are
none, 1 when there are some, 2 on bad usage. Standard library only.
"""

import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
APP_SOURCES = ["app", "tests/app", "tests/editor", "tests/support", "python"]
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc")


def sources(root, folder, headers_only=False):
    top = os.path.join(root, folder)
    for path, subfolders, files in os.walk(top):
        subfolders.sort()
        for name in sorted(files):
            if name.endswith((".h", ".hpp")) or (not headers_only and name.endswith(SOURCE_SUFFIXES)):
                yield os.path.join(path, name)


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as text:
        for number, line in enumerate(text, 1):
            match = INCLUDE.match(line)
            if match:
                yield number, match.group(1), match.group(2)


def weft_header_problem(root, name, allow_bench):
    """Why `#include <name>` (name starting weft/) is not the public API, or None."""
    if os.path.isfile(os.path.join(root, "engine", "include", name)):
        return None
    if allow_bench and os.path.isfile(os.path.join(root, "bench", name)):
        return None
    if os.path.isfile(os.path.join(root, "engine", name)):
        return "private engine header (engine/%s); use the public API in engine/include/" % name
    if not allow_bench and os.path.isfile(os.path.join(root, "bench", name)):
        return "the engine's public headers do not include the task library"
    return "no such public header"


def check(root):
    problems = []
    engine = os.path.realpath(os.path.join(root, "engine"))
    cli = os.path.realpath(os.path.join(root, "app", "weft"))
    editor = os.path.realpath(os.path.join(root, "app", "editor"))

    def report(path, number, spelled, why):
        problems.append("%s:%d: %s: %s" % (os.path.relpath(path, root), number, spelled, why))

    for folder in APP_SOURCES:
        for path in sources(root, folder):
            here = os.path.realpath(os.path.dirname(path))
            for number, kind, name in includes(path):
                spelled = ("<%s>" if kind == "<" else '"%s"') % name
                if kind == "<" and name.startswith("weft/"):
                    why = weft_header_problem(root, name, allow_bench=True)
                    if why:
                        report(path, number, spelled, why)
                elif kind == '"':
                    target = os.path.realpath(os.path.join(here, name))
                    if target.startswith(engine + os.sep):
                        report(path, number, spelled, "reaches into engine/; include the public "
                               "header as <weft/...>")
                    elif here.startswith(editor) and target.startswith(cli + os.sep):
                        report(path, number, spelled, "the editor includes the weft tool's own "
                               "files (app/weft/)")
    for folder, allow_bench in (("engine/include", False), ("bench", True)):
        for path in sources(root, folder, headers_only=True):
            for number, kind, name in includes(path):
                if kind == "<" and name.startswith("weft/"):
                    why = weft_header_problem(root, name, allow_bench)
                    if why:
                        report(path, number, "<%s>" % name, why)
    return problems


def write(root, relative, text):
    path = os.path.join(root, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as out:
        out.write(text)


def self_test():
    """The check passes a tree that keeps to the API and finds each kind of violation."""
    with tempfile.TemporaryDirectory() as root:
        write(root, "engine/include/weft/physics/Simulator.h", "#include <weft/core/Types.h>\n")
        write(root, "engine/include/weft/core/Types.h", "")
        write(root, "engine/weft/physics/StepSolver.h", "")
        write(root, "bench/weft/bench/ForwardBench.h", "#include <weft/physics/Simulator.h>\n")
        write(root, "app/weft/Command.h", "")
        write(root, "app/weft/main.cpp",
              '#include "Command.h"\n#include <weft/physics/Simulator.h>\n'
              "#include <weft/bench/ForwardBench.h>\n#include <vector>\n")
        if check(root):
            print("self-test: a tree using only the public API was reported: %s" % check(root))
            return 1
        write(root, "app/editor/Panel.cpp",
              '#include <weft/physics/StepSolver.h>\n#include "../weft/Command.h"\n'
              '#include "../../engine/weft/physics/StepSolver.h"\n')
        write(root, "tests/app/CliTest.cpp", "#include <weft/physics/Missing.h>\n")
        write(root, "engine/include/weft/physics/Leaky.h",
              "#include <weft/physics/StepSolver.h>\n#include <weft/bench/ForwardBench.h>\n")
        expected = [
            "app/editor/Panel.cpp:1: <weft/physics/StepSolver.h>: private engine header",
            'app/editor/Panel.cpp:2: "../weft/Command.h": the editor includes',
            'app/editor/Panel.cpp:3: "../../engine/weft/physics/StepSolver.h": reaches into',
            "tests/app/CliTest.cpp:1: <weft/physics/Missing.h>: no such public header",
            "engine/include/weft/physics/Leaky.h:1: <weft/physics/StepSolver.h>: private",
            "engine/include/weft/physics/Leaky.h:2: <weft/bench/ForwardBench.h>: the engine's",
        ]
        found = check(root)
        missing = [e for e in expected if not any(p.startswith(e) for p in found)]
        if missing or len(found) != len(expected):
            print("self-test: expected %d problems, found:\n  %s\nmissing:\n  %s"
                  % (len(expected), "\n  ".join(found), "\n  ".join(missing)))
            return 1
    print("self-test: the include check finds private headers, engine/ paths, the editor "
          "reaching into app/weft and leaky public headers")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) > 2 or (len(argv) == 2 and argv[1].startswith("-")):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    root = argv[1] if len(argv) == 2 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print("%d include(s) outside the public API" % len(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
