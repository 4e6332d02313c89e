"""Checks that no function of the kernel (kernel/src, kernel/include, kernel/python) is longer than MAX_LINES,
from its signature's first line to its closing brace, member functions defined in their class included and the
lambdas inside a function counted as part of it.

The scanner knows just enough C++: comments, string and character literals are blanked; a `{` opens a function
when it sits at namespace or class scope and the text before it (since the previous `;`, `{` or `}`) ends like a
signature (a parameter list, maybe followed by qualifiers or a constructor's initializers); namespaces, classes and
aggregate initializers are scopes, not functions.
Run: /usr/bin/python3 tests/lint/check_function_length.py [kernel dir]; exit status 1 lists the long functions."""
import os
import re
import sys

MAX_LINES = 150

_SCOPE = re.compile(r'(^|\W)(namespace|class|struct|union|enum)(\W|$)|extern\s*"C"')
_SIGNATURE_END = re.compile(r'\)\s*(const|noexcept|override|final|mutable|volatile|&|&&|->\s*[\w:<>,\s*&]+|\s)*$')


def blank(text):
    """Comments, strings and characters replaced by spaces (newlines kept, so line numbers stay)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            j = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    """(first line, last line, signature) of every function defined in the file."""
    text = blank(open(path, encoding="utf-8").read())
    stack = []  # per open brace: "scope", "function" (with its start) or "inner"
    header_start = 0  # offset where the text before the next brace began
    found = []
    line_of = lambda offset: text.count("\n", 0, offset) + 1  # noqa: E731
    for i, c in enumerate(text):
        if c in ";}":
            if c == "}" and stack:
                kind = stack.pop()
                if isinstance(kind, tuple):
                    start, signature = kind
                    found.append((line_of(start), line_of(i), signature))
            if not stack or stack[-1] == "scope":
                header_start = i + 1
        elif c == "{":
            inside_function = any(k != "scope" for k in stack)
            header = text[header_start:i]
            if inside_function:
                stack.append("inner")
            elif _SCOPE.search(header) and "(" not in header.split("=")[0].split(":")[0]:
                stack.append("scope")
                header_start = i + 1
            elif _SIGNATURE_END.search(header.strip()) or re.search(r"\)\s*:\s*[\w:]+[({]", header):
                start = header_start + len(header) - len(header.lstrip())
                stack.append((start, " ".join(header.split())[:100]))
            else:
                stack.append("inner")  # an initializer at namespace scope
    return found


def violations(kernel):
    found = []
    for folder in ("src", "include", "python"):
        for root, _, files in os.walk(os.path.join(kernel, folder)):
            for name in sorted(files):
                if not name.endswith((".cpp", ".hpp")):
                    continue
                path = os.path.join(root, name)
                for first, last, signature in functions(path):
                    length = last - first + 1
                    if length > MAX_LINES:
                        found.append("%s:%d: %d lines: %s" % (os.path.relpath(path, kernel), first, length, signature))
    return found


def main():
    kernel = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "kernel")
    found = violations(kernel)
    for line in found:
        print(line)
    print("%d function(s) over %d lines" % (len(found), MAX_LINES))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
