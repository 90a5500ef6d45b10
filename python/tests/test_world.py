# SPDX-License-Identifier: MIT
"""smb.World over many steps (inserts, removes, re-inserts, moves, teleports) against the brute
force, with its events, filters, static boxes, queries, ray casts, periodic domains and errors."""

import numpy as np
import pytest

import smb
from reference import (DIMS, DTYPES, brute_pairs, brute_periodic, filter_keep, random_boxes, ray_entry,
                       sorted_rows)


class WorldModel:
    """What a World holds, kept in plain NumPy: ids, boxes, filters, statics, generations."""

    def __init__(self, dim, dtype):
        self.dim, self.dtype = dim, dtype
        self.boxes = {}
        self.generation = {}
        self.categories, self.masks, self.static = {}, {}, {}
        self.previous = {}
        self.next_generation = 0

    def insert(self, ids, boxes):
        for i, box in zip(ids.tolist(), boxes):
            self.boxes[i] = box.copy()
            self.generation[i] = self.next_generation
            self.next_generation += 1
            self.categories[i], self.masks[i], self.static[i] = 1, 0xFFFFFFFF, False

    def remove(self, ids):
        for i in ids.tolist():
            for table in (self.boxes, self.generation, self.categories, self.masks, self.static):
                del table[i]

    def arrays(self):
        ids = np.array(sorted(self.boxes), dtype=np.int64)
        boxes = np.array([self.boxes[i] for i in ids.tolist()], dtype=self.dtype).reshape(-1, 2, self.dim)
        return ids, boxes

    def pairs(self):
        ids, boxes = self.arrays()
        keep = filter_keep([self.categories[i] for i in ids.tolist()], [self.masks[i] for i in ids.tolist()],
                           [self.static[i] for i in ids.tolist()])
        return sorted_rows(ids[brute_pairs(boxes, keep)])

    def events(self, pairs):
        now = {(a, self.generation[a], b, self.generation[b]): (a, b) for a, b in pairs.tolist()}
        begun = sorted_rows([now[key] for key in now.keys() - self.previous.keys()])
        ended = sorted_rows([self.previous[key] for key in self.previous.keys() - now.keys()])
        self.previous = now
        return begun, ended


