#include "steps/patch_polymer_tracker.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace structmd {

PatchPolymerTracker::PatchPolymerTracker(int monomers, int maxLen, int64_t step)
    : maxLen_(maxLen), polymerOf_(monomers, -1), onSurface_(monomers, false) {
    for (int a = 0; a < monomers; ++a) recorded_.push_back({step, state_key(a)});
}

void PatchPolymerTracker::check(bool ok, const char* what, int a, int b) const {
    if (!ok)
        throw Error(STRUCTMD_ERR_STATE, std::string("PatchPolymers: ") + what + " (monomers " + std::to_string(a) +
                                            " and " + std::to_string(b) +
                                            " of the group); every bond must join a start patch to an end patch");
}

void PatchPolymerTracker::create(std::vector<int> chain) {
    const int id = nextPolymer_++;
    for (int m : chain) polymerOf_[m] = id;
    polymers_[id] = std::move(chain);
}

void PatchPolymerTracker::erase(int polymer) {
    for (int m : polymers_.at(polymer)) polymerOf_[m] = -1;
    polymers_.erase(polymer);
}

void PatchPolymerTracker::polymerize(int64_t step, int a, int b) {
    const int pa = polymerOf_[a], pb = polymerOf_[b];
    check(a != b, "a monomer bonded to itself", a, b);
    check(pa < 0 || (!rings_.count(pa) && polymers_[pa].back() == a), "a new bond from inside a chain", a, b);
    check(pb < 0 || (!rings_.count(pb) && polymers_[pb].front() == b), "a new bond to inside a chain", a, b);
    if (pa < 0 && pb < 0) {
        create({a, b});
    } else if (pa == pb) {
        rings_.insert(pa);
    } else if (pa < 0) {
        std::vector<int> chain = polymers_[pb];
        chain.insert(chain.begin(), a);
        erase(pb);
        create(std::move(chain));
    } else if (pb < 0) {
        polymers_[pa].push_back(b);
        polymerOf_[b] = pa;
    } else {
        std::vector<int> tail = polymers_[pb];
        erase(pb);
        for (int m : tail) polymerOf_[m] = pa;
        polymers_[pa].insert(polymers_[pa].end(), tail.begin(), tail.end());
    }
    record(step, a);
}

void PatchPolymerTracker::depolymerize(int64_t step, int a, int b) {
    const int p = polymerOf_[a];
    check(p >= 0 && p == polymerOf_[b], "a broken bond between different polymers", a, b);
    std::vector<int>& chain = polymers_[p];
    const auto ia = std::find(chain.begin(), chain.end(), a) - chain.begin();
    const auto ib = std::find(chain.begin(), chain.end(), b) - chain.begin();
    const auto size = static_cast<std::ptrdiff_t>(chain.size());
    if (rings_.count(p)) {
        check(ib == (ia + 1) % size, "a broken bond between monomers not next to each other", a, b);
        // The ring opens into the chain that starts at b and ends at a.
        std::rotate(chain.begin(), chain.begin() + ib, chain.end());
        rings_.erase(p);
    } else {
        check(ib == ia + 1, "a broken bond between monomers not next to each other", a, b);
        std::vector<int> head(chain.begin(), chain.begin() + ib), tail(chain.begin() + ib, chain.end());
        erase(p);
        if (head.size() > 1) create(std::move(head));
        if (tail.size() > 1) create(std::move(tail));
    }
    record(step, a);
}

void PatchPolymerTracker::move_to_surface(int64_t step, int a, bool onSurface) {
    onSurface_[a] = onSurface;
    record(step, a);
}

bool PatchPolymerTracker::polymer_on_surface(int polymer) const {
    for (int m : polymers_.at(polymer))
        if (onSurface_[m]) return true;
    return false;
}

std::string PatchPolymerTracker::state_key(int a) const {
    const int p = polymerOf_[a];
    int before = 0, after = 0;
    bool surface = onSurface_[a], ring = false;
    if (p >= 0) {
        const std::vector<int>& chain = polymers_.at(p);
        before = static_cast<int>(std::find(chain.begin(), chain.end(), a) - chain.begin());
        after = static_cast<int>(chain.size()) - 1 - before;
        surface = polymer_on_surface(p);
        ring = rings_.count(p) > 0;
    }
    std::string key = surface ? "S_" : "B_";
    if (before + after > maxLen_) return key + (ring ? "RM" : "LM");
    if (ring) return key + "R_" + std::to_string(before + after);
    return key + "L_" + std::to_string(before) + "_" + std::to_string(after);
}

void PatchPolymerTracker::record(int64_t step, int a) {
    Recorded& old = recorded_[a];
    const std::string now = state_key(a);
    transitions_[{old.key, old.key}] += static_cast<uint64_t>(step - old.step);
    transitions_[{old.key, now}] += 1;
    old = {step, now};
}

std::vector<int64_t> PatchPolymerTracker::distribution(bool onSurface) const {
    size_t longest = 0;
    for (const auto& [id, chain] : polymers_) longest = std::max(longest, chain.size() - 1);
    std::vector<int64_t> counts(longest + 1, 0);
    for (size_t a = 0; a < polymerOf_.size(); ++a)
        if (polymerOf_[a] < 0 && onSurface_[a] == onSurface) ++counts[0];
    for (const auto& [id, chain] : polymers_)
        if (polymer_on_surface(id) == onSurface) ++counts[chain.size() - 1];
    return counts;
}

double PatchPolymerTracker::surface_fraction() const {
    if (onSurface_.empty()) return 0.0;
    const auto on = std::count(onSurface_.begin(), onSurface_.end(), true);
    return static_cast<double>(on) / static_cast<double>(onSurface_.size());
}

}  // namespace structmd
