// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/neural_baseline.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/flight_series.hpp"
#include "geaware/model/rotor_drag.hpp"
#include "geaware/model/vehicle_schema.hpp"
#include "geaware/neural/weights_file.hpp"
#include "geaware/sim/rigs.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Training rows of one flight, from sensor-derived values only (see the header). Memory is
/// reserved up front: onTick never allocates.
class TrainingRows final : public FlightObserver {
 public:
  TrainingRows(const model::VehicleParams& controller_vehicle, std::size_t ticks, int stride)
      : mass_kg_(controller_vehicle.mass_kg),
        k_T_(controller_vehicle.rotor.k_T_N_per_rpm2),
        d_high_(model::RotorDragModel(controller_vehicle.drag).highAltitudeCoefficients()),
        stride_(static_cast<std::size_t>(std::max(stride, 1))) {
    features_.reserve(ticks / stride_ + 2);
    labels_.reserve(ticks / stride_ + 2);
  }

  void onTick(const FlightTick& t) noexcept override {
    if (!t.controller_active || !t.input.height_valid) return;
    if ((active_++ % stride_) != 0 || features_.size() == features_.capacity()) return;
    const Eigen::Matrix3d R = t.input.estimate.q_WB.toRotationMatrix();
    const double thrust = k_T_ * t.input.rotor_speeds_rpm.squaredNorm();
    const Eigen::Vector3d label = mass_kg_ * (R * t.input.accel_B) - thrust * R.col(2) -
                                  model::RotorDragModel::force_W(R, t.input.estimate.v_W, d_high_);
    const control::ResidualFeatures f{t.input.height_m, t.input.estimate.v_W, t.input.estimate.q_WB,
                                      t.input.rotor_speeds_rpm};
    features_.push_back(neural::makeFeatures(f));
    labels_.push_back(label);
  }

  [[nodiscard]] const std::vector<neural::FeatureVector>& features() const { return features_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& labels() const { return labels_; }

 private:
  double mass_kg_;
  double k_T_;
  Eigen::Vector2d d_high_;
  std::size_t stride_;
  std::size_t active_ = 0;
  std::vector<neural::FeatureVector> features_;
  std::vector<Eigen::Vector3d> labels_;
};

std::string num(double v) { return fmt::format("{}", v); }

/// One line per vehicle parameter in use (model/vehicle_schema.hpp), "<p>.<key> = <values>":
/// every number the controller-side model is built from, the name aside.
void vehicleLines(std::string& k, const std::string& p, const model::VehicleParams& v) {
  model::forEachParameter(v, [&](std::string_view key, std::string_view, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<V, double>) {
      k += fmt::format("{}.{} = {}\n", p, key, num(value));
    } else if constexpr (std::is_same_v<V, std::vector<double>>) {
      k += fmt::format("{}.{} =", p, key);
      for (const double x : value) k += " " + num(x);
      k += "\n";
    }
  });
}

/// The truth as far as it shapes the collected data: its scalar parameters and a fingerprint of
/// its aerodynamics (noise-free platform wrenches at a few heights and tilts), so that any
/// change of the truth's aerodynamics invalidates the cache without listing their fields.
void truthLines(std::string& k, const sim::TruthParams& t) {
  k += fmt::format("truth.mass_kg = {}\ntruth.inertia_kgm2 = {} {} {}\n", num(t.mass_kg),
                   num(t.inertia_kgm2(0, 0)), num(t.inertia_kgm2(1, 1)), num(t.inertia_kgm2(2, 2)));
  k += fmt::format("truth.cog_offset_m = {} {} {}\n", num(t.cog_offset_B.x()),
                   num(t.cog_offset_B.y()), num(t.cog_offset_B.z()));
  k += fmt::format("truth.rotor = {} {} {} {}\n", num(t.k_T_N_per_rpm2), num(t.k_I_Nm_per_rpm2),
                   num(t.propeller_radius_m), num(t.motor.J_R_kgm2));
  k += fmt::format("truth.motor = {} {} {} {} {} {}\n", num(t.motor.time_constant_s),
                   num(t.motor.min_speed_rpm), num(t.motor.max_speed_rpm),
                   num(t.motor.throttle.c2_rpm2), num(t.motor.throttle.c1_rpm2),
                   num(t.motor.throttle.c0_rpm2));
  k += fmt::format("truth.battery = {} {} {}\n", t.battery.enabled, num(t.battery.full_voltage_V),
                   num(t.battery.internal_resistance_ohm));
  sim::PlatformParams quiet;
  quiet.force_noise_N = 0.0;
  quiet.torque_noise_Nm = 0.0;
  const sim::ForceTorquePlatform platform(t.rotorGeometry(), t.aero, quiet);
  k += "truth.aero =";
  for (double h : {0.08, 0.12, 0.2, 0.3, 0.5, 1.0, 2.0}) {
    for (double tilt : {0.0, 5.0}) {
      const auto w = platform.wrench(h, tilt, {10000.0, 10500.0, 9800.0, 10200.0}).wrench;
      k += fmt::format(" {} {}", num(w.force_B.z()), num(w.torque_B.y()));
    }
  }
  k += "\n";
}

