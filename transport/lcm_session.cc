// LCM instance creation and receive-buffer diagnostics.
#include "transport/lcm_session.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace birotor {
namespace {

// Provider of an LCM URL ("udpm" for "udpm://host:port?opts").
std::string Provider(const std::string& url) {
  const size_t end = url.find("://");
  return end == std::string::npos ? std::string() : url.substr(0, end);
}

// Value of option `key` in the query part of an LCM URL ("a=1&b=2").
std::optional<std::string> UrlOption(const std::string& url, const std::string& key) {
  const size_t query = url.find('?');
  if (query == std::string::npos) return std::nullopt;
  size_t begin = query + 1;
  while (begin <= url.size()) {
    size_t end = url.find('&', begin);
    if (end == std::string::npos) end = url.size();
    const std::string pair = url.substr(begin, end - begin);
    const size_t equals = pair.find('=');
    if (equals != std::string::npos && pair.compare(0, equals, key) == 0) {
      return pair.substr(equals + 1);
    }
    begin = end + 1;
  }
  return std::nullopt;
}

std::optional<int64_t> ParsePositiveInteger(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || *end != '\0' || value <= 0) return std::nullopt;
  return static_cast<int64_t>(value);
}

}  // namespace

std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url, std::string* error) {
  auto lcm = std::make_unique<lcm::LCM>(url);
  if (!lcm->good()) {
    if (error) {
      *error = "cannot open LCM URL '" + url +
               "': the provider (udpm://, memq://, file://, tcpq://) is unknown, "
               "the URL is malformed, or the socket/file cannot be opened";
      if (Provider(url) == "udpm") {
        *error +=
            " (for udpm without a network, route multicast to loopback: "
            "ip route add 224.0.0.0/4 dev lo)";
      }
    }
    return nullptr;
  }
  return lcm;
}

std::optional<int64_t> RequestedReceiveBuffer(const std::string& url) {
  const std::optional<std::string> value = UrlOption(url, "recv_buf_size");
  if (!value) return std::nullopt;
  return ParsePositiveInteger(*value);
}

int64_t ReadRmemMax(const std::string& path) {
  std::ifstream file(path);
  int64_t value = -1;
  if (!(file >> value) || value <= 0) return -1;
  return value;
}

std::string ReceiveBufferReport(const std::string& url, int64_t rmem_max_bytes, bool* sufficient) {
  if (sufficient) *sufficient = true;
  const std::string provider = Provider(url);
  if (provider != "udpm") {
    return "LCM provider '" + provider + "' uses no UDP receive buffer";
  }
  const std::string limit = rmem_max_bytes > 0 ? "kernel rmem_max is " + std::to_string(rmem_max_bytes) + " B"
                                               : std::string("kernel rmem_max is unknown");
  const std::optional<int64_t> requested = RequestedReceiveBuffer(url);
  if (!requested) {
    return "no recv_buf_size in the LCM URL: the kernel default receive buffer "
           "applies (" +
           limit + ")";
  }
  const std::string request = "requested " + std::to_string(*requested) + " B receive buffer; " + limit;
  if (rmem_max_bytes > 0 && *requested > rmem_max_bytes) {
    if (sufficient) *sufficient = false;
    return request + ": raise it with sysctl -w net.core.rmem_max=" + std::to_string(*requested);
  }
  return request;
}

bool ParseUdpmUrl(const std::string& url, UdpmUrl* parsed, std::string* error) {
  *parsed = UdpmUrl();
  if (Provider(url) != "udpm") {
    *error = "not a udpm:// URL: '" + url.substr(0, 80) + "'";
    return false;
  }
  const size_t address_begin = url.find("://") + 3;
  const size_t query = url.find('?', address_begin);
  const std::string address =
      url.substr(address_begin, query == std::string::npos ? std::string::npos : query - address_begin);
  if (!address.empty()) {
    const size_t colon = address.rfind(':');
    parsed->group = address.substr(0, colon);
    if (colon != std::string::npos) {
      const std::optional<int64_t> port = ParsePositiveInteger(address.substr(colon + 1));
      if (!port || *port > 65535) {
        *error = "bad port in udpm URL '" + url.substr(0, 80) + "'";
        return false;
      }
      parsed->port = static_cast<int>(*port);
    }
  }
  if (const std::optional<std::string> ttl = UrlOption(url, "ttl")) {
    const std::optional<int64_t> value = *ttl == "0" ? std::optional<int64_t>(0) : ParsePositiveInteger(*ttl);
    if (!value || *value > 255) {
      *error = "bad ttl in udpm URL '" + url.substr(0, 80) + "' (0..255)";
      return false;
    }
    parsed->ttl = static_cast<int>(*value);
  }
  if (UrlOption(url, "recv_buf_size")) {
    const std::optional<int64_t> size = RequestedReceiveBuffer(url);
    if (!size || *size > INT_MAX) {
      *error = "bad recv_buf_size in udpm URL '" + url.substr(0, 80) + "'";
      return false;
    }
    parsed->recv_buf_size = *size;
  }
  return true;
}

int HandleFor(lcm::LCM& lcm, double timeout_s) {
  const double timeout_ms = std::isnan(timeout_s) ? 0.0 : timeout_s * 1e3;
  const double clamped_ms = std::min(std::max(timeout_ms, 0.0), double{INT_MAX});
  return lcm.handleTimeout(static_cast<int>(std::lround(clamped_ms)));
}

}  // namespace birotor
