"""The engine's folders include one way, lower stages first (engine_cpp/): every ``#include "dir/..."``
of a C++ file names its own folder or one earlier in :data:`STAGES`, so the stages form no cycle
(the iteration loop uses the net-order policies, which route trial orders on the one-region router;
the region router knows nothing of either). The check itself is tried on drawn includes."""

from __future__ import annotations

import re
from pathlib import Path

ENGINE = Path(__file__).resolve().parent.parent / "engine_cpp"

# Lowest first: a folder may include its own files and those of the folders before it.
STAGES: tuple[str, ...] = (
    "geom", "errors", "db", "io", "drc", "grid", "pa", "route", "verify", "groute",
    "region", "order", "loop", "bindings", "fuzz",
)

_INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/', re.MULTILINE)


def upward_includes(folder: str, text: str) -> list[str]:
    """The folders `text` (a file of `folder`) includes that are not at or below its stage."""
    rank = STAGES.index(folder)
    return [d for d in _INCLUDE.findall(text) if d in STAGES and STAGES.index(d) > rank]


def test_every_folder_with_cpp_has_a_stage() -> None:
    folders = {p.parent.name for p in ENGINE.rglob("*.[ch]pp")}
    assert folders, f"no C++ files under {ENGINE}"
    assert folders <= set(STAGES), f"folders without a stage: {sorted(folders - set(STAGES))}"


def test_includes_go_to_lower_stages_only() -> None:
    bad = []
    for path in sorted(ENGINE.rglob("*.[ch]pp")):
        for d in upward_includes(path.parent.name, path.read_text()):
            bad.append(f"{path.relative_to(ENGINE)} includes {d}/")
    assert not bad, "\n".join(bad)


def test_the_check_finds_an_upward_include() -> None:
    drawn = '#include "region/region_router.hpp"\n#include "order/policy.hpp"\n#include <vector>\n'
    assert upward_includes("region", drawn) == ["order"]
    assert upward_includes("loop", drawn) == []
    assert upward_includes("groute", '#include "loop/regions.hpp"\n') == ["loop"]
