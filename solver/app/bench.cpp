// `erythro bench` (issue 3 items 9–10): MLUPS of FluidLattice::step() per grid,
// collision model, boundary set-up and thread count, and the STREAM-like copy
// bandwidth of the same run, giving the bandwidth bound
//   bound_MLUPS = bandwidth / 144 B   (D2Q9 doubles: 9·8 B read + 9·8 B written per update).
// Every configuration is warmed up, then timed `repeats` times; the table shows the
// median and the spread (min, max). A short ablation times the two steps of the AA
// pattern apart (pull_swap and local, fluid/stream_collide.hpp). The result record is
// informative: MLUPS and the fraction of the bound are recorded with `at_least 0`,
// never asserted. Method and figures: docs/performance.md.
#include "app/bench.hpp"

#include <omp.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <numbers>
#include <span>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "app/bench_metric.hpp"
#include "app/coupled_bench.hpp"
#include "app/scene_bench.hpp"
#include "common/error.hpp"
#include "fluid/fluid_lattice.hpp"
#include "io/result_record.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace erythro::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kBytesPerUpdate = 144.0;  // 9 doubles read + 9 doubles written
constexpr double kTau = 0.8;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// ---------------------------------------------------------------- copy bandwidth

struct FreeDeleter {
  void operator()(double* p) const { std::free(p); }
};
using AlignedArray = std::unique_ptr<double[], FreeDeleter>;

AlignedArray aligned_array(std::size_t n) {
  auto* p = static_cast<double*>(std::aligned_alloc(64, n * sizeof(double)));
  if (!p) throw std::runtime_error("bench: cannot allocate " + std::to_string(n * sizeof(double) >> 20) + " MiB");
  return AlignedArray(p);
}

constexpr std::size_t kCopyElements = std::size_t{1} << 24;  // 128 MiB per array, 4× the 32 MiB L3

bool streaming_stores_available() {
#if defined(__SSE2__)
  return true;
#else
  return false;
#endif
}

// b ← a over n doubles (n a multiple of 8, both 64-byte aligned), counted as 16 B per
// element. Written with explicit vector loads/stores so that the compiler cannot turn
// the loop into a memcpy call (glibc's memcpy switches to streaming stores itself).
void copy_once(const double* __restrict a, double* __restrict b, std::size_t n, bool streaming) {
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; i += 8) {
#if defined(__AVX512F__)
      const __m512d v = _mm512_load_pd(a + i);
      if (streaming) {
        _mm512_stream_pd(b + i, v);
      } else {
        _mm512_store_pd(b + i, v);
      }
#elif defined(__AVX__)
      const __m256d lo = _mm256_load_pd(a + i), hi = _mm256_load_pd(a + i + 4);
      if (streaming) {
        _mm256_stream_pd(b + i, lo);
        _mm256_stream_pd(b + i + 4, hi);
      } else {
        _mm256_store_pd(b + i, lo);
        _mm256_store_pd(b + i + 4, hi);
      }
#elif defined(__SSE2__)
      for (std::size_t k = 0; k < 8; k += 2) {
        const __m128d v = _mm_load_pd(a + i + k);
        if (streaming) {
          _mm_stream_pd(b + i + k, v);
        } else {
          _mm_store_pd(b + i + k, v);
        }
      }
#else
      for (std::size_t k = 0; k < 8; ++k) b[i + k] = a[i + k];
#endif
    }
#if defined(__SSE2__)
    if (streaming) _mm_sfence();
#endif
  }
}

// Two initialised copy arrays; one timed copy at a time, alternating the direction.
class CopyArrays {
 public:
  CopyArrays() : a_(aligned_array(kCopyElements)), b_(aligned_array(kCopyElements)) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < kCopyElements; ++i) {
      a_[i] = 1.0 + static_cast<double>(i % 7);
      b_[i] = 0.0;
    }
    copy_once(a_.get(), b_.get(), kCopyElements, true);  // warm-up (page faults, clocks)
    copy_once(b_.get(), a_.get(), kCopyElements, false);
  }
  // GB/s (10⁹ B/s, read + write bytes) of one copy.
  double sample(bool streaming) {
    const auto start = Clock::now();
    copy_once(forward_ ? a_.get() : b_.get(), forward_ ? b_.get() : a_.get(), kCopyElements, streaming);
    forward_ = !forward_;
    return 2.0 * sizeof(double) * static_cast<double>(kCopyElements) / seconds_since(start) / 1e9;
  }

 private:
  AlignedArray a_, b_;
  bool forward_ = true;
};

