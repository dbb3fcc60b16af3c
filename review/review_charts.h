// The review page's charts for one log or two overlaid (A and B): which
// series each chart draws, in which colour (an estimate solid, its truth and
// a reference dashed, log B in other hues), its robust y range, the x-z path
// and the events marked through every chart, as the page's JSON.
#pragma once

#include <string>
#include <vector>

#include "review/display_series.h"
#include "review/flight_data.h"
#include "review/flight_headline.h"

namespace birotor {

// Most points of one drawn x-z path (every n-th sample).
inline constexpr size_t kMaxPathPoints = 3000;

// One log to chart: its data, its input rates and gaps (InputRatesAndGaps)
// and its headline (for the markers). Labels get "A: " / "B: " when there
// are two logs.
struct ChartedLog {
  const FlightData* data = nullptr;
  const Table* rates = nullptr;
  const FlightHeadline* headline = nullptr;
};

// Every chart with data, in page order (the questions first: forces,
// position against the setpoint, attitude, FORCE status lanes), then the
// estimator's and the inputs' details, then the controller.
std::vector<DisplayChart> ReviewCharts(const std::vector<ChartedLog>& logs);

// {"charts":[...],"paths":[...],"events":[...]}: what the page's script draws.
std::string ReviewJson(const std::vector<ChartedLog>& logs, const std::vector<DisplayChart>& charts);

// One plain sentence per kind of data the log lacks, saying what is left
// out and where such data comes from; "" when nothing is missing.
std::string MissingDataHtml(const FlightData& data);

}  // namespace birotor
