"""Connectivity (opens) check: drawn DEF cases with exact pin groups, a random
cross-check against a brute-force reference, and the unrouted contest designs."""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from drawn import contest_input, load_drawn
from lef_text import library, macro, pin, site, stack
from xroute import _engine

# Three routing layers, all 100 DBU wide (half width 50); V12 / V23 are
# 100 x 100 squares on each of their three layers, centred on the via point.
TECH_LEF = library(
    stack(width=0.1, spacing=None, cut_width=None, cut_spacing=None),
    site("core", 0.2, 1.0),
    macro("CELL", 1.0, 1.0,
          pin("A", "INPUT", [("M1", (0.1, 0.4, 0.3, 0.6))], use=None),
          pin("Y", "OUTPUT", [("M1", (0.7, 0.4, 0.9, 0.6))], use=None),
          pin("B", "INPUT", [("M1", (0.4, 0.1, 0.6, 0.2))], [("M2", (0.4, 0.8, 0.6, 0.9))], use=None),
          site_name="core"),
    grid=None,
)

# Cells at x = 0, 2000, 4000 (all N). Pin shapes in design coordinates:
#   u1/Y (700,400)-(900,600)     u2/A (2100,400)-(2300,600)    u3/A (4100,400)-(4300,600)
#   u2/B M1 (2400,100)-(2600,200) and M2 (2400,800)-(2600,900)
DEF_TEMPLATE = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN conn ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 20000 20000 ) ;
COMPONENTS 3 ;
- u1 CELL + PLACED ( 0 0 ) N ;
- u2 CELL + PLACED ( 2000 0 ) N ;
- u3 CELL + PLACED ( 4000 0 ) N ;
END COMPONENTS
{pins}NETS {count} ;
{nets}
END NETS
END DESIGN
"""


def load(tmp_path: Path, nets: list[str], pins: str = ""):
    return load_drawn(tmp_path, TECH_LEF, DEF_TEMPLATE.format(pins=pins, count=len(nets), nets="\n".join(nets)), "conn")


def single(report: dict) -> dict:
    """The open-net entry of the only checked net, or None when it is connected."""
    assert report["nets_checked"] == 1
    return report["opens"][0] if report["opens"] else None


Y1_A2 = [[("u1", "Y")], [("u2", "A")]]


def test_wire_on_the_pin_layer(tmp_path):
    # M1 (800,500)-(2200,500): rect (750,450)-(2250,550) overlaps both pins.
    db = load(tmp_path, ["- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 2200 500 ) ;"])
    r = db.check_connectivity()
    assert r == {"nets_checked": 1, "open_nets": 0, "single_pin_nets": 0, "unrouted_nets": 0,
                 "floating_pieces": 0, "opens": []}


VIA_STACK = ("- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) V12 ( 800 1500 ) V23 ( 2200 1500 ) {v23}"
             " NEW M2 ( 2200 1500 ) ( 2200 500 ) V12 ;")


def test_via_stack(tmp_path):
    # u1/Y -V12- M2 up -V23- M3 across -V23- M2 down -V12- u2/A.
    db = load(tmp_path, [VIA_STACK.format(v23="V23")])
    r = db.check_connectivity()
    assert (r["open_nets"], r["floating_pieces"], r["opens"]) == (0, 0, [])


def test_layers_join_only_through_vias(tmp_path):
    # Without the second V23 the M3 wire (750,1450)-(2250,1550) lies over the
    # M2 wire (2150,450)-(2250,1550) but does not connect to it.
    db = load(tmp_path, [VIA_STACK.format(v23="")])
    r = db.check_connectivity()
    assert r["open_nets"] == 1
    assert single(r) == {"net": "n1", "pins": 2, "groups": Y1_A2, "floating_pieces": 0}


def test_one_dbu_gap_is_open_shared_edge_is_connected(tmp_path):
    # Left piece ends at x 1499 + 50 = 1549, right piece starts at 1600 - 50 = 1550.
    gap = "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( {x} 500 ) NEW M1 ( 1600 500 ) ( 2200 500 ) ;"
    r = load(tmp_path, [gap.format(x=1499)]).check_connectivity()
    assert r["open_nets"] == 1
    assert single(r) == {"net": "n1", "pins": 2, "groups": Y1_A2, "floating_pieces": 0}
    # Ending at 1500: both rects have the edge x = 1550, y 450..550 -> connected.
    r = load(tmp_path, [gap.format(x=1500)]).check_connectivity()
    assert r["open_nets"] == 0


def test_corner_touch_is_open(tmp_path):
    # Left piece (750,450)-(1250,550); right piece from (x,600): rect (x-50,550)-(2250,650),
    # which overlaps u2/A (y 550..600). At x = 1300 the pieces share only the
    # point (1250,550); at x = 1299 they share the segment x 1249..1250 of y = 550.
    corner = "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 1200 500 ) NEW M1 ( {x} 600 ) ( 2200 600 ) ;"
    r = load(tmp_path, [corner.format(x=1300)]).check_connectivity()
    assert single(r) == {"net": "n1", "pins": 2, "groups": Y1_A2, "floating_pieces": 0}
    r = load(tmp_path, [corner.format(x=1299)]).check_connectivity()
    assert r["open_nets"] == 0


def test_corner_touch_of_patches_is_open(tmp_path):
    # Patches: (700,400)-(1000,500) from u1/Y up to the corner (1000,500), then
    # (1000,500)-(2200,600) onwards to u2/A. Corner only -> open.
    net = "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 1000 500 ) RECT ( -300 -100 0 0 ) NEW M1 ( 1000 500 ) RECT ( 0 {dy} 1200 100 ) ;"
    r = load(tmp_path, [net.format(dy=0)]).check_connectivity()
    assert single(r)["groups"] == Y1_A2
    # Starting 1 DBU lower, the patches share the segment x = 1000, y 499..500.
    r = load(tmp_path, [net.format(dy=-1)]).check_connectivity()
    assert r["open_nets"] == 0


def test_default_extension_closes_the_gap(tmp_path):
    # Points 1500 and 1600 are 100 apart; the default extensions (50 each) meet
    # at x = 1550. With an explicit 0 extension on the facing ends they do not.
    ext = "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 1500 500 {e} ) NEW M1 ( 1600 500 {e} ) ( 2200 500 ) ;"
    assert load(tmp_path, [ext.format(e="")]).check_connectivity()["open_nets"] == 0
    r = load(tmp_path, [ext.format(e="0")]).check_connectivity()
    assert single(r) == {"net": "n1", "pins": 2, "groups": Y1_A2, "floating_pieces": 0}
    # Extension 50 written explicitly on one end only: (1500+50) meets (1600-0)? No: 1550 < 1600.
    r = load(tmp_path, ["- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 1500 500 50 ) NEW M1 ( 1600 500 0 ) ( 2200 500 ) ;"]).check_connectivity()
    assert r["open_nets"] == 1
    # ... but 100 on that end reaches it (edge x = 1600 shared).
    r = load(tmp_path, ["- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 1500 500 100 ) NEW M1 ( 1600 500 0 ) ( 2200 500 ) ;"]).check_connectivity()
    assert r["open_nets"] == 0


def test_three_pins_one_unreached(tmp_path):
    # Pins in net order: u1/Y (pin 0), u3/A (pin 1), u2/A (pin 2); the wire
    # joins u1/Y and u2/A. Groups are ordered by their first pin.
    db = load(tmp_path, ["- n1 ( u1 Y ) ( u3 A ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 2200 500 ) ;"])
    r = db.check_connectivity()
    assert single(r) == {"net": "n1", "pins": 3, "groups": [[("u1", "Y"), ("u2", "A")], [("u3", "A")]],
                         "floating_pieces": 0}


def test_ports_of_one_pin_are_connected(tmp_path):
    # u1/Y -> u2/B's M1 port (2400,100)-(2600,200) on M1; from u2/B's M2 port
    # (2400,800)-(2600,900) on M2 over to (4200,850), down to V12 at u3/A.
    # The two pieces meet only inside the cell (one pin = one node).
    net = ("- n1 ( u1 Y ) ( u2 B ) ( u3 A ) + ROUTED M1 ( 800 500 ) ( 800 150 ) ( 2500 150 )"
           " NEW M2 ( 2500 850 ) ( 4200 850 ) ( 4200 500 ) V12 ;")
    r = load(tmp_path, [net]).check_connectivity()
    assert (r["open_nets"], r["floating_pieces"]) == (0, 0)


def test_io_pin(tmp_path):
    # io1: M2 rect (-50,0)-(50,100) about (5000,2000), orient S -> (4950,1900)-(5050,2000).
    # Route: V12 on u1/Y, M2 up to y 1900, across to x 5000: rect (750,1850)-(5050,1950)
    # overlaps the S-placed shape (an N-placed one would be (4950,2000)-(5050,2100)).
    pins = ("PINS 1 ;\n- io1 + NET n1 + DIRECTION INPUT + USE SIGNAL\n"
            "  + LAYER M2 ( -50 0 ) ( 50 100 ) + PLACED ( 5000 2000 ) {o} ;\nEND PINS\n")
    net = "- n1 ( PIN io1 ) ( u1 Y ) + ROUTED M1 ( 800 500 ) V12 ( 800 1900 ) ( 5000 1900 ) ;"
    r = load(tmp_path, [net], pins.format(o="S")).check_connectivity()
    assert (r["open_nets"], r["opens"]) == (0, [])
    r = load(tmp_path, [net], pins.format(o="N")).check_connectivity()
    assert single(r) == {"net": "n1", "pins": 2, "groups": [[("PIN", "io1")], [("u1", "Y")]], "floating_pieces": 0}


def test_floating_pieces_and_totals(tmp_path):
    # n1: connected, plus an M1 wire with a V12 on its end far away (one piece)
    # and a lone M3 patch (another). n2: open, one stray via (a third piece).
    # n3 has one pin (skipped), n4 has two pins and no routing.
    nets = [
        "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 2200 500 ) NEW M1 ( 8000 8000 ) ( 9000 8000 ) V12"
        " NEW M3 ( 12000 12000 ) RECT ( 0 0 500 100 ) ;",
        "- n2 ( u3 A ) ( u2 B ) + ROUTED M1 ( 15000 15000 ) V12 ;",
        "- n3 ( u3 Y ) ;",
        "- n4 ( u1 A ) ( u1 B ) ;",
    ]
    r = load(tmp_path, nets).check_connectivity()
    assert {k: v for k, v in r.items() if k != "opens"} == {
        "nets_checked": 3, "open_nets": 2, "single_pin_nets": 1, "unrouted_nets": 1, "floating_pieces": 3}
    assert r["opens"] == [
        {"net": "n2", "pins": 2, "groups": [[("u3", "A")], [("u2", "B")]], "floating_pieces": 1},
        {"net": "n4", "pins": 2, "groups": [[("u1", "A")], [("u1", "B")]], "floating_pieces": 0},
    ]


def test_pins_touching_directly_need_no_routing(tmp_path):
    # u2 at x 2000 is replaced by one abutting u1: u1/Y (700..900) and a cell at
    # x 600 with A at (700..900) overlap -> connected without any routing.
    abut = (DEF_TEMPLATE.replace("- u2 CELL + PLACED ( 2000 0 ) N", "- u2 CELL + PLACED ( 600 0 ) N")
            .format(pins="", count=1, nets="- n1 ( u1 Y ) ( u2 A ) ;"))
    r = load_drawn(tmp_path, TECH_LEF, abut, "conn", def_stem="abut").check_connectivity()
    assert (r["open_nets"], r["unrouted_nets"]) == (0, 1)


# ---------------------------------------------------------------------------
# Random cross-check against a brute-force reference.

PIN_RECTS = {("u1", "Y"): [("M1", (700, 400, 900, 600))], ("u2", "A"): [("M1", (2100, 400, 2300, 600))],
             ("u3", "A"): [("M1", (4100, 400, 4300, 600))],
             ("u2", "B"): [("M1", (2400, 100, 2600, 200)), ("M2", (2400, 800, 2600, 900))]}


def touches(a, b):
    ox = min(a[2], b[2]) - max(a[0], b[0])
    oy = min(a[3], b[3]) - max(a[1], b[1])
    return ox >= 0 and oy >= 0 and (ox > 0 or oy > 0)


def reference_groups(pins, pieces):
    """pins: list of (comp, pin); pieces: list of [(layer, rect), ...] (one node each)."""
    nodes = [PIN_RECTS[p] for p in pins] + pieces
    parent = list(range(len(nodes)))

    def find(x):
        while parent[x] != x:
            x = parent[x]
        return x

    for i in range(len(nodes)):
        for j in range(i + 1, len(nodes)):
            if any(la == lb and touches(ra, rb) for la, ra in nodes[i] for lb, rb in nodes[j]):
                parent[find(j)] = find(i)
    groups: dict[int, list] = {}
    for k, p in enumerate(pins):
        groups.setdefault(find(k), []).append(p)
    floating = {find(k) for k in range(len(pins), len(nodes))} - {find(k) for k in range(len(pins))}
    return list(groups.values()), len(floating)


CENTERS = {("u1", "Y"): (800, 500), ("u2", "A"): (2200, 500), ("u3", "A"): (4200, 500), ("u2", "B"): (2500, 150)}


class RandomNet:
    """A random net: paths from pin to pin (up through vias, an L on some
    layer, down again), with jitter that sometimes breaks them, random wire
    extensions and stray pieces; the DEF text and the reference's pieces."""

    def __init__(self, rng: random.Random) -> None:
        self.rng = rng
        self.text: list[str] = []
        self.pieces: list[list] = []

    def jitter(self, x: int, y: int) -> tuple[int, int]:
        if self.rng.random() < 0.2:
            return x + self.rng.choice([-150, -101, -100, 100, 101, 150]), y + self.rng.choice([-100, 0, 0, 100])
        return x, y

    def slide(self, p, q):
        """p, sometimes moved along the line p-q (keeps the wire straight)."""
        if p == q or self.rng.random() >= 0.3:
            return p
        d = self.rng.choice([-200, -101, -100, -51, 100, 101, 151, 200])
        return (p[0] + d, p[1]) if p[1] == q[1] else (p[0], p[1] + d)

    def wire(self, layer: str, p, q) -> None:
        if p == q:
            return
        (x, y), (x2, y2) = p, q
        e1, e2 = self.rng.choice([None, None, 0, 25, 100]), self.rng.choice([None, None, 0, 25, 100])
        f = lambda e: "" if e is None else f" {e}"
        self.text.append(f"{layer} ( {x} {y}{f(e1)} ) ( {x2} {y2}{f(e2)} )")
        a, b = (50 if e1 is None else e1), (50 if e2 is None else e2)
        if y == y2:
            lo, hi = (x - a, x2 + b) if x <= x2 else (x2 - b, x + a)
            self.pieces.append([(layer, (lo, y - 50, hi, y + 50))])
        else:
            lo, hi = (y - a, y2 + b) if y <= y2 else (y2 - b, y + a)
            self.pieces.append([(layer, (x - 50, lo, x + 50, hi))])

    def via(self, name: str, p) -> None:
        lo, hi = {"V12": ("M1", "M2"), "V23": ("M2", "M3")}[name]
        x, y = self.jitter(*p)
        self.text.append(f"{lo} ( {x} {y} ) {name}")
        r = (x - 50, y - 50, x + 50, y + 50)
        self.pieces.append([(lo, r), (hi, r)])

    def patch(self, layer: str, x: int, y: int, w: int, h: int) -> None:
        self.text.append(f"{layer} ( {x} {y} ) RECT ( 0 0 {w} {h} )")
        self.pieces.append([(layer, (x, y, x + w, y + h))])

    def path(self, a, b) -> None:
        z = self.rng.choice([1, 2, 2, 3])
        layers = ["M1", "M2", "M3"][:z]
        for k in range(1, z):
            self.via(["V12", "V23"][k - 1], a)
        corner = (b[0], a[1]) if self.rng.random() < 0.5 else (a[0], b[1])
        self.wire(layers[-1], self.slide(a, corner), corner)
        self.wire(layers[-1], self.slide(corner, b), b)
        for k in range(z - 1, 0, -1):
            self.via(["V12", "V23"][k - 1], b)

    def stray(self, layer: str | None = None) -> None:
        rng = self.rng
        x, y = rng.randrange(0, 4600, 50), rng.randrange(0, 1100, 50)
        layer = layer or rng.choice(["M1", "M2", "M3"])
        kind = rng.random()
        if kind < 0.4:
            length = rng.randrange(50, 1500, 50) * rng.choice([-1, 1])
            self.wire(layer, (x, y), (x + length, y) if rng.random() < 0.5 else (x, y + length))
        elif kind < 0.7:
            self.patch(layer, x, y, rng.randrange(50, 800, 50), rng.randrange(50, 400, 50))
        else:
            self.via(rng.choice(["V12", "V23"]), (x, y))


