#!/usr/bin/env python3
"""Import circles between the modules of each crate of the workspace (issue 53, item 3).

A module is a source file (`src/a.rs` or `src/a/mod.rs` is `a`, `src/a/b.rs` is `a::b`). Module
A imports B when A's code outside its unit tests names a path into B: a `use` line (brace groups
expanded) or a path written in the code (`crate::b::f()`, `super::b::T`). A path that ends in a
parent module's re-export (`pub use child::T` in `a/mod.rs`) is followed to the child that
defines it. A module naming its own ancestor or descendant is not an import (the parent
declares the child; the child reads what the parent re-exports, followed as above). Comments,
doc comments and string literals are not code.

Prints each circle (a strongly connected component of more than one module) with one import
that closes it, and exits 1 when there is any; exits 0 and prints the module and import counts
otherwise.

    scripts/import-circles.py            # every crate of the workspace and the firmware
    scripts/import-circles.py DIR...     # the crates (folders with src/) named
    scripts/import-circles.py --self-test
"""

import os
import re
import sys
import tempfile

# fuzz/ has no modules: each target is one file.
CRATES = ["core", "scenes", "maps", "host", "web", "tests", "firmware"]
ROOTS = ["lib.rs", "main.rs"]


def strip_comments_and_strings(text):
    """The code of `text` with comments, string and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    if text[i] == "\n":
                        out.append("\n")
                    i += 1
        elif c == "r" and re.match(r'r#*"', text[i:]) and not (i and (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'r(#*)"', text[i:])
            end = text.find('"' + m.group(1), i + len(m.group(0)))
            end = n if end < 0 else end + 1 + len(m.group(1))
            out.append("\n" * text.count("\n", i, end) + '""')
            i = end
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append("\n" * text.count("\n", i, j) + '""')
            i = j + 1
        elif c == "'" and re.match(r"'(\\.|[^\\'])'", text[i:]):
            i += len(re.match(r"'(\\.[^']*|[^\\'])'", text[i:]).group(0))
            out.append("' '")
        else:
            out.append(c)
            i += 1
    return "".join(out)


def strip_test_modules(code):
    """`code` without the items under `#[cfg(test)]` (a `mod … { … }` or `mod …;`)."""
    out, i = [], 0
    for m in re.finditer(r"#\[cfg\(test\)\]", code):
        if m.start() < i:
            continue
        rest = code[m.end():]
        item = re.match(r"\s*(pub(\([^)]*\))?\s+)?mod\s+\w+\s*([;{])", rest)
        if not item:
            continue
        out.append(code[i:m.start()])
        j = m.end() + item.end()
        if item.group(3) == "{":
            depth = 1
            while j < len(code) and depth:
                depth += {"{": 1, "}": -1}.get(code[j], 0)
                j += 1
        i = j
    out.append(code[i:])
    return "".join(out)


def expand_use(tree):
    """The paths of a use tree: `a::{b, c::{d as e, self}}` -> a::b, a::c::d, a::c."""
    tree = re.sub(r"\s+", "", tree)
    depth, start = 0, None
    for k, ch in enumerate(tree):
        if ch == "{":
            if depth == 0:
                start = k
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                prefix, inner, suffix = tree[:start], tree[start + 1:k], tree[k + 1:]
                parts, d, s = [], 0, 0
                for q, c in enumerate(inner):
                    d += {"{": 1, "}": -1}.get(c, 0)
                    if c == "," and d == 0:
                        parts.append(inner[s:q])
                        s = q + 1
                parts.append(inner[s:])
                paths = []
                for p in parts:
                    if not p:
                        continue
                    for sub in expand_use(p + suffix):
                        paths.append(prefix + sub)
                return paths
    return [re.sub(r"::self$", "", tree)]


USE = re.compile(r"\buse\s+([^;]+);")
RENAME = re.compile(r"\s+as\s+\w+")
# `$crate::…` in a macro body is resolved where the macro expands, not imported here.
PATH = re.compile(r"(?<![\w:$])((?:crate|super|self)(?:::[A-Za-z_]\w*)+)")


class Crate:
    def __init__(self, folder):
        self.folder = folder
        self.modules = {}  # module path (tuple) -> file
        src = os.path.join(folder, "src")
        root = next((r for r in ROOTS if os.path.exists(os.path.join(src, r))), None)
        self.root = root
        for dirpath, _, files in os.walk(src):
            for f in files:
                if not f.endswith(".rs"):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, f), src)
                parts = rel[:-3].split(os.sep)
                if parts == [root[:-3]]:
                    parts = []
                elif parts[-1] == "mod":
                    parts = parts[:-1]
                elif len(parts) == 1 and parts[0] in ("lib", "main", "build"):
                    continue  # a second crate root (host's main.rs): not a module of this tree
                self.modules[tuple(parts)] = os.path.join(dirpath, f)
        self.code = {}
        self.reexports = {}  # module -> {name: absolute path}
        for mod, path in self.modules.items():
            with open(path, encoding="utf-8") as fh:
                self.code[mod] = strip_test_modules(strip_comments_and_strings(fh.read()))
        for mod, code in self.code.items():
            names = {}
            for m in re.finditer(r"\bpub(\([^)]*\))?\s+use\s+([^;]+);", code):
                for p in expand_use(RENAME.sub("", m.group(2))):
                    absolute = self.absolute(mod, p.split("::"))
                    if absolute:
                        names[absolute[-1]] = absolute
            self.reexports[mod] = names

    def absolute(self, mod, segs):
        """`segs` (a path written in `mod`) as a path from the crate root, or None (another crate)."""
        if not segs:
            return None
        if segs[0] == "crate":
            return segs[1:]
        if segs[0] in ("self", "super"):
            base = list(mod)
            while segs and segs[0] in ("self", "super"):
                if segs[0] == "super":
                    if not base:
                        return None
                    base.pop()
                segs = segs[1:]
            return base + segs
        if (tuple(mod) + (segs[0],)) in self.modules:  # a child module named plainly
            return list(mod) + segs
        if self.root == "lib.rs" and not mod and (segs[0],) in self.modules:
            return segs
        return None

    def owner(self, path, seen=0):
        """The module (file) that defines what `path` (from the root) names."""
        best = ()
        for k in range(len(path), -1, -1):
            if tuple(path[:k]) in self.modules:
                best = tuple(path[:k])
                break
        rest = path[len(best):]
        if rest and seen < 8:
            target = self.reexports.get(best, {}).get(rest[0])
            if target and tuple(target[:len(best)]) == best and len(target) > len(best):
                return self.owner(list(target) + rest[1:], seen + 1)
        return best

    def imports(self):
        """{module: {imported module: an example path}}."""
        edges = {}
        for mod, code in self.code.items():
            out = edges.setdefault(mod, {})
            paths = []
            for m in USE.finditer(code):
                paths += expand_use(RENAME.sub("", m.group(1)))
            paths += [m.group(1) for m in PATH.finditer(USE.sub("", code))]
            for p in paths:
                absolute = self.absolute(mod, p.split("::"))
                if absolute is None:
                    continue
                target = self.owner(absolute)
                related = target[:len(mod)] == mod or mod[:len(target)] == target
                if not related:
                    out.setdefault(target, p)
        return edges


def circles(edges):
    """The strongly connected components of more than one node (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []
    counter = [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def name(mod):
    return "::".join(mod) or "crate"


def check(folders):
    total_modules = total_imports = 0
    bad = []
    for folder in folders:
        crate = Crate(folder)
        edges = crate.imports()
        total_modules += len(edges)
        total_imports += sum(len(v) for v in edges.values())
        for comp in circles(edges):
            inside = set(comp)
            lines = [
                f"  {name(a)} -> {name(b)} ({edges[a][b]})"
                for a in comp
                for b in sorted(edges[a])
                if b in inside
            ]
            bad.append(f"{folder}: {' <-> '.join(name(m) for m in comp)}\n" + "\n".join(lines))
    return total_modules, total_imports, bad


def self_test():
    """A circle is found, its absence passes, and comments, tests and re-exports are read right."""
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "c", "src")
        os.makedirs(os.path.join(src, "a"))
        files = {
            "lib.rs": "mod a;\nmod b;\nmod c;\n",
            "a/mod.rs": "mod x;\nmod y;\npub use x::X;\n",
            "a/x.rs": "use super::y::Y; // use crate::b::B;\npub struct X;\n",
            "a/y.rs": "pub struct Y;\n#[cfg(test)]\nmod tests { use crate::c::C; }\n",
            "b.rs": "pub struct B;\nfn f() { let _ = \"crate::c::C\"; }\n",
            "c.rs": "use crate::a::X;\npub struct C;\n",
        }
        for rel, text in files.items():
            with open(os.path.join(src, rel), "w") as fh:
                fh.write(text)
        folder = os.path.join(tmp, "c")
        _, imports, bad = check([folder])
        assert not bad, bad
        edges = Crate(folder).imports()
        assert edges[("c",)] == {("a", "x"): "crate::a::X"}, edges[("c",)]
        assert edges[("a", "x")] == {("a", "y"): "super::y::Y"}, edges[("a", "x")]
        assert imports == 2, imports
        with open(os.path.join(src, "a/y.rs"), "a") as fh:
            fh.write("fn g() -> crate::c::C { crate::c::C }\n")
        _, _, bad = check([folder])
        assert len(bad) == 1 and "a::x <-> a::y <-> c" in bad[0], bad
        assert "a::y -> c (crate::c::C)" in bad[0], bad[0]
    print("import-circles self-test: a circle of three found, none where there is none")


def main(argv):
    if argv[1:] == ["--self-test"]:
        self_test()
        return 0
    here = os.path.dirname(os.path.abspath(__file__))
    workspace = os.path.dirname(here)
    folders = argv[1:] or [os.path.join(workspace, c) for c in CRATES]
    for f in folders:
        if not os.path.isdir(os.path.join(f, "src")):
            print(f"import-circles: {f}: no src/ folder", file=sys.stderr)
            return 2
    modules, imports, bad = check(folders)
    if bad:
        print(f"import circles: {len(bad)}", file=sys.stderr)
        for b in bad:
            print(b, file=sys.stderr)
        return 1
    print(f"import circles: none ({modules} modules, {imports} imports between them)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
