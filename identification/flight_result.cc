// Result stage of the flight fit: the estimates of k, d, c_T and m_p with
// their notes, floors and warnings, and the fit-versus-data plot panels.
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "identification/fit_stages.h"
#include "identification/flight_fit.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

std::vector<FitPlot> FlightPlots(const FlightProblem& fit) {
  std::vector<FitPlot> plots;
  const size_t count = fit.functors.size();
  for (size_t n = 1; n <= 2 && n < count; ++n) {
    const size_t w = n * count / 3;
    const FreeArmWindowResidual& f = *fit.functors[w];
    const std::vector<FreeArmState<double>> predicted =
        f.Predict(fit.ratio[kFlightK], fit.ratio[kFlightD], fit.ratio[kFlightThrust], fit.ratio[kFlightTipMass],
                  fit.states[w].data(), fit.knots[w].empty() ? nullptr : fit.knots[w].data());
    for (int arm = 0; arm < kBirotorRotors; ++arm) {
      FitPlot plot;
      plot.panel = FitPanel::kFlightDeflection;
      plot.arm = arm;
      plot.window = static_cast<int>(w);
      plot.windows = static_cast<int>(count);
      double t_s = 0.0;
      for (size_t j = 0; j < predicted.size(); ++j) {
        plot.x.push_back(t_s);
        plot.data.push_back(1e3 * f.samples()[j].deflection_rad[arm]);
        plot.model.push_back(1e3 * predicted[j](arm == 0 ? kFreeB1 : kFreeB2));
        t_s += f.samples()[j].dt_s;
      }
      plots.push_back(std::move(plot));
    }
  }
  return plots;
}

namespace {

// m_p kept at the base value (CheckTipMass held it, or the flight agrees
// with the base file): the estimate says why, the warning what to fly, and,
// when m_p was held in the fit, the combination the flight determines is named.
void ExplainHeldTipMass(const TipMassCheck& check, const BirotorParams& base, const ParameterEstimate& c_t,
                        ParameterEstimate* tip_mass, IdentificationResult* result) {
  tip_mass->value = base.tip_mass_kg;
  tip_mass->determined = false;
  tip_mass->sigma = std::numeric_limits<double>::quiet_NaN();
  if (check.agrees_with_base) {
    tip_mass->note = EstimateNote();
    tip_mass->note.basis = EstimateBasis::kTipMassAgreesWithBase;
    tip_mass->note.value = check.flight_value_kg;
    tip_mass->note.sigma = check.flight_sigma_kg;
    tip_mass->note.distance_sigmas = check.sigmas_from_base;
    IdentificationWarning agrees{WarningKind::kTipMassAgreesWithBase, "m_p"};
    agrees.value = check.flight_value_kg;
    agrees.sigma = check.flight_sigma_kg;
    agrees.distance_sigmas = check.sigmas_from_base;
    result->warnings.push_back(agrees);
    return;  // k and c_T are those of the fit with m_p free
  }
  tip_mass->note = EstimateNote();
  tip_mass->note.basis = EstimateBasis::kTipMassHeld;
  tip_mass->note.relative_sigma = check.relative_sigma;
  tip_mass->note.data_share = check.data_share;
  result->warnings.push_back({WarningKind::kTipMassHeldInFlight, "m_p", ExcitationAdvice::kTipMassSteps});
  DeterminedCombination named;
  named.kind = CombinationKind::kThrustOverTotalMass;
  named.a = "c_T";
  named.b = "m_p";
  named.relative_sigma = c_t.sigma / c_t.value;
  named.held_value = base.tip_mass_kg;
  result->correlations.push_back(named);
}

}  // namespace

