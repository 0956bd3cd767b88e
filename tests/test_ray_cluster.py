"""``xroute batch --backend ray --ray-address`` on a real two-node Ray cluster.

The test starts a head node and a worker node on this machine (``ray.cluster_utils.Cluster``:
separate GCS and raylet processes, as ``ray start --head`` and ``ray start --address`` make) and
stops both at the end. The head offers no CPU, so every job (one CPU each) must run on the worker
node. ``xroute batch`` runs as its own process, a driver that joins the cluster by its address, as
a user would; its results must equal the local backend's byte for byte.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import available

pytestmark = pytest.mark.slow

S1 = available("ispd18_sample")[0]
POLICIES = ("heuristic", "random")


def batch(tmp_path: Path, name: str, *args: str) -> dict:
    spec = tmp_path / f"{name}.yaml"
    spec.write_text(f"testcases: [{S1}]\npolicies: [{', '.join(POLICIES)}]\nout_dir: {tmp_path / name}\n")
    done = subprocess.run([sys.executable, "-m", "xroute", "batch", str(spec), "--jobs", "2", "--json", *args],
                          capture_output=True, text=True, timeout=600, env={**os.environ, "CI": "true"})
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(done.stdout)


def outputs(doc: dict) -> dict[str, tuple]:
    """Per job: the figures and the md5s of its routed DEF and DRC report (the metrics JSON holds times)."""
    seen = {}
    for job in doc["jobs"]:
        run_dir = Path(job["run_dir"])
        files = {p.name: hashlib.md5(p.read_bytes()).hexdigest()
                 for p in sorted(run_dir.iterdir()) if p.name.endswith((".routed.def", ".drc.rpt"))}
        seen[job["id"]] = (job["status"], job["wirelength_um"], job["vias"], job["violations"],
                           job["open_nets"], files)
    return seen


def test_batch_on_a_two_node_cluster_equals_the_local_backend(tmp_path: Path, testcase) -> None:
    pytest.importorskip("ray", reason="ray is an optional extra (pip install 'xroute[ray]')")
    from ray.cluster_utils import Cluster

    testcase(S1)
    local = batch(tmp_path, "local")
    cluster = Cluster(initialize_head=True, head_node_args={"num_cpus": 0, "include_dashboard": False})
    try:
        cluster.add_node(num_cpus=2)
        cluster.wait_for_nodes()
        assert len(cluster.list_all_nodes()) == 2
        remote = batch(tmp_path, "cluster", "--backend", "ray", "--ray-address", cluster.address)
    finally:
        cluster.shutdown()
    assert remote["backend"] == "ray" and local["backend"] == "local"
    assert remote["counts"] == local["counts"] == {"jobs": 2, "failed": 0, "errors": 0, "resumed": 0}
    assert outputs(remote) == outputs(local)
    assert len(outputs(remote)) == len(POLICIES) and all(len(v[-1]) == 2 for v in outputs(remote).values())
    assert all(Path(job["run_dir"]).is_relative_to(tmp_path / "cluster") for job in remote["jobs"])


def test_an_unreachable_cluster_is_one_line(tmp_path: Path, testcase) -> None:
    pytest.importorskip("ray", reason="ray is an optional extra (pip install 'xroute[ray]')")
    testcase(S1)
    spec = tmp_path / "b.yaml"
    spec.write_text(f"testcases: [{S1}]\npolicies: [heuristic]\nout_dir: {tmp_path / 'out'}\n")
    done = subprocess.run([sys.executable, "-m", "xroute", "batch", str(spec), "--backend", "ray",
                           "--ray-address", "127.0.0.1:9"], capture_output=True, text=True, timeout=60,
                          env={**os.environ, "CI": "true"})
    assert done.returncode != 0
    assert done.stderr == "error: cannot start or reach Ray at 127.0.0.1:9: nothing answers there (connection refused)\n"
    assert "Traceback" not in done.stderr and not (tmp_path / "out").exists()
