/**
 * @file
 * @brief The public C ABI of structmd, a GPU molecular dynamics engine.
 *
 * This header is the reference of the interface: each function is documented where it is declared,
 * and the HTML reference is rendered from it by Doxygen (docs/Doxyfile). docs/c-api.md explains how
 * the pieces fit together.
 *
 * A host program (C, C++, Fortran through iso_c_binding, Python through ctypes or cffi) creates an
 * opaque handle, loads a simulation described in the UAMMD-structured JSON format, steps it, reads
 * forces and energies, sets positions, velocities or extra forces, steps again and destroys it.
 *
 * Rules that hold for every function below:
 * - Every function that can fail returns a structmd_status (0 = STRUCTMD_OK). No C++ exception,
 *   exit, abort or signal ever leaves the library. After a failure, structmd_last_error(sim) says
 *   what went wrong, where (JSON path, argument name, particle id and step) and what was expected.
 *   A failed call leaves the handle usable and its previous state intact, unless the message says
 *   the state was lost.
 * - A NULL handle is STRUCTMD_ERR_ARGUMENT, with the message under structmd_last_error(NULL) on the
 *   calling thread (structmd_destroy and structmd_last_error accept NULL). A NULL output pointer is
 *   STRUCTMD_ERR_ARGUMENT unless the function says it is optional. A function that needs a loaded
 *   simulation returns STRUCTMD_ERR_STATE before a successful load.
 * - No global mutable state: two handles in one process are independent. One thread at a time per
 *   handle; different handles may be driven from different threads at once. Every call returns
 *   when its work is complete.
 * - Arrays are owned by the caller: the library reads or writes them during the call and keeps no
 *   pointer to them. Vector quantities are double[3*n] (x0,y0,z0,x1,...), scalars double[n], always
 *   in ascending particle-id order whatever order the engine keeps internally. n must equal the
 *   number of particles, otherwise STRUCTMD_ERR_ARGUMENT and nothing is written.
 * - Values returned are consistent with the current state: a getter evaluates what is stale (forces
 *   after positions changed, say) and nothing more. Energies and virials are computed only when
 *   someone asks for them.
 * - Units are those of the loaded input (global.units); the API does not convert.
 */
#ifndef STRUCTMD_H
#define STRUCTMD_H

#include <stddef.h>
#include <stdint.h>

#ifndef STRUCTMD_API
#if defined(_WIN32)
#define STRUCTMD_API __declspec(dllimport)
#else
#define STRUCTMD_API __attribute__((visibility("default")))
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Version of the binary interface; raised whenever a name or a meaning below changes. */
#define STRUCTMD_ABI_VERSION 4

/** @name Status codes
 *  The values are fixed and part of the ABI.
 *  @{ */
#define STRUCTMD_OK 0               /**< success */
#define STRUCTMD_ERR_ARGUMENT 1     /**< null pointer, wrong array length, unknown name, bad option */
#define STRUCTMD_ERR_INPUT 2        /**< the JSON input is malformed or inconsistent (message names the path) */
#define STRUCTMD_ERR_STATE 3        /**< call not valid now (for example step before load) */
#define STRUCTMD_ERR_NUMERICAL 4    /**< NaN, Inf or blow-up detected (message names particle id and step) */
#define STRUCTMD_ERR_IO 5           /**< a file could not be read or written */
#define STRUCTMD_ERR_DEVICE 6       /**< GPU error, or a GPU was demanded and none is usable */
#define STRUCTMD_ERR_MEMORY 7       /**< out of host or device memory */
#define STRUCTMD_ERR_UNSUPPORTED 8  /**< a valid request this build or backend cannot do */
#define STRUCTMD_ERR_INTERNAL 9     /**< a bug: please report */
#define STRUCTMD_ERR_CALLBACK 10    /**< a host callback failed (message: the host's own, see structmd_set_callback_error) */
/** @} */

/** @name Compute flags
 *  For structmd_compute, combined with bitwise or.
 *  @{ */
#define STRUCTMD_FORCES 1u  /**< the force on every particle */
#define STRUCTMD_ENERGY 2u  /**< energies: every term and the per-particle split */
#define STRUCTMD_VIRIAL 4u  /**< the virial tensor */
/** @} */

/** A status code, one of the STRUCTMD_OK / STRUCTMD_ERR_* values. */
typedef int32_t structmd_status;

/** The opaque simulation handle. Create with structmd_create, release with structmd_destroy. */
typedef struct structmd_sim structmd_sim;

/** @name Version
 *  @{ */

/**
 * @return STRUCTMD_ABI_VERSION of the library actually loaded; a host compares it with the value of
 *         the header it was compiled against. Never fails.
 */
STRUCTMD_API int structmd_abi_version(void);

/**
 * @return the library version, "MAJOR.MINOR.PATCH"; a static string, valid for the life of the
 *         process, never freed. Never fails.
 */
STRUCTMD_API const char* structmd_version(void);

/** @} */

/** @name Handle and errors
 *  @{ */

