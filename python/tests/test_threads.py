# SPDX-License-Identifier: MIT
"""Detection runs without the GIL: other Python threads run meanwhile, detections in threads run
side by side and give the same pairs, and one object refuses a second thread."""

import threading

import numpy as np
import pytest

import smb
from reference import brute_pairs, random_boxes


def scene(seed, count=20_000, dim=3):
    rng = np.random.default_rng(seed)
    lo = rng.random((count, dim)) * 100.0
    return np.stack([lo, lo + rng.random((count, dim)) * 2.0], axis=1)


def test_other_threads_run_during_a_detection():
    """While one thread detects, the main thread enters the same detector and is told it is in
    use: it could only get there if the detecting thread had let the GIL go."""
    boxes = scene(1)
    detector = smb.Detector(3)
    finished = threading.Event()

    def detect_repeatedly():
        for _ in range(30):
            detector.detect(boxes)
        finished.set()

    worker = threading.Thread(target=detect_repeatedly)
    worker.start()
    refused = 0
    tiny = np.zeros((1, 2, 3))
    while not finished.is_set():
        try:
            detector.detect(tiny)
        except RuntimeError as error:
            assert "in use by another thread" in str(error)
            refused += 1
    worker.join()
    assert refused > 0


def test_world_calls_are_refused_while_it_detects():
    world = smb.World(3)
    world.assign(scene(2))
    finished = threading.Event()

    def detect_repeatedly():
        for _ in range(30):
            world.detect()
        finished.set()

    worker = threading.Thread(target=detect_repeatedly)
    worker.start()
    refused_changes, refused_reads = 0, 0
    while not finished.is_set():
        try:
            world.update([0], np.zeros((1, 2, 3)))
        except RuntimeError:
            refused_changes += 1
        try:
            world.stats  # a read, which the detection changes under it
        except RuntimeError:
            refused_reads += 1
    worker.join()
    assert refused_changes > 0 and refused_reads > 0


@pytest.mark.parametrize("dim", (2, 3))
def test_threads_detect_side_by_side(dim):
    scenes = [random_boxes(np.random.default_rng(seed), 300, dim, np.float64) for seed in range(4)]
    expected = [brute_pairs(boxes) for boxes in scenes]
    results = [None] * len(scenes)

    def work(index):
        detector = smb.Detector(dim)
        for _ in range(5):
            results[index] = detector.detect(scenes[index], sort=True)
        results[index] = (results[index], smb.find_overlapping_pairs(scenes[index]))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(scenes))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for (detected, found), wanted in zip(results, expected):
        np.testing.assert_array_equal(detected, wanted)
        np.testing.assert_array_equal(found, wanted)
