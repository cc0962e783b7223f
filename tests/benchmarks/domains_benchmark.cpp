// Scaling of one Lennard-Jones liquid split in space over MPI ranks (spatial domains,
// src/parallel/domains_over_ranks.hpp): the liquid of structmd_lj_benchmark (lj_liquid.hpp: fcc at
// density 0.8442, T = 1.44, LJ cut at 2.5 sigma, 0.3 sigma skin, NVE velocity Verlet, dt = 0.005)
// run over every rank of MPI_COMM_WORLD, one GPU each (a rank takes its node rank's GPU).
//
//   mpirun -np K structmd_domains_benchmark [--n N]... [--backend B] [--precision P] [--steps S]
//                                            [--repeats R] [--warmup W] [--exchange E] [--csv PATH]
//
// With K = 1 the handle is an ordinary engine: the baseline of the same binary, MPI and input.
// For each N: build the input, load it (collective; timed as setup), take W untimed steps, then
// R timed calls of S steps with a barrier before and after each; the median call gives the rate.
// Rank 0 prints one row per N (and appends it to --csv, with a header when the file is new): n,
// ranks, how the ghosts travel (--exchange: the option "ghost_exchange", auto, host or nccl),
// steps/s, particle-steps/s, domain rebuilds, neighbour-list builds and force evaluations per 1000
// steps (rank 0's), setup seconds, and the relative drift of the total energy over the timed steps
// (an NVE run: a wrong ghost shows there).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
// The MPI C API only (Open MPI's and MPICH's mpi.h pull in their C++ bindings otherwise).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <nlohmann/json.hpp>

#include "lj_liquid.hpp"
#include "structmd.hpp"

namespace {

using namespace structmd::benchmarks;
using structmd::host::check;

double total_energy(structmd_sim* sim) {
    double e = 0.0;
    check(structmd_get_energy(sim, "total", &e), sim, "structmd_get_energy");
    return e;
}

}  // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);

    CLI::App app{"structmd spatial-domain scaling benchmark (LJ liquid over MPI ranks)"};
    std::vector<int64_t> sizes;
    std::string backend = "cuda", precision = "single", exchange = "auto", csvPath;
    int64_t steps = 200;
    int repeats = 3, warmup = 100;
    app.add_option("--n", sizes, "particles (rounded to an fcc lattice)")->required();
    app.add_option("--backend", backend);
    app.add_option("--precision", precision);
    app.add_option("--steps", steps, "steps per timed call");
    app.add_option("--repeats", repeats);
    app.add_option("--warmup", warmup, "untimed steps after the load");
    app.add_option("--exchange", exchange, "how ghosts travel between ranks: auto, host or nccl");
    app.add_option("--csv", csvPath);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        MPI_Finalize();
        return code;
    }

    nlohmann::json options = nlohmann::json::parse(create_options(backend, precision, 0));
    options["log"] = "info";  // the domains' timing: rebuilds and the ghosts' exchange
    options["mpi_comm"] = static_cast<long long>(MPI_Comm_c2f(MPI_COMM_WORLD));
    options["ghost_exchange"] = exchange;
    const std::string optionText = options.dump();
    if (rank == 0)
        std::printf("%10s %5s %8s %10s %12s %16s %18s %18s %10s %10s\n", "n", "ranks", "exchange", "steps/s",
                    "particle-st/s", "rebuilds/1000st", "list builds/1000st", "force evals/1000st", "setup s",
                    "drift");
    int failed = 0;
    for (int64_t requested : sizes) {
        LjLiquid liquid;
        liquid.cells = cells_per_edge(requested);
        liquid.scheduleSteps = warmup + repeats * steps + 1000;
        const std::string input = lj_liquid_input(liquid);
        structmd_sim* sim = nullptr;
        try {
            check(structmd_create(optionText.c_str(), &sim), sim, "structmd_create");
            MPI_Barrier(MPI_COMM_WORLD);
            const double loadStart = MPI_Wtime();
            check(structmd_load_string(sim, input.c_str()), sim, "structmd_load_string");
            MPI_Barrier(MPI_COMM_WORLD);
            const double setup = MPI_Wtime() - loadStart;
            int64_t n = 0;
            check(structmd_get_num_particles(sim, &n), sim, "structmd_get_num_particles");
            check(structmd_step(sim, warmup), sim, "structmd_step (warm-up)");
            const nlohmann::json before = engine_counters(sim);
            const double e0 = total_energy(sim);
            std::vector<double> seconds;
            for (int r = 0; r < repeats; ++r) {
                MPI_Barrier(MPI_COMM_WORLD);
                const double start = MPI_Wtime();
                check(structmd_step(sim, steps), sim, "structmd_step");
                MPI_Barrier(MPI_COMM_WORLD);
                seconds.push_back(MPI_Wtime() - start);
            }
            const double drift = std::abs(total_energy(sim) - e0) / std::abs(e0);
            const nlohmann::json after = engine_counters(sim);
            std::sort(seconds.begin(), seconds.end());
            const double rate = static_cast<double>(steps) / seconds[seconds.size() / 2];
            const double perThousand = 1000.0 / static_cast<double>(repeats * steps);
            const double rebuilds =
                perThousand * (after["domain_rebuilds"].get<double>() - before["domain_rebuilds"].get<double>());
            const double lists = perThousand * (after["neighbour_list_builds"].get<double>() -
                                                before["neighbour_list_builds"].get<double>());
            const double forces = perThousand * (after["force_evaluations"].get<double>() -
                                                 before["force_evaluations"].get<double>());
            if (rank == 0) {
                std::printf("%10lld %5d %8s %10.2f %12.4g %16.1f %18.1f %18.1f %10.1f %10.2e\n",
                            static_cast<long long>(n), ranks, exchange.c_str(), rate, rate * static_cast<double>(n),
                            rebuilds, lists, forces, setup, drift);
                std::fflush(stdout);
                if (!csvPath.empty()) {
                    std::ofstream csv(csvPath, std::ios::app);
                    if (csv.tellp() == 0)
                        csv << "n,ranks,backend,precision,ghost_exchange,steps_per_second,particle_steps_per_second,"
                               "domain_rebuilds_per_1000_steps,list_builds_per_1000_steps,"
                               "force_evaluations_per_1000_steps,setup_seconds,energy_drift\n";
                    csv << n << ',' << ranks << ',' << backend << ',' << precision << ',' << exchange << ',' << rate
                        << ',' << rate * static_cast<double>(n) << ',' << rebuilds << ',' << lists << ',' << forces
                        << ',' << setup << ',' << drift << '\n';
                }
            }
        } catch (const std::exception& e) {
            if (rank == 0) std::printf("%10lld %5d failed: %s\n", static_cast<long long>(requested), ranks, e.what());
            failed = 1;
        }
        structmd_destroy(sim);
    }
    MPI_Finalize();
    return failed;
}
