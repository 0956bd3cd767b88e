"""xroute's compiled engine (private; use the xroute Python API)."""

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

    def unjudged_rules(self) -> list[tuple[str, str]]:
        """
        The rules the LEF states on metal and cut layers that the checker does not judge, as (layer, rule) pairs in LEF order: skipped statements and forms (MINSTEP, SPACING NOTCHLENGTH, SPACINGTABLE TWOWIDTHS, ...), LEF58 properties other than the corner spacing it models, and rules kept for the router only (MINWIDTH, SPACING SAMENET).
        """

    @property
    def warning_count(self) -> int:
        """Warnings raised while reading (LEF + DEF)."""

    def warnings(self) -> list[str]:
        """
        Odd but routable things found after reading, one 'file:line: message' each.
        """

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

    def trim_dangling(self) -> dict:
        """
        Cuts every net's routing back to what joins its pins, as the flow does after each iteration:
        a wire's end past the last thing it meets on its centre line (another wire or via of the net,
        or a pin shape) goes back to it, or the wire goes; a via with nothing on one of its layers
        goes; then a patch touching none of the net's metal goes. Returns {wires (removed), shortened,
        vias, patches, length_dbu (centre line removed)}.
        """

    def write_def(self, path: str) -> None:
        """Writes the design as DEF (atomically: temporary file, then rename)."""

    def def_text(self) -> str:
        """The design as DEF text."""

    def compare(self, other: Database, max_diffs: int = 20) -> list[str]:
        """Differences between two designs (empty list = equal)."""

    def check_drc(self, skip_fixed_pairs: bool = True, window: tuple[int, int, int, int] | None = None, band_shapes: int = 2000000, threads: int = 1) -> list:
        """
        Design-rule check of the whole design (pins, OBS, blockages, special and regular routing).
        Net ids in the markers: regular nets 0..nets-1, special nets next, then pins on no net;
        -1 = obstruction. Same marker dicts as check_shapes. band_shapes: a design of more shapes
        is checked in horizontal bands of about this many (0: at once; not with skip_fixed_pairs off
        or a window); threads: layers checked at once. Neither changes the markers.
        """

    def drc_shapes(self) -> list:
        """
        The shapes check_drc checks: (layer index, xlo, ylo, xhi, yhi, net, origin) tuples.
        """

    def check_connectivity(self) -> dict:
        """
        Opens check of every regular net with >= 2 pins: are its pins joined by its routing?

        Conductors: pin shapes (one node per pin), wires (half-width or given extensions), vias (one node
        each), patches; same-layer shapes connect when they overlap or share an edge segment (a corner
        point does not), layers connect only through vias. Returns {nets_checked, open_nets,
        single_pin_nets (fewer than 2 pins, not checked), unrouted_nets (checked nets without routing),
        floating_pieces (routing components touching no pin), opens: [{net, pins, groups, floating_pieces}]}
        where groups lists the connected pin groups, each a list of (component, pin) names
        (("PIN", name) for an IO pin), groups ordered by their first pin in the net.
        """

    def metrics(self) -> dict:
        """
        Routing metrics of the regular nets: {wirelength_dbu (sum of wire piece lengths, extensions not
        counted), wirelength_um, wirelength_by_layer {routing layer: DBU}, vias (instances),
        vias_by_cut_layer {cut layer: count}, nets_routed (nets with any routing)}.
        """

    def check_routing(self, skip_fixed_pairs: bool = True, report_path: str = '', threads: int = 1) -> dict:
        """
        Everything a routed design is judged on, in one call (the engine side of `xroute check`); with
        report_path, also writes the markers found as write_drc_report does (no second check). threads:
        layers checked at once (the result does not depend on it).

        Regular nets (NETS) only, except the markers (the whole design, as check_drc). Returns {opens
        (open nets), connectivity (check_connectivity's dict), markers (check_drc's list),
        wirelength_dbu/_um and vias (as metrics), wrong_way_wirelength_dbu/_um, off_track_wirelength_dbu/
        _um, off_track_vias, scorer_pitch_dbu (the contest score's unit of length: the LEF PITCH of the
        second routing layer), has_guides, out_of_guide_wirelength_dbu/_um and out_of_guide_vias (None
        without a guide file)}. A wire piece (from != to; length |to - from|, extensions not counted) is
        wrong-way when it runs across its layer's DIRECTION; off-track when its centre line lies on no
        track line of its layer parallel to it (TRACKS Y lines for a horizontal piece, TRACKS X for a
        vertical one; a layer with no such lines counts none); out-of-guide for the part of its centre
        line outside the union of its net's guides on its layer (closed rects). A via is off-track when
        its point is off the preferred-direction tracks of its bottom or top metal layer (y on a TRACKS Y
        line of a horizontal layer, x on a TRACKS X line of a vertical one), and out-of-guide when no
        guide of its net on its bottom metal, or none on its top metal, contains its point.
        """

    def write_drc_report(self, path: str, skip_fixed_pairs: bool = True, threads: int = 1) -> dict:
        """
        Design-rule check of the whole design (as check_drc), written to `path` atomically (threads:
        layers checked at once, the result does not depend on it): a header
        '# markers N <type> <count> ...' then one line per marker '<type> <layer> <xlo> <ylo> <xhi> <yhi>
        <net1> <net2>' (DBU; net names, '-' for none or an obstruction; pins on no net as comp/pin,
        */pin or PIN/name). Returns {marker type: count} for every type. Raises InputError when the
        file cannot be written (nothing is left behind).
        """

    def pin_access(self, max_points_per_pin: int = 6, threads: int = 1, share_classes: bool = True, check_in_context: bool = True) -> dict:
        """
        Access points of every net pin (every entry of pin_refs), best first.

        Returns a dict:
          start: int32[pin_refs + 1]; pin ref i owns rows start[i] .. start[i+1] of points.
          points: int32[n, 5] rows (x, y, z, dirs, cost): x, y in DBU; z = routing layer index;
            dirs = OR of ACCESS_UP (1), ACCESS_EAST (2), ACCESS_WEST (4), ACCESS_NORTH (8),
            ACCESS_SOUTH (16); cost: 0 = on-track in x and y, 1 per half-track coordinate, 2 per
            shape-centre coordinate, 3 per enclosed-edge coordinate, +8 when only planar exits are
            legal on a layer with vias up, 100 = fallback (no legal point found).
          via: int32[n], LEF via index (into via_names) of the ACCESS_UP exit, -1 for none.
          via_names: list of every LEF via name, by index.
          fallback_pins: number of pin refs whose only point is a fallback.
          classes: number of component classes computed (same macro, orientation and track phase).
        threads > 1 splits the classes over worker threads; the result is the same.
        share_classes=False computes every component on its own (slow; to check the classes):
        the points are the same, classes is then the number of components with net pins.
        check_in_context=True checks each component pin's access vias again against the shapes its class
        did not see (neighbouring cells, special nets, blockages): one too close loses ACCESS_UP (+8 cost).
        """

