// The flight review page of birotor-review: one self-contained HTML file
// (dygraphs inlined from Debian's libjs-dygraphs at build time, the data as
// JSON) that opens offline: forces with their one-sigma band and the truth,
// thrust efficiencies, status bits as lanes, per-input NIS and fusion counts,
// input rates and gaps, position, controller commands, modes and fallbacks,
// all on one time axis that zooms and pans together; tables of the channels,
// the first rise of each alarm and the controller's fallbacks.
#pragma once

#include <string>
#include <vector>

#include "review/flight_data.h"

namespace birotor {

// The page for data. Presentation text (titles, labels) lives here.
std::string ReviewPageHtml(const FlightData& data);
// Two (or more) logs on one page: a headline column per log, their series
// overlaid on each chart ("A: ...", "B: ..."), each on its own t = 0.
std::string ReviewPageHtml(const std::vector<const FlightData*>& logs);

// Flight figures as text lines for a terminal (birotor-review prints them;
// tools/demo.sh --controller shows them): the position held (deviation from
// the first TRUTH sample, else the first POSE: max and RMS of x and z) and
// the controller's commands and fallbacks with their times, and the headline
// ("flight: headline: <question>: <answer>" lines, review/flight_headline.h).
std::string FlightSummaryText(const FlightData& data);

// The dygraphs library and style sheet, from libjs-dygraphs (generated file).
extern const char* const kDygraphJs;
extern const char* const kDygraphCss;

}  // namespace birotor
