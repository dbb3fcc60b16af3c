// Text that came over the wire or out of a log (channel names, the strings of
// estimator_status_t) on its way to a terminal or a page: control characters
// (ESC sequences that move the cursor or retitle the terminal, BEL, CR, DEL,
// C1 controls) are replaced by '?', so a hostile or damaged name cannot drive
// the terminal. UTF-8 beyond them is kept as it is.
#pragma once

#include <string>

namespace birotor {

inline std::string PrintableWireText(const std::string& text) {
  std::string out = text;
  for (size_t i = 0; i < out.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(out[i]);
    // C0 controls and DEL; C1 controls (U+0080..U+009F) as their UTF-8 form 0xC2 0x80..0x9F.
    if (c < 0x20 || c == 0x7f) out[i] = '?';
    if (c == 0xc2 && i + 1 < out.size() && static_cast<unsigned char>(out[i + 1]) >= 0x80 &&
        static_cast<unsigned char>(out[i + 1]) <= 0x9f) {
      out[i] = '?';
      out.erase(i + 1, 1);
    }
  }
  return out;
}

}  // namespace birotor
