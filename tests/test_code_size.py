"""The house limits on size (CONTRIBUTING.md, Style), measured by bench/code_size.py: no C++ file over 600
lines, no C++ or Python function over 120; and the measuring itself, on drawn code."""

from __future__ import annotations

from pathlib import Path

from conftest import load_file

code_size = load_file("bench/code_size.py")

DRAWN_CPP = """\
#include <vector>
// a comment with { braces } and a function() call
namespace xroute {

struct Box {
  int area() const {
    return w_ * h_;
  }
  int w_ = 0, h_ = 0;
};

static const char* kText = "not { a body }";

int sum(const std::vector<int>& v) {
  int s = 0;
  for (int x : v) {
    if (x > 0) { s += x; }
  }
  auto twice = [](int y) {
    return 2 * y;
  };
  return twice(s);
}

}  // namespace xroute
"""


def test_cpp_functions_are_found_with_their_lengths(tmp_path: Path, monkeypatch) -> None:
    """A method in a class body and a free function with a lambda and blocks inside are two functions
    of the right lengths; braces in comments and strings, the namespace and the struct are not."""
    path = tmp_path / "drawn.cpp"
    path.write_text(DRAWN_CPP)
    monkeypatch.setattr(code_size, "ROOT", tmp_path)
    found = {(f.name, f.line, f.lines) for f in code_size.cpp_functions(path)}
    assert found == {("area", 6, 3), ("sum", 14, 10)}


def test_python_functions_count_their_decorators_and_nested_code(tmp_path: Path, monkeypatch) -> None:
    path = tmp_path / "drawn.py"
    path.write_text("class A:\n    @property\n    def b(self):\n        def c():\n            pass\n"
                    "        return 1\n\n\ndef d():\n    pass\n")
    monkeypatch.setattr(code_size, "ROOT", tmp_path)
    found = {(f.name, f.line, f.lines) for f in code_size.py_functions(path)}
    assert found == {("A.b", 2, 5), ("d", 9, 2)}


def test_the_product_keeps_within_the_limits(capsys) -> None:
    """`python bench/code_size.py --check` exits 0: every C++ file within 600 lines, every function
    within 120 (the check found planNet at 322 lines and three files over 600 before the split)."""
    rc = code_size.main(["--top", "3", "--check"])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "0 over 600" in out and out.count("0 over 120") == 2