// Copy bandwidth in GB/s over `repeats` copies (at least 5).
Stats copy_bandwidth(int threads, bool streaming, int repeats) {
  omp_set_num_threads(threads);
  CopyArrays arrays;
  std::vector<double> gbs;
  for (int r = 0; r < std::max(repeats, 5); ++r) gbs.push_back(arrays.sample(streaming));
  return stats_of(gbs);
}

// ---------------------------------------------------------------- fluid step

struct StepResult {
  Stats mlups;
  long steps_per_sample = 0;
  int samples = 0;
  double wall_time_s = 0.0;
};

// Warm-up: at least 3 steps and 0.1 s; returns the number of steps of one sample lasting at
// least `sample_seconds`.
long warm_up(const std::function<void()>& step, double sample_seconds) {
  const auto start = Clock::now();
  long warm = 0;
  while (warm < 3 || seconds_since(start) < 0.1) {
    step();
    ++warm;
  }
  const double per_step = seconds_since(start) / static_cast<double>(warm);
  return std::max(1L, static_cast<long>(std::ceil(sample_seconds / per_step)));
}

// MLUPS of one sample of `steps` steps.
double sample_mlups(const std::function<void()>& step, std::size_t nodes, long steps) {
  const auto start = Clock::now();
  for (long s = 0; s < steps; ++s) step();
  return static_cast<double>(nodes) * static_cast<double>(steps) / seconds_since(start) / 1e6;
}

// Warm-up, then `repeats` samples of at least `sample_seconds` each.
StepResult time_steps(const std::function<void()>& step, std::size_t nodes, int repeats, double sample_seconds) {
  const auto start_all = Clock::now();
  const long steps = warm_up(step, sample_seconds);
  std::vector<double> mlups;
  for (int r = 0; r < repeats; ++r) mlups.push_back(sample_mlups(step, nodes, steps));
  return {stats_of(mlups), steps, repeats, seconds_since(start_all)};
}

struct StepConfig {
  int n = 0;
  fluid::CollisionModel model = fluid::CollisionModel::bgk;
  bool channel = false;  // walls at bottom and top; otherwise periodic box
  int threads = 1;
};

std::string boundary_name(bool channel) { return channel ? "channel" : "periodic"; }

fluid::BoundaryConfig boundaries(bool channel) {
  fluid::BoundaryConfig b;
  if (channel) b.bottom.type = b.top.type = fluid::SideType::wall;
  return b;
}

// u_x(y) of a decaying shear wave, 0.01 sin(2π (y+½)/n): a valid flow for both set-ups.
double shear_wave(int y, int n) { return 0.01 * std::sin(2.0 * std::numbers::pi * (y + 0.5) / n); }

// A lattice of the benchmark set-up holding the decaying shear wave (equilibrium).
fluid::FluidLattice shear_wave_lattice(const StepConfig& c) {
  fluid::FluidLattice lat(Grid{c.n, c.n}, {c.model, kTau, 3.0 / 16.0}, boundaries(c.channel));
  const std::size_t N = lat.grid().size();
  std::vector<double> rho(N, 1.0), ux(N), uy(N, 0.0);
  for (int y = 0; y < c.n; ++y) {
    for (int x = 0; x < c.n; ++x) ux[lat.grid().index(x, y)] = shear_wave(y, c.n);
  }
  lat.initialize(rho, ux, uy);
  return lat;
}

StepResult measure_lattice(const StepConfig& c, int repeats, double sample_seconds) {
  const auto start = Clock::now();
  omp_set_num_threads(c.threads);
  fluid::FluidLattice lat = shear_wave_lattice(c);
  StepResult r = time_steps([&] { lat.step(); }, lat.grid().size(), repeats, sample_seconds);
  if (!lat.check_health(0.3).healthy) throw std::runtime_error("bench: the benchmark flow diverged");
  r.wall_time_s = seconds_since(start);
  return r;
}

// The two AA steps timed apart: FluidLattice::step() alternates them, a pull_swap step
// (reads and writes shifted slots) from the natural layout the lattice starts in, then a
// local step (each node's own slots).
std::pair<StepResult, StepResult> measure_half_steps(const StepConfig& c, int repeats, double sample_seconds) {
  const auto start = Clock::now();
  omp_set_num_threads(c.threads);
  fluid::FluidLattice lat = shear_wave_lattice(c);
  double seconds[2] = {0.0, 0.0};  // pull_swap, local
  auto pair_of_steps = [&] {
    for (int half = 0; half < 2; ++half) {
      const auto t = Clock::now();
      lat.step();
      seconds[half] += seconds_since(t);
    }
  };
  const long pairs = warm_up(pair_of_steps, sample_seconds);
  std::vector<double> mlups[2];
  for (int r = 0; r < repeats; ++r) {
    seconds[0] = seconds[1] = 0.0;
    for (long p = 0; p < pairs; ++p) pair_of_steps();
    for (int half = 0; half < 2; ++half) {
      mlups[half].push_back(static_cast<double>(lat.grid().size()) * static_cast<double>(pairs) / seconds[half] / 1e6);
    }
  }
  if (!lat.check_health(0.3).healthy) throw std::runtime_error("bench: the benchmark flow diverged");
  const double wall = seconds_since(start);
  return {StepResult{stats_of(mlups[0]), pairs, repeats, wall}, StepResult{stats_of(mlups[1]), pairs, repeats, wall}};
}