FlightScenario collectionScenario(const FlightScenario& base, const NeuralSettings& s,
                                  std::size_t k) {
  FlightScenario f = base;
  traj::LemniscateParams p;
  p.half_extent_x_m = s.half_extent_x_m;
  p.half_extent_y_m = s.half_extent_y_m;
  p.height_m = s.heights_m[k];
  p.peak_speed_mps = s.speed_mps;
  f.trajectory = std::make_shared<traj::Lemniscate>(p);
  f.controller.acceleration = s.acceleration;
  f.controller.torque = s.torque;
  f.residual = nullptr;
  f.seed = s.first_seed + k;
  return f;
}

}  // namespace

neural::TrainOptions NeuralSettings::defaultTrainOptions() {
  neural::TrainOptions o;
  o.hidden_widths = {32, 32};
  o.epochs = 300;
  o.batch_size = 64;
  o.learning_rate = 1e-3;
  o.lipschitz_gamma = 10.0;
  o.seed = 1;
  return o;
}

std::string hashText(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;  // FNV-1a 64
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", h);
}

std::string neuralCacheKey(const FlightScenario& base, const NeuralSettings& s) {
  std::string k = fmt::format("geaware neural-lander cache, version {}\n", kNeuralCacheVersion);
  vehicleLines(k, "controller", base.vehicle);
  truthLines(k, base.truth ? *base.truth : sim::fromNominal(base.vehicle));
  if (base.mismatch) {
    const auto& m = *base.mismatch;
    k += fmt::format("mismatch = {} {} {} {} {}\n", num(m.mass_rel), num(m.inertia_rel),
                     num(m.cog_offset_m), num(m.cog_offset_z_m), num(m.thrust_spread_rel));
  } else {
    k += "mismatch = none\n";
  }
  if (!s.world_key.empty()) k += "world:\n" + s.world_key;
  const auto& d = base.disturbances;
  k += fmt::format("turbulence = {} {} {} {} {} {} {} {} {} {} {}\n", d.turbulence,
                   num(d.turbulence_params.force_std_N.x()), num(d.turbulence_params.force_std_N.y()),
                   num(d.turbulence_params.force_std_N.z()), num(d.turbulence_params.torque_std_Nm.x()),
                   num(d.turbulence_params.torque_std_Nm.y()), num(d.turbulence_params.torque_std_Nm.z()),
                   num(d.turbulence_params.correlation_time_s), num(d.turbulence_params.scale_height_m),
                   num(d.turbulence_params.cutoff_height_m), d.wind);
  k += fmt::format("flights.start_hover_s = {}\nflights.plant_rate_hz = {}\n", num(base.start_hover_s),
                   num(base.plant_rate_hz));
  k += fmt::format("flights.controller = {}:{} rate {} gains {} {} {} {} {} {} {} {} {} {} {} {}\n",
                   control::toString(s.acceleration), control::toString(s.torque),
                   num(base.controller.rate_hz), num(base.controller.k_p_per_s2.x()),
                   num(base.controller.k_p_per_s2.y()), num(base.controller.k_p_per_s2.z()),
                   num(base.controller.k_v_per_s.x()), num(base.controller.k_v_per_s.y()),
                   num(base.controller.k_v_per_s.z()), num(base.controller.k_xi_per_s.x()),
                   num(base.controller.k_xi_per_s.y()), num(base.controller.k_xi_per_s.z()),
                   num(base.controller.k_w_per_s.x()), num(base.controller.k_w_per_s.y()),
                   num(base.controller.k_w_per_s.z()));
  k += "flights.heights_m =";
  for (double h : s.heights_m) k += " " + num(h);
  k += fmt::format("\nflights.lemniscate = {} {} {}\nflights.first_seed = {}\nflights.tick_stride = {}\n",
                   num(s.speed_mps), num(s.half_extent_x_m), num(s.half_extent_y_m), s.first_seed,
                   s.tick_stride);
  const auto& o = s.train;
  k += "train.hidden_widths =";
  for (int w : o.hidden_widths) k += fmt::format(" {}", w);
  k += fmt::format(
      "\ntrain = epochs {} batch {} lr {} decay {} sn {} gamma {} power {} validation {} "
      "min_std {} seed {}\n",
      o.epochs, o.batch_size, num(o.learning_rate), num(o.weight_decay), o.spectral_normalisation,
      num(o.lipschitz_gamma), o.power_iterations, num(o.validation_fraction),
      num(o.min_input_std), o.seed);
  return k;
}

