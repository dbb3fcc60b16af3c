// Result stage of the flight fit: the estimates of k, d, c_T and m_p with
// their notes, floors and warnings, and the fit-versus-data plot panels.
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "identification/fit_stages.h"
#include "identification/flight_fit.h"

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
    for (int arm = 0; arm < 2; ++arm) {
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
void ExplainHeldTipMass(const TipMassCheck& check, const VehicleParams& base, const ParameterEstimate& c_t,
                        ParameterEstimate* tip_mass, IdentificationResult* result) {
  std::ostringstream why;
  why.precision(4);
  tip_mass->value = base.tip_mass_kg;
  tip_mass->determined = false;
  tip_mass->sigma = std::numeric_limits<double>::quiet_NaN();
  if (check.agrees_with_base) {
    why << "base value kept: the flight's m_p = " << check.flight_value_kg << " +- " << check.flight_sigma_kg
        << " kg is " << std::setprecision(3) << check.sigmas_from_base
        << " sigma from it (consistency_sigmas): this flight does not show the base file wrong, and its sigma is "
           "wider than a bench's";
    tip_mass->note = why.str();
    IdentificationWarning agrees{WarningKind::kTipMassAgreesWithBase, "m_p"};
    agrees.value = check.flight_value_kg;
    agrees.sigma = check.flight_sigma_kg;
    agrees.distance_sigmas = check.sigmas_from_base;
    result->warnings.push_back(agrees);
    return;  // k and c_T are those of the fit with m_p free
  }
  why << "held at the base value: at the fit with m_p held its relative sigma would be " << 100.0 * check.relative_sigma
      << " % with " << 100.0 * check.data_share
      << " % of its information from the data (the rest from the assumed rotor turbulence)";
  tip_mass->note = why.str();
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
                       const TipMassCheck& tip_check, const VehicleParams& base, const IdentificationOptions& options,
                       IdentificationResult* result) {
  ParameterEstimate k = ParameterEstimate::Named("arm_stiffness_n_m_rad", "k");
  ParameterEstimate damping = ParameterEstimate::Named("arm_damping_n_m_s_rad", "d");
  ParameterEstimate c_t = ParameterEstimate::Named("thrust_coeff_n_s2_rad2", "c_T");
  ParameterEstimate tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p");
  std::string note = "output error of the free-flight arm model over " + std::to_string(fit.windows.size()) + " of " +
                     std::to_string(data.candidates.size()) + " windows" +
                     (data.any_imu ? " with IMU" : " without IMU");
  if (fit.joint) {
    note = "joint fit (one problem): " + std::to_string(fit.bench.thrust.size()) + " load-cell pairs, " +
           std::to_string(fit.bench.arms.size()) + " clamped-arm windows and " + note;
  }
  const FreeArmWindowResidual::Scales& scales = fit.scales;
  std::array<double, kFlightParameters> ratio = fit.ratio;
  const RatioParameter parameters[kFlightParameters] = {{&k, &ratio[kFlightK], scales.stiffness_n_m_rad},
                                                        {&damping, &ratio[kFlightD], scales.damping_n_m_s_rad},
                                                        {&c_t, &ratio[kFlightThrust], scales.thrust_coeff_n_s2_rad2},
                                                        {&tip_mass, &ratio[kFlightTipMass], scales.tip_mass_kg}};
  for (int i = 0; i < kFlightParameters; ++i) FillEstimate(parameters[i], sigma[i], options.max_relative_sigma, note);
  if (tip_check.applies && tip_check.free) {
    std::ostringstream share;
    share.precision(3);
    share << "; " << 100.0 * tip_check.data_share << " % of m_p's information from the data";
    tip_mass.note += share.str();
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
        AddRelativeFloor(e, relative, "gauge scale's (--gauge-scale-std)");
      } else {
        e->note +=
            "; relative to the base file's gauge_scale (the flight determines it over s_i; "
            "--gauge-scale-std adds the scale's uncertainty)";
      }
    }
  }
  if (!fit.joint && !options.flight_fit_damping) {
    damping.determined = false;
    damping.sigma = kNaN;
    damping.note = "held at the base value (flight_fit_damping is off: flight data barely constrain d)";
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
