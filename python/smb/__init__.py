# SPDX-License-Identifier: MIT
"""smb: broad-phase collision detection of moving boxes (Sort Moving Boxes) over NumPy arrays.

Boxes are arrays of shape (N, 2, D), rows min then max, or (N, 2*D) as
xmin, ymin[, zmin], xmax, ymax[, zmax]; D is 2 or 3, the dtype float32 or float64. Two boxes
overlap when they overlap or touch on every axis (closed boxes). Pairs of indices (Detector,
find_overlapping_pairs) come back as (P, 2) int64 arrays, pairs of ids (World, whose ids are
any integers in [0, 2**64 - 1]) as (P, 2) uint64 arrays. Detection runs without the GIL.

Errors: bad boxes (NaN, infinity, min > max), unknown and duplicate ids raise InvalidBoxError,
UnknownIdError and DuplicateIdError, subclasses of smb.Error, itself a ValueError; a call that
raises changes nothing. A wrong shape or value raises ValueError, a wrong type or dtype
TypeError (integer boxes that float64 cannot hold exactly included).
"""

import collections as _collections
import math as _math

import numpy as _np

from . import _arguments
from . import _readout
from . import _smb
from ._box_index import BoxIndex
from ._pair_events import PairEvents
from ._smb import (
    ArgumentError,
    DuplicateIdError,
    Error,
    InvalidBoxError,
    PairLimitError,
    UnknownIdError,
    openmp_enabled,
)

__all__ = [
    "ArgumentError",
    "BoxIndex",
    "CandidatePairs",
    "Detector",
    "DuplicateIdError",
    "Error",
    "InvalidBoxError",
    "PairEvents",
    "PairLimitError",
    "UnknownIdError",
    "World",
    "find_overlapping_pairs",
    "openmp_enabled",
]

Error.__doc__ = """What the library refuses: the base of smb's own errors, a ValueError."""
InvalidBoxError.__doc__ = """A box with NaN, an infinity or min > max on some axis (the message names its
index or id), or a box too large for a periodic domain. Nothing changed."""
UnknownIdError.__doc__ = """An id that the World does not hold (update, remove, box, filter, ...).
Nothing changed."""
DuplicateIdError.__doc__ = """An id that the World holds already, or one named twice in one insert.
Nothing changed."""
PairLimitError.__doc__ = """A detection found more than max_pairs_held pairs: the limit that keeps a
runaway scene from exhausting memory. Raise max_pairs_held if the memory allows."""
ArgumentError.__doc__ = """A bad setting, ray, periodic domain or call sequence (a periodic detection
on a World with filters, a swap_remove with removed > last). Nothing changed."""

CandidatePairs = _collections.namedtuple("CandidatePairs", ["pairs", "margin", "available"])
CandidatePairs.__doc__ = """Detector.candidates(): the Verlet list of a Detector with a skin.

pairs: (C, 2) int64, every pair of indices whose fat boxes (each box as it was when the list
was made, grown by the skin) overlap, i < j, in an unspecified order; a superset of the last
detection's pairs. margin: every pair of boxes that overlap once each is grown by margin on
every side is in pairs (about the skin after a rebuild, less as boxes move). available: False,
with pairs empty, when the last detection did not use the list (no skin, no detection yet,
filters, a periodic domain, boxes that moved more than the skin); use the detection's pairs."""
CandidatePairs.pairs.__doc__ = "(C, 2) int64 array of candidate pairs of indices, i < j."
CandidatePairs.margin.__doc__ = "Growth of every box within which pairs holds every overlapping pair."
CandidatePairs.available.__doc__ = "Whether the last detection kept a candidate list."

_DEFAULT_TARGET_CELL_POPULATION = _arguments.DEFAULT_TARGET_CELL_POPULATION
_DEFAULT_MAX_PAIRS_HELD = _arguments.DEFAULT_MAX_PAIRS_HELD


