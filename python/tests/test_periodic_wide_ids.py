# SPDX-License-Identifier: MIT
"""A periodic World whose ids do not fit in 32 bits: the pairs are reported, and nothing crashes
(each check runs in a child interpreter, so that a crash is a failure rather than the end of the
suite)."""

import subprocess
import sys
import textwrap

import pytest


def run_child(script):
    child = subprocess.run([sys.executable, "-c", textwrap.dedent(script)], capture_output=True, text=True,
                           timeout=120)
    assert child.returncode == 0, child.stderr
    return child.stdout


@pytest.mark.parametrize("dim", [2, 3])
def test_periodic_world_with_an_id_of_2_to_the_32(dim):
    out = run_child(f"""
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
    assert out.split() == f"[[7, 4294967296]] [[{', '.join(['0'] * dim)}]]".split()


def test_periodic_world_with_wide_ids_against_the_plain_detection():
    # Ids on both sides of 2^32 and 2^62; well inside the domain, the periodic pairs are the
    # ordinary ones, each with the shift 0.
    out = run_child("""
        import numpy as np
        import smb
        rng = np.random.default_rng(35)
        ids = np.array([7, 2**32, 2**32 - 1, 2**32 + 1, 2**31, 2**62, 2**62 + 2**32, 3 * 2**32], dtype=np.int64)
        lo = rng.random((len(ids), 3)) * 4 + 4
        world = smb.World(dim=3)
        world.insert(ids, np.stack([lo, lo + 1.5], axis=1))
        plain = world.detect(sort=True)
        pairs, shifts = world.detect_periodic(np.zeros(3), np.full(3, 16.0), sort=True)
        assert len(plain) > 0
        np.testing.assert_array_equal(pairs, plain)
        assert not np.any(shifts)
        print("same", len(plain))
    """)
    assert out.startswith("same ")
