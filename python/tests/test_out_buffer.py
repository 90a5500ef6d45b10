# SPDX-License-Identifier: MIT
"""detect(out=...): the pairs written into the caller's array when they fit, a new array when
not, the same pairs and events either way; a bad buffer is refused before anything changes."""

import numpy as np
import pytest

import smb
from reference import as_set, brute_pairs, random_boxes


def test_detector_loop_with_a_reused_buffer():
    rng = np.random.default_rng(3)
    detector = smb.Detector(3, events=True)
    twin = smb.Detector(3, events=True)
    out = np.empty((0, 2), dtype=np.int64)
    boxes = random_boxes(rng, 300, 3, np.float64)
    grew = 0
    for _ in range(12):
        pairs = detector.detect(boxes, out=out)
        expected = twin.detect(boxes)
        np.testing.assert_array_equal(pairs, expected)
        np.testing.assert_array_equal(detector.begun, twin.begun)
        if len(pairs) > len(out):
            assert not np.shares_memory(pairs, out)
            out = np.empty((len(pairs) + len(pairs) // 4, 2), dtype=np.int64)
            grew += 1
        else:
            assert np.shares_memory(pairs, out) and pairs.base is out
        boxes = np.concatenate([boxes, random_boxes(rng, 30, 3, np.float64)])
    assert grew >= 2
    sorted_pairs = detector.detect(boxes, out=out, sort=True)
    np.testing.assert_array_equal(sorted_pairs, brute_pairs(boxes))


def test_world_detect_into_a_uint64_buffer():
    world = smb.World(2)
    world.insert([(1 << 64) - 1, 3, 9], [[0, 0, 1, 1], [1, 1, 2, 2], [5, 5, 6, 6]])
    out = np.full((4, 2), 77, dtype=np.uint64)
    pairs = world.detect(out=out)
    assert as_set(pairs) == {(3, (1 << 64) - 1)} and np.shares_memory(pairs, out)
    assert out[1:].tolist() == [[77, 77]] * 3


@pytest.mark.parametrize("bad, error", [
    ([[0, 0]], TypeError), (np.empty((4, 2), dtype=np.float64), TypeError),
    (np.empty((4, 2), dtype=np.int32), TypeError), (np.empty((4, 3), dtype=np.int64), ValueError),
    (np.empty(8, dtype=np.int64), ValueError), (np.empty((2, 4), dtype=np.int64)[:, ::2], ValueError)])
def test_a_bad_buffer_changes_nothing(bad, error):
    rng = np.random.default_rng(4)
    boxes = random_boxes(rng, 100, 2, np.float64)
    detector = smb.Detector(2, events=True)
    first = detector.detect(boxes)
    with pytest.raises(error, match="^out must"):
        detector.detect(boxes[:50], out=bad)
    detector.detect(boxes)
    assert len(detector.begun) == 0 and len(detector.ended) == 0 and len(first) > 0
    readonly = np.empty((10, 2), dtype=np.int64)
    readonly.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        detector.detect(boxes, out=readonly)
    world = smb.World(2)
    with pytest.raises(TypeError, match="uint64"):
        world.detect(out=np.empty((4, 2), dtype=np.int64))


def test_a_failed_detection_into_a_buffer_changes_nothing():
    rng = np.random.default_rng(6)
    boxes = random_boxes(rng, 100, 3, np.float64)
    detector = smb.Detector(3, events=True)
    out = np.zeros((5000, 2), dtype=np.int64)
    first = detector.detect(boxes, out=out).copy()
    bad = boxes.copy()
    bad[7, 1, 0] = np.nan
    with pytest.raises(smb.InvalidBoxError):
        detector.detect(bad, out=out)
    with pytest.raises(smb.PairLimitError):
        smb.Detector(3, max_pairs_held=1).detect(boxes, out=out)
    np.testing.assert_array_equal(out[:len(first)], first)
    again = detector.detect(boxes, out=out)
    assert as_set(again) == as_set(first) and len(again) == len(first)
    assert len(detector.begun) == 0 and len(detector.ended) == 0