// Node updates per µs that a copy bandwidth (GB/s, read + write bytes) allows: bw / 144 B.
double bound_mlups(double gbs) { return gbs * 1e9 / kBytesPerUpdate / 1e6; }

// The fraction of the bound with the bound measured beside each kernel sample: `pairs` times an
// untimed copy, a streaming and a plain copy (the better one is that pair's bound) and then one
// kernel sample of FluidLattice::step(). The host's copy bandwidth drifts by tens of per cent within minutes
// (docs/performance.md), so a bound measured once at the start can be off by that much; the
// median of the per-pair ratios is not.
struct PairedResult {
  Stats fraction, mlups, gbs;
  int pairs = 0;
  double wall_time_s = 0.0;
};

PairedResult measure_paired(const StepConfig& c, int pairs, double sample_seconds) {
  const auto start = Clock::now();
  omp_set_num_threads(c.threads);
  CopyArrays arrays;
  fluid::FluidLattice lat = shear_wave_lattice(c);
  const auto step = [&] { lat.step(); };
  const long steps = warm_up(step, sample_seconds);
  std::vector<double> fraction, mlups, gbs;
  for (int p = 0; p < pairs; ++p) {
    // An untimed copy first: the in-place kernel leaves up to an L3 of dirty lattice lines,
    // whose write-back would otherwise slow the timed copy (a lower bound, a flattering
    // fraction). Then a streaming copy from that clean cache, as at the start of the run,
    // and a plain one (its own dirty lines are part of what a plain copy measures).
    arrays.sample(true);
    const double streaming = arrays.sample(true);
    const double bw = std::max(streaming, arrays.sample(false));
    const double m = sample_mlups(step, lat.grid().size(), steps);
    gbs.push_back(bw);
    mlups.push_back(m);
    fraction.push_back(m / bound_mlups(bw));
  }
  if (!lat.check_health(0.3).healthy) throw std::runtime_error("bench: the benchmark flow diverged");
  return {stats_of(fraction), stats_of(mlups), stats_of(gbs), pairs, seconds_since(start)};
}

// ---------------------------------------------------------------- machine state

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double l1 = 0, l5 = 0, l15 = 0;
  if (!(in >> l1 >> l5 >> l15)) return "unknown";
  std::ostringstream s;
  s << l1 << " " << l5 << " " << l15;
  return s.str();
}

// The processor as far as this machine tells: /proc/cpuinfo's model name (a virtual machine
// may give only the product line, "AMD EPYC" for Zen 3 and Zen 4 alike), its family and model
// numbers, whether it has AVX-512, and the vectors this binary was built for. Figures of two
// runs compare only on the same processor.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string name = "unknown", family = "?", model = "?";
  bool avx512 = false;
  auto key_is = [](const std::string& line, const char* key) {  // "key<tabs or spaces>: value"
    const std::size_t n = std::char_traits<char>::length(key);
    return line.rfind(key, 0) == 0 && line.find_first_not_of(" \t", n) == line.find(':');
  };
  auto value = [](const std::string& line) {
    const auto colon = line.find(':');
    return colon == std::string::npos ? std::string() : line.substr(std::min(colon + 2, line.size()));
  };
  for (std::string line; std::getline(in, line) && !line.empty();) {  // the first processor's lines
    if (key_is(line, "model name"))
      name = value(line);
    else if (key_is(line, "cpu family"))
      family = value(line);
    else if (key_is(line, "model"))
      model = value(line);
    else if (key_is(line, "flags"))
      avx512 = (" " + value(line) + " ").find(" avx512f ") != std::string::npos;
  }
#if defined(__AVX512F__)
  const char* built = "AVX-512";
#elif defined(__AVX2__)
  const char* built = "AVX2";
#else
  const char* built = "SSE2";
#endif
  return name + " (family " + family + ", model " + model + ", AVX-512 " + (avx512 ? "yes" : "no") +
         "; this binary built for " + built + ")";
}

std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

std::string tag(const StepConfig& c) {
  std::ostringstream s;
  s << boundary_name(c.channel) << "_" << fluid::to_string(c.model) << "_" << c.n << "_t" << c.threads;
  return s.str();
}

