"""``xroute export CHECKPOINT --out model.onnx``: a training checkpoint as an ONNX net-order model.

The model follows the contract read by ``OnnxPolicy`` (see :mod:`xroute.policies.rl.export`). Needs
the ``train`` extra (torch, onnx). Exit status 2 for a missing or foreign checkpoint.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import stdout_console
from xroute.errors import XrouteError


class ExportError(XrouteError):
    """Export cannot run (missing extra)."""


def export(
    checkpoint: Annotated[Path, typer.Argument(help="A .pt checkpoint written by `xroute train`.", show_default=False)],
    out: Annotated[Path, typer.Option("--out", help="The ONNX file to write.")],
) -> None:
    """Export a training checkpoint to an ONNX model that scores a region's candidate nets in one call."""
    try:
        import onnx  # noqa: F401
        import torch  # noqa: F401
    except ImportError as exc:
        raise ExportError(f"export needs the train extra: pip install 'xroute[train]' ({exc.name} is missing)") from exc
    from xroute.policies.rl.export import export_checkpoint

    path = export_checkpoint(checkpoint, out)
    stdout_console().print(f"wrote {path} ({path.stat().st_size / 1024:,.0f} KiB)", highlight=False)
