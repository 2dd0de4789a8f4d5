#pragma once
// A VTK texture whose mipmap levels are made on the CPU, where the texture is built (off the GUI
// thread: scene_props.h), and uploaded with its image, instead of by OpenGL's glGenerateMipmap.
// With Mesa's software OpenGL (llvmpipe) that call compiles a blit shader with LLVM on the GUI
// thread in every process (Mesa's on-disk shader cache does not keep it): 40-55 ms of the GUI
// thread's CPU in the 3D view's start-up (docs/benchmarks.md, "thaw gui"). The levels are the
// image's successive 2x2 box-filter halvings, as glGenerateMipmap's are. Knows nothing of thaw.
#include <vtkOpenGLTexture.h>

#include <cstddef>
#include <vector>

class vtkImageData;

namespace thaw::gui {

/// One mipmap level: width x height pixels of `components` unsigned bytes, rows bottom-up as
/// OpenGL and vtkImageData store them.
struct MipLevel {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;
};

/// The levels below `base` (components bytes per pixel, power-of-two sides): each the previous
/// one halved by averaging 2x2 pixels (rounded to nearest), down to 1x1; a side already 1 stays
/// 1 (two pixels averaged). Empty for a 1x1 base.
std::vector<MipLevel> mip_levels(const MipLevel& base, int components);

class MipmappedTexture : public vtkOpenGLTexture {
 public:
  static MipmappedTexture* New();
  vtkTypeMacro(MipmappedTexture, vtkOpenGLTexture);
  /// Takes `image` (unsigned char scalars, power-of-two sides) as the input and makes its levels
  /// now. The levels are used while Mipmap is on (trilinear sampling), else the image alone.
  void set_image(vtkImageData* image);
  /// The levels below the image (tests).
  const std::vector<MipLevel>& levels() const { return m_levels; }
  /// vtkOpenGLTexture's, with the levels uploaded after it (re)loads the image with Mipmap on.
  void Load(vtkRenderer* renderer) override;

 protected:
  MipmappedTexture() = default;

 private:
  void upload_levels();
  std::vector<MipLevel> m_levels;
  int m_components = 0;
};

}  // namespace thaw::gui
