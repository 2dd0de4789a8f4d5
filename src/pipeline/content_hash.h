#pragma once
// Content fingerprints for deciding what is up to date: 64-bit FNV-1a over bytes (Fowler, Noll,
// Vo). Not cryptographic: it detects edits, it does not resist forgery.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace thaw::pipeline {

class ContentHash {
 public:
  ContentHash& add(std::string_view bytes) noexcept {
    for (unsigned char c : bytes) {
      m_state ^= c;
      m_state *= 0x100000001b3ULL;
    }
    // A separator so ("ab","c") and ("a","bc") differ.
    m_state ^= 0xff;
    m_state *= 0x100000001b3ULL;
    return *this;
  }
  ContentHash& add(double v);
  /// Adds a file's whole contents; a missing file hashes as the marker "<missing>".
  ContentHash& add_file(const std::filesystem::path& file);
  /// 16 lowercase hex digits.
  std::string hex() const;

 private:
  std::uint64_t m_state = 0xcbf29ce484222325ULL;
};

}  // namespace thaw::pipeline
