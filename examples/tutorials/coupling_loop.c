/*
 * Tutorial: a coupling loop in C (docs/tutorials/coupling-loop.md). A host code owns a field that
 * structmd does not know: here a harmonic tether toward the box centre, f_i = -k x_i, energy
 * k |x_i|^2 / 2 (the box spans [-L/2, L/2), so its centre is the origin). Every round the host reads
 * the positions, answers with the field's forces and energy, and lets structmd take some steps.
 * It prints one line a round: step, the field's energy, the potential energy of the force field,
 * and the particles' mean distance from the centre. examples/tutorials/coupling_loop.py is the same
 * loop in Python; the test runs both and compares their lines.
 *
 * usage: tutorial_coupling_loop_c INPUT_JSON [OPTIONS_JSON]   (options default {"backend":"cpu"})
 */
#include <structmd.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { ROUNDS = 40, STEPS_PER_ROUND = 25 };
static const double STIFFNESS = 0.5;

/* Nonzero, after saying why, when a call did not return STRUCTMD_OK. */
static int failed(const structmd_sim* sim, structmd_status status, const char* call) {
    if (status == STRUCTMD_OK) return 0;
    fprintf(stderr, "%s returned status %d: %s\n", call, (int)status, structmd_last_error(sim));
    return 1;
}

#define CALL(sim, call) \
    if (failed((sim), (call), #call)) goto done

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s INPUT_JSON [OPTIONS_JSON]\n", argv[0]);
        return 2;
    }
    const char* options = argc > 2 ? argv[2] : "{\"backend\":\"cpu\"}";
    structmd_sim* sim = NULL;
    double* x = NULL;
    double* f = NULL;
    int exit_status = 1;
    if (failed(NULL, structmd_create(options, &sim), "structmd_create")) return 1;
    CALL(sim, structmd_load_file(sim, argv[1]));
    int64_t n = 0;
    CALL(sim, structmd_get_num_particles(sim, &n));
    x = malloc(3 * (size_t)n * sizeof(double));
    f = malloc(3 * (size_t)n * sizeof(double));
    if (x == NULL || f == NULL) goto done;

    printf("# step field_energy potential mean_distance\n");
    for (int round = 0; round <= ROUNDS; ++round) {
        /* The host's side: the field at the current positions. */
        CALL(sim, structmd_get_positions(sim, x, n));
        double field_energy = 0.0, distance = 0.0;
        for (int64_t i = 0; i < n; ++i) {
            double r2 = 0.0;
            for (int d = 0; d < 3; ++d) {
                f[3 * i + d] = -STIFFNESS * x[3 * i + d];
                r2 += x[3 * i + d] * x[3 * i + d];
            }
            field_energy += 0.5 * STIFFNESS * r2;
            distance += sqrt(r2);
        }
        /* Handed to structmd: added to every force evaluation until replaced. */
        CALL(sim, structmd_set_external_forces(sim, f, n));
        CALL(sim, structmd_set_external_energy(sim, field_energy));

        int64_t step = 0;
        double potential = 0.0;
        CALL(sim, structmd_get_step(sim, &step));
        CALL(sim, structmd_get_energy(sim, "potential", &potential));
        printf("%lld %.12e %.12e %.12e\n", (long long)step, field_energy, potential, distance / (double)n);
        if (round < ROUNDS) CALL(sim, structmd_step(sim, STEPS_PER_ROUND));
    }
    exit_status = 0;
done:
    free(x);
    free(f);
    structmd_destroy(sim);
    return exit_status;
}
