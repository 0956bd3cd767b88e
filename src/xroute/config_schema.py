"""YAML -> frozen dataclasses, validated in one pass with the file and line of every problem.

The schema is the dataclasses themselves: each field's type annotation says what a value may be
(``int``, ``float``, ``bool``, ``str``, ``X | None``, ``tuple[int, int]``, ``tuple[T, ...]``,
``Literal[...]``, or a nested dataclass), and ``field(metadata=...)`` adds ``min`` / ``max``
bounds and a ``check``: the name of a function ``(value, ctx) -> (value, problem)`` that may
also transform the value (e.g. resolve a path relative to the file). The YAML is
composed into its node tree (not just ``safe_load``), so every key and value keeps its line:
unknown keys, duplicate keys, wrong types and out-of-range values are reported as
``<file>:<line>: <dotted.key>: <problem>``. All problems are collected; :class:`ConfigError`
shows the first one and counts the rest.

Other commands reuse this module with their own dataclasses (see :func:`load_sections`).
"""

from __future__ import annotations

import dataclasses
import math
import os
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Literal, Union

import yaml

from xroute.errors import InputError, did_you_mean, one_line
from xroute.safe_yaml import SEXAGESIMAL_HINT, looks_sexagesimal

_NUMBER_TYPES = (int, float)
_NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")


class ConfigError(InputError):
    """A bad configuration file: ``path`` and ``line`` name the first problem; ``problems`` holds
    every problem found as ``(line, message)``."""

    def __init__(self, message: str, path: str = "", line: int = 0,
                 problems: tuple[tuple[int, str], ...] = ()) -> None:
        self.problems = problems or ((line, message),)
        super().__init__(message, path, line)

    def __reduce__(self):  # keep everything through pickling (worker processes)
        return (type(self), (self.message, self.path, self.line, self.problems))


Check = Callable[[Any, "Context"], "tuple[Any, str | None]"]


@dataclass
class Context:
    """What a validation pass knows: the file (for messages and relative paths) and the problems."""

    path: str  # the YAML file as named by the user
    base_dir: Path  # relative paths in the file are relative to this folder
    checks: dict[str, Check]  # named checks
    problems: list[tuple[int, str]] = dataclasses.field(default_factory=list)

    def problem(self, node: yaml.Node | None, key: str, message: str) -> None:
        line = node.start_mark.line + 1 if node is not None else 0
        self.problems.append((line, one_line(f"{key}: {message}" if key else message)))

    def resolve(self, value: str) -> Path:
        """A path from the file: ``~`` expanded, relative to the file's folder."""
        p = Path(os.path.expanduser(value))
        return p if p.is_absolute() else self.base_dir / p


def compose_file(path: str | os.PathLike[str]) -> yaml.Node | None:
    """The YAML node tree of a file. Raises ConfigError for unreadable files and bad YAML."""
    from xroute.safe_yaml import YamlProblem, compose_text, read_text_limited

    p = Path(path)
    try:
        text = read_text_limited(str(p))
    except YamlProblem as exc:
        raise ConfigError(exc.message, str(p), exc.line) from None
    except InputError as exc:  # missing, not a regular file (a FIFO would block), unreadable
        raise ConfigError(f"cannot read config file: {exc.message}", exc.path, 0) from None
    except OSError as exc:
        raise ConfigError(f"cannot read config file: {exc.strerror or exc}", str(p), 0) from exc
    except UnicodeDecodeError as exc:
        raise ConfigError("config file is not UTF-8 text", str(p), 0) from exc
    try:
        return compose_text(text)  # no custom tags or merge keys; depth and size limited
    except YamlProblem as exc:
        raise ConfigError(exc.message, str(p), exc.line) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else 0
        raise ConfigError(f"invalid YAML: {exc.problem or exc}", str(p), line) from exc
    except yaml.YAMLError as exc:
        raise ConfigError(f"invalid YAML: {exc}", str(p), 0) from exc


_CONSTRUCTOR = yaml.SafeLoader("")  # turns scalar nodes into Python values (int, float, bool, str, None)