// The propagation pattern of FluidLattice::step(), for the table and the record.
constexpr const char* kPattern = "AA, in place";

struct Bandwidth {
  double plain = 0.0, streaming = 0.0;  // GB/s, read + write bytes
  double best() const { return std::max(plain, streaming); }
};


// A section of the bench run alone, in a record of its own (so that it does not replace the
// fluid step's): the record's requirement, the machine's state before and after, `body`
// measuring into it, the record written where --out or $ERYTHRO_RESULTS_DIR says.
int run_alone(const BenchOptions& o, const char* name, const std::string& requirement,
              const std::function<void(io::ResultRecord&)>& body) {
  const auto start = Clock::now();
  const std::string load_start = load_average();
  io::ResultRecord record(name, "benchmark");
  record.set_requirement(requirement);
  record.set_reference("none: a measurement of this code on this machine (docs/performance.md)");
  record.set_parameter("cpu", cpu_model());
  record.set_parameter("load_average_start", load_start);
  record.set_parameter("omp_wait_policy", env_or("OMP_WAIT_POLICY", "default"));
  body(record);
  const std::string load_end = load_average();
  record.set_parameter("load_average_end", load_end);
  record.set_wall_time(seconds_since(start));
  std::printf("load average (1, 5, 15 min): start %s, end %s\n", load_start.c_str(), load_end.c_str());
  std::printf("processor: %s\n", cpu_model().c_str());
  const std::string path = o.out.empty() ? record.write_to_results_dir() : (record.write(o.out), o.out);
  std::printf("record: %s\n", path.c_str());
  return record.passed() ? exit_code::ok : exit_code::runtime_failure;
}

// The coupled step alone (--coupled-only).
int run_coupled_only(const BenchOptions& o) {
  return run_alone(o, "benchmark.coupled",
                   "Informative: measure the cost of the immersed cells per cell and time step, and the stages of the "
                   "coupled step, beside the fluid step of the same grid without cells.",
                   [&](io::ResultRecord& record) {
                     if (o.coupled.scene.empty()) run_coupled_bench(o.coupled, record);
                     else run_scene_bench(o.coupled.scene, o.coupled, record);
                   });
}

// ---------------------------------------------------------------- the fluid step's inputs

// What each input of the coupled step costs the fluid step (issue 18's "grid overhead",
// docs/performance-coupled-step.md, "What the grid overhead is made of"): the benchmark lattice
// (periodic BGK) with a force field, a τ field that varies along every row (so every node takes its
// own rates), both, and both with the velocity written by the step (the dense immersed cells'
// set-up), each timed like the plain step, in that order per grid and thread count.
struct InputVariant {
  const char* name;
  const char* key;  // in metric names
  bool force, tau, velocity;
};
constexpr InputVariant kInputVariants[] = {{"plain", "plain", false, false, false},
                                           {"force field", "force", true, false, false},
                                           {"tau field", "tau", false, true, false},
                                           {"force and tau fields", "force_tau", true, true, false},
                                           {"force, tau, velocity written", "force_tau_velocity", true, true, true}};

StepResult measure_inputs(const StepConfig& c, const InputVariant& v, int repeats, double sample_seconds) {
  const auto start = Clock::now();
  omp_set_num_threads(c.threads);
  fluid::FluidLattice lat = shear_wave_lattice(c);
  const Grid g = lat.grid();
  const double k = 2.0 * std::numbers::pi / c.n;
  if (v.force) {  // zero mean along x: no net acceleration of the periodic box
    lat.enable_force_field();
    const std::span<double> fx = lat.force_x(), fy = lat.force_y();
    for (int y = 0; y < c.n; ++y)
      for (int x = 0; x < c.n; ++x) {
        fx[g.index(x, y)] = 1e-7 * std::sin(k * (x + 0.5));
        fy[g.index(x, y)] = 1e-7 * std::cos(k * (x + 0.5));
      }
  }
  if (v.tau) {
    lat.enable_tau_field();
    const std::span<double> tau = lat.tau_field();
    for (int y = 0; y < c.n; ++y)
      for (int x = 0; x < c.n; ++x) tau[g.index(x, y)] = kTau + 0.1 * std::sin(k * (x + y + 0.5));
    lat.refresh_tau_rows();
  }
  std::vector<double> ux(v.velocity ? g.size() : 0), uy(ux.size());
  const auto step = [&] {
    if (v.velocity) lat.write_velocity_with_next_step(ux, uy);
    lat.step();
  };
  StepResult r = time_steps(step, g.size(), repeats, sample_seconds);
  if (!lat.check_health(0.3).healthy) throw std::runtime_error("bench: the benchmark flow diverged");
  r.wall_time_s = seconds_since(start);
  return r;
}

