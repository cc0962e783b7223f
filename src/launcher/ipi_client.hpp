// `structmd client --ipi ADDRESS INPUT.json`: the engine as a client of an i-PI server (i-PI, or ASE's
// SocketIOCalculator), answering its force requests over a TCP or UNIX socket. The protocol and the
// units are those of bindings/python/structmd/ipi.py (docs/python.md).
#ifndef STRUCTMD_LAUNCHER_IPI_CLIENT_HPP
#define STRUCTMD_LAUNCHER_IPI_CLIENT_HPP

#include <string>

namespace structmd::launcher {

struct IpiClientOptions {
    std::string address;           // HOST:PORT, or unix:NAME for the UNIX socket /tmp/ipi_NAME
    std::string input;             // the input document's path
    std::string createOptions;     // structmd_create's options, JSON
    double lengthUnit = 1.0;       // one input length in Å
    double energyUnit = 1.0;       // one input energy in eV
    double connectTimeout = 60.0;  // seconds to keep trying while no server listens yet
    // Seconds to wait for each read from the server (0: forever), so that a server gone silent
    // ends the client. An hour: i-PI may wait long on its other clients between two requests.
    double readTimeout = 3600.0;
    bool quiet = false;
};

// Serves the server until it sends EXIT or closes the connection. Returns the exit status: 0, the
// structmd_status of a failed engine call (STRUCTMD_ERR_ARGUMENT also for a malformed address or a
// wrong number of atoms), or STRUCTMD_ERR_IO for a connection or protocol failure; every failure is
// reported on standard error.
int run_ipi_client(const IpiClientOptions& options);

}  // namespace structmd::launcher

#endif
