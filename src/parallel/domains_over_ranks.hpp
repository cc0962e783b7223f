#pragma once
// One system (one batch) spread in space over the K ranks of an MPI communicator: spatial domain
// decomposition, first increment (slabs, CPU-tested; the CUDA engine compiles the same path).
//
// Design.
// - Domains: K slabs of equal width along the longest box axis; rank r owns the particles whose
//   fractional coordinate along it lies in [r/K, (r+1)/K). Its neighbours are ranks r-1 and r+1
//   (periodic; with K = 2 both are the other rank, and a border particle is sent to it once).
// - The engine of a domain is an ordinary Engine made from a spec of its own (domain_spec.hpp: the
//   whole system's spec, read once, with the domain's rows) whose slots are the owned particles (in
//   increasing global id when made, in no particular order after a rebuild in place), then the
//   ghosts: copies of the particles other ranks own within the ghost width W of the slab's faces.
//   Slots keep their global id for the noise (NoiseKey::ids), so a particle draws the same numbers
//   on any rank, and Langevin trajectories are those of one rank to rounding.
// - Ghosts: before every force evaluation at new positions the engine refreshes them
//   (GhostExchange, simulation/domain_exchange.hpp): the positions of its border slots, in the
//   engine's own precision, go to the neighbours and theirs come back into the ghost slots: from GPU
//   to GPU through NCCL, queued on the engine's stream (option "ghost_exchange", nccl_channel.hpp),
//   or staged through pinned host memory, MPI point to point (two shifts along the ring of ranks). Ghosts
//   are integrated locally like any particle but with incomplete forces; the refresh overwrites
//   their positions and clears their velocities (no term under domains reads a velocity), so only
//   owned particles' motion counts.
// - Pairs: full neighbour lists over owned and ghost slots; an owned particle's pair force is
//   complete from them, so forces need no reverse communication. Per-particle energies are half of
//   each pair's, so the sum over owned slots of all ranks counts each pair once.
// - Bonds (Bond2): a rank keeps every bond of which it owns a particle; the bond kernel gives each
//   particle its whole force from its own bonds, and its energy share (half), so again the sum
//   over owned slots counts each bond once. Bonds between two ghosts are left out.
// - The ghost set is fixed between rebuilds. W = max(list radius + skin, 1.5 x the longest bond at
//   load), the skin being the lists' reach beyond the cutoff rc.
//   A pair within the cutoff rc of an owned particle is a ghost as long as no particle moved more
//   than (W - rc)/2 since the rebuild; the domains are rebuilt when the largest move over all ranks
//   passes half that (a collective decision, checked after every step on one number each rank's
//   engine reduces where its particles live), and a move past it is an error (never a silently
//   wrong force). A rebuild migrates particles that left the slab to their
//   new owner (sent to the neighbour with position, velocity and image), picks the ghosts anew
//   and either renumbers the engine's slots in place (rebuild_in_place: terms that hold nothing by
//   slot, e.g. pair terms alone; which slots stay, leave or border a face is found and the slots
//   renumbered where the particles live, simulation/domain_slots.hpp, so the host handles only the
//   migrants and the ghosts' ids) or makes the domain's engine again from its spec, at the same
//   step and time, with the
//   schedule's remaining steps, without beginning its integrator again (half-step Langevin
//   velocities carry over).
// - Energies: kinetic from owned velocities, potential from owned per-particle energies, summed
//   over ranks. Per-particle arrays are gathered (global id, values) from every rank into id order;
//   every gather checks that each id arrives exactly once.
// - Simulation steps: made once from the whole system's document at load (so their files are
//   opened once), fired by this view on rank 0 with the other ranks serving its gathers
//   (steps_on_rank_zero.hpp), at the same steps as one engine would.
// - Everything else is refused by name: "<what> is not available under domain decomposition"
//   (domain_support.hpp at load; the API calls below).
// Memory: every rank loads the whole document and the whole system once at load (the same initial
// velocities as one rank), then holds its domain only (plus the whole spec, for the rebuilds).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/logger.hpp"
#include "engines/engine_options.hpp"
#include "forcefield/component_set.hpp"
#include "parallel/communicator.hpp"
#include "parallel/domain_spec.hpp"
#ifdef STRUCTMD_HAVE_NCCL
#include "parallel/nccl_channel.hpp"
#endif
#include "parallel/steps_on_rank_zero.hpp"
#include "simulation/local_engine.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

class DomainsOverRanks final : public StepsOnRankZero, private GhostExchange {
public:
    // `whole`: the system loaded whole on this rank from `spec`, released once the domains are
    // made. Collective.
    DomainsOverRanks(const EngineOptions& options, DomainSpec spec, std::unique_ptr<LocalEngine> whole,
                     const ForceFieldComponents& components, const Logger& log, std::shared_ptr<const Communicator> comm);
    ~DomainsOverRanks() override;

    int64_t particle_count() const override { return total_; }
    int64_t massive_count() const override { return massive_; }
    ScheduleClock clock() const override { return {local_->current_step(), local_->current_time(), finalStep_}; }
    std::array<double, 3> box() const override { return box_; }
    const std::vector<std::string>& type_names() const override { return typeNames_; }
    Counters counters() override;  // this rank's engines since load

    void advance(int64_t n) override;
    void request_stop(const std::string& by) override {
        if (stoppedBy_.empty()) stoppedBy_ = by;
    }
    const std::string& stopped_by() const override { return stoppedBy_; }
    void compute(unsigned flags) override;
    void read(PerParticle q, double* out) override;
    double energy(const std::string& term) override;

