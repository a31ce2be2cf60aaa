// SocketCAN CAN_RAW transport.
#include "firmware_protocol/transport/socketcan_transport.h"

#include "firmware_protocol/transport/socketcan_error_frame.h"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

namespace vesica::fp {

namespace {
Nanoseconds realtime_now() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return Nanoseconds{static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
}
std::string errno_text(const char* what) { return std::string(what) + ": " + std::strerror(errno); }
}  // namespace

bool SocketCanTransport::kernel_supports_can(std::string& why_not) {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    why_not = errno_text("socket(AF_CAN, SOCK_RAW, CAN_RAW)");
    return false;
  }
  ::close(fd);
  return true;
}

std::unique_ptr<SocketCanTransport> SocketCanTransport::open(const SocketCanConfig& config, std::string& error) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    error = errno_text("socket(AF_CAN, SOCK_RAW, CAN_RAW)");
    return nullptr;
  }
  std::unique_ptr<SocketCanTransport> t(new SocketCanTransport());
  t->fd_ = fd;
  t->fd_frames_ = config.fd_frames;
  auto opt = [&](int level, int name, const void* v, socklen_t n, const char* what) {
    if (::setsockopt(fd, level, name, v, n) == 0) return true;
    error = errno_text(what);
    return false;
  };
  const int one = 1, own = config.receive_own ? 1 : 0, loop = config.loopback ? 1 : 0;
  if (config.fd_frames && !opt(SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &one, sizeof one, "setsockopt(CAN_RAW_FD_FRAMES)"))
    return nullptr;
  if (!opt(SOL_CAN_RAW, CAN_RAW_LOOPBACK, &loop, sizeof loop, "setsockopt(CAN_RAW_LOOPBACK)")) return nullptr;
  if (!opt(SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof own, "setsockopt(CAN_RAW_RECV_OWN_MSGS)")) return nullptr;
  if (!config.filters.empty()) {
    std::vector<can_filter> f;
    for (const CanIdFilter& c : config.filters) f.push_back({c.id, c.mask});
    if (!opt(SOL_CAN_RAW, CAN_RAW_FILTER, f.data(), static_cast<socklen_t>(f.size() * sizeof(can_filter)),
             "setsockopt(CAN_RAW_FILTER)"))
      return nullptr;
  }
  const can_err_mask_t err_mask = config.error_frames ? CAN_ERR_MASK : 0;
  if (!opt(SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask, "setsockopt(CAN_RAW_ERR_FILTER)")) return nullptr;
  if (!opt(SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one, "setsockopt(SO_TIMESTAMPNS)")) return nullptr;
  if (!opt(SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one, "setsockopt(SO_RXQ_OVFL)")) return nullptr;

  ifreq ifr{};
  if (config.interface.size() >= IFNAMSIZ) {
    error = "interface name too long: " + config.interface;
    return nullptr;
  }
  std::strncpy(ifr.ifr_name, config.interface.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
    error = errno_text(("SIOCGIFINDEX " + config.interface).c_str());
    return nullptr;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    error = errno_text(("bind " + config.interface).c_str());
    return nullptr;
  }
  return t;
}

SocketCanTransport::~SocketCanTransport() {
  if (fd_ >= 0) ::close(fd_);
}

Nanoseconds SocketCanTransport::now() const { return realtime_now(); }

void SocketCanTransport::set_state(BusState s, Nanoseconds t) {
  if (s == state_) return;
  state_ = s;
  events_.push_back({BusEvent::Kind::StateChanged, s, static_cast<std::uint32_t>(s), t});
}

