/* Spatial domain decomposition (one system over the ranks of MPI_COMM_WORLD, slabs): every rank runs
 * each input twice, through a handle over MPI_COMM_WORLD (the system split in space) and through a
 * handle alone (one rank, the reference), and compares them at every output:
 *   - an LJ liquid in double precision, 1,000 steps of velocity Verlet: positions and energies to
 *     ~1e-10 relative, the total energy conserved;
 *   - bead chains laid across the slabs' faces (harmonic bonds, WCA): the bonds cross domains;
 *   - the LJ liquid under Langevin (BBK): the noise is keyed by global id, so the same trajectory;
 *   - a salt (Debye-Hueckel between +1 and -1 charges, WCA): charges travel with their particles;
 *   - a dilute gas flowing along the split axis, so that every particle migrates many times: the
 *     particle count and the positions of every id (the gather refuses an id held twice or never)
 *     checked at every output;
 *   - an ideal gas (no force field) flowing the same way under Langevin: no ghosts and no rebuilds;
 *   - every case but the ideal gas rebuilds its domains (the counter domain_rebuilds);
 *   - a blow-up (a time step of 0.5) fails every rank, and the handle refuses further calls;
 *   - an unsupported integrator, and an unsupported call (the virial), refused by name.
 *
 * usage (under mpirun with 2 or more ranks): test_mpi_domains */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi_checks.h"
#include "structmd.h"

/* A growing text buffer. */
typedef struct {
    char* text;
    size_t used, size;
} Text;

static void put(Text* t, const char* format, ...) __attribute__((format(printf, 2, 3)));
#include <stdarg.h>
static void put(Text* t, const char* format, ...) {
    for (;;) {
        va_list args;
        va_start(args, format);
        const int n = vsnprintf(t->text + t->used, t->size - t->used, format, args);
        va_end(args);
        if (t->used + (size_t)n < t->size) {
            t->used += (size_t)n;
            return;
        }
        t->size = 2 * t->size + (size_t)n;
        t->text = realloc(t->text, t->size);
    }
}

