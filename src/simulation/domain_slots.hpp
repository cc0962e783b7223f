#pragma once
// The slots of a spatial domain's engine (simulation/domain_exchange.hpp), kept where the
// particles live: the global id of every slot, the owned slots each link sends as ghosts, the owned
// positions at the last layout (the move check), and a rebuild's renumbering. A rebuild touches
// the host only for the particles that cross between ranks and the ghosts' ids and attributes: which
// owned slots stay, leave or border a face is decided on the backend (SlabGeometry, the view's
// own rule), and the slots are renumbered there, in buffers that keep their allocation while it
// has room (B::fit): a rebuild allocates nothing in the steady state, and the particles' arrays
// keep their addresses, so what holds them (the neighbour lists) stays valid.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/box.hpp"
#include "core/error.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "core/slab_geometry.hpp"
#include "simulation/domain_exchange.hpp"
#include "simulation/engine_functors.hpp"
#include "state/particles.hpp"

namespace structmd {

// Owned slot i goes `destination` (SlabGeometry::kStays ...).
template <class R>
struct BoundFor {
    const Real4<R>* pos;
    SlabGeometry geometry;
    int destination;
    SMD_HD bool operator()(int64_t i) const { return geometry.destination(geometry.along(pos[i])) == destination; }
};

// New owned slot k (old slot order[k] for k < stay, else arrival k - stay) borders the face `link`
// sends across.
template <class R>
struct BordersFace {
    const Real4<R>* pos;
    const int64_t* order;
    int64_t stay;
    const Real4<R>* arrived;
    SlabGeometry geometry;
    int link;
    SMD_HD bool operator()(int64_t k) const {
        const Real4<R> p = k < stay ? pos[order[k]] : arrived[k - stay];
        return (geometry.borders(geometry.along(p)) >> link) & 1;
    }
};

// Slot k of a renumbered array: old slot order[k] for k < stay, else added[k - stay].
template <class T>
struct Renumbered {
    const T* old;
    const int64_t* order;
    int64_t stay;
    const T* added;
    T* out;
    SMD_HD void operator()(int64_t k) const { out[k] = k < stay ? old[order[k]] : added[k - stay]; }
};

// Ghost k takes its owner's position, at slot owned + k; its velocity, integrated with incomplete
// forces between refreshes, is cleared (nothing reads a ghost's).
template <class R>
struct PlaceGhosts {
    const Real4<R>* positions;
    int64_t owned;
    Real4<R>* pos;
    Real4<R>* vel;
    SMD_HD void operator()(int64_t k) const {
        const int64_t i = owned + k;
        pos[i] = {positions[k].x, positions[k].y, positions[k].z, pos[i].w};
        vel[i] = {R(0), R(0), R(0), vel[i].w};
    }
};

template <class B, class R>
class DomainSlots {
public:
    template <class T>
    using Buffer = typename B::template Buffer<T>;

    explicit DomainSlots(const B& backend) : backend_(backend) {}

    bool held() const { return exchange_ != nullptr; }
    int64_t owned() const { return owned_; }
    const int64_t* global_ids() const { return globalIds_.data(); }

    // The domain as it was made (a new engine): ids, images and border slots from the host.
    void hold(Particles<B, R>& p, const DomainLayout& layout, GhostExchange* exchange) {
        exchange_ = exchange;
        owned_ = layout.owned;
        backend_.upload(globalIds_, layout.globalIds.data(), layout.globalIds.size());
        backend_.upload(border_, layout.borderSlots.data(), layout.borderSlots.size());
        borderCount_ = static_cast<int64_t>(layout.borderSlots.size());
        std::vector<Image> images(static_cast<size_t>(p.count), Image{0, 0, 0});
        for (size_t s = 0; s < layout.images.size(); ++s)
            images[s] = Image{layout.images[s][0], layout.images[s][1], layout.images[s][2]};
        backend_.upload(p.image, images.data(), images.size());
        remember_positions(p);
    }

