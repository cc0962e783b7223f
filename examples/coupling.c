/*
 * coupling.c - drives structmd from a C host the way a coupled code does: step, read forces and
 * energies, answer with an external force field that depends on the positions, step again.
 *
 * The field here is a harmonic tether toward the box centre, f_i = -k x_i (the box spans [-L/2, L/2),
 * so its centre is the origin). At the end the program checks its own results and exits non-zero,
 * saying what failed, if any check does:
 *   - the forces with the field minus the forces with the field cleared equal the field;
 *   - every energy read is finite;
 *   - the step counter advanced by exactly the steps taken.
 *
 * usage: example_coupling_c [INPUT_JSON [OPTIONS_JSON]]
 *   INPUT_JSON    default: the bead_spring.json bundled with the examples
 *   OPTIONS_JSON  structmd_create options, default {"backend":"auto"}
 * Exit status: 0 on success, 1 on any failure, 77 when the requested backend is not available in this
 * build or on this machine (the exit code test drivers read as "skipped").
 */
#include <structmd.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef STRUCTMD_EXAMPLE_INPUT
#define STRUCTMD_EXAMPLE_INPUT "bead_spring.json"
#endif

enum { COUPLING_ROUNDS = 20, STEPS_PER_ROUND = 10, EXIT_SKIPPED = 77 };

/* Weak enough to leave the dynamics of the bundled inputs almost untouched. */
static const double TETHER_STIFFNESS = 0.05;

/* Forces are accumulated in the engine's precision, so the field is recovered to that precision. */
static const double DOUBLE_PRECISION_TOLERANCE = 1e-9;
static const double SINGLE_PRECISION_TOLERANCE = 1e-5;

/* Prints the failed call and the library's message; returns whether status is STRUCTMD_OK. */
static int succeeded(const structmd_sim* sim, structmd_status status, const char* call) {
    if (status == STRUCTMD_OK) return 1;
    fprintf(stderr, "FAILED: %s returned status %d: %s\n", call, (int)status, structmd_last_error(sim));
    return 0;
}

#define CHECKED(sim, call) succeeded((sim), (call), #call)

/* Reads structmd_get_info into a buffer the caller frees; NULL on failure. */
static char* handle_info(const structmd_sim* sim) {
    size_t needed = 0;
    structmd_status status = structmd_get_info(sim, NULL, 0, &needed);
    if (needed == 0) {
        if (succeeded(sim, status, "structmd_get_info(sim, NULL, 0, &needed)"))
            fprintf(stderr, "FAILED: structmd_get_info reported no size for its text\n");
        return NULL;
    }
    char* info = malloc(needed);
    if (info == NULL) {
        fprintf(stderr, "FAILED: out of memory for %zu bytes of handle info\n", needed);
        return NULL;
    }
    if (!CHECKED(sim, structmd_get_info(sim, info, needed, NULL))) {
        free(info);
        return NULL;
    }
    return info;
}

/* Largest |with_field - without_field - field| relative to the largest of the three magnitudes,
 * per component. */
static double field_recovery_error(const double* with_field, const double* without_field,
                                   const double* field, int64_t count) {
    double worst = 0.0;
    for (int64_t i = 0; i < count; ++i) {
        double scale = fmax(fabs(field[i]), fmax(fabs(with_field[i]), fabs(without_field[i])));
        if (scale == 0.0) continue;
        double error = fabs(with_field[i] - without_field[i] - field[i]) / scale;
        if (isnan(error)) return error;
        worst = fmax(worst, error);
    }
    return worst;
}

/* Runs the coupling loop and the checks on a loaded handle; returns the number of failed checks, or
 * -1 when a call failed. */
