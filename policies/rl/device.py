"""The torch device a trainer runs on: ``auto`` (CUDA when torch sees one, else the CPU), ``cpu`` or ``cuda``.

:data:`DEVICES` imports without torch (the CLI checks a name before it knows torch is installed).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import torch

DEVICES = ("auto", "cpu", "cuda")


def pick_device(name: str) -> torch.device:
    """``auto`` -> cuda when available, else cpu; ``cuda`` without a CUDA device is an error."""
    import torch

    if name not in DEVICES:
        raise ValueError(f"unknown device {name!r}: use {', '.join(DEVICES)}")
    if name == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    if name == "cuda" and not torch.cuda.is_available():
        raise ValueError("device cuda asked for but torch sees no CUDA device")
    return torch.device(name)
