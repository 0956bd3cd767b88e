"""The Python view of a loaded design (LEF + DEF + guides).

Everything is in DEF database units (DBU) unless a name says otherwise. Large
per-net arrays are zero-copy numpy views into the engine's database; they stay
valid as long as the :class:`Design` (or the view) is alive.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from xroute.errors import InputError

# Rules in Design.unjudged_rules() that the router reads although no marker judges them.
ROUTER_ONLY_RULES = frozenset({"MINWIDTH"})


def _engine():
    from xroute import _engine as engine  # compiled module; imported on first use

    return engine


@dataclass(frozen=True)
class LayerInfo:
    """One LEF layer. Lengths in DBU, ``min_area`` in DBU²."""

    index: int  # LEF layer index (the value in guide_layers / shape arrays)
    name: str
    type: str  # ROUTING, CUT, MASTERSLICE, ...
    routing_index: int  # 0.. over routing layers, -1 otherwise
    direction: str  # HORIZONTAL, VERTICAL or ""
    pitch: tuple[int, int]
    offset: tuple[int, int]
    width: int
    min_width: int
    min_area: int
    min_spacing: int
    rules: dict[str, Any]  # spacing_table, eol_rules, spacing_rules, cut/corner rules, properties


class Design:
    """A loaded design. Build one with :func:`load_design`."""

    def __init__(self, db: Any, testcase: str | None = None) -> None:
        self._db = db
        self.testcase = testcase
        self._layers: list[LayerInfo] | None = None
        self._net_names: list[str] | None = None
        # Set by xroute.groute.global_route when the guides come from the built-in global router.
        self.global_route_stats: Any = None

    # -- identity -----------------------------------------------------------
    @property
    def name(self) -> str:
        """DESIGN name from the DEF."""
        return self._db.design_name

    @property
    def lef_paths(self) -> list[str]:
        return list(self._db.lef_paths)

    @property
    def def_path(self) -> str:
        return self._db.def_path

    @property
    def guide_path(self) -> str | None:
        return self._db.guide_path or None

    @property
    def dbu_per_micron(self) -> int:
        return self._db.dbu_per_micron

    @property
    def die_area(self) -> tuple[int, int, int, int]:
        """(xlo, ylo, xhi, yhi) in DBU."""
        return tuple(self._db.die_area)

    @property
    def engine(self) -> Any:
        """The underlying engine object (``xroute._engine.Database``)."""
        return self._db

    # -- counts and summaries ---------------------------------------------
    def counts(self) -> dict[str, int]:
        """Counts of everything read: layers, macros, components, nets, pins, guides, ..."""
        return dict(self._db.counts())

    def skipped_statements(self) -> dict[str, int]:
        """LEF/DEF statements the readers did not understand and skipped, by keyword."""
        return dict(self._db.skipped_statements())

    def unjudged_rules(self) -> list[dict[str, Any]]:
        """The rules the LEF states on metal and cut layers that the checker does not judge, one
        entry per rule in the order first read: ``{"rule": "MINSTEP", "layers": ["M1", "M2"]}``
        (skipped statements and forms, LEF58 properties it does not model, rules kept for the
        router only such as MINWIDTH; electrical properties are no rules and are not listed)."""
        by_rule: dict[str, list[str]] = {}
        for layer, rule in self._db.unjudged_rules():
            by_rule.setdefault(rule, []).append(layer)
        return [{"rule": rule, "layers": layers} for rule, layers in by_rule.items()]

    def unmodelled_rules(self) -> list[dict[str, Any]]:
        """:meth:`unjudged_rules` less those the router reads (MINWIDTH sizes its pin access and
        wires): the rules neither the router nor the checker models, as ``xroute route`` warns of them."""
        return [r for r in self.unjudged_rules() if r["rule"] not in ROUTER_ONLY_RULES]

    def warnings(self) -> list[str]:
        """Odd but readable things the readers found (LEF then DEF), one 'file:line: message' each."""
        return list(self._db.warnings())

    @property
    def warning_count(self) -> int:
        """Warnings raised while reading: one per LEF statement skipped, one per DEF item kept only
        approximately (a polygon as its bounding box, a dropped via orientation, ...)."""
        return int(self._db.warning_count)

    @property
    def layers(self) -> list[LayerInfo]:
        if self._layers is None:
            out = []
            for i, d in enumerate(self._db.layers()):
                rules = {
                    k: d[k]
                    for k in (
                        "spacing_table",
                        "spacing_rules",
                        "eol_rules",
                        "corner_spacing_rules",
                        "cut_spacing_rules",
                        "properties",
                    )
                }
                out.append(
                    LayerInfo(
                        index=i,
                        name=d["name"],
                        type=d["type"],
                        routing_index=d["routing_index"],
                        direction=d["direction"],
                        pitch=tuple(d["pitch"]),
                        offset=tuple(d["offset"]),
                        width=d["width"],
                        min_width=d["min_width"],
                        min_area=d["min_area"],
                        min_spacing=d["min_spacing"],
                        rules=rules,
                    )
                )
            self._layers = out
        return self._layers

    @property
    def routing_layers(self) -> list[LayerInfo]:
        return [layer for layer in self.layers if layer.type == "ROUTING"]

    @property
    def cut_layers(self) -> list[LayerInfo]:
        return [layer for layer in self.layers if layer.type == "CUT"]

    def layer(self, name: str) -> LayerInfo:
        for layer in self.layers:
            if layer.name == name:
                return layer
        raise KeyError(f"no layer named {name}")

    def tracks(self) -> list[dict[str, Any]]:
        """DEF TRACKS: dicts with layer, axis ('X' = vertical lines at x), start, count, step."""
        return list(self._db.tracks())

    def gcell_lines(self, axis: str) -> np.ndarray:
        """GCell grid line coordinates along 'x' or 'y' (DBU); empty without GCELLGRID."""
        return self._db.gcell_lines(axis)

    def gcell_grid_size(self) -> tuple[int, int]:
        """Number of GCells along x and y (0, 0 without GCELLGRID)."""
        xs, ys = self.gcell_lines("x"), self.gcell_lines("y")
        return (max(len(xs) - 1, 0), max(len(ys) - 1, 0))

    # -- nets, pins and guides ---------------------------------------------
    @property
    def net_names(self) -> list[str]:
        if self._net_names is None:
            self._net_names = list(self._db.net_names())
        return self._net_names

    @property
    def num_nets(self) -> int:
        return len(self.net_names)

    def net_id(self, net: str | int) -> int:
        if isinstance(net, (int, np.integer)):
            if not 0 <= int(net) < self.num_nets:
                raise IndexError(f"net index {net} out of range 0..{self.num_nets - 1}")
            return int(net)
        nid = self._db.net_id(net)
        if nid < 0:
            raise KeyError(f"no net named {net}")
        return nid

    @property
    def net_pin_start(self) -> np.ndarray:
        """int32[nets+1]: net i owns ``pin_refs[net_pin_start[i]:net_pin_start[i+1]]``."""
        return self._db.net_pin_start

    @property
    def pin_refs(self) -> np.ndarray:
        """int32[pins, 2]: (component id, macro pin index), or (-1, IO pin id)."""
        return self._db.pin_refs

    def pins_per_net(self) -> np.ndarray:
        return np.diff(self.net_pin_start)

    def net_pins(self, net: str | int) -> list[tuple[str, str]]:
        """A net's pins as (component, pin); IO pins as ('PIN', name)."""
        return [tuple(p) for p in self._db.net_pins(self.net_id(net))]

    def net_pin_shapes(self, net: str | int) -> np.ndarray:
        """int32[shapes, 6]: (pin index in net, layer index, xlo, ylo, xhi, yhi), placed, DBU."""
        return self._db.net_pin_shapes(self.net_id(net))

    @property
    def has_guides(self) -> bool:
        return len(self._db.guide_start) > 0

    @property
    def guide_source(self) -> str:
        """Where the guides came from: "file", "built-in" (the global router) or "none"."""
        if self.global_route_stats is not None:
            return "built-in"
        return "file" if self.has_guides else "none"

    @property
    def guide_start(self) -> np.ndarray:
        """int32[nets+1] (empty without guides)."""
        return self._db.guide_start

    @property
    def guide_rects(self) -> np.ndarray:
        """int32[guides, 4]: xlo, ylo, xhi, yhi (DBU)."""
        return self._db.guide_rects

    @property
    def guide_layers(self) -> np.ndarray:
        """int32[guides]: LEF layer index of each guide."""
        return self._db.guide_layers

    def net_guides(self, net: str | int) -> tuple[np.ndarray, np.ndarray]:
        """(rects int32[k, 4], layer indices int32[k]) of one net's guides."""
        if not self.has_guides:
            return np.zeros((0, 4), np.int32), np.zeros(0, np.int32)
        i = self.net_id(net)
        lo, hi = int(self.guide_start[i]), int(self.guide_start[i + 1])
        return self.guide_rects[lo:hi], self.guide_layers[lo:hi]

    # -- cells ---------------------------------------------------------------
    def component(self, name: str) -> dict[str, Any]:
        return dict(self._db.component(name))

    def component_pin_shapes(self, component: str, pin: str) -> list[tuple[str, int, int, int, int]]:
        """A component pin's shapes in design coordinates: (layer, xlo, ylo, xhi, yhi)."""
        return [tuple(s) for s in self._db.component_pin_shapes(component, pin)]

    def macro(self, name: str) -> dict[str, Any]:
        return dict(self._db.macro(name))

    @property
    def macro_names(self) -> list[str]:
        return list(self._db.macro_names())

    # -- vias, IO pins, special nets and routing -----------------------------
    def via(self, name: str) -> dict[str, Any]:
        """A LEF VIA: ``name``, ``default``, ``bottom``/``cut``/``top`` layer names and
        ``shapes`` as (layer, xlo, ylo, xhi, yhi) in DBU. KeyError if absent."""
        return dict(self._db.via(name))

    def via_rule(self, name: str) -> dict[str, Any]:
        """A LEF VIARULE: ``generate``/``default`` flags and its ``layers`` in order (DBU). KeyError if absent."""
        return dict(self._db.via_rule(name))

    def sites(self) -> list[dict[str, Any]]:
        """LEF SITEs in order: ``name``, ``class``, ``size`` (DBU), ``symmetry``."""
        return [dict(s) for s in self._db.sites()]

    def routed_via_shapes(self, name: str) -> list[tuple[str, int, int, int, int]]:
        """Shapes of the via a net's routing names, as (layer, xlo, ylo, xhi, yhi) in DBU relative to its
        origin: the DEF VIAS entry of that name, else the LEF VIA (the DEF reader's order). KeyError if neither."""
        try:
            return list(self._db.def_via(name)["shapes"])
        except KeyError:
            return list(self._db.via(name)["shapes"])

    def def_via(self, name: str) -> dict[str, Any]:
        """A DEF VIAS entry: ``generated``, ``rule``, ``rowcol``, ``bottom``/``cut``/``top``
        layer names and ``shapes`` as (layer, xlo, ylo, xhi, yhi) in DBU. KeyError if absent."""
        return dict(self._db.def_via(name))

    def io_pin(self, name: str) -> dict[str, Any]:
        """A DEF PINS entry: ``net``, ``net_id``, ``direction``, ``use``, ``status``, ``location``,
        ``orient`` and ``shapes`` placed in design coordinates (layer, xlo, ylo, xhi, yhi). KeyError if absent."""
        return dict(self._db.io_pin(name))

    def special_net(self, name: str) -> dict[str, Any]:
        """A SPECIALNETS entry: ``use``, ``pins`` (component, pin), ``wires`` (layer, width, shape,
        x1, y1, x2, y2), ``vias`` (name, x, y, shape), ``rects`` (layer, xlo, ylo, xhi, yhi); DBU.
        KeyError if absent."""
        return dict(self._db.special_net(name))

    def net_routing(self, net: str | int) -> dict[str, Any]:
        """A net's routing: ``wires`` (layer, x1, y1, x2, y2, width, ext_from, ext_to; width 0 =
        default, ext -1 = half width), ``vias`` (name, x, y), ``patches`` (layer, xlo, ylo, xhi, yhi); DBU."""
        return dict(self._db.net_routing(self.net_id(net)))

    # -- output ----------------------------------------------------------------
    def write_def(self, path: str | os.PathLike[str]) -> Path:
        """Writes the design (with any routing) as DEF, atomically."""
        path = Path(path)
        self._db.write_def(str(path))
        return path

    def def_text(self) -> str:
        return self._db.def_text()

    def compare(self, other: "Design", max_diffs: int = 20) -> list[str]:
        """Differences between this design and another (empty = same database)."""
        return list(self._db.compare(other._db, max_diffs))

    def __repr__(self) -> str:
        c = self.counts()
        return (
            f"<Design {self.name}: {c['components']} components, {c['nets']} nets, "
            f"{c['routing_layers']} routing layers, {c['guides']} guides>"
        )


