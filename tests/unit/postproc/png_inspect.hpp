#pragma once
// What a PNG file shows, decoded with cairo independently of how it was drawn:
// its size, its number of distinct colours and its share of non-white pixels
// (the pictures are drawn on white). A file cairo cannot decode gives 0 x 0.
#include <cstdint>
#include <filesystem>
#include <set>

#include <cairo.h>

namespace kinetofem::post::testing {

struct PngStats {
  int width = 0, height = 0;
  size_t colours = 0;
  double ink = 0;  // share of pixels that are not white
};

inline PngStats inspect(const std::filesystem::path& png) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.string().c_str());
  PngStats out;
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(s);
    out.width = cairo_image_surface_get_width(s);
    out.height = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    std::set<uint32_t> colours;
    size_t ink = 0;
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) {
        const uint32_t p = *reinterpret_cast<const uint32_t*>(data + y * stride + 4 * x);
        colours.insert(p);
        ink += (p & 0xffffffu) != 0xffffffu;
      }
    out.colours = colours.size();
    out.ink = double(ink) / (double(out.width) * out.height);
  }
  cairo_surface_destroy(s);
  return out;
}

}  // namespace kinetofem::post::testing