/**
 * Creates a handle holding no simulation yet, on the backend and precision the options select.
 * May be called from any thread at any time.
 *
 * @param options_json  NULL, "" or a JSON object with the optional keys
 *                      "backend": "auto" (default: CUDA if a usable GPU exists, else CPU) | "cpu" | "cuda";
 *                      "device": GPU ordinal (default 0; under "mpi_comm", the rank's place among
 *                      the communicator's ranks on its node, modulo the node's GPUs);
 *                      "precision": "single" (default) | "mixed" | "double"
 *                      (mixed: state, forces and sums in double, pair potentials in single;
 *                      one the build lacks, CMake STRUCTMD_PRECISIONS, is STRUCTMD_ERR_UNSUPPORTED,
 *                      and the default is then the first of single, mixed and double it has);
 *                      "threads": CPU threads, >= 1 (default: all the OpenMP runtime offers);
 *                      "log": "quiet" | "warning" (default) | "info" | "debug";
 *                      "log_file": path, appended to (default: standard error);
 *                      "plugins": an array of paths of plugin libraries this handle loads, after
 *                      those loaded by structmd_load_plugin (docs/plugins.md);
 *                      "mpi_comm": an MPI communicator as a Fortran handle integer (MPI_Comm_c2f),
 *                      whose ranks share the batches of every input the handle loads; every call
 *                      on the handle, this one included, is then collective over it
 *                      (docs/c-api.md, MPI). The host
 *                      initialises and finalises MPI; the library never does;
 *                      "ghost_exchange": how the ghosts of spatial domains travel between ranks:
 *                      "auto" (default: "nccl" where the build has NCCL and the backend is CUDA,
 *                      else "host") | "host" (MPI through pinned host memory) | "nccl" (from GPU
 *                      to GPU on the engine's stream);
 *                      "pair_traversal": how pair terms walk their neighbours: "auto" (default:
 *                      "particles", the faster on both backends today) | "clusters" (pairs of
 *                      clusters of 4 particles, each cluster's partners loaded once for all its
 *                      particles) | "particles" (a list per particle). Same physics either way,
 *                      summed in another order; lists with a condition, exclusions or batches, boxes
 *                      under four list radii a side, spatial domains and expression or plugin
 *                      potentials walk per-particle lists whatever is asked (docs/c-api.md);
 *                      "step_graphs": true (default: the CUDA backend runs the steps of a call as
 *                      CUDA graphs) | false (each kernel launched as it comes: slower at small N,
 *                      for profilers and debuggers; no effect on the CPU backend).
 *                      Read during the call only.
 * @param[out] out      receives the new handle, owned by the caller until structmd_destroy; set to
 *                      NULL on failure.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for malformed options, an unknown key, a bad value, a
 *         "device" that does not exist, or out == NULL; STRUCTMD_ERR_DEVICE when "cuda" is demanded
 *         and no GPU is usable; STRUCTMD_ERR_UNSUPPORTED when "cuda" is demanded from a CPU-only
 *         build or from one whose CUDA module cannot load its CUDA libraries; STRUCTMD_ERR_IO when "log_file" cannot be opened; for "plugins", the statuses of
 *         structmd_load_plugin, the message naming the option; for "mpi_comm",
 *         STRUCTMD_ERR_UNSUPPORTED from a build without MPI and STRUCTMD_ERR_STATE before MPI_Init;
 *         for "ghost_exchange": "nccl", STRUCTMD_ERR_UNSUPPORTED from a build without NCCL and
 *         STRUCTMD_ERR_ARGUMENT on the CPU backend;
 *         STRUCTMD_ERR_MEMORY. On failure
 *         structmd_last_error(NULL) says why, on this thread.
 */
STRUCTMD_API structmd_status structmd_create(const char* options_json, structmd_sim** out);

/**
 * Releases the handle and everything it owns (host and device memory, open files, flushed and
 * closed). The handle must not be used afterwards, and no other thread may be using it meanwhile.
 * C cannot tell a destroyed handle from a live one in general: its memory may already hold something
 * else. As a courtesy, the handle is marked on destroy, so that a second destroy, or a call on the
 * handle, made before its memory is reused is refused (destroy does nothing; other calls return
 * STRUCTMD_ERR_ARGUMENT, saying so under structmd_last_error(NULL)) rather than crashing. Do not rely
 * on it: set the pointer to NULL after destroying.
 *
 * @param sim  the handle; NULL does nothing.
 */
STRUCTMD_API void structmd_destroy(structmd_sim* sim);

/**
 * The explanation of the last failure. A successful call does not clear it: check the status first,
 * then read the message.
 *
 * @param sim  a handle, or NULL for the last failure on the calling thread that had no handle to hold
 *             its message (a failed structmd_create, a call given a NULL handle).
 * @return the message of the last failed call on this handle, "" if none. The string is owned by the
 *         library and stays valid until the next call on the same handle (or, for NULL, the next
 *         failure without a handle on this thread); copy it to keep it.
 */
STRUCTMD_API const char* structmd_last_error(const structmd_sim* sim);

/** @} */

/** @name Loading
 *  @{ */

/**
 * Builds the simulation from a whole input document (UAMMD-structured JSON, comments allowed) and
 * puts it at its initial state: step and time from global.fundamental, else 0; velocities from the
 * state, else drawn from Maxwell-Boltzmann at the first integrator's temperature. Loading again
 * replaces the previous simulation (closing its output files) and clears the external forces and
 * force callbacks. A load is all or nothing: on failure the handle says why and keeps the simulation
 * it held before, if any, untouched and usable (step, time, state, outputs, callbacks); the new one
 * is built beside it, so for the duration of the call both occupy memory.
 *
 * @param sim   the handle.
 * @param path  a file path, read during the call.
 * @return STRUCTMD_OK; STRUCTMD_ERR_IO if the file cannot be read; STRUCTMD_ERR_INPUT if the document
 *         is malformed (line and column) or inconsistent (JSON path and what was expected);
 *         STRUCTMD_ERR_UNSUPPORTED for a valid input this build or backend cannot run;
 *         STRUCTMD_ERR_MEMORY if the system does not fit; STRUCTMD_ERR_DEVICE for a GPU failure.
 */
STRUCTMD_API structmd_status structmd_load_file(structmd_sim* sim, const char* path);

/**
 * As structmd_load_file, from text held by the caller. Relative output paths in the document are
 * relative to the process's working directory, as for structmd_load_file.
 *
 * @param sim   the handle.
 * @param json  the whole document, NUL-terminated, read during the call.
 * @return as structmd_load_file, less STRUCTMD_ERR_IO for reading the input.
 */
STRUCTMD_API structmd_status structmd_load_string(structmd_sim* sim, const char* json);

/** @} */

/** @name Plugins
 *  @{ */

/**
 * Loads a plugin library: a shared library built with structmd_add_plugin (the installed CMake
 * package) that adds force-field components, which inputs then name like built-in ones
 * (docs/plugins.md). The list of plugins loaded this way is process-wide and guarded by a lock, so
 * any thread may call this at any time: every handle created AFTER the call knows the plugin's
 * components; handles that exist already are not changed. A handle may also load plugins of its own
 * through the "plugins" option of structmd_create, which no other handle sees. The plugin is checked
 * before any of its code but two version queries runs: a plugin built for another plugin ABI or
 * another build of structmd (version, compiler, CUDA or not) is refused and not loaded. Loading a
 * path loaded already does nothing. An accepted library is never unloaded; a refused one is unloaded
 * again, its registration never called.
 *
 * @param path  the plugin library's file path, read during the call.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for path == NULL, a library that is not a structmd
 *         plugin, or a plugin whose component names are known already (built-in or from another
 *         plugin); STRUCTMD_ERR_IO when the file does not exist or cannot be loaded (the message has
 *         the loader's reason); STRUCTMD_ERR_UNSUPPORTED for a plugin built for another plugin ABI
 *         or another build of structmd (the message says both); STRUCTMD_ERR_MEMORY. On failure
 *         structmd_last_error(NULL) says why, on this thread.
 */
