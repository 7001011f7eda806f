#!/usr/bin/python3
"""Lists C++ functions longer than a limit (issue 25: no function over 120 lines in the host).

    python3 tools/function_lengths.py [--max N] [--ignore NAME]... [--all] [PATH...]

PATH defaults to app/src, app/include and plugins (relative to the repository root); files ending
in .cpp, .cc, .h or .hpp are scanned. No dependencies: comments, string, character and raw string
literals are blanked, then braces are matched. A brace at namespace or class scope whose header
holds a parameter list (and is not a class, enum, namespace or initialiser) opens a function body;
its length is counted from the line of the function's name to the closing brace, both included
(as ctags' line and end fields). Lambdas and local classes count towards the enclosing function.
NAME is matched against the qualified name printed (e.g. App::runInteractive) or its last part.
Prints "lines  path:line  name" for each function over --max (every function with --all), longest
first; exits 1 if any function over --max is not ignored.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
DEFAULT_PATHS = ["app/src", "app/include", "plugins"]
EXTENSIONS = (".cpp", ".cc", ".h", ".hpp")
NOT_FUNCTIONS = {"class", "struct", "union", "enum", "namespace"}
CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype", "alignof",
           "static_assert", "noexcept", "requires"}
IDENT = re.compile(r"[A-Za-z_~][A-Za-z_0-9]*(?:\s*::\s*~?[A-Za-z_][A-Za-z_0-9]*)*$")


def blank(text):
    """Returns text with comments and literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)

    def keep_newlines(s):
        return "".join("\n" if c == "\n" else " " for c in s)

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
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
                                                         or text[i - 1] in "uUL8"):
            k = text.find("(", i + 2)
            delim = text[i + 2:k]
            j = text.find(")" + delim + '"', k)
            j = n if j < 0 else j + len(delim) + 2
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):  # 1'000 digit separators
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == "#" and (i == 0 or text[text.rfind("\n", 0, i) + 1:i].strip() == ""):
            j = i
            while True:  # preprocessor lines, with continuations
                e = text.find("\n", j)
                if e < 0:
                    e = n
                    break
                if text[e - 1] != "\\":
                    break
                j = e + 1
            out.append(keep_newlines(text[i:e]))
            i = e
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_name(header):
    """The name of the function whose header (text before its body's brace) this is, or None."""
    h = re.sub(r"\s+", " ", header).strip()
    if not h or "(" not in h:
        return None
    words = set(re.findall(r"[A-Za-z_]+", h.split("(")[0]))
    if words & NOT_FUNCTIONS and not re.search(r"\boperator\b", h):
        return None
    # The parameter list: the first '(' at depth 0 that follows a name (operator() included).
    depth = 0
    for k, ch in enumerate(h):
        if ch == "(":
            if depth == 0:
                before = h[:k].rstrip()
                m = re.search(r"(operator\s*(\(\)|[^\sA-Za-z_0-9(]+|[A-Za-z_][A-Za-z_0-9 ]*)|"
                              r"[A-Za-z_~][A-Za-z_0-9]*(?:\s*::\s*~?[A-Za-z_][A-Za-z_0-9]*)*"
                              r"(?:\s*::\s*operator\s*\S+)?)$", before)
                if m is None:
                    return None
                name = re.sub(r"\s+", "", m.group(0))
                last = name.split("::")[-1]
                if last in CONTROL or "=" in before.split(")")[-1] and not name.startswith("operator"):
                    return None
                return name
            depth += 1
        elif ch == ")":
            depth -= 1
    return None


def scan(path):
    """Yields (name, first_line, length) for each function body in the file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = blank(f.read())
    line_of = []
    line = 1
    for ch in text:
        line_of.append(line)
        if ch == "\n":
            line += 1
    i, n = 0, len(text)
    header_start = 0
    scope = []  # kinds of open braces at declaration level: 'decl' (namespace, class, extern)

    def skip_group(j):
        """Index after the brace group that opens at j."""
        depth = 0
        while j < n:
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0:
                    return j + 1
            j += 1
        return n

    while i < n:
        c = text[i]
        if c in ";":
            header_start = i + 1
        elif c == "}":
            if scope:
                scope.pop()
            header_start = i + 1
        elif c == "{":
            header = text[header_start:i]
            name = function_name(header)
            stripped = header.rstrip()
            # A brace in a constructor's initialiser list (x_{a}) or a default member initialiser.
            if name and re.search(r"\)\s*(noexcept\s*)?:", header) and stripped and \
                    (stripped[-1].isalnum() or stripped[-1] == "_"):
                tail = stripped.split(")")[-1]
                if not re.search(r"\b(const|override|final|noexcept|mutable|volatile)\s*$", tail):
                    i = skip_group(i)
                    continue
            if name and not stripped.endswith("="):
                end = skip_group(i)
                m = re.search(re.escape(name.split("::")[-1]) if not name.startswith("operator") else r"operator",
                              header)
                start = header_start + (m.start() if m else len(header) - len(header.lstrip()))
                yield name, line_of[start], line_of[end - 1] - line_of[start] + 1
                i = end
                header_start = i
                continue
            words = re.findall(r"[A-Za-z_]+", header)
            if words and (set(words) & {"namespace", "class", "struct", "union"} or words[0] == "extern") \
                    and "=" not in header and "enum" not in words:
                scope.append("decl")
                header_start = i + 1
            else:
                i = skip_group(i)  # enum bodies, initialisers, arrays
                header_start = i
                continue
        i += 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", help="files or folders (default: %s)" % " ".join(DEFAULT_PATHS))
    ap.add_argument("--max", type=int, default=120, help="longest allowed function, in lines (default 120)")
    ap.add_argument("--ignore", action="append", default=[], metavar="NAME",
                    help="a function allowed to be longer (qualified or last part of its name); repeatable")
    ap.add_argument("--all", action="store_true", help="print every function, not only those over --max")
    args = ap.parse_args(argv)
    paths = args.paths or [os.path.join(ROOT, p) for p in DEFAULT_PATHS]
    files = []
    for p in paths:
        if os.path.isdir(p):
            for d, _, names in os.walk(p):
                files += [os.path.join(d, f) for f in names if f.endswith(EXTENSIONS)]
        elif os.path.isfile(p):
            files.append(p)
        else:
            print("function_lengths: no such file or folder: %s" % p, file=sys.stderr)
            return 2
    found = []
    for f in sorted(files):
        for name, line, length in scan(f):
            found.append((length, os.path.relpath(f, ROOT) if f.startswith(ROOT) else f, line, name))
    found.sort(key=lambda r: (-r[0], r[1], r[2]))
    failing = 0
    for length, f, line, name in found:
        over = length > args.max
        ignored = name in args.ignore or name.split("::")[-1] in args.ignore
        if over or args.all:
            print("%5d  %s:%d  %s%s" % (length, f, line, name, "  (ignored)" if over and ignored else ""))
        if over and not ignored:
            failing += 1
    print("function_lengths: %d function(s) in %d file(s), %d over %d lines%s"
          % (len(found), len(files), sum(1 for r in found if r[0] > args.max), args.max,
             "" if not failing else ", %d not ignored" % failing))
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
