#include "firmware_protocol/emulator/flash_model.h"

namespace vesica::fp::emulator {

FlashModel::FlashModel(std::size_t size, std::size_t sector_size)
    : bytes_(size, 0xFF), sector_size_(sector_size > 0 ? sector_size : 1) {}

bool FlashModel::Read(std::size_t offset, std::uint8_t* dst, std::size_t n) const {
  if (offset > bytes_.size() || n > bytes_.size() - offset) return false;
  for (std::size_t i = 0; i < n; ++i) dst[i] = bytes_[offset + i];
  return true;
}

std::size_t FlashModel::OperationsFor(std::size_t offset, std::size_t n) const {
  if (n == 0) return 0;
  const std::size_t first = offset / sector_size_;
  const std::size_t last = (offset + n - 1) / sector_size_;
  return (last - first + 1) * sector_size_ + n;
}

bool FlashModel::Spend() {
  if (!powered_) return false;
  if (budget_ == 0) {
    powered_ = false;
    return false;
  }
  if (budget_ != std::numeric_limits<std::size_t>::max()) --budget_;
  return true;
}

bool FlashModel::Write(std::size_t offset, const std::uint8_t* src, std::size_t n) {
  if (offset > bytes_.size() || n > bytes_.size() - offset) return false;
  if (n == 0) return powered_;
  const std::size_t first = offset / sector_size_ * sector_size_;
  const std::size_t end = ((offset + n - 1) / sector_size_ + 1) * sector_size_;
  for (std::size_t i = first; i < end && i < bytes_.size(); ++i) {
    if (!Spend()) {
      bytes_[i] |= 0xF0;  // an erase cut short sets only some bits
      return false;
    }
    bytes_[i] = 0xFF;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!Spend()) {
      bytes_[offset + i] &= static_cast<std::uint8_t>(src[i] | 0x0F);  // programming cut short
      return false;
    }
    bytes_[offset + i] &= src[i];  // programming only clears bits
  }
  return true;
}

}  // namespace vesica::fp::emulator
