"""xroute: a VLSI detailed router whose net order is chosen by a pluggable policy.

The Python API lives here; the compiled engine is the private module
``xroute_cli._engine``.
"""

from xroute_cli.design import Design, load_design
from xroute_cli.errors import InputError, TestcaseNotFound, XrouteError

__all__ = ["Design", "InputError", "TestcaseNotFound", "XrouteError", "load_design"]
__version__ = "0.1.0"
