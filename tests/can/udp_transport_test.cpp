// CAN over UDP: cannelloni packet bytes, loopback exchange, malformed packets counted, lost packets seen.
#include "firmware_protocol/transport/udp_transport.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "firmware_protocol/transport/cannelloni_packet.h"

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

TEST(CannelloniPacketTest, BytesMatchTheDocumentedFormat) {
  CanFrame f[2];
  f[0].id = 0x181;
  f[0].len = 2;
  f[0].data[0] = 0xAA;
  f[0].data[1] = 0xBB;
  f[1].id = 0x1234567;
  f[1].flags = CanFrame::kExtendedId | CanFrame::kFdFrame | CanFrame::kBitRateSwitch;
  f[1].len = 12;
  std::uint8_t buf[64];
  const std::size_t n = write_cannelloni_packet(f, 2, 7, buf, sizeof buf);
  // header 5 + (4+1+2) + (4+1+1+12)
  ASSERT_EQ(n, 5u + 7u + 18u);
  const std::uint8_t head[] = {2, 0, 7, 0, 2, 0x00, 0x00, 0x01, 0x81, 0x02, 0xAA, 0xBB, 0x81, 0x23, 0x45, 0x67, 0x8C, 0x01};
  for (std::size_t i = 0; i < sizeof head; ++i) EXPECT_EQ(buf[i], head[i]) << "byte " << i;
  std::uint8_t seq = 0;
  std::vector<CanFrame> back;
  EXPECT_EQ(parse_cannelloni_packet(buf, n, seq, [&](const CanFrame& x) { back.push_back(x); }), CannelloniError::None);
  EXPECT_EQ(seq, 7);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0], f[0]);
  EXPECT_EQ(back[1], f[1]);
}

