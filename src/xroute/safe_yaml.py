"""YAML read safely: a node tree with no surprises, or one clear error line.

:func:`compose_text` composes YAML text into its node tree (keys and values keep their lines)
and refuses, with ``<file>:<line>: <problem>``:

* files larger than :data:`MAX_BYTES`, and nesting deeper than :data:`MAX_DEPTH` (checked while
  composing, so a 5,000-deep file is an error, not a RecursionError);
* tags other than the plain ones (str, int, float, bool, null, seq, map, timestamp): no
  ``!custom``, no ``!!python/...``, no ``!!binary``;
* merge keys (``<<:``), which would silently bring in keys from elsewhere;
* documents whose aliases expand to more than :data:`MAX_NODES` nodes ("billion laughs");
* several documents in one file.

Numbers are read as YAML 1.2 reads them: ``1:30`` is the text "1:30", not YAML 1.1's base-60
number 90 (a seed or a time written that way would silently become another value); a setting
that expects a number then says so (:data:`SEXAGESIMAL_HINT`).

The composer never constructs Python objects; the schema layer
(:mod:`xroute.config_schema`) turns the checked scalars into values.
"""

from __future__ import annotations

import re

import yaml

MAX_BYTES = 1 << 20  # 1 MiB of YAML is far more than any config needs
MAX_DEPTH = 64  # nested mappings / lists
MAX_NODES = 50_000  # nodes after expanding aliases (the largest shipped config has about 300)

_PLAIN_TAGS = frozenset(
    "tag:yaml.org,2002:" + t for t in ("str", "int", "float", "bool", "null", "seq", "map", "timestamp")
)


class YamlProblem(ValueError):
    """A YAML problem with the 1-based line it is on (0: the file as a whole)."""

    def __init__(self, message: str, line: int = 0) -> None:
        super().__init__(message)
        self.message = message
        self.line = line


_INT = "tag:yaml.org,2002:int"
_FLOAT = "tag:yaml.org,2002:float"
_SEXAGESIMAL = re.compile(r"[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+(?:\.[0-9_]*)?")
SEXAGESIMAL_HINT = (" (YAML 1.1 would read this as a base-60 number; xroute does not: write the number itself, "
                    "e.g. 90 for 1:30)")


def looks_sexagesimal(text: str) -> bool:
    """Whether ``text`` is a YAML 1.1 base-60 number (``1:30``, ``-2:05:00``, ``1:30.5``)."""
    return _SEXAGESIMAL.fullmatch(text.strip()) is not None


