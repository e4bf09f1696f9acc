#!/usr/bin/env python3
"""Lists the longest function bodies in the C++ sources, and fails when one is over the limit.

    tests/architecture/function_lengths.py [--limit 120] [--top 10] [DIR...]   (default: every source folder)

A brace counter, not a parser: comments, string and character literals are blanked first; braces of
namespaces, classes, structs, enums and initialisers are transparent, and a brace that opens after a
parameter list `(...)` (plus const, noexcept, override, a trailing return type or a constructor's
initialiser list) opens a function. Its length runs from the line of its name to its closing brace.
Lambdas inside a function count as part of it."""
import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
FOLDERS = ["core", "decomposition", "radiosity", "scenes", "apps", "bench", "tests"]


def blank(text):
    """Comments, strings and chars replaced by spaces (newlines kept, so line numbers hold)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(c); i += 1; continue
            out.append(" " * (j + 1 - i)); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


HEAD = re.compile(r"\)\s*(const|noexcept|override|final|mutable|\s|->[^{;]*)*$")


def functions(path):
    text = blank(path.read_text(errors="replace"))
    found, stack, start = [], [], 0  # stack: 'scope' (transparent) or ('fn', name, line) or 'block'
    depth_fn = 0
    for i, c in enumerate(text):
        if c == "{":
            if depth_fn > 0:
                depth_fn += 1
                stack.append("block")
            else:
                head = text[start:i]
                flat = " ".join(head.split())
                # A constructor's initialiser list: cut at the ") :" that starts it.
                sig = re.sub(r"\)\s*:\s*[^()]*\(.*$", ")", flat) if re.search(r"\)\s*:\s*\w", flat) else flat
                is_fn = bool(HEAD.search(sig)) and "=" not in sig.split("(")[0] and not re.match(
                    r"^(namespace|struct|class|union|enum|extern)\b", sig.split("(")[0].strip() or "x")
                if re.search(r"\b(namespace|struct|class|union|enum)\b[^()]*$", flat) or not is_fn:
                    stack.append("scope")
                else:
                    name = re.findall(r"([~\w:]+)\s*\(", sig)
                    line = text.count("\n", 0, start + len(head) - len(head.lstrip())) + 1
                    stack.append(("fn", name[0] if name else "?", line))
                    depth_fn = 1
            start = i + 1
        elif c == "}":
            top = stack.pop() if stack else "scope"
            if isinstance(top, tuple):
                depth_fn = 0
                found.append((text.count("\n", 0, i) + 1 - top[2] + 1, top[1], top[2]))
            elif top == "block":
                depth_fn -= 1
            start = i + 1
        elif c == ";" and depth_fn == 0:
            start = i + 1
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--limit", type=int, default=120)
    ap.add_argument("--top", type=int, default=10)
    ap.add_argument("dirs", nargs="*", default=FOLDERS)
    a = ap.parse_args()
    rows = []
    for d in a.dirs:
        for p in sorted((ROOT / d).rglob("*")):
            if p.suffix in (".cpp", ".h") and "build" not in p.relative_to(ROOT).parts:
                rows += [(n, f"{p.relative_to(ROOT)}:{line}", name) for n, name, line in functions(p)]
    rows.sort(reverse=True)
    for n, where, name in rows[: a.top]:
        print(f"{n:5d}  {name:40s} {where}")
    over = [r for r in rows if r[0] > a.limit]
    print(f"{len(rows)} functions, {len(over)} over {a.limit} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
