# SPDX-License-Identifier: MIT
"""The names that the docs' Python fragments use without defining them (a reader's program has
them by then), for tests/docs/run_python_snippets.py: a Detector with boxes to detect, and the
number of steps of a loop. Small, so that the snippets run in a moment; each block is given a
fresh copy of these names, and a block that defines its own replaces them."""

import numpy

import smb

steps = 3
_lo = numpy.random.default_rng(7).random((2_000, 3)) * 20.0
boxes = numpy.stack([_lo, _lo + 0.5], axis=1)
detector = smb.Detector(dim=3)
