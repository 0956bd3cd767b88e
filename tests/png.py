"""PNG pixels for tests: the size of an image, how many colours it holds, how many pixels of one colour.

Pillow decodes (it comes with matplotlib, in the test group); each file's content is decoded once
and the counts run on numpy arrays (a full-page screenshot is 3.4 million pixels).
"""

from __future__ import annotations

import functools
import io
from pathlib import Path

import numpy as np


def png_size(path: Path) -> tuple[int, int]:
    """(width, height) of the PNG."""
    height, width, _ = _pixels(path).shape
    return width, height


def _pixels(path: Path) -> np.ndarray:
    """The image as a (height, width, samples) uint8 array."""
    return _decode(path.read_bytes())


@functools.lru_cache(maxsize=8)
def _decode(data: bytes) -> np.ndarray:
    from PIL import Image

    with Image.open(io.BytesIO(data)) as image:
        assert image.format == "PNG", image.format
        if image.mode not in ("L", "LA", "RGB", "RGBA"):
            image = image.convert("RGBA")
        array = np.asarray(image, dtype=np.uint8)
    return array.reshape(array.shape[0], array.shape[1], -1)


def distinct_colours(path: Path, limit: int = 1000) -> int:
    """How many distinct pixel values the image holds (at most ``limit``)."""
    pixels = _pixels(path).astype(np.uint32)
    packed = np.zeros(pixels.shape[:2], dtype=np.uint32)
    for channel in range(pixels.shape[2]):  # at most 4 samples of 8 bits: one 32-bit key per pixel
        packed = (packed << 8) | pixels[:, :, channel]
    return min(limit, len(np.unique(packed)))


def colour_pixels(path: Path, rgb: tuple[int, int, int], tolerance: int = 12) -> int:
    """How many pixels are within ``tolerance`` of ``rgb`` in every channel."""
    pixels = _pixels(path)[:, :, :3].astype(np.int16)
    close = np.abs(pixels - np.array(rgb, dtype=np.int16)) <= tolerance
    return int(np.count_nonzero(close.all(axis=2)))
