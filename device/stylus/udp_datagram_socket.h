#pragma once
// A non-blocking UDP socket on IPv4 with one peer: the Omni emulator link's transport (both
// ends). Plain datagrams, unlike fp::UdpTransport which carries CAN frames.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace vesica::device {

struct UdpEndpoint {
  std::string address = "127.0.0.1";
  std::uint16_t port = 0;  ///< local: 0 = any free port
};

class UdpDatagramSocket {
 public:
  /// Binds `local` and sends to `peer`. nullptr and *error naming the address and errno text on
  /// failure.
  static std::unique_ptr<UdpDatagramSocket> Open(const UdpEndpoint& local, const UdpEndpoint& peer, std::string* error);
  ~UdpDatagramSocket();
  UdpDatagramSocket(const UdpDatagramSocket&) = delete;
  UdpDatagramSocket& operator=(const UdpDatagramSocket&) = delete;

  /// Sends one datagram to the peer; false (and *error) when the kernel refused it. A peer that
  /// is not there is not an error on UDP: the datagram is dropped.
  bool Send(std::span<const std::uint8_t> bytes, std::string* error);
  /// Reads one waiting datagram from anyone into `buffer`; its length, or -1 when none is waiting.
  /// *from_peer says whether it came from the configured peer.
  long Receive(std::span<std::uint8_t> buffer, bool* from_peer);
  /// Blocks up to timeout_ns for a datagram to arrive; true when one is waiting.
  bool Wait(std::int64_t timeout_ns);

  std::uint16_t local_port() const { return local_port_; }
  const UdpEndpoint& peer() const { return peer_; }

 private:
  UdpDatagramSocket() = default;
  int fd_ = -1;
  std::uint16_t local_port_ = 0;
  UdpEndpoint peer_;
  unsigned char peer_addr_[16] = {};  // sockaddr_in
};

}  // namespace vesica::device