STRUCTMD_API structmd_status structmd_load_plugin(const char* path);

/** @} */

/** @name Advancing
 *  @{ */

/**
 * Advances nsteps integration steps along integrator.schedule, switching integrators where the
 * schedule says, firing each simulationStep at its interval. Past the end of the schedule the
 * integrator of its last stage (the last row with steps > 0) goes on, so a coupling driver decides
 * the length of the run as it goes; the final state of the schedule is still given to the
 * measures as when the schedule ends there. A flow-control step of the input (AFMMaxForce, an
 * escape time with stopSimulation) may end the call early, at the step whose state met its
 * condition: the call returns STRUCTMD_OK there and structmd_get_info's "stopped_by" names the step.
 * Outputs (trajectory writers, measures) fire at the steps of their interval as they are reached,
 * the step the call ends on included, and every file is flushed after each firing: when the call
 * returns, a host stepping in a loop finds on disk every frame and row due up to the current step,
 * as after LAMMPS's "run N" or OpenMM's step(n), and a host may stop and destroy the handle at any
 * point without losing one. A frame off the interval is written only at the schedule's end (the
 * final state above): a host that wants one where its own loop ends makes the schedule end there
 * (its final_step), as the launcher's --steps does.
 * Needs a load. Returns when the steps are finished on the device, so wall-clock time around the
 * call is the time of the steps.
 *
 * @param sim     the handle.
 * @param nsteps  number of steps, >= 0; 0 does nothing.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load, or when the input has no integrator to step; STRUCTMD_ERR_ARGUMENT for nsteps < 0; STRUCTMD_ERR_IO when an output cannot be written;
 *         STRUCTMD_ERR_MEMORY when the device cannot hold what a step needs (a neighbour list, say);
 *         STRUCTMD_ERR_DEVICE for a GPU failure; STRUCTMD_ERR_NUMERICAL when a position, velocity
 *         or force became non-finite or a particle moved farther than the neighbour-list skin in
 *         one step: the message names the step, particle id and quantity, and the state (positions,
 *         velocities, step, time, the integrators' own state) is back where the call started; files
 *         that measures wrote during the call stay written; STRUCTMD_ERR_INPUT, naming the
 *         parameter's path, for the few parameters that can only be judged against the state when
 *         their integrator starts (a hydrodynamics integrator without a radius takes its group's
 *         radii, whose near field may reach beyond half the box); STRUCTMD_ERR_UNSUPPORTED when a
 *         hydrodynamics integrator finds the box changed since it started.
 */
STRUCTMD_API structmd_status structmd_step(structmd_sim* sim, int64_t nsteps);

/**
 * Advances until the schedule ends, or until a flow-control step ends the call (as structmd_step);
 * at the schedule's end or past it, does nothing. Needs a load.
 *
 * @param sim  the handle.
 * @return as structmd_step.
 */
STRUCTMD_API structmd_status structmd_run(structmd_sim* sim);

/**
 * Evaluates now, without advancing time, what flags asks for, unless it is already current (then it
 * costs nothing). Getters do this themselves; this call lets a host choose when the work happens.
 * Needs a load.
 *
 * @param sim    the handle.
 * @param flags  STRUCTMD_FORCES, STRUCTMD_ENERGY and STRUCTMD_VIRIAL, combined with bitwise or.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for unknown bits; STRUCTMD_ERR_STATE before a load.
 */
STRUCTMD_API structmd_status structmd_compute(structmd_sim* sim, uint32_t flags);

/** @} */

/** @name Reading particle data
 *  Each needs a load. The arrays are the caller's, in ascending particle-id order; n must equal the
 *  number of particles (STRUCTMD_ERR_ARGUMENT otherwise, and nothing is written).
 *  @{ */

/**
 * @param sim      the handle.
 * @param[out] n   number of particles of the loaded simulation.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load.
 */
STRUCTMD_API structmd_status structmd_get_num_particles(const structmd_sim* sim, int64_t* n);

/**
 * @param sim        the handle.
 * @param[out] ids   int64_t[n], the particle ids in ascending order (0..n-1).
 * @param n          the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_ids(structmd_sim* sim, int64_t* ids, int64_t n);

/**
 * @param sim        the handle.
 * @param[out] xyz   double[3n], positions wrapped into the box [-L/2, L/2) (length).
 * @param n          the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_positions(structmd_sim* sim, double* xyz, int64_t n);

/**
 * @param sim      the handle.
 * @param[out] v   double[3n], velocities (length/time).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_velocities(structmd_sim* sim, double* v, int64_t n);

/**
 * Orientations of the particles as unit quaternions, scalar part first (UAMMD-structured's
 * "direction": the body frame's axes in the lab frame are the columns of R(q)). A simulation whose
 * input gives no directions, and whose integrators turn no particle, has every particle at the
 * identity [1, 0, 0, 0] (and keeps no orientation array until structmd_set_orientations).
 *
 * @param sim      the handle.
 * @param[out] q   double[4n], [q0, q1, q2, q3] per particle (dimensionless).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_orientations(structmd_sim* sim, double* q, int64_t n);

/**
 * The torque on each particle from the terms that act on orientations (["External","ConstantTorque"]),
 * in the lab frame; zero where no such term acts. Evaluated with the forces, as structmd_get_forces:
 * a simulation whose integrators turn no particle starts keeping torques at the first call, and from
 * then on evaluates them with every force evaluation.
 *
 * @param sim      the handle.
 * @param[out] t   double[3n], torques (energy).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_torques(structmd_sim* sim, double* t, int64_t n);

/**
 * The magnetic moment of each particle in the lab frame: the magnitude of the state's magnetization
 * times its body-frame direction turned by the particle's orientation (mu = M R(q) m). Zero for a
 * simulation whose state gives no magnetization.
 *
 * @param sim      the handle.
 * @param[out] m   double[3n], moments (energy/field).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_magnetic_moments(structmd_sim* sim, double* m, int64_t n);

/**
 * The forces are evaluated first when stale (after a load, structmd_set_positions or
 * structmd_set_box); otherwise they are those the integrator computed at the current positions, so
 * reading them after a step costs only the copy.
 *
 * @param sim      the handle.
 * @param[out] f   double[3n], the total force on each particle, external forces included
 *                 (energy/length).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE; STRUCTMD_ERR_NUMERICAL when a force
 *         is not finite (overlapping particles, say), and nothing is written.
 */
