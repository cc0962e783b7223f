// UAMMD's side of tests/benchmarks/hydrodynamics_benchmark.py (issue 33): for one method and size, the
// steps per second of UAMMD's own integrator on the benchmark's system, or the relative RMS error of
// its dt M F against that script's kind of reference. UAMMD is used as a library through its headers;
// its precision is chosen when this file is compiled (-DDOUBLE_PRECISION, see build.sh).
//
// usage: uammd_hydrodynamics MODE --method M --n N [--tolerance T] [--seconds S] [--seed K]
//   MODE rate:  prints steps/s of a thermal run (kT 1, a constant random force on every particle,
//               nothing read back between steps), timed after a warm-up, as the script does.
//   MODE error: prints the relative RMS error of one step's displacement at temperature 0 (dt M F) at
//               tolerance T against: the free-space RPY product in double on the host (cholesky,
//               lanczos); the same method at tolerance 1e-6 (pse; fcm, with its kernel refitted to the
//               radius the measured run got); the same method on a grid twice as fine (quasi2d, whose
//               tolerance UAMMD ignores; dpstokes, the same kernel sampled twice as finely).
// Details go to stderr; stdout holds the one number.
#include "Integrator/BDHI/BDHI_Cholesky.cuh"
#include "Integrator/BDHI/BDHI_EulerMaruyama.cuh"
#include "Integrator/BDHI/BDHI_FCM.cuh"
#include "Integrator/BDHI/BDHI_Lanczos.cuh"
#include "Integrator/BDHI/BDHI_PSE.cuh"
#include "Integrator/BDHI/DoublyPeriodic/DPStokesSlab.cuh"
#include "Integrator/Hydro/BDHI_quasi2D.cuh"
#include "uammd.cuh"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace uammd_peer {
using namespace uammd;

// The benchmark's system (hydrodynamics_benchmark.py).
constexpr double radius = 1.0;
constexpr double viscosity = 1.0;
constexpr double volumeFraction = 0.05;
constexpr double timeStep = 0.01;
constexpr double referenceTolerance = 1e-6;
constexpr double slabHeight = 16.0 * radius;
// UAMMD's recommended DPStokes kernel for forces alone (DPStokesSlab.cuh): support w = 6 grid points,
// beta = 1.714 w, a / h = 1.554.
constexpr int slabSupport = 6;
constexpr double slabBetaPerSupport = 1.714;
constexpr double slabRadiusPerSpacing = 1.554;

struct Options {
  std::string mode, method;
  int n = 0;
  double tolerance = 1e-3;
  double seconds = 1.0;
  unsigned seed = 11;
};

bool isOpenBoundary(const std::string &method) { return method == "cholesky" or method == "lanczos"; }

double side(const std::string &method, int n) {
  if (method == "quasi2d")
    return std::sqrt(M_PI * radius * radius * n / volumeFraction);
  if (method == "dpstokes")
    return std::sqrt(4.0 * M_PI * radius * radius * radius * n / 3.0 / volumeFraction /
                     (slabHeight - 4.0 * radius));
  return std::cbrt(4.0 * M_PI * radius * radius * radius * n / 3.0 / volumeFraction);
}

// Uniform positions in the box the script uses (the plane z = 0 for quasi2d, |z| <= H/2 - 2a for the
// slab) and standard normal forces, drawn here: the same distributions as the script's numpy draws.
struct Configuration {
  std::vector<double3> positions, forces;
};

Configuration placement(const Options &o) {
  std::mt19937_64 engine(o.seed);
  const double length = side(o.method, o.n);
  std::uniform_real_distribution<double> inBox(-length / 2, length / 2);
  std::uniform_real_distribution<double> inSlab(-(slabHeight / 2 - 2 * radius), slabHeight / 2 - 2 * radius);
  std::normal_distribution<double> normal;
  Configuration c;
  for (int i = 0; i < o.n; i++) {
    double3 p{inBox(engine), inBox(engine), inBox(engine)};
    if (o.method == "quasi2d")
      p.z = 0;
    if (o.method == "dpstokes")
      p.z = inSlab(engine);
    c.positions.push_back(p);
  }
  for (int i = 0; i < o.n; i++)
    c.forces.push_back({normal(engine), normal(engine), normal(engine)});
  return c;
}