def load(lef_paths: Sequence[str], def_path: str, guide_path: str | None = None) -> Database:
    """
    Reads LEF files, a DEF and optionally a guide file. Raises xroute.errors.InputError on bad input.
    """

def load_lef(lef_paths: Sequence[str]) -> Database:
    """
    Reads LEF files only (the design part stays empty). Raises InputError on bad input.
    """

MARKER_TYPES: tuple = ...

def check_shapes(db: Database, shapes: Annotated[NDArray[numpy.int32], dict(shape=(None, None), order='C', device='cpu', writable=False)], origins: Annotated[NDArray[numpy.int32], dict(shape=(None,), order='C', device='cpu', writable=False)] | None = None, skip_fixed_pairs: bool = False, window: tuple[int, int, int, int] | None = None) -> list:
    """
    Design-rule check of a set of shapes against the technology of `db`.

    shapes: int32[N, 6] rows (LEF layer index, xlo, ylo, xhi, yhi, net) in DBU; net < 0 marks an
    obstruction. origins: optional int[N], 0 wire, 1 via, 2 pin, 3 obstruction, 4 special net
    (default: 3 for net < 0, else 0). skip_fixed_pairs drops violations among pins, obstructions
    and special nets only. window: optional (xlo, ylo, xhi, yhi); only markers touching it.
    Returns markers sorted, as dicts {type, layer, box: (xlo, ylo, xhi, yhi), nets: (n1, n2)}.
    """

