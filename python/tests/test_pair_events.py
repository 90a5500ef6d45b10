# SPDX-License-Identifier: MIT
"""smb.PairEvents alone, over random pair lists with names across the 64-bit range, renames
(replace, swap_remove) between updates, against a model; bad input changes nothing."""

import numpy as np
import pytest

import smb
from reference import as_set, sorted_rows

TOP = (1 << 64) - 1


def test_events_over_random_lists_with_renames():
    """Bodies carry a uid the events never see; the model names the events by uid pairs."""
    rng = np.random.default_rng(5)
    events = smb.PairEvents(threads=2)
    pool = np.unique(np.concatenate([np.array([0, 1, 1 << 32, 1 << 63, TOP - 1, TOP], dtype=np.uint64),
                                     rng.integers(0, TOP, size=200, dtype=np.uint64, endpoint=True)]))
    pool = [int(name) for name in pool]
    uid_at = {pool[k]: uid for uid, k in enumerate(rng.choice(len(pool), 50, replace=False).tolist())}
    next_uid = len(uid_at)
    previous = {}  # uid pair -> the names the previous list gave it
    for _ in range(15):
        names = sorted(uid_at)
        chosen = {tuple(sorted(names[k] for k in rng.choice(len(names), 2, replace=False))) for _ in range(80)}
        pairs = sorted_rows(np.fromiter((n for pair in chosen for n in pair), dtype=np.uint64).reshape(-1, 2))
        events.update(pairs[rng.permutation(len(pairs))])
        now = {frozenset((uid_at[a], uid_at[b])): (a, b) for a, b in chosen}
        assert as_set(events.begun) == {now[k] for k in now.keys() - previous.keys()}
        assert as_set(events.ended) == {previous[k] for k in previous.keys() - now.keys()}
        assert events.begun.dtype == np.uint64 and len(events) == len(pairs)
        previous = now
        for _ in range(int(rng.integers(0, 3))):  # the body at `removed` goes, the one at `last` moves there
            held = sorted(uid_at)
            removed, last = sorted(held[k] for k in rng.choice(len(held), 2, replace=False))
            events.swap_remove(removed, last)
            uid_at[removed] = uid_at.pop(last)
        for _ in range(int(rng.integers(0, 3))):  # a new body under an old name
            held = sorted(uid_at)
            name = held[int(rng.integers(0, len(held)))]
            events.replace(name)
            uid_at[name], next_uid = next_uid, next_uid + 1
        for name in [pool[k] for k in rng.choice(len(pool), 3, replace=False)]:  # new bodies, unused names
            if name not in uid_at:
                uid_at[name], next_uid = next_uid, next_uid + 1


def test_bad_input_changes_nothing():
    events = smb.PairEvents()
    events.update([[1, 2], [2, TOP]])
    for bad, error in (([[2, 1]], smb.ArgumentError), ([[1, 2], [1, 2]], smb.ArgumentError),
                       ([[-1, 2]], ValueError), ([[1, 2, 3]], ValueError), ([[1.5, 2]], TypeError),
                       (np.zeros((2, 2, 2), dtype=np.int64), ValueError)):
        with pytest.raises(error):
            events.update(bad)
    with pytest.raises(smb.ArgumentError):
        events.swap_remove(3, 2)
    with pytest.raises(ValueError):
        events.swap_remove(-1, 2)
    with pytest.raises(ValueError):
        events.replace([-3])
    assert as_set(events.begun) == {(1, 2), (2, TOP)} and len(events) == 2
    events.update(np.array([[2, TOP]], dtype=np.uint64))
    assert as_set(events.ended) == {(1, 2)} and len(events.begun) == 0
    events.update(np.empty((0, 2), dtype=np.int64))
    assert as_set(events.ended) == {(2, TOP)}
    events.update([])
    assert len(events) == 0
