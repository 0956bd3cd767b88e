"""xroute: a VLSI detailed router whose net order is chosen by a pluggable, learnable policy.

One import root, in layers that only import downward (ARCHITECTURE.md):

* bottom: :mod:`xroute.errors` and the private compiled engine ``xroute._engine``;
* the library: :mod:`xroute.design` (load_design, Design), :mod:`xroute.groute` (built-in global
  router), :mod:`xroute.router` (route_design), :mod:`xroute.policy` (the net-order seam and the
  built-in policies), :mod:`xroute.outputs`, :mod:`xroute.config` and :mod:`xroute.pipeline`
  (load -> global route when needed -> route -> write and check), which every command and
  environment runs;
* on top of it: :mod:`xroute.policies` (policy files, ONNX models, learning), :mod:`xroute.envs`
  (Gymnasium environments) and :mod:`xroute.testcases` (the search path, generators, regions);
* last: :mod:`xroute.cli`, the ``xroute`` command.

Importing ``xroute`` loads neither the compiled engine (that happens on first use) nor torch.
"""

from importlib.metadata import PackageNotFoundError, version

from xroute.design import Design, load_design
from xroute.errors import (
    InputError,
    PolicyError,
    RouteArgumentError,
    SettingsError,
    TestcaseNotFound,
    XrouteError,
)
from xroute.pipeline import prepare_design, route_to_outputs
from xroute.router import RouteResult, RouteSettings, route_design

try:
    __version__ = version("xroute")  # the one definition is pyproject.toml's
except PackageNotFoundError:  # not installed (a source tree on sys.path)
    __version__ = "0+unknown"

__all__ = [
    "Design",
    "InputError",
    "PolicyError",
    "RouteArgumentError",
    "RouteResult",
    "RouteSettings",
    "SettingsError",
    "TestcaseNotFound",
    "XrouteError",
    "load_design",
    "prepare_design",
    "route_design",
    "route_to_outputs",
]