    // Before a force evaluation at new positions: the ghosts take their owners' (collective).
    void refresh(Particles<B, R>& p, typename B::template Staging<Real4<R>>& host) {
        const int64_t border = borderCount_;
        const int64_t ghosts = p.count - owned_;
        if (exchange_->exchanges_on_device() && backend_.host_launch_stream()) {
            backend_.fit(exchanged_, static_cast<size_t>(border + ghosts));
            Real4<R>* values = exchanged_.data();
            if (border > 0) backend_.for_each(border, GatherById<Real4<R>>{p.pos.data(), border_.data(), values});
            exchange_->exchange_on_device(values, values + border, sizeof(Real4<R>), backend_.host_launch_stream());
            if (ghosts > 0)
                backend_.for_each(ghosts, PlaceGhosts<R>{values + border, owned_, p.pos.data(), p.vel.data()});
            return;
        }
        Real4<R>* values = host.reserve(static_cast<size_t>(border + ghosts));
        if (border > 0) {
            backend_.for_each(border, GatherById<Real4<R>>{p.pos.data(), border_.data(), values});
            backend_.wait_for_writes_to_host(host, static_cast<size_t>(border));
        }
        exchange_->exchange(values, values + border, sizeof(Real4<R>));
        if (ghosts > 0) {
            backend_.for_each(ghosts, PlaceGhosts<R>{values + border, owned_, p.pos.data(), p.vel.data()});
            backend_.read_from_host(host, static_cast<size_t>(border + ghosts));
        }
    }

    double largest_owned_move(const Particles<B, R>& p) const {
        return backend_.maximum(owned_, SquaredMoveSince<R>{p.pos.data(), heldPositions_.data(), p.box});
    }

    // Which owned slots stay (their order kept for place_owned) and the particles that leave.
    SlabSort sort_owned(const Particles<B, R>& p, const SlabGeometry& geometry) {
        geometry_ = geometry;
        backend_.fit(order_, static_cast<size_t>(owned_));
        SlabSort sorted;
        stay_ = backend_.select(owned_, BoundFor<R>{p.pos.data(), geometry, SlabGeometry::kStays}, order_.data());
        sorted.stay = stay_;
        if (stay_ == owned_) return sorted;
        sorted.up = leaving(p, BoundFor<R>{p.pos.data(), geometry, SlabGeometry::kUp});
        sorted.down = leaving(p, BoundFor<R>{p.pos.data(), geometry, SlabGeometry::kDown});
        if (static_cast<int64_t>(sorted.up.size() + sorted.down.size()) + stay_ < owned_) {
            const std::vector<Migrant> astray = leaving(p, BoundFor<R>{p.pos.data(), geometry, SlabGeometry::kAstray});
            for (const Migrant& m : astray) sorted.astray = std::max(sorted.astray, m.id);
        }
        return sorted;
    }

    // The slots that stay, then the arrivals, are the owned ones from now on; returns, by link, the
    // global ids of those within the ghost width of its face (their slots kept for place_ghosts).
    std::vector<std::vector<int64_t>> place_owned(const std::vector<Migrant>& arrivals, const SlotAttributes& attributes,
                                                  const Particles<B, R>& p) {
        arrivals_ = arrivals;
        arrivalAttributes_ = attributes;
        const auto n = static_cast<int64_t>(arrivals.size());
        std::vector<Real4<R>> positions(static_cast<size_t>(n));
        std::vector<int64_t> ids(static_cast<size_t>(n));
        for (size_t k = 0; k < arrivals.size(); ++k) {
            const Migrant& m = arrivals[k];
            positions[k] = {R(m.position[0]), R(m.position[1]), R(m.position[2]), R(attributes.typeIndex[k])};
            ids[k] = m.id;
        }
        backend_.fit(arrivedPositions_, positions.size());
        backend_.upload(arrivedPositions_, positions.data(), positions.size());
        const int64_t owned = stay_ + n;
        std::vector<std::vector<int64_t>> sent(static_cast<size_t>(geometry_.links()));
        backend_.fit(border_, static_cast<size_t>(geometry_.links() * owned));
        int64_t border = 0;
        // The new owned slots' global ids, to name the ghosts to the neighbours.
        backend_.fit(stagedIds_, ids.size());
        backend_.upload(stagedIds_, ids.data(), ids.size());
        backend_.fit(newIds_, static_cast<size_t>(owned));
        backend_.for_each(owned,
                          Renumbered<int64_t>{globalIds_.data(), order_.data(), stay_, stagedIds_.data(), newIds_.data()});
        for (int link = 0; link < geometry_.links(); ++link) {
            const int64_t count = backend_.select(
                owned, BordersFace<R>{p.pos.data(), order_.data(), stay_, arrivedPositions_.data(), geometry_, link},
                border_.data() + border);
            sent[static_cast<size_t>(link)] = download_at(newIds_, border_, border, count);
            border += count;
        }
        borderCount_ = border;
        return sent;
    }

