"""How the router reaches pins drawn on several layers (engine_cpp/region/region_prepare.cpp,
``pinTouches``), on a tiny drawn design with the exact route expected (DBU).

Technology: the drawn stack of ``lef_text.stack`` with four layers (M1 and M3 horizontal, M2 and
M4 vertical; tracks every 200 from 100, wires 60 wide, spacing 70, default vias V12, V23, V34).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from drawn import write_design
from lef_text import library, macro, pin, stack
from xroute import _engine
from xroute.check import check_design
from xroute.design import load_design



def block(m2_xlo: float, m2_xhi: float) -> str:
    """A 600 x 600 block whose pin A is drawn on M3 (the 200 x 200 square at its bottom middle)
    and on M2 (x m2_xlo..m2_xhi um of that square), with an obstruction on V2 over the whole block
    and on M3 all around the pin."""
    return macro("BLOCK", 0.6, 0.6,
                 pin("A", "INOUT", [("M2", (m2_xlo, 0.0, m2_xhi, 0.2)), ("M3", (0.2, 0.0, 0.4, 0.2))]),
                 obs=[("V2", (0.0, 0.0, 0.6, 0.6)), ("M3", (0.0, 0.27, 0.6, 0.6)), ("M3", (0.0, 0.0, 0.13, 0.27)),
                      ("M3", (0.47, 0.0, 0.6, 0.27))], klass="BLOCK")

# A 200 x 200 cell with pin A a 60 x 60 M1 square at its centre.
CELL = macro("PIN1", 0.2, 0.2, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.13))]))


# M2 as wide as M3's square, and 40 wide: narrower than the 60 wide wire, which then covers it
# across (a wire ending on a pin needs the pin's metal along the wire only).
@pytest.mark.parametrize("m2", [(0.2, 0.4), (0.28, 0.32)])
def test_a_pin_drawn_on_two_layers_is_reached_on_the_lower_one_without_a_via(
        tmp_path: Path, m2: tuple[float, float]) -> None:
    # The block at (1000, 1000): its pin covers x 1200..1400, y 1000..1200 on M3 and (at most) M2. Pin
    # access offers one point, on M3 at (1300, 1100), whose via goes up to M4 (M2's via up would
    # cut through the V2 obstruction). The cell's pin is at (1300, 300), straight below, on the
    # M2 track x = 1300. A wire on M2 ending at (1300, 1100) lies on the pin's M2 metal: that
    # reaches the pin. Before, the route had to end at the M3 point: a V23 at (1300, 700),
    # outside the obstruction, and M3 the wrong way up into the pin (two vias instead of one).
    def_text = (
        'VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN pins ;\nUNITS DISTANCE MICRONS 1000 ;\n'
        "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
        "TRACKS Y 100 DO 20 STEP 200 LAYER M1 M2 M3 M4 ;\n"
        "TRACKS X 100 DO 20 STEP 200 LAYER M1 M2 M3 M4 ;\n"
        "GCELLGRID X 0 DO 5 STEP 1000 ;\nGCELLGRID Y 0 DO 5 STEP 1000 ;\n"
        "COMPONENTS 2 ;\n- b BLOCK + PLACED ( 1000 1000 ) N ;\n- u PIN1 + PLACED ( 1200 200 ) N ;\n"
        "END COMPONENTS\nNETS 1 ;\n- n1 ( b A ) ( u A ) ;\nEND NETS\nEND DESIGN\n")
    lef, def_ = write_design(tmp_path, library(stack(layers=4), CELL, block(*m2)), def_text, stem="pins")
    d = load_design(lef=lef, def_=def_)
    pa = d.engine.pin_access()
    points = np.asarray(pa["points"])[pa["start"][0]:pa["start"][1]]
    assert points[:, :3].tolist() == [[1300, 1100, 2]]  # the block's pin: on M3 only

    session = _engine.RoutingSession(d.engine)
    region = session.open_region(tuple(int(v) for v in d.die_area))
    for i in range(len(region.candidates)):
        region.route_net(i)
    assert region.metrics()["violations"] == 0
    region.commit()
    routing = d.net_routing(0)
    assert routing["wires"] == [("M2", 1300, 1100, 1300, 300, 0, -1, -1)]
    assert routing["vias"] == [("V12", 1300, 300)]
    r = check_design(d)
    assert (r.opens, r.violations) == (0, 0)
