// Codec: every message round-trips; the decoder rejects bad frames with counted, named errors.
#include "firmware_protocol/codec/codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vesica::fp {
namespace {

// One representative of every message kind, with values off the grid's zero.
std::vector<Message> sample_messages() {
  return {
      Nmt{NmtCommand::EnterPreOperational, 5},
      EStop{3},
      Sync{200},
      Emergency{2, FaultCode::OverCurrent, 1, 7, -1234},
      JointState{1, 17, NodeState::Operational, true, Limiter::Torque, {0.5f, -1.25f, 0.1234f}},
      CurrentCommand{2, 255, CommandMode::JointTorque, {-1.5f, 2.25f, 29.999f}},
      AuxState{127, 9, true, false, true, -3.0f, 1.2f, 24.37f},
      Control{4, 33, ControlCommand::FaultReset},
      CurrentState{1, 1, -12, {0.001f, -0.5f, 10.0f}},
      CalibrationCommand{1, CalibrationProcedure::FindIndex, 0b101, 0.75f},
      CalibrationProgress{1, CalibrationProcedure::CurrentOffset, CalibrationStatus::Running, 42, 2, -98765},
      Identity{9, 1, 0, 3, 2, 0xDEADBEEF},
      Hello{9, 1, 2},
      ParameterRequest{1, ParameterOp::Write, ParameterType::F32, 0x0011, 0x40490FDB},
      ParameterResponse{1, ParameterOp::Read, true, ParameterType::U32, 0x0102, 0x06020000},
      Heartbeat{6, NodeState::Fault, false, FaultCode::CommandWatchdog},
  };
}

void expect_near(const JointArray& a, const JointArray& b, float tol) {
  for (int j = 0; j < kJointCount; ++j) EXPECT_NEAR(a[j], b[j], tol) << "joint " << j;
}

// Field-by-field comparison with the quantisation step as tolerance.
void expect_same(const Message& a, const Message& b) {
  ASSERT_EQ(a.index(), b.index());
  EXPECT_EQ(node_of(a), node_of(b));
  if (auto* x = std::get_if<JointState>(&a)) {
    auto& y = std::get<JointState>(b);
    EXPECT_EQ(x->counter, y.counter);
    EXPECT_EQ(x->state, y.state);
    EXPECT_EQ(x->enabled, y.enabled);
    EXPECT_EQ(x->limiter, y.limiter);
    EXPECT_NEAR(x->position[0], y.position[0], 0.5e-4);
    EXPECT_NEAR(x->position[1], y.position[1], 0.5e-4);
    EXPECT_NEAR(x->position[2], y.position[2], 0.5e-5);
  } else if (auto* c = std::get_if<CurrentCommand>(&a)) {
    auto& d = std::get<CurrentCommand>(b);
    EXPECT_EQ(c->counter, d.counter);
    EXPECT_EQ(c->mode, d.mode);
    expect_near(c->value, d.value, 0.5e-3f);
  } else if (auto* s = std::get_if<AuxState>(&a)) {
    auto& t = std::get<AuxState>(b);
    EXPECT_EQ(s->counter, t.counter);
    EXPECT_EQ(s->pedal, t.pedal);
    EXPECT_EQ(s->estop_input, t.estop_input);
    EXPECT_EQ(s->handle_button, t.handle_button);
    EXPECT_NEAR(s->roll_rad, t.roll_rad, 0.5e-4);
    EXPECT_NEAR(s->jaw_rad, t.jaw_rad, 0.5e-4);
    EXPECT_NEAR(s->bus_V, t.bus_V, 0.5e-2);
  } else if (auto* u = std::get_if<CurrentState>(&a)) {
    auto& v = std::get<CurrentState>(b);
    EXPECT_EQ(u->counter, v.counter);
    EXPECT_EQ(u->board_temperature_degC, v.board_temperature_degC);
    expect_near(u->current, v.current, 0.5e-3f);
  } else if (auto* e = std::get_if<Emergency>(&a)) {
    auto& g = std::get<Emergency>(b);
    EXPECT_EQ(e->fault, g.fault);
    EXPECT_EQ(e->joint, g.joint);
    EXPECT_EQ(e->history_count, g.history_count);
    EXPECT_EQ(e->detail, g.detail);
  } else if (auto* k = std::get_if<CalibrationCommand>(&a)) {
    auto& l = std::get<CalibrationCommand>(b);
    EXPECT_EQ(k->procedure, l.procedure);
    EXPECT_EQ(k->joint_mask, l.joint_mask);
    EXPECT_NEAR(k->max_current, l.max_current, 0.5e-3);
  } else if (auto* p = std::get_if<CalibrationProgress>(&a)) {
    auto& q = std::get<CalibrationProgress>(b);
    EXPECT_EQ(p->procedure, q.procedure);
    EXPECT_EQ(p->status, q.status);
    EXPECT_EQ(p->percent, q.percent);
    EXPECT_EQ(p->joint, q.joint);
    EXPECT_EQ(p->result, q.result);
  } else if (auto* i = std::get_if<Identity>(&a)) {
    auto& j = std::get<Identity>(b);
    EXPECT_EQ(i->protocol_major, j.protocol_major);
    EXPECT_EQ(i->min_minor, j.min_minor);
    EXPECT_EQ(i->max_minor, j.max_minor);
    EXPECT_EQ(i->negotiated_minor, j.negotiated_minor);
    EXPECT_EQ(i->serial, j.serial);
  } else if (auto* r = std::get_if<ParameterRequest>(&a)) {
    auto& s2 = std::get<ParameterRequest>(b);
    EXPECT_EQ(r->op, s2.op);
    EXPECT_EQ(r->type, s2.type);
    EXPECT_EQ(r->index, s2.index);
    EXPECT_EQ(r->raw_value, s2.raw_value);
  } else if (auto* pr = std::get_if<ParameterResponse>(&a)) {
    auto& ps = std::get<ParameterResponse>(b);
    EXPECT_EQ(pr->op, ps.op);
    EXPECT_EQ(pr->aborted, ps.aborted);
    EXPECT_EQ(pr->type, ps.type);
    EXPECT_EQ(pr->index, ps.index);
    EXPECT_EQ(pr->raw_value, ps.raw_value);
  } else if (auto* h = std::get_if<Heartbeat>(&a)) {
    auto& hb = std::get<Heartbeat>(b);
    EXPECT_EQ(h->state, hb.state);
    EXPECT_EQ(h->enabled, hb.enabled);
    EXPECT_EQ(h->latched_fault, hb.latched_fault);
  } else if (auto* n = std::get_if<Nmt>(&a)) {
    EXPECT_EQ(n->command, std::get<Nmt>(b).command);
    EXPECT_EQ(n->target_node, std::get<Nmt>(b).target_node);
  } else if (auto* es = std::get_if<EStop>(&a)) {
    EXPECT_EQ(es->source_node, std::get<EStop>(b).source_node);
  } else if (auto* sy = std::get_if<Sync>(&a)) {
    EXPECT_EQ(sy->counter, std::get<Sync>(b).counter);
  } else if (auto* co = std::get_if<Control>(&a)) {
    EXPECT_EQ(co->command, std::get<Control>(b).command);
    EXPECT_EQ(co->counter, std::get<Control>(b).counter);
  } else if (auto* he = std::get_if<Hello>(&a)) {
    EXPECT_EQ(he->protocol_major, std::get<Hello>(b).protocol_major);
    EXPECT_EQ(he->protocol_minor, std::get<Hello>(b).protocol_minor);
  }
}

TEST(CodecTest, SamplesCoverEveryMessageKind) {
  std::vector<bool> seen(kMessageKindCount, false);
  for (const Message& m : sample_messages()) seen[m.index()] = true;
  for (std::size_t k = 0; k < kMessageKindCount; ++k) EXPECT_TRUE(seen[k]) << kMessageSpecs[k].name;
}

TEST(CodecTest, EveryMessageRoundTrips) {
  for (const Message& m : sample_messages()) {
    SCOPED_TRACE(spec_of(kind_of(m)).name);
    CanFrame f;
    ASSERT_EQ(encode(m, f), EncodeError::None);
    EXPECT_EQ(f.id, can_id(kind_of(m), node_of(m)));
    EXPECT_EQ(f.len, spec_of(kind_of(m)).length);
    Message back;
    ASSERT_EQ(decode(f, back), DecodeError::None);
    expect_same(m, back);
    // Bytes are a fixed point: re-encoding the decoded message gives the same frame.
    CanFrame again;
    ASSERT_EQ(encode(back, again), EncodeError::None);
    EXPECT_EQ(f, again);
  }
}

TEST(CodecTest, JointStateBytesFollowTheDocumentedLayout) {
  // Independent hand-packed reference: counter 0x11, state 2 | enabled<<3 | limiter 2<<4,
  // yaw 0.5 rad = 5000 = 0x1388, pitch -1.25 rad = -12500 = 0xCF2C, insertion 0.1234 m = 12340 = 0x3034.
  CanFrame f;
  ASSERT_EQ(encode(JointState{1, 0x11, NodeState::Operational, true, Limiter::Torque, {0.5f, -1.25f, 0.1234f}}, f),
            EncodeError::None);
  EXPECT_EQ(f.id, 0x181u);
  const std::uint8_t expected[8] = {0x11, 0x2A, 0x88, 0x13, 0x2C, 0xCF, 0x34, 0x30};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(f.data[i], expected[i]) << "byte " << i;
}

TEST(CodecTest, EmergencyUsesCanopenErrorCodes) {
  CanFrame f;
  ASSERT_EQ(encode(Emergency{3, FaultCode::CommandWatchdog, 0xFF, 1, 4}, f), EncodeError::None);
  EXPECT_EQ(f.id, 0x083u);
  EXPECT_EQ(f.data[0] | (f.data[1] << 8), 0x8130);  // CiA 301 heartbeat/life-guard error
  EXPECT_EQ(f.data[2], 0x11);                        // error register: generic | communication
}

TEST(CodecTest, HeartbeatByteZeroIsTheCanopenState) {
  CanFrame f;
  ASSERT_EQ(encode(Heartbeat{5, NodeState::Operational, true, FaultCode::None}, f), EncodeError::None);
  EXPECT_EQ(f.id, 0x705u);
  EXPECT_EQ(f.data[0], 0x05);
  ASSERT_EQ(encode(Heartbeat{5, NodeState::PreOperational, false, FaultCode::None}, f), EncodeError::None);
  EXPECT_EQ(f.data[0], 0x7F);
}

TEST(CodecTest, WrongLengthIsRejectedForEveryMessage) {
  for (const Message& m : sample_messages()) {
    CanFrame f;
    ASSERT_EQ(encode(m, f), EncodeError::None);
    for (std::uint8_t len : {std::uint8_t(f.len - 1), std::uint8_t(f.len + 1)}) {
      if (len > 8) continue;
      CanFrame g = f;
      g.len = len;
      Message out;
      EXPECT_EQ(decode(g, out), DecodeError::WrongLength) << spec_of(kind_of(m)).name << " len " << int(len);
    }
  }
}

TEST(CodecTest, UnknownIdsAreRejected) {
  Message out;
  CanFrame f;
  f.len = 8;
  for (std::uint32_t id : {0x002u, 0x07Fu, 0x100u, 0x17Fu, 0x180u, 0x780u, 0x7FFu, 0x800u}) {
    f.id = id;
    EXPECT_EQ(decode(f, out), DecodeError::UnknownId) << std::hex << id;
  }
  f.id = 0x181;
  f.flags = CanFrame::kExtendedId;
  EXPECT_EQ(decode(f, out), DecodeError::UnknownId);
  f.flags = CanFrame::kRemote;
  EXPECT_EQ(decode(f, out), DecodeError::RemoteFrame);
}

TEST(CodecTest, OutOfRangeFieldsAreRejected) {
  Message out;
  CanFrame f;
  ASSERT_EQ(encode(JointState{1, 0, NodeState::Boot, false, Limiter::None, {0, 0, 0}}, f), EncodeError::None);
  CanFrame g = f;
  g.data[1] = 0x05;  // state 5 does not exist
  EXPECT_EQ(decode(g, out), DecodeError::OutOfRange);
  g = f;
  g.data[1] = 0x70;  // limiter 7 does not exist
  EXPECT_EQ(decode(g, out), DecodeError::OutOfRange);
  g = f;
  g.data[2] = 0xFF; g.data[3] = 0x7F;  // yaw 3.2767 rad > pi
  EXPECT_EQ(decode(g, out), DecodeError::OutOfRange);

  ASSERT_EQ(encode(CurrentCommand{1, 0, CommandMode::MotorCurrent, {0, 0, 0}}, f), EncodeError::None);
  g = f;
  g.data[1] = 2;  // unknown mode
  EXPECT_EQ(decode(g, out), DecodeError::OutOfRange);
  g = f;
  g.data[2] = 0x31; g.data[3] = 0x75;  // 30001 mA > 30 A
  EXPECT_EQ(decode(g, out), DecodeError::OutOfRange);

  CanFrame nmt;
  nmt.id = 0;
  nmt.len = 2;
  nmt.data[0] = 0x03;  // not an NMT command
  EXPECT_EQ(decode(nmt, out), DecodeError::OutOfRange);
  CanFrame estop;
  estop.id = 1;
  estop.len = 2;
  estop.data[0] = 0x00;  // wrong magic
  EXPECT_EQ(decode(estop, out), DecodeError::OutOfRange);
}

TEST(CodecTest, InconsistentFieldsAreRejected) {
  Message out;
  CanFrame f;
  ASSERT_EQ(encode(Heartbeat{1, NodeState::Operational, true, FaultCode::None}, f), EncodeError::None);
  f.data[0] = 0x04;  // says stopped while byte 1 says operational
  EXPECT_EQ(decode(f, out), DecodeError::Inconsistent);
  ASSERT_EQ(encode(Emergency{1, FaultCode::OverCurrent, 0, 1, 0}, f), EncodeError::None);
  f.data[0] = 0x00;  // error code no longer matches the fault byte
  EXPECT_EQ(decode(f, out), DecodeError::Inconsistent);
}

TEST(CodecTest, EncoderRefusesOutOfRangeValuesAndBadNodes) {
  CanFrame f;
  EXPECT_EQ(encode(CurrentCommand{1, 0, CommandMode::MotorCurrent, {31.0f, 0, 0}}, f), EncodeError::OutOfRange);
  EXPECT_EQ(encode(CurrentCommand{1, 0, CommandMode::MotorCurrent, {NAN, 0, 0}}, f), EncodeError::OutOfRange);
  EXPECT_EQ(encode(JointState{1, 0, NodeState::Boot, false, Limiter::None, {4.0f, 0, 0}}, f), EncodeError::OutOfRange);
  EXPECT_EQ(encode(CurrentCommand{0, 0, CommandMode::MotorCurrent, {0, 0, 0}}, f), EncodeError::BadNode);
  EXPECT_EQ(encode(CurrentCommand{128, 0, CommandMode::MotorCurrent, {0, 0, 0}}, f), EncodeError::BadNode);
  EXPECT_STREQ(to_string(EncodeError::OutOfRange), "out_of_range");
}

TEST(CodecTest, SequenceTrackerRejectsRepeatsAndStaleCountersAndCountsGaps) {
  SequenceTracker t;
  EXPECT_EQ(t.check(250), DecodeError::None);
  EXPECT_EQ(t.check(251), DecodeError::None);
  EXPECT_EQ(t.check(251), DecodeError::BadCounter);  // repeat
  EXPECT_EQ(t.check(2), DecodeError::None);          // wraps 251 -> 2: 6 lost
  EXPECT_EQ(t.lost_frames(), 6u);
  EXPECT_EQ(t.check(200), DecodeError::BadCounter);  // 198 back: stale
  EXPECT_EQ(t.check(3), DecodeError::None);
}

TEST(CodecTest, DecodeErrorsAreCountedByName) {
  DecodeErrorCounters c;
  Message out;
  CanFrame f;
  f.id = 0x123;
  c.add(decode(f, out));
  f.id = 0x181;
  f.len = 3;
  c.add(decode(f, out));
  c.add(decode(f, out));
  EXPECT_EQ(c[DecodeError::UnknownId], 1u);
  EXPECT_EQ(c[DecodeError::WrongLength], 2u);
  EXPECT_EQ(c.total(), 3u);
  EXPECT_STREQ(to_string(DecodeError::WrongLength), "wrong_length");
  EXPECT_STREQ(to_string(DecodeError::BadCounter), "bad_counter");
}

TEST(CodecTest, EveryStandardIdEitherDecodesOrIsCountedNeverCrashes) {
  // Exhaustive over ids and lengths with a fixed payload pattern: each result is a named error or success.
  Message out;
  for (std::uint32_t id = 0; id < 0x800; ++id) {
    for (std::uint8_t len = 0; len <= 8; ++len) {
      CanFrame f;
      f.id = id;
      f.len = len;
      for (int i = 0; i < 8; ++i) f.data[i] = static_cast<std::uint8_t>(id * 31 + i * 7);
      const DecodeError e = decode(f, out);
      EXPECT_NE(std::string(to_string(e)), "?");
    }
  }
}

}  // namespace
}  // namespace vesica::fp