    // The ghosts follow the owned slots; every per-slot array is renumbered to the new count (the
    // ghosts' positions come with the next refresh).
    void place_ghosts(Particles<B, R>& p, const std::vector<int64_t>& ghostIds, const SlotAttributes& attributes) {
        const int64_t arrived = static_cast<int64_t>(arrivals_.size());
        const int64_t owned = stay_ + arrived, count = owned + static_cast<int64_t>(ghostIds.size());
        const size_t added = static_cast<size_t>(count - stay_);
        std::vector<Real4<R>> pos(added), vel(added), force(added, Real4<R>{R(0), R(0), R(0), R(0)});
        std::vector<Image> images(added, Image{0, 0, 0});
        std::vector<R> radius(added), charge(added);
        std::vector<int> model(added);
        std::vector<int64_t> ids(added);
        for (size_t k = 0; k < added; ++k) {
            const bool arrival = k < arrivals_.size();
            const SlotAttributes& a = arrival ? arrivalAttributes_ : attributes;
            const size_t j = arrival ? k : k - arrivals_.size();
            pos[k] = {R(0), R(0), R(0), R(a.typeIndex[j])};
            vel[k] = {R(0), R(0), R(0), R(a.mass[j])};
            radius[k] = R(a.radius[j]);
            charge[k] = R(a.charge[j]);
            model[k] = a.model[j];
            if (!arrival) {
                ids[k] = ghostIds[j];
                continue;
            }
            const Migrant& m = arrivals_[j];
            pos[k] = {R(m.position[0]), R(m.position[1]), R(m.position[2]), pos[k].w};
            vel[k] = {R(m.velocity[0]), R(m.velocity[1]), R(m.velocity[2]), vel[k].w};
            force[k] = {R(m.force[0]), R(m.force[1]), R(m.force[2]), R(0)};
            images[k] = Image{m.image[0], m.image[1], m.image[2]};
            ids[k] = m.id;
        }
        renumber(p.pos, count, pos);
        renumber(p.vel, count, vel);
        // The owned slots' forces stay those of their positions (a ghost's is never read).
        renumber(p.force, count, force);
        renumber(p.image, count, images);
        // Arrays the input left empty stay empty.
        if (!p.radius.empty()) renumber(p.radius, count, radius);
        if (!p.charge.empty()) renumber(p.charge, count, charge);
        if (!p.model.empty()) renumber(p.model, count, model);
        renumber(globalIds_, count, ids);
        if (!p.energy.empty()) backend_.fit(p.energy, static_cast<size_t>(count));
        if (!p.virial.empty()) backend_.fit(p.virial, static_cast<size_t>(count));
        owned_ = owned;
        p.count = count;
        arrivals_.clear();
        remember_positions(p);
    }

    std::vector<int64_t> ids_on_host(int64_t count) const {
        std::vector<int64_t> ids(static_cast<size_t>(count));
        backend_.download(globalIds_, ids.data(), ids.size());
        return ids;
    }

private:
    // The particles at the owned slots `bound` selects, with their ids, velocities, images and forces.
    template <class Bound>
    std::vector<Migrant> leaving(const Particles<B, R>& p, const Bound& bound) {
        backend_.fit(leavingSlots_, static_cast<size_t>(owned_));
        const int64_t m = backend_.select(owned_, bound, leavingSlots_.data());
        std::vector<Migrant> out(static_cast<size_t>(m));
        if (m == 0) return out;
        const std::vector<Real4<R>> x = download_at(p.pos, leavingSlots_, 0, m);
        const std::vector<Real4<R>> v = download_at(p.vel, leavingSlots_, 0, m);
        const std::vector<Real4<R>> f = download_at(p.force, leavingSlots_, 0, m);
        const std::vector<Image> images = download_at(p.image, leavingSlots_, 0, m);
        const std::vector<int64_t> ids = download_at(globalIds_, leavingSlots_, 0, m);
        for (size_t k = 0; k < out.size(); ++k) {
            out[k].id = ids[k];
            out[k].position = {double(x[k].x), double(x[k].y), double(x[k].z)};
            out[k].velocity = {double(v[k].x), double(v[k].y), double(v[k].z)};
            out[k].force = {double(f[k].x), double(f[k].y), double(f[k].z)};
            out[k].image = {images[k].x, images[k].y, images[k].z};
        }
        return out;
    }

