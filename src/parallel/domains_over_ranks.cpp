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

constexpr int kHeldValues = 10;  // id, position, velocity, image
constexpr int kGhostValues = 7;  // id, position, velocity

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

// The fractional coordinate of x in a periodic box of length L, in [0, 1).
double fraction(double x, double length) {
    const double f = x / length - std::floor(x / length);
    return f < 1.0 ? f : 0.0;
}

}  // namespace

DomainsOverRanks::DomainsOverRanks(const EngineOptions& options, DomainSpec spec, std::unique_ptr<Simulation> whole,
                                   const ForceFieldComponents& components, const Logger& log,
                                   std::shared_ptr<const Communicator> comm)
    : StepsOnRankZero(std::move(comm)),
      options_(options),
      spec_(std::move(spec)),
      components_(&components),
      log_(log) {
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

    std::vector<Held> owned;
    for (int64_t i = 0; i < total_; ++i) {
        if (slab_of(x[3 * i + axis_]) != comm_->rank()) continue;
        Held h;
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
              std::to_string(ids_.size() - owned_) + " ghosts (ghost width " + number(width_) + ")");
}

DomainsOverRanks::~DomainsOverRanks() {
    if (comm_->rank() == 0)
        log_.info("spatial domains rebuilt " + std::to_string(rebuilds_) + " times (ghost width " + number(width_) +
                  ", rebuilt past a move of " + number(0.5 * moveLimit_) + "); rank 0 spent " +
                  number(rebuildSeconds_) + " s rebuilding and " + number(exchangeSeconds_) +
                  " s in the ghosts' MPI exchange");
}

void DomainsOverRanks::set_step_firing(StepFiring*) {
    throw Error(STRUCTMD_ERR_INTERNAL, "the steps of spatial domains are fired by the view itself");
}

void DomainsOverRanks::unsupported(const std::string& what) const {
    throw Error(STRUCTMD_ERR_UNSUPPORTED, what + " is not available under domain decomposition");
}

int DomainsOverRanks::slab_of(double x) const {
    const int ranks = comm_->size();
    return std::min(ranks - 1, static_cast<int>(fraction(x, box_[axis_]) * ranks));
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
        run_together(*comm_, [&] { local_->advance(1); });
        broken_ = false;
        begun_ = true;
        check_moves();
    }
    if (current_step() == last) fire_due(true);
}

std::vector<DomainsOverRanks::Held> DomainsOverRanks::owned_now() {
    const size_t slots = ids_.size();
    std::vector<double> x(3 * slots), v(3 * slots);
    std::vector<int32_t> images(3 * slots);
    run_together(*comm_, [&] {
        local_->get_positions(x.data());
        local_->get_velocities(v.data());
        local_->get_images(images.data());
    });
    std::vector<int64_t> owned(static_cast<size_t>(owned_));
    for (int64_t s = 0; s < owned_; ++s) owned[static_cast<size_t>(s)] = s;
    return held_at(owned, x, v, images);
}

