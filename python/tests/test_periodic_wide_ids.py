# SPDX-License-Identifier: MIT
"""A periodic World whose ids do not fit in 32 bits: the pair is reported, and nothing crashes
(run in a child interpreter, so that a crash is a failure rather than the end of the suite)."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import smb


@pytest.mark.parametrize("dim", [2, 3])
def test_periodic_world_with_an_id_of_2_to_the_32(dim):
    script = textwrap.dedent(f"""
        import numpy as np
        import smb
        dim = {dim}
        world = smb.World(dim=dim)
        lo = np.zeros((2, dim))
        hi = np.ones((2, dim))
        lo[1, 0], hi[1, 0] = 1, 2
        world.insert(np.array([2**32, 7], dtype=np.int64), np.stack([lo, hi], axis=1))
        pairs, shifts = world.detect_periodic(np.zeros(dim), np.full(dim, 12.0), sort=True)
        print(pairs.tolist(), shifts.tolist())
    """)
    child = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert child.returncode == 0, child.stderr
    assert child.stdout.split() == f"[[7, 4294967296]] [[{', '.join(['0'] * dim)}]]".split()


def test_periodic_world_with_wide_ids_against_the_plain_detection():
    # Ids on both sides of 2^32 and 2^62; well inside the domain, the periodic pairs are the
    # ordinary ones, each with the shift 0.
    rng = np.random.default_rng(35)
    ids = np.array([7, 2**32, 2**32 - 1, 2**32 + 1, 2**31, 2**62, 2**62 + 2**32, 3 * 2**32], dtype=np.int64)
    lo = rng.random((len(ids), 3)) * 4 + 4
    boxes = np.stack([lo, lo + 1.5], axis=1)
    world = smb.World(dim=3)
    world.insert(ids, boxes)
    plain = world.detect(sort=True)
    pairs, shifts = world.detect_periodic(np.zeros(3), np.full(3, 16.0), sort=True)
    np.testing.assert_array_equal(pairs, plain)
    assert not np.any(shifts)
    assert len(plain) > 0
