// The live-source factory.
#include "sources/message_source.h"

#include "sources/lcm_source.h"
#include "sources/udpm_source.h"

namespace birotor {

const std::string& MessageSource::error() const {
  static const std::string kNone;
  return kNone;
}

std::unique_ptr<MessageSource> OpenLiveSource(const std::string& url, lcm::LCM* lcm, std::string* error) {
  if (url.rfind("udpm://", 0) == 0) {
    UdpmUrl parsed;
    if (!ParseUdpmUrl(url, &parsed, error)) return nullptr;
    auto source = std::make_unique<UdpmSource>();
    if (!source->Open(parsed, error)) return nullptr;
    return source;
  }
  return std::make_unique<LcmSource>(lcm);
}

}  // namespace birotor
