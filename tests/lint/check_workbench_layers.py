"""Checks that the workbench's Python modules import each other in layers, like FreeCAD's Draft workbench: every
import of a latticewb module (at module level or inside a function) goes to the same or a lower layer, and the
graph of imports between modules has no cycle. Function-local imports count: a cycle hidden behind a local
import is still a cycle.

Run: /usr/bin/python3 tests/lint/check_workbench_layers.py [Mod/LatticeWorkbench]; exit status 1 lists the
violations."""
import ast
import os
import sys

# Lowest first. A module may import modules of its own layer and of the layers before it.
LAYERS = [
    ["latticewb", "latticewb.utils"],
    ["latticewb.kernel"],
    ["latticewb.objects"],
    ["latticewb.taskpanels"],
    ["latticewb.viewproviders"],
    ["latticewb.make"],
    ["latticewb.api", "latticewb.macro"],
    ["latticewb.gui"],
    ["latticewb.features"],  # only re-exports, kept for documents saved before the layers
]


def layer_of(module):
    """The layer of a module: the longest package prefix listed in LAYERS."""
    best, best_len = None, -1
    for index, prefixes in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best_len:
                best, best_len = index, len(prefix)
    return best


def modules(package_dir):
    """{module name: path} of every .py file of the latticewb package."""
    found = {}
    root = os.path.dirname(package_dir)
    for folder, _, files in os.walk(package_dir):
        for name in files:
            if not name.endswith(".py"):
                continue
            path = os.path.join(folder, name)
            parts = os.path.relpath(path, root)[:-3].split(os.sep)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            found[".".join(parts)] = path
    return found


def imports(path, module, known):
    """The latticewb modules `path` imports, with line numbers, wherever the import statement is."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    package = module if path.endswith("__init__.py") else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(alias.name, node.lineno) for alias in node.names if alias.name.startswith("latticewb")]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:  # relative import
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else []))
            if not base.startswith("latticewb"):
                continue
            for alias in node.names:  # `from latticewb.x import y`: y may be a module of its own
                candidate = base + "." + alias.name
                out.append((candidate if candidate in known else base, node.lineno))
    return out


def violations(mod_dir):
    package_dir = os.path.join(mod_dir, "latticewb")
    known = modules(package_dir)
    found, graph = [], {}
    for module, path in sorted(known.items()):
        own = layer_of(module)
        if own is None:
            found.append("%s is in no layer (add it to LAYERS)" % module)
            continue
        graph[module] = set()
        for target, line in imports(path, module, known):
            target_layer = layer_of(target)
            if target_layer is None:
                found.append("%s:%d imports %s, which is in no layer" % (module, line, target))
            elif target_layer > own:
                found.append("%s:%d imports %s from a higher layer (%s above %s)"
                             % (module, line, target, LAYERS[target_layer][0], LAYERS[own][0]))
            if target in known and target != module:
                graph[module].add(target)
    # cycles, by depth-first search
    state = {}

    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                found.append("import cycle: " + " -> ".join(stack[stack.index(nxt):] + [nxt]))
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
    return found


def main():
    mod_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "Mod",
                                                                  "LatticeWorkbench")
    found = violations(mod_dir)
    for line in found:
        print(line)
    print("%d violation(s)" % len(found))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