def find_overlapping_pairs(boxes, b_boxes=None, *, threads=1,
                           target_cell_population=_DEFAULT_TARGET_CELL_POPULATION,
                           max_pairs_held=_DEFAULT_MAX_PAIRS_HELD):
    """Every pair of overlapping boxes, as a (P, 2) int64 array sorted by rows.

    find_overlapping_pairs(boxes): the pairs (i, j), i < j, within one set.
    find_overlapping_pairs(a_boxes, b_boxes): the pairs (i, j) with a_boxes[i] overlapping
    b_boxes[j] (i and j index different sets: i < j does not hold).

    float32 boxes are detected as floats, any other dtype as float64 (two sets as floats only
    when both are float32). threads: OpenMP threads (0: all cores). More than max_pairs_held
    pairs raise PairLimitError.
    """
    threads = _arguments.count("threads", threads)
    target_cell_population = _arguments.count("target_cell_population", target_cell_population)
    max_pairs_held = _arguments.count("max_pairs_held", max_pairs_held)
    if b_boxes is None:
        return _smb.find_overlapping_pairs(boxes, threads, target_cell_population, max_pairs_held)
    return _smb.find_overlapping_pairs_between(boxes, b_boxes, threads, target_cell_population,
                                               max_pairs_held)


class _Readouts:
    """What Detector and World both tell of their last detection and of themselves."""

    stats = _readout.forwarded("stats", "What the last detection did and cost: a dict of counts and seconds.")

    profile = _readout.forwarded(
        "profile",
        "Where the last detection spent its time, phase by phase and level by level (a dict of "
        "seconds and counts); all zero unless constructed with profile=True.",
    )

    precision = _readout.forwarded(
        "precision", "What the last detection held: 'none', 'floats' or 'doubles'."
    )

    bytes_held = _readout.forwarded(
        "bytes_held", "Heap bytes the object holds (a Detector's caller's array not counted)."
    )

    threads = _readout.forwarded(
        "threads", "OpenMP threads a detection may use (0: all cores), as constructed."
    )


