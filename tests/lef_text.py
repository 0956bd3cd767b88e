"""LEF text for drawn tests, built from parts instead of copied from file to file.

Imported as ``from lef_text import ...`` (pytest puts tests/ on ``sys.path``). Lengths are in
microns, as LEF writes them (``DATABASE MICRONS 1000``: 0.001 = 1 DBU). A test's LEF is
``library(*parts)``; the parts are statements of the LEF reference:

* :func:`routing` / :func:`cut`: a layer, with any further rule lines (``"AREA 0.05 ;"``);
* :func:`stack`: the usual drawn stack M1 (horizontal), V1, M2 (vertical), V2, M3 (horizontal)
  and its default vias V12 and V23, each via's metal one wire wide, one via-width long;
* :func:`via`, :func:`site`, :func:`macro` with :func:`pin` ports and obstructions.
"""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Iterable

Rect = tuple[float, float, float, float]  # xlo, ylo, xhi, yhi in microns
Shapes = Iterable[tuple[str, Rect]]  # (layer, rect) pairs; consecutive rects on one layer share its LAYER line

# A 35-line technology LEF: UNITS 1000, SITE core, layers M1 V1 M2, VIA V12 (the LEF reader's tests).
TECH_LEF = Path(__file__).resolve().parent / "data" / "lef" / "tech.lef"
TECH = TECH_LEF.read_text()

HEADER = 'VERSION 5.8 ;\nBUSBITCHARS "[]" ;\nDIVIDERCHAR "/" ;\nUNITS\n  DATABASE MICRONS 1000 ;\nEND UNITS\n'


def _num(v: float) -> str:
    return f"{v:g}"


def _rect(r: Rect) -> str:
    return "RECT " + " ".join(_num(v) for v in r) + " ;"


def _shapes(shapes: Shapes, indent: str) -> str:
    out, last = [], None
    for layer, rect in shapes:
        if layer != last:
            out.append(f"{indent}LAYER {layer} ;")
            last = layer
        out.append(f"{indent}  {_rect(rect)}")
    return "\n".join(out) + "\n"


def library(*parts: str, grid: float | None = 0.001, header: Iterable[str] = ()) -> str:
    """A whole LEF: the header (units 1000 per micron, ``MANUFACTURINGGRID grid`` unless None,
    then the ``header`` lines), the parts in order, ``END LIBRARY``."""
    head = HEADER + (f"MANUFACTURINGGRID {grid} ;\n" if grid is not None else "")
    head += "".join(line + "\n" for line in header)
    return head + "".join(parts) + "END LIBRARY\n"


def routing(name: str, direction: str, pitch: float, width: float, spacing: float | None = None,
            rules: Iterable[str] = ()) -> str:
    """``LAYER name`` of TYPE ROUTING; ``rules`` are further lines inside it."""
    lines = [f"LAYER {name}", "  TYPE ROUTING ;", f"  DIRECTION {direction} ;", f"  PITCH {_num(pitch)} ;",
             f"  WIDTH {_num(width)} ;"]
    if spacing is not None:
        lines.append(f"  SPACING {_num(spacing)} ;")
    lines += [f"  {r}" for r in rules]
    return "\n".join(lines) + f"\nEND {name}\n"


def cut(name: str, width: float | None = None, spacing: float | None = None, rules: Iterable[str] = ()) -> str:
    """``LAYER name`` of TYPE CUT; ``rules`` are further lines inside it."""
    lines = [f"LAYER {name}", "  TYPE CUT ;"]
    if width is not None:
        lines.append(f"  WIDTH {_num(width)} ;")
    if spacing is not None:
        lines.append(f"  SPACING {_num(spacing)} ;")
    lines += [f"  {r}" for r in rules]
    return "\n".join(lines) + f"\nEND {name}\n"


