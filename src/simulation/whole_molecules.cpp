#include "simulation/whole_molecules.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/box.hpp"

namespace structmd {

namespace {

// The bond graph in compressed rows: the neighbours of particle i are
// neighbours[first[i] .. first[i + 1]).
struct BondGraph {
    std::vector<int64_t> first;
    std::vector<int64_t> neighbours;
};

BondGraph bond_graph(size_t n, const std::vector<BondSpec>& bonds) {
    BondGraph graph;
    std::vector<int64_t> degree(n, 0);
    auto for_each_edge = [&](auto&& visit) {
        for (const BondSpec& bond : bonds)
            for (size_t start = 0; start + static_cast<size_t>(bond.arity) <= bond.members.size();
                 start += static_cast<size_t>(bond.arity))
                for (int k = 1; k < bond.arity; ++k) visit(bond.members[start + k - 1], bond.members[start + k]);
    };
    for_each_edge([&](int a, int b) {
        ++degree[a];
        ++degree[b];
    });
    graph.first.assign(n + 1, 0);
    for (size_t i = 0; i < n; ++i) graph.first[i + 1] = graph.first[i] + degree[i];
    graph.neighbours.resize(static_cast<size_t>(graph.first[n]));
    std::vector<int64_t> filled(graph.first.begin(), graph.first.end() - 1);
    for_each_edge([&](int a, int b) {
        graph.neighbours[filled[a]++] = b;
        graph.neighbours[filled[b]++] = a;
    });
    return graph;
}

// Along an open axis (length infinity) the nearest image is the particle itself.
double nearest_image(double d, double length) {
    return is_open_axis(length) ? d : d - length * std::nearbyint(d / length);
}

}  // namespace

void make_bonded_groups_whole(std::vector<std::array<double, 3>>& positions, const std::array<double, 3>& box,
                              const std::vector<BondSpec>& bonds) {
    const size_t n = positions.size();
    const BondGraph graph = bond_graph(n, bonds);
    if (graph.neighbours.empty()) return;
    std::vector<char> reached(n, 0);
    std::vector<int64_t> queue;
    for (size_t root = 0; root < n; ++root) {
        if (reached[root] || graph.first[root] == graph.first[root + 1]) continue;
        reached[root] = 1;
        queue.assign(1, static_cast<int64_t>(root));
        for (size_t head = 0; head < queue.size(); ++head) {
            const int64_t from = queue[head];
            for (int64_t e = graph.first[from]; e < graph.first[from + 1]; ++e) {
                const int64_t to = graph.neighbours[e];
                if (reached[to]) continue;
                reached[to] = 1;
                for (int d = 0; d < 3; ++d)
                    positions[to][d] = positions[from][d] + nearest_image(positions[to][d] - positions[from][d], box[d]);
                queue.push_back(to);
            }
        }
    }
}

}  // namespace structmd
