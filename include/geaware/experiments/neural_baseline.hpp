// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Step 2 of the campaign: the Neural-Lander baseline (Shi et al. 2019; docs/neural-lander.md)
// trained for the campaign's vehicle. Flights at several heights are flown with a baseline
// controller that has no ground-effect model (translational INDI by default) and logged
// through a FlightObserver; the training rows are built from sensor-derived values only, as
// on a real vehicle:
//   features = (ranger height, estimated velocity and attitude, telemetry rotor speeds)
//   label    = m·R·f_imu − k_T·Σn²·z_B − f_D∞(R, v)          [N, world frame]
// (f_imu the bias-corrected specific force, m, k_T and the high-altitude drag f_D∞ those of
// the controller's vehicle): the force the controller's nominal model leaves unexplained, which
// is exactly what the controller subtracts in `neural` mode (it compensates f_D∞ itself).
//
// The trained network is cached as a weight file named by a hash of everything that affects
// it (kNeuralCacheVersion, the controller's and the truth's parameters, the disturbances, the
// collection flights, the training options); a matching file is loaded instead of retraining.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/progress.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/neural/residual_network.hpp"
#include "geaware/neural/trainer.hpp"

namespace geaware::experiments {

/// Bump when the collection, the labels or the training change in a way the key does not see.
inline constexpr int kNeuralCacheVersion = 1;

struct NeuralSettings {
  /// Lemniscate heights of the collection flights [m].
  std::vector<double> heights_m = {0.09, 0.12, 0.15, 0.2, 0.3, 0.5, 1.0};
  double speed_mps = 1.0;        ///< peak speed of the collection lemniscates [m/s]
  double half_extent_x_m = 1.5;  ///< [m]
  double half_extent_y_m = 0.8;  ///< [m]
  control::AccelerationCompensation acceleration = control::AccelerationCompensation::kIndi;
  control::TorqueCompensation torque = control::TorqueCompensation::kNone;
  std::uint64_t first_seed = 1000;  ///< flight k uses first_seed + k (apart from the table's)
  int tick_stride = 4;              ///< one row every tick_stride active control ticks
  neural::TrainOptions train = defaultTrainOptions();
  /// The world's `truth:` section as the truth file writes it (io::truthSectionYaml; the
  /// campaign fills it): part of the cache key, so that any truth-file key (sensors, room air,
  /// per-motor spread…) changes the key. Empty: not part of the key.
  std::string world_key;

  /// 17 → 32 → 32 → 3, 300 epochs, batch 64, Adam 1e-3, γ = 10 (the ground effect near
  /// 0.1 m needs ≈ 10 N per σ_h, docs/neural-lander.md), seed 1.
  [[nodiscard]] static neural::TrainOptions defaultTrainOptions();
};

struct NeuralBaseline {
  std::shared_ptr<const neural::ResidualNetwork> network;
  bool trained = false;          ///< false: loaded from the cache or the user's file
  bool user_file = false;        ///< the user's weight file (CampaignOptions::neural_weights)
  std::string key_hash;          ///< 16 hex digits
  std::filesystem::path file;    ///< the cached weight file (empty without a cache)
  std::size_t rows = 0;          ///< training rows collected (0 when loaded)
  double train_loss_N2 = 0.0;    ///< final losses (NaN when loaded) [N²]
  double validation_loss_N2 = 0.0;
  double wall_s = 0.0;           ///< collection + training (or loading) [s]
};

/// The cache key text (one "name = value" a line) for flights built on `base` (its vehicle is
/// the controller's, its truth the simulator's; trajectory, controller switches and seed are
/// replaced per collection flight). Numbers in their shortest round-trip form.
[[nodiscard]] std::string neuralCacheKey(const FlightScenario& base, const NeuralSettings& s);
/// FNV-1a 64 of the text, as 16 hex digits.
[[nodiscard]] std::string hashText(const std::string& text);

/// Loads the cached network for this key from `cache_dir` when there is one, otherwise flies
/// the collection flights on `jobs` threads, trains and (with a cache_dir) saves. An empty
/// cache_dir disables the cache. `progress` (optional) receives the stages, the collection
/// flights and the training epochs.
[[nodiscard]] NeuralBaseline prepareNeuralBaseline(const FlightScenario& base,
                                                   const NeuralSettings& s,
                                                   const std::filesystem::path& cache_dir, int jobs,
                                                   Progress* progress = nullptr);

// ------------------------------------------------------------------ training on real logs

/// Training rows from a flight log (ident/rig_logs.hpp: height, world velocity, attitude,
/// external acceleration and rotor speeds, as `identify flight` reads it from a CSV or through
/// a log map): features (h, v_W, q_WB, n) and the label m·a_ext − f_D∞(R_WB, v_W) [N], with the
/// mass and the high-altitude drag of `vehicle` (the controller's, which compensates f_D∞
/// itself) — the rows prepareNeuralBaseline collects in the simulator, from a log. m·a_ext is
/// m·R·f_imu − k_T·Σn²·z_B, the force the nominal model leaves unexplained. Rows with a
/// non-finite value are skipped. Returns the rows added. Throws std::invalid_argument naming the
/// log when it lacks velocity, attitude or the horizontal external acceleration (a hover log).
std::size_t addLogRows(neural::TrainingSet& set, const ident::FlightLog& log,
                       const model::VehicleParams& vehicle);

/// Mean squared error per force component of the labels themselves (no network: what the
/// nominal model alone leaves) [N²]; NaN for an empty set.
[[nodiscard]] double labelMeanSquare(const neural::TrainingSet& set);

}  // namespace geaware::experiments
