// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Seeded noise and fixed-rate scheduling, shared by the simulated sensors and the disturbances.
//
// Every noise source (each sensor, each disturbance) owns one MT19937-64 engine seeded from the
// scenario seed and a fixed per-source salt, so adding or reconfiguring one source never
// changes another's noise, and the same seed gives bit-identical samples. The standard
// distributions (std::normal_distribution …) are implementation-defined; the mappings here are
// our own, so the streams depend only on mt19937_64 (specified bit for bit) and on libm's exp
// and log in the rare tail branches of the normal generator. The engine is our own
// implementation of std::mt19937_64 (same output, tested against it): libstdc++'s refill
// branches on a random bit of every word and took ~7.5 ns per draw here, ours ~1.5–2 ns.

#include <array>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "geaware/sim/plant_state.hpp"

namespace geaware::sim {

/// Per-source salts. Fixed forever: changing one changes that source's noise for every seed.
namespace salt {
inline constexpr std::uint64_t kImu = 0x696d75'00000001ULL;
inline constexpr std::uint64_t kMocap = 0x6d6f63'00000002ULL;
inline constexpr std::uint64_t kRotorTelemetry = 0x74656c'00000003ULL;
inline constexpr std::uint64_t kRanger = 0x726e67'00000004ULL;
inline constexpr std::uint64_t kGroundTurbulence = 0x747262'00000005ULL;
inline constexpr std::uint64_t kWind = 0x77696e'00000006ULL;
inline constexpr std::uint64_t kImuVibration = 0x766962'00000007ULL;
inline constexpr std::uint64_t kMocapJitter = 0x6a6974'00000008ULL;
inline constexpr std::uint64_t kUnsteadiness = 0x756e73'00000009ULL;
inline constexpr std::uint64_t kFaultOutliers = 0x666c74'0000000bULL;  // experiments/faults.hpp
/// Single-beam rangers (obstacles.hpp): beam k draws from kBeamRanger + k.
inline constexpr std::uint64_t kBeamRanger = 0x62656d'00000100ULL;
}  // namespace salt

/// MT19937-64 (Matsumoto & Nishimura; Nishimura 2000), bit for bit the engine std::mt19937_64
/// (C++ [rand.eng.mers], the same seeding from one 64-bit value), with a branch-free refill.
/// Satisfies UniformRandomBitGenerator.
class Mt19937_64 {
 public:
  using result_type = std::uint64_t;
  static constexpr std::size_t kStateSize = 312;  // n
  static constexpr std::size_t kShift = 156;      // m

  explicit Mt19937_64(std::uint64_t seed = 5489u) noexcept;

  [[nodiscard]] static constexpr result_type min() noexcept { return 0; }
  [[nodiscard]] static constexpr result_type max() noexcept { return ~result_type{0}; }

  /// The next 64-bit output.
  result_type operator()() noexcept {
    if (index_ >= kStateSize) refill();
    return output_[index_++];
  }

 private:
  /// Regenerate the state (the "twist") and temper it into the next 312 outputs, in two loops
  /// the compiler vectorises.
  void refill() noexcept;

  std::array<std::uint64_t, kStateSize> state_{};
  std::array<std::uint64_t, kStateSize> output_{};  // tempered state_
  std::size_t index_ = kStateSize;
};

/// The seed of one noise stream: SplitMix64's finaliser (Steele, Lea & Flood 2014) applied to
/// the scenario seed and the salt, so that nearby seeds or salts give unrelated streams.
[[nodiscard]] std::uint64_t streamSeed(std::uint64_t scenario_seed, std::uint64_t stream_salt) noexcept;

/// One seeded random stream: the one random source of the simulator (sensors, disturbances,
/// the virtual rigs, the truth mismatch). Uniforms and standard normals; each mapping from the
/// engine's 64-bit draws is fixed here, so a stream is the same on every standard library.
class NoiseSource {
 public:
  /// The stream of a scenario seed and a salt (streamSeed): one per sensor or disturbance.
  NoiseSource(std::uint64_t scenario_seed, std::uint64_t stream_salt);
  /// The stream of the engine seeded with `seed` itself (the rigs, the truth mismatch).
  [[nodiscard]] static NoiseSource fromEngineSeed(std::uint64_t seed);

  /// Uniform in [0, 1), 53 random bits.
  [[nodiscard]] double uniformHalfOpen() noexcept {
    return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }

  /// One N(0, σ²) sample by Box–Muller with u1 in (0, 1] and u2 in [0, 1), the second value of
  /// each pair kept for the next call (σ = 0 still draws, so the sequence does not depend on σ).
  /// The rigs' noise; the sensors use the faster normal().
  [[nodiscard]] double boxMuller(double sigma) noexcept;

  /// Uniform in the open interval (0, 1), 53 random bits.
  [[nodiscard]] double uniform() noexcept {
    return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;
  }

