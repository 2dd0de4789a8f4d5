#include "src/gui/mipmapped_texture.h"

#include <vtkImageData.h>
#include <vtkObjectFactory.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <utility>

#include "base/check.h"

namespace thaw::gui {

std::vector<MipLevel> mip_levels(const MipLevel& base, int components) {
  std::vector<MipLevel> out;
  const MipLevel* from = &base;
  while (from->width > 1 || from->height > 1) {
    MipLevel to;
    to.width = std::max(1, from->width / 2);
    to.height = std::max(1, from->height / 2);
    to.pixels.resize(static_cast<std::size_t>(to.width) * to.height * components);
    // The 2x2 block of the level above (one of its sides may be 1 already: then 2 pixels).
    const int sx = from->width > 1 ? 2 : 1, sy = from->height > 1 ? 2 : 1;
    for (int y = 0; y < to.height; ++y)
      for (int x = 0; x < to.width; ++x)
        for (int c = 0; c < components; ++c) {
          int sum = 0;
          for (int dy = 0; dy < sy; ++dy)
            for (int dx = 0; dx < sx; ++dx)
              sum += from->pixels[(static_cast<std::size_t>(sy * y + dy) * from->width +
                                   static_cast<std::size_t>(sx * x + dx)) *
                                      components +
                                  c];
          const int n = sx * sy;
          to.pixels[(static_cast<std::size_t>(y) * to.width + x) * components + c] =
              static_cast<unsigned char>((sum + n / 2) / n);
        }
    out.push_back(std::move(to));
    from = &out.back();
  }
  return out;
}

vtkStandardNewMacro(MipmappedTexture);

void MipmappedTexture::set_image(vtkImageData* image) {
  THAW_CHECK(image && image->GetScalarType() == VTK_UNSIGNED_CHAR, "a texture of bytes");
  int size[3];
  image->GetDimensions(size);
  THAW_CHECK(size[2] == 1 && (size[0] & (size[0] - 1)) == 0 && (size[1] & (size[1] - 1)) == 0,
             "a 2D texture with power-of-two sides");
  m_components = image->GetNumberOfScalarComponents();
  MipLevel base;
  base.width = size[0];
  base.height = size[1];
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  base.pixels.assign(pixels, pixels + static_cast<std::size_t>(size[0]) * size[1] * m_components);
  m_levels = mip_levels(base, m_components);
  SetInputData(image);
}

void MipmappedTexture::Load(vtkRenderer* renderer) {
  // vtkOpenGLTexture loads the image (level 0) with its filters, without glGenerateMipmap; when
  // it did (a new image, context or setting: its load time moved), the levels follow.
  const bool mipmap = Mipmap;
  Mipmap = false;
  const vtkMTimeType loaded = LoadTime.GetMTime();
  vtkOpenGLTexture::Load(renderer);
  Mipmap = mipmap;
  if (mipmap && LoadTime.GetMTime() != loaded && !m_levels.empty()) upload_levels();
}

void MipmappedTexture::upload_levels() {
  // The texture is bound (Load activates it) with its image as level 0.
  vtkTextureObject* t = GetTextureObject();
  const GLenum internal = t->GetInternalFormat(VTK_UNSIGNED_CHAR, m_components, false);
  const GLenum format = t->GetFormat(VTK_UNSIGNED_CHAR, m_components, false);
  GLint alignment = 4;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 1 or 2 RGB pixels are not 4-byte aligned
  for (std::size_t k = 0; k < m_levels.size(); ++k)
    glTexImage2D(t->GetTarget(), static_cast<GLint>(k + 1), static_cast<GLint>(internal),
                 m_levels[k].width, m_levels[k].height, 0, format, GL_UNSIGNED_BYTE,
                 m_levels[k].pixels.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
  t->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
  // as vtkOpenGLTexture sets it for a mipmapped texture (vtkTexture's default 4): the floor seen
  // at a grazing angle keeps its rows instead of blurring to the mean
  t->SetMaximumAnisotropicFiltering(GetMaximumAnisotropicFiltering());
  t->SetBaseLevel(0);
  t->SetMaxLevel(static_cast<int>(m_levels.size()));
  t->SendParameters();
}

}  // namespace thaw::gui
