#pragma once
// How an engine moves particle arrays between the host's layout (doubles in id order) and the
// backend's (Real4 records): whole arrays through pinned staging, subsets by id gathered or
// scattered by one backend loop, and the watched region, whose positions the last kernel of a step
// call gathers so that a coupling host reads them without a launch or a wait of its own.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "simulation/engine_functors.hpp"
#include "simulation/host_transfer.hpp"
#include "state/particles.hpp"

namespace structmd {

template <class B, class R>
class ParticleIo {
public:
    template <class T>
    using Buffer = typename B::template Buffer<T>;

    ParticleIo(B& backend, Particles<B, R>& p) : backend_(backend), p_(p) {}

    // Whole arrays (p_.count particles) from the host: positions wrapped into the box with their
    // images, velocities with their masses, orientations as quaternions [q0, q1, q2, q3].
    void upload_positions(const double* xyz, const std::array<double, 3>& box, const std::vector<int32_t>& types) {
        const auto n = static_cast<size_t>(p_.count);
        pack_positions_of<R>(xyz, nullptr, p_.count, box, types, vectors_.reserve(n), images_.reserve(n));
        backend_.upload(p_.pos, vectors_, n);
        backend_.upload(p_.image, images_, n);
    }
    void upload_velocities(const double* v, const std::vector<double>& masses) {
        const auto n = static_cast<size_t>(p_.count);
        pack_velocities_of<R>(v, nullptr, p_.count, masses, vectors_.reserve(n));
        backend_.upload(p_.vel, vectors_, n);
    }
    void upload_orientations(const double* q) {
        const auto n = static_cast<size_t>(p_.count);
        Real4<R>* values = vectors_.reserve(n);
        for (size_t i = 0; i < n; ++i) values[i] = {R(q[4 * i]), R(q[4 * i + 1]), R(q[4 * i + 2]), R(q[4 * i + 3])};
        backend_.upload(p_.dir, vectors_, n);
    }
    // The m forces f (3m values) into the vector staging, as Real4 with w = 0.
    Real4<R>* pack_forces(const double* f, int64_t m) {
        Real4<R>* values = vectors_.reserve(static_cast<size_t>(m));
        for (int64_t k = 0; k < m; ++k) values[k] = {R(f[3 * k]), R(f[3 * k + 1]), R(f[3 * k + 2]), R(0)};
        return values;
    }
    // The staging that pack_forces filled, once a backend loop read it.
    void staged_read(int64_t m) { backend_.read_from_host(vectors_, static_cast<size_t>(m)); }

    template <class T>
    std::vector<T> download(const Buffer<T>& buffer) {
        std::vector<T> values(buffer.size());
        backend_.download(buffer, values.data(), values.size());
        return values;
    }
    // A whole array of vectors as 3 doubles each.
    void download_vectors(const Buffer<Real4<R>>& buffer, double* out) {
        backend_.activate();
        unpack_vectors(backend_.download(buffer, vectors_, buffer.size()), static_cast<int64_t>(buffer.size()), out);
    }

    // Subsets by id (m > 0): the ids go to the backend once (a coupling loop names the same region
    // call after call), then one backend loop gathers the m entries into the host staging or
    // scatters them from it, directly (pinned memory on CUDA): one launch, no copy.
    void upload_ids(const int64_t* ids, int64_t m) {
        backend_.activate();
        if (uploadedIds_.size() == static_cast<size_t>(m) && std::equal(ids, ids + m, uploadedIds_.begin())) return;
        std::copy(ids, ids + m, hostIds_.reserve(static_cast<size_t>(m)));
        backend_.upload(subsetIds_, hostIds_, static_cast<size_t>(m));
        uploadedIds_.assign(ids, ids + m);
    }
    // The m values of `from` at the uploaded ids, in the vector staging (valid until the next transfer).
    const Real4<R>* gather(const Buffer<Real4<R>>& from, int64_t m) { return gather(from, subsetIds_, m); }
    // Positions of the particles ids (wrapped, images counted from the positions given) and
    // velocities (with their masses) at the ids, which it uploads.
    void scatter_positions(const int64_t* ids, int64_t m, const double* xyz, const std::array<double, 3>& box,
                           const std::vector<int32_t>& types) {
        pack_positions_of<R>(xyz, ids, m, box, types, vectors_.reserve(m), images_.reserve(m));
        upload_ids(ids, m);
        scatter(vectors_, p_.pos, m);
        scatter(images_, p_.image, m);
    }
    void scatter_velocities(const int64_t* ids, int64_t m, const double* v, const std::vector<double>& masses) {
        pack_velocities_of<R>(v, ids, m, masses, vectors_.reserve(m));
        upload_ids(ids, m);
        scatter(vectors_, p_.vel, m);
    }
    const int64_t* uploaded_ids() const { return subsetIds_.data(); }
    const Real4<R>* staged_vectors() const { return vectors_.data(); }
    // One particle's position as it is on the backend, and a new one put in its place.
    Real4<R> position_of(int64_t id) {
        upload_ids(&id, 1);
        return *gather(p_.pos, subsetIds_, 1);
    }
    void place_position(int64_t id, const Real4<R>& value) {
        upload_ids(&id, 1);
        *vectors_.reserve(1) = value;
        scatter(vectors_, p_.pos, 1);
    }

