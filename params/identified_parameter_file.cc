#include "params/identified_parameter_file.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "params/birotor_params_yaml.h"

namespace birotor {
namespace {

std::string MapText(const DeflectionForceMap& map) {
  std::ostringstream out;
  out << std::setprecision(8) << "force_n = ";
  for (size_t j = 0; j < map.coefficients.size(); ++j) {
    if (j > 0) out << " + ";
    out << map.coefficients[j] << " (+-" << std::setprecision(3) << map.sigmas[j] << std::setprecision(8) << ")";
    if (j == 1) out << " b";
    if (j > 1) out << " b^" << j;
  }
  out << std::setprecision(4) << "; residual RMS " << map.residual_rms_n << " N over " << map.samples
      << " samples, b in [" << map.deflection_min_rad << ", " << map.deflection_max_rad << "] rad";
  return out.str();
}

// What would determine the parameter (issue 26 item 2).
std::string AdviceText(ExcitationAdvice advice) {
  switch (advice) {
    case ExcitationAdvice::kTipMassSteps:
      return "to determine it, fly 30 s of 0.4 m steps, horizontal and vertical (birotor-sim --scenario mass_id: m_p "
             "sigma 0.7 %), weigh the tip mass (--tip-mass-kg with a bench log) or identify it on the bench (0.1 %)";
    case ExcitationAdvice::kNone:
      break;
  }
  return "";
}

// The words of what a fit added to an estimate (EstimateNote::remarks).
std::string RemarkText(EstimateRemark remark, const EstimateNote& note) {
  switch (remark) {
    case EstimateRemark::kDampingFloor:
      return "; sigma includes the damping floor (bench_damping_floor)";
    case EstimateRemark::kFrequencyFloor:
      return "; sigma includes the frequency floor (bench_frequency_floor)";
    case EstimateRemark::kGaugeScaleFloor:
      return "; sigma includes the gauge scale's (--gauge-scale-std)";
    case EstimateRemark::kTipMassFloorThroughOffset:
      return "; sigma includes m_p's frequency floor through the static intercept";
    case EstimateRemark::kWidenedForMisfit:
      return "; widened for the model misfit";
    case EstimateRemark::kTipMassDataShare: {
      std::ostringstream out;
      out << std::setprecision(3) << "; " << 100.0 * note.data_share << " % of m_p's information from the data";
      return out.str();
    }
    case EstimateRemark::kRelativeToGaugeScale:
      return "; relative to the base file's gauge_scale (the flight determines it over s_i; --gauge-scale-std adds "
             "the scale's uncertainty)";
    case EstimateRemark::kBenchLogsAlone:
      return "; bench logs alone (held in the joint fit: the flight reads its deflections through it)";
  }
  return "";
}

void AppendReason(const char* stream, const DroppedSamples& d, std::string* out) {
  if (d.total() == 0) return;
  std::string text;
  auto add = [&](int64_t n, const char* what) {
    if (n == 0) return;
    if (!text.empty()) text += ", ";
    text += std::to_string(n) + " " + what;
  };
  add(d.non_finite, "non-finite");
  add(d.bad_stamp, "bad stamp");
  add(d.out_of_order, "out of order");
  add(d.duplicate, "duplicate");
  if (!out->empty()) *out += "; ";
  *out += std::string(stream) + " " + text;
}

std::string Percent(double fraction, int decimals) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << 100.0 * fraction;
  return out.str();
}

}  // namespace

// The library's rule (identification/fit_support.h SigmaDetermines): a
// sigma above the judged size (|value|, or the note's judged_size) is not
// determined; tau_m's excitation is the library's (EstimateBasis).
std::string ReportStatus(const ParameterEstimate& e) {
  const double size = std::isfinite(e.note.judged_size) ? e.note.judged_size : std::abs(e.value);
  const double relative_sigma = e.sigma / size;
  if (!e.determined || !std::isfinite(relative_sigma)) return "NOT determined";
  if (relative_sigma > 1.0) return "NOT determined relative to its size: zero within one sigma";
  return "determined";
}

