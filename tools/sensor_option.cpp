#include "tools/sensor_option.hpp"

#include <arpa/inet.h>

#include "io/input_error.hpp"
#include "io/udp_endpoint.hpp"

namespace conicloc::tools {

void apply_sensor_option(const std::string& text, const std::string& flag,
                         io::StreamConfig& stream) {
  const io::UdpEndpoint endpoint = io::parse_listen_endpoint(text, flag);
  if (endpoint.port == 0) {
    throw io::InputError(flag, "'" + text + "'", "a sensor's data port cannot be 0");
  }
  stream.data_port = endpoint.port;
  stream.source_address =
      endpoint.host.empty() ? 0 : ntohl(io::socket_address(endpoint).sin_addr.s_addr);
}

std::string sensor_text(const io::StreamConfig& stream) {
  std::string address;
  if (stream.source_address != 0) {
    const std::uint32_t a = stream.source_address;
    address = std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 0xFF) + "." +
              std::to_string((a >> 8) & 0xFF) + "." + std::to_string(a & 0xFF);
  }
  return address + ":" + std::to_string(stream.data_port);
}

}  // namespace conicloc::tools
