/* A coupled MPI code hands structmd sub-communicators: MPI_COMM_WORLD (4 ranks) is split into two
 * halves, and each half's ranks share one handle's batches through its "mpi_comm" option. On every
 * rank a second handle without "mpi_comm" runs the same input alone. After the steps, each half's
 * gathered positions and velocities and its per-batch energies must equal the lone handle's bit for
 * bit, whole-system energies to rounding; the two halves (different seeds) must differ; and an input
 * with a bond between the halves' shares is refused on every rank of the half alike.
 *
 * usage (under mpirun with an even number of ranks): test_mpi_comm_halves */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi_checks.h"
#include "structmd.h"

enum { kBatches = 4, kPerBatch = 12, kN = kBatches * kPerBatch, kSteps = 300 };

/* kBatches overlaid copies of a bead chain (harmonic bonds, Lennard-Jones between all pairs of a
 * batch) under Brownian dynamics; bridge != 0 adds a bond from batch 1's last bead to batch 2's first. */
static char* chain_input(unsigned seed, int bridge) {
    size_t size = 64 * 1024, used = 0;
    char* text = malloc(size);
#define PUT(...) used += (size_t)snprintf(text + used, size - used, __VA_ARGS__)
    PUT("{\"system\": {\"info\": {\"type\": [\"Simulation\", \"Information\"], \"parameters\": {\"name\": \"halves\", "
        "\"seed\": %u}}},", seed);
    PUT("\"global\": {\"types\": {\"type\": [\"Types\", \"Basic\"], \"labels\": [\"name\", \"mass\", \"radius\", "
        "\"charge\"], \"data\": [[\"A\", 1.0, 0.5, 0.0]]},");
    PUT("\"ensemble\": {\"type\": [\"Ensemble\", \"NVT\"], \"labels\": [\"box\", \"temperature\"], \"data\": "
        "[[[30.0, 30.0, 30.0], 1.0]]}},");
    PUT("\"integrator\": {\"bd\": {\"type\": [\"Brownian\", \"EulerMaruyama\"], \"parameters\": {\"timeStep\": 0.001, "
        "\"viscosity\": 1.0}}, \"schedule\": {\"type\": [\"Schedule\", \"Integrator\"], \"labels\": [\"order\", "
        "\"integrator\", \"steps\"], \"data\": [[1, \"bd\", %d]]}},", kSteps);
    PUT("\"state\": {\"labels\": [\"id\", \"position\"], \"data\": [");
    for (int i = 0; i < kN; ++i) {
        const int k = i % kPerBatch;
        PUT("%s[%d, [%.3f, %.3f, 0.0]]", i ? ", " : "", i, 1.05 * (k % 6) - 3.0, 1.05 * (k / 6));
    }
    PUT("]}, \"topology\": {\"structure\": {\"labels\": [\"id\", \"type\", \"batchId\"], \"data\": [");
    for (int i = 0; i < kN; ++i) PUT("%s[%d, \"A\", %d]", i ? ", " : "", i, i / kPerBatch);
    PUT("]}, \"forceField\": {\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"], \"parameters\": "
        "{\"cutOffVerletFactor\": 1.2}},");
    PUT("\"lj\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"], \"parameters\": {\"cutOffFactor\": 2.5, "
        "\"condition\": \"all\"}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": "
        "[[\"A\", \"A\", 1.0, 1.0]]},");
    PUT("\"bonds\": {\"type\": [\"Bond2\", \"Harmonic\"], \"labels\": [\"id_i\", \"id_j\", \"K\", \"r0\"], \"data\": [");
    int first = 1;
    for (int i = 0; i < kN; ++i) {
        if ((i + 1) % kPerBatch == 0) continue;
        PUT("%s[%d, %d, 100.0, 1.05]", first ? "" : ", ", i, i + 1);
        first = 0;
    }
    if (bridge) PUT(", [%d, %d, 100.0, 1.05]", 2 * kPerBatch - 1, 2 * kPerBatch);
    PUT("]}}}}");
