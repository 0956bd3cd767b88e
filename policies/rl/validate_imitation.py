"""Routes validation regions (training regions the scorer was not trained on) with set-scorer checkpoints.

    python -m xroute.policies.rl.validate_imitation TEACHER.npz CKPT.pt [CKPT.pt ...] [--val-every 5]

The validation regions are the teacher regions with ``index % val_every == 0`` (``imitation
--val-every`` leaves them out of training): never the held-out regions of the benchmark. Prints,
per testcase, the summed cost of the heuristic, the mean random order and the best teacher order
(from the teacher data) and of each checkpoint's order (routed here).
"""

from __future__ import annotations

import argparse
from collections import defaultdict
from pathlib import Path

import numpy as np
import torch


def main() -> None:
    from xroute import load_design
    from xroute.defaults import REGION_SIZE
    from xroute.policies.rl.imitation import model_order
    from xroute.policies.rl.set_scorer import load_checkpoint
    from xroute.policies.rl.teacher import load, score_orders
    from xroute.session import first_pass, open_session

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("teacher", type=Path)
    ap.add_argument("checkpoints", type=Path, nargs="+")
    ap.add_argument("--val-every", type=int, default=5)
    ap.add_argument("--region-size", type=int, default=REGION_SIZE)
    a = ap.parse_args()
    torch.set_num_threads(1)
    models = {p.parent.name + "/" + p.stem: load_checkpoint(p) for p in a.checkpoints}
    by_case = defaultdict(list)
    for r in load(a.teacher):
        if r.index % a.val_every == 0:
            by_case[r.testcase].append(r)
    for case, regions in sorted(by_case.items()):
        design = load_design(case)
        fp = first_pass(open_session(design), a.region_size)
        fns = {name: (lambda f, m=m: model_order(m, f)) for name, m in models.items()}
        got = score_orders(fp, [r.index for r in regions], fns, design.dbu_per_micron)
        heur = sum(r.costs[0] for r in regions)
        rows = {"heuristic": heur, "random (mean)": sum(r.costs[1:].mean() for r in regions),
                f"best of {len(regions[0].costs)}": sum(r.costs.min() for r in regions)}
        rows.update({k: float(np.sum(v)) for k, v in got.items()})
        print(f"{case}: {len(regions)} validation regions")
        for k, v in rows.items():
            print(f"  {k:<40}{v:>12,.1f}{100 * (v - heur) / heur:>+8.1f}%")


if __name__ == "__main__":
    main()
