// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/neural/trainer.hpp"

#include <dlib/dnn.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "geaware/model/field_check.hpp"

// Why dlib, and what is ours. dlib (Debian's libdlib-dev) gives the dense/ReLU layers, their
// back-propagation and Adam, and lets a training loop be written step by step
// (compute_parameter_gradients → update_parameters), so that the spectral projection of Shi et
// al. can run between steps on the layers' parameter tensors. What we do ourselves, and why:
//  - initialisation: dlib seeds its layers from std::rand(), a global; we overwrite every
//    parameter from our own seeded generator, so that training is reproducible and leaves no
//    global state behind;
//  - split and shuffling: std::shuffle and the std distributions are implementation-defined, so
//    Fisher–Yates on std::mt19937_64 (whose output the standard fixes) with rejection sampling;
//  - the final exact projection (SVD) in double: power iteration under-estimates σ_max, so the
//    certificate ∏σ_max ≤ γ would otherwise hold only approximately.
// dlib trains in float; the exported network is double.

namespace geaware::neural {
namespace {

// ---------------------------------------------------------------------------------------------
// Deterministic random numbers.

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform integer in [0, n), n ≥ 1, without modulo bias.
  std::size_t below(std::size_t n) {
    const std::uint64_t range = n;
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() -
                                std::numeric_limits<std::uint64_t>::max() % range;
    std::uint64_t r = engine_();
    while (r >= limit) r = engine_();
    return static_cast<std::size_t>(r % range);
  }
  template <typename T>
  void shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(i)]);
  }

 private:
  std::mt19937_64 engine_;
};

// ---------------------------------------------------------------------------------------------
// The dlib network: ReLU(fc) × H, then fc → 3, with the mean-squared-error loss. Hidden widths
// are template placeholders (1) set at run time; only the depth is a compile-time property.

using Input = dlib::input<dlib::matrix<float, 0, 1>>;
template <typename Sub>
using Hidden = dlib::relu<dlib::fc<1, Sub>>;
template <int H>
struct HiddenStack {
  using type = Hidden<typename HiddenStack<H - 1>::type>;
};
template <>
struct HiddenStack<0> {
  using type = Input;
};
template <int H>
using Net = dlib::loss_mean_squared_multioutput<
    dlib::fc<static_cast<unsigned long>(kOutputCount), typename HiddenStack<H>::type>>;

/// The parameters of one dense layer as dlib stores them: a row-major (inputs × outputs) weight
/// block Wᵀ, then the outputs biases.
struct DlibDense {
  dlib::tensor* params = nullptr;
  long inputs = 0;
  long outputs = 0;

  using WeightsT =
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
  [[nodiscard]] WeightsT weightsT() const { return {params->host(), inputs, outputs}; }
  [[nodiscard]] float* bias() const { return params->host() + inputs * outputs; }
};

/// Visits dlib's layers (output first) and sets the hidden widths.
struct WidthSetter {
  const std::vector<int>* widths;  // input order
  int* visited;                    // dense layers seen so far, output first
  template <unsigned long N, dlib::fc_bias_mode M>
  void operator()(dlib::fc_<N, M>& l) const {
    const int from_input = static_cast<int>(widths->size()) - *visited;  // output layer: H
    if (*visited > 0)
      l.set_num_outputs(static_cast<long>((*widths)[static_cast<std::size_t>(from_input)]));
    ++*visited;
  }
  template <typename T>
  void operator()(T&) const {}
};

/// Visits dlib's layers (output first) and records their parameter tensors.
struct DenseCollector {
  std::vector<DlibDense>* out;
  template <unsigned long N, dlib::fc_bias_mode M>
  void operator()(dlib::fc_<N, M>& l) const {
    DlibDense d;
    d.params = &l.get_layer_params();
    d.outputs = static_cast<long>(l.get_num_outputs());
    d.inputs = static_cast<long>(d.params->size()) / d.outputs - 1;  // (inputs + 1) × outputs
    out->push_back(d);
  }
  template <typename T>
  void operator()(T&) const {}
};

// ---------------------------------------------------------------------------------------------
// Evaluation and export.

