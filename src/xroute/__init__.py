"""xroute: a VLSI detailed router whose net order is chosen by a pluggable, learnable policy.

One import root, in layers that only import downward (ARCHITECTURE.md):

* bottom: :mod:`xroute.errors` and the private compiled engine ``xroute._engine``;
* the library: :mod:`xroute.design` (load_design, Design), :mod:`xroute.groute` (built-in global
  router), :mod:`xroute.router` (route_design), :mod:`xroute.net_order` (the net-order seam and the
  built-in policies), :mod:`xroute.outputs`, :mod:`xroute.config` and :mod:`xroute.pipeline`
  (load -> global route when needed -> route -> write and check), which every command and
  environment runs;
* on top of it: :mod:`xroute.policies` (policy files, ONNX models, learning), :mod:`xroute.envs`
  (Gymnasium environments) and :mod:`xroute.testcases` (the search path, generators, regions);
* last: :mod:`xroute.cli`, the ``xroute`` command.

Importing ``xroute`` loads neither the compiled engine (that happens on first use) nor torch.
"""

from __future__ import annotations

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from xroute.errors import (
    InputError,
    PolicyError,
    RouteArgumentError,
    SettingsError,
    TestcaseNotFound,
    XrouteError,
)

try:
    __version__ = version("xroute")  # the one definition is pyproject.toml's
except PackageNotFoundError:  # not installed (a source tree on sys.path)
    __version__ = "0+unknown"

# The library's entry points, imported on first use (the router modules load the engine).
_LAZY = {
    "Design": "xroute.design",
    "load_design": "xroute.design",
    "prepare_design": "xroute.pipeline",
    "route_to_outputs": "xroute.pipeline",
    "RouteResult": "xroute.router",
    "RouterSettings": "xroute.router",
    "route_design": "xroute.router",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'xroute' has no attribute '{name}'")


__all__ = [
    "Design",
    "InputError",
    "PolicyError",
    "RouteArgumentError",
    "RouteResult",
    "RouterSettings",
    "SettingsError",
    "TestcaseNotFound",
    "XrouteError",
    "load_design",
    "prepare_design",
    "route_design",
    "route_to_outputs",
]
