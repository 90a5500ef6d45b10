# SPDX-License-Identifier: MIT
"""Arguments and messages: settings that are not counts, dims that are not 2 or 3, membership of
what cannot be an id, the pair limit's advice; the package's names and their docstrings."""

import inspect

import numpy as np
import pytest

import smb


def makers():
    """Every public constructor and one-shot call that takes threads and the limits."""
    boxes = np.zeros((3, 2, 2))
    return [lambda **kw: smb.Detector(2, **kw), lambda **kw: smb.World(2, **kw),
            lambda **kw: smb.find_overlapping_pairs(boxes, **kw),
            lambda **kw: smb.find_overlapping_pairs(boxes, boxes, **kw)]


@pytest.mark.parametrize("make", makers())
@pytest.mark.parametrize("name", ["threads", "max_pairs_held", "target_cell_population"])
def test_counts_are_checked_with_a_short_message(make, name):
    for bad, error in ((-1, ValueError), (1 << 64, ValueError), (1.5, TypeError), ("2", TypeError),
                       (None, TypeError)):
        with pytest.raises(error, match=f"^{name} must") as raised:
            make(**{name: bad})
        assert "incompatible function arguments" not in str(raised.value)
    make(**{name: np.int64(64)})


def test_pair_events_threads_are_checked():
    with pytest.raises(ValueError, match="^threads must not be negative"):
        smb.PairEvents(threads=-1)


@pytest.mark.parametrize("kind", [smb.Detector, smb.World])
def test_dim_must_be_the_integer_2_or_3(kind):
    for bad in (3.0, "3", 2.5, None, True):
        with pytest.raises(TypeError, match="^dim must be an integer"):
            kind(dim=bad)
    for bad in (1, 4, -3):
        with pytest.raises(ValueError, match="^dim must be 2 or 3"):
            kind(dim=bad)
    assert kind(dim=np.int32(3)).dim == 3
    with pytest.raises(TypeError, match="^dtype must be float32 or float64"):
        kind(2, np.int64)


def test_other_settings():
    with pytest.raises(TypeError, match="^pipeline must be"):
        smb.World(2, pipeline=3)
    with pytest.raises(TypeError, match="^skin must be a number"):
        smb.Detector(2, skin="wide")
    with pytest.raises(TypeError, match="^max_t"):
        smb.World(2).cast_ray([0, 0], [1, 0], (1 << 53) + 1)


def test_swap_remove_refuses_what_is_not_an_index():
    detector = smb.Detector(2, events=True)
    for removed, last, error in ((-1, 2, ValueError), (0, 1 << 64, ValueError), ("a", 1, TypeError),
                                 (0.0, 1, TypeError)):
        with pytest.raises(error, match="^(removed|last) must be an integer") as raised:
            detector.swap_remove(removed, last)
        assert "incompatible function arguments" not in str(raised.value)
    with pytest.raises(smb.ArgumentError):
        detector.swap_remove(3, 2)


def test_membership_of_anything_is_true_or_false():
    world = smb.World(2)
    world.insert([0, 5], np.zeros((2, 4)))
    for thing in (-1, "a", 2 ** 70, 1 << 64, 5.0, None, [5], (5,), object()):
        assert (thing in world) is False
    assert 5 in world and np.int8(5) in world and np.uint64(5) in world


def test_axes_is_one_per_axis():
    detector = smb.Detector(3)
    with pytest.raises(ValueError, match=r"axes has 1 entries; 3 expected \(one per axis\)"):
        detector.detect_periodic(np.zeros((2, 2, 3)), [0, 0, 0], [9, 9, 9], axes=[True])
    world = smb.World(2)
    with pytest.raises(ValueError, match=r"one per axis"):
        world.detect_periodic([0, 0], [9, 9], axes=[True, False, True])


def test_pair_limit_tells_what_python_can_do():
    boxes = np.zeros((5, 2, 2))
    calls = [lambda: smb.Detector(2, max_pairs_held=3).detect(boxes),
             lambda: smb.find_overlapping_pairs(boxes, max_pairs_held=3)]
    world = smb.World(2, max_pairs_held=3)
    world.assign(boxes)
    calls.append(world.detect)
    for call in calls:
        with pytest.raises(smb.PairLimitError, match="max_pairs_held") as raised:
            call()
        assert "sink" not in str(raised.value)


def test_the_namespace_is_the_public_names():
    public = {name for name in dir(smb) if not name.startswith("_")}
    assert public == set(smb.__all__)
    assert "annotations" not in dir(smb) and "math" not in dir(smb)


def documented(holder):
    """(name, object) for `holder` and each of its public members that Python lets us document."""
    yield holder.__name__, holder
    if inspect.isclass(holder):
        for name, member in vars(holder).items():
            if not name.startswith("_") or name in ("__init__", "__contains__", "__len__"):
                if callable(member) or isinstance(member, property):
                    yield f"{holder.__name__}.{name}", member


def test_every_public_name_has_a_docstring():
    assert smb.__doc__
    missing = []
    for name in smb.__all__:
        for label, obj in documented(getattr(smb, name)):
            if label.endswith("__init__"):
                continue  # the class docstring documents the constructor
            doc = getattr(obj, "__doc__", None)
            if not doc or doc.startswith(("Initialize self", "Return len", "Return key in", "Create new instance")):
                missing.append(label)
    assert missing == []
    assert "max_pairs_held" in smb.PairLimitError.__doc__
