"""The testcases xroute knows by name, with their published sizes, and the static regions.

Sources of the figures (a figure that no source confirms is ``None``, never a guess):

* [TR] A. B. Kahng, L. Wang, B. Xu, "TritonRoute: The Open Source Detailed Router",
  IEEE TCAD 2020, Table VI "Benchmark information", which reproduces the ISPD-2018 contest
  table (S. Mantik et al., "ISPD 2018 Initial Detailed Routing Contest and Benchmarks",
  ISPD 2018): #std cells, #blk (macro blocks), #net, #pin (IO pins), #layer, die size, node.
* [DEF] counted in the copies under ``../shared/testcases`` (DEF ``COMPONENTS``, ``NETS``,
  ``PINS``, ``DIEAREA``; LEF ``TYPE ROUTING`` layers; macro blocks = components whose LEF
  macro is ``CLASS BLOCK``). Where [TR] and [DEF] overlap (ispd18_test1) they agree.
* Guides: the contests shipped ``<name>.input.guide`` with every testcase (the OpenROAD
  ISPD regression scripts pass ``-guide <name>.input.guide`` for all 20); our copy of
  ispd19_test3 has none, so it is marked ``has_guide=False``.

We found no public table for ISPD-2019 testcases other than the two we hold, so their
sizes are ``None``.
"""

from __future__ import annotations

from dataclasses import dataclass

ISPD2018 = "ISPD-2018"
ISPD2019 = "ISPD-2019"


@dataclass(frozen=True)
class KnownTestcase:
    """A contest testcase and its published (or counted) size."""

    name: str
    contest: str  # ISPD-2018 or ISPD-2019
    components: int | None  # placed instances: standard cells + macro blocks (DEF COMPONENTS)
    macros: int | None  # macro blocks among the components
    nets: int | None  # regular nets (DEF NETS)
    io_pins: int | None  # IO pins (DEF PINS)
    metal_layers: int | None  # routing layers in the LEF
    tech_node: str | None  # e.g. "45nm"
    die_mm: tuple[float, float] | None  # die width x height in mm (published ones rounded to 0.01)
    has_guide: bool  # a <name>.input.guide comes with it (see the module docstring)
    sample: bool  # a small sample released before the contest testcases
    source: str  # where the figures come from ([TR], [DEF]; see the module docstring)


@dataclass(frozen=True)
class StaticRegion:
    """A fixed routing region of the XRoute paper (``../shared/testcases/README.md``)."""

    name: str  # Region1 .. Region10
    testcase: str
    size_gcells: tuple[int, int]  # GCells along x, y
    lower_left: tuple[int, int]  # DBU
    upper_right: tuple[int, int]  # DBU

    @property
    def bbox(self) -> tuple[int, int, int, int]:
        """(xlo, ylo, xhi, yhi) in DBU."""
        return (*self.lower_left, *self.upper_right)


def _ispd18(n: int, std: int, blk: int, nets: int, pins: int, die: tuple[float, float], node: str) -> KnownTestcase:
    # [TR] Table VI; components = #std + #blk.
    return KnownTestcase(
        name=f"ispd18_test{n}", contest=ISPD2018, components=std + blk, macros=blk, nets=nets,
        io_pins=pins, metal_layers=9, tech_node=node, die_mm=die, has_guide=True, sample=False,
        source="TR",
    )


def _unknown19(n: int) -> KnownTestcase:
    return KnownTestcase(
        name=f"ispd19_test{n}", contest=ISPD2019, components=None, macros=None, nets=None,
        io_pins=None, metal_layers=None, tech_node=None, die_mm=None, has_guide=True, sample=False,
        source="",
    )


def _held(name: str, contest: str, comps: int, macros: int, nets: int, pins: int, layers: int,
          die_dbu: tuple[int, int], guide: bool, sample: bool) -> KnownTestcase:
    # [DEF] counted in our copy; die from DIEAREA at 2000 DBU per micron.
    die = (die_dbu[0] / 2_000_000, die_dbu[1] / 2_000_000)
    return KnownTestcase(
        name=name, contest=contest, components=comps, macros=macros, nets=nets, io_pins=pins,
        metal_layers=layers, tech_node=None, die_mm=die, has_guide=guide, sample=sample,
        source="DEF",
    )


