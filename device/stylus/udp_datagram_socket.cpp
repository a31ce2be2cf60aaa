#include "device/stylus/udp_datagram_socket.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vesica::device {
namespace {

bool ToSockaddr(const UdpEndpoint& e, sockaddr_in* out, std::string* error) {
  std::memset(out, 0, sizeof *out);
  out->sin_family = AF_INET;
  out->sin_port = htons(e.port);
  if (inet_pton(AF_INET, e.address.c_str(), &out->sin_addr) != 1) {
    *error = "'" + e.address + "' is not an IPv4 address";
    return false;
  }
  return true;
}

}  // namespace

std::unique_ptr<UdpDatagramSocket> UdpDatagramSocket::Open(const UdpEndpoint& local, const UdpEndpoint& peer,
                                                           std::string* error) {
  static_assert(sizeof(sockaddr_in) <= sizeof(UdpDatagramSocket::peer_addr_));
  sockaddr_in local_addr{};
  sockaddr_in peer_addr{};
  if (!ToSockaddr(local, &local_addr, error) || !ToSockaddr(peer, &peer_addr, error)) return nullptr;
  std::unique_ptr<UdpDatagramSocket> s(new UdpDatagramSocket());
  s->fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (s->fd_ < 0) {
    *error = std::string("socket(): ") + std::strerror(errno);
    return nullptr;
  }
  if (bind(s->fd_, reinterpret_cast<const sockaddr*>(&local_addr), sizeof local_addr) != 0) {
    *error = "cannot bind UDP " + local.address + ":" + std::to_string(local.port) + ": " + std::strerror(errno);
    return nullptr;
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  getsockname(s->fd_, reinterpret_cast<sockaddr*>(&bound), &len);
  s->local_port_ = ntohs(bound.sin_port);
  s->peer_ = peer;
  std::memcpy(s->peer_addr_, &peer_addr, sizeof peer_addr);
  return s;
}

UdpDatagramSocket::~UdpDatagramSocket() {
  if (fd_ >= 0) close(fd_);
}

bool UdpDatagramSocket::Send(std::span<const std::uint8_t> bytes, std::string* error) {
  const ssize_t n =
      sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(peer_addr_), sizeof(sockaddr_in));
  if (n == static_cast<ssize_t>(bytes.size())) return true;
  // Loopback reports an absent peer as ECONNREFUSED from an earlier ICMP: not a send failure.
  if (n < 0 && errno == ECONNREFUSED) return true;
  *error = "sendto " + peer_.address + ":" + std::to_string(peer_.port) + ": " +
           (n < 0 ? std::strerror(errno) : "short write");
  return false;
}

long UdpDatagramSocket::Receive(std::span<std::uint8_t> buffer, bool* from_peer) {
  sockaddr_in from{};
  socklen_t len = sizeof from;
  for (;;) {
    const ssize_t n = recvfrom(fd_, buffer.data(), buffer.size(), MSG_TRUNC, reinterpret_cast<sockaddr*>(&from), &len);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return -1;  // EAGAIN (nothing waiting) or a pending ICMP error: nothing to read
    const auto* peer = reinterpret_cast<const sockaddr_in*>(peer_addr_);
    *from_peer = from.sin_addr.s_addr == peer->sin_addr.s_addr && from.sin_port == peer->sin_port;
    return static_cast<long>(n);  // MSG_TRUNC: the real length, so an oversize datagram is seen as such
  }
}

bool UdpDatagramSocket::Wait(std::int64_t timeout_ns) {
  pollfd p{fd_, POLLIN, 0};
  timespec ts{static_cast<time_t>(timeout_ns / 1'000'000'000), static_cast<long>(timeout_ns % 1'000'000'000)};
  return ppoll(&p, 1, &ts, nullptr) > 0;
}

}  // namespace vesica::device