SendStatus SocketCanTransport::send(const CanFrame& frame, Nanoseconds deadline) {
  if (fd_ < 0) return SendStatus::Closed;
  if (state_ == BusState::BusOff) return SendStatus::BusOff;
  canfd_frame out{};
  out.can_id = frame.id & (frame.extended() ? CAN_EFF_MASK : CAN_SFF_MASK);
  if (frame.extended()) out.can_id |= CAN_EFF_FLAG;
  if (frame.remote()) out.can_id |= CAN_RTR_FLAG;
  std::size_t size = CAN_MTU;
  if (frame.fd()) {
    if (!fd_frames_ || !is_valid_fd_length(frame.len)) return SendStatus::Invalid;
    size = CANFD_MTU;
    out.flags = frame.brs() ? CANFD_BRS : 0;
  } else if (frame.len > CAN_MAX_DLEN) {
    return SendStatus::Invalid;
  }
  out.len = frame.len;
  std::memcpy(out.data, frame.data, frame.len);
  for (;;) {
    if (now() > deadline) {
      ++stats_.tx_dropped;
      events_.push_back({BusEvent::Kind::TxDropped, state_, frame.id, now()});
      return SendStatus::DeadlineMissed;
    }
    const ssize_t n = ::write(fd_, &out, size);
    if (n == static_cast<ssize_t>(size)) {
      ++stats_.tx_frames;
      return SendStatus::Queued;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == ENOBUFS || errno == EAGAIN)) {
      // The interface queue is full (ENOBUFS is SocketCAN's usual answer): wait for room until the
      // deadline instead of spinning.
      const auto left = deadline - now();
      if (left.count() <= 0) continue;
      pollfd p{fd_, POLLOUT, 0};
      timespec ts{static_cast<time_t>(left.count() / 1'000'000'000), static_cast<long>(left.count() % 1'000'000'000)};
      ::ppoll(&p, 1, &ts, nullptr);
      if (now() > deadline) {
        ++stats_.tx_dropped;
        events_.push_back({BusEvent::Kind::TxDropped, state_, frame.id, now()});
        return SendStatus::QueueFull;
      }
      continue;
    }
    if (n < 0 && (errno == ENETDOWN || errno == ENODEV || errno == ENXIO)) {
      set_state(BusState::Down, now());
      events_.push_back({BusEvent::Kind::DeviceLost, state_, static_cast<std::uint32_t>(errno), now()});
      return SendStatus::Closed;
    }
    ++stats_.tx_dropped;
    return SendStatus::Invalid;
  }
}

void SocketCanTransport::handle_error_frame(const std::uint8_t* data, std::uint32_t id, Nanoseconds t) {
  ++stats_.error_frames;
  const ErrorFrameEffect e = interpret_error_frame(id, data);
  events_.push_back({BusEvent::Kind::ErrorFrame, state_, e.error_class, t});
  if (e.has_state) set_state(e.state, t);
  if (e.overflow) events_.push_back({BusEvent::Kind::RxOverflow, state_, data[1], t});
}

void SocketCanTransport::drain_socket() {
  for (;;) {
    canfd_frame in{};
    iovec iov{&in, sizeof in};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t))];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == ENETDOWN || errno == ENODEV) {
        set_state(BusState::Down, now());
        events_.push_back({BusEvent::Kind::DeviceLost, state_, static_cast<std::uint32_t>(errno), now()});
      }
      return;
    }
    Nanoseconds t = now();
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPNS) {
        timespec ts;
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        t = Nanoseconds{static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
      } else if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t dropped;
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        if (dropped != last_overflow_count_) {
          const std::uint32_t lost = dropped - last_overflow_count_;
          last_overflow_count_ = dropped;
          stats_.rx_dropped += lost;
          events_.push_back({BusEvent::Kind::RxOverflow, state_, lost, t});
        }
      }
    }
    if (n != static_cast<ssize_t>(CAN_MTU) && n != static_cast<ssize_t>(CANFD_MTU)) {
      ++stats_.malformed;
      continue;
    }
    if (in.can_id & CAN_ERR_FLAG) {
      handle_error_frame(in.data, in.can_id, t);
      continue;
    }
    TimedFrame f;
    f.timestamp = t;
    f.frame.id = in.can_id & ((in.can_id & CAN_EFF_FLAG) ? CAN_EFF_MASK : CAN_SFF_MASK);
    if (in.can_id & CAN_EFF_FLAG) f.frame.flags |= CanFrame::kExtendedId;
    if (in.can_id & CAN_RTR_FLAG) f.frame.flags |= CanFrame::kRemote;
    if (n == static_cast<ssize_t>(CANFD_MTU)) {
      f.frame.flags |= CanFrame::kFdFrame;
      if (in.flags & CANFD_BRS) f.frame.flags |= CanFrame::kBitRateSwitch;
    }
    f.frame.len = in.len > kFdMaxLength ? kFdMaxLength : in.len;
    std::memcpy(f.frame.data, in.data, f.frame.len);
    rx_.push_back(f);
    ++stats_.rx_frames;
  }
}

bool SocketCanTransport::receive(TimedFrame& out) {
  if (rx_.empty()) drain_socket();
  if (rx_.empty()) return false;
  out = rx_.front();
  rx_.pop_front();
  return true;
}

bool SocketCanTransport::poll_event(BusEvent& out) {
  drain_socket();
  if (events_.empty()) return false;
  out = events_.front();
  events_.pop_front();
  return true;
}

bool SocketCanTransport::wait(Nanoseconds timeout) {
  if (!rx_.empty() || !events_.empty()) return true;
  pollfd p{fd_, POLLIN, 0};
  timespec ts{static_cast<time_t>(timeout.count() / 1'000'000'000), static_cast<long>(timeout.count() % 1'000'000'000)};
  return ::ppoll(&p, 1, &ts, nullptr) > 0;
}

}  // namespace vesica::fp