class MazeCosts:
    """The maze's costs (cost units: DBU of wire), as in route/maze.hpp."""

    def __init__(self, *, via_cost: int = 1200, via_pitches: int = 4, wrong_way_factor: int = 4, out_of_guide_factor: int = 3, built_in_guide_factor: int = 1, fixed_penalty: int = 400000, use_penalty: int = 8000, marker_unit: int = 1, bottom_layer_factor: int = 1, reserve_penalty: int = 20000, landing_penalty: int = 0, sole_landing_penalty: int = -1, crossing_pull: int = 2) -> None:
        """Each field by its keyword; a field left out has the engine's default."""

    @property
    def via_cost(self) -> int:
        """Cost units per via (at least via_pitches pitches)."""

    @via_cost.setter
    def via_cost(self, arg: int, /) -> None: ...

    @property
    def via_pitches(self) -> int:
        """
        A via costs at least this many pitches of the second routing layer (the contest scorer's via weight); 0: via_cost alone.
        """

    @via_pitches.setter
    def via_pitches(self, arg: int, /) -> None: ...

    @property
    def wrong_way_factor(self) -> int:
        """Wrong-way wire length multiplier."""

    @wrong_way_factor.setter
    def wrong_way_factor(self, arg: int, /) -> None: ...

    @property
    def out_of_guide_factor(self) -> int:
        """Wire length / via multiplier outside the net's guides."""

    @out_of_guide_factor.setter
    def out_of_guide_factor(self, arg: int, /) -> None: ...

    @property
    def built_in_guide_factor(self) -> int:
        """out_of_guide_factor where the guides are the built-in global router's."""

    @built_in_guide_factor.setter
    def built_in_guide_factor(self, arg: int, /) -> None: ...

    @property
    def fixed_penalty(self) -> int:
        """Entering a node a fixed shape of another net forbids."""

    @fixed_penalty.setter
    def fixed_penalty(self, arg: int, /) -> None: ...

    @property
    def use_penalty(self) -> int:
        """
        Per routed shape of another net a wire or via there would violate (iteration 0).
        """

    @use_penalty.setter
    def use_penalty(self, arg: int, /) -> None: ...

    @property
    def marker_unit(self) -> int:
        """Multiplier of the grid's marker costs."""

    @marker_unit.setter
    def marker_unit(self, arg: int, /) -> None: ...

    @property
    def bottom_layer_factor(self) -> int:
        """Wire length multiplier on routing layer 0."""

    @bottom_layer_factor.setter
    def bottom_layer_factor(self, arg: int, /) -> None: ...

    @property
    def reserve_penalty(self) -> int:
        """Entering another net's access point or boundary terminal."""

    @reserve_penalty.setter
    def reserve_penalty(self, arg: int, /) -> None: ...

    @property
    def landing_penalty(self) -> int:
        """
        Entering the landing above another net's access point while that net is unrouted.
        """

    @landing_penalty.setter
    def landing_penalty(self, arg: int, /) -> None: ...

    @property
    def sole_landing_penalty(self) -> int:
        """
        Entering the landing above the only via access point of another unrouted net's pin; -1 (the default): 8000 where at least half the design's net pins have one via point, else 0.
        """

    @sole_landing_penalty.setter
    def sole_landing_penalty(self, arg: int, /) -> None: ...

    @property
    def crossing_pull(self) -> int:
        """Per DBU a free crossing lies off the range of the pins beyond it."""

    @crossing_pull.setter
    def crossing_pull(self, arg: int, /) -> None: ...

    def replace(self, *, via_cost: int = ..., via_pitches: int = ..., wrong_way_factor: int = ..., out_of_guide_factor: int = ..., built_in_guide_factor: int = ..., fixed_penalty: int = ..., use_penalty: int = ..., marker_unit: int = ..., bottom_layer_factor: int = ..., reserve_penalty: int = ..., landing_penalty: int = ..., sole_landing_penalty: int = ..., crossing_pull: int = ...) -> MazeCosts:
        """A copy with the fields given by keyword changed."""

    def to_dict(self) -> dict:
        """The fields by name, in the engine's order."""

    def __eq__(self, other: object | None) -> object:
        """Equal when every field is."""

    def __repr__(self) -> str:
        """The fields by name."""

    def __copy__(self) -> MazeCosts:
        """A copy."""

    def __deepcopy__(self, memo: object) -> MazeCosts:
        """A copy."""

    def __getstate__(self) -> dict:
        """The fields (pickling)."""

    def __setstate__(self, state: dict) -> None:
        """The fields (pickling)."""

    __hash__: None = None

