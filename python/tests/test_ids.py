# SPDX-License-Identifier: MIT
"""Ids across the whole 64-bit range, in every World call that takes or gives ids: uint64 arrays
up to 2**64 - 1, Python integers, int64 arrays; negative and larger values refused."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import smb
from reference import DIMS, as_set, brute_pairs, brute_periodic, filter_keep, random_boxes, ray_entry, sorted_rows

TOP = (1 << 64) - 1


def wide_ids(rng, count):
    """`count` distinct uint64 ids spread over the whole range, with its edges among them."""
    edges = np.array([0, 1, (1 << 32) - 1, 1 << 32, (1 << 53) + 1, (1 << 63) - 1, 1 << 63, TOP - 1, TOP],
                     dtype=np.uint64)
    ids = np.unique(np.concatenate([edges, rng.integers(0, TOP, size=count, dtype=np.uint64, endpoint=True)]))
    rng.shuffle(ids)
    return ids[:count]


def named_pairs(index_pairs, ids):
    """Pairs of indices into `ids` as sorted pairs of ids (a < b)."""
    rows = [sorted((int(ids[i]), int(ids[j]))) for i, j in index_pairs.tolist()]
    return sorted_rows(np.array(rows, dtype=np.uint64).reshape(-1, 2))


@pytest.mark.parametrize("dim", DIMS)
def test_world_steps_with_ids_across_the_range(dim):
    rng = np.random.default_rng(64 + dim)
    world = smb.World(dim, events=True)
    ids = wide_ids(rng, 150)
    boxes = random_boxes(rng, len(ids), dim, np.float64)
    world.insert(ids, boxes)
    previous, replaced = set(), set()
    for step in range(12):
        pairs = world.detect(sort=True)
        assert pairs.dtype == np.uint64
        expected = named_pairs(brute_pairs(boxes), ids)
        np.testing.assert_array_equal(pairs, expected)
        now = as_set(expected)
        renewed = {p for p in now | previous if p[0] in replaced or p[1] in replaced}
        assert as_set(world.begun) == (now - previous) | (renewed & now)
        assert as_set(world.ended) == (previous - now) | (renewed & previous)
        assert world.begun.dtype == np.uint64 and world.ended.dtype == np.uint64
        previous, replaced = now, set()
        moved = rng.random(len(ids)) < 0.3
        boxes[moved] = random_boxes(rng, int(moved.sum()), dim, np.float64)
        world.update(ids[moved], boxes[moved])
        if step % 3 == 2:  # remove a few and insert them again as new bodies: their pairs restart
            gone = ids[:5]
            world.remove(gone)
            assert not any(int(i) in world for i in gone)
            world.insert(gone, boxes[:5])
            replaced = set(gone.tolist())
    for i in ids[:20].tolist():
        assert i in world and np.uint64(i) in world
        np.testing.assert_array_equal(world.box(i), boxes[list(ids).index(i)])


def test_filters_statics_queries_and_rays_with_wide_ids():
    rng = np.random.default_rng(7)
    dim = 3
    world = smb.World(dim)
    ids = wide_ids(rng, 120)
    boxes = random_boxes(rng, len(ids), dim, np.float64)
    world.insert(ids, boxes)
    categories = rng.integers(1, 4, size=len(ids))
    masks = rng.integers(1, 4, size=len(ids))
    statics = rng.random(len(ids)) < 0.3
    world.set_filter(ids, categories, masks)
    world.set_static(ids[statics])
    expected = named_pairs(brute_pairs(boxes, filter_keep(categories, masks, statics)), ids)
    np.testing.assert_array_equal(world.detect(sort=True), expected)
    top = int(ids[0])
    assert world.filter(top) == (int(categories[0]), int(masks[0]))
    assert world.is_static(np.uint64(top)) == bool(statics[0])
    query = random_boxes(rng, 1, dim, np.float64)[0]
    hits = world.query(query)
    assert hits.dtype == np.uint64
    overlapping = [int(ids[i]) for i in range(len(ids))
                   if np.all(boxes[i, 0] <= query[1]) and np.all(query[0] <= boxes[i, 1])]
    np.testing.assert_array_equal(hits, np.array(sorted(overlapping), dtype=np.uint64))
    batch = world.query_batch(query[None])
    np.testing.assert_array_equal(batch[:, 1], hits)
    origin, direction = np.array([-1.0, 5.0, 5.0]), np.array([1.0, 0.0, 0.0])
    hit_ids, ts = world.cast_ray(origin, direction, all=True)
    entries = sorted((t, int(ids[i])) for i in range(len(ids))
                     if (t := ray_entry(origin, direction, np.inf, boxes[i])) is not None)
    assert [int(i) for i in hit_ids] == [i for _, i in entries]


def test_python_integers_and_int64_arrays_as_ids():
    world = smb.World(2)
    world.insert([TOP, 1 << 63, 5], [[0, 0, 1, 1], [1, 0, 2, 1], [5, 5, 6, 6]])
    world.insert(np.array([7, 9], dtype=np.int64), [[0, 1, 1, 2], [9, 9, 9, 9]])
    world.insert(TOP - 1, [[1, 1, 2, 2]])
    assert len(world) == 6 and TOP in world and (1 << 63) in world
    pairs = world.detect(sort=True)
    assert as_set(pairs) == {(7, 1 << 63), (7, TOP - 1), (7, TOP), (1 << 63, TOP - 1), (1 << 63, TOP), (TOP - 1, TOP)}
    world.remove([TOP, 1 << 63])
    assert TOP not in world and len(world) == 4


@pytest.mark.parametrize("bad, error", [(-1, ValueError), ([3, -2], ValueError), (1 << 64, ValueError),
                                        ([1 << 64, 3], ValueError), ([-1, TOP], ValueError),
                                        (1.0, TypeError), (["a"], TypeError), (np.array([1.5]), TypeError)])
def test_bad_ids_are_refused_and_change_nothing(bad, error):
    world = smb.World(2, events=True)
    world.insert([1, 2], [[0, 0, 1, 1], [1, 1, 2, 2]])
    world.detect()
    count = np.size(bad)
    with pytest.raises(error, match="ids"):
        world.insert(bad, np.zeros((count, 4)))
    with pytest.raises(error, match="ids"):
        world.remove(bad)
    with pytest.raises(error, match="ids"):
        world.set_static(bad)
    assert len(world) == 2 and as_set(world.detect()) == {(1, 2)} and len(world.begun) == 0


def test_single_id_calls_refuse_what_cannot_be_an_id():
    world = smb.World(2)
    world.insert([TOP], [[0, 0, 1, 1]])
    for bad in (-1, 1 << 64, 1 << 70):
        assert bad not in world
        with pytest.raises(ValueError, match=r"id must be an integer in \[0, 2\*\*64 - 1\]"):
            world.box(bad)
        with pytest.raises(ValueError, match="id must be"):
            world.filter(bad)
        with pytest.raises(ValueError, match="id must be"):
            world.is_static(bad)
    for bad in ("a", 1.0, None, (1,)):
        assert bad not in world
        with pytest.raises(TypeError, match="id must be"):
            world.box(bad)
    with pytest.raises(smb.UnknownIdError):
        world.box(TOP - 1)
    assert TOP in world


PERIODIC_WIDE_IDS = textwrap.dedent("""
    import numpy as np, smb
    for dim in (2, 3):
        ids = np.array([7, 1 << 32, (1 << 64) - 1, 1 << 63], dtype=np.uint64)
        boxes = np.zeros((4, 2, dim))
        boxes[:, 0, 0] = [0, 1, 11.5, 4]
        boxes[:, 1, 0] = [1, 2, 12, 5]
        boxes[:, 1, 1:] = 1
        world = smb.World(dim)
        world.insert(ids, boxes)
        pairs, shifts = world.detect_periodic(np.zeros(dim), np.full(dim, 12.0), sort=True)
        assert pairs.dtype == np.uint64, pairs.dtype
        got = sorted(zip(map(tuple, pairs.tolist()), map(tuple, shifts.tolist())))
        zero = (0,) * (dim - 1)
        want = sorted([((7, 1 << 32), (0,) + zero), ((7, (1 << 64) - 1), (-1,) + zero)])
        assert got == want, got
    print("ok")
""")


def test_periodic_world_with_wide_ids():
    """In a child interpreter, so that a crash fails this test alone."""
    run = subprocess.run([sys.executable, "-c", PERIODIC_WIDE_IDS], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and run.stdout.strip() == "ok", (run.returncode, run.stdout, run.stderr)
