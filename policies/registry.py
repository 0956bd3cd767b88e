"""Policies by name: ``get_policy(spec, seed)`` for the net order, ``get_schedule_policy(spec)`` for
the iteration plans (``"rule"`` or a ``.py`` file defining ``plan(history, rule)``). Net-order spec ``"heuristic"``, ``"random"``, ``"rollout"``,
``"victims"``, ``"best-of-8"`` or ``"path/to/file.py"``.

A ``.py`` file is loaded with importlib from its path (it need not be on ``sys.path``) and must
define ``order(region, features)`` (see :mod:`xroute.net_order`); it may also set ``NAME`` (default:
the file's stem) and ``NEEDS_REGION = True`` (the region being routed is lent to ``order``). A ``.onnx`` file is an :class:`~xroute.policies.onnx_policy.OnnxPolicy` (onnxruntime
loaded then, not before).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from pathlib import Path
from typing import Any

from xroute.net_order import (
    BUILTIN_POLICIES,
    CallablePolicy,
    CallableSequentialPolicy,
    NetOrderPolicy,
    PolicyError,
    builtin_policy,
    is_builtin_name,
)
from xroute.errors import InputError, did_you_mean, safe_text
from xroute.policy_guard import kept_cwd
from xroute.policy_process import PolicyExit, user_code
from xroute.regular_files import check_input
from xroute.schedule import CallableSchedule, RuleSchedule, SchedulePolicy


def _check_regular(p: Path) -> None:
    """PolicyError unless ``p`` is a regular file (a FIFO or a device would block the import)."""
    try:
        check_input(p, "policy file")
    except InputError as exc:
        raise PolicyError(f"{exc.path}: {exc.message}") from None


def _load_module(p: Path) -> Any:
    """A policy file run as a module of its own (PolicyError, one line, when it cannot be)."""
    if not os.path.lexists(p):
        raise PolicyError(f"policy file not found: {p}")
    _check_regular(p)
    # A module name unique per file, so two policy files with the same stem do not collide.
    module_name = "xroute_policy_" + hashlib.sha1(str(p.resolve()).encode()).hexdigest()[:12]
    spec = importlib.util.spec_from_file_location(module_name, p)
    if spec is None or spec.loader is None:
        raise PolicyError(f"cannot load policy file {p}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        # a module that calls os.chdir does not move the run; its prints go to stderr (policy_process)
        with kept_cwd(), user_code(p.stem, str(p), "load"):
            spec.loader.exec_module(module)
    except KeyboardInterrupt:
        sys.modules.pop(module_name, None)
        raise
    except BaseException as exc:  # noqa: BLE001 - the user's file, whatever it raises: one line
        sys.modules.pop(module_name, None)
        import traceback

        here = os.path.abspath(p)  # the frames name the file by its absolute path
        lines = [f.lineno for f in traceback.extract_tb(exc.__traceback__) if os.path.abspath(f.filename) == here]
        line = getattr(exc, "lineno", None) if isinstance(exc, SyntaxError) else (lines[-1] if lines else None)
        where = f"{p}:{line}: " if line else f"{p}: "
        if isinstance(exc, PolicyExit):
            raise PolicyError(f"{where}policy file {p} failed to load: it called os._exit({safe_text(exc.code)}) "
                              "(a policy cannot end the run)") from None
        message = safe_text(exc)
        raise PolicyError(f"{where}policy file {p} failed to load: {type(exc).__name__}"
                          + (f": {message}" if message else "")) from None
    return module


def load_policy_file(path: str | Path) -> CallablePolicy | CallableSequentialPolicy:
    """The policy defined by a Python file's ``next_net(region, features)`` function (sequential:
    asked after every routed net) or else its ``order(region, features)`` function."""
    p = Path(path)
    module = _load_module(p)
    name = getattr(module, "NAME", None) or p.stem
    step: Any = getattr(module, "next_net", None)
    if callable(step):
        return CallableSequentialPolicy(step, name=str(name))
    fn: Any = getattr(module, "order", None)
    if not callable(fn):
        raise PolicyError(f"policy file {p} defines no function order(region, features) or next_net(region, features)")
    policy = CallablePolicy(fn, name=str(name))
    # NEEDS_REGION = True: region["engine_region"] is the region being routed, lent for the call (e.g. to
    # run a built-in search in this region only: region["engine_region"].route_rest("victims", search_budget=4)).
    policy.needs_region = bool(getattr(module, "NEEDS_REGION", False))  # type: ignore[attr-defined]
    return policy


def get_policy(spec: str, seed: int = 1, search_budget: int | None = None) -> NetOrderPolicy:
    """The policy named by ``spec``: ``heuristic``, ``random`` (seeded with ``seed``), ``rollout`` and
    ``victims`` (``search_budget`` trial routings per region; None: the engine's default), ``bestof`` (K =
    ``search_budget``), ``best-of-K``, a ``.py`` file defining ``order(region, features)`` (or
    ``next_net(region, features)``), or a ``.onnx`` net-order model. Raises :class:`PolicyError`
    (an ``XrouteError``) for anything else or a file that cannot be used."""
    if is_builtin_name(spec):
        return builtin_policy(spec, seed, search_budget)
    suffix = Path(spec).suffix.lower()
    if suffix == ".onnx":
        from xroute.policies.onnx_policy import OnnxPolicy

        if os.path.lexists(spec):
            _check_regular(Path(spec))
        return OnnxPolicy(spec)
    if suffix == ".py":
        return load_policy_file(spec)
    raise PolicyError(
        f"unknown policy '{spec}'{did_you_mean(spec, BUILTIN_POLICIES)}: use {', '.join(BUILTIN_POLICIES)}, best-of-K, "
        "a .py file defining order(region, features) or a .onnx net-order model"
    )


def get_schedule_policy(spec: str | None) -> SchedulePolicy:
    """The schedule policy ``spec``: None or ``"rule"`` (the router's own plans), the path of a
    Python file defining ``plan(history, rule)`` (:mod:`xroute.schedule`; ``NAME`` optional), or a
    ``.json`` schedule model (:mod:`xroute.schedule_model`)."""
    if spec is None or spec == RuleSchedule.name:
        return RuleSchedule()
    p = Path(spec)
    if p.suffix.lower() == ".json":
        from xroute.schedule_model import load_schedule_model

        return load_schedule_model(p)
    if p.suffix != ".py":
        raise PolicyError(f"unknown schedule policy '{spec}': use 'rule', the path of a .py file defining "
                          "plan(history, rule) or a .json schedule model")
    module = _load_module(p)
    fn: Any = getattr(module, "plan", None)
    if not callable(fn):
        raise PolicyError(f"schedule policy file {p} defines no function plan(history, rule)")
    return CallableSchedule(fn, name=str(getattr(module, "NAME", None) or p.stem))
