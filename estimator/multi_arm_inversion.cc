#include "estimator/multi_arm_inversion.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>

#include "model/multi_arm_linearization.h"

namespace birotor {

MultiArmInversion::MultiArmInversion(const VehicleDescription& vehicle, const InversionOptions& options)
    : n_(vehicle.arm_count), vehicle_(vehicle), options_(options), motor_(vehicle) {
  options_.window_samples = std::clamp(options_.window_samples, 3, kMaxWindow);
  for (const ArmDescription& arm : vehicle.arms) {
    if (!arm.has_gauge) throw std::invalid_argument("inversion: needs a strain gauge on every arm");
  }
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  if (!hover.converged) throw std::invalid_argument("inversion: no hover equilibrium");
  const MultiArmLinearModel model = LinearizeMultiArmAtHover(vehicle, hover);
  // [q; v] with q = x, z, phi, b_1 .. b_N: the rows of b_i_ddot.
  const int n_q = 3 + n_;
  a_deflection_ = model.a.block(n_q + 3, 3, n_, n_);
  a_rate_ = model.a.block(n_q + 3, n_q + 3, n_, n_);
  const ArmMatrix b = model.b.block(n_q + 3, 0, n_, n_);
  const Eigen::FullPivLU<ArmMatrix> lu(b);
  if (!lu.isInvertible()) throw std::invalid_argument("inversion: the forces do not drive the arms independently");
  b_inverse_ = lu.inverse();
  deflection_hover_rad_ = hover.deflection_rad;
  force_hover_n_ = hover.force_n;
  Reset();
}

void MultiArmInversion::Reset() {
  motor_.Reset();
  head_ = 0;
  count_ = 0;
  facts_ = MultiArmFilterFacts();
}

void MultiArmInversion::FitWindow(int64_t utime,
                                  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxArms>* derivatives) const {
  // Least squares b(tau) = c0 + c1 tau + c2 tau^2, tau = t - t_newest in ms
  // (scaled for conditioning), all arms at once (baseline_estimators.cc).
  constexpr double kTauScale = 1e-3;  // [s per unit of tau]
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxArms> rhs =
      Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxArms>::Zero(3, n_);
  for (int j = 0; j < options_.window_samples; ++j) {
    const size_t slot = static_cast<size_t>((head_ - 1 - j + 2 * kMaxWindow) % kMaxWindow);
    const double tau = static_cast<double>(utime_[slot] - utime) * 1e-6 / kTauScale;
    const Eigen::Vector3d basis(1.0, tau, tau * tau);
    normal.noalias() += basis * basis.transpose();
    for (int i = 0; i < n_; ++i) rhs.col(i) += basis * deflection_rad_[slot][static_cast<size_t>(i)];
  }
  *derivatives = normal.ldlt().solve(rhs);
  derivatives->row(1) /= kTauScale;
  derivatives->row(2) *= 2.0 / (kTauScale * kTauScale);
}

void MultiArmInversion::AddMotor(const MultiArmMotorSample& sample) {
  reports_.Open();
  if (motor_.AddMotor(sample)) {
    reports_.Add(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
  }
}

void MultiArmInversion::AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) {
  reports_.Open();
  reports_.Add(MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused));
  reports_.Close();
  const size_t slot = static_cast<size_t>(head_);
  utime_[slot] = sample.utime;
  for (int i = 0; i < n_; ++i) {
    const size_t k = static_cast<size_t>(i);
    const ArmDescription& arm = vehicle_.arms[k];
    // The description's calibration (a NaN reading stays NaN: no estimate from it).
    deflection_rad_[slot][k] = (sample.deflection_rad[k] - arm.gauge_offset_rad) / arm.gauge_scale;
  }
  head_ = (head_ + 1) % kMaxWindow;
  count_ = std::min(count_ + 1, kMaxWindow);
  motor_.Advance(sample.utime);

  *estimate = MultiArmForceEstimate();
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  estimate->n_rotors = n_;
  facts_ = MultiArmFilterFacts();
  ArmVector force = force_hover_n_;  // until the window is full: the hover forces
  if (count_ >= options_.window_samples) {
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxArms> d;
    FitWindow(sample.utime, &d);
    const ArmVector b = d.row(0).transpose(), b_dot = d.row(1).transpose(), b_ddot = d.row(2).transpose();
    // Thesis eq. 5.2: f = f_hover + B^-1 (b_ddot - A_bb (b - b_hover) - A_bd b_dot).
    force += b_inverse_ * (b_ddot - a_deflection_ * (b - deflection_hover_rad_) - a_rate_ * b_dot);
    facts_.convergence = FilterConvergence::kConverged;
  } else {
    facts_.convergence = FilterConvergence::kConverging;
  }
  for (int i = 0; i < n_; ++i) {
    const size_t k = static_cast<size_t>(i);
    estimate->force_n[k] = force(i);
    estimate->force_std_n[k] = options_.force_std_n;
    estimate->thrust_scale[k] =
        facts_.convergence == FilterConvergence::kConverged ? motor_.ThrustScale(i, force(i)) : 1.0;
  }
  const MultiArmStatusBits bits = ComposeMultiArmFilterStatus(facts_, n_);
  estimate->status = bits.status;
  estimate->rotor_fault_bits = bits.rotor_fault_bits;
}

}  // namespace birotor
