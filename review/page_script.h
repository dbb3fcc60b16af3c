// The review page's script and style sheet (review/review_page.cc inlines
// them after dygraphs): the charts from the page's REVIEW JSON, one time axis
// for all, the event markers through every chart, the x-z path on a canvas,
// and a summary the browser test reads (charts, rows, headline, errors).
#pragma once

namespace birotor {

extern const char* const kReviewPageScript;
extern const char* const kReviewPageStyle;

}  // namespace birotor