def scalar_value(node: yaml.ScalarNode) -> Any:
    if node.tag in _NUMBER_TAGS and looks_sexagesimal(str(node.value)):  # "!!int 1:30": text, never 90
        return str(node.value)
    try:
        return _CONSTRUCTOR.construct_object(node, deep=True)
    except (ValueError, OverflowError, yaml.YAMLError):  # e.g. a date-like "2020-13-45": keep the text
        return str(node.value)


def _type_name(tp: Any) -> str:
    origin = typing.get_origin(tp)
    if tp is type(None):
        return "null"
    if origin is Literal:
        return "one of " + ", ".join(repr(a) for a in typing.get_args(tp))
    if origin in (Union, types.UnionType):
        return " or ".join(_type_name(a) for a in typing.get_args(tp))
    if origin is tuple:
        args = typing.get_args(tp)
        if len(args) == 2 and args[1] is Ellipsis:
            return f"a list of {_type_name(args[0])}"
        return f"a list of {len(args)} values [{', '.join(_type_name(a) for a in args)}]"
    if dataclasses.is_dataclass(tp):
        return "a mapping"
    return {int: "an integer", float: "a number", bool: "true or false", str: "a string"}.get(tp, str(tp))


def _convert(tp: Any, node: yaml.Node, key: str, ctx: Context, meta: typing.Mapping[str, Any]) -> Any:
    """The value of ``node`` as type ``tp``; records a problem and returns None when it is not."""
    origin = typing.get_origin(tp)
    if origin in (Union, types.UnionType):
        args = typing.get_args(tp)
        if isinstance(node, yaml.ScalarNode) and scalar_value(node) is None and type(None) in args:
            return None
        rest = [a for a in args if a is not type(None)]
        if len(rest) == 1:
            return _convert(rest[0], node, key, ctx, meta)
        for a in rest:  # first alternative that fits without problems
            trial = Context(ctx.path, ctx.base_dir, ctx.checks)
            value = _convert(a, node, key, trial, meta)
            if not trial.problems:
                return value
        ctx.problem(node, key, f"expected {_type_name(tp)}")
        return None
    if dataclasses.is_dataclass(tp):
        return build(tp, node, key, ctx)
    if origin is tuple:
        return _convert_tuple(tp, node, key, ctx, meta)
    if not isinstance(node, yaml.ScalarNode):
        ctx.problem(node, key, f"expected {_type_name(tp)}, found a {'list' if isinstance(node, yaml.SequenceNode) else 'mapping'}")
        return None
    value = scalar_value(node)
    if origin is Literal:
        if value not in typing.get_args(tp):
            ctx.problem(node, key, f"expected {_type_name(tp)}, found {value!r}")
            return None
        return value
    ok = isinstance(value, tp) and not (tp is not bool and isinstance(value, bool))
    if tp is float and isinstance(value, int) and not isinstance(value, bool):
        value, ok = float(value), True
    if not ok:
        hint = SEXAGESIMAL_HINT if tp in _NUMBER_TYPES and isinstance(value, str) and looks_sexagesimal(value) else ""
        ctx.problem(node, key, f"expected {_type_name(tp)}, found {value!r}{hint}")
        return None
    if isinstance(value, float) and not math.isfinite(value):  # NaN passes every bound check
        ctx.problem(node, key, f"must be a finite number, found {value!r}")
        return None
    if isinstance(value, _NUMBER_TYPES):
        lo, hi = meta.get("min"), meta.get("max")
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            bounds = f"between {lo} and {hi}" if lo is not None and hi is not None else (
                f"at least {lo}" if lo is not None else f"at most {hi}")
            ctx.problem(node, key, f"must be {bounds}, found {value!r}")
            return None
    check = meta.get("check")
    if check is not None:
        value, message = ctx.checks[check](value, ctx)
        if message:
            ctx.problem(node, key, message)
            return None
    return value


