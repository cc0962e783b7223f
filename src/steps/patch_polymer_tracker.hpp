#pragma once
// The polymers of ["TopologicalMeasures","PatchPolymers"] (patch_polymers.hpp), kept up to date event
// by event on the host. Monomers are numbered 0..n-1 here. A polymer is the sequence of monomers in
// which each one's start patch is bonded to the next one (so a new bond from a's start patch joins a,
// the last monomer of its chain or a free monomer, to b, the first of its chain or a free monomer); a
// ring is a polymer whose last monomer is bonded back to its first. Each monomer has a state: on the
// surface or in the bulk (a polymer is on the surface when any of its monomers is), in a ring or a
// linear chain, and its position in the chain (monomers before and after it). After each event the
// monomer the event belongs to moves to its new state, and the transition counts add the steps it
// spent in the old one (key (old, old)) and one transition (key (old, new)), as UAMMD-structured
// counts them; the other monomers of the polymer keep their recorded state until an event of theirs.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace structmd {

class PatchPolymerTracker {
public:
    // Every monomer free and in the bulk, in that state since `step`. maxLen: longest chain (monomers
    // before plus after) whose state keys spell out the positions; longer ones are "LM" / "RM".
    PatchPolymerTracker(int monomers, int maxLen, int64_t step);

    // Monomer a's start patch bonded to b / unbonded from b, at `step`. Throws ERR_STATE when the
    // bond does not fit the polymers (a patch bonded to a patch of the same kind).
    void polymerize(int64_t step, int a, int b);
    void depolymerize(int64_t step, int a, int b);
    // Monomer a reaches the surface (onSurface) or leaves it.
    void move_to_surface(int64_t step, int a, bool onSurface);

    // counts[k]: the polymers of k + 1 monomers (k bonds for a chain; rings as chains of their
    // monomers), free monomers at k = 0, over the polymers in the bulk (onSurface false) or on the
    // surface; both have one entry beyond the longest polymer's k.
    std::vector<int64_t> distribution(bool onSurface) const;
    double surface_fraction() const;
    // (from, to) -> count: (s, s) the steps spent in s, (s, t) the transitions from s to t.
    const std::map<std::pair<std::string, std::string>, uint64_t>& transitions() const { return transitions_; }

    // The key of monomer a's present state: S_ / B_ (surface, bulk), then L_<before>_<after> (a chain
    // of at most maxLen + 1 monomers), R_<monomers - 1> (a ring), LM or RM (longer).
    std::string state_key(int a) const;

private:
    struct Recorded {
        int64_t step;
        std::string key;
    };
    bool polymer_on_surface(int polymer) const;
    void create(std::vector<int> chain);
    void erase(int polymer);
    void record(int64_t step, int a);
    void check(bool ok, const char* what, int a, int b) const;

    int maxLen_;
    int nextPolymer_ = 0;
    std::vector<int> polymerOf_;  // by monomer, -1 when free
    std::vector<bool> onSurface_;
    std::map<int, std::vector<int>> polymers_;
    std::set<int> rings_;
    std::vector<Recorded> recorded_;
    std::map<std::pair<std::string, std::string>, uint64_t> transitions_;
};

}  // namespace structmd
