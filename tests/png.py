"""PNG pixels for tests (8-bit greyscale/RGB/RGBA, no interlace): are the pixels all one colour?

Pillow (a dependency of matplotlib, in the test group) decodes when it is installed; otherwise a
minimal reader of our own does, slowly (pure Python: seconds for a full-page screenshot). Each
file is decoded once per content; the counts run on numpy arrays.
"""

from __future__ import annotations

import functools
import struct
import zlib
from pathlib import Path

import numpy as np

CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # PNG colour type -> samples per pixel


def read_png(path: Path) -> tuple[int, int, int, list[bytes]]:
    """(width, height, bytes per pixel, unfiltered rows)."""
    pixels = _pixels(path)
    height, width, bpp = pixels.shape
    return width, height, bpp, [row.tobytes() for row in pixels]


def _pixels(path: Path) -> np.ndarray:
    """The image as a (height, width, samples) uint8 array."""
    data = path.read_bytes()
    return _decode(data)


@functools.lru_cache(maxsize=8)
def _decode(data: bytes) -> np.ndarray:
    try:
        from PIL import Image
    except ImportError:
        return _decode_here(data)
    import io

    with Image.open(io.BytesIO(data)) as image:
        assert image.format == "PNG", image.format
        mode = {"L": 1, "LA": 2, "RGB": 3, "RGBA": 4}
        if image.mode not in mode:
            image = image.convert("RGBA")
        array = np.asarray(image, dtype=np.uint8)
    return array.reshape(array.shape[0], array.shape[1], -1)


def _decode_here(data: bytes) -> np.ndarray:
    """The pure-Python decoder: unfilter every row (filters None, Sub, Up, Average, Paeth)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert header is not None
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and interlace == 0 and colour in CHANNELS, header
    bpp = CHANNELS[colour]
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows: list[bytes] = []
    prev = bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, bpp)


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
