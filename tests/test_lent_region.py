"""The policy seam lends the region being routed to a policy that declares ``needs_region``."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from conftest import pick, REPO_ROOT, require_testcase

SAMPLE = pick("ispd18_sample")  # or its generated stand-in without the contest data


class Peeking:
    """Routes the first pending net itself, then leaves the rest to the returned order."""

    name = "peeking"
    needs_region = True

    def __init__(self) -> None:
        self.lent = []

    def order(self, region, features):
        r = region["engine_region"]
        assert r.lent and tuple(r.box) == tuple(region["box"])
        assert len(r.candidates) == len(features) and r.unrouted() == list(range(len(features)))
        g = r.grid()
        assert g["flags"].shape[0] > 0
        r.route_net(0)
        assert r.is_routed(0)
        with pytest.raises(RuntimeError, match="committed by the router"):
            r.commit()
        self.lent.append(r)
        return list(range(len(features)))


def test_a_policy_needing_the_region_gets_it_for_one_call() -> None:
    from xroute.policies import CallablePolicy
    from xroute import load_design
    from xroute.router import route_design

    require_testcase(SAMPLE)
    policy = Peeking()
    d = load_design(SAMPLE)
    result = route_design(d, region_size=2, iterations=1, policy=policy)
    assert len(policy.lent) == result.final.regions > 0
    assert d.engine.check_connectivity()["open_nets"] == 0
    # Gone once the call returned: no dangling access.
    with pytest.raises(RuntimeError, match="lent to a policy for one call"):
        policy.lent[0].unrouted()
    # Without needs_region the dict has no engine_region (and the built-in order is unchanged).
    seen = []

    def plain(region, features):
        seen.append("engine_region" in region)
        return np.arange(len(features))

    route_design(load_design(SAMPLE), region_size=2, iterations=1, policy=CallablePolicy(plain))
    assert seen and not any(seen)


def test_importing_policies_loads_no_engine_torch_or_onnxruntime() -> None:
    code = ("import sys, policies, xroute.policies.onnx_policy, xroute.policies.rl.observation; "
            "print([m for m in ('torch', 'onnxruntime', 'xroute._engine') if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], cwd=REPO_ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_load_region_refuses_a_folder_without_or_with_a_bad_yaml(tmp_path) -> None:
    from xroute.testcases.regions import load_region
    from xroute.errors import InputError

    with pytest.raises(InputError, match="not a region folder"):
        load_region(tmp_path)
    (tmp_path / "region.yaml").write_text("files: [unclosed\n")
    with pytest.raises(InputError, match="malformed region description"):
        load_region(tmp_path)
