// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/sampling.hpp"

#include <cmath>
#include <numbers>
#include <limits>

namespace geaware::sim {
namespace {

std::uint64_t splitmix64(std::uint64_t z) noexcept {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Doornik, "An Improved Ziggurat Method to Generate Normal Random Samples" (2005), ZIGNOR with
// 128 layers of equal area V; R is the start of the tail.
constexpr int kZigLayers = 128;
constexpr double kZigR = 3.442619855899;
constexpr double kZigV = 9.91256303526217e-3;

struct ZigguratTables {
  std::array<double, kZigLayers + 1> x{};  // layer edges, x[1] = R > x[2] > … > x[128] = 0; x[0] = V/f(R)
  std::array<double, kZigLayers> r{};      // x[i+1]/x[i]: the part of layer i surely under the curve

  ZigguratTables() {
    double f = std::exp(-0.5 * kZigR * kZigR);
    x[0] = kZigV / f;  // the bottom layer: a box of area V including the tail
    x[1] = kZigR;
    x[kZigLayers] = 0.0;
    for (int i = 2; i < kZigLayers; ++i) {
      x[i] = std::sqrt(-2.0 * std::log(kZigV / x[i - 1] + f));
      f = std::exp(-0.5 * x[i] * x[i]);
    }
    for (int i = 0; i < kZigLayers; ++i) r[i] = x[i + 1] / x[i];
  }
};

const ZigguratTables& zigguratTables() {
  static const ZigguratTables tables;
  return tables;
}

}  // namespace

Mt19937_64::Mt19937_64(std::uint64_t seed) noexcept {
  // [rand.eng.mers]: x_i = f·(x_{i−1} xor (x_{i−1} >> (w − 2))) + i, f = 6364136223846793005.
  state_[0] = seed;
  for (std::size_t i = 1; i < kStateSize; ++i) {
    const std::uint64_t prev = state_[i - 1];
    state_[i] = 6364136223846793005ULL * (prev ^ (prev >> 62)) + i;
  }
  index_ = kStateSize;
}

void Mt19937_64::refill() noexcept {
  // x_k = x_{k+m} xor (y >> 1) xor (a if y is odd), y = upper bit of x_k | lower 31 of x_{k+1}.
  // The "if odd" is a mask, not a branch: on random bits a branch mispredicts half the time.
  constexpr std::uint64_t kUpper = 0xFFFFFFFF80000000ULL;
  constexpr std::uint64_t kLower = 0x7FFFFFFFULL;
  constexpr std::uint64_t kMatrix = 0xB5026F5AA96619E9ULL;
  const auto twist = [](std::uint64_t xk, std::uint64_t xk1, std::uint64_t xkm) {
    const std::uint64_t y = (xk & kUpper) | (xk1 & kLower);
    return xkm ^ (y >> 1) ^ ((std::uint64_t{0} - (y & 1u)) & kMatrix);
  };
  std::size_t k = 0;
  for (; k < kStateSize - kShift; ++k)
    state_[k] = twist(state_[k], state_[k + 1], state_[k + kShift]);
  for (; k < kStateSize - 1; ++k)
    state_[k] = twist(state_[k], state_[k + 1], state_[k + kShift - kStateSize]);
  state_[kStateSize - 1] = twist(state_[kStateSize - 1], state_[0], state_[kShift - 1]);
  // Tempering, [rand.eng.mers] with (u, d, s, b, t, c, l) = (29, 0x5555…, 17, 0x71D6…, 37,
  // 0xFFF7…, 43).
  for (std::size_t i = 0; i < kStateSize; ++i) {
    std::uint64_t x = state_[i];
    x ^= (x >> 29) & 0x5555555555555555ULL;
    x ^= (x << 17) & 0x71D67FFFEDA60000ULL;
    x ^= (x << 37) & 0xFFF7EEE000000000ULL;
    x ^= x >> 43;
    output_[i] = x;
  }
  index_ = 0;
}

std::uint64_t streamSeed(std::uint64_t scenario_seed, std::uint64_t stream_salt) noexcept {
  return splitmix64(splitmix64(scenario_seed) ^ stream_salt);
}

NoiseSource::NoiseSource(std::uint64_t scenario_seed, std::uint64_t stream_salt)
    : engine_(streamSeed(scenario_seed, stream_salt)),
      zig_x_(zigguratTables().x.data()),
      zig_r_(zigguratTables().r.data()) {}

NoiseSource::NoiseSource(EngineSeed, std::uint64_t seed)
    : engine_(seed), zig_x_(zigguratTables().x.data()), zig_r_(zigguratTables().r.data()) {}

NoiseSource NoiseSource::fromEngineSeed(std::uint64_t seed) { return {EngineSeed{}, seed}; }

double NoiseSource::boxMuller(double sigma) noexcept {
  if (has_spare_) {
    has_spare_ = false;
    return sigma * spare_;
  }
  const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
  const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;          // [0, 1)
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return sigma * r * std::cos(a);
}

double NoiseSource::normalSlow(double u, int i) noexcept {
  // The bottom layer's overhang is the tail beyond R.
  if (i == 0) return normalTail(u < 0.0);
  // The wedge between x[i+1] and x[i]: accept under the density, else start over.
  const double x = u * zig_x_[i];
  const double f0 = std::exp(-0.5 * (zig_x_[i] * zig_x_[i] - x * x));
  const double f1 = std::exp(-0.5 * (zig_x_[i + 1] * zig_x_[i + 1] - x * x));
  if (f1 + uniform() * (f0 - f1) < 1.0) return x;
  return normal();
}

double NoiseSource::normalTail(bool negative) noexcept {
  // Marsaglia (1964): exponential proposals beyond R.
  double x = 0.0;
  double y = 0.0;
  do {
    x = std::log(uniform()) / kZigR;
    y = std::log(uniform());
  } while (-2.0 * y < x * x);
  return negative ? x - kZigR : kZigR - x;
}

std::int64_t NoiseSource::geometric(double p) noexcept {
  const double u = uniform();
  constexpr auto kNever = std::numeric_limits<std::int64_t>::max() / 2;
  if (!(p > 0.0)) return kNever;
  if (p >= 1.0) return 1;
  const double k = std::floor(std::log(u) / std::log1p(-p));
  return k >= static_cast<double>(kNever) ? kNever : static_cast<std::int64_t>(k) + 1;
}

bool SampleClock::due(double t_s) noexcept {
  if (t_s + kTolerance_s < next_s()) return false;
  // The first index strictly after t (with the same tolerance).
  const auto k = static_cast<std::int64_t>(std::floor((t_s + kTolerance_s) / period_s_)) + 1;
  next_index_ = k > next_index_ ? k : next_index_ + 1;
  return true;
}

GaussMarkov3::GaussMarkov3(double correlation_time_s, NoiseSource& noise) noexcept
    : tau_s_(correlation_time_s), x_(noise.normal3()) {}

GaussMarkovWrench::GaussMarkovWrench(double correlation_time_s, std::uint64_t scenario_seed,
                                     std::uint64_t stream_salt)
    : noise_(scenario_seed, stream_salt),
      force_(correlation_time_s, noise_),
      torque_(correlation_time_s, noise_) {}

void GaussMarkovWrench::advance(double dt_s) noexcept {
  if (!(std::isfinite(dt_s) && dt_s >= 0.0)) return;
  force_.advance(dt_s, noise_);
  torque_.advance(dt_s, noise_);
}

const Eigen::Vector3d& GaussMarkov3::advance(double dt_s, NoiseSource& noise) noexcept {
  if (dt_s != last_dt_s_) {
    last_dt_s_ = dt_s;
    phi_ = std::exp(-dt_s / tau_s_);
    drive_ = std::sqrt(1.0 - phi_ * phi_);
  }
  x_ = phi_ * x_ + drive_ * noise.normal3();
  return x_;
}

bool isFinite(const PlantState& s) noexcept {
  // A NaN or ±∞ anywhere makes the sum non-finite (physical magnitudes cannot overflow it).
  // Summed as a tree, not a chain: every sensor calls this at every plant step.
  const double a = (s.t_s + s.p_W.sum()) + (s.v_W.sum() + s.q_WB.coeffs().sum());
  const double b = (s.w_B.sum() + s.a_W.sum()) + (s.w_dot_B.sum() + (s.n_rpm[0] + s.n_rpm[1]));
  return std::isfinite(a + (b + (s.n_rpm[2] + s.n_rpm[3])));
}

}  // namespace geaware::sim
