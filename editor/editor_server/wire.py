"""What travels: binary frames, JSON read from request bodies, refusals with their HTTP status."""

import json
import math
import struct

import numpy as np

from .limits import MAX_DIGITS


class Refusal(Exception):
    """a request refused with an HTTP status and a one-line reason"""

    def __init__(self, status, reason):
        super().__init__(reason)
        self.status = status


def shown(value, limit=80):
    """repr(value), cut to `limit` characters for a message"""
    r = repr(value)
    return r if len(r) <= limit else r[:limit - 3] + "..."


def json_safe(value):
    """value with numpy scalars as Python numbers and non-finite floats as None (JSON.parse has no NaN)"""
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def frame(header, arrays):
    """b"TCB1", the JSON header's length (uint32, little endian), the header, then each array (little endian, each
    at a multiple of 8 bytes); the header lists them: {"arrays": [{"name", "dtype", "shape", "offset"}]}.
    `arrays`: pairs (name, array), or triples (name, array, dtype) to convert it to dtype as it is copied in.
    Returns one preallocated bytearray: each array is copied once, straight into place."""
    entries, sources, offset = [], [], 0
    for name, a, *dtype in arrays:
        a = np.asarray(a)
        dt = np.dtype(dtype[0]) if dtype else a.dtype
        entries.append({"name": name, "dtype": dt.str, "shape": list(a.shape), "offset": offset})
        sources.append((a, dt, offset))
        offset += -(-a.size * dt.itemsize // 8) * 8
    head = json.dumps(dict(header, arrays=entries)).encode()
    head += b" " * (-(8 + len(head)) % 8)
    start = 8 + len(head)
    out = bytearray(start + offset)  # zeros: the padding
    out[:4] = b"TCB1"
    struct.pack_into("<I", out, 4, len(head))
    out[8:start] = head
    for a, dt, at in sources:
        if a.size:
            np.copyto(np.frombuffer(out, dt, a.size, start + at).reshape(a.shape), a, casting="unsafe")
    return out


def json_integer(text):
    """an integer of a request: refused (ValueError) above MAX_DIGITS digits, before Python's own limit (4300
    digits, whose ValueError would come from deep inside the parser) and its quadratic-time conversion"""
    digits = len(text) - text.startswith("-")
    if digits > MAX_DIGITS:
        raise ValueError(f"an integer of {digits} digits (at most {MAX_DIGITS})")
    return int(text)


def json_constant(name):
    """NaN, Infinity, -Infinity: Python's json reads them, JSON has no such numbers"""
    raise ValueError(f"{name} is not a JSON number")
