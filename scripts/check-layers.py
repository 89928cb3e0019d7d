#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The include graph of src/meshmorph keeps its floors (docs/library.md).

check-layers.py [SRC]   (SRC: the src/ directory; default: the one beside this script)

1. Between folders, includes go only downwards:
     core <- parallel <- mesh <- {io, quality} <- morph <- design <- app,   core <- deform <- morph
   (a folder may include any folder below it).
2. Inside a folder, no include runs back up: the files (a .h and its .cpp count as one)
   form no cycle.
Prints every violation; exit 1 if there is any.
"""
import os
import re
import sys

BELOW = {
    "core": set(),
    "parallel": {"core"},
    "mesh": {"core", "parallel"},
    "io": {"core", "parallel", "mesh"},
    "quality": {"core", "parallel", "mesh"},
    "deform": {"core"},
    "morph": {"core", "parallel", "mesh", "io", "quality", "deform"},
    "design": {"core", "parallel", "mesh", "io", "quality", "deform", "morph"},
    "app": {"core", "parallel", "mesh", "io", "quality", "deform", "morph", "design"},
}
INCLUDE = re.compile(r'#include "meshmorph/([a-z_]+)/([a-z_0-9]+)\.h"')


def includes(root):
    """(folder, file stem) -> set of (folder, stem) it includes."""
    graph = {}
    for folder in sorted(os.listdir(root)):
        path = os.path.join(root, folder)
        if not os.path.isdir(path):
            continue
        for name in sorted(os.listdir(path)):
            if not name.endswith((".h", ".cpp")):
                continue
            node = (folder, name.rsplit(".", 1)[0])
            with open(os.path.join(path, name)) as f:
                found = {m.groups() for m in INCLUDE.finditer(f.read())}
            graph.setdefault(node, set()).update(found - {node})
    return graph


def cycles(graph, folder):
    """Strongly connected components of more than one file inside `folder` (Tarjan)."""
    nodes = [n for n in graph if n[0] == folder]
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w[0] != folder:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w[1])
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in nodes:
        if v not in index:
            visit(v)
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "src")
    root = os.path.join(src, "meshmorph")
    graph = includes(root)
    problems = []
    for (folder, stem), targets in sorted(graph.items()):
        if folder not in BELOW:
            problems.append(f"{folder}/: a folder the layering does not know (add it to BELOW)")
            continue
        for target_folder, target in sorted(targets):
            if target_folder != folder and target_folder not in BELOW[folder]:
                problems.append(f"{folder}/{stem} includes {target_folder}/{target}.h: "
                                f"{target_folder} is not below {folder}")
    for folder in sorted({f for f, _ in graph}):
        for component in cycles(graph, folder):
            problems.append(f"{folder}/: include cycle among {', '.join(component)} "
                            "(move the shared record into a header of its own)")
    for p in sorted(set(problems)):
        print(p)
    print(f"check-layers: {len(graph)} files, {len(set(problems))} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