TEST(CannelloniPacketTest, MalformedPacketsAreNamed) {
  std::uint8_t seq;
  auto ignore = [](const CanFrame&) {};
  const std::uint8_t short_header[] = {2, 0, 1};
  EXPECT_EQ(parse_cannelloni_packet(short_header, 3, seq, ignore), CannelloniError::Truncated);
  const std::uint8_t v1[] = {1, 0, 0, 0, 0};
  EXPECT_EQ(parse_cannelloni_packet(v1, 5, seq, ignore), CannelloniError::BadVersion);
  const std::uint8_t ack[] = {2, 1, 0, 0, 0};
  EXPECT_EQ(parse_cannelloni_packet(ack, 5, seq, ignore), CannelloniError::BadOpCode);
  const std::uint8_t too_long[] = {2, 0, 0, 0, 1, 0, 0, 1, 0x81, 9, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(parse_cannelloni_packet(too_long, sizeof too_long, seq, ignore), CannelloniError::BadLength);
  const std::uint8_t missing_data[] = {2, 0, 0, 0, 1, 0, 0, 1, 0x81, 8, 1, 2};
  EXPECT_EQ(parse_cannelloni_packet(missing_data, sizeof missing_data, seq, ignore), CannelloniError::Truncated);
  const std::uint8_t trailing[] = {2, 0, 0, 0, 0, 0xFF};
  EXPECT_EQ(parse_cannelloni_packet(trailing, sizeof trailing, seq, ignore), CannelloniError::TrailingBytes);
}

struct UdpPair {
  std::unique_ptr<UdpTransport> a, b;
  UdpPair() {
    std::string err;
    a = UdpTransport::open({"127.0.0.1", 0, "127.0.0.1", 1}, err);
    b = UdpTransport::open({"127.0.0.1", 0, "127.0.0.1", 1}, err);
    if (a && b) {
      a->set_remote_port(b->local_port());
      b->set_remote_port(a->local_port());
    }
  }
};

bool receive_within(Transport& t, TimedFrame& out, Nanoseconds timeout) {
  const auto until = t.now() + timeout;
  while (t.now() < until) {
    if (t.receive(out)) return true;
    t.wait(1ms);
  }
  return t.receive(out);
}

TEST(UdpTransportTest, FramesCrossLoopbackBothWaysWithTimestamps) {
  UdpPair p;
  ASSERT_TRUE(p.a && p.b);
  CanFrame f;
  f.id = 0x201;
  f.len = 8;
  for (int i = 0; i < 8; ++i) f.data[i] = static_cast<std::uint8_t>(i * 17);
  const auto before = p.b->now();
  ASSERT_EQ(p.a->send(f, p.a->now() + 10ms), SendStatus::Queued);
  TimedFrame rx;
  ASSERT_TRUE(receive_within(*p.b, rx, 1s));
  EXPECT_EQ(rx.frame, f);
  EXPECT_GE(rx.timestamp, before);
  f.id = 0x181;
  ASSERT_EQ(p.b->send(f, p.b->now() + 10ms), SendStatus::Queued);
  ASSERT_TRUE(receive_within(*p.a, rx, 1s));
  EXPECT_EQ(rx.frame.id, 0x181u);
}

// A plain socket bound on loopback that plays the transport's peer (or a stranger) byte by byte.
struct RawPeer {
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  std::uint16_t port = 0;
  RawPeer() {
    sockaddr_in local{};
    local.sin_family = AF_INET;
    inet_pton(AF_INET, "127.0.0.1", &local.sin_addr);
    ::bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local);
    socklen_t len = sizeof local;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len);
    port = ntohs(local.sin_port);
  }
  ~RawPeer() { ::close(fd); }
  void SendTo(std::uint16_t to_port, const std::uint8_t* bytes, std::size_t n) const {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(to_port);
    inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
    ::sendto(fd, bytes, n, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  void SendFrame(std::uint16_t to_port, const CanFrame& f, std::uint8_t seq) const {
    std::uint8_t buf[32];
    const std::size_t n = write_cannelloni_packet(&f, 1, seq, buf, sizeof buf);
    SendTo(to_port, buf, n);
  }
};

TEST(UdpTransportTest, MalformedDatagramIsCountedAndSkipped) {
  UdpPair p;
  ASSERT_TRUE(p.a && p.b);
  RawPeer peer;
  p.b->set_remote_port(peer.port);
  const std::uint8_t junk[] = {0x42, 0x00, 0x01};
  peer.SendTo(p.b->local_port(), junk, sizeof junk);
  CanFrame f;
  f.id = 0x700 + 1;
  f.len = 3;
  peer.SendFrame(p.b->local_port(), f, 0);
  TimedFrame rx;
  ASSERT_TRUE(receive_within(*p.b, rx, 1s));
  EXPECT_EQ(rx.frame.id, 0x701u);
  EXPECT_EQ(p.b->stats().malformed, 1u);
}

TEST(UdpTransportTest, SequenceGapIsReportedAsLostFrames) {
  UdpPair p;
  ASSERT_TRUE(p.a && p.b);
  RawPeer peer;
  p.b->set_remote_port(peer.port);
  // Hand-made packets with seq 10 then 13: two datagrams lost in between.
  CanFrame f;
  f.id = 0x181;
  f.len = 1;
  peer.SendFrame(p.b->local_port(), f, 10);
  peer.SendFrame(p.b->local_port(), f, 13);
  TimedFrame rx;
  ASSERT_TRUE(receive_within(*p.b, rx, 1s));
  ASSERT_TRUE(receive_within(*p.b, rx, 1s));
  BusEvent ev;
  ASSERT_TRUE(p.b->poll_event(ev));
  EXPECT_EQ(ev.kind, BusEvent::Kind::RxOverflow);
  EXPECT_EQ(ev.detail, 2u);
  EXPECT_EQ(p.b->stats().rx_dropped, 2u);
}

// Anyone on the host can send to the bridge's port: a stray tool, a second emulator, a spoofer.
// Only the configured peer's datagrams become frames; the others are counted and dropped, and do
// not disturb the peer's sequence tracking.
TEST(UdpTransportTest, DatagramsFromOtherThanTheConfiguredPeerAreDroppedAndCounted) {
  UdpPair p;
  ASSERT_TRUE(p.a && p.b);
  RawPeer stranger;
  CanFrame injected;
  injected.id = 0x201;  // a torque command for node 1
  injected.len = 8;
  injected.data[1] = 0;
  stranger.SendFrame(p.b->local_port(), injected, 0);
  stranger.SendFrame(p.b->local_port(), injected, 1);
  // The same address but another port is a stranger too: a's peer is b, not this socket.
  CanFrame genuine;
  genuine.id = 0x181;
  genuine.len = 1;
  genuine.data[0] = 0x5A;
  ASSERT_EQ(p.a->send(genuine, p.a->now() + 10ms), SendStatus::Queued);
  TimedFrame rx;
  ASSERT_TRUE(receive_within(*p.b, rx, 1s));
  EXPECT_EQ(rx.frame, genuine);
  EXPECT_FALSE(p.b->receive(rx)) << "a stranger's frame got through, id " << std::hex << rx.frame.id;
  EXPECT_EQ(p.b->stats().foreign, 2u);
  EXPECT_EQ(p.b->stats().rx_frames, 1u);
  EXPECT_EQ(p.b->stats().rx_dropped, 0u);
  BusEvent ev;
  EXPECT_FALSE(p.b->poll_event(ev));
}

TEST(UdpTransportTest, BadAddressIsANamedErrorNotACrash) {
  std::string err;
  EXPECT_EQ(UdpTransport::open({"not-an-ip", 0, "127.0.0.1", 1}, err), nullptr);
  EXPECT_NE(err.find("bad local address"), std::string::npos);
}

}  // namespace
}  // namespace vesica::fp
