// SPDX-License-Identifier: MIT
#pragma once
// The report a pipeline calls when it runs over a gathered array of boxes (index i of the array
// is one box): it tests the filter bits and the predicate of each pair of indices, and hands
// the pairs that pass, under their ids, to the caller's output. Filtered pairs go no further
// than these two loads and a test; the pipeline's own runs of pairs lose their (a < b) order
// through the ids, so they are reported one by one.

#include <cstddef>
#include <span>

#include "core/pair_output.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <class Output>
class FilteredReport {
public:
    /// `ids` empty: index i is id i. `filters` one per index. `predicate` null or non-empty.
    FilteredReport(Output& output, std::span<const BoxId> ids, std::span<const Filter> filters,
                   const PairPredicate* predicate)
        : output_(output), ids_(ids), filters_(filters), predicate_(predicate) {}

    void operator()(BoxId a, BoxId b) {
        if (!filters_pass(filters_[a], filters_[b])) return;
        const BoxId id_a = ids_.empty() ? a : ids_[a];
        const BoxId id_b = ids_.empty() ? b : ids_[b];
        if (predicate_ != nullptr) {
            const Pair pair = ordered_pair(id_a, id_b);
            if (!(*predicate_)(pair.a, pair.b)) return;
        }
        output_(id_a, id_b);
    }

    void append(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) (*this)(p.a, p.b);
    }

private:
    Output& output_;
    std::span<const BoxId> ids_;
    std::span<const Filter> filters_;
    const PairPredicate* predicate_;
};

}  // namespace smb::detail
