#pragma once
// A linear-radiance float RGB image, row-major, row 0 at the top. Knows nothing about files.
#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "render/math/color.h"

namespace thaw::render {

/// std::allocator that leaves elements made without arguments uninitialised (a vector's
/// resize/size constructor), so that a large image is not zeroed by one thread before the
/// render's threads write every pixel (a 2000x2000 image: 48 MB written twice, the first time
/// serially, ~4 % of S4's wall time). Elements made from a value are constructed as usual.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

class Image {
 public:
  using Pixels = std::vector<Rgb, UninitialisedAllocator<Rgb>>;
  /// Tag: pixels left unset, for a writer that sets every one before anything reads them.
  struct ForOverwrite {};

  Image() = default;
  /// Black.
  Image(int width, int height)
      : m_width(width), m_height(height), m_pixels(std::size_t(width) * height, Rgb{}) {}
  Image(int width, int height, ForOverwrite)
      : m_width(width), m_height(height), m_pixels(std::size_t(width) * height) {}

  int width() const { return m_width; }
  int height() const { return m_height; }
  Rgb& at(int x, int y) { return m_pixels[std::size_t(y) * m_width + x]; }
  const Rgb& at(int x, int y) const { return m_pixels[std::size_t(y) * m_width + x]; }
  const Pixels& pixels() const { return m_pixels; }

 private:
  int m_width = 0, m_height = 0;
  Pixels m_pixels;
};

}  // namespace thaw::render