// Every grid and thread count with each input of kInputVariants, into the record.
void measure_fluid_inputs(const BenchOptions& o, io::ResultRecord& record) {
  record.set_parameter("tau", kTau);
  std::printf("the fluid step's inputs (periodic BGK, tau %.2f; time / plain: the step's time over the plain step's)\n",
              kTau);
  std::printf("%5s %3s %-30s %7s %15s %12s\n", "grid", "thr", "inputs", "MLUPS", "min-max", "time / plain");
  for (int n : o.sizes) {
    for (int threads : o.threads) {
      const StepConfig c{n, fluid::CollisionModel::bgk, false, threads};
      double plain = 0.0;
      for (const InputVariant& v : kInputVariants) {
        const StepResult r = measure_inputs(c, v, o.repeats, o.sample_seconds);
        if (!v.force && !v.tau) plain = r.mlups.median;
        const double ratio = plain / r.mlups.median;
        std::printf("%5d %3d %-30s %7.1f %7.1f-%-7.1f %12.3f\n", n, threads, v.name, r.mlups.median, r.mlups.min,
                    r.mlups.max, ratio);
        std::fflush(stdout);
        record.add_run({{"kind", std::string("fluid step inputs")},
                        {"inputs", std::string(v.name)},
                        {"grid_n", static_cast<double>(n)},
                        {"threads", static_cast<double>(threads)},
                        {"samples", static_cast<double>(r.samples)},
                        {"steps_per_sample", static_cast<double>(r.steps_per_sample)},
                        {"mlups_median", r.mlups.median},
                        {"mlups_min", r.mlups.min},
                        {"mlups_max", r.mlups.max},
                        {"time_over_plain", ratio},
                        {"wall_time_s", r.wall_time_s}});
        record.add_metric(informative("time_over_plain_" + std::string(v.key) + "_" + std::to_string(n) + "_t" +
                                          std::to_string(threads),
                                      std::string("time of the fluid step with ") + v.name + " / the plain step's", "",
                                      ratio));
      }
    }
  }
}

// The fluid step with each input of the coupled step (--fluid-inputs).
int run_fluid_inputs(const BenchOptions& o) {
  return run_alone(o, "benchmark.fluid_inputs",
                   "Informative: measure what a force field, a tau field and the velocity written by the step each "
                   "add to the fused stream-collide step, beside the plain step of the same grid.",
                   [&](io::ResultRecord& record) { measure_fluid_inputs(o, record); });
}

