#pragma once
// Content fingerprints for deciding what is up to date: 64-bit FNV-1a over bytes (Fowler, Noll,
// Vo; base/fnv_hash.h). Not cryptographic: it detects edits, it does not resist forgery.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "base/fnv_hash.h"

namespace thaw::pipeline {

class ContentHash {
 public:
  ContentHash& add(std::string_view bytes) noexcept {
    // A separator byte after each part so ("ab","c") and ("a","bc") differ.
    m_state = fnv1a_64("\xff", fnv1a_64(bytes, m_state));
    return *this;
  }
  ContentHash& add(double v);
  /// Adds a file's whole contents; a missing file hashes as the marker "<missing>".
  ContentHash& add_file(const std::filesystem::path& file);
  /// 16 lowercase hex digits.
  std::string hex() const;

 private:
  std::uint64_t m_state = kFnv1aOffset;
};

}  // namespace thaw::pipeline
