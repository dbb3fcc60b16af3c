// Output of the identification: the parameter file the estimator and the
// simulator load (a full `vehicle:` section, uncertainties and the
// deflection-force maps as comments) and a readable report. The tool writes
// them through transport/output_file.h. Here, beside the reader of the same
// file, so that the keys are written from the reader's table.
#pragma once

#include <string>

#include "identification/identification_result.h"

namespace birotor {

// The words of a warning of the identification (the library gives its kind
// and numbers): one line, as the report, the file header and birotor-identify
// print it, with the advice on what to fly when there is one.
std::string WarningText(const IdentificationWarning& warning);

// The words of a combination the data determine where its parameters are
// not separated (one line, as the report and birotor-identify print it).
std::string CombinationText(const DeterminedCombination& combination);

// The note of an estimate: how its value and sigma were obtained (the
// basis, then each remark in the order the fit added it), or why it was kept
// at the base value. One line, as the report prints it.
std::string NoteText(const EstimateNote& note);

// The calibration fact the bench fit used (weighed tip mass or factory gauge
// scale); empty when the result has none (flight). As the report, the file
// header, the --update-params stamp and birotor-identify print it.
std::string CalibrationFactText(const IdentificationResult& result);

// One parameter's information shares, e.g. "k: a.lcm 70.0 %, b.lcm 30.0 %".
std::string LogSharesText(const LogShares& shares);

// The bad samples dropped before fitting: "12 dropped: STRAIN 1 bad stamp,
// 10 duplicate; MOTOR 1 non-finite", or "no sample dropped".
std::string DroppedSamplesText(const SampleCleaningReport& report);

// The name of a block of residuals in the report's table, and the unit of
// its rms_si.
std::string ResidualBlockText(ResidualBlock block);
std::string ResidualBlockUnit(ResidualBlock block);

// YAML text: comment header (sources, one-sigma values, maps, residuals)
// followed by BirotorParamsYaml(result.params).
std::string IdentifiedParameterYaml(const IdentificationResult& result);

// Markdown report: parameters with value, sigma, relative sigma and status,
// residual RMS per residual block, maps, undetermined parameters, warnings.
std::string IdentificationReport(const IdentificationResult& result);
// The report's status of one estimate: "determined" only when the fit
// determined it, its one sigma is at most 100 % of its value (an offset
// near zero reads "NOT determined relative to its size: zero within one
// sigma"), and for tau_m the logs held a command step (the motor fit's
// excitation); "NOT determined" when the fit did not determine it.
std::string ReportStatus(const ParameterEstimate& e);

}  // namespace birotor