/* Uniform in [0, 1), the same sequence on every rank. */
static unsigned long long rng_state = 88172645463325252ull;
static double uniform(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

typedef struct {
    const char* name;
    int n;                /* particles */
    double box[3];
    const char* integrator;  /* the integrator entry's JSON */
    const char* pair;        /* "lj" (cutoff 2.5), "wca", "ions" (WCA and Debye-Hueckel between types A +1
                                and B -1) or "none" (an ideal gas: no force field) */
    int chain;            /* beads per chain (0: no bonds) */
    double flow;          /* a drift velocity along x added to every particle */
    int steps, interval;
} Case;

static char* make_input(const Case* c) {
    Text t = {malloc(1 << 16), 0, 1 << 16};
    rng_state = 88172645463325252ull;
    put(&t, "{\"system\": {\"info\": {\"type\": [\"Simulation\", \"Information\"], \"parameters\": {\"name\": \"%s\", "
            "\"seed\": 7}}},", c->name);
    const int ions = strcmp(c->pair, "ions") == 0;
    put(&t, "\"global\": {\"types\": {\"type\": [\"Types\", \"Basic\"], \"labels\": [\"name\", \"mass\", \"radius\", "
            "\"charge\"], \"data\": [[\"A\", 1.0, 0.5, %s], [\"B\", 1.0, 0.5, %s]]},", ions ? "1.0" : "0.0",
        ions ? "-1.0" : "0.0");
    put(&t, "\"ensemble\": {\"type\": [\"Ensemble\", \"NVT\"], \"labels\": [\"box\", \"temperature\"], \"data\": "
            "[[[%.17g, %.17g, %.17g], 1.0]]}},", c->box[0], c->box[1], c->box[2]);
    put(&t, "\"integrator\": {\"dynamics\": %s, \"schedule\": {\"type\": [\"Schedule\", \"Integrator\"], \"labels\": "
            "[\"order\", \"integrator\", \"steps\"], \"data\": [[1, \"dynamics\", %d]]}},", c->integrator, c->steps);
    put(&t, "\"state\": {\"labels\": [\"id\", \"position\", \"velocity\"], \"data\": [");
    /* A jittered simple cubic lattice filling the box (chains: runs of consecutive sites along x). */
    int per[3];
    const double volume = c->box[0] * c->box[1] * c->box[2];
    const double spacing = cbrt(volume / c->n);
    for (int d = 0; d < 3; ++d) per[d] = (int)ceil(c->box[d] / spacing - 1e-9);
    for (int i = 0; i < c->n; ++i) {
        const int ix = i % per[0], iy = (i / per[0]) % per[1], iz = i / (per[0] * per[1]);
        double x[3] = {(ix + 0.5) * c->box[0] / per[0], (iy + 0.5) * c->box[1] / per[1], (iz + 0.5) * c->box[2] / per[2]};
        for (int d = 0; d < 3; ++d) x[d] += 0.05 * (uniform() - 0.5) - 0.5 * c->box[d];
        double v[3];
        for (int d = 0; d < 3; ++d) v[d] = 2.0 * (uniform() - 0.5);
        v[0] += c->flow;
        put(&t, "%s[%d, [%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]]", i ? ", " : "", i, x[0], x[1], x[2], v[0], v[1], v[2]);
    }
    put(&t, "]}, \"topology\": {\"structure\": {\"labels\": [\"id\", \"type\"], \"data\": [");
    for (int i = 0; i < c->n; ++i) put(&t, "%s[%d, \"%s\"]", i ? ", " : "", i, ions && i % 2 ? "B" : "A");
    if (strcmp(c->pair, "none") == 0) {
        put(&t, "]}, \"forceField\": {}}}");
        return t.text;
    }
    put(&t, "]}, \"forceField\": {\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"], \"parameters\": "
            "{\"cutOffVerletFactor\": 1.2}},");
    if (strcmp(c->pair, "lj") == 0)
        put(&t, "\"pairs\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"], \"parameters\": {\"cutOffFactor\": 2.5, "
                "\"condition\": \"all\", \"shift\": true}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": "
                "[[\"A\", \"A\", 1.0, 1.0]]}");
    else if (ions)
        put(&t, "\"pairs\": {\"type\": [\"NonBonded\", \"WCAType2\"], \"parameters\": {\"cutOffFactor\": 1.0, "
                "\"condition\": \"all\"}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": "
                "[[\"A\", \"A\", 1.0, 1.0], [\"A\", \"B\", 1.0, 1.0], [\"B\", \"B\", 1.0, 1.0]]}, "
                "\"dh\": {\"type\": [\"NonBonded\", \"DebyeHuckel\"], \"parameters\": {\"cutOffFactor\": 2.5, "
                "\"dielectricConstant\": 2.0, \"debyeLength\": 1.0, \"condition\": \"all\", \"shift\": true}}");
    else
        put(&t, "\"pairs\": {\"type\": [\"NonBonded\", \"WCAType2\"], \"parameters\": {\"cutOffFactor\": 1.0, "
                "\"condition\": \"all\"}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": "
                "[[\"A\", \"A\", 1.0, 1.0]]}");
    if (c->chain) {
        put(&t, ", \"bonds\": {\"type\": [\"Bond2\", \"Harmonic\"], \"labels\": [\"id_i\", \"id_j\", \"K\", \"r0\"], "
                "\"data\": [");
        int first = 1;
        for (int i = 0; i + 1 < c->n; ++i) {
            if ((i + 1) % c->chain == 0 || (i + 1) % per[0] == 0) continue; /* chains along x, within a row */
            put(&t, "%s[%d, %d, 50.0, 1.0]", first ? "" : ", ", i, i + 1);
            first = 0;
        }
        put(&t, "]}");
    }
    put(&t, "}}}");
    return t.text;
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

static double largest_difference(const double* a, const double* b, int64_t n, const double* box) {
    double worst = 0.0;
    for (int64_t k = 0; k < n; ++k) {
        double d = a[k] - b[k];
        if (box) d -= box[k % 3] * round(d / box[k % 3]);
        worst = fmax(worst, fabs(d));
    }
    return worst;
}

static char world_options[256];

/* A counter of structmd_get_counters by name (-1 when missing). */
static long long counter(structmd_sim* sim, const char* name) {
    char counters[1024], key[128];
    check(structmd_get_counters(sim, counters, sizeof counters), sim, "structmd_get_counters");
    snprintf(key, sizeof key, "\"%s\":", name);
    const char* at = strstr(counters, key);
    long long value = -1;
    if (at) sscanf(at + strlen(key), "%lld", &value);
    return value;
}