STRUCTMD_API structmd_status structmd_get_forces(structmd_sim* sim, double* f, int64_t n);

/**
 * @param sim      the handle.
 * @param[out] e   double[n], potential energy per particle (energy): each interaction's energy is
 *                 split equally among the particles it involves, so the values sum to the potential
 *                 energy.
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_particle_energies(structmd_sim* sim, double* e, int64_t n);

/**
 * @param sim      the handle.
 * @param[out] m   double[n], masses, after the state's per-particle overrides (mass).
 * @param n        the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_masses(structmd_sim* sim, double* m, int64_t n);

/**
 * @param sim               the handle.
 * @param[out] type_index   int32_t[n], each particle's row in global.types (0-based).
 * @param n                 the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_types(structmd_sim* sim, int32_t* type_index, int64_t n);

/** @} */

/** @name Reading global quantities
 *  Each needs a load (STRUCTMD_ERR_STATE before one).
 *  @{ */

/**
 * @param sim         the handle.
 * @param term        "potential", "kinetic", "total" (kinetic + potential + external), "external"
 *                    (the host's field energy given by structmd_set_external_energy, 0 unless
 *                    given; a topology.forceField entry called "external" keeps the name, and the
 *                    host's energy is then read only as part of "total"), or the name of a
 *                    topology.forceField entry (its share of the potential energy). Any term may
 *                    end in "@batch:K" for the share of the particles whose batchId is K, for
 *                    example "potential@batch:2"; the host's energy belongs to no batch, so
 *                    "total@batch:K" leaves it out and "external@batch:K" is refused (unless every
 *                    particle has batchId K: then "@batch:K" means the whole system).
 * @param[out] value  the energy, in the input's energy unit.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for an unknown term (the message lists the known ones) or
 *         a K that no particle has; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_energy(structmd_sim* sim, const char* term, double* value);

/**
 * @param sim      the handle.
 * @param[out] w   the virial tensor W = sum over pair terms of (r_i - r_j) (x) F_ij (minimum image;
 *                 multi-body terms add sum_k d_k (x) F_k), row-major 3x3 (w[3a + b] = W_ab, energy):
 *                 the convention of LAMMPS's pressure virial. External forces set by the host are
 *                 not part of it.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_virial(structmd_sim* sim, double w[9]);

/**
 * @param sim      the handle.
 * @param[out] p   pressure P = (2K + trace W) / (3V), K the kinetic energy, V the box volume
 *                 (energy/length^3). While the next step runs an overdamped (Brownian) integrator,
 *                 which has no velocities, P = (N k_B T + trace W / 3) / V at its bath temperature T.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_pressure(structmd_sim* sim, double* p);

/**
 * @param sim      the handle.
 * @param[out] t   temperature T = 2K / (3 N k_B), K the kinetic energy, N the particles of mass > 0,
 *                 k_B the input units' Boltzmann constant. While the next step runs an overdamped
 *                 (Brownian) integrator, which has no velocities, the bath temperature of that
 *                 integrator (the T of structmd_get_pressure).
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_temperature(structmd_sim* sim, double* t);

/**
 * @param sim            the handle.
 * @param[out] lengths   box edge lengths Lx, Ly, Lz; the box is orthorhombic and spans [-L/2, L/2)
 *                       along each periodic axis; an open (non-periodic) axis reads as infinity
 *                       (INFINITY), given as 0 or "inf" in the input or by structmd_set_box.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_box(structmd_sim* sim, double lengths[3]);

/**
 * @param sim         the handle.
 * @param[out] step   the current step number: global.fundamental's currentStep, else 0, plus one
 *                    per integration step taken.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_step(const structmd_sim* sim, int64_t* step);

/**
 * @param sim      the handle.
 * @param[out] t   the current simulation time: the initial simulationTime plus the time step of
 *                 every step taken.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_time(const structmd_sim* sim, double* t);

/** @} */

/** @name Transversers
 *  A transverser is a computation over the pairs of particles run on the backend, each particle
 *  getting its own total (UAMMD's Transverser; docs/c-api.md). Each needs a load.
 *  @{ */

/**
 * Runs an expression transverser once, for the current state: each particle's sum over its pairs
 * (i, j), j != i, of an expression of the pair. The first call with a given expression and cutoff
 * prepares it (a neighbour list; on CUDA the expression is compiled into the traversal's kernel, as
 * an Expression potential is) and later calls reuse it. The list is a pair term's, kept up to date
 * by the steps, where one offers every pair within the cutoff (no condition, no exclusions), else
 * one of the transverser's own.
 *
 * @param sim        the handle.
 * @param compute    the expression, in the language of the Expression potentials, of r (the
 *                   distance), dx, dy, dz (r_j - r_i by minimum image), type_i, type_j (rows of
 *                   global.types), charge_i, charge_j, radius_i, radius_j, mass_i and mass_j; a
 *                   comparison is 1 or 0, so "r < 1.5" gives coordination numbers.
 * @param cutoff     > 0: only the pairs closer than cutoff, found through a neighbour list; 0: every
 *                   pair (the nearest periodic image of each other particle), at a cost of n^2.
 * @param[out] sums  double[n], each particle's sum, in id order.
 * @param n          the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_INPUT for an expression that does not parse or names an unknown
 *         variable, or a cutoff that is negative or not finite (the message says which);
 *         STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE; STRUCTMD_ERR_UNSUPPORTED under spatial domains
 *         or batches over ranks.
 */
STRUCTMD_API structmd_status structmd_traverse_expression(structmd_sim* sim, const char* compute, double cutoff,
                                                          double* sums, int64_t n);

