#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace vesica::fp::emulator {

/// NOR flash as a board's parameter memory: erased bytes read 0xFF, programming can only clear
/// bits, a write first erases the sectors it covers. Power can be cut after any number of byte
/// operations (erasing or programming one byte is one operation): the cut byte is left half done
/// and nothing after it happens, so a test can stop a save at every byte offset.
class FlashModel {
 public:
  static constexpr std::size_t kDefaultSize = 2048;
  static constexpr std::size_t kDefaultSectorSize = 256;

  explicit FlashModel(std::size_t size = kDefaultSize, std::size_t sector_size = kDefaultSectorSize);

  /// False (nothing read) when the range is outside the chip.
  bool Read(std::size_t offset, std::uint8_t* dst, std::size_t n) const;
  /// Erases the sectors covering [offset, offset + n), then programs the bytes. False when the
  /// range is outside the chip or the power went out on the way.
  bool Write(std::size_t offset, const std::uint8_t* src, std::size_t n);

  /// Power is lost after `operations` more byte operations (erase or program).
  void CutPowerAfter(std::size_t operations) { budget_ = operations; }
  void RestorePower() {
    budget_ = std::numeric_limits<std::size_t>::max();
    powered_ = true;
  }
  bool powered() const { return powered_; }
  /// Byte operations a Write of n bytes at offset costs (erase of whole sectors + program).
  std::size_t OperationsFor(std::size_t offset, std::size_t n) const;

  std::vector<std::uint8_t>& bytes() { return bytes_; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::size_t sector_size() const { return sector_size_; }

 private:
  bool Spend();  ///< one byte operation; false once the power is gone

  std::vector<std::uint8_t> bytes_;
  std::size_t sector_size_;
  std::size_t budget_ = std::numeric_limits<std::size_t>::max();
  bool powered_ = true;
};

}  // namespace vesica::fp::emulator
