#include "app/calibrate/stored_calibration.h"

#include <fstream>
#include <iterator>

#include "app/calibrate/exit_codes.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::app::calibrate {

namespace param = fp::param;

std::string SlotName(int slot) { return slot == 0 ? "A" : slot == 1 ? "B" : "-"; }

CalibrationValues ValuesOf(const fp::ParameterStore& p) {
  CalibrationValues v;
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    auto& o = v.joint[j];
    o.direction = static_cast<std::int32_t>(p.u32(param::kEncoderDirection + jj)) < 0 ? -1 : 1;
    o.position_offset = p.f32(param::kPositionOffset + jj);
    o.current_offset_A = p.f32(param::kCurrentOffset + jj);
    o.joint_min = p.f32(param::kJointMin + jj);
    o.joint_max = p.f32(param::kJointMax + jj);
    o.index_position = p.f32(param::kIndexPosition + jj);
    o.coulomb = p.f32(param::kCoulombFriction + jj);
    o.viscous = p.f32(param::kViscousFriction + jj);
    o.torque_constant_correction = p.f32(param::kTorqueConstantCorrection + jj);
  }
  v.gravity_sin = p.f32(param::kGravitySin);
  v.gravity_cos = p.f32(param::kGravityCos);
  v.roll_sensor_offset_rad = p.f32(param::kRollSensorOffset);
  v.jaw_closed_counts = p.u32(param::kJawClosedCounts);
  v.jaw_open_counts = p.u32(param::kJawOpenCounts);
  v.pedal_released_counts = p.u32(param::kPedalReleasedCounts);
  v.pedal_pressed_counts = p.u32(param::kPedalPressedCounts);
  return v;
}

void Encode(StoredImage& image) {
  std::uint8_t params[fp::ParameterStore::kImageSize];
  const std::size_t n = image.params.serialize(params, sizeof params, image.layout);
  image.bytes.assign(fp::slot::size_of_layout(image.layout), 0);
  fp::encode_slot(image.header, params, n, image.bytes.data(), image.bytes.size());
}

namespace {
// Whether the node has parameter i (a node below protocol 1.3 has no layout-2 parameters).
bool NodeHas(const device::calibration::CalibrationLink& link, std::size_t i) {
  return fp::parameter_layout(i) == 1 || link.negotiated_minor() == 0xFF ||
         link.negotiated_minor() >= fp::kLayout2Minor;
}
}  // namespace

StoredImage ReadStoredCalibration(device::calibration::CalibrationLink& link,
                                  const device::calibration::NodeInfo& info) {
  StoredImage image;
  image.layout = info.stored_layout == 1 ? 1 : fp::slot::kLayoutVersion;
  for (std::size_t i = 0; i < fp::kParameterCount; ++i) {
    const fp::ParameterSpec& spec = fp::kParameterSpecs[i];
    if (!spec.persistent || !NodeHas(link, i)) continue;  // the image holds defaults there, as the node's does
    image.params.set_internal(spec.index, link.Read(spec.index).raw_value);
  }
  image.header.generation =
      info.active_slot >= 0 ? info.slot_generation[static_cast<std::size_t>(info.active_slot)] : 0;
  image.header.date_s = info.calibration_date_s;
  image.header.tool_version = info.calibration_tool_version;
  image.header.serial = info.identity.serial;
  Encode(image);
  return image;
}

bool WriteImageFile(const std::string& path, const StoredImage& image, std::string* error) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(image.bytes.data()), static_cast<std::streamsize>(image.bytes.size()));
  out.close();
  if (!out) {
    *error = "cannot write " + path;
    return false;
  }
  return true;
}

ImageFileCheck ReadImageFile(const std::string& path) {
  ImageFileCheck c;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    c.exit_code = kExitIo;
    c.message = "cannot read " + path;
    return c;
  }
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool magic = bytes.size() >= 4 && fp::slot_detail::get_u32(bytes.data()) == fp::slot::kMagic;
  if (!magic || (bytes.size() != fp::slot::kSize && bytes.size() != fp::slot::kLayout1Size)) {
    c.exit_code = kExitStorage;
    c.message = path + " is not a Vesica calibration image (" +
                (magic ? std::to_string(bytes.size()) + " bytes, a slot has " + std::to_string(fp::slot::kSize) +
                             " (layout 2) or " + std::to_string(fp::slot::kLayout1Size) + " (layout 1)"
                       : std::string("no VCS1 header")) +
                "); nothing was written";
    return c;
  }
  const fp::SlotCheck check = fp::check_slot(bytes.data(), bytes.size());
  if (check.status != fp::StorageResult::Ok) {
    c.exit_code = kExitStorage;
    c.message = path + ": " + device::calibration::NodeInfo::SlotText(check.status) + "; nothing was written";
    return c;
  }
  if (check.size != bytes.size() ||
      c.image.params.deserialize(bytes.data() + fp::slot::kHeaderSize, bytes.size() - fp::slot::kHeaderSize - 4,
                                 &c.image.layout) != fp::StorageResult::Ok) {
    c.exit_code = kExitStorage;
    c.message = path + ": the parameter image inside is not valid; nothing was written";
    return c;
  }
  c.image.header = check.header;
  c.image.bytes = std::move(bytes);
  return c;
}

void WriteToNode(device::calibration::CalibrationLink& link, const StoredImage& image) {
  for (std::size_t i = 0; i < fp::kParameterCount; ++i) {
    const fp::ParameterSpec& spec = fp::kParameterSpecs[i];
    if (!spec.persistent || spec.access != fp::ParameterAccess::ReadWrite || spec.index == param::kNodeId ||
        !NodeHas(link, i))
      continue;
    const std::uint32_t raw = image.params.u32(spec.index);
    switch (spec.type) {
      case fp::ParameterType::F32:
        link.WriteF32(spec.index, fp::bits_f32(raw));
        break;
      case fp::ParameterType::I32:
        link.WriteI32(spec.index, static_cast<std::int32_t>(raw));
        break;
      default:
        link.WriteU32(spec.index, raw);
        break;
    }
  }
  link.WriteU32(param::kCalibrationDate_s, image.header.date_s);
  link.WriteU32(param::kCalibrationToolVersion, image.header.tool_version);
  link.Save();
}

}  // namespace vesica::app::calibrate
