# SPDX-License-Identifier: MIT
"""smb.Detector over many steps (moves, teleports, appends, swap-removes) against the brute force,
with its events, filters, static boxes, skin and periodic domains."""

import numpy as np
import pytest

import smb
from reference import (DIMS, DTYPES, as_set, brute_pairs, brute_periodic, filter_keep, random_boxes,
                       sorted_rows)


class EventModel:
    """The events a Detector must report, from bodies named by a uid that follows them."""

    def __init__(self):
        self.previous = {}  # uid pair -> index pair as the previous list named it

    def update(self, pairs, uids):
        now = {}
        for i, j in pairs.tolist():
            now[tuple(sorted((uids[i], uids[j])))] = (i, j)
        begun = sorted_rows([now[key] for key in now.keys() - self.previous.keys()])
        ended = sorted_rows([self.previous[key] for key in self.previous.keys() - now.keys()])
        self.previous = now
        return begun, ended


def step_scene(rng, boxes, uids, next_uid, detector, dim, dtype):
    """One step of motion: jitter, a few teleports, appends, swap-removes and replacements."""
    count = len(boxes)
    jitter = (rng.integers(-1, 2, size=(count, 1, dim)) / 2.0).astype(dtype)
    boxes = boxes + jitter
    teleported = rng.choice(count, size=max(1, count // 20), replace=False)
    boxes[teleported] = random_boxes(rng, len(teleported), dim, dtype)
    for _ in range(rng.integers(0, 4)):
        removed = int(rng.integers(0, len(boxes)))
        last = len(boxes) - 1
        boxes[removed] = boxes[last]
        uids[removed] = uids[last]
        boxes = boxes[:last]
        uids = uids[:last]
        detector.swap_remove(removed, last)
    for _ in range(rng.integers(0, 3)):
        index = int(rng.integers(0, len(boxes)))
        boxes[index] = random_boxes(rng, 1, dim, dtype)[0]
        uids[index] = next_uid
        next_uid += 1
        detector.replace(index)
    added = int(rng.integers(0, 6))
    boxes = np.concatenate([boxes, random_boxes(rng, added, dim, dtype)])
    uids = uids + list(range(next_uid, next_uid + added))
    return boxes, uids, next_uid + added


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("skin", [0.0, 1.5])
def test_many_steps_with_events(dim, dtype, skin):
    rng = np.random.default_rng(dim * 10 + (dtype == np.float32) + int(skin))
    detector = smb.Detector(dim, dtype, skin=skin, events=True)
    boxes = random_boxes(rng, 200, dim, dtype)
    uids = list(range(len(boxes)))
    next_uid = len(boxes)
    model = EventModel()
    events_seen = 0
    for _ in range(25):
        pairs = detector.detect(boxes, sort=True)
        expected = brute_pairs(boxes)
        np.testing.assert_array_equal(pairs, expected)
        begun, ended = model.update(expected, uids)
        np.testing.assert_array_equal(detector.begun, begun)
        np.testing.assert_array_equal(detector.ended, ended)
        events_seen += len(begun) + len(ended)
        assert detector.stats["pairs"] == len(expected)
        assert detector.stats["boxes"] == len(boxes)
        boxes, uids, next_uid = step_scene(rng, boxes, uids, next_uid, detector, dim, dtype)
    assert events_seen > 0
    assert detector.precision in ("floats", "doubles")


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_unsorted_pairs_are_the_same_set(dim, dtype):
    boxes = random_boxes(np.random.default_rng(9), 300, dim, dtype)
    pairs = smb.Detector(dim, dtype).detect(boxes)
    assert np.all(pairs[:, 0] < pairs[:, 1])
    assert len(pairs) == len(as_set(pairs))
    assert as_set(pairs) == as_set(brute_pairs(boxes))


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_filters_and_static_boxes(dim, dtype):
    rng = np.random.default_rng(21 + dim)
    detector = smb.Detector(dim, dtype)
    for _ in range(6):
        boxes = random_boxes(rng, 250, dim, dtype)
        categories = rng.choice([0, 1, 2, 4, 3], size=len(boxes)).astype(np.uint32)
        masks = rng.choice([0, 1, 6, 0xFFFFFFFF], size=len(boxes))
        static = rng.random(len(boxes)) < 0.3
        pairs = detector.detect(boxes, categories=categories, masks=masks, static=static, sort=True)
        expected = brute_pairs(boxes, filter_keep(categories, masks, static))
        np.testing.assert_array_equal(pairs, expected)
        assert len(expected) > 0
        # One value stands for every box.
        only_static = detector.detect(boxes, static=static, sort=True)
        np.testing.assert_array_equal(only_static, brute_pairs(boxes, filter_keep(np.ones(len(boxes)),
                                                                              np.ones(len(boxes)), static)))
        np.testing.assert_array_equal(detector.detect(boxes, categories=2, masks=2, sort=True), brute_pairs(boxes))


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_periodic_domain(dim, dtype):
    rng = np.random.default_rng(31 + dim)
    lo, hi = np.full(dim, 0.0), np.full(dim, 16.0)
    axes = [True] * dim
    axes[0] = False
    detector = smb.Detector(dim, dtype, events=True)
    for _ in range(5):
        start = rng.integers(0, 32, size=(150, dim)) / 2.0
        size = rng.integers(0, 7, size=(150, dim)) / 2.0
        boxes = np.stack([start, start + size], axis=1).astype(dtype)
        pairs, shifts = detector.detect_periodic(boxes, lo, hi, axes=axes, sort=True)
        expected_pairs, expected_shifts = brute_periodic(boxes, lo, hi, axes)
        np.testing.assert_array_equal(pairs, expected_pairs)
        np.testing.assert_array_equal(shifts, expected_shifts)
        assert shifts.dtype == np.int32 and shifts.shape == (len(pairs), dim)
        assert np.any(shifts != 0)
        assert np.all(shifts[:, 0] == 0)


def test_periodic_box_too_large_and_bad_domain():
    detector = smb.Detector(2)
    boxes = np.array([[[0.0, 0.0], [9.0, 1.0]]])
    with pytest.raises(smb.InvalidBoxError):
        detector.detect_periodic(boxes, [0, 0], [16, 16])
    with pytest.raises(smb.ArgumentError):
        detector.detect_periodic(boxes, [0, 0], [0, 16])
    with pytest.raises(ValueError, match=r"\(2,\)"):
        detector.detect_periodic(boxes, [0, 0, 0], [16, 16, 16])


@pytest.mark.parametrize("dtype", DTYPES)
def test_a_failed_detection_changes_nothing(dtype):
    rng = np.random.default_rng(41)
    detector = smb.Detector(3, dtype, events=True)
    boxes = random_boxes(rng, 150, 3, dtype)
    first = detector.detect(boxes, sort=True)
    begun = detector.begun
    bad = boxes.copy()
    bad[17, 0, 1] = np.nan
    with pytest.raises(smb.InvalidBoxError, match="17"):
        detector.detect(bad)
    np.testing.assert_array_equal(detector.begun, begun)
    # The next detection compares with the last one that succeeded.
    moved = boxes + dtype(0.5)
    pairs = detector.detect(moved, sort=True)
    np.testing.assert_array_equal(pairs, brute_pairs(moved))
    np.testing.assert_array_equal(detector.begun, np.empty((0, 2), np.int64))
    np.testing.assert_array_equal(detector.ended, np.empty((0, 2), np.int64))
    assert len(first) == len(pairs)


def test_wrong_dtype_and_shape():
    detector = smb.Detector(3, np.float32)
    rng = np.random.default_rng(3)
    exact = random_boxes(rng, 50, 3, np.float64)  # half-units: exact in float32
    np.testing.assert_array_equal(detector.detect(exact, sort=True), brute_pairs(exact))
    inexact = exact + 0.1
    with pytest.raises(TypeError, match="float32"):
        detector.detect(inexact)
    with pytest.raises(ValueError, match=r"\(N, 2, 3\) or \(N, 6\)"):
        detector.detect(np.zeros((4, 2, 2), np.float32))
    with pytest.raises(ValueError, match="categories has 3 entries; 50 expected"):
        detector.detect(exact, categories=[1, 2, 3])
    with pytest.raises(ValueError, match="negative"):
        detector.detect(exact, masks=-1)
    with pytest.raises(ValueError, match="above the largest"):
        detector.detect(exact, masks=1 << 32)
    with pytest.raises(TypeError, match="integers"):
        detector.detect(exact, categories=np.ones(50))
    with pytest.raises(ValueError, match="dim"):
        smb.Detector(4)
    with pytest.raises(TypeError, match="dtype"):
        smb.Detector(3, np.int32)


def test_bad_settings_are_refused():
    with pytest.raises(smb.ArgumentError, match="skin"):
        smb.Detector(3, skin=-1.0)
    with pytest.raises(smb.ArgumentError, match="target_cell_population"):
        smb.Detector(3, target_cell_population=0)


def test_events_off():
    detector = smb.Detector(2)
    detector.detect(np.zeros((3, 2, 2)))
    with pytest.raises(RuntimeError, match="events=True"):
        detector.begun
    with pytest.raises(smb.ArgumentError):
        smb.Detector(2, events=True).swap_remove(5, 3)


def test_clear_keeps_detecting():
    boxes = random_boxes(np.random.default_rng(8), 100, 2, np.float64)
    detector = smb.Detector(2)
    detector.detect(boxes)
    assert detector.bytes_held > 0
    detector.clear()
    np.testing.assert_array_equal(detector.detect(boxes, sort=True), brute_pairs(boxes))


@pytest.mark.parametrize("cls", ["Detector", "World"])
def test_profile_is_zero_unless_asked_for(cls):
    rng = np.random.default_rng(5)
    boxes = random_boxes(rng, 3000, 3, np.float64)
    for profile in (False, True):
        if cls == "Detector":
            broad_phase = smb.Detector(3, np.float64, profile=profile)
            broad_phase.detect(boxes)
        else:
            broad_phase = smb.World(3, np.float64, profile=profile)
            broad_phase.assign(boxes)
            broad_phase.detect()
        phases = broad_phase.profile
        assert set(phases) >= {"check_seconds", "copy_seconds", "level_seconds", "cells", "sort_moves"}
        assert len(phases["level_seconds"]) == 3
        if profile:
            assert phases["check_seconds"] > 0
            assert phases["cells"] > 0
        else:
            assert phases["check_seconds"] == 0
            assert phases["cells"] == 0
            assert all(seconds == 0 for seconds in phases["level_seconds"])
        assert broad_phase.stats["boxes"] == len(boxes)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_renumbering_by_the_suggested_order(dim, dtype):
    rng = np.random.default_rng(11)
    detector = smb.Detector(dim, dtype)
    boxes = random_boxes(rng, 800, dim, dtype)
    uids = np.arange(len(boxes))  # follows each body through the renumberings
    assert detector.suggested_order().size == 0
    for step in range(12):
        boxes = boxes + (rng.integers(-1, 2, size=(len(boxes), 1, dim)) / 4.0).astype(dtype)
        pairs = detector.detect(boxes)
        assert as_set(np.sort(uids[pairs], axis=1)) == as_set(np.sort(uids[brute_pairs(boxes)], axis=1))
        order = detector.suggested_order()
        assert order.dtype == np.int64
        assert np.array_equal(np.sort(order), np.arange(len(boxes)))
        if step % 3 == 0:
            boxes, uids = boxes[order], uids[order]
            detector.follow_suggested_order()
    detector.detect_periodic(boxes, [-50.0] * dim, [50.0] * dim)
    assert detector.suggested_order().size == 0
