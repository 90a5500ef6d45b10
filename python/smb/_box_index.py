# SPDX-License-Identifier: MIT
"""smb.BoxIndex: region queries and ray casts over an array of boxes, indexed once."""

import math

import numpy as np

from . import _arguments
from . import _readout


def _box_shape(boxes):
    """The dimension of an array of boxes, (N, 2, D) or (N, 2*D)."""
    shape = np.shape(boxes)
    if len(shape) == 3 and shape[1] == 2 and shape[2] in (2, 3):
        return shape[2]
    if len(shape) == 2 and shape[1] in (4, 6):
        return shape[1] // 2
    raise ValueError("boxes must have shape (N, 2, D) (rows min, max) or (N, 2*D) with D = 2 or 3; "
                     f"got shape {shape}")


class BoxIndex:
    """The boxes of one moment, indexed for queries: every box overlapping a query box (closed:
    touching counts) and the boxes a ray enters.

    BoxIndex(boxes, ids=None, *, dtype=None): box i under ids[i], or under its index i when ids
    is None. The index holds a copy of the boxes; build() again after they change (linear time,
    reusing the memory). Ids come back as uint64 when given (any integers in [0, 2**64 - 1],
    repeats allowed), as int64 when they are indices. dim is the boxes' (2 or 3); dtype float32
    or float64, by default float32 for float32 boxes and float64 for any other (converted only
    when every value converts exactly, else TypeError). InvalidBoxError for NaN, infinity or
    min > max; a call that raises leaves the index as it was.
    """

    def __init__(self, boxes, ids=None, *, dtype=None):
        if dtype is None:
            dtype = np.float32 if getattr(boxes, "dtype", None) == np.float32 else np.float64
        implementation, self.dim, self.dtype = _arguments.implementation("BoxIndex", _box_shape(boxes), dtype)
        self._impl = implementation()
        self._impl.build(boxes, ids)

    def build(self, boxes, ids=None):
        """Replaces the indexed boxes (same dim and dtype), as the constructor takes them."""
        self._impl.build(boxes, ids)

    def query(self, box):
        """Ids of the boxes overlapping `box` ((2, dim) or (2*dim,)), sorted."""
        return self._impl.query(box)

    def query_batch(self, boxes):
        """(H, 2) array of (query index, id) for every box overlapping each query box, sorted."""
        return self._impl.query_batch(boxes)

    def cast_ray(self, origin, direction, max_t=math.inf, *, all=False):
        """The boxes the ray origin + t * direction, 0 <= t <= max_t, enters: (ids, t).

        The nearest one (least t, then least id), or with all=True every one sorted by (t, id).
        t is 0 for a box containing the origin. ArgumentError for an invalid ray.
        """
        return self._impl.cast_ray(origin, direction, _arguments.real("max_t", max_t), bool(all))

    def __len__(self):
        """The number of boxes indexed."""
        return self._impl.size()

    bytes_held = _readout.forwarded("bytes_held", "Heap bytes the index holds.")

    def __repr__(self):
        return f"smb.BoxIndex(dim={self.dim}, dtype={self.dtype.name}, size={len(self)})"