def random_net(rng: random.Random, m1_strays: int = 0):
    """DEF text of a random net, its pins and its pieces as the reference sees them."""
    pins = [("u1", "Y"), ("u2", "A"), ("u3", "A"), ("u2", "B")][: rng.randint(2, 4)]
    net = RandomNet(rng)
    for a, b in zip(pins, pins[1:]):
        net.path(CENTERS[a], CENTERS[b])
    for _ in range(rng.randint(0, 4)):
        net.stray()
    for _ in range(m1_strays):
        net.stray("M1")
    pin_text = " ".join(f"( {c} {p} )" for c, p in pins)
    return f"- n1 {pin_text} + ROUTED " + " NEW ".join(net.text) + " ;", pins, net.pieces


@pytest.mark.parametrize("seed", range(60))
def test_random_nets_match_brute_force(tmp_path, seed):
    rng = random.Random(seed)
    text, pins, pieces = random_net(rng)
    groups, floating = reference_groups(pins, pieces)
    r = load(tmp_path, [text]).check_connectivity()
    assert r["nets_checked"] == 1 and r["floating_pieces"] == floating
    if len(groups) == 1:
        assert r["opens"] == [], text
    else:
        assert r["opens"][0]["groups"] == groups, text


@pytest.mark.parametrize("seed", range(3))
def test_random_big_net_matches_brute_force(tmp_path, seed):
    # Over 256 shapes on M1: contacts come from the box index, not the sweep.
    text, pins, pieces = random_net(random.Random(1000 + seed), m1_strays=400)
    assert sum(1 for p in pieces if p[0][0] == "M1") > 256
    groups, floating = reference_groups(pins, pieces)
    r = load(tmp_path, [text]).check_connectivity()
    assert r["floating_pieces"] == floating
    assert (r["opens"][0]["groups"] if r["opens"] else [pins]) == groups


