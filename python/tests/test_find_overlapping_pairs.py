# SPDX-License-Identifier: MIT
"""smb.find_overlapping_pairs, one set and two, against the NumPy brute force."""

import numpy as np
import pytest

import smb
from reference import DIMS, DTYPES, brute_pairs, brute_pairs_between, random_boxes


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("seed", range(3))
def test_one_set_matches_brute_force(dim, dtype, seed):
    rng = np.random.default_rng(seed)
    boxes = random_boxes(rng, 300, dim, dtype)
    pairs = smb.find_overlapping_pairs(boxes)
    assert pairs.dtype == np.int64 and pairs.shape[1] == 2
    np.testing.assert_array_equal(pairs, brute_pairs(boxes))
    assert len(pairs) > 0


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_flat_layout_gives_the_same_pairs(dim, dtype):
    boxes = random_boxes(np.random.default_rng(7), 200, dim, dtype)
    flat = boxes.reshape(len(boxes), 2 * dim)  # xmin, ymin[, zmin], xmax, ymax[, zmax]
    np.testing.assert_array_equal(smb.find_overlapping_pairs(flat), brute_pairs(boxes))


@pytest.mark.parametrize("dim", DIMS)
def test_threads_give_the_same_pairs(dim):
    boxes = random_boxes(np.random.default_rng(3), 500, dim, np.float64)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(boxes, threads=2), brute_pairs(boxes))


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("seed", range(2))
def test_two_sets_match_brute_force(dim, dtype, seed):
    rng = np.random.default_rng(100 + seed)
    a = random_boxes(rng, 150, dim, dtype)
    b = random_boxes(rng, 90, dim, dtype)
    pairs = smb.find_overlapping_pairs(a, b)
    assert pairs.dtype == np.int64
    np.testing.assert_array_equal(pairs, brute_pairs_between(a, b))
    assert len(pairs) > 0


def test_two_sets_of_mixed_dtypes_are_detected_as_doubles():
    rng = np.random.default_rng(5)
    a = random_boxes(rng, 80, 3, np.float32)
    b = random_boxes(rng, 80, 3, np.float64)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(a, b), brute_pairs_between(a, b))


def test_two_sets_of_different_dimensions_are_refused():
    with pytest.raises(ValueError, match="same dimension"):
        smb.find_overlapping_pairs(np.zeros((3, 2, 2)), np.zeros((3, 2, 3)))


@pytest.mark.parametrize("dim", DIMS)
def test_empty_and_single(dim):
    assert smb.find_overlapping_pairs(np.zeros((0, 2, dim))).shape == (0, 2)
    assert smb.find_overlapping_pairs(np.zeros((1, 2, dim))).shape == (0, 2)
    assert smb.find_overlapping_pairs(np.zeros((0, 2, dim)), np.zeros((4, 2, dim))).shape == (0, 2)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_non_contiguous_input(dim, dtype):
    boxes = random_boxes(np.random.default_rng(11), 400, dim, dtype)
    every_other = boxes[::2]
    assert not every_other.flags.c_contiguous
    np.testing.assert_array_equal(smb.find_overlapping_pairs(every_other), brute_pairs(every_other))
    fortran = np.asfortranarray(boxes)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(fortran), brute_pairs(boxes))
    # Columns picked out of a wider table: (N, 2*dim) with a stride of its own.
    table = np.concatenate([boxes.reshape(len(boxes), -1), np.ones((len(boxes), 3), dtype)], axis=1)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(table[:, : 2 * dim]), brute_pairs(boxes))


def test_other_numeric_dtypes_are_read_as_float64():
    boxes = random_boxes(np.random.default_rng(2), 120, 2, np.float64) * 2
    as_int = boxes.astype(np.int32)
    np.testing.assert_array_equal(smb.find_overlapping_pairs(as_int), brute_pairs(as_int))
    np.testing.assert_array_equal(smb.find_overlapping_pairs(as_int.tolist()), brute_pairs(as_int))


def test_wrong_shapes_say_what_is_expected():
    for shape in [(5,), (5, 5), (5, 3, 3), (5, 2, 4), (5, 2, 2, 1)]:
        with pytest.raises(ValueError, match=r"\(N, 2, D\)"):
            smb.find_overlapping_pairs(np.zeros(shape))


def test_wrong_dtypes_are_type_errors():
    with pytest.raises(TypeError, match="numbers"):
        smb.find_overlapping_pairs(np.array([["a", "b", "c", "d"]]))
    with pytest.raises(TypeError, match="numbers"):
        smb.find_overlapping_pairs(np.zeros((3, 4), dtype=np.complex128))


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("dtype", DTYPES)
def test_invalid_boxes_raise_invalid_box_error(bad, dtype):
    boxes = random_boxes(np.random.default_rng(1), 20, 3, dtype)
    boxes[7, 1, 2] = bad
    with pytest.raises(smb.InvalidBoxError) as raised:
        smb.find_overlapping_pairs(boxes)
    assert isinstance(raised.value, ValueError)
    assert "7" in str(raised.value)


def test_min_above_max_raises_invalid_box_error():
    boxes = np.zeros((4, 2, 2))
    boxes[2, 0, 0] = 1.0
    with pytest.raises(smb.InvalidBoxError):
        smb.find_overlapping_pairs(boxes)
    with pytest.raises(smb.InvalidBoxError):
        smb.find_overlapping_pairs(np.zeros((2, 2, 2)), boxes)


def test_pair_limit():
    boxes = np.zeros((10, 2, 2))
    with pytest.raises(smb.PairLimitError):
        smb.find_overlapping_pairs(boxes, max_pairs_held=44)
    assert len(smb.find_overlapping_pairs(boxes, max_pairs_held=45)) == 45


def test_result_outlives_its_input():
    boxes = random_boxes(np.random.default_rng(4), 100, 3, np.float64)
    pairs = smb.find_overlapping_pairs(boxes)
    expected = brute_pairs(boxes)
    del boxes
    np.testing.assert_array_equal(pairs, expected)
