# SPDX-License-Identifier: MIT
"""Integer boxes are taken only when they convert exactly to the object's dtype: beyond 2**53 a
float64 holds only some integers, and rounding them could make or break a pair."""

import numpy as np
import pytest

import smb

B = 1 << 53
# Apart (B + 3 < B + 4), but rounded to float64 they touch: B + 3 becomes B + 4.
APART = [[[0, 0], [B + 3, 1]], [[B + 4, 0], [B + 5, 1]]]


@pytest.mark.parametrize("dtype", [np.int64, np.uint64, "list"])
def test_integers_beyond_float64_are_refused_everywhere(dtype):
    boxes = APART if dtype == "list" else np.array(APART, dtype=dtype)
    with pytest.raises(TypeError, match="convert exactly"):
        smb.find_overlapping_pairs(boxes)
    with pytest.raises(TypeError, match="convert exactly"):
        smb.find_overlapping_pairs(boxes, np.zeros((1, 2, 2)))
    with pytest.raises(TypeError, match="convert exactly"):
        smb.find_overlapping_pairs(np.zeros((1, 2, 2)), boxes)
    detector = smb.Detector(2, events=True)
    with pytest.raises(TypeError, match="convert exactly"):
        detector.detect(boxes)
    with pytest.raises(TypeError, match="convert exactly"):
        detector.detect_periodic(boxes, [0, 0], [4 * B, 4 * B])
    world = smb.World(2)
    with pytest.raises(TypeError, match="convert exactly"):
        world.insert([1, 2], boxes)
    with pytest.raises(TypeError, match="convert exactly"):
        world.assign(boxes)
    assert len(world) == 0
    world.insert([1, 2], np.zeros((2, 2, 2)))
    with pytest.raises(TypeError, match="convert exactly"):
        world.update([1, 2], boxes)
    with pytest.raises(TypeError, match="convert exactly"):
        world.query(boxes[0])
    with pytest.raises(TypeError, match="convert exactly"):
        world.query_batch(boxes)
    with pytest.raises(TypeError, match="convert exactly"):
        world.cast_ray(boxes[0][1], [1, 0])
    with pytest.raises(TypeError, match="convert exactly"):
        world.detect_periodic([0, 0], [B + 1, 1])
    with pytest.raises(TypeError, match="convert exactly"):
        smb.BoxIndex(boxes)
    np.testing.assert_array_equal(world.box(1), np.zeros((2, 2)))
    assert len(detector.detect(np.zeros((2, 2, 2)))) == 1 and len(detector.begun) == 1


def test_integers_that_convert_exactly_are_taken():
    exact = np.array([[[0, 0], [B, 1]], [[B, 0], [B + 2, 1]], [[B + 2, 0], [1 << 62, 1]]], dtype=np.int64)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(exact), [[0, 1], [1, 2]])
    np.testing.assert_array_equal(smb.find_overlapping_pairs(exact.astype(np.uint64)), [[0, 1], [1, 2]])
    np.testing.assert_array_equal(smb.Detector(2).detect(exact.tolist(), sort=True), [[0, 1], [1, 2]])
    small = np.array([[[0, 0], [3, 1]], [[3, 0], [5, 1]]], dtype=np.int32)
    np.testing.assert_array_equal(smb.Detector(2, np.float32).detect(small), [[0, 1]])


def test_float32_objects_refuse_integers_beyond_2_to_the_24():
    boxes = np.array([[[0, 0], [(1 << 24) + 1, 1]], [[(1 << 24) + 2, 0], [(1 << 24) + 3, 1]]], dtype=np.int32)
    with pytest.raises(TypeError, match="convert exactly to float32"):
        smb.Detector(2, np.float32).detect(boxes)
    with pytest.raises(TypeError, match="convert exactly to float32"):
        smb.World(2, np.float32).assign(boxes)
    assert len(smb.Detector(2, np.float64).detect(boxes)) == 0