/* Runs the case split and alone, comparing them at every output. */
static void run_case(const Case* c, double position_tolerance, double energy_tolerance, int conserves) {
    char* input = make_input(c);
    structmd_sim* split = create(world_options);
    structmd_sim* alone = create("{\"backend\": \"cpu\", \"precision\": \"double\", \"threads\": 1}");
    check(structmd_load_string(split, input), split, "structmd_load_string (split)");
    check(structmd_load_string(alone, input), alone, "structmd_load_string (alone)");
    free(input);
    const int64_t n = c->n;
    double* a = malloc(sizeof(double) * 3 * n);
    double* b = malloc(sizeof(double) * 3 * n);
    char what[256];
    double worst_x = 0.0, worst_e = 0.0, drift = 0.0, e0 = 0.0, seconds_split = 0.0, seconds_alone = 0.0;
    for (int step = 0; step <= c->steps; step += c->interval) {
        if (step > 0) {
            MPI_Barrier(MPI_COMM_WORLD);
            double start = MPI_Wtime();
            check(structmd_step(split, c->interval), split, "structmd_step (split)");
            seconds_split += MPI_Wtime() - start;
            start = MPI_Wtime();
            check(structmd_step(alone, c->interval), alone, "structmd_step (alone)");
            seconds_alone += MPI_Wtime() - start;
        }
        int64_t count = 0;
        check(structmd_get_num_particles(split, &count), split, "structmd_get_num_particles");
        snprintf(what, sizeof what, "%s, step %d: %lld particles, expected %lld", c->name, step, (long long)count,
                 (long long)n);
        expect(count == n, what);
        /* The gather checks that every id arrives once; a lost or doubled particle fails the call. */
        check(structmd_get_positions(split, a, n), split, "structmd_get_positions (split)");
        check(structmd_get_positions(alone, b, n), alone, "structmd_get_positions (alone)");
        worst_x = fmax(worst_x, largest_difference(a, b, 3 * n, c->box));
        check(structmd_get_velocities(split, a, n), split, "structmd_get_velocities (split)");
        check(structmd_get_velocities(alone, b, n), alone, "structmd_get_velocities (alone)");
        worst_x = fmax(worst_x, largest_difference(a, b, 3 * n, NULL));
        const char* terms[] = {"kinetic", "potential", "pairs"};
        const int named = strcmp(c->pair, "none") == 0 ? 2 : 3; /* an ideal gas has no entry "pairs" */
        for (int k = 0; k < named; ++k) {
            const double es = energy(split, terms[k]), ea = energy(alone, terms[k]);
            worst_e = fmax(worst_e, fabs(es - ea) / fmax(fabs(ea), 1.0));
        }
        const double total = energy(split, "kinetic") + energy(split, "potential");
        if (step == 0) e0 = total;
        drift = fmax(drift, fabs(total - e0) / fabs(e0));
    }
    if (world_rank == 0)
        printf("%-8s %d particles, %d steps over the ranks against one rank: positions and velocities differ by at "
               "most %.3g, energies by %.3g relative; total energy drift %.3g; steps took %.3f s split, %.3f s alone\n",
               c->name, c->n, c->steps, worst_x, worst_e, drift, seconds_split, seconds_alone);
    snprintf(what, sizeof what, "%s: positions or velocities differ by %.3g (> %.3g)", c->name, worst_x,
             position_tolerance);
    expect(worst_x <= position_tolerance, what);
    snprintf(what, sizeof what, "%s: energies differ by %.3g relative (> %.3g)", c->name, worst_e, energy_tolerance);
    expect(worst_e <= energy_tolerance, what);
    if (conserves) {
        snprintf(what, sizeof what, "%s: the total energy drifts by %.3g relative", c->name, drift);
        expect(drift < 1e-3, what);
    }
    /* The particles moved far enough that the domains were rebuilt (so what was compared includes
     * rebuilds), except where nothing reaches across a face. */
    const long long rebuilds = counter(split, "domain_rebuilds");
    const int none = strcmp(c->pair, "none") == 0;
    snprintf(what, sizeof what, "%s: %lld domain rebuilds, expected %s", c->name, rebuilds, none ? "none" : "some");
    expect(none ? rebuilds == 0 : rebuilds > 0, what);
    /* A rebuild in place (no bonds) renumbers the slots with their forces: the step after it
     * evaluates forces no more often than one rank does. An output may evaluate them once more
     * (the energy of one term over the ranks computes its forces; its ghosts may be refreshed right
     * after a rebuild), never once per rebuild. */
    const long long evaluations_split = counter(split, "force_evaluations");
    const long long evaluations_alone = counter(alone, "force_evaluations");
    const int outputs = c->steps / c->interval + 1;
    if (world_rank == 0)
        printf("%-8s %lld domain rebuilds; force evaluations %lld split, %lld alone\n", c->name, rebuilds,
               evaluations_split, evaluations_alone);
    snprintf(what, sizeof what, "%s: %lld force evaluations over the ranks against %lld on one rank (%d outputs)",
             c->name, evaluations_split, evaluations_alone, outputs);
    expect(c->chain > 0 || evaluations_split <= evaluations_alone + 2 * outputs, what);
    free(a);
    free(b);
    structmd_destroy(split);
    structmd_destroy(alone);
}

