/*
 * Loads one bundled example input on the CPU in double precision and checks it describes what the
 * examples promise: the particle count, the number density, finite forces and energies, and the
 * starting temperature 2K / (3 N k_B) (units None: k_B = 1).
 *
 * usage: test_bundled_input INPUT PARTICLES DENSITY TEMPERATURE TEMPERATURE_TOLERANCE
 * The tolerance is absolute: 0-ish when the input gives velocities, a few standard deviations of the
 * sample temperature when the engine draws them.
 */
#include <structmd.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int failures = 0;

static void expect(int condition, const char* what) {
    if (condition) return;
    ++failures;
    fprintf(stderr, "FAILED: %s\n", what);
}

static void require(const structmd_sim* sim, structmd_status status, const char* call) {
    if (status == STRUCTMD_OK) return;
    fprintf(stderr, "FAILED: %s returned %d: %s\n", call, (int)status, structmd_last_error(sim));
    exit(EXIT_FAILURE);
}

int main(int argc, char** argv) {
    if (argc != 6) {
        fprintf(stderr, "usage: %s INPUT PARTICLES DENSITY TEMPERATURE TEMPERATURE_TOLERANCE\n", argv[0]);
        return EXIT_FAILURE;
    }
    const char* input = argv[1];
    const int64_t expected_particles = strtoll(argv[2], NULL, 10);
    const double expected_density = strtod(argv[3], NULL);
    const double expected_temperature = strtod(argv[4], NULL);
    const double temperature_tolerance = strtod(argv[5], NULL);

    structmd_sim* sim = NULL;
    require(NULL, structmd_create("{\"backend\":\"cpu\",\"precision\":\"double\"}", &sim), "structmd_create");
    require(sim, structmd_load_file(sim, input), "structmd_load_file");

    int64_t n = 0;
    double box[3];
    require(sim, structmd_get_num_particles(sim, &n), "structmd_get_num_particles");
    require(sim, structmd_get_box(sim, box), "structmd_get_box");
    double density = (double)n / (box[0] * box[1] * box[2]);
    printf("%s: %lld particles, density %.10g\n", input, (long long)n, density);
    expect(n == expected_particles, "particle count as promised");
    expect(fabs(density - expected_density) <= 1e-9 * expected_density, "number density as promised");

    double* forces = malloc(3 * (size_t)n * sizeof(double));
    if (forces == NULL) {
        fprintf(stderr, "FAILED: out of memory\n");
        return EXIT_FAILURE;
    }
    require(sim, structmd_get_forces(sim, forces, n), "structmd_get_forces");
    int forces_finite = 1;
    for (int64_t i = 0; i < 3 * n; ++i) forces_finite = forces_finite && isfinite(forces[i]);
    expect(forces_finite, "initial forces finite");
    free(forces);

    double potential = 0.0;
    double kinetic = 0.0;
    require(sim, structmd_get_energy(sim, "potential", &potential), "structmd_get_energy(potential)");
    require(sim, structmd_get_energy(sim, "kinetic", &kinetic), "structmd_get_energy(kinetic)");
    double temperature = 2.0 * kinetic / (3.0 * (double)n);
    printf("potential energy per particle %.6g, temperature %.6g\n", potential / (double)n, temperature);
    expect(isfinite(potential), "initial potential energy finite");
    expect(fabs(temperature - expected_temperature) <= temperature_tolerance, "starting temperature as promised");

    structmd_destroy(sim);
    if (failures > 0) fprintf(stderr, "%d check(s) failed\n", failures);
    return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