    // The watched region: a coupling host reads the positions of the same particles after every step
    // call, so the call's last kernel gathers them into pinned memory and the fault check's wait
    // brings them back with it. A region the host stopped reading (not read since the last gather)
    // is no longer gathered.
    void watched_positions(const int64_t* ids, int64_t m, double* xyz) {
        if (watching(ids, m) && watchedVersion_ == p_.version) {
            unpack_vectors(watchedPositions_.data(), m, xyz);  // gathered by the last step call
        } else {
            watch(ids, m);
            unpack_vectors(gather(p_.pos, watchedIdsOnBackend_, m), m, xyz);
        }
        watchedRead_ = true;
    }
    // Returns whether it gathered: the same kernel then brought the fault word along (fault_word()),
    // and the step call's fault check needs only to wait for it.
    bool gather_watched_positions() {
        if (watchedIds_.empty()) return false;
        if (!watchedRead_) {
            watchedIds_.clear();
            watchedIdsOnBackend_.release();
            return false;
        }
        const auto m = static_cast<int64_t>(watchedIds_.size());
        Real4<R>* values = watchedPositions_.reserve(static_cast<size_t>(m));
        backend_.for_each(m, GatherWithFaultWord<R>{p_.pos.data(), watchedIdsOnBackend_.data(), values,
                                                    p_.fault.data(), faultWord_.reserve(1)});
        backend_.written_to_host(watchedPositions_, static_cast<size_t>(m));
        backend_.written_to_host(faultWord_, 1);
        watchedVersion_ = p_.version;
        watchedRead_ = false;
        return true;
    }
    unsigned long long staged_fault_word() {
        backend_.synchronize();
        return *faultWord_.data();
    }

    // The vector staging itself, for transfers an engine arranges (a domain's ghost refresh).
    typename B::template Staging<Real4<R>>& vector_staging() { return vectors_; }

private:
    bool watching(const int64_t* ids, int64_t m) const {
        return watchedIds_.size() == static_cast<size_t>(m) && std::equal(ids, ids + m, watchedIds_.begin());
    }
    void watch(const int64_t* ids, int64_t m) {
        backend_.activate();
        if (!watching(ids, m)) {
            std::copy(ids, ids + m, hostIds_.reserve(static_cast<size_t>(m)));
            backend_.upload(watchedIdsOnBackend_, hostIds_, static_cast<size_t>(m));
            watchedIds_.assign(ids, ids + m);
        }
        watchedVersion_ = -1;
    }
    const Real4<R>* gather(const Buffer<Real4<R>>& from, const Buffer<int64_t>& ids, int64_t m) {
        Real4<R>* values = vectors_.reserve(static_cast<size_t>(m));
        backend_.for_each(m, GatherById<Real4<R>>{from.data(), ids.data(), values});
        backend_.wait_for_writes_to_host(vectors_, static_cast<size_t>(m));
        return values;
    }
    template <class T>
    void scatter(typename B::template Staging<T>& host, Buffer<T>& to, int64_t m) {
        backend_.for_each(m, ScatterById<T>{host.data(), subsetIds_.data(), to.data()});
        backend_.read_from_host(host, static_cast<size_t>(m));
    }

    B& backend_;
    Particles<B, R>& p_;
    // Host staging of every transfer of particle arrays (pinned on CUDA): packed and unpacked here.
    typename B::template Staging<Real4<R>> vectors_;
    typename B::template Staging<Image> images_;
    typename B::template Staging<int64_t> hostIds_;
    // The ids of the last subset call on the backend, and on the host to compare the next with.
    Buffer<int64_t> subsetIds_;
    std::vector<int64_t> uploadedIds_;
    // The watched region: its ids, their positions as of watchedVersion_ (-1: none), and whether the
    // host read them since they were gathered.
    std::vector<int64_t> watchedIds_;
    Buffer<int64_t> watchedIdsOnBackend_;
    typename B::template Staging<Real4<R>> watchedPositions_;
    int64_t watchedVersion_ = -1;
    bool watchedRead_ = false;
    typename B::template Staging<unsigned long long> faultWord_;
};

}  // namespace structmd