    void term_energies_and_forces(const std::string& term, double* energies, double* forces, double* torques) override;
    bool has_magnetization() const override { return false; }

private:
    // One neighbour the ghosts are exchanged with: this rank sends `sent` particles to `to` and
    // receives `received` from `from`.
    struct Link {
        int to = 0, from = 0;
        int64_t sent = 0, received = 0;
    };

    // GhostExchange
    void exchange(const void* border, void* ghosts, size_t bytes) override;
    bool exchanges_on_device() const override { return onDevice_; }
    void exchange_on_device(const void* border, void* ghosts, size_t bytes, void* stream) override;

    void fire_due(bool final);
    // The owned particles as they are now: positions, velocities and images (whole, since load).
    std::vector<Migrant> owned_now();
    // `out` to rank `to`, and whatever rank `from` sends in the same shift (its count first).
    std::vector<double> shift_values(const std::vector<double>& out, int to, int from) const;
    // After a step, given the largest move since the rebuild over all ranks: fails past the ghost
    // layer's limit, rebuilds past half of it.
    void check_moves(double move);
    // Owned particles that left the slab go to their new owner; returns what this rank owns now.
    std::vector<Migrant> migrate(std::vector<Migrant> held);
    // The particles leaving for the ranks above and below go there, once every rank knows that none
    // strayed farther (`astray`: the largest id of one that did, -1 for none); returns those that
    // arrived here.
    std::vector<Migrant> cross(const std::vector<Migrant>& up, const std::vector<Migrant>& down, int64_t astray) const;
    // A rebuild that renumbers the present engine's slots where they live
    // (DomainSpec::renumbers_in_place): only the migrants and the new ghosts' ids cross the host.
    // Collective.
    void rebuild_in_place();
    // The attributes of these particles, from the whole system's spec.
    SlotAttributes attributes_of(const std::vector<int64_t>& ids) const;
    // The links of this rank's slab (SlabGeometry::links), their counts zero.
    std::vector<Link> no_links() const;
    // A domain ready to be adopted: its slots, ghosts and engine.
    struct Domain {
        DomainLayout layout;
        std::vector<Link> links;
        std::unique_ptr<LocalEngine> engine;
    };
    // Picks the ghosts of `owned` and loads the domain's engine, leaving the present one untouched
    // (collective: the ghosts are exchanged).
    Domain build(std::vector<Migrant> owned) const;
    // Makes `next` this rank's domain. Called by every rank once all have built theirs, so that a
    // build that fails on one rank leaves every rank with the domains it had.
    void adopt(Domain next);
    SlabGeometry geometry() const;
    // Each slot's global id (owned slots first); after a rebuild in place, from the engine.
    const std::vector<int64_t>& slot_ids();
    // Per-particle values of the owned slots (k each, from `local` over all the engine's slots) of
    // every rank, into `all` in id order.
    void gather_owned(const std::vector<double>& local, int k, double* all);
    double sum_owned(const std::vector<double>& values) const;
    Simulation& inner() const override { return *local_; }
    std::string refusal(Operation op, PerParticle quantity) const override;
    std::string refusal_reason() const override { return "under domain decomposition"; }
    // Throws ERR_STATE after a step or a rebuild in place that failed part way.
    void usable() const;

    EngineOptions options_;
    DomainSpec spec_;
    const ForceFieldComponents* components_;
    Logger log_;
    std::unique_ptr<LocalEngine> local_;
    std::vector<std::unique_ptr<SimulationStep>> steps_;
    std::vector<SimulationStep*> dueSteps_;
    std::string stoppedBy_;

    int64_t total_ = 0;
    int64_t massive_ = 0;
    std::vector<double> masses_, radii_;
    std::vector<int32_t> types_;
    std::vector<std::string> typeNames_;
    std::array<double, 3> box_{};
    int axis_ = 0;
    double width_ = 0.0;      // of the ghost layer
    double moveLimit_ = 0.0;  // the largest move since a rebuild that keeps every pair force whole

    std::vector<int64_t> ids_;  // global id by slot (owned, then ghosts), while idsKnown_
    bool idsKnown_ = false;
    int64_t owned_ = 0;
    std::vector<Link> links_;
    int64_t startStep_ = 0;  // the step and time of the document, for the first engine
    double startTime_ = 0.0;
    int64_t finalStep_ = 0;  // where the whole system's schedule ends
    bool begun_ = false;  // the integrator began on an engine of this domain
    bool inPlace_ = false;  // rebuilds renumber the engine's slots (DomainSpec::renumbers_in_place)
    bool broken_ = false;   // a step or a rebuild in place failed part way: the ranks disagree
    int64_t rebuilds_ = 0;  // since load, logged at the end: how often the ghost layer ran out
    Counters retired_;      // of the engines this domain had before the present one
    // Whether the ghosts go from GPU to GPU (NCCL), and its channel, made at the first refresh.
    bool onDevice_ = false;
#ifdef STRUCTMD_HAVE_NCCL
    std::unique_ptr<NcclChannel> channel_;
#endif
    double rebuildSeconds_ = 0.0, exchangeSeconds_ = 0.0;  // wall time, logged at the end
    // A rebuild in place's wall time by phase: sorting the owned slots, migrating, naming the
    // ghosts (the border slots and the ids exchanged), renumbering the slots.
    std::array<double, 4> rebuildPhases_{};
};

}  // namespace structmd