std::string NoteText(const EstimateNote& n) {
  std::ostringstream out;
  switch (n.basis) {
    case EstimateBasis::kNone:
      break;
    case EstimateBasis::kClampedArmFit:
      out << "output error of the clamped arm over " << n.windows << " windows";
      break;
    case EstimateBasis::kThrustPairs:
      out << n.windows << " load-cell/telemetry pairs " << n.spacing_s << " s apart (turbulence averaged)";
      break;
    case EstimateBasis::kMotorFit:
      out << "output error over " << n.windows << " windows; " << n.command_steps[0] + n.command_steps[1]
          << " command steps";
      break;
    case EstimateBasis::kMotorFitContinuous:
      out << "output error over " << n.windows << " windows; " << n.command_steps[0] + n.command_steps[1]
          << " command steps: excited by the commands' continuous variation (relative sigma "
          << Percent(n.relative_sigma, 2) << " %)";
      break;
    case EstimateBasis::kMotorNotExcited:
      out << MotorNotExcitedError(n);
      break;
    case EstimateBasis::kFreeArmFit:
      if (n.joint) {
        out << "joint fit (one problem): " << n.load_cell_pairs << " load-cell pairs, " << n.clamped_windows
            << " clamped-arm windows and ";
      }
      out << "output error of the free-flight arm model over " << n.windows << " of " << n.candidate_windows
          << " windows" << (n.with_imu ? " with IMU" : " without IMU");
      break;
    case EstimateBasis::kTipMassAgreesWithBase:
      out << std::setprecision(4) << "base value kept: the flight's m_p = " << n.value << " +- " << n.sigma << " kg is "
          << std::setprecision(3) << n.distance_sigmas
          << " sigma from it (consistency_sigmas): this flight does not show the base file wrong, and its sigma is "
             "wider than a bench's";
      break;
    case EstimateBasis::kTipMassHeld:
      out << std::setprecision(4) << "held at the base value: at the fit with m_p held its relative sigma would be "
          << 100.0 * n.relative_sigma << " % with " << 100.0 * n.data_share
          << " % of its information from the data (the rest from the assumed rotor turbulence)";
      break;
    case EstimateBasis::kDampingNotFitted:
      out << "held at the base value (flight_fit_damping is off: flight data barely constrain d)";
      break;
  }
  for (EstimateRemark remark : n.remarks) out << RemarkText(remark, n);
  return out.str();
}

std::string CalibrationFactText(const IdentificationResult& result) {
  if (!result.has_calibration_fact) return "";
  const CalibrationFact& fact = result.calibration_fact;
  std::ostringstream text;
  if (fact.TipMassWeighed()) {
    text << "weighed tip mass m_p = " << fact.tip_mass_kg << " +- " << fact.tip_mass_std_kg
         << " kg; gauge scales identified";
    if (fact.gauge_scale_std > 0.0) text << " with the factory scale prior +- " << fact.gauge_scale_std;
  } else {
    text << "factory gauge scale s = [" << result.factory_gauge_scale[0] << ", " << result.factory_gauge_scale[1]
         << "]";
    if (fact.gauge_scale_std > 0.0) {
      text << " +- " << std::fixed << std::setprecision(6) << fact.gauge_scale_std;  // as std::to_string
    } else {
      text << " (held)";
    }
    text << "; tip mass identified";
  }
  return text.str();
}

std::string DroppedSamplesText(const SampleCleaningReport& report) {
  if (report.total() == 0) return "no sample dropped";
  std::string reasons;
  AppendReason("STRAIN", report.strain, &reasons);
  AppendReason("MOTOR", report.motor, &reasons);
  AppendReason("IMU", report.imu, &reasons);
  AppendReason("POSE", report.pose, &reasons);
  AppendReason("LOADCELL", report.loadcell, &reasons);
  return std::to_string(report.total()) + " dropped: " + reasons;
}

std::string ResidualBlockText(ResidualBlock block) {
  switch (block) {
    case ResidualBlock::kMotorTelemetry:
      return "motor telemetry (omega_meas - model)";
    case ResidualBlock::kLoadCell:
      return "load cell (force - c_T omega^2)";
    case ResidualBlock::kClampedArm:
      return "strain (clamped arm model)";
    case ResidualBlock::kFreeFlightStrain1:
      return "strain arm 1 (free-flight model)";
    case ResidualBlock::kFreeFlightStrain2:
      return "strain arm 2 (free-flight model)";
    case ResidualBlock::kGyroPitchRate:
      return "gyro pitch rate";
    case ResidualBlock::kAccelerometerX:
      return "accelerometer x";
    case ResidualBlock::kAccelerometerZ:
      return "accelerometer z";
    case ResidualBlock::kLoadCellJointFit:
      return "load cell (force - c_T omega^2), joint fit";
    case ResidualBlock::kClampedArmJointFit:
      return "strain (clamped arm model), joint fit";
  }
  return "";
}