KNOWN_TESTCASES: tuple[KnownTestcase, ...] = (
    # ISPD-2018 contest testcases, [TR] Table VI. ispd18_test1 also matches [DEF].
    _ispd18(1, 8879, 0, 3153, 0, (0.20, 0.19), "45nm"),
    _ispd18(2, 35913, 0, 36834, 1211, (0.65, 0.57), "45nm"),
    _ispd18(3, 35973, 4, 36700, 1211, (0.99, 0.70), "45nm"),
    _ispd18(4, 72094, 0, 72401, 1211, (0.89, 0.61), "32nm"),
    _ispd18(5, 71954, 0, 72394, 1211, (0.93, 0.92), "32nm"),
    _ispd18(6, 107919, 0, 107701, 1211, (0.86, 0.53), "32nm"),
    _ispd18(7, 179865, 16, 179863, 1211, (1.36, 1.33), "32nm"),
    _ispd18(8, 191987, 16, 179863, 1211, (1.36, 1.33), "32nm"),
    _ispd18(9, 192911, 0, 178857, 1211, (0.91, 0.78), "32nm"),
    _ispd18(10, 290386, 0, 182000, 1211, (0.91, 0.87), "32nm"),
    # ISPD-2019 contest testcases: test1 and test3 counted in our copies [DEF]; the rest unknown.
    _held("ispd19_test1", ISPD2019, 8879, 0, 3153, 0, 9, (296800, 292000), guide=True, sample=False),
    _unknown19(2),
    _held("ispd19_test3", ISPD2019, 8283, 1, 8953, 57, 9, (390600, 390000), guide=False, sample=False),
    *(_unknown19(n) for n in range(4, 11)),
    # Samples [DEF].
    _held("ispd18_sample", ISPD2018, 22, 0, 11, 0, 9, (20800, 19380), guide=True, sample=True),
    _held("ispd18_sample2", ISPD2018, 23, 1, 16, 0, 9, (34900, 19380), guide=True, sample=True),
    _held("ispd18_sample3", ISPD2018, 6, 1, 7, 5, 16, (3854000, 3919700), guide=True, sample=True),
    _held("ispd19_sample4", ISPD2019, 67, 0, 22, 0, 9, (390600, 390000), guide=True, sample=True),
)

KNOWN_BY_NAME: dict[str, KnownTestcase] = {t.name: t for t in KNOWN_TESTCASES}

# The ten static regions of the XRoute paper, as listed in ../shared/testcases/README.md.
STATIC_REGIONS: tuple[StaticRegion, ...] = (
    StaticRegion("Region1", "ispd18_test1", (1, 1), (199500, 245100), (205200, 250800)),
    StaticRegion("Region2", "ispd18_test1", (1, 1), (142500, 233700), (148200, 239400)),
    StaticRegion("Region3", "ispd18_test1", (1, 1), (148200, 210900), (153900, 216600)),
    StaticRegion("Region4", "ispd19_test3", (2, 2), (138000, 132000), (144000, 138000)),
    StaticRegion("Region5", "ispd19_test3", (2, 2), (96000, 186000), (102000, 192000)),
    StaticRegion("Region6", "ispd19_test3", (2, 2), (108000, 186000), (114000, 192000)),
    StaticRegion("Region7", "ispd18_test5", (3, 3), (1566000, 639000), (1575000, 648000)),
    StaticRegion("Region8", "ispd18_test5", (3, 3), (1332000, 1224000), (1341000, 1233000)),
    StaticRegion("Region9", "ispd19_test7", (3, 3), (612000, 1314000), (621000, 1323000)),
    StaticRegion("Region10", "ispd19_test7", (3, 3), (648000, 1386000), (657000, 1395000)),
)


def known_testcase(name: str) -> KnownTestcase | None:
    """The registry entry for ``name``, or None for a testcase the registry does not list."""
    return KNOWN_BY_NAME.get(name)
