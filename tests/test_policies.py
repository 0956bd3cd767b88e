"""Net-order policies without the engine: the protocol, the built-ins' Python orders, the order
check and the registry (names, .py files, .onnx files: see test_onnx_policy.py)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from xroute.policies import (
    FEATURE_COLUMNS,
    CallablePolicy,
    HeuristicPolicy,
    NetOrderPolicy,
    PolicyError,
    RandomPolicy,
    get_policy,
    heuristic_order,
)
from xroute.net_order import check_order
from xroute.errors import XrouteError

REPO_ROOT = Path(__file__).resolve().parent.parent
REGION = {"iteration": 0, "region": 3, "box": (0, 0, 1000, 1000)}


def features(rows: list[tuple[int, int, int, int, int, int]]) -> np.ndarray:
    """int32[n, len(FEATURE_COLUMNS)] from (net, terminals, xlo, ylo, xhi, yhi) rows (pins = access points =
    terminals; the later columns 0)."""
    out = np.zeros((len(rows), len(FEATURE_COLUMNS)), dtype=np.int32)
    for i, (net, terms, xlo, ylo, xhi, yhi) in enumerate(rows):
        out[i, :9] = (net, terms, terms, terms, xlo, ylo, xhi, yhi, terms)
    return out


def test_feature_columns_match_the_engine() -> None:
    engine = pytest.importorskip("xroute._engine")
    assert tuple(engine.POLICY_FEATURES) == FEATURE_COLUMNS


def test_heuristic_order_on_drawn_candidates() -> None:
    f = features([
        (10, 2, 0, 0, 100, 100),   # row 0: half perimeter 200
        (11, 2, 0, 0, 50, 50),     # row 1: 100
        (12, 3, 0, 0, 100, 100),   # row 2: 200, more terminals than row 0
        (9, 2, 0, 0, 100, 100),    # row 3: 200, 2 terminals, lower net id than row 0
        (13, 4, 10, 10, 10, 10),   # row 4: 0 (a point)
    ])
    assert list(heuristic_order(f)) == [4, 1, 2, 3, 0]
    assert list(HeuristicPolicy().order(REGION, f)) == [4, 1, 2, 3, 0]
    assert list(heuristic_order(features([]))) == []


def test_random_policy_python_order_is_a_seeded_permutation() -> None:
    f = features([(i, 2, 0, 0, i, i) for i in range(40)])
    a = list(RandomPolicy(7).order(REGION, f))
    assert sorted(a) == list(range(40))
    assert a == list(RandomPolicy(7).order(REGION, f))
    assert a != list(RandomPolicy(8).order(REGION, f))
    assert a != list(RandomPolicy(7).order({**REGION, "region": 4}, f))
    with pytest.raises(PolicyError, match="seed"):
        RandomPolicy(-1)


def test_every_policy_satisfies_the_protocol() -> None:
    for p in (HeuristicPolicy(), RandomPolicy(3), CallablePolicy(lambda r, f: range(len(f)), name="fwd")):
        assert isinstance(p, NetOrderPolicy)
    assert (HeuristicPolicy.builtin, RandomPolicy.builtin, CallablePolicy.builtin) == ("heuristic", "random", None)

    def my_order(region, feats):
        return range(len(feats))

    assert CallablePolicy(my_order).name == "my_order"
    with pytest.raises(PolicyError, match="callable"):
        CallablePolicy(42)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("order", "message"),
    [
        ([0, 1], "returned 2 indices for 3 candidate nets"),
        ([0, 1, 1], "returned index 1 twice"),
        ([0, 1, 3], r"returned index 3, outside range\(3\)"),
        ([0, -1, 1], r"returned index -1, outside range\(3\)"),
        ([0.0, 1.0, 2.0], "float64"),
        ([[0, 1, 2]], "shape"),
        (None, "not a sequence of 3 ints"),
    ],
)
def test_check_order_rejects_non_permutations(order, message) -> None:
    with pytest.raises(PolicyError, match=message) as info:
        check_order(order, 3, "mine")
    assert "net-order policy 'mine'" in str(info.value)
    assert isinstance(info.value, XrouteError)


def test_check_order_accepts_any_int_sequence() -> None:
    assert check_order(np.array([2, 0, 1], dtype=np.int64), 3, "p") == [2, 0, 1]
    assert check_order(range(3), 3, "p") == [0, 1, 2]
    assert check_order((1, 0), 2, "p") == [1, 0]
    assert check_order([], 0, "p") == []


def test_registry_builtins() -> None:
    assert isinstance(get_policy("heuristic", 5), HeuristicPolicy)
    r = get_policy("random", 5)
    assert isinstance(r, RandomPolicy) and r.seed == 5
    with pytest.raises(PolicyError, match="unknown policy 'greedy'"):
        get_policy("greedy", 1)


def test_registry_loads_a_python_file(tmp_path: Path) -> None:
    path = tmp_path / "reverse.py"
    path.write_text("def order(region, features):\n    return list(range(len(features)))[::-1]\n")
    p = get_policy(str(path), 1)
    assert isinstance(p, CallablePolicy) and p.name == "reverse"
    assert list(p.order(REGION, features([(1, 2, 0, 0, 1, 1)] * 3))) == [2, 1, 0]
    named = tmp_path / "other.py"
    named.write_text("NAME = 'my-policy'\ndef order(region, features):\n    return range(len(features))\n")
    assert get_policy(str(named), 1).name == "my-policy"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (None, "policy file not found"),
        ("x = 1\n", "defines no function order"),
        ("order = 3\n", "defines no function order"),
        ("def order(region, features:\n", "failed to load: SyntaxError"),
        ("raise RuntimeError('boom')\n", "failed to load: RuntimeError: boom"),
    ],
)
def test_registry_bad_python_files(tmp_path: Path, text: str | None, message: str) -> None:
    path = tmp_path / "policy.py"
    if text is not None:
        path.write_text(text)
    with pytest.raises(PolicyError, match=message):
        get_policy(str(path), 1)


def test_importing_policies_loads_no_engine_and_no_torch() -> None:
    code = textwrap.dedent(
        """
        import sys
        import xroute.policies, xroute.net_order, xroute.policies.registry
        xroute.policies.get_policy("heuristic", 1)
        print(sorted(m for m in sys.modules if m.startswith("xroute._engine") or m.split(".")[0] == "torch"))
        """
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=REPO_ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