class RouterSettings:
    """The routing run's settings, as in loop/router.hpp."""

    def __init__(self, *, region_size: int = 0, iterations: int = 16, threads: int = 1, schedule: list[tuple[int, int]] = [], costs: MazeCosts = ..., use_penalty_step: int = 4000, access_points_per_pin: int = 6, marker_penalty: int = 3000, history_penalty: int = 1000, stop_at_zero: bool = True, repair_rounds: int = 0, first_repair_rounds: int = 0, repair_penalty: int = 3000, rip_neighbours_of_persistent: bool = True, late_search_markers: int = 50, late_search_budget: int = 4, trim_dangling: bool = True, partial_check_share: float = 0.15, check_band_shapes: int = 2000000) -> None:
        """Each field by its keyword; a field left out has the engine's default."""

    @property
    def region_size(self) -> int:
        """GCells per region side (0: auto_region_size(db))."""

    @region_size.setter
    def region_size(self, arg: int, /) -> None: ...

    @property
    def iterations(self) -> int:
        """Iterations at most (1..max_iterations)."""

    @iterations.setter
    def iterations(self, arg: int, /) -> None: ...

    @property
    def threads(self) -> int:
        """Worker threads for the regions of one colour."""

    @threads.setter
    def threads(self, arg: int, /) -> None: ...

    @property
    def schedule(self) -> list[tuple[int, int]]:
        """
        Per-iteration (region size, offset) in GCells, cycled over the iterations; empty: region_size with offsets 0, C/3, 2C/3.
        """

    @schedule.setter
    def schedule(self, arg: Sequence[tuple[int, int]], /) -> None: ...

    @property
    def costs(self) -> MazeCosts:
        """Maze costs of iteration 0."""

    @costs.setter
    def costs(self, arg: MazeCosts, /) -> None: ...

    @property
    def use_penalty_step(self) -> int:
        """Added to costs.use_penalty at each later iteration."""

    @use_penalty_step.setter
    def use_penalty_step(self, arg: int, /) -> None: ...

    @property
    def access_points_per_pin(self) -> int:
        """Access points kept per pin."""

    @access_points_per_pin.setter
    def access_points_per_pin(self, arg: int, /) -> None: ...

    @property
    def marker_penalty(self) -> int:
        """Cost units per node near a marker of the last iteration."""

    @marker_penalty.setter
    def marker_penalty(self, arg: int, /) -> None: ...

    @property
    def history_penalty(self) -> int:
        """Cost units per node near any earlier marker."""

    @history_penalty.setter
    def history_penalty(self, arg: int, /) -> None: ...

    @property
    def stop_at_zero(self) -> bool:
        """Stop when an iteration ends without markers."""

    @stop_at_zero.setter
    def stop_at_zero(self, arg: bool, /) -> None: ...

    @property
    def repair_rounds(self) -> int:
        """
        Check-and-reroute rounds inside each region in iterations after the first (0..max_repair_rounds).
        """

    @repair_rounds.setter
    def repair_rounds(self, arg: int, /) -> None: ...

    @property
    def first_repair_rounds(self) -> int:
        """The same in iteration 0."""

    @first_repair_rounds.setter
    def first_repair_rounds(self, arg: int, /) -> None: ...

    @property
    def repair_penalty(self) -> int:
        """Cost units per node near a region marker, times the repair round."""

    @repair_penalty.setter
    def repair_penalty(self, arg: int, /) -> None: ...

    @property
    def rip_neighbours_of_persistent(self) -> bool:
        """
        A marker that survived its nets' reroute also rips up the other nets with metal near it (farther the longer it lasts; an EndOfLine one of age 2+ also costs nodes farther out).
        """

    @rip_neighbours_of_persistent.setter
    def rip_neighbours_of_persistent(self, arg: bool, /) -> None: ...

    @property
    def late_search_markers(self) -> int:
        """
        Once a check leaves this many markers or fewer (and some), the next iterations run the victims search (when the run's policy is the heuristic).
        """

    @late_search_markers.setter
    def late_search_markers(self, arg: int, /) -> None: ...

    @property
    def late_search_budget(self) -> int:
        """
        Trial routings per region of that late search (0: never; at most max_search_budget).
        """

    @late_search_budget.setter
    def late_search_budget(self, arg: int, /) -> None: ...

    @property
    def trim_dangling(self) -> bool:
        """
        After each iteration's routing, cut the routing of every net it rerouted back to what joins its pins.
        """

    @trim_dangling.setter
    def trim_dangling(self, arg: bool, /) -> None: ...

    @property
    def partial_check_share(self) -> float:
        """
        After the first iteration, an iteration that changed at most this share of the nets is checked again only where it changed (the same markers as a whole check); 0: every check is whole.
        """

    @partial_check_share.setter
    def partial_check_share(self, arg: float, /) -> None: ...

    @property
    def check_band_shapes(self) -> int:
        """
        A whole-design check of more shapes than this runs in horizontal bands of about this many (the same markers, less memory); 0: at once.
        """

    @check_band_shapes.setter
    def check_band_shapes(self, arg: int, /) -> None: ...

    def replace(self, *, region_size: int = ..., iterations: int = ..., threads: int = ..., schedule: list[tuple[int, int]] = ..., costs: MazeCosts = ..., use_penalty_step: int = ..., access_points_per_pin: int = ..., marker_penalty: int = ..., history_penalty: int = ..., stop_at_zero: bool = ..., repair_rounds: int = ..., first_repair_rounds: int = ..., repair_penalty: int = ..., rip_neighbours_of_persistent: bool = ..., late_search_markers: int = ..., late_search_budget: int = ..., trim_dangling: bool = ..., partial_check_share: float = ..., check_band_shapes: int = ...) -> RouterSettings:
        """A copy with the fields given by keyword changed."""

    def to_dict(self) -> dict:
        """The fields by name, in the engine's order."""

    def __eq__(self, other: object | None) -> object:
        """Equal when every field is."""

    def __repr__(self) -> str:
        """The fields by name."""

    def __copy__(self) -> RouterSettings:
        """A copy."""

    def __deepcopy__(self, memo: object) -> RouterSettings:
        """A copy."""

    def __getstate__(self) -> dict:
        """The fields (pickling)."""

    def __setstate__(self, state: dict) -> None:
        """The fields (pickling)."""

    __hash__: None = None

