# SPDX-License-Identifier: MIT
"""Detector.candidates(), the Verlet list of a Detector with a skin, against the brute force over
many steps: it holds every pair within its margin of overlapping, and only pairs of boxes within
two skins of each other."""

import numpy as np
import pytest

import smb
from reference import DIMS, DTYPES, as_set, brute_pairs, random_boxes


def loose_boxes(rng, count, dim, dtype):
    """Boxes at continuous random places: a grid scene's exact touches make the detector hold
    doubles, where it keeps no candidate list."""
    lo = rng.random((count, dim)) * 20.0
    return np.stack([lo, lo + rng.random((count, dim)) * 2.0], axis=1).astype(dtype)


def grown(boxes, by):
    boxes = np.asarray(boxes, dtype=np.float64).copy()
    boxes[:, 0, :] -= by
    boxes[:, 1, :] += by
    return boxes


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_candidates_over_many_steps(dim, dtype):
    rng = np.random.default_rng(dim + 5 * (dtype == np.float32))
    skin = 1.0
    detector = smb.Detector(dim, dtype, skin=skin)
    boxes = loose_boxes(rng, 200, dim, dtype)
    seen_available = 0
    for _ in range(12):
        pairs = detector.detect(boxes)
        listed = detector.candidates()
        assert isinstance(listed, smb.CandidatePairs)
        if listed.available:
            seen_available += 1
            held = as_set(listed.pairs)
            assert listed.pairs.dtype == np.int64 and len(held) == len(listed.pairs)
            assert np.all(listed.pairs[:, 0] < listed.pairs[:, 1])
            assert as_set(pairs) <= held
            assert 0 <= listed.margin <= skin
            assert as_set(brute_pairs(grown(boxes, listed.margin))) <= held
            assert held <= as_set(brute_pairs(grown(boxes, 2 * skin)))
        else:
            assert len(listed.pairs) == 0
        boxes = boxes + (rng.normal(0.0, 0.05, size=(len(boxes), 1, dim))).astype(dtype)
        if rng.random() < 0.2:
            boxes = np.concatenate([boxes, loose_boxes(rng, 3, dim, dtype)])
    assert seen_available > 6


def test_no_list_without_a_skin_or_before_a_detection():
    boxes = random_boxes(np.random.default_rng(1), 50, 2, np.float64)
    assert smb.Detector(2, skin=1.0).candidates().available is False
    plain = smb.Detector(2)
    plain.detect(boxes)
    listed = plain.candidates()
    assert listed.available is False and listed.pairs.shape == (0, 2)
    skinned = smb.Detector(2, skin=1.0)
    skinned.detect_periodic(boxes, [0, 0], [40, 40])
    assert skinned.candidates().available is False
