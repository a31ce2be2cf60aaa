// CAN over UDP (cannelloni v2 packets) on POSIX sockets.
#include "firmware_protocol/transport/udp_transport.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "firmware_protocol/transport/cannelloni_packet.h"

namespace vesica::fp {

namespace {
Nanoseconds monotonic_now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return Nanoseconds{static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
}
bool make_address(const std::string& host, std::uint16_t port, sockaddr_in& out) {
  std::memset(&out, 0, sizeof out);
  out.sin_family = AF_INET;
  out.sin_port = htons(port);
  return inet_pton(AF_INET, host.c_str(), &out.sin_addr) == 1;
}
}  // namespace

std::unique_ptr<UdpTransport> UdpTransport::open(const UdpTransportConfig& config, std::string& error) {
  sockaddr_in local{}, remote{};
  if (!make_address(config.local_address, config.local_port, local)) {
    error = "udp: bad local address '" + config.local_address + "'";
    return nullptr;
  }
  if (!make_address(config.remote_address, config.remote_port, remote)) {
    error = "udp: bad remote address '" + config.remote_address + "'";
    return nullptr;
  }
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    error = std::string("udp: socket: ") + std::strerror(errno);
    return nullptr;
  }
  if (::bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0) {
    error = "udp: bind " + config.local_address + ":" + std::to_string(config.local_port) + ": " + std::strerror(errno);
    ::close(fd);
    return nullptr;
  }
  socklen_t len = sizeof local;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len);
  std::unique_ptr<UdpTransport> t(new UdpTransport());
  t->fd_ = fd;
  t->local_port_ = ntohs(local.sin_port);
  std::memcpy(t->remote_, &remote, sizeof remote);
  return t;
}

UdpTransport::~UdpTransport() {
  if (fd_ >= 0) ::close(fd_);
}

void UdpTransport::set_remote_port(std::uint16_t port) {
  sockaddr_in remote;
  std::memcpy(&remote, remote_, sizeof remote);
  remote.sin_port = htons(port);
  std::memcpy(remote_, &remote, sizeof remote);
}

Nanoseconds UdpTransport::now() const { return monotonic_now(); }

SendStatus UdpTransport::send(const CanFrame& frame, Nanoseconds deadline) {
  if (fd_ < 0) return SendStatus::Closed;
  if (frame.fd() ? !is_valid_fd_length(frame.len) : frame.len > kClassicMaxLength) return SendStatus::Invalid;
  std::uint8_t packet[kCannelloniHeaderSize + 4 + 2 + kFdMaxLength];
  const std::size_t n = write_cannelloni_packet(&frame, 1, tx_seq_, packet, sizeof packet);
  for (;;) {
    if (now() > deadline) {
      ++stats_.tx_dropped;
      return SendStatus::DeadlineMissed;
    }
    const ssize_t sent = ::sendto(fd_, packet, n, 0, reinterpret_cast<const sockaddr*>(remote_), sizeof(sockaddr_in));
    if (sent == static_cast<ssize_t>(n)) {
      ++tx_seq_;
      ++stats_.tx_frames;
      return SendStatus::Queued;
    }
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == ENOBUFS) {
      // Socket buffer full: wait for room until the deadline.
      const auto left = deadline - now();
      if (left.count() <= 0) continue;
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, static_cast<int>(left.count() / 1'000'000) + 1);
      continue;
    }
    if (errno == ECONNREFUSED) {  // no listener (yet): the datagram is lost, like a bus without nodes
      ++stats_.tx_dropped;
      return SendStatus::Queued;
    }
    ++stats_.tx_dropped;
    events_.push_back({BusEvent::Kind::DeviceLost, state_, static_cast<std::uint32_t>(errno), now()});
    return SendStatus::Closed;
  }
}

void UdpTransport::drain_socket() {
  std::uint8_t packet[2048];
  sockaddr_in peer;
  std::memcpy(&peer, remote_, sizeof peer);
  for (;;) {
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, packet, sizeof packet, 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) {
      if (errno == EINTR) continue;
      return;  // EAGAIN: empty; ECONNREFUSED from an earlier send: ignore
    }
    // Only the configured peer speaks on this link: anything else on the port (a stray tool, a
    // second emulator, a spoofer) would inject torque commands or joint states. Dropped, counted.
    if (from_len != sizeof from || from.sin_family != AF_INET || from.sin_addr.s_addr != peer.sin_addr.s_addr ||
        from.sin_port != peer.sin_port) {
      ++stats_.foreign;
      continue;
    }
    const Nanoseconds t = now();
    std::uint8_t seq = 0;
    std::size_t frames = 0;
    const CannelloniError e = parse_cannelloni_packet(packet, static_cast<std::size_t>(n), seq, [&](const CanFrame& f) {
      if (f.id & kLinuxErrFlag) {
        ++stats_.error_frames;
        events_.push_back({BusEvent::Kind::ErrorFrame, state_, f.id & 0x1FFFFFFFu, t});
        return;
      }
      rx_.push_back({f, t});
      ++stats_.rx_frames;
      ++frames;
    });
    if (e != CannelloniError::None) {
      ++stats_.malformed;
      continue;
    }
    if (rx_seq_primed_ && seq != static_cast<std::uint8_t>(rx_seq_ + 1)) {
      const std::uint8_t lost = static_cast<std::uint8_t>(seq - rx_seq_ - 1);
      stats_.rx_dropped += lost;
      events_.push_back({BusEvent::Kind::RxOverflow, state_, lost, t});
    }
    rx_seq_primed_ = true;
    rx_seq_ = seq;
  }
}

bool UdpTransport::receive(TimedFrame& out) {
  if (rx_.empty()) drain_socket();
  if (rx_.empty()) return false;
  out = rx_.front();
  rx_.pop_front();
  return true;
}

bool UdpTransport::poll_event(BusEvent& out) {
  drain_socket();
  if (events_.empty()) return false;
  out = events_.front();
  events_.pop_front();
  return true;
}

bool UdpTransport::wait(Nanoseconds timeout) {
  if (!rx_.empty() || !events_.empty()) return true;
  pollfd p{fd_, POLLIN, 0};
  const auto us = timeout.count() / 1000;
  // poll() has millisecond resolution; sub-millisecond waits use ppoll.
  timespec ts{static_cast<time_t>(us / 1'000'000), static_cast<long>((us % 1'000'000) * 1000)};
  return ::ppoll(&p, 1, &ts, nullptr) > 0;
}

}  // namespace vesica::fp