// Adds each particle's fixed external force (by particle id, so any reordering inside UAMMD is harmless).
class ConstantForce : public Interactor {
  thrust::device_vector<real3> forceById;

public:
  ConstantForce(std::shared_ptr<ParticleData> pd, const std::vector<double3> &forces)
      : Interactor(pd, "ConstantForce") {
    std::vector<real3> converted;
    for (const auto &f : forces)
      converted.push_back(make_real3(f.x, f.y, f.z));
    forceById = converted;
  }

  void sum(Computables comp, cudaStream_t st) override {
    if (not comp.force)
      return;
    auto force = pd->getForce(access::gpu, access::readwrite);
    auto id = pd->getId(access::gpu, access::read);
    const real3 *byId = thrust::raw_pointer_cast(forceById.data());
    real4 *f = force.raw();
    const int *ids = id.raw();
    thrust::for_each_n(thrust::cuda::par.on(st), thrust::make_counting_iterator(0), pd->getNumParticles(),
                       [=] __device__(int i) { f[i] += make_real4(byId[ids[i]], 0); });
  }
};

std::shared_ptr<ParticleData> makeParticles(const Configuration &c) {
  auto pd = std::make_shared<ParticleData>(int(c.positions.size()));
  auto pos = pd->getPos(access::cpu, access::write);
  auto id = pd->getId(access::cpu, access::write);
  for (size_t i = 0; i < c.positions.size(); i++) {
    pos[i] = make_real4(c.positions[i].x, c.positions[i].y, c.positions[i].z, 0);
    id[i] = int(i);
  }
  return pd;
}

// What sets up one run: the method at a tolerance, and for the references a grid `refinement` times
// finer, or (fcm) the radius to refit the kernel to.
struct Variant {
  double tolerance;
  int refinement = 1;
  double fcmRadius = 0;
};

template <class Method>
std::shared_ptr<Integrator> eulerMaruyama(std::shared_ptr<ParticleData> pd, typename Method::Parameters par,
                                          double temperature, double tolerance, real boxSide) {
  par.temperature = temperature;
  par.viscosity = viscosity;
  par.hydrodynamicRadius = radius;
  par.dt = timeStep;
  par.tolerance = tolerance;
  par.box = Box(make_real3(boxSide, boxSide, boxSide));
  auto integrator = std::make_shared<BDHI::EulerMaruyama<Method>>(pd, par);
  std::fprintf(stderr, "[uammd_peer] %s: hydrodynamic radius %g\n", type_name<Method>().c_str(),
               double(integrator->getHydrodynamicRadius()));
  return integrator;
}

// UAMMD's FCM Gaussian: width h f(tol) with the "upsampling" f (FCM_kernels.cuh); its inverse gives the
// tolerance at which a grid of spacing h carries a Gaussian of a given width.
double fcmUpsampling(double tolerance) {
  return std::min(0.55 + (-std::log10(3 * tolerance) / 10.0) * 1.1, 1.65);
}
double fcmToleranceFor(double upsampling) { return std::pow(10.0, -(upsampling - 0.55) * 10.0 / 1.1) / 3.0; }

