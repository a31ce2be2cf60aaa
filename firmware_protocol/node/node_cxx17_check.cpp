// Compiles the reference node template as the firmware would: C++17, no exceptions, no RTTI
// (flags of vesica_fp_codec). A board type with the NodeHardware members is enough; this one
// exists only so the template is instantiated in this build, it is not used at run time.
#include "firmware_protocol/node/node.h"

#if __cplusplus > 201703L
#error "node_cxx17_check.cpp must be compiled as C++17 (the firmware's dialect)"
#endif

namespace vesica::fp {
namespace cxx17_check {

struct Cxx17CheckBoard {
  HardwareSample sense() { return {}; }
  void apply_currents(const JointArray&) {}
  bool storage_read(std::size_t, std::uint8_t*, std::size_t) { return false; }
  bool storage_write(std::size_t, const std::uint8_t*, std::size_t) { return false; }
};

}  // namespace cxx17_check

template class Node<cxx17_check::Cxx17CheckBoard>;

}  // namespace vesica::fp
