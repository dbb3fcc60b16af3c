// Determinability stages of the flight fit (issue 26): how much of a
// parameter's information the recorded data give rather than the assumed
// turbulence statistics, and the m_p check run between the solves.
#include <algorithm>
#include <cmath>
#include <limits>

#include "identification/fit_support.h"
#include "identification/flight_fit.h"

namespace birotor {

namespace {

// Replaces every window's turbulence prior by one of std turbulence_std * widen.
void SetTurbulencePriors(double widen, FlightProblem* fit) {
  for (size_t w = 0; w < fit->priors.size(); ++w) {
    if (fit->priors[w] == nullptr) continue;
    fit->problem.RemoveResidualBlock(fit->priors[w]);
    fit->priors[w] = fit->problem.AddResidualBlock(
        fit->functors[w]->TurbulencePrior(fit->turbulence_std * widen, fit->turbulence_corr_time_s), nullptr,
        fit->knots[w].data());
  }
}

double RelativeSigma(const IdentificationOptions& options, int block, FlightProblem* fit) {
  const std::vector<BlockSigma> sigma = ComputeBlockSigmas(&fit->problem, fit->Blocks(), 1.0, options.num_threads);
  const double ratio = std::abs(fit->ratio[block]);
  if (!sigma[block].determined || ratio <= 0.0) return std::numeric_limits<double>::infinity();
  return sigma[block].sigma / ratio;
}

}  // namespace

PriorSensitivity RatioPriorSensitivity(const IdentificationOptions& options, int block, double widen,
                                       FlightProblem* fit) {
  double* ratio = &fit->ratio[block];
  const bool was_constant = fit->problem.IsParameterBlockConstant(ratio);
  fit->problem.SetParameterBlockVariable(ratio);
  PriorSensitivity out;
  out.relative_sigma = RelativeSigma(options, block, fit);
  SetTurbulencePriors(widen, fit);
  out.relative_sigma_widened = RelativeSigma(options, block, fit);
  SetTurbulencePriors(1.0, fit);
  if (was_constant) fit->problem.SetParameterBlockConstant(ratio);
  return out;
}

TipMassCheck CheckTipMass(const IdentificationOptions& options, FlightProblem* fit) {
  TipMassCheck check;
  double* tip_mass = &fit->ratio[kFlightTipMass];
  check.applies = !fit->joint && options.flight_fit_tip_mass && fit->model_turbulence &&
                  !fit->problem.IsParameterBlockConstant(tip_mass);
  if (!check.applies) {
    SolveFlightProblem(options, fit, 0.15);
    check.free = !fit->problem.IsParameterBlockConstant(tip_mass);
    return check;
  }
  fit->problem.SetParameterBlockConstant(tip_mass);
  SolveFlightProblem(options, fit, 0.15);
  ReportProgress(options, {"flight: determinability of m_p", static_cast<int>(fit->windows.size()), 0, 0.6});
  const PriorSensitivity s = RatioPriorSensitivity(options, kFlightTipMass, kPriorWidening, fit);
  check.relative_sigma = s.relative_sigma;
  check.data_share = DataInformationShare(s, kPriorWidening);
  check.free = std::isfinite(s.relative_sigma) && s.relative_sigma <= options.max_relative_sigma &&
               check.data_share >= options.flight_min_data_share;
  if (check.free) fit->problem.SetParameterBlockVariable(tip_mass);
  return check;
}

double DataInformationShare(const PriorSensitivity& s, double widen) {
  if (!std::isfinite(s.relative_sigma) || !std::isfinite(s.relative_sigma_widened) || s.relative_sigma <= 0.0) {
    return 0.0;
  }
  const double r = s.relative_sigma_widened / s.relative_sigma;
  const double w2 = 1.0 / (widen * widen);
  return std::clamp((1.0 / (r * r) - w2) / (1.0 - w2), 0.0, 1.0);
}

}  // namespace birotor
