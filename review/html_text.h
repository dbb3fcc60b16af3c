// Text from a log on its way into the review page: HTML-escaped, and with
// every control character as '?' (transport/wire_text.h), so a channel name
// or a path cannot break the page or carry a terminal escape into it.
#pragma once

#include <string>

#include "transport/wire_text.h"

namespace birotor {

inline std::string EscapeHtml(const std::string& text) {
  std::string out;
  for (const char c : PrintableWireText(text)) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace birotor