def random_step(rng, world, model, dim, dtype):
    ids = np.array(sorted(model.boxes), dtype=np.int64)
    moved = rng.choice(ids, size=len(ids) // 2, replace=False)
    boxes = np.array([model.boxes[i] for i in moved.tolist()]).reshape(-1, 2, dim)
    boxes = boxes + (rng.integers(-1, 2, size=(len(moved), 1, dim)) / 2.0).astype(dtype)
    teleports = rng.random(len(moved)) < 0.1
    boxes[teleports] = random_boxes(rng, int(teleports.sum()), dim, dtype)
    world.update(moved, boxes)
    for i, box in zip(moved.tolist(), boxes):
        model.boxes[i] = box.copy()
    removed = rng.choice(ids, size=int(rng.integers(0, 8)), replace=False)
    world.remove(removed)
    model.remove(removed)
    # New ids, and some of the ids just removed, which come back as new boxes.
    fresh = np.arange(model.next_generation + 10_000, model.next_generation + 10_000 + rng.integers(0, 8))
    back = removed[: len(removed) // 2]
    inserted = np.concatenate([fresh, back]).astype(np.int64)
    new_boxes = random_boxes(rng, len(inserted), dim, dtype)
    world.insert(inserted, new_boxes)
    model.insert(inserted, new_boxes)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("pipeline", ["persistent_cuts", "paper_lists"])
def test_many_steps_with_events(dim, dtype, pipeline):
    rng = np.random.default_rng(dim * 7 + (dtype == np.float32) + len(pipeline))
    world = smb.World(dim, dtype, events=True, pipeline=pipeline)
    model = WorldModel(dim, dtype)
    ids = rng.choice(1 << 40, size=200, replace=False).astype(np.int64)
    boxes = random_boxes(rng, len(ids), dim, dtype)
    world.insert(ids, boxes)
    model.insert(ids, boxes)
    for _ in range(20):
        pairs = world.detect(sort=True)
        expected = model.pairs()
        np.testing.assert_array_equal(pairs, expected)
        begun, ended = model.events(expected)
        np.testing.assert_array_equal(world.begun, begun)
        np.testing.assert_array_equal(world.ended, ended)
        assert len(world) == len(model.boxes)
        random_step(rng, world, model, dim, dtype)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_filters_and_static_boxes(dim, dtype):
    rng = np.random.default_rng(55 + dim)
    world = smb.World(dim, dtype)
    model = WorldModel(dim, dtype)
    ids = np.arange(250, dtype=np.int64)
    boxes = random_boxes(rng, len(ids), dim, dtype)
    world.insert(ids, boxes)
    model.insert(ids, boxes)
    for _ in range(8):
        chosen = rng.choice(ids, size=60, replace=False)
        categories = rng.choice([0, 1, 2, 3], size=len(chosen))
        masks = rng.choice([1, 2, 0xFFFFFFFF], size=len(chosen))
        world.set_filter(chosen, categories, masks)
        statics = rng.choice(ids, size=30, replace=False)
        flag = bool(rng.random() < 0.7)
        world.set_static(statics, flag)
        for i, c, m in zip(chosen.tolist(), categories.tolist(), masks.tolist()):
            model.categories[i], model.masks[i] = c, m
        for i in statics.tolist():
            model.static[i] = flag
        np.testing.assert_array_equal(world.detect(sort=True), model.pairs())
        some = int(chosen[0])
        assert world.filter(some) == (model.categories[some], model.masks[some])
        assert world.is_static(int(statics[0])) == flag
        random_step(rng, world, model, dim, dtype)
        ids = np.array(sorted(model.boxes), dtype=np.int64)
    world.set_filter(ids)  # the defaults again
    for i in ids.tolist():
        model.categories[i], model.masks[i] = 1, 0xFFFFFFFF
    np.testing.assert_array_equal(world.detect(sort=True), model.pairs())


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_skin_over_many_steps_with_events_and_filters(dim, dtype):
    rng = np.random.default_rng(91 + dim + (dtype == np.float32))
    world = smb.World(dim, dtype, skin=1.5, events=True)
    model = WorldModel(dim, dtype)
    ids = rng.choice(1 << 40, size=200, replace=False).astype(np.int64)
    boxes = random_boxes(rng, len(ids), dim, dtype)
    world.insert(ids, boxes)
    model.insert(ids, boxes)
    for step in range(16):
        if step == 8:  # the second half through the filters and the statics
            chosen = np.array(sorted(model.boxes), dtype=np.int64)[::3]
            world.set_filter(chosen, np.full(len(chosen), 2), np.full(len(chosen), 1))
            world.set_static(chosen[:10], True)
            for i in chosen.tolist():
                model.categories[i], model.masks[i] = 2, 1
            for i in chosen[:10].tolist():
                model.static[i] = True
        pairs = world.detect(sort=True)
        expected = model.pairs()
        np.testing.assert_array_equal(pairs, expected)
        begun, ended = model.events(expected)
        np.testing.assert_array_equal(world.begun, begun)
        np.testing.assert_array_equal(world.ended, ended)
        random_step(rng, world, model, dim, dtype)
    with pytest.raises(smb.ArgumentError, match="skin"):
        smb.World(dim, dtype, skin=-1.0)


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_queries_and_ray_casts(dim, dtype):
    rng = np.random.default_rng(71 + dim)
    world = smb.World(dim, dtype)
    boxes = random_boxes(rng, 200, dim, dtype)
    ids = np.arange(len(boxes), dtype=np.int64) * 3 + 1
    world.insert(ids, boxes)
    queries = random_boxes(rng, 25, dim, dtype)
    for query in queries:
        hits = world.query(query)
        expected = ids[[bool(np.all(query[0] <= b[1]) and np.all(b[0] <= query[1])) for b in boxes]]
        np.testing.assert_array_equal(hits, expected)
    batch = world.query_batch(queries)
    expected_rows = [(q, i) for q, query in enumerate(queries) for i in world.query(query).tolist()]
    np.testing.assert_array_equal(batch, np.array(expected_rows, dtype=np.int64).reshape(-1, 2))
    assert len(batch) > 0
    for _ in range(20):
        origin = (rng.integers(-4, 44, size=dim) / 2.0).astype(dtype)
        direction = rng.integers(-3, 4, size=dim).astype(dtype)
        if not direction.any():
            direction[0] = 1
        entries = [(ray_entry(origin, direction, np.inf, b), i) for b, i in zip(boxes, ids.tolist())]
        entered = sorted((dtype(t), i) for t, i in entries if t is not None)
        hit_ids, ts = world.cast_ray(origin, direction, all=True)
        assert ts.dtype == dtype
        np.testing.assert_array_equal(hit_ids, [i for _, i in entered])
        np.testing.assert_array_equal(ts, np.array([t for t, _ in entered], dtype=dtype))
        nearest_ids, nearest_ts = world.cast_ray(origin, direction)
        np.testing.assert_array_equal(nearest_ids, [i for _, i in entered[:1]])
    with pytest.raises(smb.ArgumentError):
        world.cast_ray(np.zeros(dim), np.zeros(dim))
    with pytest.raises(smb.InvalidBoxError):
        world.query(np.array([[1.0] * dim, [0.0] * dim]))


@pytest.mark.parametrize("dim", DIMS)
@pytest.mark.parametrize("dtype", DTYPES)
def test_periodic_domain(dim, dtype):
    rng = np.random.default_rng(91 + dim)
    lo, hi = np.full(dim, -8.0), np.full(dim, 8.0)
    world = smb.World(dim, dtype, events=True)
    start = rng.integers(-16, 16, size=(150, dim)) / 2.0
    size = rng.integers(0, 7, size=(150, dim)) / 2.0
    boxes = np.stack([start, start + size], axis=1).astype(dtype)
    world.assign(boxes)
    pairs, shifts = world.detect_periodic(lo, hi, sort=True)
    expected_pairs, expected_shifts = brute_periodic(boxes, lo, hi, [True] * dim)
    np.testing.assert_array_equal(pairs, expected_pairs)
    np.testing.assert_array_equal(shifts, expected_shifts)
    assert np.any(shifts != 0)
    world.set_static([0], True)
    with pytest.raises(smb.ArgumentError):
        world.detect_periodic(lo, hi)


@pytest.mark.parametrize("dtype", DTYPES)
def test_errors_change_nothing(dtype):
    rng = np.random.default_rng(3)
    world = smb.World(3, dtype, events=True)
    boxes = random_boxes(rng, 100, 3, dtype)
    world.insert(np.arange(100), boxes)
    before = world.detect(sort=True)
    bad = random_boxes(rng, 3, 3, dtype)
    bad[1, 0, 0] = np.inf
    with pytest.raises(smb.InvalidBoxError):
        world.insert([200, 201, 202], bad)
    with pytest.raises(smb.InvalidBoxError):
        world.update([5, 6, 7], bad)
    with pytest.raises(smb.DuplicateIdError, match="42"):
        world.insert([300, 42], random_boxes(rng, 2, 3, dtype))
    with pytest.raises(smb.DuplicateIdError):
        world.insert([300, 300], random_boxes(rng, 2, 3, dtype))
    with pytest.raises(smb.UnknownIdError, match="1000"):
        world.remove([3, 1000])
    with pytest.raises(smb.UnknownIdError):
        world.update([1000], random_boxes(rng, 1, 3, dtype))
    with pytest.raises(smb.UnknownIdError):
        world.box(1000)
    with pytest.raises(smb.UnknownIdError):
        world.set_filter([1, 1000], 2, 2)
    with pytest.raises(ValueError, match="negative"):
        world.remove([3, -1])
    with pytest.raises(ValueError, match="2 ids but 3 boxes"):
        world.insert([400, 401], random_boxes(rng, 3, 3, dtype))
    with pytest.raises(TypeError, match="integers"):
        world.remove([1.5])
    with pytest.raises(ValueError, match=r"\(N, 2, 3\)"):
        world.update([1], np.zeros((1, 2, 2), dtype))
    for error in (smb.InvalidBoxError, smb.DuplicateIdError, smb.UnknownIdError):
        assert issubclass(error, ValueError)
    assert len(world) == 100 and 3 in world and 200 not in world and 300 not in world
    np.testing.assert_array_equal(world.box(5), boxes[5])
    assert world.filter(1) == (1, 0xFFFFFFFF)
    np.testing.assert_array_equal(world.detect(sort=True), before)
    assert len(world.begun) == 0 and len(world.ended) == 0


def test_large_ids_and_single_id():
    world = smb.World(2)
    big = np.array([(1 << 63) - 1, (1 << 62)], dtype=np.uint64)
    world.insert(big, np.zeros((2, 2, 2)))
    np.testing.assert_array_equal(world.detect(), [[1 << 62, (1 << 63) - 1]])
    world.insert(np.array([1 << 63], dtype=np.uint64), np.zeros((1, 2, 2)))
    with pytest.raises(ValueError, match="negative"):
        world.insert(-7, np.zeros((1, 4)))
    world.insert(7, np.zeros((1, 4)))
    assert 7 in world and len(world) == 4
    world.remove(7)
    assert 7 not in world


def test_pair_limit_leaves_the_world_valid():
    world = smb.World(2, max_pairs_held=5)
    world.assign(np.zeros((4, 2, 2)))
    with pytest.raises(smb.PairLimitError):
        world.detect()
    world.remove([0])
    assert len(world.detect()) == 3