NeuralBaseline prepareNeuralBaseline(const FlightScenario& base, const NeuralSettings& s,
                                     const std::filesystem::path& cache_dir, int jobs,
                                     Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  auto say = [&](const std::string& m) {
    if (progress != nullptr) progress->message(m);
  };
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  NeuralBaseline nb;
  const std::string key = neuralCacheKey(base, s);
  nb.key_hash = hashText(key);
  if (!cache_dir.empty()) {
    nb.file = cache_dir / ("neural-lander-" + nb.key_hash + ".yaml");
    if (std::filesystem::exists(nb.file)) {
      try {
        neural::WeightsDocument doc = neural::loadWeights(nb.file);
        const auto it = doc.provenance.find("cache_key");
        if (it != doc.provenance.end() && it->second == key) {
          nb.network = std::make_shared<neural::ResidualNetwork>(doc.weights);
          nb.trained = false;
          nb.train_loss_N2 = kNaN;
          nb.validation_loss_N2 = kNaN;
          nb.wall_s = elapsed();
          say(fmt::format("Neural-Lander: reusing {} (inputs unchanged)", nb.file.string()));
          return nb;
        }
        say(fmt::format("Neural-Lander: {} does not match its key; retraining", nb.file.string()));
      } catch (const std::exception& e) {
        say(fmt::format("Neural-Lander: cannot reuse {} ({}); retraining", nb.file.string(),
                        e.what()));
      }
    }
  }

  // 1. Collection flights, one observer each (results do not depend on the thread count).
  std::vector<FlightJob> jobs_list;
  std::vector<std::unique_ptr<TrainingRows>> rows;
  for (std::size_t k = 0; k < s.heights_m.size(); ++k) {
    FlightScenario f = collectionScenario(base, s, k);
    rows.push_back(std::make_unique<TrainingRows>(base.vehicle, expectedTicks(f), s.tick_stride));
    jobs_list.push_back({std::move(f), rows.back().get(),
                         fmt::format("Neural-Lander collection flight at {} m", s.heights_m[k])});
  }
  say(fmt::format("Neural-Lander: {} collection flights ({}:{}, {} m/s lemniscates)",
                  jobs_list.size(), control::toString(s.acceleration), control::toString(s.torque),
                  s.speed_mps));
  const auto flights = runFlights(
      jobs_list, jobs, [&](std::size_t done, std::size_t total, const FlightJob&, const FlightResult&) {
        if (progress != nullptr) {
          progress->update(static_cast<double>(done), static_cast<double>(total), "collection flights");
        }
      });
  neural::TrainingSet set;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (flights[k].crash) {
      say(fmt::format("Neural-Lander: collection flight at {} m ended in a strike ({}); its rows "
                      "up to the strike are kept",
                      s.heights_m[k], flights[k].crash_description));
    }
    for (std::size_t i = 0; i < rows[k]->features().size(); ++i) {
      (void)set.add(rows[k]->features()[i], rows[k]->labels()[i]);
    }
  }
  nb.rows = set.size();

  // 2. Training.
  say(fmt::format("Neural-Lander: training on {} rows ({} epochs)", nb.rows, s.train.epochs));
  const neural::TrainResult trained =
      neural::train(set, s.train, [&](int epoch, double /*train*/, double /*validation*/) {
        if (progress != nullptr) progress->update(epoch, s.train.epochs, "epochs");
      });
  nb.train_loss_N2 = trained.train_loss.empty() ? kNaN : trained.train_loss.back();
  nb.validation_loss_N2 = trained.validation_loss.empty() ? kNaN : trained.validation_loss.back();
  nb.network = std::make_shared<neural::ResidualNetwork>(trained.weights);
  nb.trained = true;

  // 3. Cache. A cache that cannot be written costs the next run a training, never this run's
  // result: a warning, and the network is used unsaved.
  if (!nb.file.empty()) {
    try {
      std::filesystem::create_directories(cache_dir);
      neural::WeightsDocument doc;
      doc.weights = trained.weights;
      doc.provenance["produced_by"] = "geaware bench (experiments::prepareNeuralBaseline)";
      doc.provenance["cache_key_hash"] = nb.key_hash;
      doc.provenance["cache_key"] = key;
      doc.provenance["rows"] = std::to_string(nb.rows);
      doc.provenance["final_validation_loss_N2"] = num(nb.validation_loss_N2);
      // Written through a temporary file and renamed (io::AtomicFile), so a concurrent reader
      // never sees half a file.
      neural::saveWeights(nb.file, doc);
    } catch (const std::exception& e) {
      say(fmt::format("warning: Neural-Lander: the cache {} cannot be written ({}); the trained "
                      "network is used without saving it",
                      nb.file.string(), e.what()));
      nb.file.clear();
    }
  }
  nb.wall_s = elapsed();
  say(fmt::format("Neural-Lander: trained in {:.1f} s (validation MSE {:.4f} N² per component)",
                  nb.wall_s, nb.validation_loss_N2));
  return nb;
}

}  // namespace geaware::experiments
