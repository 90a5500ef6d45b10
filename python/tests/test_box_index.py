# SPDX-License-Identifier: MIT
"""smb.BoxIndex against the brute force: region queries and ray casts over random scenes,
rebuilt over several steps, with indices and with ids across the 64-bit range; bad input
leaves the index as it was."""

import numpy as np
import pytest

import smb
from reference import DIMS, DTYPES, overlap_matrix, random_boxes, ray_entry


def expected_hits(boxes, names, queries):
    rows = [(q, int(names[i])) for q, i in np.argwhere(overlap_matrix(queries, boxes)).tolist()]
    return sorted(rows)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("named", [False, True])
def test_queries_and_rays_over_several_builds(dim, dtype, named):
    rng = np.random.default_rng(dim * 3 + (dtype == np.float32) + 10 * named)
    boxes = random_boxes(rng, 150, dim, dtype)
    names = rng.integers(0, (1 << 64) - 1, size=len(boxes), dtype=np.uint64, endpoint=True) if named else None
    index = smb.BoxIndex(boxes, names)
    assert index.dim == dim and index.dtype == dtype and len(index) == len(boxes)
    id_dtype = np.uint64 if named else np.int64
    for _ in range(4):
        shown = names if named else np.arange(len(boxes))
        queries = random_boxes(rng, 20, dim, dtype)
        batch = index.query_batch(queries)
        assert batch.dtype == id_dtype
        assert [tuple(r) for r in batch.tolist()] == expected_hits(boxes, shown, queries)
        for q in range(3):
            found = index.query(queries[q])
            assert found.dtype == id_dtype
            assert found.tolist() == sorted(i for p, i in expected_hits(boxes, shown, queries[q:q + 1]))
        for _ in range(5):
            origin = (rng.integers(-4, 44, size=dim) / 2.0).astype(dtype)
            direction = rng.integers(-3, 4, size=dim).astype(dtype)
            if not direction.any():
                direction[0] = 1
            ids, ts = index.cast_ray(origin, direction, all=True)
            entries = sorted((dtype(t), int(shown[i])) for i in range(len(boxes))
                             if (t := ray_entry(origin, direction, np.inf, boxes[i])) is not None)
            assert ids.dtype == id_dtype and ts.dtype == dtype
            assert [(t, i) for t, i in zip(ts.tolist(), ids.tolist())] == [(float(t), i) for t, i in entries]
            nearest, _ = index.cast_ray(origin, direction)
            assert nearest.tolist() == [i for _, i in entries[:1]]
        moved = rng.random(len(boxes)) < 0.3
        boxes[moved] = random_boxes(rng, int(moved.sum()), dim, dtype)
        boxes = np.concatenate([boxes, random_boxes(rng, 5, dim, dtype)])
        if named:
            names = np.concatenate([names, rng.integers(0, 1 << 40, size=5).astype(np.uint64)])
        index.build(boxes, names)
        assert len(index) == len(boxes)


def test_bad_input_leaves_the_index_as_it_was():
    boxes = np.array([[[0, 0], [1, 1]], [[1, 1], [2, 2]]], dtype=np.float64)
    index = smb.BoxIndex(boxes, [5, 1 << 63])
    bad_boxes = [(np.array([[[0, 0], [np.nan, 1]]]), smb.InvalidBoxError),
                 (np.array([[[0, 0], [np.inf, 1]]]), smb.InvalidBoxError),
                 (np.array([[[2, 0], [1, 1]]]), smb.InvalidBoxError),
                 (np.zeros((1, 2, 3)), ValueError), (np.zeros((1, 5)), ValueError),
                 (np.array([["a", "b", "c", "d"]]), TypeError)]
    for bad, error in bad_boxes:
        with pytest.raises(error):
            index.build(bad)
        with pytest.raises(error if error is not smb.InvalidBoxError else smb.InvalidBoxError):
            index.query_batch(bad)
    with pytest.raises(ValueError, match="one id per box"):
        index.build(np.zeros((3, 2, 2)), [1, 2])
    with pytest.raises(ValueError, match="negative"):
        index.build(np.zeros((1, 2, 2)), [-1])
    with pytest.raises(smb.ArgumentError):
        index.cast_ray([0, 0], [np.nan, 1])
    with pytest.raises(ValueError, match="shape"):
        index.query([0, 0, 1])
    assert len(index) == 2
    np.testing.assert_array_equal(index.query([1, 1, 1, 1]), np.array([5, 1 << 63], dtype=np.uint64))


def test_an_empty_index_answers_nothing():
    index = smb.BoxIndex(np.empty((0, 2, 3)))
    assert len(index) == 0 and len(index.query(np.zeros(6))) == 0
    assert index.query_batch(np.zeros((2, 6))).shape == (0, 2)
    ids, ts = index.cast_ray([0, 0, 0], [1, 0, 0])
    assert len(ids) == 0 and len(ts) == 0