@pytest.mark.parametrize("removed", [None, 100, 349])
def test_long_chain_of_patches(tmp_path, removed):
    # 350 M1 patches (800+4k, 450)-(804+4k, 550), k = 0..349, each sharing its
    # right edge with the next, run from u1/Y to x 2200 in u2/A (box index
    # path). Taking out patch 100 leaves a 4 DBU gap; patch 349 is the last,
    # and the one before it still reaches into u2/A (x 2196 > 2100).
    patches = [f"M1 ( {800 + 4 * k} 450 ) RECT ( 0 0 4 100 )" for k in range(350) if k != removed]
    net = "- n1 ( u1 Y ) ( u2 A ) + ROUTED " + " NEW ".join(patches) + " ;"
    r = load(tmp_path, [net]).check_connectivity()
    if removed == 100:
        assert single(r) == {"net": "n1", "pins": 2, "groups": Y1_A2, "floating_pieces": 0}
    else:
        assert (r["open_nets"], r["floating_pieces"]) == (0, 0)


def test_random_nets_cover_both_outcomes():
    # The random cases above are open and connected, with and without floating pieces.
    outcomes = set()
    for seed in range(60):
        _, pins, pieces = random_net(random.Random(seed))
        groups, floating = reference_groups(pins, pieces)
        outcomes.add((len(groups) == 1, floating > 0))
    assert outcomes == {(True, False), (True, True), (False, False), (False, True)}


