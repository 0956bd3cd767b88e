"""DEF and route-guide files as token statements, for tools that rewrite them (tiling).

This is not a DEF reader (the engine has that): it splits a file into statements of
whitespace-separated tokens, keeps sections together and knows just enough of the
grammar to move points and rename things. Coordinates are DEF database units (DBU).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from xroute.errors import InputError

_TOKEN = re.compile(r'"[^"]*"|[^\s"]+')
# Sections whose body is a list of "- ... ;" entries (or statements) closed by "END <name>".
SECTIONS = (
    "PROPERTYDEFINITIONS", "VIAS", "NONDEFAULTRULES", "STYLES", "COMPONENTS", "PINS", "PINPROPERTIES",
    "BLOCKAGES", "SLOTS", "FILLS", "SPECIALNETS", "NETS", "SCANCHAINS", "GROUPS", "REGIONS",
    "COMPONENTMASKSHIFT", "CONSTRAINTS", "ASSERTIONS", "IOTIMINGS", "FLOORPLANCONSTRAINTS",
    "TIMINGDISABLES", "EXTENSION",
)


@dataclass
class Section:
    """One DEF section: its header tokens (``NETS 3153``) and its statements."""

    name: str
    header: list[str]
    body: list[list[str]] = field(default_factory=list)


@dataclass
class DefText:
    """A DEF file as top-level statements (token lists without ';') and sections, in file order."""

    items: list[list[str] | Section] = field(default_factory=list)


def is_int(token: str) -> bool:
    return token.lstrip("-").isdigit()


def read_def_text(path: Path) -> DefText:
    """Splits a DEF file into statements; raises InputError on an unclosed section or statement."""
    text = path.read_text()
    lines = [line.split("#", 1)[0] if '"' not in line else line for line in text.splitlines()]
    tokens = _TOKEN.findall("\n".join(lines))
    out = DefText()
    current: Section | None = None
    stmt: list[str] = []
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if not stmt and tok == "END" and i + 1 < len(tokens):
            nxt = tokens[i + 1]
            if current is not None and nxt == current.name:
                out.items.append(current)
                current = None
                i += 2
                continue
            if current is None and nxt == "DESIGN":
                break
        if tok == ";":
            if current is None and stmt and stmt[0] in SECTIONS:
                current = Section(stmt[0], stmt)
            elif current is not None:
                current.body.append(stmt)
            else:
                out.items.append(stmt)
            stmt = []
        else:
            stmt.append(tok)
        i += 1
    if current is not None or stmt:
        raise InputError(f"unterminated {'section ' + current.name if current else 'statement'}", str(path))
    return out


def format_statement(tokens: list[str]) -> str:
    """One statement as text; a long entry breaks its line before each '+' and 'NEW'."""
    out = " ".join(tokens)
    if len(tokens) > 12:
        out = " ".join(("\n   " + t) if t in ("+", "NEW") and k else t for k, t in enumerate(tokens))
        out = out.replace(" \n", "\n")
    return out + " ;"


def write_def_text(d: DefText) -> str:
    out: list[str] = []
    for item in d.items:
        if isinstance(item, Section):
            out.append(format_statement(item.header))
            out.extend(format_statement(s) for s in item.body)
            out.append(f"END {item.name}")
            out.append("")
        else:
            out.append(format_statement(item))
    out.append("END DESIGN")
    return "\n".join(out) + "\n"


@dataclass
class IoPin:
    """An IO pin of a generated design: one shape on one layer, placed at (x, y)."""

    name: str
    direction: str  # INPUT or OUTPUT
    layer: str
    rect: tuple[int, int, int, int]  # DBU, relative to (x, y)
    x: int
    y: int

    @property
    def center(self) -> tuple[int, int]:
        return self.x + (self.rect[0] + self.rect[2]) // 2, self.y + (self.rect[1] + self.rect[3]) // 2


def components_and_pins(comps: list, ios: list[IoPin], net_of_io: dict[str, str]) -> list[str]:
    """The COMPONENTS and PINS sections of a generated design's DEF (``comps``: objects with name,
    cell.name, x, y and orient; every IO pin's net by its name)."""
    out = [f"COMPONENTS {len(comps)} ;"]
    out += [f"- {p.name} {p.cell.name} + PLACED ( {p.x} {p.y} ) {p.orient} ;" for p in comps]
    out += ["END COMPONENTS", "", f"PINS {len(ios)} ;"]
    for io in ios:
        x0, y0, x1, y1 = io.rect
        out.append(f"- {io.name} + NET {net_of_io[io.name]} + DIRECTION {io.direction} + USE SIGNAL")
        out.append(f"  + LAYER {io.layer} ( {x0} {y0} ) ( {x1} {y1} ) + PLACED ( {io.x} {io.y} ) N ;")
    return out + ["END PINS", ""]


@dataclass
class GuideNet:
    name: str
    rects: list[tuple[int, int, int, int, str]]  # xlo, ylo, xhi, yhi (DBU), layer name


def read_guides(path: Path) -> list[GuideNet]:
    """ISPD route guides: ``net`` ``(`` ``xlo ylo xhi yhi layer`` ... ``)`` per net."""
    nets: list[GuideNet] = []
    cur: GuideNet | None = None
    for lineno, raw in enumerate(path.read_text().splitlines(), 1):
        words = raw.split()
        if not words:
            continue
        if words == ["("]:
            if cur is None:
                raise InputError("'(' without a net name", str(path), lineno)
        elif words == [")"]:
            cur = None
        elif len(words) == 1:
            cur = GuideNet(words[0], [])
            nets.append(cur)
        elif len(words) == 5 and cur is not None and all(is_int(w) for w in words[:4]):
            x0, y0, x1, y1 = (int(w) for w in words[:4])
            cur.rects.append((x0, y0, x1, y1, words[4]))
        else:
            raise InputError(f"unexpected guide line {raw.strip()!r}", str(path), lineno)
    return nets


def write_guides(nets: list[GuideNet]) -> str:
    out: list[str] = []
    for net in nets:
        out.append(net.name)
        out.append("(")
        out.extend(f"{x0} {y0} {x1} {y1} {layer}" for x0, y0, x1, y1, layer in net.rects)
        out.append(")")
    return "\n".join(out) + "\n"