/**
 * The number of values per particle that a registered transverser writes (1 for a count, 3 for a
 * force...): structmd_traverse fills n = values x (number of particles) doubles. Needs no load.
 *
 * @param sim          the handle.
 * @param name         the transverser's name, as a plugin the handle knows registered it
 *                     (docs/plugins.md, "Transversers").
 * @param[out] values  its values per particle, >= 1.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for a NULL pointer or a name no plugin of the handle
 *         registered (the message lists those it knows).
 */
STRUCTMD_API structmd_status structmd_transverser_values(structmd_sim* sim, const char* name, int* values);

/**
 * Runs a transverser that a plugin registered (written in C++ against the Transverser contract,
 * docs/plugins.md) once, for the current state, and copies each particle's values to the host. The
 * plugin's code runs on the handle's backend (for CUDA, a plugin compiled with nvcc). The neighbour
 * list is a pair term's, kept up to date by the steps, where one offers every pair within the cutoff
 * (no condition, no exclusions); else one of the cutoff's own, made at the first call with it and
 * reused after.
 *
 * @param sim         the handle.
 * @param name        the transverser's name.
 * @param parameters  NULL, "" or a JSON object: the transverser's named parameters (absent ones
 *                    take their defaults) and, optionally, "group": the name of a group of the force
 *                    field (["Groups", "GroupsList"]); only its particles are traversed and pair
 *                    with each other, the others get 0.
 * @param cutoff      > 0: only the pairs closer than cutoff, found through a neighbour list; 0: every
 *                    pair (the nearest periodic image, or in an open box the particle itself), at a
 *                    cost of n^2.
 * @param[out] out    double[n]: particle i's values at out[values * i ...] (structmd_transverser_values),
 *                    particles in id order.
 * @param n           values x the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for an unknown name, parameters that are not a JSON
 *         object, a wrong n or a NULL pointer; STRUCTMD_ERR_INPUT for a parameter it does not take, a
 *         value that breaks its rule, an unknown group or a negative or non-finite cutoff (the message
 *         names it); STRUCTMD_ERR_STATE without a load; STRUCTMD_ERR_UNSUPPORTED on a backend the
 *         plugin was not compiled for, under spatial domains or batches over ranks.
 */
STRUCTMD_API structmd_status structmd_traverse(structmd_sim* sim, const char* name, const char* parameters,
                                               double cutoff, double* out, int64_t n);

/** @} */

/** @name Changing the state
 *  Each needs a load; none advances time.
 *  @{ */

/**
 * Replaces all positions (wrapped into the box) and marks forces, energies, virial and the
 * neighbour list stale.
 *
 * @param sim  the handle.
 * @param xyz  double[3n], the new positions (length).
 * @param n    the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if any value is not finite (the
 *         message names the particle) or n is wrong; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_positions(structmd_sim* sim, const double* xyz, int64_t n);

/**
 * Replaces all velocities.
 *
 * @param sim  the handle.
 * @param v    double[3n], the new velocities (length/time).
 * @param n    the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if any value is not finite or n is
 *         wrong; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_velocities(structmd_sim* sim, const double* v, int64_t n);

/**
 * Replaces all orientations, and marks forces, energies and virial stale (terms may read
 * orientations). A simulation without orientations keeps them from this call on.
 *
 * @param sim  the handle.
 * @param q    double[4n], unit quaternions [q0, q1, q2, q3], scalar part first (dimensionless).
 * @param n    the number of particles.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if any value is not finite, any
 *         quaternion's squared norm differs from 1 by more than 1e-6 (the message names the
 *         particle), or n is wrong; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_orientations(structmd_sim* sim, const double* q, int64_t n);

/**
 * Sets the box edge lengths, keeping fractional coordinates (particles are scaled with the box, as
 * a barostat would) along the axes periodic before and after; along an axis open before or after,
 * positions are kept as they are.
 *
 * @param sim      the handle.
 * @param lengths  the new edges Lx, Ly, Lz: each > 0 and <= 1e15, or 0 or infinity for an open
 *                 (non-periodic) axis, which reads back as infinity.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if a length is negative, NaN or above
 *         1e15 but finite, or if a cutoff of the force field would exceed half the box;
 *         STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_box(structmd_sim* sim, const double lengths[3]);

/**
 * Adds f to each particle's force at every force evaluation, during steps and in getters, until
 * replaced. This is how a coupled code applies its field. The array is copied. Forces already
 * evaluated at the present positions change by the field's difference in place, without a new
 * force evaluation (so a field set every step costs no extra evaluation; the sum may differ from
 * a fresh evaluation in the last bit). The engine cannot know the energy of this field: the host may give it with structmd_set_external_energy; the field
 * is part of no virial. A new load clears it.
 *
 * @param sim  the handle.
 * @param f    double[3n], the forces (energy/length); NULL with n = 0 clears them, and the energy
 *             given by structmd_set_external_energy with them.
 * @param n    the number of particles, or 0 with f = NULL.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if any value is not finite or n is
 *         wrong; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_external_forces(structmd_sim* sim, const double* f, int64_t n);

/**
 * Gives the energy of the host's external field (the one whose forces structmd_set_external_forces
 * and structmd_set_external_forces_of apply), which the engine cannot compute itself. It is the
 * energy term "external" of structmd_get_energy, part of "total" (not of "potential" nor of the
 * per-particle energies, which stay the force field's), and the column "external" of the
 * thermodynamic measure, whose "total" includes it. It holds until replaced; clearing the external
 * forces (NULL, n = 0) or a new load sets it back to 0. It is not stored in checkpoints.
 *
 * @param sim     the handle.
 * @param energy  the field's energy at the current positions (energy).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, if energy is not finite;
 *         STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_external_energy(structmd_sim* sim, double energy);

/** @} */

/** @name Subsets by id
 *  Reading and changing m particles chosen by id, without moving the others: values are double[3m]
 *  laid out x, y, z per particle in the order of ids (not sorted). Only the m ids and m values
 *  cross between the host and the backend (on CUDA, a kernel gathers or scatters them on the
 *  device), so the cost follows m, not the number of particles. Each needs a load.
 *  Every argument is checked before anything is written or changed: m < 0, ids or values NULL with
 *  m > 0, an id that is not a particle's (0..n-1), an id given twice, or (setters) a value that is
 *  not finite is STRUCTMD_ERR_ARGUMENT naming the argument, index and particle id, and nothing is
 *  written or changed. m = 0 does nothing (both pointers may then be NULL).
 *  @{ */

