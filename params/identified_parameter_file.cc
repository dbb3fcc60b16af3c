#include "params/identified_parameter_file.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "params/vehicle_params_yaml.h"

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

}  // namespace

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
  if (!result.calibration_fact.empty()) out << "# Calibration fact used: " << result.calibration_fact << "\n";
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
  out << VehicleParamsYaml(result.params, marks);
  return out.str();
}

std::string IdentificationReport(const IdentificationResult& result) {
  std::ostringstream out;
  out << "# Identification report (" << result.mode << " mode)\n\n";
  out << "Logs:\n";
  for (const std::string& s : result.sources) out << "- " << s << "\n";
  out << "\nBad samples (non-finite, bad stamp, out of order, duplicate): " << result.dropped.Summary() << ".\n";
  if (!result.ok) {
    out << "\n**No parameters: the data lacks what the identification needs.**\n\n";
    for (const std::string& e : result.errors) out << "- " << e << "\n";
  }
  if (!result.calibration_fact.empty()) {
    out << "\nCalibration fact (the one of gauge scale, stiffness, tip mass that statics and dynamics cannot give): "
        << result.calibration_fact << "\n";
  }
  out << "\n## Parameters\n\n| parameter | key | value | one sigma | relative sigma | status "
         "|\n|---|---|---|---|---|---|\n";
  out << std::setprecision(6);
  for (const ParameterEstimate& e : result.estimates) {
    const double rel = std::abs(e.value) > 0 ? e.sigma / std::abs(e.value) : NAN;
    out << "| " << e.symbol << " | " << e.key << " | " << e.value << " | " << e.sigma << " | " << std::setprecision(3)
        << 100.0 * rel << " % | " << (e.determined ? "determined" : "NOT determined") << std::setprecision(6) << " |\n";
  }
  out << "\nNotes:\n";
  for (const ParameterEstimate& e : result.estimates) out << "- " << e.symbol << ": " << e.note << "\n";
  out << "\n## Residuals (after the fit)\n\n| block | count | RMS [sigma] | RMS | covariance inflation "
         "|\n|---|---|---|---|---|\n";
  for (const ResidualSummary& r : result.residuals) {
    out << "| " << r.name << " | " << r.count << " | " << std::setprecision(4) << r.rms_whitened << " | " << r.rms_si
        << " " << r.unit << " | " << r.variance_inflation << " |\n";
  }
  if (!result.maps.empty()) {
    out << "\n## Static deflection-force maps\n\n";
    for (const DeflectionForceMap& m : result.maps) out << "- arm " << m.arm + 1 << ": " << MapText(m) << "\n";
  }
  if (!result.log_shares.empty()) {
    out << "\n## Which log determines which parameter (share of the information, each log alone)\n\n";
    for (const std::string& line : result.log_shares) out << "- " << line << "\n";
  }
  if (!result.correlations.empty()) {
    out << "\n## Parameters the data cannot separate\n\n";
    for (const DeterminedCombination& c : result.correlations) out << "- " << CombinationText(c) << "\n";
  }
  out << "\n## Undetermined parameters\n\n";
  bool any = false;
  for (const ParameterEstimate& e : result.estimates) {
    if (!e.determined) {
      out << "- " << e.symbol << " (" << e.key << ")\n";
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
