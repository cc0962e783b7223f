// The i-PI client of the launcher over POSIX sockets. Messages: 12-byte space-padded ASCII headers,
// then int32 and float64 values in the machine's byte order (bindings/python/structmd/ipi.py has the
// protocol in prose; both clients implement the same one, and tests/python/test_ipi_conformance.py
// holds both to it, message by message).
#include "ipi_client.hpp"

#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "structmd.hpp"

namespace structmd::launcher {
namespace {

using structmd::host::check;
using structmd::host::Failure;
using structmd::host::Handle;

// ase.units (CODATA 2014), as in structmd/ipi.py, so that an ASE server and this client convert alike.
constexpr double kBohrInAngstrom = 0.5291772105638411;
constexpr double kHartreeInEv = 27.211386024367243;
constexpr size_t kHeaderSize = 12;
// The longest INIT string accepted (i-PI's are a few bytes): a server announcing 2^31 - 1 bytes would
// otherwise have the client allocate them, then wait for them.
constexpr int32_t kMaxInitLength = 1 << 20;
const char* const kUnixSocketPrefix = "/tmp/ipi_";

// A failure of the connection or of the server's side of the protocol.
class ConnectionFailure : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Socket {
public:
    explicit Socket(int fd) : fd_(fd) {}

    // Each read then fails after seconds without data (0: waits forever).
    void set_read_timeout(double seconds) {
        readTimeout_ = seconds;
        timeval limit{};
        limit.tv_sec = static_cast<time_t>(seconds);
        limit.tv_usec = static_cast<suseconds_t>((seconds - static_cast<double>(limit.tv_sec)) * 1e6);
        if (setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit) != 0)
            throw ConnectionFailure(std::string("setting the read timeout: ") + std::strerror(errno));
    }
    ~Socket() {
        if (fd_ >= 0) close(fd_);
    }
    Socket(Socket&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
    Socket(const Socket&) = delete;
    Socket& operator=(const Socket&) = delete;
    Socket& operator=(Socket&&) = delete;

    // Reads size bytes; false when the server closed the connection before the first byte and
    // at_boundary allows that (between messages), a ConnectionFailure otherwise.
    bool read(void* data, size_t size, bool at_boundary = false) {
        auto* bytes = static_cast<char*>(data);
        size_t done = 0;
        while (done < size) {
            const ssize_t got = recv(fd_, bytes + done, size - done, 0);
            if (got < 0 && errno == EINTR) continue;
            if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
                char seconds[32];
                std::snprintf(seconds, sizeof seconds, "%g", readTimeout_);
                throw ConnectionFailure(std::string("no data from the server for ") + seconds + " s (--read-timeout)");
            }
            if (got < 0) throw ConnectionFailure(std::string("reading from the server: ") + std::strerror(errno));
            if (got == 0) {
                if (at_boundary && done == 0) return false;
                throw ConnectionFailure("the server closed the connection in the middle of a message");
            }
            done += static_cast<size_t>(got);
        }
        return true;
    }

    void write(const void* data, size_t size) {
        const auto* bytes = static_cast<const char*>(data);
        size_t done = 0;
        while (done < size) {
            // MSG_NOSIGNAL: a server that went away is an error message, not a SIGPIPE.
            const ssize_t sent = send(fd_, bytes + done, size - done, MSG_NOSIGNAL);
            if (sent < 0 && errno == EINTR) continue;
            if (sent < 0) throw ConnectionFailure(std::string("writing to the server: ") + std::strerror(errno));
            done += static_cast<size_t>(sent);
        }
    }

    int32_t read_int32() {
        int32_t value = 0;
        read(&value, sizeof value);
        return value;
    }

    std::vector<double> read_doubles(size_t count) {
        std::vector<double> values(count);
        read(values.data(), count * sizeof(double));
        return values;
    }

    void write_header(const std::string& text) {
        std::string padded = text;
        padded.resize(kHeaderSize, ' ');
        write(padded.data(), kHeaderSize);
    }

