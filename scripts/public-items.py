#!/usr/bin/env python3
"""The public items of footprint-core, counted and held under a ceiling (issue 53, item 2).

An item counts when a path from outside the crate reaches it: a module, struct, enum, union,
trait, function, constant, static, type alias or macro under a public path, once however many
paths reach it (a re-export is the item it names; a glob re-export brings its module's items).
Enum variants, fields and associated items are not counted. The list comes from rustdoc's JSON
output, built with the stable toolchain (`RUSTC_BOOTSTRAP=1`, as rustdoc's JSON is unstable) into
its own folder, target/api.

    scripts/public-items.py --ceiling N     # build, count, fail (exit 1) above N
    scripts/public-items.py --list          # build and print every item with its path
    scripts/public-items.py --self-test     # the count of a small hand-written crate
"""

import json
import os
import subprocess
import sys
import tempfile

ITEMS = {
    "module", "struct", "enum", "union", "trait", "function", "constant", "static",
    "type_alias", "macro", "trait_alias", "proc_macro",
}


def kind(item):
    return next(iter(item["inner"]))


def reachable(doc):
    """{item id: (its first path, its kind)} for every item a public path reaches."""
    index = doc["index"]
    found = {}

    def add(item_id, path):
        item = index.get(str(item_id))
        if item is None or kind(item) not in ITEMS or item_id in found:
            return
        found[item_id] = ("::".join(path), kind(item))
        if kind(item) == "module":
            walk(item_id, path)

    def walk(module_id, path):
        for child_id in index[str(module_id)]["inner"]["module"]["items"]:
            child = index.get(str(child_id))
            if child is None:
                continue
            if kind(child) == "use":
                use = child["inner"]["use"]
                target = use.get("id")
                if target is None or str(target) not in index:
                    continue  # a re-export from another crate
                if use["is_glob"]:
                    if kind(index[str(target)]) == "module":
                        walk(target, path)
                else:
                    add(target, path + [use["name"]])
            else:
                add(child_id, path + [child["name"]])

    root = doc["root"]
    walk(root, [index[str(root)]["name"]])
    return found


def build(workspace):
    """footprint-core's rustdoc JSON, built into target/api."""
    env = dict(os.environ, RUSTC_BOOTSTRAP="1", CARGO_TARGET_DIR=os.path.join(workspace, "target", "api"))
    subprocess.run(
        ["cargo", "rustdoc", "-q", "-p", "footprint-core", "--lib", "--",
         "-Z", "unstable-options", "--output-format", "json"],
        cwd=workspace, env=env, check=True,
    )
    with open(os.path.join(workspace, "target", "api", "doc", "footprint_core.json")) as fh:
        return json.load(fh)


def self_test():
    """A crate of a struct with a variant-holding enum, a module, a re-export of one of its
    functions (counted once) and a glob re-export: five items."""
    def module(name, items):
        return {"name": name, "inner": {"module": {"items": items, "is_stripped": False}}}

    def plain(name, k):
        return {"name": name, "inner": {k: {}}}

    def use(name, target, glob=False):
        return {"name": name, "inner": {"use": {"id": target, "name": name, "is_glob": glob}}}

    index = {
        "0": module("c", [1, 2, 3, 6, 8, 9]),
        "1": plain("S", "struct"),
        "2": plain("E", "enum"),
        "3": module("m", [4, 5]),
        "4": plain("f", "function"),
        "5": plain("V", "variant"),
        "6": use("f", 4),
        "7": module("hidden", [10]),
        "8": use("*", 7, glob=True),
        "9": use("Vec", 99),
        "10": plain("g", "function"),
    }
    found = reachable({"root": 0, "index": index})
    paths = sorted(p for p, _ in found.values())
    assert paths == ["c::E", "c::S", "c::g", "c::m", "c::m::f"], paths
    print("public-items self-test: 5 items counted, a re-export once, a variant not")


def main(argv):
    if argv[1:] == ["--self-test"]:
        self_test()
        return 0
    workspace = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if argv[1:] == ["--list"]:
        for path, k in sorted(reachable(build(workspace)).values()):
            print(f"{k:10} {path}")
        return 0
    if len(argv) != 3 or argv[1] != "--ceiling" or not argv[2].isdigit():
        print("usage: public-items.py --ceiling N | --list | --self-test", file=sys.stderr)
        return 2
    ceiling = int(argv[2])
    count = len(reachable(build(workspace)))
    if count > ceiling:
        print(
            f"footprint-core has {count} public items, over the ceiling of {ceiling} "
            "(scripts/public-items.py --list names them)",
            file=sys.stderr,
        )
        return 1
    print(f"footprint-core: {count} public items (ceiling {ceiling}, target 120)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
