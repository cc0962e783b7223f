#pragma once
// The particles sorted by the grid line (y, z) along x that their mesh kernel starts on, for the
// mesh methods that spread particle values onto a grid one line per thread (the particle-mesh Ewald
// of electrostatics, the force coupling method of hydrodynamics): each line then sums the particles
// of the bins its kernel reaches, each bin in particle order, with no atomics on the mesh, so a
// run is reproducible bit for bit whatever the thread count.
//
// The counting sort is the list build's (its scan of bin counts, verlet_list_kernels.hpp, run with
// its flag held raised); the rank a particle gets in its bin depends on thread timing, so the bins
// are sorted afterwards.
#include <cmath>
#include <cstdint>

#include "core/atomic.hpp"
#include "core/hd.hpp"
#include "neighbour/verlet_list_kernels.hpp"

namespace structmd {

// Bins particle i by the line LineOf gives it (-1: it spreads nothing).
template <class LineOf>
struct BinByLine {
    LineOf lineOf;
    int* lineCount;
    int* lineOfParticle;
    int* rankInLine;

    SMD_HD void operator()(int64_t i) const {
        const int line = lineOf(i);
        lineOfParticle[i] = line;
        if (line >= 0) rankInLine[i] = atomic_add(lineCount + line, 1);
    }
};

struct PlaceInLine {
    const int* lineOf;
    const int* rankInLine;
    const int* lineStart;
    int* order;
    SMD_HD void operator()(int64_t i) const {
        if (lineOf[i] >= 0) order[lineStart[lineOf[i]] + rankInLine[i]] = static_cast<int>(i);
    }
};

struct SortLineBin {
    const int* lineStart;
    int* order;
    SMD_HD void operator()(int64_t line) const {
        const int first = lineStart[line], members = lineStart[line + 1] - first;
        if (members <= 32)
            insertion_sort(order + first, members);
        else
            heap_sort(order + first, members);
    }
};

#if SMD_HOST_CODE
template <class B>
class LineBins {
public:
    LineBins(const B& backend, int lines) : backend_(backend), lines_(lines) {
        backend_.resize(lineCount_, lines);
        backend_.fill(lineCount_, 0);
        backend_.resize(lineStart_, lines + 1);
        // As the list sizes its scan: about as many chunks as lines per chunk, in whole warps.
        chunkLines_ = 32 * static_cast<int>(std::ceil(std::sqrt(static_cast<double>(lines)) / 32));
        chunks_ = (lines + chunkLines_ - 1) / chunkLines_;
        backend_.resize(chunkTotal_, chunks_);
        backend_.resize(scanControl_, kControlSlots);
        backend_.fill(scanControl_, 0);
        backend_.write(scanControl_, kRebuild, 1);
    }

    // Sorts particles [0, count) by line: afterwards the members of line l are
    // order()[line_start()[l] .. line_start()[l + 1]), in particle order.
    template <class LineOf>
    void sort(int64_t count, const LineOf& lineOf) {
        if (particles_ != count) {
            particles_ = count;
            backend_.resize(lineOf_, count);
            backend_.resize(rankInLine_, count);
            backend_.resize(order_, count);
        }
        backend_.for_each(count, BinByLine<LineOf>{lineOf, lineCount_.data(), lineOf_.data(), rankInLine_.data()});
        backend_.for_each_lanes(chunks_, SumCellChunks{scanControl_.data(), lineCount_.data(), chunkTotal_.data(),
                                                       chunkLines_, lines_},
                                LaneSizing::kFillDevice);
        backend_.for_each_lanes(chunks_, StartCells{scanControl_.data(), lineCount_.data(), chunkTotal_.data(),
                                                    lineStart_.data(), chunkLines_, lines_},
                                LaneSizing::kFillDevice);
        backend_.for_each(count, PlaceInLine{lineOf_.data(), rankInLine_.data(), lineStart_.data(), order_.data()});
        backend_.for_each(lines_, SortLineBin{lineStart_.data(), order_.data()});
    }

    const int* order() const { return order_.data(); }
    const int* line_start() const { return lineStart_.data(); }

private:
    const B& backend_;
    int lines_;
    int64_t particles_ = -1;
    int chunkLines_ = 1, chunks_ = 0;
    typename B::template Buffer<int> lineCount_, lineStart_, lineOf_, rankInLine_, order_, chunkTotal_, scanControl_;
};
#endif

}  // namespace structmd
