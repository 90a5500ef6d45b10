# SPDX-License-Identifier: MIT
"""Obviously correct NumPy references the tests compare smb against, and the random scenes."""

import itertools

import numpy as np

DIMS = (2, 3)
DTYPES = (np.float32, np.float64)


def random_boxes(rng, count, dim, dtype, extent=20.0):
    """`count` boxes on a half-unit grid, so that many touch exactly; a few are identical or
    have zero extent on some axis. Shape (count, 2, dim)."""
    lo = rng.integers(0, int(2 * extent), size=(count, dim)) / 2.0
    size = rng.integers(0, 7, size=(count, dim)) / 2.0
    boxes = np.stack([lo, lo + size], axis=1).astype(dtype)
    if count >= 4:
        boxes[count - 1] = boxes[0]
    return boxes


def overlap_matrix(a, b):
    """m[i, j]: a[i] overlaps b[j], closed (touching counts), in float64 of the boxes' values."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    lo_a, hi_a = a[:, 0, :], a[:, 1, :]
    lo_b, hi_b = b[:, 0, :], b[:, 1, :]
    return np.all((lo_a[:, None, :] <= hi_b[None, :, :]) & (lo_b[None, :, :] <= hi_a[:, None, :]), axis=2)


def brute_pairs(boxes, keep=None):
    """Every overlapping pair (i, j), i < j, sorted, as a (P, 2) int64 array; `keep(i, j)`, a
    vectorised predicate over index arrays, filters them further."""
    boxes = np.asarray(boxes)
    if len(boxes) == 0:
        return np.empty((0, 2), dtype=np.int64)
    matrix = np.triu(overlap_matrix(boxes, boxes), k=1)
    pairs = np.argwhere(matrix).astype(np.int64)
    if keep is not None and len(pairs):
        pairs = pairs[keep(pairs[:, 0], pairs[:, 1])]
    return pairs.reshape(-1, 2)


def brute_pairs_between(a, b):
    if len(a) == 0 or len(b) == 0:
        return np.empty((0, 2), dtype=np.int64)
    return np.argwhere(overlap_matrix(a, b)).astype(np.int64).reshape(-1, 2)


def filter_keep(categories, masks, statics):
    """The predicate of the filters: the bits pass both ways and the boxes are not both static."""
    categories = np.asarray(categories, dtype=np.uint64)
    masks = np.asarray(masks, dtype=np.uint64)
    statics = np.asarray(statics, dtype=bool)

    def keep(i, j):
        bits = ((categories[i] & masks[j]) != 0) & ((categories[j] & masks[i]) != 0)
        return bits & ~(statics[i] & statics[j])

    return keep


def brute_periodic(boxes, lo, hi, axes):
    """Every (i, j, shift), i < j, with box i overlapping box j translated by shift periods
    (the relation of smb::overlaps_with_shift, in float64), sorted; boxes lie within one period
    of the domain, so shifts are -1, 0 or +1."""
    boxes = np.asarray(boxes, dtype=np.float64)
    dim = boxes.shape[2]
    lo = np.asarray(lo, dtype=np.float64)
    hi = np.asarray(hi, dtype=np.float64)
    period = hi - lo
    found = []
    options = [(-1, 0, 1) if axes[k] else (0,) for k in range(dim)]
    for shift in itertools.product(*options):
        t = np.asarray(shift, dtype=np.float64) * np.where(axes, period, 0.0)
        moved_lo = boxes[:, 0, :] + t
        moved_hi = boxes[:, 1, :] + t
        meets = np.all((boxes[:, None, 0, :] <= moved_hi[None, :, :]) & (moved_lo[None, :, :] <= boxes[:, None, 1, :]),
                       axis=2)
        for i, j in np.argwhere(np.triu(meets, k=1)):
            found.append((i, j) + shift)
    found.sort()
    rows = np.asarray(found, dtype=np.int64).reshape(-1, 2 + dim)
    return rows[:, :2], rows[:, 2:].astype(np.int32)


def ray_entry(origin, direction, max_t, box):
    """smb::ray_entry in float64: the entry t of the ray into the closed box, or None."""
    enter, leave = 0.0, float(max_t)
    for k in range(len(origin)):
        o, d = float(origin[k]), float(direction[k])
        low, high = float(box[0][k]), float(box[1][k])
        if d == 0:
            if o < low or o > high:
                return None
            continue
        a, b = (low - o) / d, (high - o) / d
        if a > b:
            a, b = b, a
        enter, leave = max(enter, a), min(leave, b)
        if enter > leave:
            return None
    return enter


def as_set(pairs):
    return set(map(tuple, np.asarray(pairs).tolist()))


def sorted_rows(pairs):
    pairs = np.asarray(pairs).reshape(-1, 2)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]
