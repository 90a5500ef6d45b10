# SPDX-License-Identifier: MIT
"""smb.PairEvents: the pairs that began and ended overlapping between two lists of pairs."""

from . import _arguments
from . import _readout
from . import _smb


class PairEvents:
    """Contact events over the pair lists of any source, as the C++ smb::PairEvents.

    update(pairs) compares a list of pairs (every overlapping pair now, each once, a < b, any
    order; (P, 2) integers in [0, 2**64 - 1]) with the list of the update before: begun then
    holds the pairs new in it and ended those gone from it, each sorted, as (P, 2) uint64. The
    first update reports every pair as begun. Bodies renamed between two updates are told with
    replace (a new body under an old name), replace_all, and swap_remove (an array kept by
    swap-remove). ArgumentError for a pair with a >= b or a pair listed twice; a call that
    raises changes nothing. threads: OpenMP threads an update may use (0: all cores).
    """

    def __init__(self, *, threads=1):
        self._impl = _smb.PairEvents(_arguments.count("threads", threads))

    def update(self, pairs, replaced=None):
        """Compares `pairs` with the previous list, after replace(replaced) when given."""
        self._impl.update(pairs, replaced)

    def replace(self, names):
        """The bodies now under `names` are new ones: their old pairs end, their pairs begin."""
        self._impl.replace(names)

    def replace_all(self):
        """Every body is a new one: every old pair ends and every pair begins."""
        self._impl.replace_all()

    def swap_remove(self, removed, last):
        """The body at `removed` is gone and the body at `last` moved there (its pairs go on, no
        event); removed == last: the last body was popped. ArgumentError if removed > last."""
        self._impl.swap_remove(removed, last)

    def clear(self):
        """Forgets the previous list and the calls since; the next update reports every pair."""
        self._impl.clear()

    begun = _readout.forwarded(
        "begun", "Pairs of the last update's list that were not in the one before, sorted."
    )

    ended = _readout.forwarded(
        "ended", "Pairs of the list before the last update that are not in it, sorted."
    )

    def __len__(self):
        """Pairs in the last update's list."""
        return self._impl.size()

    threads = _readout.forwarded(
        "threads", "OpenMP threads an update may use (0: all cores), as constructed."
    )

    bytes_held = _readout.forwarded("bytes_held", "Heap bytes held now.")

    def __repr__(self):
        return f"smb.PairEvents(threads={self.threads}, size={len(self)})"
