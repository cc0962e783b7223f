// The Communicator over MPI where the build has it, and its refusal otherwise.
#include "parallel/communicator.hpp"

#include <algorithm>

#include "core/error.hpp"

#ifdef STRUCTMD_HAVE_MPI
// The C interface only: MPI's deprecated C++ bindings are not used.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace structmd {

namespace {

class SingleProcess final : public Communicator {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    int node_rank() const override { return 0; }
    void all_gather(const double* mine, double* all, const std::vector<int64_t>& counts) const override {
        std::copy(mine, mine + counts[0], all);
    }
    void all_gather(const int32_t* mine, int32_t* all, const std::vector<int64_t>& counts) const override {
        std::copy(mine, mine + counts[0], all);
    }
    void all_sum(double*, int) const override {}
    int64_t all_min(int64_t value) const override { return value; }
    int64_t all_max(int64_t value) const override { return value; }
    void broadcast(std::string&, int) const override {}
    void send_receive(const double*, double*, int64_t, int partner) const override {
        throw Error(STRUCTMD_ERR_INTERNAL, "an exchange with rank " + std::to_string(partner) + " of one process");
    }
    void shift(const double* sent, int64_t n, int to, double* received, int64_t m, int from) const override {
        copy(sent, n, to, received, m, from);
    }
    void shift(const unsigned char* sent, int64_t n, int to, unsigned char* received, int64_t m,
               int from) const override {
        copy(sent, n, to, received, m, from);
    }

private:
    template <class T>
    static void copy(const T* sent, int64_t n, int to, T* received, int64_t m, int from) {
        if (to != 0 || from != 0 || n != m)
            throw Error(STRUCTMD_ERR_INTERNAL, "a shift between ranks of one process");
        std::copy(sent, sent + n, received);
    }
};

}  // namespace

std::shared_ptr<const Communicator> single_process() { return std::make_shared<SingleProcess>(); }

void raise_first_failure(const Communicator& comm, int64_t first, structmd_status status, const std::string& message) {
    if (first == comm.size()) return;
    std::string report = std::to_string(static_cast<int>(status)) + " " + message;
    comm.broadcast(report, static_cast<int>(first));
    const size_t space = report.find(' ');
    const auto code = static_cast<structmd_status>(std::stoi(report.substr(0, space)));
    std::string text = report.substr(space + 1);
    if (comm.rank() != first) text += " (on MPI rank " + std::to_string(first) + ")";
    throw Error(code, text);
}

#ifdef STRUCTMD_HAVE_MPI

namespace {

void check(int code, const char* call) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw Error(STRUCTMD_ERR_INTERNAL, std::string(call) + " failed: " + std::string(text, length));
}

// The counts and displacements of an MPI_Allgatherv, which takes int.
void gather_layout(const std::vector<int64_t>& counts, std::vector<int>& sizes, std::vector<int>& offsets) {
    sizes.resize(counts.size());
    offsets.resize(counts.size());
    int64_t offset = 0;
    for (size_t r = 0; r < counts.size(); ++r) {
        if (counts[r] > INT32_MAX || offset > INT32_MAX)
            throw Error(STRUCTMD_ERR_UNSUPPORTED, "a gather over ranks of more than 2^31 values");
        sizes[r] = static_cast<int>(counts[r]);
        offsets[r] = static_cast<int>(offset);
        offset += counts[r];
    }
}