class Detector(_Readouts):
    """The SMB broad phase over an array of boxes the caller keeps: box i is body i.

    Each detect() takes the whole array and returns every overlapping pair of indices. The
    detector keeps what makes the next call fast (its axial cuts, the order of the bodies), so
    box i should be the same body from one call to the next; the array may grow or shrink.

    dim, dtype: the boxes' dimension (2 or 3) and dtype (float32 or float64). Boxes of another
    dtype are converted when every value converts exactly, else TypeError.
    skin: grow each box by this much and keep the candidate pairs between calls (a Verlet list);
    pays while boxes move much less than the skin per call. 0 detects from scratch each call.
    threads: OpenMP threads for a detection (0: all cores); the pairs do not depend on it.
    events: keep the pairs of the previous call, so that begun and ended give the pairs that
    began and ended overlapping (costs about 60 bytes per pair).
    profile: time every phase of each detection (the profile attribute); costs a few clock reads.
    """

    def __init__(self, dim=3, dtype=_np.float64, *, skin=0.0, threads=1, events=False, profile=False,
                 target_cell_population=_DEFAULT_TARGET_CELL_POPULATION,
                 max_pairs_held=_DEFAULT_MAX_PAIRS_HELD):
        implementation, self.dim, self.dtype = _arguments.implementation("Detector", dim, dtype)
        self._impl = implementation(_arguments.real("skin", skin), _arguments.count("threads", threads),
                                    _arguments.count("target_cell_population", target_cell_population),
                                    _arguments.count("max_pairs_held", max_pairs_held), bool(events),
                                    bool(profile))

    def detect(self, boxes, *, categories=None, masks=None, static=None, sort=False, out=None):
        """Every overlapping pair (i, j), i < j, of `boxes`, as a (P, 2) int64 array.

        categories, masks: per-box collision filter bits (one value or one per box): boxes i
        and j pair when categories[i] & masks[j] and categories[j] & masks[i] are both non-zero.
        static: per-box flags; two static boxes never pair. sort: return the pairs sorted by
        rows (otherwise in a deterministic but unspecified order).

        out: a writeable C-contiguous (M, 2) int64 array to reuse for the pairs: when they fit
        (P <= M) they are written into its first rows and out[:P] is returned; otherwise a new
        array is returned, so len(result) > len(out) says to grow out for the next call. A loop
        that passes the same out spares each call a fresh allocation of its pairs; the detector
        keeps the vector it detects into (16 bytes a pair) for the next such call.
        """
        return self._impl.detect(boxes, categories, masks, static, bool(sort), out)

    def candidates(self):
        """The Verlet list after the last detect(), as CandidatePairs(pairs, margin, available).

        With a skin, the pairs of boxes whose fat boxes overlap: every pair within `margin` of
        overlapping, for force loops with a cut-off. available is False (pairs empty) when the
        last detection did not run on the list; the detection's pairs are exact in every case.
        """
        pairs, margin, available = self._impl.candidates()
        return CandidatePairs(pairs, margin, available)

    def suggested_order(self):
        """The indices of the last detection's boxes in the order the next one reads them.

        An int64 array holding every index once (cell by cell, each column in x order), after a
        detection over the whole array without the skin, filters that split it or a periodic
        domain; empty otherwise. Renumber every per-body array by it (new index i holds the body
        at order[i], e.g. boxes = boxes[order]) and call follow_suggested_order(): the following
        detections then read the array as one stream. Events by index see renumbered bodies as
        other bodies.
        """
        return self._impl.suggested_order()

    def follow_suggested_order(self):
        """Tells the detector that the bodies were renumbered by suggested_order()."""
        self._impl.follow_suggested_order()

    def detect_periodic(self, boxes, lo, hi, *, axes=None, sort=False):
        """Pairs in a periodic domain: (pairs, shifts), (P, 2) int64 and (P, dim) int32.

        Axis k wraps around over [lo[k], hi[k]) where axes[k] is true (every axis when axes is
        None). Box i overlaps box j translated by shifts[p] periods. Each box's extent must be
        below half the period (else InvalidBoxError).
        """
        return self._impl.detect_periodic(boxes, lo, hi, axes, bool(sort))

    begun = _readout.forwarded(
        "begun", "Pairs of the last detection that were not in the one before, sorted ((P, 2) int64)."
    )

    ended = _readout.forwarded(
        "ended", "Pairs of the detection before the last that are not in the last one, sorted."
    )

    def swap_remove(self, removed, last):
        """Tells the events that body `last` moved to index `removed`, whose body is gone: its
        pairs end at the next detection, and those of the moved body go on under `removed`
        (no event). removed == last: the last body was popped. ArgumentError if removed > last."""
        self._impl.swap_remove(removed, last)

    def replace(self, indices):
        """Tells the events that the bodies at `indices` are new ones: their old pairs end."""
        self._impl.replace(indices)

    def replace_all(self):
        """Tells the events that every body is a new one."""
        self._impl.replace_all()

    def clear(self):
        """Forgets the cuts and the order and releases their memory; keeps the settings."""
        self._impl.clear()

    skin = _readout.forwarded(
        "skin", "How much each box is grown for the candidate list kept between calls (0: none)."
    )

    def __repr__(self):
        return f"smb.Detector(dim={self.dim}, dtype={self.dtype.name}, skin={self.skin})"