    // from[slots[first + k]] for k < m, on the host.
    template <class T>
    std::vector<T> download_at(const Buffer<T>& from, const Buffer<int64_t>& slots, int64_t first, int64_t m) {
        std::vector<T> values(static_cast<size_t>(m));
        if (m == 0) return values;
        Buffer<T>& gathered = scratch(T{});
        backend_.fit(gathered, static_cast<size_t>(m));
        backend_.for_each(m, GatherById<T>{from.data(), slots.data() + first, gathered.data()});
        backend_.download(gathered, values.data(), values.size());
        return values;
    }

    // `array` renumbered in place: the slots that stay (order_), then `added`, count in all.
    template <class T>
    void renumber(Buffer<T>& array, int64_t count, const std::vector<T>& added) {
        Buffer<T>& renumbered = scratch(T{});
        Buffer<T>& staged = staging(T{});
        backend_.fit(staged, added.size());
        backend_.upload(staged, added.data(), added.size());
        backend_.fit(renumbered, static_cast<size_t>(count));
        backend_.for_each(count, Renumbered<T>{array.data(), order_.data(), stay_, staged.data(), renumbered.data()});
        backend_.fit(array, static_cast<size_t>(count));
        backend_.for_each(count, CopyArray<T>{renumbered.data(), array.data()});
    }

    // Working buffers by value type, kept from one rebuild to the next.
    template <class T>
    struct Spare {
        Buffer<T> scratch, staged;
    };
    Buffer<int64_t>& scratch(int64_t) { return spareIds_.scratch; }
    Buffer<Real4<R>>& scratch(Real4<R>) { return spareVectors_.scratch; }
    Buffer<Image>& scratch(Image) { return spareImages_.scratch; }
    Buffer<R>& scratch(R) { return spareReals_.scratch; }
    Buffer<int>& scratch(int) { return spareInts_.scratch; }
    Buffer<int64_t>& staging(int64_t) { return spareIds_.staged; }
    Buffer<Real4<R>>& staging(Real4<R>) { return spareVectors_.staged; }
    Buffer<Image>& staging(Image) { return spareImages_.staged; }
    Buffer<R>& staging(R) { return spareReals_.staged; }
    Buffer<int>& staging(int) { return spareInts_.staged; }

    void remember_positions(const Particles<B, R>& p) {
        backend_.fit(heldPositions_, static_cast<size_t>(p.count));
        backend_.for_each(p.count, CopyArray<Real4<R>>{p.pos.data(), heldPositions_.data()});
    }

    const B& backend_;
    GhostExchange* exchange_ = nullptr;
    int64_t owned_ = 0;
    Buffer<int64_t> globalIds_;
    Buffer<int64_t> border_;  // owned slots each link sends, concatenated in link order (borderCount_)
    Buffer<Real4<R>> heldPositions_;
    Buffer<Real4<R>> exchanged_;  // the border's positions, then the ghosts', where GPUs exchange directly
    // A rebuild in progress: the geometry, the old owned slots that stay in their new order, the
    // arrivals, the border slots chosen and the new owned slots' ids.
    SlabGeometry geometry_;
    Buffer<int64_t> order_, leavingSlots_, stagedIds_, newIds_;
    Buffer<Real4<R>> arrivedPositions_;
    Spare<int64_t> spareIds_;
    Spare<Real4<R>> spareVectors_;
    Spare<Image> spareImages_;
    Spare<R> spareReals_;
    Spare<int> spareInts_;
    int64_t stay_ = 0, borderCount_ = 0;
    std::vector<Migrant> arrivals_;
    SlotAttributes arrivalAttributes_;
};

}  // namespace structmd