# ---------------------------------------------------------------------------
# Contest designs (unrouted): every multi-pin net is open.

def multi_pin_nets_in_def_text(path: Path) -> tuple[int, int]:
    """(nets with >= 2 pins, nets with fewer), counted from the NETS section text."""
    text = path.read_text()
    section = re.search(r"^NETS \d+ ;(.*?)^END NETS", text, re.S | re.M).group(1)
    statements = [s for s in section.split(";") if s.strip().startswith("-")]
    pins = [len(re.findall(r"\(\s*\S+\s+\S+\s*\)", s)) for s in statements]
    return sum(1 for p in pins if p >= 2), sum(1 for p in pins if p < 2)


@pytest.mark.parametrize("name, multi, single_pin", [("ispd18_sample", 11, 0), ("ispd18_test1", 3152, 1),
                                                    ("standin_sample4", None, None)])
def test_unrouted_contest_design_is_all_open(name, multi, single_pin):
    base = contest_input(name)
    if multi is None:  # a generated design: the figures counted from its text
        multi, single_pin = multi_pin_nets_in_def_text(Path(str(base) + ".def"))
        assert multi > 10
    assert multi_pin_nets_in_def_text(Path(str(base) + ".def")) == (multi, single_pin)
    db = _engine.load([str(base) + ".lef"], str(base) + ".def")
    r = db.check_connectivity()
    assert {k: v for k, v in r.items() if k != "opens"} == {
        "nets_checked": multi, "open_nets": multi, "single_pin_nets": single_pin, "unrouted_nets": multi,
        "floating_pieces": 0}
    # Each open net: every pin is its own group.
    assert len(r["opens"]) == multi
    assert all(len(o["groups"]) == o["pins"] and all(len(g) == 1 for g in o["groups"]) for o in r["opens"])