class IterationPlan:
    """
    What one iteration runs with, as in loop/router.hpp: the rule's plan, or a schedule policy's. The maze's costs other than use_penalty are the run's.
    """

    def __init__(self, *, region_size: int = 10, offset: int = 0, repair_rounds: int = 0, marker_penalty: int = 3000, history_penalty: int = 1000, use_penalty: int = 8000, stop: bool = False, search_budget: int = 0) -> None:
        """Each field by its keyword; a field left out has the engine's default."""

    @property
    def region_size(self) -> int:
        """GCells per region side (1..max_region_size)."""

    @region_size.setter
    def region_size(self, arg: int, /) -> None: ...

    @property
    def offset(self) -> int:
        """GCells, 0 <= offset < region_size."""

    @offset.setter
    def offset(self, arg: int, /) -> None: ...

    @property
    def repair_rounds(self) -> int:
        """Check-and-reroute rounds inside each region (0..max_repair_rounds)."""

    @repair_rounds.setter
    def repair_rounds(self, arg: int, /) -> None: ...

    @property
    def marker_penalty(self) -> int:
        """Cost units per node near a marker of the last iteration."""

    @marker_penalty.setter
    def marker_penalty(self, arg: int, /) -> None: ...

    @property
    def history_penalty(self) -> int:
        """What each marker this iteration leaves adds near it from then on."""

    @history_penalty.setter
    def history_penalty(self, arg: int, /) -> None: ...

    @property
    def use_penalty(self) -> int:
        """
        Cost units per shape of another net that a step would violate (the maze's costs.use_penalty).
        """

    @use_penalty.setter
    def use_penalty(self, arg: int, /) -> None: ...

    @property
    def stop(self) -> bool:
        """End the run instead of running this iteration (not the first)."""

    @stop.setter
    def stop(self, arg: bool, /) -> None: ...

    @property
    def search_budget(self) -> int:
        """
        0: the run's net-order policy orders each region's nets; B >= 1: the victims search with B trial routings per region, in this iteration only.
        """

    @search_budget.setter
    def search_budget(self, arg: int, /) -> None: ...

    def replace(self, *, region_size: int = ..., offset: int = ..., repair_rounds: int = ..., marker_penalty: int = ..., history_penalty: int = ..., use_penalty: int = ..., stop: bool = ..., search_budget: int = ...) -> IterationPlan:
        """A copy with the fields given by keyword changed."""

    def to_dict(self) -> dict:
        """The fields by name, in the engine's order."""

    def __eq__(self, other: object | None) -> object:
        """Equal when every field is."""

    def __repr__(self) -> str:
        """The fields by name."""

    def __copy__(self) -> IterationPlan:
        """A copy."""

    def __deepcopy__(self, memo: object) -> IterationPlan:
        """A copy."""

    def __getstate__(self) -> dict:
        """The fields (pickling)."""

    def __setstate__(self, state: dict) -> None:
        """The fields (pickling)."""

    __hash__: None = None