int run_bench(BenchOptions o) {
  o.coupled.threads = o.threads;
  if (o.quick) {
    o.sizes = {256, 1024};
    o.repeats = 3;
    o.sample_seconds = 0.05;
    o.coupled.cells = {2, 8};
    o.coupled.steps = 100;
    o.coupled.pairs = 1;
  }
  if (!o.write_scenes.empty()) {
    write_box_scenes(o.coupled, o.write_scenes);
    return exit_code::ok;
  }
  if (o.coupled_only) return run_coupled_only(o);
  if (o.fluid_inputs) return run_fluid_inputs(o);
  const auto start_all = Clock::now();
  const std::string load_start = load_average();
  io::ResultRecord record("benchmark.fluid", "benchmark");
  record.set_requirement(
      "Informative: measure the throughput of the fused D2Q9 stream-collide step (MLUPS) and its fraction of "
      "the memory-bandwidth bound, copy bandwidth / 144 B per node update, on this machine.");
  record.set_reference(
      "Bandwidth bound of a D2Q9 double-precision update: 9 x 8 B read + 9 x 8 B written = 144 B per node "
      "update, for two lattices and for the in-place AA pattern alike (Wittmann et al. 2013, Comput Math Appl "
      "65:924, roofline model); copy bandwidth measured with a STREAM-like copy (McCalpin 1995), counted as "
      "read + write bytes.");
  record.set_parameter("cpu", cpu_model());
  record.set_parameter("load_average_start", load_start);
  record.set_parameter("omp_wait_policy", env_or("OMP_WAIT_POLICY", "default"));
  record.set_parameter("tau", kTau);
  record.set_parameter("repeats", static_cast<double>(o.repeats));
  record.set_parameter("sample_seconds", o.sample_seconds);
  record.set_parameter("bytes_per_update", kBytesPerUpdate);
  record.set_parameter("copy_array_mib", static_cast<double>(kCopyElements * sizeof(double)) / (1 << 20));
  record.set_parameter("propagation", std::string(kPattern));
  record.set_parameter("bound_definition",
                       "best of the plain-store and streaming-store copy bandwidths / 144 B; the plain-store bound "
                       "(write-allocate traffic uncounted, as in most published STREAM figures) is also given");

  // Copy bandwidth per thread count: plain stores (write-allocate: 24 B really move
  // per 16 B counted) and streaming stores.
  std::printf("copy bandwidth (STREAM-like, read + write bytes, 2 x %zu MiB arrays), load %s\n",
              kCopyElements * sizeof(double) >> 20, load_start.c_str());
  std::vector<Bandwidth> bandwidth(o.threads.size());
  for (std::size_t t = 0; t < o.threads.size(); ++t) {
    const int th = o.threads[t];
    const Stats plain = copy_bandwidth(th, false, o.repeats);
    std::printf("  %d thread(s): plain stores %6.1f GB/s (%.1f-%.1f)", th, plain.median, plain.min, plain.max);
    record.add_metric(informative("copy_gbs_t" + std::to_string(th), "STREAM-like copy, plain stores", "GB/s",
                                  plain.median));
    bandwidth[t].plain = plain.median;
    if (streaming_stores_available()) {
      const Stats nt = copy_bandwidth(th, true, o.repeats);
      std::printf(", streaming stores %6.1f GB/s (%.1f-%.1f)", nt.median, nt.min, nt.max);
      record.add_metric(informative("copy_nt_gbs_t" + std::to_string(th), "STREAM-like copy, streaming stores",
                                    "GB/s", nt.median));
      bandwidth[t].streaming = nt.median;
    }
    std::printf("\n      bound %.0f MLUPS (plain-store bound %.0f MLUPS)\n", bound_mlups(bandwidth[t].best()),
                bound_mlups(bandwidth[t].plain));
    record.set_parameter("bandwidth_gbs_t" + std::to_string(th), bandwidth[t].best());
  }

  std::printf("\n%-9s %-4s %5s %3s %-16s %7s %15s %6s %6s %6s %6s %6s\n", "boundary", "coll", "grid", "thr", "kernel",
              "MLUPS", "min-max", "spread", "GB/s", "bound", "frac", "fr.pl");
  auto report = [&](const std::string& kind, const std::string& pattern, const StepConfig& c, std::size_t t,
                    const StepResult& r) {
    const double bound = bound_mlups(bandwidth[t].best()), plain_bound = bound_mlups(bandwidth[t].plain);
    const double fraction = r.mlups.median / bound, fraction_plain = r.mlups.median / plain_bound;
    const double gbs = r.mlups.median * 1e6 * kBytesPerUpdate / 1e9;
    std::printf("%-9s %-4s %5d %3d %-16s %7.1f %7.1f-%-7.1f %5.1f%% %6.1f %6.0f %5.0f%% %5.0f%%\n",
                boundary_name(c.channel).c_str(), std::string(fluid::to_string(c.model)).c_str(), c.n, c.threads,
                pattern.c_str(), r.mlups.median, r.mlups.min, r.mlups.max, 100.0 * r.mlups.spread(), gbs, bound,
                100.0 * fraction, 100.0 * fraction_plain);
    std::fflush(stdout);
    record.add_run({{"kind", kind},
                    {"boundary", boundary_name(c.channel)},
                    {"model", std::string(fluid::to_string(c.model))},
                    {"grid_n", static_cast<double>(c.n)},
                    {"threads", static_cast<double>(c.threads)},
                    {"propagation", pattern},
                    {"steps_per_sample", static_cast<double>(r.steps_per_sample)},
                    {"samples", static_cast<double>(r.samples)},
                    {"mlups_median", r.mlups.median},
                    {"mlups_min", r.mlups.min},
                    {"mlups_max", r.mlups.max},
                    {"effective_gbs", gbs},
                    {"bandwidth_gbs", bandwidth[t].best()},
                    {"bound_mlups", bound},
                    {"fraction_of_bound", fraction},
                    {"fraction_of_plain_store_bound", fraction_plain},
                    {"wall_time_s", r.wall_time_s}});
    return std::pair{bound, fraction};
  };

  for (bool channel : {false, true}) {
    for (auto model : {fluid::CollisionModel::bgk, fluid::CollisionModel::trt}) {
      // One plot series per thread count: MLUPS vs nodes, the bound as reference.
      std::vector<io::Series> series(o.threads.size());
      for (std::size_t t = 0; t < o.threads.size(); ++t) {
        io::Series& s = series[t];
        s.name = boundary_name(channel) + " " + std::string(fluid::to_string(model)) + " " +
                 std::to_string(o.threads[t]) + " thread(s)";
        s.title = "Fluid step throughput, " + s.name + " (reference: bandwidth bound)";
        s.xlabel = "nodes";
        s.ylabel = "MLUPS";
      }
      for (int n : o.sizes) {
        for (std::size_t t = 0; t < o.threads.size(); ++t) {
          const StepConfig c{n, model, channel, o.threads[t]};
          const StepResult r = measure_lattice(c, o.repeats, o.sample_seconds);
          const auto [bound, fraction] =
              report("FluidLattice::step", kPattern, c, t, r);
          record.add_metric(informative("mlups_" + tag(c), "median MLUPS of FluidLattice::step()", "MLUPS",
                                        r.mlups.median));
          record.add_metric(informative("fraction_of_bound_" + tag(c),
                                        "median MLUPS / (best copy bandwidth / 144 B)", "", fraction));
          series[t].x.push_back(static_cast<double>(n) * n);
          series[t].y.push_back(r.mlups.median);
          series[t].y_reference.push_back(bound);
        }
      }
      for (const auto& s : series) record.add_series(s);
    }
  }

  // Ablation: the two AA steps apart, periodic BGK, one thread, at the largest benchmark
  // grid of at most 1024² (the bound-relevant case).
  int n_ablation = 0;
  for (int n : o.sizes) {
    if (n <= 1024) n_ablation = std::max(n_ablation, n);
  }
  const std::size_t t1 = static_cast<std::size_t>(std::find(o.threads.begin(), o.threads.end(), 1) - o.threads.begin());
  if (n_ablation > 0 && t1 < o.threads.size()) {
    std::printf("\nablation: the two AA steps timed apart (periodic BGK, 1 thread)\n");
    const StepConfig c{n_ablation, fluid::CollisionModel::bgk, false, 1};
    const auto [pull_swap, local] = measure_half_steps(c, o.repeats, o.sample_seconds);
    report("kernel, pull_swap step", "AA pull_swap", c, t1, pull_swap);
    report("kernel, local step", "AA local", c, t1, local);
  }

  // The headline of issue 3 (1024², periodic BGK, one thread) with a paired bound.
  const bool has_1024 = std::find(o.sizes.begin(), o.sizes.end(), 1024) != o.sizes.end();
  const bool has_1_thread = std::find(o.threads.begin(), o.threads.end(), 1) != o.threads.end();
  if (has_1024 && has_1_thread) {
    const StepConfig c{1024, fluid::CollisionModel::bgk, false, 1};
    const PairedResult p = measure_paired(c, std::max(o.repeats, 5), o.sample_seconds);
    std::printf("\npaired (copy, then step; %d pairs), periodic BGK 1024^2, 1 thread: fraction of the bound %.0f %% "
                "(%.0f-%.0f %%), MLUPS %.1f (%.1f-%.1f), copy %.1f GB/s (%.1f-%.1f)\n",
                p.pairs, 100.0 * p.fraction.median, 100.0 * p.fraction.min, 100.0 * p.fraction.max, p.mlups.median,
                p.mlups.min, p.mlups.max, p.gbs.median, p.gbs.min, p.gbs.max);
    record.add_run({{"kind", std::string("paired: copy then FluidLattice::step")},
                    {"boundary", boundary_name(false)},
                    {"model", std::string("bgk")},
                    {"grid_n", 1024.0},
                    {"threads", 1.0},
                    {"propagation", std::string(kPattern)},
                    {"samples", static_cast<double>(p.pairs)},
                    {"mlups_median", p.mlups.median},
                    {"mlups_min", p.mlups.min},
                    {"mlups_max", p.mlups.max},
                    {"bandwidth_gbs", p.gbs.median},
                    {"fraction_of_bound", p.fraction.median},
                    {"fraction_of_bound_min", p.fraction.min},
                    {"fraction_of_bound_max", p.fraction.max},
                    {"wall_time_s", p.wall_time_s}});
    record.add_metric(informative("fraction_of_bound_paired_periodic_bgk_1024_t1",
                                  "median over pairs of MLUPS / (copy bandwidth measured just before / 144 B)", "",
                                  p.fraction.median));
  }

  run_coupled_bench(o.coupled, record);

  const std::string load_end = load_average();
  record.set_parameter("load_average_end", load_end);
  record.set_wall_time(seconds_since(start_all));
  std::printf("\nfrac: of the bound (best copy bandwidth / 144 B); fr.pl: of the plain-store copy bound\n");
  std::printf("load average (1, 5, 15 min): start %s, end %s\n", load_start.c_str(), load_end.c_str());
  std::printf("processor: %s\n", cpu_model().c_str());
  const std::string path = o.out.empty() ? record.write_to_results_dir() : (record.write(o.out), o.out);
  std::printf("record: %s\n", path.c_str());
  return record.passed() ? exit_code::ok : exit_code::runtime_failure;
}

}  // namespace