def _check_file(path: str | os.PathLike[str], what: str) -> str:
    """``path`` as text if it is a regular file (a FIFO would block the reader): InputError otherwise."""
    from xroute.regular_files import check_input

    return check_input(path, f"{what} file")


def load_design(
    testcase: str | None = None,
    *,
    lef: str | os.PathLike[str] | Sequence[str | os.PathLike[str]] | None = None,
    def_: str | os.PathLike[str] | None = None,
    guide: str | os.PathLike[str] | None = None,
    use_guide: bool = True,
) -> Design:
    """Loads a design by testcase name (through the search path) or by explicit paths.

    ``load_design("ispd18_test1")`` finds ``ispd18_test1.input.{lef,def,guide}``
    in the first folder of the search path that holds them (see
    :func:`testcases.find_testcase`). ``load_design(lef=..., def_=..., guide=...)``
    reads the given files. Raises :class:`InputError` (file and line) on bad input.
    """
    if testcase is not None:
        if lef is not None or def_ is not None:
            raise ValueError("give either a testcase name or lef=/def_= paths, not both")
        from xroute.testcases.registry import find_testcase

        found = find_testcase(testcase)
        lef_paths = [str(found.lef)]
        def_path = str(found.def_)
        guide_path = str(found.guide) if (use_guide and found.guide is not None) else None
        name = found.name
    else:
        if lef is None or def_ is None:
            raise ValueError("load_design needs a testcase name, or both lef= and def_=")
        lefs = [lef] if isinstance(lef, (str, os.PathLike)) else list(lef)
        lef_paths = [_check_file(p, "LEF") for p in lefs]
        def_path = _check_file(def_, "DEF")
        guide_path = _check_file(guide, "guide") if guide is not None else None
        name = None
    db = _engine().load(lef_paths, def_path, guide_path)
    return Design(db, testcase=name)
