#include <qverify/render/render.hpp>
#include <qverify/scene/files.hpp>

#include <png.h>

#include <stdexcept>

namespace qverify::render {

void write_png(const std::string& file, int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::runtime_error(file + ": internal error: image size does not match its pixels");
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  // Encoded in memory (the first call sizes the buffer), then written by the checked write of files.hpp.
  png_alloc_size_t size = 0;
  std::vector<std::uint8_t> png;
  if (png_image_write_get_memory_size(image, size, 0, rgb.data(), 0, nullptr)) {
    png.resize(size);
    if (!png_image_write_to_memory(&image, png.data(), &size, 0, rgb.data(), 0, nullptr)) png.clear();
  }
  if (png.empty()) {
    const std::string why = image.message;
    png_image_free(&image);
    throw std::runtime_error(file + ": internal error: cannot encode PNG: " + why);
  }
  write_file(file, std::string_view(reinterpret_cast<const char*>(png.data()), size));
}

}  // namespace qverify::render
