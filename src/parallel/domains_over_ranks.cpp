#include "parallel/domains_over_ranks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "core/error.hpp"
#include "engines/make_engine.hpp"

namespace structmd {

namespace {

constexpr int kMigrantValues = 13;  // id, position, velocity, force, image
constexpr int kGhostValues = 7;  // id, position, velocity (a new engine's ghosts)

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

}  // namespace

DomainsOverRanks::DomainsOverRanks(const EngineOptions& options, DomainSpec spec, std::unique_ptr<LocalEngine> whole,
                                   const ForceFieldComponents& components, const Logger& log,
                                   std::shared_ptr<const Communicator> comm)
    : StepsOnRankZero(std::move(comm)),
      options_(options),
      spec_(std::move(spec)),
      components_(&components),
      log_(log) {
    onDevice_ = options.ghostExchange == EngineOptions::GhostExchange::nccl ||
                (options.ghostExchange == EngineOptions::GhostExchange::automatic && nccl_compiled() &&
                 options.backend == BackendKind::cuda);
    total_ = whole->particle_count();
    massive_ = whole->massive_count();
    const auto n = static_cast<size_t>(total_);
    masses_.resize(n);
    radii_.resize(n);
    types_.resize(n);
    whole->get_masses(masses_.data());
    whole->get_radii(radii_.data());
    whole->get_types(types_.data());
    typeNames_ = whole->type_names();
    startStep_ = whole->current_step();
    startTime_ = whole->current_time();
    finalStep_ = whole->final_step();
    box_ = whole->box();
    axis_ = static_cast<int>(std::max_element(box_.begin(), box_.end()) - box_.begin());

    std::vector<double> x(3 * n), v(3 * n);
    std::vector<int32_t> images(3 * n);
    whole->get_positions(x.data());
    whole->get_velocities(v.data());
    whole->get_images(images.data());
    // The ghost width: the neighbour lists' reach and their skin again, so that the domains are
    // rebuilt about as often as the lists (past half the skin), and room for every bond with half
    // as much again.
    double longestBond = 0.0;
    for (int64_t i = 0; i < total_; ++i)
        for (int64_t j : spec_.bonded_to(i)) {
            double r2 = 0.0;
            for (int d = 0; d < 3; ++d) {
                double dx = x[3 * i + d] - x[3 * j + d];
                dx -= box_[d] * std::round(dx / box_[d]);
                r2 += dx * dx;
            }
            longestBond = std::max(longestBond, std::sqrt(r2));
        }
    const double listRadius = whole->list_radius();
    const double cutoff = whole->pair_cutoff();
    width_ = std::max(listRadius > 0.0 ? 2.0 * listRadius - cutoff : 0.0, 1.5 * longestBond);
    // Without pairs or bonds nothing reaches across a face: no ghosts, and no move calls for a rebuild.
    moveLimit_ = width_ > 0.0 ? 0.5 * (width_ - (listRadius > 0.0 ? cutoff : 0.0))
                              : std::numeric_limits<double>::infinity();
    const double slab = box_[axis_] / comm_->size();
    if (slab < width_)
        throw Error(STRUCTMD_ERR_UNSUPPORTED,
                    "slabs of " + number(slab) + " along the box's longest axis, thinner than the ghost width " +
                        number(width_) + " (neighbour lists' reach, or 1.5 x the longest bond), are not available "
                        "under domain decomposition: use fewer MPI ranks");
    whole->take_steps(steps_);
    inPlace_ = spec_.renumbers_in_place();

    std::vector<Migrant> owned;
    const SlabGeometry slabs = geometry();
    for (int64_t i = 0; i < total_; ++i) {
        if (slabs.slab_of(x[3 * i + axis_]) != comm_->rank()) continue;
        Migrant h;
        h.id = i;
        for (int d = 0; d < 3; ++d) {
            h.position[d] = x[3 * i + d];
            h.velocity[d] = v[3 * i + d];
            h.image[d] = images[3 * i + d];
        }
        owned.push_back(h);
    }
    whole.reset();
    Domain first;
    run_together(*comm_, [&] { first = build(std::move(owned)); });
    adopt(std::move(first));
    log_.info("MPI rank " + std::to_string(comm_->rank()) + " of " + std::to_string(comm_->size()) +
              ": spatial domain along axis " + std::to_string(axis_) + ", " + std::to_string(owned_) + " particles and " +
              std::to_string(local_->particle_count() - owned_) + " ghosts (ghost width " + number(width_) +
              "; ghosts exchanged " + (onDevice_ ? "from GPU to GPU through NCCL)" : "through the host's memory by MPI)"));
}

DomainsOverRanks::~DomainsOverRanks() {
    if (comm_->rank() == 0)
        log_.info("spatial domains rebuilt " + std::to_string(rebuilds_) + " times (ghost width " + number(width_) +
                  ", rebuilt past a move of " + number(0.5 * moveLimit_) + "); rank 0 spent " +
                  number(rebuildSeconds_) + " s rebuilding (in place: " + number(rebuildPhases_[0]) +
                  " s sorting the owned slots, " + number(rebuildPhases_[1]) + " s migrating, " +
                  number(rebuildPhases_[2]) + " s naming the ghosts, " + number(rebuildPhases_[3]) +
                  " s renumbering) and " + number(exchangeSeconds_) + " s exchanging the ghosts" +
                  (onDevice_ ? " (queueing NCCL's transfers, which run on the GPU's stream)" : ""));
}

SlabGeometry DomainsOverRanks::geometry() const {
    SlabGeometry g;
    g.axis = axis_;
    g.length = box_[axis_];
    g.ranks = comm_->size();
    g.rank = comm_->rank();
    g.width = width_;
    return g;
}

std::vector<DomainsOverRanks::Link> DomainsOverRanks::no_links() const {
    const int me = comm_->rank(), ranks = comm_->size();
    const int up = (me + 1) % ranks, down = (me + ranks - 1) % ranks;
    // Link 0 sends across the upper face, link 1 across the lower; with two ranks both faces
    // face the same rank, which gets each particle once (SlabGeometry::borders).
    if (ranks == 2) return {Link{up, up, 0, 0}};
    return {Link{up, down, 0, 0}, Link{down, up, 0, 0}};
}

const std::vector<int64_t>& DomainsOverRanks::slot_ids() {
    if (!idsKnown_) {
        ids_ = local_->global_ids();
        idsKnown_ = true;
    }
    return ids_;
}

// ---- the step loop: the engine's, with the domains checked after every step ----

void DomainsOverRanks::fire_due(bool final) {
    dueSteps_.clear();
    for (auto& s : steps_)
        if (final ? s->in_window(current_step()) : s->due(current_step())) dueSteps_.push_back(s.get());
    if (!dueSteps_.empty()) fire(dueSteps_);
}

void DomainsOverRanks::advance(int64_t n) {
    if (n < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "nsteps: expected a count >= 0, got " + std::to_string(n));
    if (n == 0) return;
    usable();
    const int64_t last = final_step();
    stoppedBy_.clear();
    for (int64_t k = 0; k < n; ++k) {
        fire_due(current_step() == last);
        if (!stoppedBy_.empty()) return;
        // A rank whose step fails (a blow-up) rolls its engine back by that step and the others
        // do not: the ranks would no longer agree on the step, so the domains go no further.
        broken_ = true;
        // One collective a step: the failures and the largest move since the last rebuild together.
        const double move = run_together_max(*comm_, [&] {
            local_->advance(1);
            return std::isinf(moveLimit_) ? 0.0 : local_->largest_owned_move();
        });
        broken_ = false;
        begun_ = true;
        check_moves(move);
    }
    fire_due(current_step() == last);  // what is due at the step the call ends on, as the engine does
}

std::vector<Migrant> DomainsOverRanks::owned_now() {
    const auto slots = static_cast<size_t>(local_->particle_count());
    std::vector<double> x(3 * slots), v(3 * slots);
    std::vector<int32_t> images(3 * slots);
    run_together(*comm_, [&] {
        slot_ids();
        local_->get_positions(x.data());
        local_->get_velocities(v.data());
        local_->get_images(images.data());
    });
    std::vector<Migrant> held(static_cast<size_t>(owned_));
    for (size_t s = 0; s < held.size(); ++s) {
        held[s].id = ids_[s];
        for (int d = 0; d < 3; ++d) {
            held[s].position[d] = x[3 * s + d];
            held[s].velocity[d] = v[3 * s + d];
            held[s].image[d] = images[3 * s + d];
        }
    }
    return held;
}

std::vector<double> DomainsOverRanks::shift_values(const std::vector<double>& out, int to, int from) const {
    double count = static_cast<double>(out.size()), incoming = 0.0;
    comm_->shift(&count, 1, to, &incoming, 1, from);
    std::vector<double> in(static_cast<size_t>(incoming));
    comm_->shift(out.data(), static_cast<int64_t>(out.size()), to, in.data(), static_cast<int64_t>(in.size()), from);
    return in;
}

void DomainsOverRanks::check_moves(double move) {
    if (move > moveLimit_)
        throw Error(STRUCTMD_ERR_NUMERICAL,
                    "step " + std::to_string(current_step()) + ": a particle moved " + number(move) +
                        " since the spatial domains were last rebuilt, more than the ghost layer allows (" +
                        number(moveLimit_) + "): its pair forces may have missed a neighbour; reduce the time step");
    if (move <= 0.5 * moveLimit_) return;
    const auto start = std::chrono::steady_clock::now();
    if (inPlace_) {
        rebuild_in_place();
    } else {
        std::vector<Migrant> held = owned_now();
        Domain next;
        run_together(*comm_, [&] { next = build(migrate(std::move(held))); });
        adopt(std::move(next));
    }
    ++rebuilds_;
    rebuildSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<Migrant> DomainsOverRanks::migrate(std::vector<Migrant> held) {
    const SlabGeometry slabs = geometry();
    std::vector<Migrant> kept, up, down;
    int64_t astray = -1;
    for (const Migrant& h : held) switch (slabs.destination(h.position[axis_])) {
            case SlabGeometry::kStays: kept.push_back(h); break;
            case SlabGeometry::kUp: up.push_back(h); break;
            case SlabGeometry::kDown: down.push_back(h); break;
            default: astray = std::max(astray, h.id);
        }
    std::vector<Migrant> arrived = cross(up, down, astray);
    kept.insert(kept.end(), arrived.begin(), arrived.end());
    return kept;
}

std::vector<Migrant> DomainsOverRanks::cross(const std::vector<Migrant>& up, const std::vector<Migrant>& down,
                                             int64_t astray) const {
    // Every rank learns of a particle that went too far before any waits on the shifts below.
    astray = comm_->all_max(astray);
    if (astray >= 0)
        throw Error(STRUCTMD_ERR_NUMERICAL, "particle id " + std::to_string(astray) + " crossed more than one domain "
                                            "between two rebuilds of the spatial domains");
    const int me = comm_->rank(), ranks = comm_->size();
    const int above = (me + 1) % ranks, below = (me + ranks - 1) % ranks;
    std::vector<Migrant> arrived;
    // Two shifts along the ring: up (from below), then down (from above).
    for (const auto& [leaving, to, from] : {std::tuple<const std::vector<Migrant>&, int, int>{up, above, below},
                                            std::tuple<const std::vector<Migrant>&, int, int>{down, below, above}}) {
        std::vector<double> out;
        out.reserve(kMigrantValues * leaving.size());
        for (const Migrant& h : leaving) {
            out.push_back(static_cast<double>(h.id));
            out.insert(out.end(), h.position.begin(), h.position.end());
            out.insert(out.end(), h.velocity.begin(), h.velocity.end());
            out.insert(out.end(), h.force.begin(), h.force.end());
            for (int d = 0; d < 3; ++d) out.push_back(h.image[d]);
        }
        const std::vector<double> in = shift_values(out, to, from);
        for (size_t k = 0; k < in.size(); k += kMigrantValues) {
            Migrant h;
            h.id = static_cast<int64_t>(in[k]);
            for (int d = 0; d < 3; ++d) {
                h.position[d] = in[k + 1 + d];
                h.velocity[d] = in[k + 4 + d];
                h.force[d] = in[k + 7 + d];
                h.image[d] = static_cast<int32_t>(in[k + 10 + d]);
            }
            arrived.push_back(h);
        }
    }
    return arrived;
}

DomainsOverRanks::Domain DomainsOverRanks::build(std::vector<Migrant> owned) const {
    std::sort(owned.begin(), owned.end(), [](const Migrant& a, const Migrant& b) { return a.id < b.id; });
    Domain d;
    DomainLayout& layout = d.layout;
    layout.owned = static_cast<int64_t>(owned.size());
    std::vector<double> positions, velocities;
    for (const Migrant& h : owned) {
        layout.globalIds.push_back(h.id);
        positions.insert(positions.end(), h.position.begin(), h.position.end());
        velocities.insert(velocities.end(), h.velocity.begin(), h.velocity.end());
        layout.images.push_back(h.image);
    }

    const SlabGeometry slabs = geometry();
    d.links = no_links();
    for (size_t l = 0; l < d.links.size(); ++l) {
        Link& link = d.links[l];
        std::vector<double> out;
        for (size_t s = 0; s < owned.size(); ++s) {
            const Migrant& h = owned[s];
            if (!((slabs.borders(h.position[axis_]) >> l) & 1)) continue;
            layout.borderSlots.push_back(static_cast<int64_t>(s));
            ++link.sent;
            out.push_back(static_cast<double>(h.id));
            out.insert(out.end(), h.position.begin(), h.position.end());
            out.insert(out.end(), h.velocity.begin(), h.velocity.end());
        }
        const std::vector<double> in = shift_values(out, link.to, link.from);
        link.received = static_cast<int64_t>(in.size()) / kGhostValues;
        for (size_t k = 0; k < in.size(); k += kGhostValues) {
            layout.globalIds.push_back(static_cast<int64_t>(in[k]));
            positions.insert(positions.end(), in.begin() + k + 1, in.begin() + k + 4);
            velocities.insert(velocities.end(), in.begin() + k + 4, in.begin() + k + 7);
        }
    }

    // Every bond of an owned particle must reach a particle the domain holds.
    const std::vector<int64_t>& ids = layout.globalIds;
    std::vector<int64_t> held(ids);
    std::sort(held.begin(), held.end());
    for (int64_t s = 0; s < layout.owned; ++s)
        for (int64_t j : spec_.bonded_to(ids[static_cast<size_t>(s)]))
            if (!std::binary_search(held.begin(), held.end(), j))
                throw Error(STRUCTMD_ERR_NUMERICAL,
                            "step " + std::to_string(local_ ? local_->current_step() : 0) + ": the bond between ids " +
                                std::to_string(ids[static_cast<size_t>(s)]) + " and " + std::to_string(j) +
                                " reaches beyond the ghost layer of the spatial domains (" + number(width_) + ")");

    const int64_t step = local_ ? local_->current_step() : startStep_;
    const double time = local_ ? local_->current_time() : startTime_;
    // Cluster pairs are not yet checked against one rank with ghosts (mpi.domains): a domain's pair
    // terms walk per-particle lists.
    EngineOptions local = options_;
    local.pairTraversal = EngineOptions::PairTraversal::particles;
    d.engine = make_simulation(
        local, spec_.local(ids, layout.owned, positions, velocities, step, time, std::max<int64_t>(0, finalStep_ - step)),
        *components_, log_);
    return d;
}

Counters DomainsOverRanks::counters() {
    Counters c = local_->counters();
    c.forceEvaluations += retired_.forceEvaluations;
    c.energyEvaluations += retired_.energyEvaluations;
    c.virialEvaluations += retired_.virialEvaluations;
    c.neighbourListBuilds += retired_.neighbourListBuilds;
    c.hostToDeviceBytes += retired_.hostToDeviceBytes;
    c.deviceToHostBytes += retired_.deviceToHostBytes;
    c.stepGraphsCaptured += retired_.stepGraphsCaptured;
    c.stepGraphsReplayed += retired_.stepGraphsReplayed;
    c.stepsJoined += retired_.stepsJoined;
    c.domainRebuilds = static_cast<uint64_t>(rebuilds_);
    return c;
}

void DomainsOverRanks::rebuild_in_place() {
    auto lap = [this, start = std::chrono::steady_clock::now()](int phase) mutable {
        const auto now = std::chrono::steady_clock::now();
        rebuildPhases_[static_cast<size_t>(phase)] += std::chrono::duration<double>(now - start).count();
        start = now;
    };
    // Which owned particles stay, and those that leave, found where they live.
    SlabSort sorted;
    run_together(*comm_, [&] { sorted = local_->sort_owned(geometry()); });
    lap(0);
    const std::vector<Migrant> arrived = cross(sorted.up, sorted.down, sorted.astray);
    lap(1);
    std::vector<int64_t> arrivedIds(arrived.size());
    for (size_t k = 0; k < arrived.size(); ++k) arrivedIds[k] = arrived[k].id;
    std::vector<std::vector<int64_t>> borders;
    run_together(*comm_, [&] { borders = local_->place_owned(arrived, attributes_of(arrivedIds)); });
    // The neighbours learn which ids their ghosts are; the positions follow at the next refresh.
    std::vector<Link> links = no_links();
    std::vector<int64_t> ghostIds;
    for (size_t l = 0; l < links.size(); ++l) {
        const std::vector<int64_t>& sent = borders[l];
        const std::vector<double> received =
            shift_values(std::vector<double>(sent.begin(), sent.end()), links[l].to, links[l].from);
        links[l].sent = static_cast<int64_t>(sent.size());
        links[l].received = static_cast<int64_t>(received.size());
        for (double id : received) ghostIds.push_back(static_cast<int64_t>(id));
    }
    owned_ = sorted.stay + static_cast<int64_t>(arrived.size());
    links_ = std::move(links);
    lap(2);
    idsKnown_ = false;
    const SystemSpec& whole = spec_.whole();
    const DomainTerms terms{&whole.forceField, &whole.integrators, components_};
    // A failure here (device memory) may leave the engine half renumbered: every rank reports it,
    // and the domains refuse to go on (usable()).
    broken_ = true;
    run_together(*comm_, [&] { local_->place_ghosts(ghostIds, attributes_of(ghostIds), terms); });
    broken_ = false;
    lap(3);
}

SlotAttributes DomainsOverRanks::attributes_of(const std::vector<int64_t>& ids) const {
    const SystemSpec& whole = spec_.whole();
    SlotAttributes a;
    for (int64_t id : ids) {
        const auto i = static_cast<size_t>(id);
        a.typeIndex.push_back(types_[i]);
        a.mass.push_back(masses_[i]);
        a.radius.push_back(radii_[i]);
        a.charge.push_back(whole.charge.empty() ? 0.0 : whole.charge[i]);
        a.model.push_back(whole.modelId.empty() ? 0 : whole.modelId[i]);
    }
    return a;
}

void DomainsOverRanks::usable() const {
    if (broken_)
        throw Error(STRUCTMD_ERR_STATE, "a step or a rebuild of the spatial domains failed part way (see the error it "
                                        "returned), and the ranks no longer agree: load the input again");
}

void DomainsOverRanks::adopt(Domain next) {
    if (local_) {
        const Counters c = counters();
        retired_ = c;
        retired_.deviceMemoryBytes = 0;
    }
    ids_ = next.layout.globalIds;
    idsKnown_ = true;
    owned_ = next.layout.owned;
    links_ = std::move(next.links);
    local_ = std::move(next.engine);
    local_->hold_ghosts(next.layout, this, begun_);
}

void DomainsOverRanks::exchange(const void* border, void* ghosts, size_t bytes) {
    const auto start = std::chrono::steady_clock::now();
    const auto* out = static_cast<const unsigned char*>(border);
    auto* in = static_cast<unsigned char*>(ghosts);
    for (const Link& link : links_) {
        comm_->shift(out, link.sent * static_cast<int64_t>(bytes), link.to, in,
                     link.received * static_cast<int64_t>(bytes), link.from);
        out += link.sent * bytes;
        in += link.received * bytes;
    }
    exchangeSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void DomainsOverRanks::exchange_on_device(const void* border, void* ghosts, size_t bytes, void* stream) {
#ifdef STRUCTMD_HAVE_NCCL
    const auto start = std::chrono::steady_clock::now();
    // Every rank's engine refreshes its ghosts at the same point of the same step: the channel is
    // made collectively there, on the engine's GPU.
    if (!channel_) channel_ = std::make_unique<NcclChannel>(*comm_);
    std::vector<NcclChannel::Shift> shifts;
    const auto* out = static_cast<const unsigned char*>(border);
    auto* in = static_cast<unsigned char*>(ghosts);
    for (const Link& link : links_) {
        const size_t sent = static_cast<size_t>(link.sent) * bytes, received = static_cast<size_t>(link.received) * bytes;
        shifts.push_back({out, sent, link.to, in, received, link.from});
        out += sent;
        in += received;
    }
    channel_->shift(shifts, stream);
    exchangeSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
#else
    (void)border, (void)ghosts, (void)bytes, (void)stream;
    throw Error(STRUCTMD_ERR_INTERNAL, "ghosts exchanged between GPUs in a build without NCCL");
#endif
}

}  // namespace structmd
