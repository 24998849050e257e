// SPDX-License-Identifier: BSD-3-Clause
// geaware.FlatMap.evaluate: the flat map at N instants, inputs broadcast row by row.

#include <algorithm>
#include <string>

#include "geaware/flatness/flat_map.hpp"
#include "python_types.hpp"

namespace geaware::python {
namespace {

/// An input of `width` numbers per instant: one instant (used for every row) or N of them.
struct Rows {
  const double* data;
  py::ssize_t count;  ///< instants given
  int width;
  [[nodiscard]] const double* at(py::ssize_t i) const noexcept {
    return data + (count == 1 ? 0 : i * width);
  }
};

Rows rows(const DoubleArray& a, int width, const char* name) {
  if (a.size() == 0 || a.size() % width != 0 || (width > 1 && a.ndim() > 2) ||
      (width > 1 && a.ndim() == 2 && a.shape(1) != width) || (width == 1 && a.ndim() > 1)) {
    throw py::value_error(std::string(name) + ": expected " +
                          (width == 1 ? std::string("a number or an array of shape (N,)")
                                      : "an array of shape (N, " + std::to_string(width) +
                                            ") or (" + std::to_string(width) + ",)") +
                          ", got " + std::to_string(a.ndim()) + " dimensions and " +
                          std::to_string(a.size()) + " numbers");
  }
  return {a.data(), a.size() / width, width};
}

}  // namespace

py::dict FlatMapHandle::evaluate(const DoubleArray& p, const DoubleArray& v, const DoubleArray& a,
                                 const DoubleArray& j, const DoubleArray& s, const DoubleArray& yaw,
                                 const DoubleArray& yaw_rate, const DoubleArray& yaw_acc,
                                 const DoubleArray& height) const {
  const Rows in[] = {rows(p, 3, "position_m"),     rows(v, 3, "velocity_mps"),
                     rows(a, 3, "accel_mps2"),     rows(j, 3, "jerk_mps3"),
                     rows(s, 3, "snap_mps4"),      rows(yaw, 1, "yaw_rad"),
                     rows(yaw_rate, 1, "yaw_rate_radps"), rows(yaw_acc, 1, "yaw_accel_radps2"),
                     rows(height, 1, "height_m")};
  py::ssize_t n = 1;
  for (const Rows& r : in) n = std::max(n, r.count);
  for (const Rows& r : in) {
    if (r.count != 1 && r.count != n) {
      throw py::value_error("FlatMap.evaluate: inputs give " + std::to_string(r.count) + " and " +
                            std::to_string(n) + " instants; each input has N rows or one");
    }
  }
  py::array_t<int> status(n);
  py::array_t<bool> feasible(n);
  DoubleArray thrust = newArray({n}), collective = newArray({n}), q = newArray({n, 4}),
              w = newArray({n, 3}), w_dot = newArray({n, 3}), tau = newArray({n, 3}),
              n_sq = newArray({n, 4}), speeds = newArray({n, 4});
  const auto put = [](DoubleArray& out, py::ssize_t i, const auto& x, int k) {
    for (int c = 0; c < k; ++c) out.mutable_data()[i * k + c] = x[c];
  };
  for (py::ssize_t i = 0; i < n; ++i) {
    traj::FlatOutput ref;
    ref.p_W = Eigen::Vector3d(in[0].at(i));
    ref.v_W = Eigen::Vector3d(in[1].at(i));
    ref.a_W = Eigen::Vector3d(in[2].at(i));
    ref.j_W = Eigen::Vector3d(in[3].at(i));
    ref.s_W = Eigen::Vector3d(in[4].at(i));
    ref.yaw_rad = *in[5].at(i);
    ref.yaw_rate_radps = *in[6].at(i);
    ref.yaw_acc_radps2 = *in[7].at(i);
    const flatness::FlatState f = map_->evaluate(ref, *in[8].at(i));
    status.mutable_data()[i] = static_cast<int>(f.status);
    feasible.mutable_data()[i] = f.rotor_speeds_feasible;
    thrust.mutable_data()[i] = f.thrust_N;
    collective.mutable_data()[i] = f.collective_acc_mps2;
    put(q, i, Eigen::Vector4d(f.q_WB.w(), f.q_WB.x(), f.q_WB.y(), f.q_WB.z()), 4);
    put(w, i, f.w_B, 3);
    put(w_dot, i, f.w_dot_B, 3);
    put(tau, i, f.tau_B, 3);
    put(n_sq, i, f.n_sq_rpm2, 4);
    put(speeds, i, f.rotor_speeds_rpm, 4);
  }
  py::dict d;
  d["status"] = status;
  d["thrust_N"] = thrust;
  d["collective_acc_mps2"] = collective;
  d["q_wxyz"] = q;
  d["w_radps"] = w;
  d["w_dot_radps2"] = w_dot;
  d["torque_Nm"] = tau;
  d["n_sq_rpm2"] = n_sq;
  d["rotor_speeds_rpm"] = speeds;
  d["feasible"] = feasible;
  return d;
}

}  // namespace geaware::python
