"""Tiling: a larger testcase made of R x C copies of a real one, for measuring how cost grows.

``tile_testcase(name, rows, cols, out_dir)`` writes ``out_dir/<tiled>.input.{lef,def,guide}`` with
``<tiled> = out_dir.name`` (the DEF's design name too; ``make-testcase`` uses ``<name>_<rows>x<cols>``). Copy (i, j) (row i from the bottom, column j from the
left) is moved by (j * dx, i * dy) and everything it owns is renamed with the suffix
``_r{i}_c{j}``: components, nets, IO pins, rows, and the net names in the guides.

* The offsets dx, dy are the die's width and height plus a margin (twice the largest step
  below, so that shapes on the die edges of neighbouring copies neither touch nor break a
  spacing rule), rounded up to a common multiple of every step that must line up across
  copies: the track steps, the row site step and the GCell pitch (GCELLGRID, or the guides'
  most common extent when the DEF has none). So every copy sees the same tracks and GCell grid
  as the original, and a thin empty strip separates neighbouring copies.
* DIEAREA covers all copies; TRACKS are extended (more of them, same start and step); ROW and
  GCELLGRID statements are repeated per copy, moved.
* IO pins stay pins in every copy (renamed, moved): each copy is a complete design, nothing is
  connected across copies.
* Special nets (power) keep their names: one special net holds the wiring of all copies, so
  rails that meet at a copy boundary are the same net, not a short.
* VIAS, NONDEFAULTRULES, STYLES and PROPERTYDEFINITIONS are copied once; other sections
  (FILLS, GROUPS, REGIONS, ...) are refused with an InputError.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

from xroute.testcases.def_text import (
    DefText,
    GuideNet,
    Section,
    is_int,
    read_def_text,
    read_guides,
    write_def_text,
    write_guides,
)
from xroute.atomic_files import atomic_copy, atomic_write_text
from xroute.testcases.registry import find_testcase
from xroute.errors import InputError, XrouteError

COPY_ONCE = ("VIAS", "NONDEFAULTRULES", "STYLES", "PROPERTYDEFINITIONS")
WIRING = ("ROUTED", "FIXED", "COVER", "SHIELD", "RECT", "POLYGON", "VIA")
SUB_OPTIONS = ("SHAPE", "STYLE", "MASK")


@dataclass(frozen=True)
class Tile:
    suffix: str
    dx: int  # DBU
    dy: int  # DBU


def _point_offset(tokens: list[str], ox: int, oy: int, start: int = 0) -> list[str]:
    """Moves every absolute point ``( x y [ext] )`` from ``start`` on; ``*`` stays ``*``."""
    out = list(tokens)
    i = start
    while i < len(out):
        if out[i] == "(":
            j = out.index(")", i)
            vals = out[i + 1 : j]
            if 2 <= len(vals) <= 3 and all(v == "*" or is_int(v) for v in vals[:2]):
                if is_int(vals[0]):
                    out[i + 1] = str(int(vals[0]) + ox)
                if is_int(vals[1]):
                    out[i + 2] = str(int(vals[1]) + oy)
            i = j
        i += 1
    return out


def _component(entry: list[str], t: Tile) -> list[str]:
    out = _point_offset(entry, t.dx, t.dy)
    out[1] += t.suffix
    return out


def _io_pin(entry: list[str], t: Tile) -> list[str]:
    out = list(entry)
    out[1] += t.suffix
    for k in range(2, len(out) - 1):
        if out[k - 1] == "+" and out[k] == "NET":
            out[k + 1] += t.suffix
        elif out[k] in ("PLACED", "FIXED", "COVER") and out[k - 1] == "+" and out[k + 1] == "(":
            out[k + 2] = str(int(out[k + 2]) + t.dx)
            out[k + 3] = str(int(out[k + 3]) + t.dy)
    return out


def _net(entry: list[str], t: Tile) -> list[str]:
    out = list(entry)
    out[1] += t.suffix
    k = 2
    while k < len(out) and out[k] == "(":  # connections: ( comp pin ), ( PIN name ), ( * pin )
        if out[k + 1] == "PIN":
            out[k + 2] += t.suffix
        elif out[k + 1] != "*":
            out[k + 1] += t.suffix
        k = out.index(")", k) + 1
    return _point_offset(out, t.dx, t.dy, k)


def _blockage(entry: list[str], t: Tile) -> list[str]:
    out = _point_offset(entry, t.dx, t.dy)
    for k in range(1, len(out) - 1):
        if out[k] == "COMPONENT" and out[k - 1] == "+":
            out[k + 1] += t.suffix
    return out


def _special_groups(entry: list[str]) -> tuple[list[str], list[list[str]]]:
    """A special net as its head (``- name`` and connections) and its ``+`` groups."""
    k = 2
    while k < len(entry) and entry[k] == "(":
        k = entry.index(")", k) + 1
    groups: list[list[str]] = []
    for i in range(k, len(entry)):
        if entry[i] == "+" and not (i + 1 < len(entry) and entry[i + 1] in SUB_OPTIONS):
            groups.append([])
        if not groups:
            raise InputError(f"special net {entry[1]}: unexpected {entry[i]!r}")
        groups[-1].append(entry[i])
    return entry[:k], groups


def _special_nets(section: Section, tiles: list[Tile]) -> list[list[str]]:
    """One entry per special net name: the connections and options of the original, the wiring of every copy."""
    merged: list[list[str]] = []
    for entry in section.body:
        head, groups = _special_groups(entry)
        wiring = [g for g in groups if g[1] in WIRING]
        options = [tok for g in groups if g[1] not in WIRING for tok in g]
        out = list(head)
        for t in tiles:
            for g in wiring:
                out.extend(_point_offset(g, t.dx, t.dy))
        merged.append(out + options)
    return merged


def _lcm_steps(steps: list[int]) -> int:
    out = 1
    for s in steps:
        if s > 0:
            out = math.lcm(out, s)
    return out


def _guide_pitch(guides: list[GuideNet], axis: int) -> int:
    sizes = Counter(r[2 + axis] - r[axis] for net in guides for r in net.rects)
    sizes.pop(0, None)
    return min(sizes, key=lambda s: (-sizes[s], s)) if sizes else 0


def _offsets(d: DefText, guides: list[GuideNet], die: tuple[int, int, int, int]) -> tuple[int, int]:
    """(dx, dy): the die size rounded up to a multiple of every step that must line up across copies."""
    steps: dict[str, list[int]] = {"X": [], "Y": []}
    gcell: dict[str, tuple[int, int]] = {}  # axis -> (DO, STEP) of the GCELLGRID line with most cells
    for s in d.items:
        if isinstance(s, Section) or not s:
            continue
        if s[0] == "TRACKS":
            steps[s[1]].append(int(s[s.index("STEP") + 1]))
        elif s[0] == "ROW" and "STEP" in s:
            k = s.index("STEP")
            steps["X"].append(int(s[k + 1]))
            steps["Y"].append(int(s[k + 2]))
        elif s[0] == "GCELLGRID":
            do, step = int(s[4]), int(s[6])
            if do > gcell.get(s[1], (0, 0))[0]:
                gcell[s[1]] = (do, step)
    for axis, k in (("X", 0), ("Y", 1)):
        steps[axis].append(gcell[axis][1] if axis in gcell else _guide_pitch(guides, k))
    margin = 2 * max(steps["X"] + steps["Y"])  # keeps shapes at the die edges of neighbours apart
    w, h = die[2] - die[0] + margin, die[3] - die[1] + margin
    lx, ly = _lcm_steps(steps["X"]), _lcm_steps(steps["Y"])
    return -(-w // lx) * lx, -(-h // ly) * ly


def _die(d: DefText) -> tuple[int, int, int, int]:
    for s in d.items:
        if not isinstance(s, Section) and s and s[0] == "DIEAREA":
            pts = [int(v) for v in s if is_int(v)]
            if len(pts) != 4:
                raise XrouteError("tiling needs a rectangular DIEAREA (two points)")
            return pts[0], pts[1], pts[2], pts[3]
    raise XrouteError("the DEF has no DIEAREA")


def tile_def(d: DefText, guides: list[GuideNet], rows: int, cols: int, design: str) -> tuple[DefText, list[GuideNet]]:
    """The tiled DEF and guides (in memory)."""
    die = _die(d)
    dx, dy = _offsets(d, guides, die)
    tiles = [Tile(f"_r{i}_c{j}", j * dx, i * dy) for i in range(rows) for j in range(cols)]
    out = DefText()
    for item in d.items:
        if isinstance(item, Section):
            out.items.append(_tile_section(item, tiles))
            continue
        key = item[0] if item else ""
        if key == "DESIGN":
            out.items.append(["DESIGN", design])
        elif key == "DIEAREA":
            x1, y1 = die[0] + (cols - 1) * dx + die[2] - die[0], die[1] + (rows - 1) * dy + die[3] - die[1]
            out.items.append(["DIEAREA", "(", str(die[0]), str(die[1]), ")", "(", str(x1), str(y1), ")"])
        elif key == "TRACKS":
            s = list(item)
            k = s.index("DO")
            extra = (cols - 1) * dx if s[1] == "X" else (rows - 1) * dy
            s[k + 1] = str(int(s[k + 1]) + extra // int(s[k + 3]))
            out.items.append(s)
        elif key == "ROW":
            for t in tiles:
                s = list(item)
                s[1] += t.suffix
                s[3], s[4] = str(int(s[3]) + t.dx), str(int(s[4]) + t.dy)
                out.items.append(s)
        elif key == "GCELLGRID":
            seen = {tuple(s) for s in out.items if not isinstance(s, Section)}
            for t in tiles:
                s = list(item)
                s[2] = str(int(s[2]) + (t.dx if s[1] == "X" else t.dy))
                if tuple(s) not in seen:
                    out.items.append(s)
                    seen.add(tuple(s))
        else:
            out.items.append(list(item))
    tiled_guides = [
        GuideNet(g.name + t.suffix, [(x0 + t.dx, y0 + t.dy, x1 + t.dx, y1 + t.dy, layer) for x0, y0, x1, y1, layer in g.rects])
        for t in tiles
        for g in guides
    ]
    return out, tiled_guides


def _tile_section(section: Section, tiles: list[Tile]) -> Section:
    if section.name in COPY_ONCE:
        return section
    if section.name == "SPECIALNETS":
        return Section(section.name, list(section.header), _special_nets(section, tiles))
    per_entry = {"COMPONENTS": _component, "PINS": _io_pin, "NETS": _net, "BLOCKAGES": _blockage}.get(section.name)
    if per_entry is None:
        raise XrouteError(f"tiling does not handle the DEF section {section.name}")
    body = [per_entry(entry, t) for t in tiles for entry in section.body]
    header = list(section.header)
    if len(header) > 1 and is_int(header[1]):
        header[1] = str(len(body))
    return Section(section.name, header, body)


def parse_by(text: str) -> tuple[int, int]:
    """``"4x4"`` -> (4, 4): rows x columns, each 1..64."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.isdigit() for p in parts) or not all(1 <= int(p) <= 64 for p in parts):
        raise XrouteError(f"--by takes ROWSxCOLS with each 1..64 (e.g. 2x2), not {text!r}")
    return int(parts[0]), int(parts[1])


def tile_testcase(name: str, rows: int, cols: int, out_dir: str | Path) -> Path:
    """Writes the testcase ``name`` tiled rows x cols into the folder ``out_dir`` (named after it); returns it."""
    if rows < 1 or cols < 1:
        raise XrouteError("tiling needs at least one row and one column")
    found = find_testcase(name)
    folder = Path(out_dir)
    tiled = folder.resolve().name
    d = read_def_text(found.def_)
    guides = read_guides(found.guide) if found.guide else []
    out_def, out_guides = tile_def(d, guides, rows, cols, tiled)
    folder.mkdir(parents=True, exist_ok=True)
    atomic_copy(found.lef, folder / f"{tiled}.input.lef")
    atomic_write_text(folder / f"{tiled}.input.def", write_def_text(out_def))
    guide_path = folder / f"{tiled}.input.guide"
    if found.guide:
        atomic_write_text(guide_path, write_guides(out_guides))
    elif guide_path.exists():
        guide_path.unlink()
    return folder