std::shared_ptr<Integrator> makeIntegrator(const Options &o, std::shared_ptr<ParticleData> pd,
                                           double temperature, const Variant &v) {
  const double length = side(o.method, o.n);
  if (o.method == "cholesky")
    return eulerMaruyama<BDHI::Cholesky>(pd, {}, temperature, v.tolerance, length);
  if (o.method == "lanczos")
    return eulerMaruyama<BDHI::Lanczos>(pd, {}, temperature, v.tolerance, length);
  if (o.method == "pse")
    return eulerMaruyama<BDHI::PSE>(pd, {}, temperature, v.tolerance, length);
  if (o.method == "fcm") {
    BDHI::FCM::Parameters par;
    if (v.fcmRadius > 0) {
      // The reference: UAMMD's own Gaussian kernel with the measured run's width, on a grid at least as
      // fine as tolerance 1e-6 asks, with the support that grid's tolerance gives.
      const double width = v.fcmRadius / std::sqrt(M_PI);
      const int cells = nextFFTWiseSize3D(make_int3(int(std::ceil(length * fcmUpsampling(v.tolerance) / width)))).x;
      const double h = length / cells;
      par.cells = make_int3(cells, cells, cells);
      par.kernel = std::make_shared<BDHI::FCM_ns::Kernels::Gaussian>(h, fcmToleranceFor(width / h));
    }
    return eulerMaruyama<BDHI::FCM>(pd, par, temperature, v.tolerance, length);
  }
  if (o.method == "quasi2d") {
    BDHI::Quasi2D::Parameters par;
    par.temperature = temperature;
    par.viscosity = viscosity;
    par.hydrodynamicRadius = radius;
    par.dt = timeStep;
    par.tolerance = v.tolerance;
    par.box = Box(make_real3(length, length, 0));
    if (v.refinement > 1) {
      // UAMMD's own grid (spacing 0.8 a, rounded to an FFT-friendly size) made `refinement` times finer.
      const int cells = nextFFTWiseSize3D(make_int3(int(length / (0.8 * radius)))).x * v.refinement;
      par.cells = make_int2(cells, cells);
    }
    return std::make_shared<BDHI::Quasi2D>(pd, par);
  }
  if (o.method == "dpstokes") {
    DPStokesSlab_ns::DPStokesIntegrator::Parameters par;
    const double h = radius / slabRadiusPerSpacing / v.refinement;
    par.nx = par.ny = int(length / h + 0.5);
    par.nz = int(M_PI * slabHeight / (2 * h));
    // A finer grid keeps the same kernel: w and alpha in grid points grow as h shrinks, beta stays.
    par.w = slabSupport * v.refinement;
    par.alpha = par.w * 0.5;
    par.beta = make_real3(slabBetaPerSupport * slabSupport, -1, -1);
    par.mode = DPStokesSlab_ns::WallMode::slit;
    par.viscosity = viscosity;
    par.Lx = par.Ly = length;
    par.H = slabHeight;
    par.temperature = temperature;
    par.dt = timeStep;
    par.tolerance = v.tolerance;
    std::fprintf(stderr, "[uammd_peer] DPStokes grid %d x %d x %d (Chebyshev), w %g\n", par.nx, par.ny, par.nz,
                 double(par.w));
    return std::make_shared<DPStokesSlab_ns::DPStokesIntegrator>(pd, par);
  }
  throw std::invalid_argument("unknown method " + o.method);
}

