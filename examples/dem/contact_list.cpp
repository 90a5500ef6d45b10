// SPDX-License-Identifier: MIT
#include "contact_list.hpp"

#include <cstddef>

namespace dem {

namespace {

smb::Pair pair_of(const Contact& contact) { return smb::Pair{contact.a, contact.b}; }

Contact fresh(const smb::Pair& pair) {
    return Contact{static_cast<std::uint32_t>(pair.a), static_cast<std::uint32_t>(pair.b), Vec3{}};
}

}  // namespace

void ContactList::apply_events(std::span<const smb::Pair> ended, std::span<const smb::Pair> begun) {
    next_.clear();
    next_.reserve(contacts_.size() + begun.size());
    std::size_t e = 0;
    std::size_t g = 0;
    for (const Contact& contact : contacts_) {
        const smb::Pair pair = pair_of(contact);
        while (g < begun.size() && begun[g] < pair) next_.push_back(fresh(begun[g++]));
        // Every ended pair is a contact of the list: they are met in the same order.
        if (e < ended.size() && ended[e] == pair) {
            ++e;
            continue;
        }
        next_.push_back(contact);
    }
    while (g < begun.size()) next_.push_back(fresh(begun[g++]));
    contacts_.swap(next_);
}

void ContactList::assign_sorted(std::span<const smb::Pair> pairs) {
    next_.clear();
    next_.reserve(pairs.size());
    std::size_t old = 0;
    for (const smb::Pair& pair : pairs) {
        while (old < contacts_.size() && pair_of(contacts_[old]) < pair) ++old;
        if (old < contacts_.size() && pair_of(contacts_[old]) == pair) {
            next_.push_back(contacts_[old]);
        } else {
            next_.push_back(fresh(pair));
        }
    }
    contacts_.swap(next_);
}

}  // namespace dem