#undef PUT
    if (used >= size) {
        fprintf(stderr, "input larger than its buffer\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    return text;
}

static structmd_sim* create(const char* options) {
    structmd_sim* sim = NULL;
    check(structmd_create(options, &sim), NULL, "structmd_create");
    return sim;
}

static double energy(structmd_sim* sim, const char* term) {
    double value = 0.0;
    check(structmd_get_energy(sim, term, &value), sim, "structmd_get_energy");
    return value;
}

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int world_size = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    if (world_size % 2 != 0 || world_size < 2) {
        if (world_rank == 0) fprintf(stderr, "needs an even number of ranks, got %d\n", world_size);
        MPI_Finalize();
        return 1;
    }
    const int half = world_rank < world_size / 2 ? 0 : 1;
    MPI_Comm half_comm;
    MPI_Comm_split(MPI_COMM_WORLD, half, world_rank, &half_comm);
    int half_rank = 0, half_size = 0;
    MPI_Comm_rank(half_comm, &half_rank);
    MPI_Comm_size(half_comm, &half_size);

    char options[256];
    snprintf(options, sizeof options, "{\"backend\": \"cpu\", \"precision\": \"double\", \"threads\": 1, \"mpi_comm\": %lld}",
             (long long)MPI_Comm_c2f(half_comm));
    structmd_sim* shared = create(options);
    structmd_sim* alone = create("{\"backend\": \"cpu\", \"precision\": \"double\", \"threads\": 1}");

    char info[1024];
    check(structmd_get_info(shared, info, sizeof info, NULL), shared, "structmd_get_info");
    /* One node: the half's ranks are its node's, in the same order. */
    char expected[128];
    snprintf(expected, sizeof expected, "\"node_rank\":%d,\"rank\":%d,\"ranks\":%d}", half_rank, half_rank,
             half_size);
    const char* mpi = strstr(info, "\"mpi\":{\"compiled\":true,\"nccl\":");
    expect(mpi != NULL && strstr(mpi, expected) != NULL, "structmd_get_info names the half's rank, node rank and size");

    char* input = chain_input(11u + (unsigned)half, 0);
    check(structmd_load_string(shared, input), shared, "structmd_load_string (shared)");
    check(structmd_load_string(alone, input), alone, "structmd_load_string (alone)");
    int64_t n = 0;
    check(structmd_get_num_particles(shared, &n), shared, "structmd_get_num_particles");
    expect(n == kN, "the shared handle counts the whole system's particles");
    check(structmd_step(shared, kSteps), shared, "structmd_step (shared)");
    check(structmd_step(alone, kSteps), alone, "structmd_step (alone)");

    static double a[3 * kN], b[3 * kN];
    check(structmd_get_positions(shared, a, kN), shared, "structmd_get_positions");
    check(structmd_get_positions(alone, b, kN), alone, "structmd_get_positions");
    expect(memcmp(a, b, sizeof a) == 0, "positions over the half's ranks equal one rank's bit for bit");
    const double x0 = a[0];
    check(structmd_get_velocities(shared, a, kN), shared, "structmd_get_velocities");
    check(structmd_get_velocities(alone, b, kN), alone, "structmd_get_velocities");
    expect(memcmp(a, b, sizeof a) == 0, "velocities over the half's ranks equal one rank's bit for bit");
    for (int batch = 0; batch < kBatches; ++batch) {
        char term[64];
        snprintf(term, sizeof term, "potential@batch:%d", batch);
        const double shared_e = energy(shared, term), alone_e = energy(alone, term);
        expect(shared_e == alone_e, "each batch's potential energy equals one rank's bit for bit");
        expect(shared_e != 0.0, "each batch has a potential energy");
    }
    const double shared_total = energy(shared, "potential"), alone_total = energy(alone, "potential");
    expect(fabs(shared_total - alone_total) <= 1e-12 * fabs(alone_total), "the whole potential energy to rounding");

    /* The halves ran different seeds: rank 0 of each compares its first coordinate with the other's. */
    double other = 0.0;
    if (world_rank == 0) MPI_Sendrecv(&x0, 1, MPI_DOUBLE, world_size / 2, 0, &other, 1, MPI_DOUBLE, world_size / 2, 0,
                                      MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (world_rank == world_size / 2) MPI_Sendrecv(&x0, 1, MPI_DOUBLE, 0, 0, &other, 1, MPI_DOUBLE, 0, 0, MPI_COMM_WORLD,
                                                   MPI_STATUS_IGNORE);
    if (world_rank == 0 || world_rank == world_size / 2) expect(other != x0, "the halves ran their own systems");

    /* A bond between batch 1 (first share) and batch 2 (second share) is refused on every rank. */
    char* bridged = chain_input(5u, 1);
    const structmd_status status = structmd_load_string(shared, bridged);
    if (half_size > 1) {
        expect(status == STRUCTMD_ERR_UNSUPPORTED, "a bond between two ranks' shares is refused");
        expect(strstr(structmd_last_error(shared), "topology.forceField.bonds.data[") != NULL,
               "the refusal names the bond's row");
    } else {
        expect(status == STRUCTMD_OK, "one rank holds every bond");
    }
    free(bridged);
    free(input);

    structmd_destroy(shared);
    structmd_destroy(alone);
    MPI_Comm_free(&half_comm);
    int all_failures = 0;
    MPI_Allreduce(&failures, &all_failures, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    if (world_rank == 0)
        printf("%d ranks in two halves of %d: %s\n", world_size, half_size, all_failures ? "FAILED" : "ok");
    MPI_Finalize();
    return all_failures ? 1 : 0;
}