double secondsOf(const std::function<void()> &work) {
  CudaSafeCall(cudaDeviceSynchronize());
  const auto start = std::chrono::steady_clock::now();
  work();
  CudaSafeCall(cudaDeviceSynchronize());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// As the script: 2 warm-up steps (launches, FFT plans), 3 to estimate, then as many as fill `seconds`.
double stepsPerSecond(const Options &o) {
  const auto c = placement(o);
  auto pd = makeParticles(c);
  auto integrator = makeIntegrator(o, pd, 1.0, {o.tolerance});
  integrator->addInteractor(std::make_shared<ConstantForce>(pd, c.forces));
  auto run = [&](int steps) {
    return secondsOf([&] {
      for (int i = 0; i < steps; i++)
        integrator->forwardTime();
    });
  };
  run(2);
  const double estimate = std::max(run(3) / 3, 1e-6);
  const int steps = std::max(3, int(o.seconds / estimate));
  return steps / run(steps);
}

// One step at temperature 0 from the configuration: dt M F, by particle id.
std::vector<double3> displacement(const Options &o, const Variant &v, double *fcmRadius = nullptr) {
  const auto c = placement(o);
  auto pd = makeParticles(c);
  auto integrator = makeIntegrator(o, pd, 0.0, v);
  if (fcmRadius)
    *fcmRadius = double(std::static_pointer_cast<BDHI::EulerMaruyama<BDHI::FCM>>(integrator)->getHydrodynamicRadius());
  integrator->addInteractor(std::make_shared<ConstantForce>(pd, c.forces));
  integrator->forwardTime();
  CudaSafeCall(cudaDeviceSynchronize());
  auto pos = pd->getPos(access::cpu, access::read);
  auto id = pd->getId(access::cpu, access::read);
  const double length = side(o.method, o.n);
  const bool periodic = not isOpenBoundary(o.method);
  std::vector<double3> moved(o.n);
  for (int i = 0; i < o.n; i++) {
    const double3 start = c.positions[id[i]];
    double3 d{pos[i].x - start.x, pos[i].y - start.y, pos[i].z - start.z};
    if (periodic) {
      d.x -= length * std::round(d.x / length);
      d.y -= length * std::round(d.y / length);
      if (o.method == "pse" or o.method == "fcm")
        d.z -= length * std::round(d.z / length);
    }
    moved[id[i]] = d;
  }
  return moved;
}

// dt M F for the free-space RPY mobility of equal spheres, overlapping pairs included (Zuk et al. 2014).
std::vector<double3> rpyProduct(const Configuration &c) {
  const double a = radius, mu0 = 1.0 / (6.0 * M_PI * viscosity * a);
  const int n = int(c.positions.size());
  std::vector<double3> out(n);
  for (int i = 0; i < n; i++) {
    const double3 pi = c.positions[i];
    double3 v = c.forces[i];
    for (int j = 0; j < n; j++) {
      if (j == i)
        continue;
      const double3 r{pi.x - c.positions[j].x, pi.y - c.positions[j].y, pi.z - c.positions[j].z};
      const double d = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
      const double3 u{r.x / d, r.y / d, r.z / d};
      const bool far = d >= 2 * a;
      const double c1 = far ? 0.75 * a / d * (1 + 2 * a * a / (3 * d * d)) : 1 - 9 * d / (32 * a);
      const double c2 = far ? 0.75 * a / d * (1 - 2 * a * a / (d * d)) : 3 * d / (32 * a);
      const double3 f = c.forces[j];
      const double projected = u.x * f.x + u.y * f.y + u.z * f.z;
      v.x += c1 * f.x + c2 * projected * u.x;
      v.y += c1 * f.y + c2 * projected * u.y;
      v.z += c1 * f.z + c2 * projected * u.z;
    }
    out[i] = {timeStep * mu0 * v.x, timeStep * mu0 * v.y, timeStep * mu0 * v.z};
  }
  return out;
}

double relativeError(const std::vector<double3> &measured, const std::vector<double3> &reference) {
  double difference = 0, norm = 0;
  for (size_t i = 0; i < measured.size(); i++) {
    const double3 m = measured[i], r = reference[i];
    difference += (m.x - r.x) * (m.x - r.x) + (m.y - r.y) * (m.y - r.y) + (m.z - r.z) * (m.z - r.z);
    norm += r.x * r.x + r.y * r.y + r.z * r.z;
  }
  return std::sqrt(difference / norm);
}

double error(const Options &o) {
  if (isOpenBoundary(o.method))
    return relativeError(displacement(o, {o.tolerance}), rpyProduct(placement(o)));
  if (o.method == "quasi2d" or o.method == "dpstokes")
    return relativeError(displacement(o, {o.tolerance}), displacement(o, {o.tolerance, 2}));
  if (o.method == "fcm") {
    double fitted = 0;
    const auto measured = displacement(o, {o.tolerance}, &fitted);
    return relativeError(measured, displacement(o, {referenceTolerance, 1, fitted}));
  }
  return relativeError(displacement(o, {o.tolerance}), displacement(o, {referenceTolerance}));
}

Options parse(int argc, char **argv) {
  if (argc < 2)
    throw std::invalid_argument("usage: uammd_hydrodynamics rate|error --method M --n N [--tolerance T] "
                                "[--seconds S] [--seed K]");
  Options o;
  o.mode = argv[1];
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--method")
      o.method = value;
    else if (key == "--n")
      o.n = std::stoi(value);
    else if (key == "--tolerance")
      o.tolerance = std::stod(value);
    else if (key == "--seconds")
      o.seconds = std::stod(value);
    else if (key == "--seed")
      o.seed = unsigned(std::stoul(value));
    else
      throw std::invalid_argument("unknown option " + key);
  }
  if (o.n <= 0 or o.method.empty() or (o.mode != "rate" and o.mode != "error"))
    throw std::invalid_argument("need rate|error, --method and --n");
  const std::vector<std::string> methods{"cholesky", "lanczos", "pse", "fcm", "quasi2d", "dpstokes"};
  if (std::find(methods.begin(), methods.end(), o.method) == methods.end())
    throw std::invalid_argument("unknown method " + o.method + " (cholesky, lanczos, pse, fcm, quasi2d, dpstokes)");
  return o;
}
} // namespace uammd_peer

int main(int argc, char **argv) {
  try {
    const auto options = uammd_peer::parse(argc, argv);
    const double value =
        options.mode == "rate" ? uammd_peer::stepsPerSecond(options) : uammd_peer::error(options);
    std::printf("%.6g\n", value);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "uammd_hydrodynamics: %s\n", e.what());
    return 1;
  }
  return 0;
}
