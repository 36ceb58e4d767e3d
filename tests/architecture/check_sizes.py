#!/usr/bin/env python3
"""Checks the size rule of docs/ARCHITECTURE.md: in src/ and apps/, no function body is longer
than 80 lines and no file longer than 600, unless the file says why in a line starting
"// Size:" near its top. Run by CTest: python3 check_sizes.py <repository>

A function body is a brace block opened at namespace or class level (or inside an extern/namespace
block) whose opening line is not a type, enum or initializer; its length counts from the line of
its opening brace to the line of its closing brace. The scan skips strings, characters and
comments; it is a heuristic over C++, not a parser.
"""
import os
import re
import sys

MAX_FUNCTION_LINES = 80
MAX_FILE_LINES = 600
REASON_PREFIX = "// Size:"
REASON_SEARCH_LINES = 30  # the reason goes at the top of the file

# Files not yet within the limits, each a repository-relative path: their breaches are printed
# but do not fail the check. Remove an entry once its file is within the limits; keep it empty.
ALLOWED_FOR_NOW = set()

SOURCE_DIRS = ("src", "apps")
EXTENSIONS = (".cpp", ".h", ".hpp", ".cc")
TYPE_KEYWORDS = re.compile(r"\b(class|struct|union|enum|namespace)\b")
NAME_BEFORE_PAREN = re.compile(r"([A-Za-z_~][\w:<>~]*(?:operator\s*[^\s(]+)?)\s*\($")


def strip_code(text):
    """Returns text with comments, strings and character literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        nxt = text[i + 1] if i + 1 < n else ""
        if c == "/" and nxt == "/":
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c == "/" and nxt == "*":
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "R" and nxt == '"' and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append("".join(ch if ch == "\n" else " " for ch in text[i:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            # A quote after a digit or letter is a digit separator (1'000), not a character literal.
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            # Preprocessor line (with continuations): blank it so macros do not confuse the scan.
            j = i
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if k > 0 and text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


def block_header(code, brace):
    """The text before an opening brace back to the previous ';', '{' or '}' (its declaration)."""
    j = brace - 1
    while j >= 0 and code[j] not in ";{}":
        j -= 1
    return code[j + 1:brace]


def drop_template_prefix(flat):
    """Removes a leading 'template <...>' (its parameters may say 'class')."""
    while flat.startswith("template"):
        k = flat.find("<")
        if k < 0:
            return flat
        depth = 0
        for j in range(k, len(flat)):
            if flat[j] == "<":
                depth += 1
            elif flat[j] == ">":
                depth -= 1
                if depth == 0:
                    flat = flat[j + 1:].lstrip()
                    break
        else:
            return flat
    return flat


def function_name(header):
    """The function's name from its declaration text, or None when the block is not a function."""
    flat = drop_template_prefix(" ".join(header.split()))
    if not flat or TYPE_KEYWORDS.search(flat.split("(")[0]) or flat.endswith("=") or "(" not in flat:
        return None
    if flat.startswith("extern"):
        return None
    # Strip a constructor initializer list and trailing specifiers: take the first top-level '('.
    depth = 0
    for k, ch in enumerate(flat):
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth = max(0, depth - 1)
        elif ch == "(" and depth == 0:
            m = NAME_BEFORE_PAREN.search(flat[:k].rstrip() + "(")
            if not m:
                return None
            name = m.group(1)
            if name in ("if", "for", "while", "switch", "catch", "return"):
                return None
            return name
    return None


def functions(code):
    """Yields (name, first line, length in lines) for each function body in stripped code."""
    stack = []  # one entry per open brace: (kind, name, line)
    line = 1
    for idx, ch in enumerate(code):
        if ch == "\n":
            line += 1
        elif ch == "{":
            outer_is_scope = all(kind == "scope" for kind, _, _ in stack)
            header = block_header(code, idx)
            if outer_is_scope:
                name = function_name(header)
                if name:
                    stack.append(("function", name, line))
                elif TYPE_KEYWORDS.search(" ".join(header.split()).split("(")[0]) and not header.rstrip().endswith("="):
                    stack.append(("scope", None, line))
                elif header.strip().startswith("extern"):
                    stack.append(("scope", None, line))
                else:
                    stack.append(("other", None, line))
            else:
                stack.append(("other", None, line))
        elif ch == "}":
            if not stack:
                continue
            kind, name, start = stack.pop()
            if kind == "function":
                yield name, start, line - start + 1


def has_reason(text):
    for row in text.splitlines()[:REASON_SEARCH_LINES]:
        if row.startswith(REASON_PREFIX) and len(row) > len(REASON_PREFIX) + 3:
            return True
    return False


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.getcwd()
    failures = []
    tolerated = []
    for top in SOURCE_DIRS:
        for folder, _, names in os.walk(os.path.join(root, top)):
            for fname in sorted(names):
                if not fname.endswith(EXTENSIONS):
                    continue
                path = os.path.join(folder, fname)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = f.read()
                bucket = tolerated if rel in ALLOWED_FOR_NOW else failures
                lines = text.count("\n") + (0 if text.endswith("\n") else 1)
                if lines > MAX_FILE_LINES and not has_reason(text):
                    bucket.append(f"{rel}:1: file has {lines} lines (limit {MAX_FILE_LINES}; "
                                  f"split it or say why in a '{REASON_PREFIX}' line at its top)")
                for name, start, length in functions(strip_code(text)):
                    if length > MAX_FUNCTION_LINES:
                        bucket.append(f"{rel}:{start}: function {name} has {length} lines "
                                      f"(limit {MAX_FUNCTION_LINES})")
    for row in tolerated:
        print("check_sizes: allowed for now: " + row)
    for row in failures:
        print("check_sizes: " + row)
    if failures:
        print(f"check_sizes: {len(failures)} size limit(s) broken")
        return 1
    print("check_sizes: every function and file is within the size limits or says why")
    return 0


if __name__ == "__main__":
    sys.exit(main())