/**
 * @param sim        the handle.
 * @param ids        int64_t[m], the particle ids, each at most once.
 * @param m          the number of ids, >= 0.
 * @param[out] xyz   double[3m], positions wrapped into the box [-L/2, L/2) (length), as
 *                   structmd_get_positions gives them.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_positions_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* xyz);

/**
 * @param sim      the handle.
 * @param ids      int64_t[m], the particle ids, each at most once.
 * @param m        the number of ids, >= 0.
 * @param[out] v   double[3m], velocities (length/time).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* v);

/**
 * The forces are evaluated first when stale, as for structmd_get_forces (all of them: a force
 * needs every neighbour); only the m asked for are copied out.
 *
 * @param sim      the handle.
 * @param ids      int64_t[m], the particle ids, each at most once.
 * @param m        the number of ids, >= 0.
 * @param[out] f   double[3m], the total force on each, external forces included (energy/length).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT; STRUCTMD_ERR_STATE; STRUCTMD_ERR_NUMERICAL when one
 *         of these m forces is not finite, and nothing is written.
 */
STRUCTMD_API structmd_status structmd_get_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* f);

/**
 * Replaces the positions of the m particles as structmd_set_positions does for all: each is wrapped
 * into the box with its image count taken from the position given (so the unwrapped position is the
 * one given), and forces, energies, virial and the neighbour lists become stale. The other
 * particles keep their positions and images.
 *
 * @param sim  the handle.
 * @param ids  int64_t[m], the particle ids, each at most once.
 * @param m    the number of ids, >= 0.
 * @param xyz  double[3m], the new positions (length).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, as for the group, or for a
 *         coordinate beyond 1e8 box lengths; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_positions_of(structmd_sim* sim, const int64_t* ids, int64_t m,
                                                       const double* xyz);

/**
 * Replaces the velocities of the m particles; the others keep theirs.
 *
 * @param sim  the handle.
 * @param ids  int64_t[m], the particle ids, each at most once.
 * @param m    the number of ids, >= 0.
 * @param v    double[3m], the new velocities (length/time).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m,
                                                        const double* v);

/**
 * Replaces the external force of the m particles (see structmd_set_external_forces); the others
 * keep theirs. Without external forces yet, the others get a zero force first. It composes with
 * structmd_set_external_forces: a whole array set before is changed only at these ids, and a whole
 * array set after replaces everything. The forces are evaluated again at the next getter or step.
 *
 * @param sim  the handle.
 * @param ids  int64_t[m], the particle ids, each at most once.
 * @param m    the number of ids, >= 0.
 * @param f    double[3m], the forces (energy/length).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing; STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_set_external_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m,
                                                             const double* f);

/** @} */

/** @name Run-time parameters
 *  Parameters of the loaded input changed between steps, named by their path in the input's own
 *  terms: "global.ensemble.temperature" (the default temperature of every integrator that does not
 *  give its own), "integrator.NAME.parameters.KEY" (timeStep, frictionConstant, temperature, ...
 *  of the integrator entry NAME; not the schedule) and "topology.forceField.NAME.parameters.KEY"
 *  (every number an entry takes under "parameters": a Common_ bond's K, a neighbour list's
 *  cutOffVerletFactor, a pair term's cutOffFactor, an Expression entry's constant, startStep ...).
 *  Values in tables (per-bond or per-type-pair columns), strings, booleans and the box
 *  (structmd_set_box) are not run-time parameters. Each needs a load.
 *  @{ */

/**
 * Changes one parameter from the next force evaluation or step on. The value is written into the
 * loaded input and the force field and the integrators are read again from it with every check of
 * a load, then made again, keeping the positions, velocities, step, time, external forces and the
 * integrators' own state; cached forces, energies and virial are dropped. A cutoff that grows is
 * honoured: the neighbour lists are made again for the new cutoffs (a cutoff not shorter than half
 * the present box is refused). An Expression entry is compiled again (on CUDA this takes seconds
 * for a NonBonded entry). The call costs about what reading the input costs, so it is meant for
 * changes between chunks of steps, not for every step. A new load forgets the changes.
 *
 * @param sim    the handle.
 * @param path   the parameter, as above; a key the entry does not give yet is added, if its component
 *               takes it.
 * @param value  the new value, in the input's units; it must satisfy the rule the input states for
 *               that parameter (a time step > 0, say).
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT, changing nothing, for a path that names no run-time
 *         parameter (no such entry, a key its component does not take, a string, a table column, the
 *         schedule) or a value the input's rules refuse, the message naming the path and why;
 *         STRUCTMD_ERR_STATE; STRUCTMD_ERR_UNSUPPORTED, STRUCTMD_ERR_DEVICE or STRUCTMD_ERR_MEMORY
 *         when the force field cannot be made again, changing nothing.
 */
STRUCTMD_API structmd_status structmd_set_parameter(structmd_sim* sim, const char* path, double value);

/**
 * Reads a parameter as the loaded input gives it, or as structmd_set_parameter last set it.
 *
 * @param sim         the handle.
 * @param path        the parameter, as for structmd_set_parameter.
 * @param[out] value  its value, in the input's units.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for a path that names no run-time parameter, or one the
 *         input leaves to its default (the message says so); STRUCTMD_ERR_STATE.
 */
STRUCTMD_API structmd_status structmd_get_parameter(structmd_sim* sim, const char* path, double* value);

/** @} */

/** @name Force callbacks
 *  The host's own force term, evaluated by the host inside the engine's loop: at every force
 *  evaluation whose positions the callback has not yet seen (once per step of an integrator, in
 *  getters after positions changed, in structmd_compute), the engine calls it, and what it adds
 *  becomes part of the forces, of the energy term "callback" (part of "potential" and "total" for
 *  the whole system, of no batch and not of the per-particle energies) and of the virial. A host
 *  callback and a device callback may be set at once; both are called. They are called on the
 *  thread that made the structmd call, never concurrently, and must not call structmd functions on
 *  the same handle other than structmd_set_callback_error: such a call is STRUCTMD_ERR_STATE, and
 *  structmd_destroy of that handle does nothing. A failure (a non-zero return, a C++
 *  exception, a non-finite value) stops the call with STRUCTMD_ERR_CALLBACK; inside structmd_step the
 *  state goes back to where the call started, as for a blow-up. A new load clears both callbacks;
 *  checkpoints do not hold them.
 *  @{ */