static int couple(structmd_sim* sim, double tolerance) {
    int result = -1;
    int failures = 0;
    int64_t n = 0;
    int64_t first_step = 0;
    int64_t last_step = 0;
    if (!CHECKED(sim, structmd_get_num_particles(sim, &n))) return -1;
    if (!CHECKED(sim, structmd_get_step(sim, &first_step))) return -1;

    double* positions = malloc(3 * (size_t)n * sizeof(double));
    double* forces = malloc(3 * (size_t)n * sizeof(double));
    double* forces_without_field = malloc(3 * (size_t)n * sizeof(double));
    double* field = malloc(3 * (size_t)n * sizeof(double));
    if (positions == NULL || forces == NULL || forces_without_field == NULL || field == NULL) {
        fprintf(stderr, "FAILED: out of memory for %lld particles\n", (long long)n);
        goto release;
    }

    printf("%8s %16s %16s %16s\n", "step", "potential", "kinetic", "max |force|");
    for (int round = 0; round < COUPLING_ROUNDS; ++round) {
        if (!CHECKED(sim, structmd_step(sim, STEPS_PER_ROUND))) goto release;
        if (!CHECKED(sim, structmd_get_forces(sim, forces, n))) goto release;
        double potential = 0.0;
        double kinetic = 0.0;
        if (!CHECKED(sim, structmd_get_energy(sim, "potential", &potential))) goto release;
        if (!CHECKED(sim, structmd_get_energy(sim, "kinetic", &kinetic))) goto release;
        if (!isfinite(potential) || !isfinite(kinetic)) {
            fprintf(stderr, "FAILED: energies not finite after round %d: potential %g, kinetic %g\n", round,
                    potential, kinetic);
            ++failures;
        }
        double max_force = 0.0;
        for (int64_t i = 0; i < 3 * n; ++i) max_force = fmax(max_force, fabs(forces[i]));

        if (!CHECKED(sim, structmd_get_positions(sim, positions, n))) goto release;
        for (int64_t i = 0; i < 3 * n; ++i) field[i] = -TETHER_STIFFNESS * positions[i];
        if (!CHECKED(sim, structmd_set_external_forces(sim, field, n))) goto release;

        if (!CHECKED(sim, structmd_get_step(sim, &last_step))) goto release;
        printf("%8lld %16.8g %16.8g %16.8g\n", (long long)last_step, potential, kinetic, max_force);
    }

    int64_t expected_step = first_step + (int64_t)COUPLING_ROUNDS * STEPS_PER_ROUND;
    if (last_step != expected_step) {
        fprintf(stderr, "FAILED: step counter is %lld after %d steps from %lld, expected %lld\n",
                (long long)last_step, COUPLING_ROUNDS * STEPS_PER_ROUND, (long long)first_step,
                (long long)expected_step);
        ++failures;
    }

    /* The field set in the last round is still in force; compare with the forces once it is cleared. */
    if (!CHECKED(sim, structmd_get_forces(sim, forces, n))) goto release;
    if (!CHECKED(sim, structmd_set_external_forces(sim, NULL, 0))) goto release;
    if (!CHECKED(sim, structmd_get_forces(sim, forces_without_field, n))) goto release;
    double error = field_recovery_error(forces, forces_without_field, field, 3 * n);
    if (!(error <= tolerance)) {
        fprintf(stderr, "FAILED: forces with the field minus forces without it differ from the field by %g "
                        "(relative), more than %g\n", error, tolerance);
        ++failures;
    }
    printf("field recovered from the forces to %.3g relative (tolerance %g)\n", error, tolerance);
    result = failures;

release:
    free(positions);
    free(forces);
    free(forces_without_field);
    free(field);
    return result;
}

int main(int argc, char** argv) {
    const char* input_path = argc > 1 ? argv[1] : STRUCTMD_EXAMPLE_INPUT;
    const char* options = argc > 2 ? argv[2] : "{\"backend\":\"auto\"}";

    if (structmd_abi_version() != STRUCTMD_ABI_VERSION) {
        fprintf(stderr, "FAILED: library ABI version %d, this program was built against %d\n",
                structmd_abi_version(), STRUCTMD_ABI_VERSION);
        return EXIT_FAILURE;
    }
    printf("structmd %s, options %s, input %s\n", structmd_version(), options, input_path);

    structmd_sim* sim = NULL;
    structmd_status status = structmd_create(options, &sim);
    if (status != STRUCTMD_OK) {
        fprintf(stderr, "structmd_create(%s) returned status %d: %s\n", options, (int)status,
                structmd_last_error(NULL));
        if (status == STRUCTMD_ERR_DEVICE || status == STRUCTMD_ERR_UNSUPPORTED) return EXIT_SKIPPED;
        return EXIT_FAILURE;
    }

    int exit_code = EXIT_FAILURE;
    char* info = NULL;
    if (CHECKED(sim, structmd_load_file(sim, input_path))) info = handle_info(sim);
    if (info != NULL) {
        printf("%s\n", info);
        int double_precision = strstr(info, "\"double\"") != NULL;
        int failures = couple(sim, double_precision ? DOUBLE_PRECISION_TOLERANCE : SINGLE_PRECISION_TOLERANCE);
        if (failures == 0) {
            printf("all checks passed\n");
            exit_code = EXIT_SUCCESS;
        } else if (failures > 0) {
            fprintf(stderr, "%d check(s) failed\n", failures);
        }
    }
    free(info);
    structmd_destroy(sim);
    return exit_code;
}
