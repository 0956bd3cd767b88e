"""The largest files and functions of the product, against the house limits (CONTRIBUTING.md).

    python bench/code_size.py [--top N] [--check]

Counts lines of C++ (``engine_cpp/``) and Python (the package's folders) files, and the length
of every function: C++ functions by their braces (a lambda or a block counts with the function
that holds it; a method defined in a class body counts on its own), Python functions with
``ast`` (a nested function counts with the one that holds it). Prints the N largest of each and
how many exceed the limits. With ``--check`` it exits 1 when any file or function is over its
hard limit: a C++ file over 600 lines, a function over 120 lines.
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CPP_DIRS = ("engine_cpp",)
PY_DIRS = ("src/xroute", "cli", "policies", "envs", "testcases")
CPP_FILE_LIMIT = 600
PY_FILE_LIMIT = 400  # a habit (CONTRIBUTING.md), reported, not enforced
FUNCTION_SOFT_LIMIT = 60
FUNCTION_LIMIT = 120


@dataclass(frozen=True)
class Function:
    path: str
    line: int
    name: str
    lines: int


def _strip_cpp(text: str) -> str:
    """The text with comments, string and character literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        two = text[i:i + 2]
        if two == "//":
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif two == "/*":
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text[i + 1:i + 2] == '"':  # raw string R"delim( ... )delim"
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r"[^\n]", " ", text[i:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    # Preprocessor lines (and their continuations) are no part of a signature.
    return re.sub(r"(?m)^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", lambda m: re.sub(r"[^\n]", " ", m.group(0)),
                  "".join(out))


_CLASS_HEAD = re.compile(r"\b(namespace|class|struct|union)\b")
_NOT_FUNCTION = re.compile(r"^\s*(if|for|while|switch|do|else|try|catch|return)\b|=\s*$|\benum\b")


def cpp_functions(path: Path) -> list[Function]:
    """Every function defined in a C++ file, with its length from signature to closing brace."""
    text = _strip_cpp(path.read_text())
    rel = str(path.relative_to(ROOT))
    found: list[Function] = []
    # Each open brace: (kind, start line, name); kinds: scope (namespace/class), function, block.
    stack: list[tuple[str, int, str]] = []
    head_start = 0  # offset where the text before the next brace began
    line = 1
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        if c not in "{};":
            continue
        if c == ";":
            if not stack or stack[-1][0] == "scope":
                head_start = i + 1
            continue
        if c == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "function":
                    found.append(Function(rel, start, name, line - start + 1))
            head_start = i + 1
            continue
        head = text[head_start:i]
        inside_function = any(k == "function" for k, _, _ in stack)
        if inside_function:
            stack.append(("block", line, ""))
        elif _CLASS_HEAD.search(head) and "(" not in head.split("{")[0].split(":")[0]:
            stack.append(("scope", line, ""))
            head_start = i + 1
        elif "(" in head and not _NOT_FUNCTION.search(head.strip()):
            first = head_start + len(head) - len(head.lstrip())
            start = line - text[first:i].count("\n")
            name_match = re.search(r"([~\w:]+(?:operator\S*)?)\s*\(", head)
            stack.append(("function", start, name_match.group(1) if name_match else "?"))
        else:
            stack.append(("block", line, ""))
    return found


def py_functions(path: Path) -> list[Function]:
    """Every top-level function and method of a Python file (nested ones count with their holder)."""
    tree = ast.parse(path.read_text(), filename=str(path))
    rel = str(path.relative_to(ROOT))
    found: list[Function] = []

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                first = min([child.lineno] + [d.lineno for d in child.decorator_list])
                found.append(Function(rel, first, prefix + child.name,
                                      (child.end_lineno or child.lineno) - first + 1))
            elif isinstance(child, ast.ClassDef):
                visit(child, prefix + child.name + ".")

    visit(tree, "")
    return found


def source_files() -> tuple[list[Path], list[Path]]:
    cpp = sorted(p for d in CPP_DIRS for p in (ROOT / d).rglob("*") if p.suffix in (".cpp", ".hpp"))
    py = sorted({p.resolve() for d in PY_DIRS for p in (ROOT / d).rglob("*.py")
                 if not p.is_symlink() and ROOT in p.resolve().parents})
    return cpp, py


def line_count(path: Path) -> int:
    return len(path.read_text().splitlines())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=int, default=10, help="how many of each to list (default 10)")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when a C++ file is over 600 lines or a function over 120")
    args = parser.parse_args(argv)
    cpp, py = source_files()
    cpp_sizes = sorted(((line_count(p), str(p.relative_to(ROOT))) for p in cpp), reverse=True)
    py_sizes = sorted(((line_count(p), str(p.relative_to(ROOT))) for p in py), reverse=True)
    cpp_funcs = sorted((f for p in cpp for f in cpp_functions(p)), key=lambda f: -f.lines)
    py_funcs = sorted((f for p in py for f in py_functions(p)), key=lambda f: -f.lines)

    def files(title: str, sizes: list[tuple[int, str]], limit: int) -> None:
        over = sum(1 for n, _ in sizes if n > limit)
        print(f"{title}: {len(sizes)} files, {sum(n for n, _ in sizes):,} lines, {over} over {limit}")
        for n, name in sizes[: args.top]:
            print(f"  {n:6d}  {name}")

    def functions(title: str, funcs: list[Function]) -> None:
        soft = sum(1 for f in funcs if f.lines > FUNCTION_SOFT_LIMIT)
        hard = sum(1 for f in funcs if f.lines > FUNCTION_LIMIT)
        print(f"{title}: {len(funcs)} functions, {soft} over {FUNCTION_SOFT_LIMIT} lines, "
              f"{hard} over {FUNCTION_LIMIT}")
        for f in funcs[: args.top]:
            print(f"  {f.lines:6d}  {f.path}:{f.line}  {f.name}")

    files("C++ files", cpp_sizes, CPP_FILE_LIMIT)
    functions("C++ functions", cpp_funcs)
    files("Python files", py_sizes, PY_FILE_LIMIT)
    functions("Python functions", py_funcs)
    bad = [f"{name}: {n} lines" for n, name in cpp_sizes if n > CPP_FILE_LIMIT]
    bad += [f"{f.path}:{f.line} {f.name}: {f.lines} lines"
            for f in cpp_funcs + py_funcs if f.lines > FUNCTION_LIMIT]
    if args.check and bad:
        print("over the hard limits:\n  " + "\n  ".join(bad), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