    int fd() const { return fd_; }

private:
    int fd_;
    double readTimeout_ = 0.0;
};

// One attempt each; an invalid socket, with the reason in error, when the server is not (yet) there.
Socket try_connect_unix(const std::string& name, int& error) {
    const std::string path = kUnixSocketPrefix + name;
    sockaddr_un address{};
    if (path.size() >= sizeof address.sun_path)
        throw ConnectionFailure("the UNIX socket name " + path + " is too long");
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
    Socket socket_fd(socket(AF_UNIX, SOCK_STREAM, 0));
    if (socket_fd.fd() < 0) throw ConnectionFailure(std::string("socket: ") + std::strerror(errno));
    if (connect(socket_fd.fd(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        error = errno;
        return Socket(-1);
    }
    return socket_fd;
}

Socket try_connect_tcp(const std::string& host, const std::string& port, int& error) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    const int resolved = getaddrinfo(host.c_str(), port.c_str(), &hints, &found);
    if (resolved != 0) throw ConnectionFailure("cannot resolve " + host + ": " + gai_strerror(resolved));
    error = ECONNREFUSED;
    for (const addrinfo* candidate = found; candidate != nullptr; candidate = candidate->ai_next) {
        Socket socket_fd(socket(candidate->ai_family, candidate->ai_socktype, candidate->ai_protocol));
        if (socket_fd.fd() < 0) continue;
        if (connect(socket_fd.fd(), candidate->ai_addr, candidate->ai_addrlen) == 0) {
            freeaddrinfo(found);
            // Every message is a short request answered at once: no waiting to fill packets.
            const int on = 1;
            setsockopt(socket_fd.fd(), IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
            return socket_fd;
        }
        error = errno;
    }
    freeaddrinfo(found);
    return Socket(-1);
}

struct ServerAddress {
    std::string text;  // as given, for messages
    bool unixSocket = false;
    std::string name;  // unix:NAME
    std::string host, port;
};

ServerAddress parse_address(const std::string& text) {
    ServerAddress address;
    address.text = text;
    if (text.rfind("unix:", 0) == 0) {
        address.unixSocket = true;
        address.name = text.substr(5);
        if (address.name.empty()) throw Failure("--ipi", STRUCTMD_ERR_ARGUMENT, "the address unix:NAME needs a NAME");
        return address;
    }
    const size_t colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0)
        throw Failure("--ipi", STRUCTMD_ERR_ARGUMENT, "address " + text + ": expected HOST:PORT or unix:NAME");
    address.host = text.substr(0, colon);
    address.port = text.substr(colon + 1);
    const std::string& port = address.port;
    const bool numeric = !port.empty() && port.size() <= 5 &&
                         std::all_of(port.begin(), port.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!numeric || std::stoi(port) == 0 || std::stoi(port) > 65535)
        throw Failure("--ipi", STRUCTMD_ERR_ARGUMENT,
                      "address " + text + ": the port must be a number from 1 to 65535");
    return address;
}

// Connects, retrying while nobody listens yet, until the timeout: a client started beside its server
// may come up first.
Socket connect_to(const ServerAddress& address, double timeout_seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
    while (true) {
        int error = 0;
        Socket connection = address.unixSocket ? try_connect_unix(address.name, error)
                                               : try_connect_tcp(address.host, address.port, error);
        if (connection.fd() >= 0) return connection;
        const bool not_there_yet = error == ECONNREFUSED || error == ENOENT;
        if (!not_there_yet || std::chrono::steady_clock::now() >= deadline)
            throw ConnectionFailure("no i-PI server at " + address.text + ": " + std::strerror(error));
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
}

// The results of one configuration, in atomic units, ready to send.
struct ForceReply {
    double energy = 0.0;
    std::vector<double> forces;
    double virial[9] = {};
};

class IpiClient {
public:
    IpiClient(structmd_sim* sim, const IpiClientOptions& options)
        : sim_(sim), bohr_(kBohrInAngstrom / options.lengthUnit), hartree_(kHartreeInEv / options.energyUnit) {
        check(structmd_get_num_particles(sim_, &particles_), sim_, "structmd_get_num_particles");
    }

    // Returns the number of configurations evaluated.
    int64_t serve(Socket& server) {
        bool initialised = false, have_data = false;
        ForceReply reply;
        int64_t evaluations = 0;
        while (true) {
            char raw[kHeaderSize];
            if (!server.read(raw, kHeaderSize, true)) return evaluations;  // ASE's server ends so
            std::string header(raw, kHeaderSize);
            header.erase(header.find_last_not_of(' ') + 1);
            if (header == "EXIT") return evaluations;
            if (header == "STATUS") {
                server.write_header(have_data ? "HAVEDATA" : initialised ? "READY" : "NEEDINIT");
            } else if (header == "INIT") {
                server.read_int32();  // the bead index
                const int32_t length = server.read_int32();
                if (length < 0) throw ConnectionFailure("INIT with a negative length");
                if (length > kMaxInitLength)
                    throw ConnectionFailure("INIT announces a string of " + std::to_string(length) +
                                            " bytes, more than the " + std::to_string(kMaxInitLength) + " accepted");
                std::vector<char> ignored(static_cast<size_t>(length));
                server.read(ignored.data(), ignored.size());
                initialised = true;
            } else if (header == "POSDATA") {
                reply = evaluate(server);
                have_data = true;
                ++evaluations;
            } else if (header == "GETFORCE") {
                if (!have_data) throw ConnectionFailure("GETFORCE before any POSDATA");
                send_forces(server, reply);
                have_data = false;
            } else {
                throw ConnectionFailure("unknown i-PI message '" + header + "'");
            }
        }
    }

private:
    ForceReply evaluate(Socket& server) {
        // The cell arrives with the lattice vectors as columns: entry (row r, column c) at 3 r + c.
        const std::vector<double> cell = server.read_doubles(9);
        server.read_doubles(9);  // the inverse cell
        const int32_t count = server.read_int32();
        if (count != particles_)
            throw Failure("POSDATA", STRUCTMD_ERR_ARGUMENT,
                          "the input has " + std::to_string(particles_) + " particles, but the server sent " +
                              std::to_string(count) + " atoms");
        std::vector<double> positions = server.read_doubles(3 * static_cast<size_t>(count));
        for (double& x : positions) x *= bohr_;

        // A NaN would pass the tilt test below, since no comparison with it holds, and a negative
        // edge would fail it for the wrong reason.
        if (!std::all_of(cell.begin(), cell.end(), [](double x) { return std::isfinite(x); }))
            throw Failure("POSDATA", STRUCTMD_ERR_ARGUMENT, "the cell must have finite entries");
        double box[3] = {cell[0] * bohr_, cell[4] * bohr_, cell[8] * bohr_};
        for (int d = 0; d < 3; ++d)
            if (!(box[d] > 0.0))
                throw Failure("POSDATA", STRUCTMD_ERR_ARGUMENT,
                              "the cell must have positive edges along x, y and z, but its edge along " +
                                  std::string(1, "xyz"[d]) + " is " + std::to_string(cell[4 * d]) + " bohr");
        const double largest = std::max({box[0], box[1], box[2]});
        for (int k : {1, 2, 3, 5, 6, 7})
            if (std::abs(cell[k] * bohr_) > 1e-12 * largest)
                throw Failure("POSDATA", STRUCTMD_ERR_UNSUPPORTED, "structmd's box is rectangular; the cell is tilted");
        double current[3];
        check(structmd_get_box(sim_, current), sim_, "structmd_get_box");
        // Only a changed box is set (that rebuilds the neighbour lists), and before the positions, so
        // that they are taken as given rather than scaled with the box.
        if (!std::equal(box, box + 3, current)) check(structmd_set_box(sim_, box), sim_, "structmd_set_box");
        check(structmd_set_positions(sim_, positions.data(), particles_), sim_, "structmd_set_positions");
        check(structmd_compute(sim_, STRUCTMD_FORCES | STRUCTMD_ENERGY | STRUCTMD_VIRIAL), sim_, "structmd_compute");

        ForceReply reply;
        reply.forces.resize(3 * static_cast<size_t>(particles_));
        check(structmd_get_energy(sim_, "potential", &reply.energy), sim_, "structmd_get_energy");
        check(structmd_get_forces(sim_, reply.forces.data(), particles_), sim_, "structmd_get_forces");
        double virial[9];
        check(structmd_get_virial(sim_, virial), sim_, "structmd_get_virial");
        reply.energy /= hartree_;
        for (double& f : reply.forces) f *= bohr_ / hartree_;
        // Sent transposed, as i-PI's column-major matrices are.
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) reply.virial[3 * r + c] = virial[3 * c + r] / hartree_;
        return reply;
    }

    static void send_forces(Socket& server, const ForceReply& reply) {
        server.write_header("FORCEREADY");
        server.write(&reply.energy, sizeof reply.energy);
        const auto atoms = static_cast<int32_t>(reply.forces.size() / 3);
        server.write(&atoms, sizeof atoms);
        server.write(reply.forces.data(), reply.forces.size() * sizeof(double));
        server.write(reply.virial, sizeof reply.virial);
        const int32_t extra_length = 0;
        server.write(&extra_length, sizeof extra_length);
    }

    structmd_sim* sim_;
    double bohr_;     // one bohr in input lengths
    double hartree_;  // one hartree in input energies
    int64_t particles_ = 0;
};

}  // namespace

int run_ipi_client(const IpiClientOptions& options) {
    try {
        const ServerAddress address = parse_address(options.address);
        Handle simulation(options.createOptions);
        structmd_sim* sim = simulation.get();
        // Loaded before connecting, so that a bad input never holds a server waiting.
        check(structmd_load_file(sim, options.input.c_str()), sim, "structmd_load_file");
        IpiClient client(sim, options);
        Socket server = connect_to(address, options.connectTimeout);
        server.set_read_timeout(options.readTimeout);
        if (!options.quiet) std::fprintf(stderr, "structmd client: connected to %s\n", options.address.c_str());
        const int64_t evaluations = client.serve(server);
        if (!options.quiet)
            std::fprintf(stderr, "structmd client: done after %lld configurations\n",
                         static_cast<long long>(evaluations));
        return 0;
    } catch (const Failure& failure) {
        std::fprintf(stderr, "structmd client: stopped: %s (status %d)\n", failure.what(),
                     static_cast<int>(failure.status()));
        return failure.status();
    } catch (const ConnectionFailure& failure) {
        std::fprintf(stderr, "structmd client: %s\n", failure.what());
        return STRUCTMD_ERR_IO;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "structmd client: out of host memory\n");
        return STRUCTMD_ERR_MEMORY;
    }
}

}  // namespace structmd::launcher
