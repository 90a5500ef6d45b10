# SPDX-License-Identifier: MIT
"""Checks of the arguments the package's constructors and calls take, so that a bad value raises
a short TypeError or ValueError naming it, before the compiled part is called."""

import operator

import numpy as np

from . import _smb

DEFAULT_TARGET_CELL_POPULATION = 24
DEFAULT_MAX_PAIRS_HELD = 1 << 28
_SIZE_LIMIT = (1 << 64) - 1


def integer(name, value):
    """`value` as a Python int: Python and NumPy integers only (not bool, float or str)."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be an integer; got {value!r}")
    try:
        return operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer; got {value!r} ({type(value).__name__})") from None


def count(name, value):
    """A non-negative integer that fits a C++ size_t (threads, cell population, pair limit)."""
    value = integer(name, value)
    if value < 0:
        raise ValueError(f"{name} must not be negative; got {value}")
    if value > _SIZE_LIMIT:
        raise ValueError(f"{name} must be at most 2**64 - 1; got {value}")
    return value


def real(name, value):
    """A float from a Python or NumPy number; an integer only when it converts exactly."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be a number; got {value!r}")
    try:
        result = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number; got {value!r} ({type(value).__name__})") from None
    except OverflowError:
        raise ValueError(f"{name} = {value} is beyond the range of float64") from None
    if isinstance(value, (int, np.integer)) and int(result) != value:
        raise TypeError(f"{name} = {value} does not convert exactly to float64; pass a float to accept the rounding")
    return result


def dimension(dim):
    dim = integer("dim", dim)
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3; got {dim}")
    return dim


def implementation(prefix, dim, dtype):
    """The compiled class for `dim` and `dtype` (float32 or float64), with the dtype."""
    dim = dimension(dim)
    dtype = np.dtype(dtype)
    if dtype == np.float32:
        suffix = "f"
    elif dtype == np.float64:
        suffix = "d"
    else:
        raise TypeError(f"dtype must be float32 or float64; got {dtype}")
    return getattr(_smb, f"{prefix}{dim}{suffix}"), dim, dtype


def pipeline(value):
    if not isinstance(value, str):
        raise TypeError(f"pipeline must be 'persistent_cuts' or 'paper_lists'; got {value!r}")
    return value
