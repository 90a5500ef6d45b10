#pragma once
// Exceptions thrown by smb. Every throwing call of World is all-or-nothing: when it throws,
// the world is exactly as it was before the call.

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

/// An id that is already in the world (insert), or named twice in one insert or remove batch.
/// (An update batch that names an id twice is accepted: the last of its boxes wins.)
class DuplicateIdError : public Error {
public:
    using Error::Error;
};

/// detect(std::vector<Pair>&) found more pairs than WorldSettings::max_pairs_held. The world
/// stays valid; detect(sink) streams any number of pairs.
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
