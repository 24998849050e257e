// SPDX-License-Identifier: BSD-3-Clause
#include "vec_sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace geaware::python {

// --- The pool ----------------------------------------------------------------------------------

StepPool::StepPool(int threads) {
  const int n = std::max(1, threads);
  for (int w = 1; w < n; ++w) workers_.emplace_back([this, w] { work(w); });
}

StepPool::~StepPool() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  start_.notify_all();
  for (auto& t : workers_) t.join();
}

void StepPool::share(int w, std::size_t n) {
  const auto t = static_cast<std::size_t>(threads());
  const auto k = static_cast<std::size_t>(w);
  for (std::size_t i = n * k / t; i < n * (k + 1) / t; ++i) (*f_)(i);
}

void StepPool::work(int w) {
  std::uint64_t seen = 0;
  for (;;) {
    std::size_t n = 0;
    {
      std::unique_lock<std::mutex> lock(m_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      n = n_;
    }
    share(w, n);
    {
      const std::lock_guard<std::mutex> lock(m_);
      --pending_;
    }
    done_.notify_one();
  }
}

void StepPool::run(std::size_t n, const std::function<void(std::size_t)>& f) {
  if (workers_.empty() || n < 2) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(m_);
    f_ = &f;
    n_ = n;
    pending_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  start_.notify_all();
  share(0, n);
  std::unique_lock<std::mutex> lock(m_);
  done_.wait(lock, [&] { return pending_ == 0; });
  f_ = nullptr;
}

// --- The batch ---------------------------------------------------------------------------------

namespace {

// Offsets of the observation row (WorldBatch::fields() names them for Python).
enum : std::size_t {
  kT = 0, kTraj = 1, kTrueP = 2, kTrueV = 5, kTrueQ = 8, kTrueW = 12, kTrueN = 15, kTrueH = 19,
  kRefP = 20, kRefV = 23, kRefA = 26, kRefYaw = 29, kImuT = 30, kGyro = 31, kAccel = 34,
  kMocapT = 37, kMocapP = 38, kMocapQ = 41, kRotorT = 45, kRotorN = 46, kBattery = 50,
  kThrottle = 51, kRangerT = 55, kRanger = 56
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<ObsField> fieldsFor(int zones) {
  return {
      {"t_s", kT, 1, "plant time [s]"},
      {"t_traj_s", kTraj, 1, "trajectory time, t_s - start_hover_s [s]"},
      {"true_p_W_m", kTrueP, 3, "TRUE position of the rotor-plane centre, world ENU [m]"},
      {"true_v_W_mps", kTrueV, 3, "TRUE velocity [m/s]"},
      {"true_q_WB", kTrueQ, 4, "TRUE attitude, body to world, (w, x, y, z)"},
      {"true_w_B_radps", kTrueW, 3, "TRUE body rates [rad/s]"},
      {"true_n_rpm", kTrueN, 4, "TRUE rotor speeds, mixer order [rpm]"},
      {"true_height_m", kTrueH, 1, "TRUE height of the rotor-plane centre above the terrain under it [m]"},
      {"ref_p_W_m", kRefP, 3, "reference position at t_traj_s [m]"},
      {"ref_v_W_mps", kRefV, 3, "reference velocity [m/s]"},
      {"ref_a_W_mps2", kRefA, 3, "reference acceleration [m/s^2]"},
      {"ref_yaw_rad", kRefYaw, 1, "reference yaw [rad]"},
      {"imu_t_s", kImuT, 1, "time of the latest IMU sample (NaN before the first) [s]"},
      {"imu_gyro_B_radps", kGyro, 3, "latest gyro sample, with bias and noise [rad/s]"},
      {"imu_accel_B_mps2", kAccel, 3, "latest accelerometer sample (specific force) [m/s^2]"},
      {"mocap_t_s", kMocapT, 1, "capture time of the latest delivered motion-capture pose [s]"},
      {"mocap_p_W_m", kMocapP, 3, "latest motion-capture position [m]"},
      {"mocap_q_WB", kMocapQ, 4, "latest motion-capture attitude (w, x, y, z)"},
      {"rotor_t_s", kRotorT, 1, "time of the latest rotor-speed telemetry [s]"},
      {"rotor_n_rpm", kRotorN, 4, "latest measured rotor speeds, mixer order [rpm]"},
      {"battery_V", kBattery, 1, "battery terminal voltage [V]"},
      {"throttle", kThrottle, 4, "throttles held over the last control period, mixer order [0, 1]"},
      {"ranger_t_s", kRangerT, 1, "time of the latest lattice-ranger frame [s]"},
      {"ranger_range_m", kRanger, static_cast<std::size_t>(zones),
       "latest ranger frame, zone (i, j) at i*side + j, distance along its ray (NaN: no return) [m]"},
  };
}

void put(double* row, std::size_t at, const Eigen::Vector3d& v) noexcept {
  for (int k = 0; k < 3; ++k) row[at + static_cast<std::size_t>(k)] = v[k];
}
void put(double* row, std::size_t at, const Eigen::Quaterniond& q) noexcept {
  row[at] = q.w();
  row[at + 1] = q.x();
  row[at + 2] = q.y();
  row[at + 3] = q.z();
}

}  // namespace

WorldBatch::WorldBatch(const experiments::FlightScenario& scenario,
                       const std::vector<std::uint64_t>& seeds, int threads)
    : slots_(seeds.size()), pool_(threads) {
  ranger_zones_ = scenario.sensors.ranger.side * scenario.sensors.ranger.side;
  fields_ = fieldsFor(ranger_zones_);
  width_ = kRanger + static_cast<std::size_t>(ranger_zones_);
  obs_.assign(slots_.size() * width_, kNaN);
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    slots_[i].scenario = scenario;
    reset(i, seeds[i]);
  }
  if (!slots_.empty()) period_s_ = slots_[0].world->controlPeriod_s();
}

void WorldBatch::reset(std::size_t i, std::uint64_t seed) {
  Slot& s = slots_[i];
  s.world.reset();  // the old world refers to the scenario: gone before the seed changes
  s.scenario.seed = seed;
  s.world = std::make_unique<experiments::SteppedWorld>(s.scenario);
  s.done = false;
  std::fill_n(obs_.begin() + static_cast<std::ptrdiff_t>(i * width_), width_, kNaN);
  const std::array<double, 4> held = s.world->throttle();
  for (std::size_t k = 0; k < 4; ++k) obs_[i * width_ + kThrottle + k] = held[k];
  record(i, s.world->sense());
  recordTick(i);
}

void WorldBatch::step(const double* throttles) {
  pool_.run(slots_.size(), [&](std::size_t i) {
    stepOne(i, {throttles[4 * i], throttles[4 * i + 1], throttles[4 * i + 2], throttles[4 * i + 3]});
  });
}

// As runFlight: the throttles are held from this tick; plant step, then every sensor at the new
// state, until the next tick, the end of the scenario or a strike.
void WorldBatch::stepOne(std::size_t i, const std::array<double, 4>& throttle) noexcept {
  Slot& s = slots_[i];
  if (s.done) return;
  experiments::SteppedWorld& w = *s.world;
  w.setThrottle(throttle);
  for (std::size_t k = 0; k < 4; ++k) obs_[i * width_ + kThrottle + k] = throttle[k];
  do {
    if (w.lastStep() || !w.step()) {
      s.done = true;
      break;
    }
    record(i, w.sense());
  } while (!w.controlTickDue());
  if (w.lastStep()) s.done = true;
  recordTick(i);
}

void WorldBatch::record(std::size_t i, const sim::SensorReadings& r) noexcept {
  double* row = obs_.data() + i * width_;
  if (r.imu) {
    row[kImuT] = r.imu->t_s;
    put(row, kGyro, r.imu->gyro_B);
    put(row, kAccel, r.imu->accel_B);
  }
  if (r.mocap) {
    row[kMocapT] = r.mocap->t_s;
    put(row, kMocapP, r.mocap->p_W);
    put(row, kMocapQ, r.mocap->q_WB);
  }
  if (r.rotors) {
    row[kRotorT] = r.rotors->t_s;
    for (int k = 0; k < 4; ++k) row[kRotorN + static_cast<std::size_t>(k)] = r.rotors->n_rpm[k];
  }
  if (r.ranger) {
    row[kRangerT] = r.ranger->t_s;
    const int zones = std::min(ranger_zones_, r.ranger->side * r.ranger->side);
    for (int z = 0; z < zones; ++z) {
      const auto k = static_cast<std::size_t>(z);
      row[kRanger + k] = r.ranger->valid[k] ? r.ranger->range_m[k] : kNaN;
    }
  }
}

void WorldBatch::recordTick(std::size_t i) noexcept {
  const experiments::SteppedWorld& w = *slots_[i].world;
  double* row = obs_.data() + i * width_;
  const sim::PlantState& x = w.truth();
  row[kT] = x.t_s;
  row[kTraj] = w.trajectoryTime_s();
  put(row, kTrueP, x.p_W);
  put(row, kTrueV, x.v_W);
  put(row, kTrueQ, x.q_WB);
  put(row, kTrueW, x.w_B);
  for (std::size_t k = 0; k < 4; ++k) row[kTrueN + k] = x.n_rpm[k];
  row[kTrueH] = x.p_W.z() - w.terrain().heightAt(x.p_W.x(), x.p_W.y());
  const traj::FlatOutput ref = w.scenario().trajectory->sample(w.trajectoryTime_s());
  put(row, kRefP, ref.p_W);
  put(row, kRefV, ref.v_W);
  put(row, kRefA, ref.a_W);
  row[kRefYaw] = ref.yaw_rad;
  row[kBattery] = w.batteryVoltage_V();
}

}  // namespace geaware::python