def region_grid_nodes(db: Database, size: int) -> float:
    """
    The upper quartile, over the regions of `size` GCells a side (offset 0) that hold an access point, of a region grid's nodes a layer (lines in x times lines in y), as auto_region_size weighs them.
    """

def auto_region_size(db: Database) -> int:
    """
    GCells per region side of a run whose region_size is 0: DEFAULTS['region_gcells'], or more while three in four regions' grids (lines at every track and access point in the region) stay within DEFAULTS['region_grid_nodes'] nodes a layer and a region does not cover the die; or fewer, down to DEFAULTS['least_region_gcells'], while they are over it at the first. Computes the design's pin access (the default access points per pin, as a run does).
    """

POLICY_FEATURES: tuple = ...

def route(db: Database, settings: RouterSettings | None = None, policy: str = 'heuristic', seed: int = 1, policy_fn: object | None = None, policy_needs_region: bool = False, progress: object | None = None, search_budget: int = 4, search_width: int = 0, policy_next: object | None = None, planner: object | None = None) -> dict:
    """
    Routes every net of the database in place (its routing is replaced). policy: 'heuristic', 'random' (seeded), 'rollout' (search_budget trial routings per region, search_width candidates per step, 0: all), 'victims' (at most search_budget trial routings per region: the victims of the markers so far first), 'bestof' (K = search_budget) or 'best-of-K' (K seeded orders, the heuristic's first); or policy_fn(region: dict, features: int32[n, len(POLICY_FEATURES)]) -> order; or, sequential, policy_next(region, features) -> index of the next net, called after every routed net with the unrouted candidates' rows as they are then. With policy_needs_region, region['engine_region'] is the Region being routed, lent for that call (the policy may route nets with it; the order applies to the rest). progress(report, regions_done, regions_total) is called after each batch of regions. settings: a RouterSettings (region size, iterations, threads, schedule, costs, penalties, repair rounds; None: the defaults); a field out of the engine's limits is a RouteArgumentError. planner(history: [report, ...], rule: IterationPlan) -> IterationPlan is asked before each iteration, with the reports of the iterations done and the rule's plan; the iteration runs the plan it returns (stop: end the run, from iteration 1 on; search_budget B >= 1: the victims search with that budget in this iteration; a field out of the engine's limits is a RouteArgumentError). Returns {'iterations': [report, ...], 'policy': name, 'sole_landing_penalty': the maze's, as the run resolved it}; a report's plan is its IterationPlan's to_dict().
    """

ACCESS_UP: int = 1

ACCESS_EAST: int = 2