/// Forward pass of a batch of raw features (17 × n) through `w`: 3 × n forces [N].
Eigen::MatrixXd forwardBatch(const NetworkWeights& w, const Eigen::MatrixXd& x_raw) {
  Eigen::MatrixXd a = (x_raw.colwise() - w.input_mean).array().colwise() / w.input_std.array();
  for (std::size_t l = 0; l < w.layers.size(); ++l) {
    Eigen::MatrixXd z = w.layers[l].weights * a;
    z.colwise() += w.layers[l].bias;
    a = l + 1 < w.layers.size() ? Eigen::MatrixXd(z.cwiseMax(0.0)) : std::move(z);
  }
  return a;
}

double mse(const NetworkWeights& w, const Eigen::MatrixXd& x_raw, const Eigen::MatrixXd& y) {
  if (x_raw.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
  return (forwardBatch(w, x_raw) - y).squaredNorm() / static_cast<double>(y.size());
}

/// dlib's float parameters → our double layers (W = (Wᵀ)ᵀ, outputs × inputs).
std::vector<DenseLayer> exportLayers(const std::vector<DlibDense>& dense) {
  std::vector<DenseLayer> layers;
  layers.reserve(dense.size());
  for (const auto& d : dense) {
    DenseLayer l;
    l.weights = d.weightsT().transpose().cast<double>();
    l.bias = Eigen::Map<const Eigen::VectorXf>(d.bias(), d.outputs).cast<double>();
    layers.push_back(std::move(l));
  }
  return layers;
}

/// Rows of the set, raw features as columns.
struct Columns {
  Eigen::MatrixXd x;  // 17 × n
  Eigen::MatrixXd y;  // 3 × n
};

Columns columns(const TrainingSet& set, const std::vector<std::size_t>& rows) {
  Columns c{Eigen::MatrixXd(kFeatureCount, static_cast<Eigen::Index>(rows.size())),
            Eigen::MatrixXd(kOutputCount, static_cast<Eigen::Index>(rows.size()))};
  for (std::size_t j = 0; j < rows.size(); ++j) {
    c.x.col(static_cast<Eigen::Index>(j)) = set.features()[rows[j]];
    c.y.col(static_cast<Eigen::Index>(j)) = set.labels()[rows[j]];
  }
  return c;
}

// ---------------------------------------------------------------------------------------------
// The training loop for a network of H hidden layers.

template <int H>
TrainResult trainDepth(const TrainingSet& set, const TrainOptions& o, const EpochCallback& cb) {
  Rng rng(o.seed);

  // 1. Split: a seeded permutation; its first rows are held out.
  std::vector<std::size_t> order(set.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  rng.shuffle(order);
  const auto n_val =
      static_cast<std::size_t>(std::floor(o.validation_fraction * static_cast<double>(set.size())));
  std::vector<std::size_t> val_rows(order.begin(), order.begin() + static_cast<long>(n_val));
  std::vector<std::size_t> train_rows(order.begin() + static_cast<long>(n_val), order.end());
  const Columns train_cols = columns(set, train_rows);
  const Columns val_cols = columns(set, val_rows);

  // 2. Standardisation from the training rows only.
  NetworkWeights result;
  result.input_mean = train_cols.x.rowwise().mean();
  const Eigen::MatrixXd centred = train_cols.x.colwise() - result.input_mean;
  const auto n_train = static_cast<double>(train_rows.size());
  result.input_std =
      (centred.rowwise().squaredNorm() / n_train).cwiseSqrt().cwiseMax(o.min_input_std);
  const Eigen::MatrixXf x_std =
      (centred.array().colwise() / result.input_std.array()).matrix().cast<float>();

  // 3. The dlib network with our widths and our seeded initialisation (He-uniform weights,
  //    zero biases), applied after a first forward pass has allocated the parameters.
  Net<H> net;
  int visited = 0;
  dlib::visit_computational_layers(net, WidthSetter{&o.hidden_widths, &visited});
  dlib::resizable_tensor x;
  {
    // to_tensor() once, so that the input layer knows its layout; later batches are written
    // into the tensor directly (same layout: samples × 1 × 17 × 1).
    const std::vector<dlib::matrix<float, 0, 1>> probe(1,
                                                       dlib::zeros_matrix<float>(kFeatureCount, 1));
    net.to_tensor(probe.begin(), probe.end(), x);
  }
  net.subnet().forward(x);
  std::vector<DlibDense> dense;
  dlib::visit_computational_layers(net, DenseCollector{&dense});
  std::reverse(dense.begin(), dense.end());  // input first
  for (const auto& d : dense) {
    const double limit = std::sqrt(6.0 / static_cast<double>(d.inputs));
    auto w = d.weightsT();
    for (long i = 0; i < d.inputs; ++i) {
      for (long j = 0; j < d.outputs; ++j) {
        w(i, j) = static_cast<float>((2.0 * rng.uniform01() - 1.0) * limit);
      }
    }
    std::fill(d.bias(), d.bias() + d.outputs, 0.0f);
  }

  // 4. Spectral normalisation (Shi et al. 2019 §IV-B): ‖W_l‖₂ ≤ γ^(1/L) for each of the L
  //    layers, so ∏‖W_l‖₂ ≤ γ. σ_max by warm-started power iteration on Wᵀ (same norm).
  const double layer_bound = std::pow(o.lipschitz_gamma, 1.0 / static_cast<double>(dense.size()));
  std::vector<Eigen::VectorXf> singular_vectors(dense.size());
  const auto project = [&] {
    for (std::size_t l = 0; l < dense.size(); ++l) {
      auto w_t = dense[l].weightsT();
      const double sigma = powerIterationNorm(w_t, singular_vectors[l], o.power_iterations);
      if (sigma > layer_bound) w_t *= static_cast<float>(layer_bound / sigma);
    }
  };
  if (o.spectral_normalisation) project();

  // 5. Mini-batch Adam.
  std::vector<dlib::adam> solvers(Net<H>::num_computational_layers,
                                  dlib::adam(static_cast<float>(o.weight_decay), 0.9f, 0.999f));
  std::vector<dlib::matrix<float, 0, 1>> labels;
  std::vector<std::size_t> batch_order(train_rows.size());
  for (std::size_t i = 0; i < batch_order.size(); ++i) batch_order[i] = i;
  const auto batch = static_cast<std::size_t>(o.batch_size);

  TrainResult out;
  out.train_rows = train_rows.size();
  out.validation_rows = val_rows.size();
  for (int epoch = 1; epoch <= o.epochs; ++epoch) {
    rng.shuffle(batch_order);
    for (std::size_t start = 0; start < batch_order.size(); start += batch) {
      const std::size_t m = std::min(batch, batch_order.size() - start);
      x.set_size(static_cast<long long>(m), 1, kFeatureCount, 1);
      float* px = x.host_write_only();
      labels.resize(m);
      for (std::size_t r = 0; r < m; ++r) {
        const auto col = static_cast<Eigen::Index>(batch_order[start + r]);
        Eigen::Map<Eigen::Matrix<float, kFeatureCount, 1>>(px + r * kFeatureCount) = x_std.col(col);
        labels[r].set_size(kOutputCount);
        for (int k = 0; k < kOutputCount; ++k) {
          labels[r](k) = static_cast<float>(train_cols.y(k, col));
        }
      }
      static_cast<void>(net.compute_parameter_gradients(x, labels.begin()));
      net.update_parameters(solvers, o.learning_rate);
      if (o.spectral_normalisation) project();
    }
    result.layers = exportLayers(dense);
    out.train_loss.push_back(mse(result, train_cols.x, train_cols.y));
    if (n_val > 0) out.validation_loss.push_back(mse(result, val_cols.x, val_cols.y));
    if (cb) {
      cb(epoch, out.train_loss.back(),
         n_val > 0 ? out.validation_loss.back() : std::numeric_limits<double>::quiet_NaN());
    }
  }

  // 6. Exact projection in double: the power-iteration estimate is a lower bound on σ_max, so
  //    the last step may have left a layer a little above its bound. After this the certificate
  //    ∏σ_max(W_l) ≤ γ holds up to rounding (kLipschitzTolerance).
  result.layers = exportLayers(dense);
  if (o.spectral_normalisation) {
    for (auto& l : result.layers) {
      const double sigma = spectralNorm(l.weights);
      if (sigma > layer_bound) l.weights *= layer_bound / sigma;
    }
    result.lipschitz_gamma = o.lipschitz_gamma;
  }
  out.weights = std::move(result);
  return out;
}

}  // namespace

bool TrainingSet::add(const control::ResidualFeatures& f, const Eigen::Vector3d& force_W) {
  return add(makeFeatures(f), force_W);
}

bool TrainingSet::add(const FeatureVector& x, const Eigen::Vector3d& force_W) {
  if (!x.allFinite() || !force_W.allFinite()) return false;
  features_.push_back(x);
  labels_.push_back(force_W);
  return true;
}

std::vector<model::FieldError> TrainOptions::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  if (hidden_widths.empty() || hidden_widths.size() > static_cast<std::size_t>(kMaxHiddenLayers)) {
    e.push_back({"hidden_widths", std::to_string(hidden_widths.size()) + " layers",
                 "1 to " + std::to_string(kMaxHiddenLayers) + " hidden layers"});
  }
  for (std::size_t i = 0; i < hidden_widths.size(); ++i) {
    if (hidden_widths[i] < 1 || hidden_widths[i] > kMaxWidth) {
      e.push_back({"hidden_widths[" + std::to_string(i) + "]", std::to_string(hidden_widths[i]),
                   "1.." + std::to_string(kMaxWidth) + " neurons"});
    }
  }
  if (epochs < 1) e.push_back({"epochs", std::to_string(epochs), "at least 1"});
  if (batch_size < 1) e.push_back({"batch_size", std::to_string(batch_size), "at least 1"});
  c.positive("learning_rate", learning_rate);
  if (!std::isfinite(weight_decay) || weight_decay < 0.0) {
    c.fail("weight_decay", model::formatValue(weight_decay), "a finite number >= 0");
  }
  c.positive("lipschitz_gamma", lipschitz_gamma);
  if (power_iterations < 1 || power_iterations > 100) {
    e.push_back({"power_iterations", std::to_string(power_iterations), "1..100"});
  }
  if (!(validation_fraction >= 0.0 && validation_fraction <= 0.9)) {
    c.fail("validation_fraction", model::formatValue(validation_fraction), "a number in [0, 0.9]");
  }
  c.positive("min_input_std", min_input_std);
  return e;
}