def via(name: str, shapes: Shapes, default: bool = True) -> str:
    """``VIA name [DEFAULT]`` with its shapes, bottom metal, cut, top metal."""
    return f"VIA {name}{' DEFAULT' if default else ''}\n" + _shapes(shapes, "  ") + f"END {name}\n"


def stack_via(name: str, bottom: str, cut_layer: str, top: str, bottom_horizontal: bool, width: float,
              cut_width: float | None = None, metal_length: float | None = None) -> str:
    """A default via whose cut is ``cut_width`` square (default: ``width``) and whose metals are
    ``width`` wide and ``metal_length`` long (default: ``width``) along each metal's direction."""
    w, c = width / 2, (cut_width if cut_width is not None else width) / 2
    length = (metal_length if metal_length is not None else width) / 2
    along_x: Rect = (-length, -w, length, w)
    along_y: Rect = (-w, -length, w, length)
    return via(name, [(bottom, along_x if bottom_horizontal else along_y), (cut_layer, (-c, -c, c, c)),
                      (top, along_y if bottom_horizontal else along_x)])


def stack(pitch: float = 0.2, width: float = 0.06, spacing: float | None = 0.07, cut_width: float | None = 0.06,
          cut_spacing: float | None = 0.08, via_metal_length: float | None = 0.1, layers: int = 3,
          rules: dict[str, Iterable[str]] | None = None) -> str:
    """The drawn stack: routing layers M1 .. M<layers> (M1 horizontal, then alternating), the cut
    layers V1 .. between them, and the default vias V12, V23, ... (``rules``: extra lines by layer
    name). Defaults: pitch 0.2, width 0.06, spacing 0.07, cuts 0.06 wide at 0.08."""
    rules = rules or {}
    parts, vias = [], []
    for k in range(1, layers + 1):
        horizontal = k % 2 == 1
        parts.append(routing(f"M{k}", "HORIZONTAL" if horizontal else "VERTICAL", pitch, width, spacing,
                             rules.get(f"M{k}", ())))
        if k < layers:
            parts.append(cut(f"V{k}", cut_width, cut_spacing, rules.get(f"V{k}", ())))
            vias.append(stack_via(f"V{k}{k + 1}", f"M{k}", f"V{k}", f"M{k + 1}", horizontal,
                                  width, cut_width, via_metal_length))
    return "".join(parts + vias)


def site(name: str, width: float, height: float, klass: str = "CORE") -> str:
    return f"SITE {name}\n  CLASS {klass} ;\n  SIZE {_num(width)} BY {_num(height)} ;\nEND {name}\n"


def pin(name: str, direction: str, *ports: Shapes, use: str | None = "SIGNAL") -> str:
    """``PIN name`` with one ``PORT`` per argument after ``direction``."""
    lines = [f"  PIN {name}", f"    DIRECTION {direction} ;"] + ([f"    USE {use} ;"] if use else [])
    text = "\n".join(lines) + "\n"
    for shapes in ports:
        text += "    PORT\n" + _shapes(shapes, "      ") + "    END\n"
    return text + f"  END {name}\n"


def macro(name: str, width: float, height: float, *pins: str, site_name: str | None = None,
          obs: Shapes = (), klass: str = "CORE") -> str:
    """``MACRO name`` of the given size (origin 0 0) with its pins and obstructions."""
    text = f"MACRO {name}\n  CLASS {klass} ;\n  ORIGIN 0 0 ;\n  SIZE {_num(width)} BY {_num(height)} ;\n"
    if site_name is not None:
        text += f"  SITE {site_name} ;\n"
    text += "".join(pins)
    obs = list(obs)
    if obs:
        text += "  OBS\n" + _shapes(obs, "    ") + "  END\n"
    return text + f"END {name}\n"


def write_lef(tmp_path: Path, text: str, name: str = "t.lef") -> str:
    """Writes ``text`` (dedented, leading newlines dropped) to ``tmp_path/name``; returns the path."""
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip("\n"))
    return str(path)