ACCESS_WEST: int = 4

ACCESS_NORTH: int = 8

ACCESS_SOUTH: int = 16

class RoutingSession:
    """
    What every region of one design shares: tracks, vias, pin access, fixed shapes.
    """

    def __init__(self, db: Database, threads: int = 1, costs: MazeCosts = ...) -> None:
        """
        Prepares routing of a loaded Database (pin access is computed here, once); the regions it opens route with the maze's costs (default: the engine's).
        """

    @property
    def gcell_lines(self) -> tuple:
        """The GCell grid lines (xs, ys) in DBU that regions align to."""

    def regions(self, size: int, offset: int = 0) -> list:
        """
        The router's partition into regions of size x size GCells (the first column and row shortened by offset), row by row: [((gcell column, row), (xlo, ylo, xhi, yhi) in DBU), ...].
        """

    def open_region(self, box: tuple[int, int, int, int], iteration: int = 0) -> Region:
        """
        Opens the region box (xlo, ylo, xhi, yhi) in DBU: nets with pins or routing inside, or whose guides cross its edges, become candidates (routed nets are ripped up inside the box).
        """

class Region:
    """One routing region, routed net by net in the caller's order."""

    @property
    def box(self) -> tuple:
        """The region box (xlo, ylo, xhi, yhi) in DBU."""

    @property
    def lent(self) -> bool:
        """
        True for a region the router lends to a policy (valid during that call; no commit).
        """

    @property
    def candidates(self) -> NDArray[numpy.int32]:
        """
        int32[candidates, len(POLICY_FEATURES)]: one row per candidate net, columns as _engine.POLICY_FEATURES (routed_nearby as the region is now). In a first-pass region a net whose guides pass the region in two pieces joined elsewhere is two candidates (two parts, each its own tree).
        """

    @property
    def route_order(self) -> list[int]:
        """
        Candidate indices in the order they were routed so far (a search policy's: the order it kept).
        """

    def is_routed(self, index: int) -> bool:
        """Whether candidate i has been routed."""

    def unrouted(self) -> list[int]:
        """Indices of the candidates not routed yet."""

    def route_net(self, index: int) -> dict:
        """
        Routes candidate i now; returns its wirelength_dbu, vias and unreached terminals.
        """

    def terminal_nodes(self, index: int) -> list[list[int]]:
        """
        Candidate i's terminals as the maze sees them: per terminal, its grid nodes (flat indices into the (nz, ny, nx) grid arrays; joined terminals first, the maze starts from the first). Reaching any node of a terminal connects it.
        """

    def terminal_joined(self, index: int) -> list[bool]:
        """
        Per terminal of terminal_nodes(i): True when its nodes are one conductor (a pin's access points: all of them join the route once one is reached), False for alternatives (a free crossing: only the node reached joins).
        """

    def moves(self, index: int, node: int) -> tuple:
        """
        The maze's six edges from grid node `node` for candidate i's net, by direction (0 up, 1 down, 2 north, 3 south, 4 east, 5 west): (neighbour nodes, step costs in maze cost units); -1 where there is no edge. Wrong-way edges reach the next existing node.
        """

    def route_net_paths(self, index: int, paths: Sequence[Sequence[int]]) -> dict:
        """
        Routes candidate i along the caller's node paths (each step one edge of moves()) through the maze's own commit (wires, vias, min-area fix, grid marks); returns what route_net returns (unreached: terminals after the first that no path touches).
        """

    def net_paths(self, index: int) -> list[list[int]]:
        """
        The node paths candidate i was routed along (by the maze or route_net_paths); empty before.
        """

    def route_rest(self, policy: str = 'heuristic', seed: int = 1, search_budget: int = 4, search_width: int = 0) -> None:
        """
        Routes every candidate not routed yet in a built-in policy's order (heuristic, random, rollout, victims, bestof, best-of-K; the searches route trial orders on copies of the region and keep the cheapest).
        """

    def metrics(self) -> dict:
        """
        The new routing so far: wirelength_dbu, vias, nets_routed, unreached terminals, and the design-rule violations inside the box (fixed-only ones skipped).
        """

    def markers(self) -> list:
        """
        The design-rule markers metrics() counts (inside the box, fixed-only ones skipped), as dicts {type, layer, box: (xlo, ylo, xhi, yhi), nets: (n1, n2)}; net ids as in candidates' net column, -1 = an obstruction.
        """

    def grid(self) -> dict:
        """
        Live numpy views of the region grid, each shaped (nz, ny, nx) (xs, ys: grid coordinates in DBU): flags (1 on track, 2 access point, 4 boundary terminal, 8 via landing above an access point, 16 access point whose via up pin access checked, 32 landing of a net already routed here: other nets' wires pass it freely; 0 = no node), fixed_owner / via_fixed_owner (-1 free, net allowed, -2 blocked), wire_use / via_use (routed shapes a wire / via there would violate), marker_cost, access_net, access_pin, routed_net (-1 = none). They stay valid while the Region lives and change as nets are routed (for a region lent to a policy: during that call only); access_net and access_pin, which do not change once the region is made, are copies.
        """

    def node_type(self) -> NDArray[numpy.uint8]:
        """
        uint8[nz, ny, nx]: 0 NOTEXIST, 1 BLOCKAGE, 2 NORMAL, 3 ACCESS (a copy).
        """

    def commit(self) -> None:
        """
        Writes the region's new routing into the design (other open regions of the session become stale).
        """