class MpiCommunicator final : public Communicator {
public:
    explicit MpiCommunicator(MPI_Comm comm) : comm_(comm) {
        check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
        check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
        MPI_Comm node = MPI_COMM_NULL;
        check(MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node), "MPI_Comm_split_type");
        check(MPI_Comm_rank(node, &nodeRank_), "MPI_Comm_rank");
        check(MPI_Comm_free(&node), "MPI_Comm_free");
    }

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int node_rank() const override { return nodeRank_; }

    void all_gather(const double* mine, double* all, const std::vector<int64_t>& counts) const override {
        gather(mine, all, counts, MPI_DOUBLE);
    }
    void all_gather(const int32_t* mine, int32_t* all, const std::vector<int64_t>& counts) const override {
        gather(mine, all, counts, MPI_INT32_T);
    }
    void all_sum(double* values, int n) const override {
        check(MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm_), "MPI_Allreduce");
    }
    int64_t all_min(int64_t value) const override { return reduce(value, MPI_MIN); }
    int64_t all_max(int64_t value) const override { return reduce(value, MPI_MAX); }
    void broadcast(std::string& bytes, int root) const override {
        int64_t length = static_cast<int64_t>(bytes.size());
        check(MPI_Bcast(&length, 1, MPI_INT64_T, root, comm_), "MPI_Bcast");
        bytes.resize(static_cast<size_t>(length));
        if (length > 0)
            check(MPI_Bcast(bytes.data(), static_cast<int>(length), MPI_CHAR, root, comm_), "MPI_Bcast");
    }
    void send_receive(const double* mine, double* theirs, int64_t n, int partner) const override {
        if (n > INT32_MAX) throw Error(STRUCTMD_ERR_UNSUPPORTED, "an exchange between ranks of more than 2^31 values");
        check(MPI_Sendrecv(mine, static_cast<int>(n), MPI_DOUBLE, partner, 0, theirs, static_cast<int>(n), MPI_DOUBLE,
                           partner, 0, comm_, MPI_STATUS_IGNORE),
              "MPI_Sendrecv");
    }
    void shift(const double* sent, int64_t n, int to, double* received, int64_t m, int from) const override {
        sendrecv(sent, n, to, received, m, from, MPI_DOUBLE);
    }
    void shift(const unsigned char* sent, int64_t n, int to, unsigned char* received, int64_t m,
               int from) const override {
        sendrecv(sent, n, to, received, m, from, MPI_BYTE);
    }

private:
    void sendrecv(const void* sent, int64_t n, int to, void* received, int64_t m, int from, MPI_Datatype type) const {
        if (n > INT32_MAX || m > INT32_MAX)
            throw Error(STRUCTMD_ERR_UNSUPPORTED, "an exchange between ranks of more than 2^31 values");
        check(MPI_Sendrecv(sent, static_cast<int>(n), type, to, 1, received, static_cast<int>(m), type, from, 1, comm_,
                           MPI_STATUS_IGNORE),
              "MPI_Sendrecv");
    }
    void gather(const void* mine, void* all, const std::vector<int64_t>& counts, MPI_Datatype type) const {
        std::vector<int> sizes, offsets;
        gather_layout(counts, sizes, offsets);
        check(MPI_Allgatherv(mine, sizes[static_cast<size_t>(rank_)], type, all, sizes.data(), offsets.data(), type,
                             comm_),
              "MPI_Allgatherv");
    }
    int64_t reduce(int64_t value, MPI_Op op) const {
        int64_t result = 0;
        check(MPI_Allreduce(&value, &result, 1, MPI_INT64_T, op, comm_), "MPI_Allreduce");
        return result;
    }

    MPI_Comm comm_;
    int rank_ = 0;
    int size_ = 1;
    int nodeRank_ = 0;
};

}  // namespace

bool mpi_compiled() { return true; }

std::shared_ptr<const Communicator> communicator_from_fortran(int64_t handle) {
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    if (!initialized || finalized)
        throw Error(STRUCTMD_ERR_STATE, "option \"mpi_comm\": MPI is not initialised (the host program calls MPI_Init "
                                        "before structmd_create and MPI_Finalize after structmd_destroy)");
    if (handle < INT32_MIN || handle > INT32_MAX)
        throw Error(STRUCTMD_ERR_ARGUMENT, "option \"mpi_comm\": " + std::to_string(handle) +
                                               " is not a Fortran communicator handle (MPI_Comm_c2f)");
    const MPI_Comm comm = MPI_Comm_f2c(static_cast<MPI_Fint>(handle));
    if (comm == MPI_COMM_NULL)
        throw Error(STRUCTMD_ERR_ARGUMENT, "option \"mpi_comm\": the null communicator (MPI_COMM_NULL)");
    return std::make_shared<MpiCommunicator>(comm);
}

#else

bool mpi_compiled() { return false; }

std::shared_ptr<const Communicator> communicator_from_fortran(int64_t) {
    throw Error(STRUCTMD_ERR_UNSUPPORTED, "option \"mpi_comm\": MPI is not compiled in (build with MPI installed, "
                                          "CMake option STRUCTMD_MPI)");
}

#endif

}  // namespace structmd