std::string ResidualBlockUnit(ResidualBlock block) {
  switch (block) {
    case ResidualBlock::kMotorTelemetry:
    case ResidualBlock::kGyroPitchRate:
      return "rad/s";
    case ResidualBlock::kLoadCell:
    case ResidualBlock::kLoadCellJointFit:
      return "N";
    case ResidualBlock::kClampedArm:
    case ResidualBlock::kFreeFlightStrain1:
    case ResidualBlock::kFreeFlightStrain2:
    case ResidualBlock::kClampedArmJointFit:
      return "rad";
    case ResidualBlock::kAccelerometerX:
    case ResidualBlock::kAccelerometerZ:
      return "m/s^2";
  }
  return "";
}

std::string LogSharesText(const LogShares& shares) {
  std::string text = shares.symbol + ": ";
  for (size_t l = 0; l < shares.shares.size(); ++l) {
    text += (l == 0 ? "" : ", ") + shares.logs[l] + " " + Percent(shares.shares[l], 1) + " %";
  }
  return text;
}

std::string WarningText(const IdentificationWarning& w) {
  std::ostringstream out;
  switch (w.kind) {
    case WarningKind::kArmModelMisfit:
      out << std::setprecision(3) << "clamped-arm model misfit: strain residual RMS " << w.value
          << " sigma; every arm sigma widened by that factor (check the vehicle model and the strain noise)";
      break;
    case WarningKind::kNotExcitedOnBench:
      out << w.symbol
          << (w.symbol == "d" ? ": not determined (the arm modes are barely excited)"
                              : ": not determined by the bench data (arm modes not excited)")
          << "; base value kept";
      break;
    case WarningKind::kNotDeterminedInFlight:
      out << w.symbol << ": not determined by the flight data; base value kept";
      break;
    case WarningKind::kTipMassHeldInFlight:
      out << w.symbol << ": not determined by this flight; base value kept";
      break;
    case WarningKind::kTipMassAgreesWithBase:
      out << std::setprecision(4) << w.symbol << ": this flight gives " << w.value << " +- " << w.sigma << " kg, "
          << std::setprecision(3) << w.distance_sigmas
          << " sigma from the base file's value, which is kept (not written by --update-params)";
      break;
  }
  if (w.advice != ExcitationAdvice::kNone) out << "; " << AdviceText(w.advice);
  return out.str();
}

std::string CombinationText(const DeterminedCombination& c) {
  std::ostringstream out;
  out.precision(3);
  switch (c.kind) {
    case CombinationKind::kRatio:
    case CombinationKind::kProduct:
      out << c.a << " and " << c.b << " are not separated by the data (correlation " << c.correlation << "); " << c.a
          << (c.kind == CombinationKind::kRatio ? " / " : " * ") << c.b << " is determined to "
          << 100.0 * c.relative_sigma << " % (one sigma)";
      break;
    case CombinationKind::kThrustOverTotalMass:
      out << c.a << " is determined relative to the total mass: " << c.a << " / (m + 2 " << c.b << ") to "
          << 100.0 * c.relative_sigma << " % (one sigma; the accelerometer sees thrust over mass), " << c.a
          << " itself with " << c.b << " = " << c.held_value << " kg of the base file";
      break;
  }
  return out.str();
}

std::string IdentifiedParameterYaml(const IdentificationResult& result) {
  std::ostringstream out;
  out << "# Identified by birotor-identify (" << result.mode << " mode) from:\n";
  for (const std::string& s : result.sources) out << "#   " << s << "\n";
  if (result.has_calibration_fact) out << "# Calibration fact used: " << CalibrationFactText(result) << "\n";
  out << "# One-sigma uncertainties (parameters not listed are taken from the base file):\n";
  out << std::setprecision(6);
  for (const ParameterEstimate& e : result.estimates) {
    out << "#   " << e.key << ": " << e.value << " +- " << e.sigma;
    if (!e.determined) out << "  (NOT DETERMINED: base value kept)";
    out << "\n";
  }
  if (!result.maps.empty()) {
    out << "# Static deflection-force maps (b in rad):\n";
    for (const DeflectionForceMap& m : result.maps) out << "#   arm " << m.arm + 1 << ": " << MapText(m) << "\n";
  }
  for (const IdentificationWarning& w : result.warnings) out << "# warning: " << WarningText(w) << "\n";
  // An undetermined parameter keeps the base file's value, marked on its own line.
  std::vector<std::pair<std::string, std::string>> marks;
  for (const ParameterEstimate& e : result.estimates) {
    if (!e.determined) marks.emplace_back(e.key, "NOT DETERMINED by these logs: value of the base file");
  }
  out << BirotorParamsYaml(result.params, marks);
  return out.str();
}