void StoreFlightResult(const FlightProblem& fit, const FlightSamples& data, const std::vector<BlockSigma>& sigma,
                       const TipMassCheck& tip_check, const BirotorParams& base, const IdentificationOptions& options,
                       IdentificationResult* result) {
  ParameterEstimate k = ParameterEstimate::Named("arm_stiffness_n_m_rad", "k");
  ParameterEstimate damping = ParameterEstimate::Named("arm_damping_n_m_s_rad", "d");
  ParameterEstimate c_t = ParameterEstimate::Named("thrust_coeff_n_s2_rad2", "c_T");
  ParameterEstimate tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p");
  EstimateNote note;
  note.basis = EstimateBasis::kFreeArmFit;
  note.windows = static_cast<int>(fit.windows.size());
  note.candidate_windows = static_cast<int>(data.candidates.size());
  note.with_imu = data.any_imu;
  note.joint = fit.joint;
  if (fit.joint) {
    note.load_cell_pairs = static_cast<int>(fit.bench.thrust.size());
    note.clamped_windows = static_cast<int>(fit.bench.arms.size());
  }
  const FreeArmWindowResidual::Scales& scales = fit.scales;
  std::array<double, kFlightParameters> ratio = fit.ratio;
  const RatioParameter parameters[kFlightParameters] = {{&k, &ratio[kFlightK], scales.stiffness_n_m_rad},
                                                        {&damping, &ratio[kFlightD], scales.damping_n_m_s_rad},
                                                        {&c_t, &ratio[kFlightThrust], scales.thrust_coeff_n_s2_rad2},
                                                        {&tip_mass, &ratio[kFlightTipMass], scales.tip_mass_kg}};
  for (int i = 0; i < kFlightParameters; ++i) FillEstimate(parameters[i], sigma[i], options.max_relative_sigma, note);
  if (tip_check.applies && tip_check.free) {
    tip_mass.note.data_share = tip_check.data_share;
    tip_mass.note.remarks.push_back(EstimateRemark::kTipMassDataShare);
  }
  if (!k.determined) result->errors.push_back("k: not determined by the flight data (arm dynamics not excited)");
  if (!c_t.determined) {
    result->errors.push_back(std::string("c_T: not determined by the flight data") +
                             (data.any_imu ? "" : " (no IMU: only c_T / k is seen by the strain gauges)"));
  }
  if (fit.joint) {
    AddBenchFloors(options, &k, &damping, &tip_mass);
  } else {
    // A flight reads its deflections through the base file's gauge scales:
    // a relative scale error delta moves k by -delta (statics, b = f L / k)
    // and m_p with it (the arm frequency fixes k / m_p); c_T comes from the
    // accelerometer against the rotor speeds and does not move. What the
    // flight determines is k / s and m_p / s.
    const double scale = 0.5 * (base.gauge_scale[0] + base.gauge_scale[1]);
    const double relative = options.calibration.gauge_scale_std / scale;
    for (ParameterEstimate* e : {&k, &tip_mass}) {
      if (relative > 0.0) {
        AddRelativeFloor(e, relative, EstimateRemark::kGaugeScaleFloor);
      } else {
        e->note.remarks.push_back(EstimateRemark::kRelativeToGaugeScale);
      }
    }
  }
  if (!fit.joint && !options.flight_fit_damping) {
    damping.determined = false;
    damping.sigma = kNaN;
    damping.note = EstimateNote();
    damping.note.basis = EstimateBasis::kDampingNotFitted;
  }
  if (!damping.determined) result->warnings.push_back({WarningKind::kNotDeterminedInFlight, "d"});
  std::vector<ParameterEstimate> estimates = {k, damping, c_t};
  if (options.flight_fit_tip_mass || fit.joint) {
    if (tip_check.applies && !tip_check.free) {
      ExplainHeldTipMass(tip_check, base, c_t, &tip_mass, result);
    } else if (!tip_mass.determined) {
      result->warnings.push_back({WarningKind::kNotDeterminedInFlight, "m_p", ExcitationAdvice::kTipMassSteps});
    }
    estimates.push_back(tip_mass);
  }
  StoreEstimates(estimates, result);
}

}  // namespace birotor