class FirstPass:
    """
    The flow's first pass (iteration 0) of a session's design, kept so that each of its regions can be opened again in context (loop/first_pass.hpp).
    """

    def __init__(self, session: RoutingSession, region_size: int = 0, policy: str = 'heuristic', seed: int = 1, threads: int = 1) -> None:
        """
        Routes iteration 0 of the session's design as `xroute route` does (regions of region_size GCells, colour by colour; policy 'heuristic' or 'random' (seeded)), keeping the design's routing and crossing choices before each colour. The design is left with the whole pass routed.
        """

    @property
    def regions(self) -> list:
        """
        The regions with work in the flow's order (colour, then row by row): [((gcell column, row), (xlo, ylo, xhi, yhi) in DBU, colour 0..3, nets), ...]; open_region(i) opens the i-th.
        """

    def open_region(self, index: int) -> Region:
        """
        Region `index` of regions, in context: the design's routing put back to what the pass had before the region's colour (earlier colours routed and their crossing points chosen, the rest unrouted) and the region's nets, pins and crossings as the flow gave them. Other open regions of the session become stale; routing it with route_rest('heuristic') gives what the pass routed there.
        """

    def restore(self, colour: int) -> None:
        """
        Puts the design's routing back to what it was before the regions of `colour` (0..3) were routed; 4: after the whole pass.
        """

    @property
    def report(self) -> dict:
        """
        Iteration 0's report (as route()'s): wirelength, vias and violations of the whole design after the pass.
        """

def gcell_capacity(db: Database) -> dict:
    """
    The global router's GCell grid and capacities: xs, ys (GCell lines, DBU), layers (routing layer names), horizontal (preferred direction per layer), capacity and tracks (per layer, int32[ny, nx]: at [y, x] the edge from GCell (x, y) to its right neighbour on a horizontal layer, to its upper neighbour on a vertical one; free tracks after blocking, and all tracks).
    """

def global_route(db: Database, out: str = '', iterations: int = 30, capacity_percent: int = 70, min_layer: int = 1, slack: int = 0, congestion_cost: float = 0.0) -> dict:
    """
    Global-routes every net of the database and replaces its guides with the result (any guides it had are dropped). out: also write them to this path in the ISPD guide format (atomically; '' = no file). iterations: rip-up-and-reroute rounds at most; capacity_percent: share of each GCell edge's free tracks the router may fill; min_layer: lowest routing-layer index carrying routes (pins get guides on their own layer and the one above regardless); slack: GCells every guide is grown by; congestion_cost: layer assignment's cost of one GCell edge at full use (0: only full layers and vias count). Returns statistics: gcells (nx, ny), layers, nets, initial_overflow, overflow, overflow_edges, overflow_3d (tracks), wirelength_gcells, vias, guides, iterations, reroutes, seconds.
    """

DEFAULTS: dict = ...