class _DepthLimitedLoader(yaml.SafeLoader):
    """SafeLoader whose composer counts nesting and stops at MAX_DEPTH; its resolver has no
    base-60 integers or floats (see the module doc)."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self._depth = 0

    def compose_node(self, parent, index):  # type: ignore[no-untyped-def]
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                mark = self.peek_event().start_mark
                raise YamlProblem(f"YAML nested deeper than {MAX_DEPTH} levels", mark.line + 1)
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


# SafeLoader's implicit resolvers less the sexagesimal forms: ints and floats re-added without them.
_DepthLimitedLoader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag not in (_INT, _FLOAT)]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
_DepthLimitedLoader.add_implicit_resolver(
    _INT, re.compile(r"""^(?:[-+]?0b[0-1_]+|[-+]?0[0-7_]+|[-+]?(?:0|[1-9][0-9_]*)|[-+]?0x[0-9a-fA-F_]+)$"""),
    list("-+0123456789"))
_DepthLimitedLoader.add_implicit_resolver(
    _FLOAT, re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+][0-9]+)?|\.[0-9][0-9_]*(?:[eE][-+][0-9]+)?
        |[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


def _code(character: object) -> str:
    return f"{character:04x}" if isinstance(character, int) else f"{ord(str(character)[:1] or chr(0)):04x}"


def _line(node: yaml.Node) -> int:
    return node.start_mark.line + 1 if node.start_mark is not None else 0


def check_tree(root: yaml.Node) -> None:
    """Raises YamlProblem for custom tags, merge keys and alias bombs in a composed tree."""
    seen = 0
    stack: list[yaml.Node] = [root]
    while stack:
        node = stack.pop()
        seen += 1
        if seen > MAX_NODES:
            raise YamlProblem(f"YAML too large: more than {MAX_NODES:,} nodes once aliases are expanded", _line(node))
        if node.tag == "tag:yaml.org,2002:merge" or (
            isinstance(node, yaml.ScalarNode) and node.value == "<<" and node.tag == "tag:yaml.org,2002:merge"
        ):
            raise YamlProblem("merge keys (<<) are not supported: write the keys out", _line(node))
        if node.tag not in _PLAIN_TAGS:
            raise YamlProblem(f"YAML tag {node.tag!r} is not allowed (plain values, lists and mappings only)",
                              _line(node))
        if isinstance(node, yaml.MappingNode):
            for k, v in node.value:
                stack.append(v)
                stack.append(k)
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(reversed(node.value))


def read_text_limited(path: str) -> str:
    """The UTF-8 text of a regular file, read up to MAX_BYTES + 1 bytes (a huge file is an error;
    a FIFO or a device is refused without blocking). Raises InputError, UnicodeDecodeError or
    YamlProblem."""
    from xroute.regular_files import read_regular_bytes

    data = read_regular_bytes(path, MAX_BYTES, "file")
    if len(data) > MAX_BYTES:
        raise YamlProblem(f"YAML file too large: more than {MAX_BYTES:,} bytes")
    return data.decode("utf-8")


def _flow_depth_check(text: str) -> None:
    """Rejects flow nesting ("[[[[..." or "{a: {b: ...") deeper than MAX_DEPTH before parsing:
    PyYAML's scanner is quadratic in it (5,000 levels took 0.5 s). Quoted text and comments are
    skipped; brackets inside plain scalars may count, which only matters past MAX_DEPTH."""
    depth = 0
    line = 1
    quote = ""
    comment = False
    prev = "\n"
    for ch in text:
        if ch == "\n":
            line += 1
            comment = False
            if quote == "":
                prev = ch
                continue
        if comment:
            continue
        if quote:
            if ch == quote:
                quote = ""
        elif ch in "'\"" and (prev in " \t\n[{,:" ):
            quote = ch
        elif ch == "#" and prev in " \t\n":
            comment = True
        elif ch in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                raise YamlProblem(f"YAML nested deeper than {MAX_DEPTH} levels", line)
        elif ch in "]}":
            depth = max(depth - 1, 0)
        prev = ch


def compose_text(text: str) -> yaml.Node | None:
    """The checked node tree of ``text`` (None for an empty document). Raises YamlProblem."""
    if len(text) > MAX_BYTES:
        raise YamlProblem(f"YAML file too large: {len(text):,} characters (at most {MAX_BYTES:,})")
    _flow_depth_check(text)
    loader = None
    try:
        try:
            loader = _DepthLimitedLoader(text)  # its reader rejects characters YAML does not allow
            node = loader.get_single_node()
        except yaml.MarkedYAMLError as exc:
            mark = exc.problem_mark or exc.context_mark
            problem = " ".join(str(exc.problem or exc).split())
            raise YamlProblem(f"invalid YAML: {problem}", mark.line + 1 if mark is not None else 0) from None
        except yaml.reader.ReaderError as exc:  # a character YAML does not allow (NUL, ...): its line
            line = text.count("\n", 0, max(exc.position, 0)) + 1
            raise YamlProblem(f"invalid YAML: {exc.reason} (character #x{_code(exc.character)})", line) from None
        except yaml.YAMLError as exc:
            raise YamlProblem("invalid YAML: " + " ".join(str(exc).split())) from None
        except RecursionError:
            raise YamlProblem(f"YAML nested deeper than {MAX_DEPTH} levels") from None
    finally:
        if loader is not None:
            loader.dispose()
    if node is not None:
        check_tree(node)
    return node
