/* The checks the MPI tests share: expect() counts a failure and goes on; check() aborts every rank
 * on a structmd call that failed (the others would wait for it in a collective call). Each test sets
 * world_rank and returns failures != 0. */
#ifndef STRUCTMD_TESTS_MPI_CHECKS_H
#define STRUCTMD_TESTS_MPI_CHECKS_H

#include <mpi.h>
#include <stdio.h>

#include "structmd.h"

static int failures = 0;
static int world_rank = 0;

static void expect(int condition, const char* what) {
    if (!condition) {
        fprintf(stderr, "rank %d: FAILED: %s\n", world_rank, what);
        ++failures;
    }
}

static void check(structmd_status status, structmd_sim* sim, const char* call) {
    if (status != STRUCTMD_OK) {
        fprintf(stderr, "rank %d: %s failed (%d): %s\n", world_rank, call, (int)status, structmd_last_error(sim));
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
}

#endif
