/*
 * coupling.c - drives structmd from a C host the way a coupled code does: step, read forces and
 * energies, answer with an external force field that depends on the positions, step again. Then the
 * same tether as a force callback (the engine calls the host inside its step loop), a region
 * exchanged by particle id, and a time step changed at run time.
 *
 * The field here is a harmonic tether toward the box centre, f_i = -k x_i (the box spans [-L/2, L/2),
 * so its centre is the origin). At the end the program checks its own results and exits non-zero,
 * saying what failed, if any check does:
 *   - the forces with the field minus the forces with the field cleared equal the field;
 *   - every energy read is finite;
 *   - the step counter advanced by exactly the steps taken;
 *   - the forces with the callback minus those without it equal its forces, its energy is the
 *     energy term "callback", and it runs once per step;
 *   - positions read for a region by id equal those of the whole array;
 *   - after halving integrator.vv.parameters.timeStep (when the input has it), time advances by
 *     the new step.
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

/* The tether as a force callback: what the engine should add, and what the host saw. */
struct tether {
    double stiffness;
    double energy;  /* the energy of the last call */
    int calls;
};

static int32_t tether_callback(const double* x, double* f, int64_t n, double* energy, double virial[9],
                               int64_t step, void* user_data) {
    struct tether* t = user_data;
    (void)step;
    t->energy = 0.0;
    for (int64_t i = 0; i < 3 * n; ++i) {
        f[i] -= t->stiffness * x[i];
        t->energy += 0.5 * t->stiffness * x[i] * x[i];
        virial[4 * (i % 3)] -= t->stiffness * x[i] * x[i];
    }
    *energy += t->energy;
    ++t->calls;
    return 0;
}

/* The callback, a region by id and a run-time parameter; returns the number of failed checks, or -1
 * when a call failed. */
static int callback_region_parameter(structmd_sim* sim, int64_t n, double tolerance) {
    int result = -1;
    int failures = 0;
    int64_t m = n / 10 > 0 ? n / 10 : 1;
    double* with_callback = malloc(3 * (size_t)n * sizeof(double));
    double* without_callback = malloc(3 * (size_t)n * sizeof(double));
    double* positions = malloc(3 * (size_t)n * sizeof(double));
    double* field = malloc(3 * (size_t)n * sizeof(double));
    double* region_positions = malloc(3 * (size_t)m * sizeof(double));
    int64_t* region = malloc((size_t)m * sizeof(int64_t));
    if (!with_callback || !without_callback || !positions || !field || !region_positions || !region) {
        fprintf(stderr, "FAILED: out of memory for %lld particles\n", (long long)n);
        goto release;
    }

    struct tether t = {TETHER_STIFFNESS, 0.0, 0};
    if (!CHECKED(sim, structmd_get_forces(sim, without_callback, n))) goto release;
    if (!CHECKED(sim, structmd_get_positions(sim, positions, n))) goto release;
    if (!CHECKED(sim, structmd_set_force_callback(sim, tether_callback, &t))) goto release;
    if (!CHECKED(sim, structmd_get_forces(sim, with_callback, n))) goto release;
    for (int64_t i = 0; i < 3 * n; ++i) field[i] = -TETHER_STIFFNESS * positions[i];
    double error = field_recovery_error(with_callback, without_callback, field, 3 * n);
    double callback_energy = 0.0;
    if (!CHECKED(sim, structmd_get_energy(sim, "callback", &callback_energy))) goto release;
    if (!(error <= tolerance) || fabs(callback_energy - t.energy) > 1e-12 * fmax(1.0, fabs(t.energy))) {
        fprintf(stderr, "FAILED: the callback's forces recovered to %g (tolerance %g), its energy %.17g "
                        "read back as %.17g\n", error, tolerance, t.energy, callback_energy);
        ++failures;
    }
    if (!CHECKED(sim, structmd_step(sim, STEPS_PER_ROUND))) goto release;
    if (t.calls != 1 + STEPS_PER_ROUND) {
        fprintf(stderr, "FAILED: the callback ran %d times over %d steps, expected %d\n", t.calls, STEPS_PER_ROUND,
                1 + STEPS_PER_ROUND);
        ++failures;
    }
    printf("callback: forces recovered to %.3g relative, energy %.8g, %d calls\n", error, callback_energy, t.calls);
    if (!CHECKED(sim, structmd_set_force_callback(sim, NULL, NULL))) goto release;

    for (int64_t k = 0; k < m; ++k) region[k] = k * (n / m); /* spread over the system, distinct */
    if (!CHECKED(sim, structmd_get_positions(sim, positions, n))) goto release;
    if (!CHECKED(sim, structmd_get_positions_of(sim, region, m, region_positions))) goto release;
    for (int64_t k = 0; k < m; ++k)
        for (int d = 0; d < 3; ++d)
            if (region_positions[3 * k + d] != positions[3 * region[k] + d]) {
                fprintf(stderr, "FAILED: particle %lld read by id differs from the whole array\n", (long long)region[k]);
                ++failures;
                k = m;
                break;
            }
    printf("region: %lld particles read by id\n", (long long)m);

    const char* time_step_path = "integrator.vv.parameters.timeStep";
    double dt = 0.0;
    if (structmd_get_parameter(sim, time_step_path, &dt) == STRUCTMD_OK) {
        double before = 0.0;
        double after = 0.0;
        if (!CHECKED(sim, structmd_set_parameter(sim, time_step_path, 0.5 * dt))) goto release;
        if (!CHECKED(sim, structmd_get_time(sim, &before))) goto release;
        if (!CHECKED(sim, structmd_step(sim, STEPS_PER_ROUND))) goto release;
        if (!CHECKED(sim, structmd_get_time(sim, &after))) goto release;
        if (fabs(after - before - STEPS_PER_ROUND * 0.5 * dt) > 1e-9 * fmax(1.0, after)) {
            fprintf(stderr, "FAILED: %d steps of %g advanced time by %g\n", STEPS_PER_ROUND, 0.5 * dt, after - before);
            ++failures;
        }
        if (!CHECKED(sim, structmd_set_parameter(sim, time_step_path, dt))) goto release;
        printf("parameter: %s %g -> %g and back\n", time_step_path, dt, 0.5 * dt);
    } else {
        printf("parameter: this input has no %s; not changed\n", time_step_path);
    }
    result = failures;

release:
    free(with_callback);
    free(without_callback);
    free(positions);
    free(field);
    free(region_positions);
    free(region);
    return result;
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
        /* The key with its value, as the library writes it (no spaces): "double" alone also
         * appears in the list of precisions compiled. */
        int double_precision = strstr(info, "\"precision\":\"double\"") != NULL;
        double tolerance = double_precision ? DOUBLE_PRECISION_TOLERANCE : SINGLE_PRECISION_TOLERANCE;
        int failures = couple(sim, tolerance);
        if (failures >= 0) {
            int64_t n = 0;
            int more = CHECKED(sim, structmd_get_num_particles(sim, &n)) ? callback_region_parameter(sim, n, tolerance) : -1;
            failures = more < 0 ? -1 : failures + more;
        }
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
