# SPDX-License-Identifier: BSD-3-Clause
"""A small PNG reader, enough for a test to look at a screenshot's pixels: 8-bit RGB or RGBA,
not interlaced, which is what Chromium writes."""

from __future__ import annotations

import struct
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {2: 3, 6: 4}  # colour type: RGB, RGBA


def read_png(data: bytes) -> tuple[int, int, int, list[bytes]]:
    """(width, height, channels, rows): rows[y][x * channels + c] is channel c of pixel (x, y).
    Raises ValueError on anything else, or on a damaged file."""
    if data[:8] != SIGNATURE:
        raise ValueError("not a PNG file")
    header, compressed, position = None, [], 8
    while position < len(data):
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        crc = data[position + 8 + length:position + 12 + length]
        if len(body) != length or crc != struct.pack(">I", zlib.crc32(kind + body)):
            raise ValueError(f"damaged {kind.decode(errors='replace')} chunk")
        position += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            compressed.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError("no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in CHANNELS or interlace:
        raise ValueError(f"unsupported PNG: bit depth {depth}, colour type {colour}, "
                         f"interlace {interlace} (8-bit RGB or RGBA, not interlaced only)")
    channels = CHANNELS[colour]
    stride = width * channels
    raw = zlib.decompress(b"".join(compressed))
    if len(raw) != height * (stride + 1):
        raise ValueError("image data is not width x height pixels")
    rows, above = [], bytes(stride)
    for y in range(height):
        start = y * (stride + 1)
        row = _unfilter(raw[start], bytearray(raw[start + 1:start + 1 + stride]), above,
                        channels)
        rows.append(bytes(row))
        above = row
    return width, height, channels, rows


def _unfilter(kind: int, row: bytearray, above: bytes, left: int) -> bytearray:
    """One row with its filter undone: each byte was stored as the difference from a
    prediction made of the byte `left` bytes before it (a), the byte above (b) and the byte
    above a (c); the row above is already unfiltered."""
    if kind not in range(5):
        raise ValueError(f"unknown filter type {kind}")
    if kind == 0:
        return row
    if kind == 2:
        return bytearray((x + b) & 255 for x, b in zip(row, above))
    for i in range(len(row)):
        a = row[i - left] if i >= left else 0
        if kind == 1:
            predicted = a
        elif kind == 3:
            predicted = (a + above[i]) >> 1
        else:  # Paeth
            b, c = above[i], above[i - left] if i >= left else 0
            pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
            predicted = a if pa <= pb and pa <= pc else b if pb <= pc else c
        row[i] = (row[i] + predicted) & 255
    return row