TrainResult train(const TrainingSet& set, const TrainOptions& options,
                  const EpochCallback& on_epoch) {
  const auto errors = options.validate();
  if (!errors.empty())
    throw std::invalid_argument(model::describeErrors("invalid training options:", errors));
  const auto n_val = static_cast<std::size_t>(
      std::floor(options.validation_fraction * static_cast<double>(set.size())));
  if (set.size() <= n_val || (options.validation_fraction > 0.0 && n_val == 0)) {
    throw std::invalid_argument(
        "training set of " + std::to_string(set.size()) +
        " rows is too small for validation "
        "fraction " +
        model::formatValue(options.validation_fraction) +
        ": need at least one training row and, when the fraction is > 0, one validation row");
  }
  switch (options.hidden_widths.size()) {
    case 1:
      return trainDepth<1>(set, options, on_epoch);
    case 2:
      return trainDepth<2>(set, options, on_epoch);
    case 3:
      return trainDepth<3>(set, options, on_epoch);
    default:
      return trainDepth<4>(set, options, on_epoch);
  }
}

double meanSquaredError(const NetworkWeights& weights, const TrainingSet& set) {
  NetworkWeights unbounded = weights;  // dimensions and finiteness only, not γ
  unbounded.lipschitz_gamma.reset();
  if (auto errors = unbounded.validate(); !errors.empty()) throw InvalidNetwork(std::move(errors));
  std::vector<std::size_t> rows(set.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i;
  const Columns c = columns(set, rows);
  return mse(weights, c.x, c.y);
}

}  // namespace geaware::neural