class World(_Readouts):
    """A set of moving boxes under caller-chosen ids, and the SMB broad phase over them.

    Ids are integers in [0, 2**64 - 1]: Python integers, or arrays of any integer dtype (uint64
    reaches the whole range); they come back as uint64, the dtype that holds every id. insert,
    update and remove take arrays of ids and boxes and change all or nothing; detect() then
    returns every overlapping pair of ids (a, b), a < b. The world keeps its axial cuts from one detection to
    the next, so a detection after small motions costs linear time.

    dim, dtype, skin, threads, events, profile: as Detector. pipeline: 'persistent_cuts' (the default)
    or 'paper_lists' (the paper's sorted lists; slower, kept to reproduce the paper; no skin).
    """

    def __init__(self, dim=3, dtype=_np.float64, *, skin=0.0, threads=1, events=False, profile=False,
                 pipeline="persistent_cuts",
                 target_cell_population=_DEFAULT_TARGET_CELL_POPULATION,
                 max_pairs_held=_DEFAULT_MAX_PAIRS_HELD):
        implementation, self.dim, self.dtype = _arguments.implementation("World", dim, dtype)
        self._impl = implementation(_arguments.count("threads", threads),
                                    _arguments.count("target_cell_population", target_cell_population),
                                    _arguments.count("max_pairs_held", max_pairs_held),
                                    _arguments.pipeline(pipeline), bool(events), _arguments.real("skin", skin),
                                    bool(profile))

    def insert(self, ids, boxes):
        """Adds boxes[i] under ids[i]. DuplicateIdError for an id present or named twice."""
        self._impl.insert(ids, boxes)

    def update(self, ids, boxes):
        """Moves or resizes the boxes of `ids`. UnknownIdError for an id not present."""
        self._impl.update(ids, boxes)

    def remove(self, ids):
        """Removes the boxes of `ids`. UnknownIdError for an id not present."""
        self._impl.remove(ids)

    def assign(self, boxes):
        """Makes the world hold exactly `boxes`, box i under id i."""
        self._impl.assign(boxes)

    def clear(self):
        """Removes every box and releases the memory held; keeps the settings."""
        self._impl.clear()

    def __len__(self):
        """The number of boxes held."""
        return self._impl.size()

    def __contains__(self, id):
        """Whether a box is under `id`; False for anything that cannot be an id."""
        return self._impl.contains(id)

    def box(self, id):
        """The box under `id`, a (2, dim) array (rows min, max). UnknownIdError if absent."""
        return self._impl.box(id)

    def detect(self, *, sort=False, out=None):
        """Every overlapping pair of ids (a, b), a < b, as a (P, 2) uint64 array.

        With filters or static boxes set, only the pairs they let through. sort: sorted by rows
        (otherwise in a deterministic but unspecified order). out: a (M, 2) uint64 array to
        reuse, as Detector.detect's out.
        """
        return self._impl.detect(bool(sort), out)

    def detect_periodic(self, lo, hi, *, axes=None, sort=False):
        """Pairs in a periodic domain: (pairs, shifts), as Detector.detect_periodic.

        ArgumentError while filters or static boxes are in use.
        """
        return self._impl.detect_periodic(lo, hi, axes, bool(sort))

    begun = _readout.forwarded(
        "begun", "Pairs of the last detection that were not in the one before, sorted ((P, 2) uint64)."
    )

    ended = _readout.forwarded(
        "ended", "Pairs of the detection before the last that are not in the last one, sorted."
    )

    def set_filter(self, ids, categories=None, masks=None):
        """Sets the collision filters of `ids` (one value or one per id; None: the default,
        category 1 and every mask bit). Boxes a and b pair when category[a] & mask[b] and
        category[b] & mask[a] are both non-zero."""
        self._impl.set_filter(ids, categories, masks)

    def filter(self, id):
        """(category, mask) of box `id`."""
        return self._impl.filter(id)

    def set_static(self, ids, is_static=True):
        """Makes the boxes of `ids` static (two static boxes never pair) or dynamic again."""
        self._impl.set_static(ids, bool(is_static))

    def is_static(self, id):
        """Whether box `id` is static. UnknownIdError if absent."""
        return self._impl.is_static(id)

    def query(self, box):
        """Ids of the boxes overlapping `box` ((2, dim) or (2*dim,)), sorted, uint64."""
        return self._impl.query(box)

    def query_batch(self, boxes):
        """(H, 2) uint64 array of (query index, id) for every box overlapping each query box,
        sorted by rows."""
        return self._impl.query_batch(boxes)

    def cast_ray(self, origin, direction, max_t=_math.inf, *, all=False):
        """The boxes the ray origin + t * direction, 0 <= t <= max_t, enters: (ids, t).

        The nearest one (least t, then least id), or with all=True every one sorted by (t, id).
        t is 0 for a box containing the origin. ArgumentError for an invalid ray.
        """
        return self._impl.cast_ray(origin, direction, _arguments.real("max_t", max_t), bool(all))

    def __repr__(self):
        return f"smb.World(dim={self.dim}, dtype={self.dtype.name}, size={len(self)})"