std::vector<DomainsOverRanks::Held> DomainsOverRanks::held_at(const std::vector<int64_t>& slots,
                                                              const std::vector<double>& x,
                                                              const std::vector<double>& v,
                                                              const std::vector<int32_t>& images) const {
    std::vector<Held> held;
    held.reserve(slots.size());
    for (int64_t slot : slots) {
        const auto s = static_cast<size_t>(slot);
        Held h;
        h.id = ids_[s];
        for (int d = 0; d < 3; ++d) {
            h.position[d] = x[3 * s + d];
            h.velocity[d] = v[3 * s + d];
            h.image[d] = baseImages_[s][d] + images[3 * s + d];
        }
        held.push_back(h);
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

void DomainsOverRanks::check_moves() {
    if (std::isinf(moveLimit_)) return;
    double largest = 0.0;
    run_together(*comm_, [&] { largest = local_->largest_owned_move(); });
    std::vector<double> all(static_cast<size_t>(comm_->size()));
    comm_->all_gather(&largest, all.data(), std::vector<int64_t>(all.size(), 1));
    const double move = *std::max_element(all.begin(), all.end());
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
        std::vector<Held> held = owned_now();
        Domain next;
        run_together(*comm_, [&] { next = build(migrate(std::move(held))); });
        adopt(std::move(next));
    }
    ++rebuilds_;
    rebuildSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<DomainsOverRanks::Held> DomainsOverRanks::migrate(std::vector<Held> held) {
    const int me = comm_->rank(), ranks = comm_->size();
    const int right = (me + 1) % ranks, left = (me + ranks - 1) % ranks;
    std::vector<Held> kept;
    std::vector<double> toRight, toLeft;
    // Every rank learns of a particle that went too far before any waits on the shifts below.
    int64_t strayed = -1;
    for (const Held& h : held) {
        const int owner = slab_of(h.position[axis_]);
        if (owner != me && owner != right && owner != left) strayed = std::max(strayed, h.id);
    }
    strayed = comm_->all_max(strayed);
    if (strayed >= 0)
        throw Error(STRUCTMD_ERR_NUMERICAL, "particle id " + std::to_string(strayed) + " crossed more than one domain "
                                            "between two rebuilds of the spatial domains");
    for (const Held& h : held) {
        const int owner = slab_of(h.position[axis_]);
        if (owner == me) {
            kept.push_back(h);
            continue;
        }
        std::vector<double>& out = owner == right ? toRight : toLeft;
        out.push_back(static_cast<double>(h.id));
        out.insert(out.end(), h.position.begin(), h.position.end());
        out.insert(out.end(), h.velocity.begin(), h.velocity.end());
        for (int d = 0; d < 3; ++d) out.push_back(h.image[d]);
    }
    // Two shifts along the ring: to the right (from the left), then to the left (from the right).
    for (const auto& [out, to, from] : {std::tuple<const std::vector<double>&, int, int>{toRight, right, left},
                                        std::tuple<const std::vector<double>&, int, int>{toLeft, left, right}}) {
        const std::vector<double> in = shift_values(out, to, from);
        for (size_t k = 0; k < in.size(); k += kHeldValues) {
            Held h;
            h.id = static_cast<int64_t>(in[k]);
            for (int d = 0; d < 3; ++d) {
                h.position[d] = in[k + 1 + d];
                h.velocity[d] = in[k + 4 + d];
                h.image[d] = static_cast<int32_t>(in[k + 7 + d]);
            }
            kept.push_back(h);
        }
    }
    return kept;
}

DomainsOverRanks::Domain DomainsOverRanks::build(std::vector<Held> owned) const {
    std::sort(owned.begin(), owned.end(), [](const Held& a, const Held& b) { return a.id < b.id; });
    Domain d;
    d.owned = static_cast<int64_t>(owned.size());
    std::vector<double> positions, velocities;
    for (const Held& h : owned) {
        d.ids.push_back(h.id);
        positions.insert(positions.end(), h.position.begin(), h.position.end());
        velocities.insert(velocities.end(), h.velocity.begin(), h.velocity.end());
        d.baseImages.push_back(h.image);
    }

    choose_borders(d.links, d.owned, [&](int64_t s) { return owned[static_cast<size_t>(s)].position[axis_]; });
    for (Link& link : d.links) {
        std::vector<double> out;
        for (int64_t s : link.sent) {
            const Held& h = owned[static_cast<size_t>(s)];
            out.push_back(static_cast<double>(h.id));
            out.insert(out.end(), h.position.begin(), h.position.end());
            out.insert(out.end(), h.velocity.begin(), h.velocity.end());
        }
        const std::vector<double> in = shift_values(out, link.to, link.from);
        link.received = static_cast<int64_t>(in.size()) / kGhostValues;
        for (size_t k = 0; k < in.size(); k += kGhostValues) {
            d.ghostSlots.push_back(static_cast<int64_t>(d.ids.size()));
            d.ids.push_back(static_cast<int64_t>(in[k]));
            positions.insert(positions.end(), in.begin() + k + 1, in.begin() + k + 4);
            velocities.insert(velocities.end(), in.begin() + k + 4, in.begin() + k + 7);
        }
        d.borderSlots.insert(d.borderSlots.end(), link.sent.begin(), link.sent.end());
    }

    // Every bond of an owned particle must reach a particle the domain holds.
    std::vector<int64_t> held(d.ids);
    std::sort(held.begin(), held.end());
    for (int64_t s = 0; s < d.owned; ++s)
        for (int64_t j : spec_.bonded_to(d.ids[static_cast<size_t>(s)]))
            if (!std::binary_search(held.begin(), held.end(), j))
                throw Error(STRUCTMD_ERR_NUMERICAL,
                            "step " + std::to_string(local_ ? local_->current_step() : 0) + ": the bond between ids " +
                                std::to_string(d.ids[static_cast<size_t>(s)]) + " and " + std::to_string(j) +
                                " reaches beyond the ghost layer of the spatial domains (" + number(width_) + ")");

    const int64_t step = local_ ? local_->current_step() : startStep_;
    const double time = local_ ? local_->current_time() : startTime_;
    d.engine = make_simulation(
        options_, spec_.local(d.ids, d.owned, positions, velocities, step, time, std::max<int64_t>(0, finalStep_ - step)),
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
    c.domainRebuilds = static_cast<uint64_t>(rebuilds_);
    return c;
}

template <class Along>
void DomainsOverRanks::choose_borders(std::vector<Link>& links, int64_t owned, Along&& along) const {
    const int me = comm_->rank(), ranks = comm_->size();
    const int right = (me + 1) % ranks, left = (me + ranks - 1) % ranks;
    const double length = box_[axis_];
    const double lower = length * me / ranks, upper = length * (me + 1) / ranks;
    // The owned particles within the ghost width of each face go to the rank beyond it; with two
    // ranks both faces face the same rank, which gets each particle once.
    links.clear();
    if (ranks == 2) {
        links.push_back({right, right, {}, 0});
    } else {
        links.push_back({right, left, {}, 0});
        links.push_back({left, right, {}, 0});
    }
    for (int64_t s = 0; s < owned; ++s) {
        const double x = fraction(along(s), length) * length;
        const bool nearUpper = upper - x < width_, nearLower = x - lower < width_;
        if (ranks == 2) {
            if (nearUpper || nearLower) links[0].sent.push_back(s);
        } else {
            if (nearUpper) links[0].sent.push_back(s);
            if (nearLower) links[1].sent.push_back(s);
        }
    }
}

void DomainsOverRanks::rebuild_in_place() {
    const int me = comm_->rank();
    const size_t slots = ids_.size();
    std::vector<double> x(3 * slots), v;
    std::vector<int32_t> images;
    std::vector<int64_t> kept, leaving;
    run_together(*comm_, [&] {
        local_->get_positions(x.data());
        for (int64_t s = 0; s < owned_; ++s)
            (slab_of(x[static_cast<size_t>(3 * s + axis_)]) == me ? kept : leaving).push_back(s);
        if (leaving.empty()) return;
        v.resize(3 * slots);
        images.resize(3 * slots);
        local_->get_velocities(v.data());
        local_->get_images(images.data());
    });
    std::vector<Held> out = held_at(leaving, x, v, images);
    const std::vector<Held> arrived = migrate(std::move(out));

    // The new slots: those that stay (their images stay in the engine), the arrivals, the ghosts.
    std::vector<int64_t> ids;
    std::vector<std::array<int32_t, 3>> baseImages;
    ids.reserve(kept.size() + arrived.size());
    baseImages.reserve(ids.capacity());
    for (int64_t s : kept) {
        ids.push_back(ids_[static_cast<size_t>(s)]);
        baseImages.push_back(baseImages_[static_cast<size_t>(s)]);
    }
    for (const Held& h : arrived) {
        ids.push_back(h.id);
        baseImages.push_back(h.image);
    }
    const auto owned = static_cast<int64_t>(ids.size());
    const auto stay = static_cast<int64_t>(kept.size());
    std::vector<Link> links;
    choose_borders(links, owned, [&](int64_t s) {
        return s < stay ? x[static_cast<size_t>(3 * kept[static_cast<size_t>(s)] + axis_)]
                        : arrived[static_cast<size_t>(s - stay)].position[axis_];
    });
    // The neighbours learn which ids their ghosts are; the positions follow at the next refresh.
    std::vector<int64_t> borderSlots, ghostSlots;
    for (Link& link : links) {
        std::vector<double> sent;
        for (int64_t s : link.sent) sent.push_back(static_cast<double>(ids[static_cast<size_t>(s)]));
        const std::vector<double> received = shift_values(sent, link.to, link.from);
        link.received = static_cast<int64_t>(received.size());
        for (double id : received) {
            ghostSlots.push_back(static_cast<int64_t>(ids.size()));
            ids.push_back(static_cast<int64_t>(id));
        }
        borderSlots.insert(borderSlots.end(), link.sent.begin(), link.sent.end());
    }

    SlotReseat plan;
    plan.kept = std::move(kept);
    const size_t added = ids.size() - static_cast<size_t>(stay);
    plan.addedPositions.assign(3 * added, 0.0);
    plan.addedVelocities.assign(3 * added, 0.0);
    for (size_t k = 0; k < arrived.size(); ++k)
        for (int d = 0; d < 3; ++d) {
            plan.addedPositions[3 * k + d] = arrived[k].position[d];
            plan.addedVelocities[3 * k + d] = arrived[k].velocity[d];
        }
    const SystemSpec& whole = spec_.whole();
    for (size_t slot = static_cast<size_t>(stay); slot < ids.size(); ++slot) {
        const auto i = static_cast<size_t>(ids[slot]);
        plan.typeIndex.push_back(types_[i]);
        plan.mass.push_back(masses_[i]);
        plan.radius.push_back(radii_[i]);
        plan.charge.push_back(whole.charge.empty() ? 0.0 : whole.charge[i]);
        plan.model.push_back(whole.modelId.empty() ? 0 : whole.modelId[i]);
    }
    plan.globalIds = ids;
    plan.forceField = &whole.forceField;
    plan.integrators = &whole.integrators;
    plan.components = components_;

    ids_ = std::move(ids);
    owned_ = owned;
    baseImages_ = std::move(baseImages);
    links_ = std::move(links);
    borderSlots_ = std::move(borderSlots);
    ghostSlots_ = std::move(ghostSlots);
    // A failure here (device memory) may leave the engine half renumbered: every rank reports it,
    // and the domains refuse to go on (usable()).
    broken_ = true;
    run_together(*comm_, [&] { local_->reseat(plan); });
    broken_ = false;
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
    ids_ = std::move(next.ids);
    owned_ = next.owned;
    baseImages_ = std::move(next.baseImages);
    links_ = std::move(next.links);
    borderSlots_ = std::move(next.borderSlots);
    ghostSlots_ = std::move(next.ghostSlots);
    local_ = std::move(next.engine);
    local_->hold_ghosts(ids_, this, begun_);
}

void DomainsOverRanks::exchange(const double* border, double* ghosts) {
    const auto start = std::chrono::steady_clock::now();
    const double* out = border;
    double* in = ghosts;
    for (const Link& link : links_) {
        const auto sent = static_cast<int64_t>(link.sent.size());
        comm_->shift(out, 6 * sent, link.to, in, 6 * link.received, link.from);
        out += 6 * sent;
        in += 6 * link.received;
    }
    exchangeSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- gathers and sums ----

void DomainsOverRanks::gather_owned(const std::vector<double>& local, int k, double* all) {
    const int ranks = comm_->size();
    std::vector<double> counts(static_cast<size_t>(ranks));
    const double mine = static_cast<double>(owned_);
    comm_->all_gather(&mine, counts.data(), std::vector<int64_t>(static_cast<size_t>(ranks), 1));
    std::vector<int64_t> idCounts(static_cast<size_t>(ranks)), valueCounts(static_cast<size_t>(ranks));
    int64_t held = 0;
    for (int r = 0; r < ranks; ++r) {
        idCounts[static_cast<size_t>(r)] = static_cast<int64_t>(counts[static_cast<size_t>(r)]);
        valueCounts[static_cast<size_t>(r)] = k * idCounts[static_cast<size_t>(r)];
        held += idCounts[static_cast<size_t>(r)];
    }
    if (held != total_)
        throw Error(STRUCTMD_ERR_INTERNAL, "the spatial domains hold " + std::to_string(held) + " particles, not " +
                                               std::to_string(total_));
    std::vector<double> myIds(ids_.begin(), ids_.begin() + owned_), allIds(static_cast<size_t>(held));
    comm_->all_gather(myIds.data(), allIds.data(), idCounts);
    std::vector<double> values(static_cast<size_t>(k * held));
    comm_->all_gather(local.data(), values.data(), valueCounts);
    std::vector<char> seen(static_cast<size_t>(total_), 0);
    for (int64_t p = 0; p < held; ++p) {
        const auto id = static_cast<int64_t>(allIds[static_cast<size_t>(p)]);
        if (id < 0 || id >= total_ || seen[static_cast<size_t>(id)])
            throw Error(STRUCTMD_ERR_INTERNAL, "particle id " + std::to_string(id) + " is held by two spatial domains");
        seen[static_cast<size_t>(id)] = 1;
        std::copy(values.begin() + k * p, values.begin() + k * (p + 1), all + k * id);
    }
}

template <class Get>
void DomainsOverRanks::gather_per_particle(Op op, double* all, int k, Get&& get) {
    usable();
    announce(op);
    std::vector<double> local(static_cast<size_t>(k) * ids_.size());
    run_together(*comm_, [&] { get(local.data()); });
    local.resize(static_cast<size_t>(k * owned_));
    gather_owned(local, k, all);
}

double DomainsOverRanks::sum_owned(const std::vector<double>& values) const {
    double sum = 0.0;
    for (int64_t s = 0; s < owned_; ++s) sum += values[static_cast<size_t>(s)];
    return sum;
}

void DomainsOverRanks::compute(unsigned flags) {
    usable();
    announce(Op::compute, std::string(), flags);
    run_together(*comm_, [&] { local_->compute(flags); });
}

void DomainsOverRanks::get_positions(double* xyz) {
    gather_per_particle(Op::positions, xyz, 3, [&](double* mine) { local_->get_positions(mine); });
}
void DomainsOverRanks::get_velocities(double* v) {
    gather_per_particle(Op::velocities, v, 3, [&](double* mine) { local_->get_velocities(mine); });
}
void DomainsOverRanks::get_forces(double* f) {
    gather_per_particle(Op::forces, f, 3, [&](double* mine) { local_->get_forces(mine); });
}
// Identity for all: the domains hold no directions and turn no particle (domain_support.hpp).
void DomainsOverRanks::get_orientations(double* q) {
    gather_per_particle(Op::orientations, q, 4, [&](double* mine) { local_->get_orientations(mine); });
}
void DomainsOverRanks::get_particle_energies(double* e) {
    gather_per_particle(Op::particleEnergies, e, 1, [&](double* mine) { local_->get_particle_energies(mine); });
}

void DomainsOverRanks::get_images(int32_t* images) {
    std::vector<double> all(static_cast<size_t>(3 * total_));
    gather_per_particle(Op::images, all.data(), 3, [&](double* mine) {
        std::vector<int32_t> local(3 * ids_.size());
        local_->get_images(local.data());
        for (int64_t s = 0; s < owned_; ++s)
            for (int d = 0; d < 3; ++d) mine[3 * s + d] = baseImages_[static_cast<size_t>(s)][d] + local[3 * s + d];
    });
    for (size_t k = 0; k < all.size(); ++k) images[k] = static_cast<int32_t>(all[k]);
}

void DomainsOverRanks::get_unwrapped_positions(double* xyz) {
    get_positions(xyz);
    std::vector<int32_t> images(static_cast<size_t>(3 * total_));
    get_images(images.data());
    for (int64_t k = 0; k < 3 * total_; ++k) xyz[k] += images[static_cast<size_t>(k)] * box_[k % 3];
}

void DomainsOverRanks::get_masses(double* m) { std::copy(masses_.begin(), masses_.end(), m); }
void DomainsOverRanks::get_types(int32_t* types) { std::copy(types_.begin(), types_.end(), types); }
void DomainsOverRanks::get_radii(double* r) { std::copy(radii_.begin(), radii_.end(), r); }

double DomainsOverRanks::energy(const std::string& term) {
    usable();
    announce(Op::energy, term);
    double value = 0.0;
    run_together(*comm_, [&] {
        const size_t slots = ids_.size();
        const bool kinetic = term == "kinetic" || term == "total";
        const bool potential = term == "potential" || term == "total";
        if (kinetic) {
            std::vector<double> v(3 * slots);
            local_->get_velocities(v.data());
            for (int64_t s = 0; s < owned_; ++s) {
                const double* u = &v[static_cast<size_t>(3 * s)];
                value += 0.5 * masses_[static_cast<size_t>(ids_[static_cast<size_t>(s)])] * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            }
        }
        if (potential) {
            std::vector<double> e(slots);
            local_->get_particle_energies(e.data());
            value += sum_owned(e);
        }
        if (kinetic || potential) return;
        const std::vector<std::string> names = local_->energy_terms();
        if (std::find(names.begin(), names.end(), term) == names.end())
            unsupported("the energy '" + term + "' (only kinetic, potential, total and the forceField entries')");
        std::vector<double> e(slots), f(3 * slots), t(3 * slots);
        local_->term_energies_and_forces(term, e.data(), f.data(), t.data());
        value = sum_owned(e);
    });
    comm_->all_sum(&value, 1);
    return value;
}

void DomainsOverRanks::term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                                double* torques) {
    usable();
    announce(Op::termArrays, term);
    const size_t slots = ids_.size();
    std::vector<double> e(slots), f(3 * slots), t(3 * slots);
    run_together(*comm_, [&] { local_->term_energies_and_forces(term, e.data(), f.data(), t.data()); });
    e.resize(static_cast<size_t>(owned_));
    f.resize(static_cast<size_t>(3 * owned_));
    t.resize(static_cast<size_t>(3 * owned_));
    gather_owned(e, 1, energies);
    gather_owned(f, 3, forces);
    gather_owned(t, 3, torques);
}

// ---- what domain decomposition does not do yet ----

void DomainsOverRanks::set_orientations(const double*) { unsupported("setting orientations"); }
void DomainsOverRanks::get_torques(double*) { unsupported("torques"); }
void DomainsOverRanks::get_magnetic_moments(double*) { unsupported("magnetic moments"); }
std::array<double, 9> DomainsOverRanks::virial() { unsupported("the virial (and the pressure)"); }
void DomainsOverRanks::get_pair_virials(double*) { unsupported("the virial of pairs"); }
void DomainsOverRanks::hessian_column(int64_t, double*) { unsupported("the Hessian (HessianMeasure)"); }
void DomainsOverRanks::pair_forces_on(int64_t, double*) { unsupported("forces between pairs"); }
void DomainsOverRanks::forces_with_displaced(int64_t, const double*, double*) {
    unsupported("forces with a particle displaced");
}
void DomainsOverRanks::set_positions(const double*) { unsupported("setting positions"); }
void DomainsOverRanks::set_velocities(const double*) { unsupported("setting velocities"); }
void DomainsOverRanks::set_box(const double*) { unsupported("changing the box"); }
void DomainsOverRanks::set_external_forces(const double*) { unsupported("external forces from the host"); }
void DomainsOverRanks::set_lambda(double) { unsupported("changing lambda"); }
double DomainsOverRanks::lambda_derivative() { unsupported("the derivative in lambda"); }
void DomainsOverRanks::get_positions_of(const int64_t*, int64_t, double*) { unsupported("positions of a subset"); }
void DomainsOverRanks::get_velocities_of(const int64_t*, int64_t, double*) { unsupported("velocities of a subset"); }
void DomainsOverRanks::get_forces_of(const int64_t*, int64_t, double*) { unsupported("forces of a subset"); }
void DomainsOverRanks::set_positions_of(const int64_t*, int64_t, const double*) {
    unsupported("setting positions of a subset");
}
void DomainsOverRanks::set_velocities_of(const int64_t*, int64_t, const double*) {
    unsupported("setting velocities of a subset");
}
void DomainsOverRanks::set_external_forces_of(const int64_t*, int64_t, const double*) {
    unsupported("external forces from the host");
}
void DomainsOverRanks::set_external_energy(double) { unsupported("an external energy from the host"); }
void DomainsOverRanks::set_force_callback(HostForceCallback) { unsupported("a force callback"); }
void DomainsOverRanks::set_device_force_callback(DeviceForceCallback) { unsupported("a device force callback"); }
Simulation::ArrayView DomainsOverRanks::view(const std::string&) { unsupported("a view of the backend's arrays"); }
void DomainsOverRanks::change_parameters(const RuntimeSpec&, const ForceFieldComponents&) {
    unsupported("changing a parameter");
}
void DomainsOverRanks::save_checkpoint(const std::string&) { unsupported("a checkpoint"); }
void DomainsOverRanks::load_checkpoint(const std::string&) { unsupported("a checkpoint"); }

}  // namespace structmd
