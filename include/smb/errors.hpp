// SPDX-License-Identifier: MIT
#pragma once
// Exceptions thrown by smb. Every call of World and Detector that throws leaves the caller's
// data as it was: a world holds the same boxes, and detect(..., std::vector<Pair>&) leaves the
// vector as it was. A world or detector whose detection was ended by the pair limit or by the
// caller's sink stays valid, and its next detection reports every pair again.

#include <stdexcept>
#include <string>

namespace smb {

/// Base of everything smb throws on bad input.
class Error : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// A box with a NaN or infinite coordinate, or with min > max on some axis.
class InvalidBoxError : public Error {
public:
    using Error::Error;
};

/// An id that is not in the world (remove, update).
class UnknownIdError : public Error {
public:
    using Error::Error;
};

/// An id that is already in the world (insert), or named twice in one insert or remove batch;
/// the message names the id and which of the two it is. (An update batch that names an id twice
/// is accepted: the last of its boxes wins.)
class DuplicateIdError : public Error {
public:
    using Error::Error;
};

/// detect(..., std::vector<Pair>&) found more pairs than max_pairs_held (WorldSettings or
/// DetectorSettings). The world or detector stays valid, the vector as it was; detect(sink)
/// streams any number of pairs.
class PairLimitError : public Error {
public:
    using Error::Error;
};

/// A caller-supplied argument that does not fit (mismatched span lengths, bad settings).
class ArgumentError : public Error {
public:
    using Error::Error;
};

}  // namespace smb