/**
 * A host force callback. Every array is the engine's, valid during the call only.
 *
 * @param positions  double[3n], positions wrapped into the box, ascending particle id (length).
 * @param forces     double[3n], zero on entry: the forces to add (energy/length).
 * @param n          the number of particles.
 * @param energy     zero on entry: the energy of these forces (energy).
 * @param virial     zero on entry: their virial, sum_k r_k (x) F_k in the convention of
 *                   structmd_get_virial, row-major (energy); leave it zero if unknown.
 * @param step       the step the positions belong to (the step being completed, inside a step).
 * @param user_data  the pointer given to structmd_set_force_callback.
 * @return 0 on success; anything else stops the engine's call with STRUCTMD_ERR_CALLBACK.
 */
typedef int32_t (*structmd_force_callback)(const double* positions, double* forces, int64_t n, double* energy,
                                           double virial[9], int64_t step, void* user_data);

/**
 * A device force callback: the engine's own arrays, without a copy. On the CUDA backend they are
 * device pointers and stream is the cudaStream_t of the engine's work (launch on it, or
 * synchronise with it); on the CPU backend they are host pointers and stream is NULL.
 *
 * @param positions  n records of four reals {x, y, z, w} (w is the engine's, do not read it):
 *                   positions wrapped into the box, ascending particle id.
 * @param forces     n records of four reals {fx, fy, fz, w}, zero on entry: the forces to add to x,
 *                   y, z (leave w).
 * @param n          the number of particles.
 * @param real_size  the size of one real in bytes: 4 in single precision, 8 in mixed and double.
 * @param energy     host memory, zero on entry: the energy of these forces.
 * @param virial     host memory, zero on entry: their virial, as for structmd_force_callback.
 * @param step       the step the positions belong to.
 * @param stream     the engine's cudaStream_t on CUDA, NULL on the CPU backend.
 * @param user_data  the pointer given to structmd_set_device_force_callback.
 * @return 0 on success; anything else stops the engine's call with STRUCTMD_ERR_CALLBACK.
 */
typedef int32_t (*structmd_device_force_callback)(const void* positions, void* forces, int64_t n,
                                                  int32_t real_size, double* energy, double virial[9], int64_t step,
                                                  void* stream, void* user_data);

/**
 * Sets, replaces or clears (NULL) the host force callback. Forces, energies and virial evaluated
 * before are stale from now on. Needs a load.
 *
 * @param sim        the handle.
 * @param callback   the callback, or NULL to clear it.
 * @param user_data  passed to every call of callback, untouched; may be NULL.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load.
 */
STRUCTMD_API structmd_status structmd_set_force_callback(structmd_sim* sim, structmd_force_callback callback,
                                                         void* user_data);

/**
 * Sets, replaces or clears (NULL) the device force callback, as structmd_set_force_callback.
 *
 * @param sim        the handle.
 * @param callback   the callback, or NULL to clear it.
 * @param user_data  passed to every call of callback, untouched; may be NULL.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load.
 */
STRUCTMD_API structmd_status structmd_set_device_force_callback(structmd_sim* sim,
                                                                structmd_device_force_callback callback,
                                                                void* user_data);

/**
 * Called by a callback before it returns non-zero: message becomes the text of
 * structmd_last_error for the failed call (after the step and the callback's return value). Outside
 * a callback it has no effect.
 *
 * @param sim      the handle the callback was called for.
 * @param message  the reason, copied.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for message == NULL.
 */
STRUCTMD_API structmd_status structmd_set_callback_error(structmd_sim* sim, const char* message);

/** @} */

/** @name Zero-copy views
 *  The engine's own arrays as DLPack tensors (dlpack.h, DLPack 0.6 or later), for CuPy, PyTorch,
 *  JAX or NumPy to read without a copy.
 *  @{ */

/** DLPack's DLManagedTensor, declared by dlpack.h; the header does not need it. */
typedef struct DLManagedTensor structmd_dlpack_tensor;

/**
 * A view of "positions" (wrapped into the box), "velocities" or "forces" (evaluated first when
 * stale): a DLPack tensor of shape (n, 3), strides (4, 1) in elements, float32 in single precision
 * and float64 in mixed and double, rows in ascending particle id, on the GPU (kDLCUDA, the handle's
 * device) or in host memory (kDLCPU). The engine's work is complete when the call returns.
 * The data are valid until the next call on the handle that steps, sets anything, loads, changes a
 * parameter or destroys it; reading them after that reads freed or changed memory. The view is
 * read-only: writing through it is undefined. Release it with its deleter (a DLPack consumer does
 * so); the deleter does not touch the handle and may be called after it is destroyed.
 *
 * @param sim        the handle.
 * @param quantity   "positions", "velocities" or "forces".
 * @param[out] view  the new tensor.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for a NULL pointer or an unknown quantity (the message
 *         lists the known ones); STRUCTMD_ERR_STATE before a load; STRUCTMD_ERR_NUMERICAL when the
 *         forces are not finite.
 */
STRUCTMD_API structmd_status structmd_get_view(structmd_sim* sim, const char* quantity, structmd_dlpack_tensor** view);

/**
 * Runs a transverser that a plugin registered once, as structmd_traverse does, and lends its output
 * as a DLPack tensor instead of copying it to the host: on CUDA the values stay on the GPU. Shape (n)
 * for a transverser of one value per particle, (n, values) otherwise (structmd_transverser_values),
 * contiguous (strides (1) or (values, 1) in elements), rows in ascending particle id, particles
 * outside the group 0; float32 in single precision and float64 in mixed and double; on the GPU
 * (kDLCUDA, the handle's device) or in host memory (kDLCPU). The engine's work is complete when the
 * call returns.
 * The data are the engine's output array of its registered transversers: valid until the next call
 * on the handle that runs a registered transverser (structmd_traverse, structmd_traverse_view, a
 * ["TransverserMeasure","Plugin"] step: any call that steps), sets anything, loads, changes a
 * parameter or destroys it. Writing through the view changes nothing the engine reads. Release it
 * with its deleter (a DLPack consumer does so); the deleter does not touch the handle and may be
 * called after it is destroyed.
 *
 * @param sim         the handle.
 * @param name        the transverser's name.
 * @param parameters  NULL, "" or a JSON object, as for structmd_traverse.
 * @param cutoff      > 0: the pairs closer than cutoff, over a neighbour list; 0: every pair.
 * @param[out] view   the new tensor.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT for an unknown name (the message lists the known ones),
 *         parameters that are not a JSON object or a NULL pointer; STRUCTMD_ERR_INPUT for a parameter
 *         it does not take, a value that breaks its rule, an unknown group or a negative or
 *         non-finite cutoff; STRUCTMD_ERR_STATE without a load; STRUCTMD_ERR_UNSUPPORTED on a backend
 *         the plugin was not compiled for, under spatial domains or batches over ranks. On failure
 *         *view is left as it was.
 */
