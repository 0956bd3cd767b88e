"""xroute's compiled engine (private; use the xroute_cli Python API)."""

from collections.abc import Sequence
from typing import Annotated

import numpy
from numpy.typing import NDArray


class Database:
    """A loaded design: technology (LEF) + design (DEF) + guides."""

    @property
    def design_name(self) -> str:
        """DESIGN name from the DEF."""

    @property
    def lef_paths(self) -> list[str]:
        """LEF files read, in order."""

    @property
    def def_path(self) -> str:
        """DEF file read."""

    @property
    def guide_path(self) -> str:
        """Guide file read, or ''."""

    @property
    def dbu_per_micron(self) -> int:
        """DEF UNITS DISTANCE MICRONS."""

    @property
    def lef_dbu_per_micron(self) -> int:
        """LEF UNITS DATABASE MICRONS."""

    @property
    def manufacturing_grid(self) -> int:
        """MANUFACTURINGGRID in DBU (0 if none)."""

    @property
    def die_area(self) -> tuple[int, int, int, int]:
        """DIEAREA bounding box (xlo, ylo, xhi, yhi) in DBU."""

    def counts(self) -> dict[str, int]:
        """Counts of everything read, by kind."""

    def skipped_statements(self) -> dict[str, int]:
        """Statements the readers skipped (not understood), keyword -> count."""

    @property
    def warning_count(self) -> int:
        """Warnings raised while reading (LEF + DEF)."""

    def layers(self) -> list:
        """Every LEF layer in order, as dicts (lengths in DBU, areas in DBU^2)."""

    def tracks(self) -> list:
        """DEF TRACKS statements as dicts (DBU)."""

    def gcell_lines(self, axis: str) -> NDArray[numpy.int32]:
        """
        GCell grid line coordinates along 'x' or 'y' (DBU, sorted); empty without GCELLGRID.
        """

    def net_names(self) -> list[str]:
        """Net names in DEF order (index = net id)."""

    def net_id(self, name: str) -> int:
        """Net id by name, -1 if absent."""

    @property
    def net_pin_start(self) -> Annotated[NDArray[numpy.int32], dict(writable=False)]:
        """int32[nets+1]: net i owns pin_refs[start[i]:start[i+1]]."""

    @property
    def pin_refs(self) -> Annotated[NDArray[numpy.int32], dict(writable=False)]:
        """
        int32[pins, 2]: (component id or -1 for an IO pin, macro pin index or IO pin id).
        """

    @property
    def guide_start(self) -> Annotated[NDArray[numpy.int32], dict(writable=False)]:
        """int32[nets+1] (empty without guides): net i owns guide rows."""

    @property
    def guide_rects(self) -> Annotated[NDArray[numpy.int32], dict(writable=False)]:
        """int32[guides, 4]: xlo, ylo, xhi, yhi in DBU."""

    @property
    def guide_layers(self) -> Annotated[NDArray[numpy.int32], dict(writable=False)]:
        """int32[guides]: LEF layer index of each guide."""

    def net_pins(self, net: int) -> list:
        """The pins of a net as (component, pin) pairs; IO pins as ('PIN', name)."""

    def net_pin_shapes(self, net: int) -> NDArray[numpy.int32]:
        """
        int32[shapes, 6]: (pin index within the net, LEF layer index, xlo, ylo, xhi, yhi) in DBU, placed.
        """

    def component(self, name: str) -> dict:
        """A component's macro, location (DBU), orientation and status."""

    def component_pin_shapes(self, component: str, pin: str) -> list:
        """
        A component pin's shapes placed in design coordinates: (layer, xlo, ylo, xhi, yhi).
        """

    def macro(self, name: str) -> dict:
        """
        A LEF macro: class, origin, size, pins (with shapes in macro coordinates, DBU) and OBS.
        """

    def via(self, name: str) -> dict:
        """
        A LEF VIA: default flag, bottom/cut/top layer names and shapes (layer, xlo, ylo, xhi, yhi) in DBU.
        """

    def via_rule(self, name: str) -> dict:
        """A LEF VIARULE: generate/default flags and its layers in order (DBU)."""

    def sites(self) -> list:
        """LEF SITEs in order: name, class, size (DBU), symmetry."""

    def macro_names(self) -> list[str]:
        """LEF macro names in order."""

    def def_via(self, name: str) -> dict:
        """
        A DEF VIAS entry: generated flag, rule, (rows, cols), layers and shapes (layer, xlo, ylo, xhi, yhi) in DBU.
        """

    def io_pin(self, name: str) -> dict:
        """
        A DEF PINS entry; shapes placed in design coordinates: (layer, xlo, ylo, xhi, yhi).
        """

    def special_net(self, name: str) -> dict:
        """
        A SPECIALNETS entry: pins, wires (layer, width, shape, x1, y1, x2, y2), vias (name, x, y, shape), rects (layer, xlo, ylo, xhi, yhi); DBU.
        """

    def net_routing(self, net: int) -> dict:
        """
        A net's routing: wires (layer, x1, y1, x2, y2, width, ext_from, ext_to; width 0 = default, ext -1 = half width), vias (name, x, y), patches (layer, xlo, ylo, xhi, yhi); DBU.
        """

    def write_def(self, path: str) -> None:
        """Writes the design as DEF (atomically: temporary file, then rename)."""

    def def_text(self) -> str:
        """The design as DEF text."""

    def compare(self, other: Database, max_diffs: int = 20) -> list[str]:
        """Differences between two designs (empty list = equal)."""

def load(lef_paths: Sequence[str], def_path: str, guide_path: str | None = None) -> Database:
    """
    Reads LEF files, a DEF and optionally a guide file. Raises xroute_cli.errors.InputError on bad input.
    """

def load_lef(lef_paths: Sequence[str]) -> Database:
    """
    Reads LEF files only (the design part stays empty). Raises InputError on bad input.
    """
