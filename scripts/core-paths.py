#!/usr/bin/env python3
"""No crate outside footprint-core names a core module but its public ones (issue 53, item 2).

The core's public API is two modules: `prelude` (the door, the second paper's tables, clamp
and tiler included) and `extend` (the samplers, and what the walk hands a sampler, a cost or a
shader), plus `embedded` behind its feature and the crate root's `Rgb`, `Error` and `Mode`. Every other module is `pub(crate)`, so the compiler already refuses a path
into it; this check also catches a module made public again and then named from outside.

    scripts/core-paths.py              # every .rs file outside core/src; exit 1 on a stray path
    scripts/core-paths.py --self-test  # a planted stray path must be found
"""

import os
import re
import sys
import tempfile

ALLOWED = {"prelude", "extend", "embedded", "Rgb", "Error", "Mode"}
ROOTS = ["host", "scenes", "maps", "web", "firmware", "tests", "fuzz", "core/examples", "core/benches"]
PATH = re.compile(r"\bfootprint_core::(\w+)")
COMMENT = re.compile(r"//[^\n]*")
STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')


def stray(workspace):
    """[(file, line, path)] for every code path into a core module that is not public."""
    found = []
    for root in ROOTS:
        for d, dirs, files in os.walk(os.path.join(workspace, root)):
            dirs[:] = [x for x in dirs if x != "target"]
            for f in files:
                if not f.endswith(".rs"):
                    continue
                path = os.path.join(d, f)
                with open(path, encoding="utf-8") as fh:
                    for n, line in enumerate(fh, 1):
                        code = COMMENT.sub("", STRING.sub('""', line))
                        for m in PATH.finditer(code):
                            if m.group(1) not in ALLOWED:
                                found.append((os.path.relpath(path, workspace), n, m.group(0)))
    return found


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "host"))
        with open(os.path.join(tmp, "host", "a.rs"), "w") as fh:
            fh.write("use footprint_core::prelude::Frame;\n"
                     "// footprint_core::terrain::camera in a comment\n"
                     "let s = \"footprint_core::num\";\n"
                     "use footprint_core::terrain::camera::Camera;\n")
        found = stray(tmp)
        assert found == [("host/a.rs", 4, "footprint_core::terrain")], found
    print("core-paths self-test: the planted path found, comments and strings left alone")


def main(argv):
    if argv[1:] == ["--self-test"]:
        self_test()
        return 0
    workspace = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    found = stray(workspace)
    for path, n, p in found:
        print(f"{path}:{n}: {p} is not a public module of footprint-core "
              f"(use footprint_core::prelude or footprint_core::extend)", file=sys.stderr)
    if found:
        return 1
    print(f"core paths: every crate outside the core names only {', '.join(sorted(ALLOWED))}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
