#!/usr/bin/python3
"""Lists the C and C++ functions longer than a limit (default 80 lines, from the line of the
signature's name to the closing brace), longest first. Functions are found by matching braces
in the source with comments, strings and preprocessor lines blanked: a brace opened at
namespace or class scope after a closing parenthesis (and qualifiers) is a function body.
GObject class_init functions are left out: they are one long list of registrations.

Usage: function_lengths.py [--max N] PATH...   (folders are searched for .c .cpp .h .hpp)
Exit status 1 when a function is over the limit."""
import os
import re
import sys

EXTENSIONS = (".c", ".cpp", ".h", ".hpp")
FUNCTION_END = re.compile(r"\)\s*(?:const|noexcept|override|final|mutable|&|&&|->[^;{}]*|\s)*$")
CONTROL = re.compile(r"\b(?:if|for|while|switch|catch)\s*\(")
SCOPE = re.compile(r"\b(?:namespace|class|struct|union)\b|extern\s*\"C\"")


def blank(text):
    """The text with comments, string and character literals and preprocessor lines replaced
    by spaces, newlines kept, so that offsets and line numbers stay those of the file."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            while i < n and not (text[i] == "\n" and text[i - 1] != "\\"):
                out.append("\n" if text[i] == "\n" else " ")
                i += 1
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        line_start = c == "\n"
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.extend("\n" if ch == "\n" else " " for ch in text[i:end])
            i = end
        elif c == 'R' and text.startswith('R"', i):
            close = text.find("(", i)
            delim = ")" + text[i + 2:close] + '"'
            end = text.find(delim, close)
            end = n if end < 0 else end + len(delim)
            out.extend("\n" if ch == "\n" else " " for ch in text[i:end])
            i = end
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator: 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n - 1) - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching(text, open_at):
    depth = 0
    for i in range(open_at, len(text)):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return i
    return len(text) - 1


def function_name(header):
    """The name before the parameter list of a function header."""
    depth = 0
    for i in range(len(header) - 1, -1, -1):
        if header[i] == ")":
            depth += 1
        elif header[i] == "(":
            depth -= 1
            if depth == 0:
                m = re.search(r"([~\w:]+(?:\s*operator\s*[^\s(]+)?)\s*$", header[:i])
                return (m.group(1) if m else "?"), i
    return "?", 0


def functions(text):
    """(name, first line, last line) of every function defined in the blanked text."""
    found = []

    def scan(start, end):
        header_start = start
        i = start
        while i < end:
            c = text[i]
            if c in ";}":
                header_start = i + 1
            elif c == "{":
                header = text[header_start:i]
                close = matching(text, i)
                if FUNCTION_END.search(header) and not CONTROL.search(header) and "=" not in header.split("(")[0]:
                    name, paren = function_name(header)
                    first = text.count("\n", 0, header_start + paren) + 1
                    found.append((name, first, text.count("\n", 0, close) + 1))
                elif SCOPE.search(header) and "(" not in header:
                    scan(i + 1, close)
                i = close
                header_start = close + 1
            i += 1

    scan(0, len(text))
    return found


def sources(paths):
    for path in paths:
        if os.path.isfile(path):
            yield path
            continue
        for root, dirs, files in os.walk(path):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(EXTENSIONS):
                    yield os.path.join(root, f)


def main():
    args = sys.argv[1:]
    limit = 80
    if args[:1] == ["--max"]:
        limit = int(args[1])
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    long_ones = []
    for path in sources(args):
        with open(path, encoding="utf-8", errors="replace") as f:
            text = blank(f.read())
        for name, first, last in functions(text):
            length = last - first + 1
            if length > limit and not name.endswith("_class_init"):
                long_ones.append((length, path, first, name))
    for length, path, first, name in sorted(long_ones, key=lambda r: (-r[0], r[1], r[2])):
        print(f"{length:5d}  {path}:{first}  {name}")
    print(f"{len(long_ones)} functions over {limit} lines")
    return 1 if long_ones else 0


if __name__ == "__main__":
    sys.exit(main())