STRUCTMD_API structmd_status structmd_traverse_view(structmd_sim* sim, const char* name, const char* parameters,
                                                    double cutoff, structmd_dlpack_tensor** view);

/** @} */

/* ---- structmd additions to the contract ---- */

/** @name Checkpoints
 *  @{ */

/**
 * Writes the dynamic state to a file: step, time, box, positions (with their periodic images),
 * velocities, orientations (when the simulation has them), external forces and the integrators' own
 * state, in the engine's working precision. The file is written beside the target and renamed over
 * it once complete, so an interrupted write never replaces a good checkpoint. The forces are not stored: they are recomputed from the
 * positions, so a restarted run continues the same trajectory (bit for bit on the CPU backend, to
 * rounding on CUDA).
 *
 * @param sim   the handle.
 * @param path  the file; it carries a format version and a checksum.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load; STRUCTMD_ERR_IO if the file cannot be
 *         written.
 */
STRUCTMD_API structmd_status structmd_save_checkpoint(structmd_sim* sim, const char* path);

/**
 * Restores the state saved by structmd_save_checkpoint into a simulation loaded from the same input
 * (same particles, precision and schedule start). The whole file is read and checked before
 * anything changes: on failure the handle keeps its state.
 *
 * @param sim   the handle.
 * @param path  the file.
 * The values are checked as the load and the setters check them, since a file can be edited and its
 * checksum recomputed: each box length finite, > 0, <= 1e15 and more than twice the largest cutoff;
 * a finite time, positions (within 1e8 box lengths), velocities, masses, orientations and
 * magnetic moments; type indices of this simulation.
 *
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load; STRUCTMD_ERR_IO for a missing, truncated or
 *         corrupt file, another format version, a checkpoint of another simulation, or values the
 *         checks above refuse (the message says which, naming the particle id).
 */
STRUCTMD_API structmd_status structmd_load_checkpoint(structmd_sim* sim, const char* path);

/** @} */

/** @name Introspection
 *  @{ */

/**
 * Describes the handle as a JSON object written into buffer (NUL-terminated), with or without a
 * load: {"version": as structmd_version, "backend": "cpu" | "cuda" (the one chosen, also under
 * "auto"), "precision": "single" | "mixed" | "double", "precisions_compiled": those the build has
 * (single to double), "device": the GPU's name or "host CPU",
 * "threads": CPU threads of the CPU backend (0 on CUDA), "loaded": bool, "particles": n (0 before
 * a load), "final_step": step at which the schedule ends (-1 before a load), "stopped_by": the
 * simulationStep entry that ended the last step call early, or null, "mpi": {"compiled": bool,
 * "ranks": ranks of the "mpi_comm" communicator (1 without), "rank": this one's (0 without),
 * "node_rank": its place among the ranks of its node, "nccl": whether the build sends spatial
 * domains' ghosts from GPU to GPU},
 * and under parallel tempering "replica_exchange": {"temperatures", and per pair of neighbouring
 * temperatures "attempts", "accepted", "acceptance"} (docs/input-format.md)}. Keys may be added in
 * later versions.
 *
 * @param sim          the handle.
 * @param[out] buffer  receives the text; may be NULL when size is 0.
 * @param size         capacity of buffer in bytes.
 * @param[out] needed  optional (may be NULL): bytes the text needs, NUL included; set also when
 *                     size is too small, so a host may call once with size 0, then with needed.
 * @return STRUCTMD_OK; STRUCTMD_ERR_ARGUMENT if buffer is too small (nothing useful is written then).
 */
STRUCTMD_API structmd_status structmd_get_info(const structmd_sim* sim, char* buffer, size_t size,
                                               size_t* needed);

/**
 * What the engine has done since the simulation was loaded, as a JSON object written into buffer
 * (NUL-terminated): {"force_evaluations", "energy_evaluations", "virial_evaluations": passes over
 * the force field that evaluated each quantity; "neighbour_list_builds"; "host_to_device_bytes",
 * "device_to_host_bytes": bytes copied between the host and the backend's buffers (on the CPU
 * backend, between the caller's arrays and the engine's); "device_memory_bytes": bytes the
 * handle's buffers hold on its backend now (GPU memory on CUDA, the CUDA context not counted);
 * "step_graphs_captured", "step_graphs_replayed": batches of up to 16 steps captured as CUDA
 * graphs, and batches that replayed one (0 on the CPU); "domain_rebuilds": how often a system
 * split in space over MPI ranks rebuilt its domains (0 otherwise); "steps_joined": steps whose
 * last pass over the particles the integrator joined to the next step's first, because nothing
 * read the state between them (velocity Verlet's closing and opening half kicks as one pass: the
 * same arithmetic, so the same trajectory; never the last step of a call, nor a step before one
 * where a simulation step fires, nor with a force callback set)}. Under spatial domains the
 * other counts are this rank's. It shows that work a scene does not
 * need is skipped: no list without pair terms, no energy between the steps that read it, no
 * particle data leaving the device while stepping.
 *
 * @param sim          the handle.
 * @param[out] buffer  receives the text; 512 bytes always suffice.
 * @param size         capacity of buffer in bytes.
 * @return STRUCTMD_OK; STRUCTMD_ERR_STATE before a load, or when the input has no integrator to step; STRUCTMD_ERR_ARGUMENT if buffer is NULL or
 *         too small (the message gives the size needed).
 */
STRUCTMD_API structmd_status structmd_get_counters(structmd_sim* sim, char* buffer, size_t size);

/** @} */

#ifdef __cplusplus
}
#endif

#endif /* STRUCTMD_H */
