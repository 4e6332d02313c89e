"""Checks the kernel's structure rules (issue 13), so that they stay true as the code grows:
  - public headers outside the brep family include neither OpenCASCADE nor CGAL (nor a brep header);
  - every public header is reachable from an umbrella header (steady/steady.hpp, steady/mesh.hpp, steady/brep.hpp);
  - internal headers (kernel/src/<family>/) are never included from a public header.
Run: /usr/bin/python3 tests/lint/check_kernel_structure.py [kernel dir]; exit status 1 lists the violations."""
import os
import re
import sys

OCC_OR_CGAL = re.compile(r'#\s*include\s*[<"]([A-Za-z0-9_]+\.hxx|CGAL/[^>"]+|Standard_[^>"]+)[>"]')
INCLUDE = re.compile(r'#\s*include\s*"([^"]+)"')
FAMILIES_WITHOUT_OCC = ("core", "cots", "lattice", "query", "properties", "mesh")


def public_headers(include_dir):
    for root, _, files in os.walk(os.path.join(include_dir, "steady")):
        for name in files:
            if name.endswith(".hpp"):
                path = os.path.join(root, name)
                yield os.path.relpath(path, include_dir).replace(os.sep, "/"), path


def violations(kernel):
    include_dir = os.path.join(kernel, "include")
    headers = dict(public_headers(include_dir))
    found = []
    for rel, path in sorted(headers.items()):
        text = open(path, encoding="utf-8").read()
        parts = rel.split("/")
        family = parts[1] if len(parts) > 2 else None
        includes = INCLUDE.findall(text)
        if family in FAMILIES_WITHOUT_OCC:
            for match in OCC_OR_CGAL.findall(text):
                found.append("%s includes %s (only the brep family may use OpenCASCADE or CGAL)" % (rel, match))
            for inc in includes:
                if inc.startswith("steady/brep"):
                    found.append("%s includes %s (a brep header outside the brep family)" % (rel, inc))
        for inc in includes:
            if not inc.startswith("steady/"):
                found.append("%s includes %s (an internal header, or not a family path)" % (rel, inc))
            elif inc not in headers:
                found.append("%s includes %s, which does not exist" % (rel, inc))
    umbrellas = ("steady/steady.hpp", "steady/mesh.hpp", "steady/brep.hpp")
    reached, todo = set(), [u for u in umbrellas if u in headers]
    if len(todo) != len(umbrellas):
        found.append("missing umbrella header(s): %s" % ", ".join(u for u in umbrellas if u not in headers))
    while todo:
        rel = todo.pop()
        if rel in reached:
            continue
        reached.add(rel)
        todo.extend(inc for inc in INCLUDE.findall(open(headers[rel], encoding="utf-8").read()) if inc in headers)
    for rel in sorted(set(headers) - reached):
        found.append("%s is not reachable from an umbrella header" % rel)
    return found


def main():
    kernel = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "kernel")
    found = violations(kernel)
    for line in found:
        print(line)
    print("%d violation(s)" % len(found))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