std::string IdentificationReport(const IdentificationResult& result) {
  std::ostringstream out;
  out << "# Identification report (" << result.mode << " mode)\n\n";
  out << "Logs:\n";
  for (const std::string& s : result.sources) out << "- " << s << "\n";
  out << "\nBad samples (non-finite, bad stamp, out of order, duplicate): " << DroppedSamplesText(result.dropped)
      << ".\n";
  if (!result.ok) {
    out << "\n**No parameters: the data lacks what the identification needs.**\n\n";
    for (const std::string& e : result.errors) out << "- " << e << "\n";
  }
  if (result.has_calibration_fact) {
    out << "\nCalibration fact (the one of gauge scale, stiffness, tip mass that statics and dynamics cannot give): "
        << CalibrationFactText(result) << "\n";
  }
  out << "\n## Parameters\n\n| parameter | key | value | one sigma | relative sigma | status "
         "|\n|---|---|---|---|---|---|\n";
  out << std::setprecision(6);
  for (const ParameterEstimate& e : result.estimates) {
    const double relative_sigma = e.sigma / std::abs(e.value);
    out << "| " << e.symbol << " | " << e.key << " | " << e.value << " | ";
    if (std::isfinite(relative_sigma)) {
      out << e.sigma << " | " << std::setprecision(3) << 100.0 * relative_sigma << " %" << std::setprecision(6);
    } else {
      out << "not determined | not determined";
    }
    out << " | " << ReportStatus(e) << " |\n";
  }
  out << "\nNotes:\n";
  for (const ParameterEstimate& e : result.estimates) out << "- " << e.symbol << ": " << NoteText(e.note) << "\n";
  out << "\n## Residuals (after the fit)\n\n| block | count | RMS [sigma] | RMS | covariance inflation "
         "|\n|---|---|---|---|---|\n";
  for (const ResidualSummary& r : result.residuals) {
    out << "| " << ResidualBlockText(r.block) << " | " << r.count << " | " << std::setprecision(4) << r.rms_whitened
        << " | " << r.rms_si << " " << ResidualBlockUnit(r.block) << " | " << r.variance_inflation << " |\n";
  }
  if (!result.maps.empty()) {
    out << "\n## Static deflection-force maps\n\n";
    for (const DeflectionForceMap& m : result.maps) out << "- arm " << m.arm + 1 << ": " << MapText(m) << "\n";
  }
  if (!result.log_shares.empty()) {
    out << "\n## Which log determines which parameter (share of the information, each log alone)\n\n";
    for (const LogShares& shares : result.log_shares) out << "- " << LogSharesText(shares) << "\n";
  }
  if (!result.correlations.empty()) {
    out << "\n## Parameters the data cannot separate\n\n";
    for (const DeterminedCombination& c : result.correlations) out << "- " << CombinationText(c) << "\n";
  }
  out << "\n## Undetermined parameters\n\n";
  bool any = false;
  for (const ParameterEstimate& e : result.estimates) {
    const std::string status = ReportStatus(e);
    if (status == "NOT determined") {
      out << "- " << e.symbol << " (" << e.key << ")\n";
      any = true;
    } else if (status != "determined") {
      // Determined by the fit's criterion, so --update-params writes it; the reader is told why to doubt it.
      out << "- " << e.symbol << " (" << e.key << "): " << status << "; the fit's value is written\n";
      any = true;
    }
  }
  if (!any) out << "None.\n";
  if (!result.warnings.empty()) {
    out << "\n## Warnings\n\n";
    for (const IdentificationWarning& w : result.warnings) out << "- " << WarningText(w) << "\n";
  }
  return out.str();
}

}  // namespace birotor
