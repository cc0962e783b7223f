#pragma once
// Suggestions for a misspelt name, shared by the input layer (unknown keys and labels, misspelt
// required keys) and the registries (unknown components): the names nearest by edit distance.
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace structmd {

// Levenshtein distance, ignoring case: "cutoffFactor" is a spelling of "cutOffFactor".
inline size_t edit_distance(const std::string& a, const std::string& b) {
    const auto lower = [](unsigned char c) { return static_cast<char>(std::tolower(c)); };
    std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t substitution = previous[j - 1] + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
        }
        std::swap(previous, current);
    }
    return previous[b.size()];
}

// The candidate the user most likely meant, if any is close enough to be worth suggesting.
inline std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates) {
    const size_t tolerance = std::max<size_t>(1, word.size() / 3);
    std::optional<std::string> best;
    size_t bestDistance = tolerance + 1;
    for (const std::string& candidate : candidates) {
        const size_t distance = edit_distance(word, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}

// Indices of up to `count` candidates nearest by `distance` (a callable of a candidate), nearest
// first, ties in the candidates' order, leaving out those more than twice as far as the nearest
// (after a near miss, far ones are noise): what an unknown name is shown instead of every known one.
template <class Candidate, class Distance>
std::vector<size_t> nearest(const std::vector<Candidate>& candidates, size_t count, Distance distance) {
    std::vector<std::pair<size_t, size_t>> ranked;  // (distance, index)
    ranked.reserve(candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i) ranked.emplace_back(distance(candidates[i]), i);
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<size_t> indices;
    for (size_t k = 0; k < std::min(count, ranked.size()); ++k) {
        if (k > 0 && ranked[k].first > 2 * std::max<size_t>(ranked[0].first, 1)) break;
        indices.push_back(ranked[k].second);
    }
    return indices;
}

}  // namespace structmd