def _convert_tuple(tp: Any, node: yaml.Node, key: str, ctx: Context, meta: typing.Mapping[str, Any]) -> Any:
    args = typing.get_args(tp)
    if not isinstance(node, yaml.SequenceNode):
        ctx.problem(node, key, f"expected {_type_name(tp)}")
        return None
    items = node.value
    if len(args) == 2 and args[1] is Ellipsis:
        lo = meta.get("min_items", 0)
        if len(items) < lo:
            ctx.problem(node, key, f"needs at least {lo} entries, found {len(items)}")
        elem_meta = meta.get("items", {})
        return tuple(_convert(args[0], n, f"{key}[{i}]", ctx, elem_meta) for i, n in enumerate(items))
    if len(items) != len(args):
        ctx.problem(node, key, f"expected {_type_name(tp)}, found {len(items)} values")
        return None
    return tuple(_convert(a, n, f"{key}[{i}]", ctx, meta) for i, (a, n) in enumerate(zip(args, items)))


def build(cls: type, node: yaml.Node | None, key: str, ctx: Context) -> Any:
    """An instance of dataclass ``cls`` from a mapping node (None = all defaults)."""
    hints = typing.get_type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    values: dict[str, Any] = {}
    before = len(ctx.problems)
    if node is not None and not (isinstance(node, yaml.ScalarNode) and scalar_value(node) is None):
        if not isinstance(node, yaml.MappingNode):
            ctx.problem(node, key, "expected a mapping of settings")
            return None
        seen: set[str] = set()
        for knode, vnode in node.value:
            name = scalar_value(knode) if isinstance(knode, yaml.ScalarNode) else None
            dotted = f"{key}.{name}" if key else str(name)
            if not isinstance(name, str):
                ctx.problem(knode, key, f"keys must be strings, found {name!r}")
                continue
            if name in seen:
                ctx.problem(knode, dotted, "duplicate key")
                continue
            seen.add(name)
            f = fields.get(name)
            if f is None:
                known = ", ".join(sorted(fields)) or "none"
                ctx.problem(knode, dotted, f"unknown key{did_you_mean(name, fields)} (known keys here: {known})")
                continue
            values[name] = _convert(hints[name], vnode, dotted, ctx, f.metadata)
    missing = [n for n, f in fields.items() if n not in values and f.default is dataclasses.MISSING
               and f.default_factory is dataclasses.MISSING]
    for n in missing:
        ctx.problem(node, f"{key}.{n}" if key else n, "required key is missing")
    if len(ctx.problems) > before:
        return None
    try:
        return cls(**values)
    except (ValueError, TypeError) as exc:  # cross-field checks in __post_init__
        ctx.problem(node, key, str(exc))
        return None


def raise_problems(ctx: Context) -> None:
    """Raises ConfigError for the first recorded problem (the message counts the others)."""
    if not ctx.problems:
        return
    line, message = ctx.problems[0]
    more = len(ctx.problems) - 1
    if more:
        message += f" (and {more} more problem{'s' if more > 1 else ''} in this file)"
    raise ConfigError(message, ctx.path, line, tuple(ctx.problems))


def load_sections(cls: type, path: str | os.PathLike[str], checks: dict[str, Check] | None = None) -> Any:
    """Loads ``path`` into the dataclass ``cls`` (whose fields are the file's top-level keys).

    ``checks`` maps the names used in ``metadata={"check": ...}`` to functions
    ``(value, ctx) -> (value, problem or None)``. Raises :class:`ConfigError` naming the file and line of a problem.
    """
    node = compose_file(path)
    ctx = Context(str(path), Path(path).resolve().parent, checks or {})
    result = build(cls, node, "", ctx)
    raise_problems(ctx)
    return result


def setting(default: Any = dataclasses.MISSING, *, min: Any = None, max: Any = None, check: str | None = None,
            unit: str = "", help: str = "", **extra: Any) -> Any:
    """A dataclass field with validation metadata (bounds, a named check, unit and help)."""
    meta = {"min": min, "max": max, "check": check, "unit": unit, "help": help, **extra}
    if isinstance(default, (list, dict, set)):
        raise TypeError("use a tuple default")
    return dataclasses.field(default=default, metadata=meta)