  /// Standard normal N(0, 1): Doornik's (2005) 128-layer ziggurat, one 64-bit draw per sample
  /// in ~99 % of cases (a few ns; the 16×16 ranger draws 25,600 of them per simulated second).
  [[nodiscard]] double normal() noexcept {
    // One draw gives both the abscissa (top 53 bits) and the layer (low 7 bits): independent
    // bits, which avoids the correlation Doornik found in the original Marsaglia–Tsang version.
    const std::uint64_t bits = engine_();
    const double u = 2.0 * ((static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53) - 1.0;  // (−1, 1)
    const auto i = static_cast<int>(bits & 0x7f);
    // Inside the rectangle of layer i that lies wholly under the density: accept (≈ 99 %).
    if (u < zig_r_[i] && -u < zig_r_[i]) return u * zig_x_[i];
    return normalSlow(u, i);
  }

  /// Three independent standard normals.
  [[nodiscard]] Eigen::Vector3d normal3() noexcept { return {normal(), normal(), normal()}; }

  /// Trials until the next success of a Bernoulli(p) sequence, counting the success (≥ 1;
  /// a huge number for p = 0). One draw per call.
  [[nodiscard]] std::int64_t geometric(double p) noexcept;

 private:
  /// The rest of the ziggurat: the wedges, the tail, and a fresh draw after a rejection.
  [[nodiscard]] double normalSlow(double u, int layer) noexcept;
  [[nodiscard]] double normalTail(bool negative) noexcept;

  struct EngineSeed {};
  NoiseSource(EngineSeed, std::uint64_t seed);

  Mt19937_64 engine_;
  double spare_ = 0.0;  // Box–Muller's second value
  bool has_spare_ = false;
  const double* zig_x_;  // ziggurat layer edges (shared, computed once)
  const double* zig_r_;  // their ratios
};

/// A fixed-rate schedule: sample k is due at k/rate. due(t) is true at the first call with
/// t ≥ k/rate (less a tolerance for the round-off of accumulated simulation time); the
/// schedule then moves to the first k' with k'/rate > t, so a caller slower than the rate gets
/// the latest sample, not a backlog, and the rate never drifts.
class SampleClock {
 public:
  /// Time tolerance of the schedule [s]: far below any simulation step, far above the
  /// round-off of t accumulated over hours.
  static constexpr double kTolerance_s = 1e-7;

  explicit SampleClock(double rate_Hz) noexcept : period_s_(1.0 / rate_Hz) {}

  /// True when a sample is due at time t; advances the schedule past t.
  [[nodiscard]] bool due(double t_s) noexcept;
  [[nodiscard]] double period_s() const noexcept { return period_s_; }
  /// Time at which the next sample falls due [s].
  [[nodiscard]] double next_s() const noexcept { return static_cast<double>(next_index_) * period_s_; }

 private:
  double period_s_;
  std::int64_t next_index_ = 0;
};

/// Vector first-order Gauss–Markov process with unit stationary variance per axis and
/// correlation time τ: x ← φ·x + √(1 − φ²)·w, φ = e^(−dt/τ), w ~ N(0, I). This is the exact
/// discretisation of dx = −x/τ·dt + √(2/τ)·dW for any dt, so the statistics do not depend on
/// the step. It starts from its stationary distribution (one draw at construction).
class GaussMarkov3 {
 public:
  GaussMarkov3(double correlation_time_s, NoiseSource& noise) noexcept;
  /// Advance by dt ≥ 0 [s]; returns the new value.
  const Eigen::Vector3d& advance(double dt_s, NoiseSource& noise) noexcept;
  [[nodiscard]] const Eigen::Vector3d& value() const noexcept { return x_; }

 private:
  double tau_s_;
  double last_dt_s_ = -1.0;  // cache of φ for a repeated dt
  double phi_ = 0.0;
  double drive_ = 0.0;
  Eigen::Vector3d x_;
};

/// A random body force and torque: two unit Gauss–Markov processes with one correlation time,
/// drawn from one noise stream (the force's process first, at construction and at every step).
/// The disturbances scale them by their own standard deviations.
class GaussMarkovWrench {
 public:
  GaussMarkovWrench(double correlation_time_s, std::uint64_t scenario_seed,
                    std::uint64_t stream_salt);
  /// Advance by dt ≥ 0 [s]; a non-finite or negative dt leaves both unchanged.
  void advance(double dt_s) noexcept;
  [[nodiscard]] const Eigen::Vector3d& force() const noexcept { return force_.value(); }
  [[nodiscard]] const Eigen::Vector3d& torque() const noexcept { return torque_.value(); }

 private:
  NoiseSource noise_;
  GaussMarkov3 force_;
  GaussMarkov3 torque_;
};

/// True when every field of the state is finite (sensors refuse anything else).
[[nodiscard]] bool isFinite(const PlantState& state) noexcept;

}  // namespace geaware::sim