static void expect_refused(const Case* c, const char* named) {
    char* input = make_input(c);
    structmd_sim* split = create(world_options);
    const structmd_status status = structmd_load_string(split, input);
    free(input);
    char what[512];
    snprintf(what, sizeof what, "%s: refused with STRUCTMD_ERR_UNSUPPORTED naming '%s' (got %d: %s)", c->name, named,
             (int)status, structmd_last_error(split));
    expect(status == STRUCTMD_ERR_UNSUPPORTED && strstr(structmd_last_error(split), named) &&
               strstr(structmd_last_error(split), "is not available under domain decomposition"),
           what);
    structmd_destroy(split);
}

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int world_size = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    snprintf(world_options, sizeof world_options,
             "{\"backend\": \"cpu\", \"precision\": \"double\", \"threads\": 1, \"log\": \"info\", \"mpi_comm\": %lld}",
             (long long)MPI_Comm_c2f(MPI_COMM_WORLD));

    const char* verlet = "{\"type\": [\"Verlet\", \"VelocityVerlet\"], \"parameters\": {\"timeStep\": 0.002}}";
    const char* langevin = "{\"type\": [\"Langevin\", \"BBK\"], \"parameters\": {\"timeStep\": 0.002, "
                           "\"frictionConstant\": 1.0}}";
    const Case liquid = {"liquid", 512, {12.0, 7.5, 7.5}, verlet, "lj", 0, 0.0, 1000, 100};
    const Case chains = {"chains", 384, {14.0, 6.0, 6.0}, verlet, "wca", 8, 0.0, 1000, 100};
    const Case thermostat = {"langevin", 512, {12.0, 7.5, 7.5}, langevin, "lj", 0, 0.0, 1000, 100};
    const Case gas = {"gas", 64, {12.0, 8.0, 8.0}, verlet, "wca", 0, 5.0, 3000, 25};
    run_case(&liquid, 1e-10, 1e-10, 1);
    run_case(&chains, 1e-10, 1e-10, 1);
    run_case(&thermostat, 1e-10, 1e-10, 0);
    run_case(&gas, 1e-10, 1e-10, 1);
    /* Charges (Debye-Hueckel between alternating +1 and -1): a per-particle array renumbered with
     * the slots when the domains are rebuilt in place. */
    const Case salt = {"ions", 512, {12.0, 7.5, 7.5}, verlet, "ions", 0, 0.0, 1000, 100};
    run_case(&salt, 1e-10, 1e-10, 1);
    /* Nothing reaches across a face: no ghosts, and however far the particles flow, no rebuild. */
    const Case ideal = {"ideal", 64, {12.0, 8.0, 8.0}, langevin, "none", 0, 5.0, 1000, 100};
    run_case(&ideal, 1e-10, 1e-10, 0);

    /* What the domains do not support is refused by name, at load or when called. */
    Case brownian = liquid;
    brownian.name = "brownian";
    brownian.integrator = "{\"type\": [\"Brownian\", \"EulerMaruyama\"], \"parameters\": {\"timeStep\": 0.001, "
                          "\"viscosity\": 1.0}}";
    expect_refused(&brownian, "integrator [\"Brownian\",\"EulerMaruyama\"]");
    {
        char* input = make_input(&liquid);
        structmd_sim* split = create(world_options);
        check(structmd_load_string(split, input), split, "structmd_load_string");
        free(input);
        double w[9];
        const structmd_status status = structmd_get_virial(split, w);
        expect(status == STRUCTMD_ERR_UNSUPPORTED &&
                   strstr(structmd_last_error(split), "the virial (and the pressure) is not available under domain "
                                                      "decomposition"),
               "the virial is refused by name");
        structmd_destroy(split);
    }

    /* A blow-up on one rank leaves it a step behind the others: every rank returns the error, and
     * the handle refuses to go on. */
    {
        Case blowup = liquid;
        blowup.integrator = "{\"type\": [\"Verlet\", \"VelocityVerlet\"], \"parameters\": {\"timeStep\": 0.5}}";
        char* input = make_input(&blowup);
        structmd_sim* split = create(world_options);
        check(structmd_load_string(split, input), split, "structmd_load_string");
        free(input);
        const structmd_status first = structmd_step(split, 20);
        char what[512];
        snprintf(what, sizeof what, "a step of 0.5 fails (got %d: %s)", (int)first, structmd_last_error(split));
        expect(first == STRUCTMD_ERR_NUMERICAL, what);
        double* x = malloc(sizeof(double) * 3 * blowup.n);
        const structmd_status again = structmd_step(split, 1), read = structmd_get_positions(split, x, blowup.n);
        free(x);
        snprintf(what, sizeof what, "after the failure, stepping and reading are STRUCTMD_ERR_STATE (got %d, %d: %s)",
                 (int)again, (int)read, structmd_last_error(split));
        expect(again == STRUCTMD_ERR_STATE && read == STRUCTMD_ERR_STATE, what);
        structmd_destroy(split);
    }

    if (world_rank == 0) printf(failures ? "FAILED\n" : "spatial domains over %d ranks: as one rank\n", world_size);
    int all = 0;
    MPI_Allreduce(&failures, &all, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    MPI_Finalize();
    return all ? 1 : 0;
}