CLI::App* add_bench_subcommand(CLI::App& cli, BenchOptions& options) {
  auto* cmd = cli.add_subcommand(
      "bench", "Measure the fluid step (MLUPS) against the memory-bandwidth bound, and the coupled step per cell");
  cmd->add_option("--out", options.out, "Result record (default: $ERYTHRO_RESULTS_DIR/benchmark.fluid.h5)");
  cmd->add_option("--sizes", options.sizes, "Grid sizes n of the n x n grids")->check(CLI::Range(3, 16384));
  cmd->add_option("--threads", options.threads, "Thread counts")->check(CLI::Range(1, 1024));
  cmd->add_option("--repeats", options.repeats, "Timed samples per configuration")->check(CLI::Range(1, 1000));
  cmd->add_option("--sample-seconds", options.sample_seconds, "Minimum duration of one sample")
      ->check(CLI::Range(1e-3, 60.0));
  cmd->add_flag("--quick", options.quick, "Smoke run: 256^2 and 1024^2, 3 short samples; 2 and 8 cells, one pair");
  CLI::Option* coupled_only =
      cmd->add_flag("--coupled-only", options.coupled_only,
                    "Only the coupled step (cells in a shear box), into $ERYTHRO_RESULTS_DIR/benchmark.coupled.h5");
  cmd->add_flag("--fluid-inputs", options.fluid_inputs,
                "Only what a force field, a tau field and the velocity output add to the fluid step, into "
                "$ERYTHRO_RESULTS_DIR/benchmark.fluid_inputs.h5");
  CLI::Option* cells = cmd->add_option("--cells", options.coupled.cells,
                                       "Cell counts of the coupled step (box sized for area fraction 0.3, or --grid)")
                           ->check(CLI::Range(1, 4096));
  CLI::Option* grid =
      cmd->add_option("--grid", options.coupled.grid,
                      "With --coupled-only: one shear box of NX x NY nodes for every cell count, instead of the box "
                      "sized for area fraction 0.3 (the overhead that scales with the grid: few cells, a large grid)")
          ->expected(2)
          ->check(CLI::Range(16, 16384))
          ->needs(coupled_only);
  cmd->add_option("--coupled-steps", options.coupled.steps, "Time steps of each coupled-step run")
      ->check(CLI::Range(10, 1000000));
  cmd->add_option("--coupled-pairs", options.coupled.pairs, "Fluid-only and coupled runs per configuration")
      ->check(CLI::Range(1, 100));
  CLI::Option* aggregation =
      cmd->add_flag("--aggregation", options.coupled.aggregation,
                    "Coupled step with Morse aggregation between the cells (De* = 5, thesis ch. IV)");
  CLI::Option* interval =
      cmd->add_option(
             "--index-interval", options.coupled.index_interval,
             "Index-field rebuild interval k of the coupled step (0: per box, the largest k with k U <= 0.1 h); "
             "each run takes max(4 k, --coupled-steps rounded up to a multiple of k) + 1 steps")
          ->check(CLI::Range(0L, 1000000L));
  cmd->add_flag("--alternate-threads", options.coupled.alternate_threads,
                "With --coupled-only: each box (or the --scene) run once, one thread and the largest of --threads "
                "in turn every block of steps, instead of separate runs (the cell work on both counts under the "
                "same conditions)")
      ->needs(coupled_only);
  CLI::Option* write_scenes =
      cmd->add_option("--write-scenes", options.write_scenes,
                      "With --coupled-only: write each box's scenes into this folder (the product's, the same cells "
                      "as [[cells]] for an older binary, the fluid alone; listed in boxes.tsv) instead of measuring: "
                      "the input of ci/bench-against.sh")
          ->needs(coupled_only)
          ->excludes(cmd->get_option("--alternate-threads"));
  cmd->add_option("--scene", options.coupled.scene,
                  "With --coupled-only: the coupled step of this scene (its cells, its physics) beside the same scene "
                  "without its cells, instead of the shear boxes")
      ->check(CLI::ExistingFile)
      ->needs(coupled_only)
      ->excludes(cells)
      ->excludes(grid)
      ->excludes(aggregation)
      ->excludes(interval)
      ->excludes(write_scenes);
  return cmd;
}

int bench_command(const BenchOptions& options) {
  try {
    return run_bench(options);
  } catch (const InputError& e) {  // a --scene that does not parse or has no cells
    std::cerr << "erythro: error: " << e.what() << "\n";
    return exit_code::bad_input;
  } catch (const OutputError& e) {
    std::cerr << "erythro: error: " << e.what() << "\n";
    return exit_code::output_failure;
  } catch (const std::exception& e) {
    std::cerr << "erythro: error: " << e.what() << "\n";
    return exit_code::runtime_failure;
  }
}

}  // namespace erythro::app
