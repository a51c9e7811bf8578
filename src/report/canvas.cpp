#include "report/canvas.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <string>

#include <cairo-svg.h>

#include "core/error.hpp"

namespace neomesh {

namespace {

// DejaVu Sans is on every Debian system; cairo falls back to the default sans otherwise.
constexpr const char* kFontFamily = "DejaVu Sans";
// Height of digits relative to the font size in DejaVu Sans, for vertical centring.
constexpr double kDigitHeight = 0.73;

void select_font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

// Advance width of text in the current font of cr.
double advance(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

cairo_status_t write_to_stream(void* stream, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ofstream*>(stream);
  out.write(reinterpret_cast<const char*>(data), length);
  return out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

}  // namespace

PictureFormat picture_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".png") return PictureFormat::Png;
  if (ext == ".svg") return PictureFormat::Svg;
  fail("cannot write picture {}: unknown extension '{}' (use .png or .svg)", path.string(),
       path.extension().string());
}

Canvas::Canvas(const std::filesystem::path& path, int width, int height)
    : path_(path),
      format_(picture_format(path)),
      width_(width),
      height_(height),
      file_(path, /*binary=*/true) {
  surface_ =
      format_ == PictureFormat::Png
          ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)
          : cairo_svg_surface_create_for_stream(write_to_stream, &file_.stream(), width, height);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
    fail("cannot draw {}: {}", path.string(),
         cairo_status_to_string(cairo_surface_status(surface_)));
  cr_ = cairo_create(surface_);
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Canvas::finish() {
  cairo_status_t status = cairo_status(cr_);
  if (status == CAIRO_STATUS_SUCCESS) {
    if (format_ == PictureFormat::Png) {
      status = cairo_surface_write_to_png_stream(surface_, write_to_stream, &file_.stream());
    } else {
      cairo_surface_finish(surface_);  // writes the rest of the SVG
      status = cairo_surface_status(surface_);
    }
  }
  if (status != CAIRO_STATUS_SUCCESS)
    fail("cannot write {}: {}", path_.string(), cairo_status_to_string(status));
  file_.commit();
}

void set_colour(cairo_t* cr, const Rgb& c, double alpha) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

double text_width(std::string_view text, double size, bool bold) {
  cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(scratch);
  select_font(cr, size, bold);
  const double width = advance(cr, std::string(text));
  cairo_destroy(cr);
  cairo_surface_destroy(scratch);
  return width;
}

void draw_text(cairo_t* cr, std::string_view text, double x, double y, double size, Anchor anchor,
               bool bold) {
  select_font(cr, size, bold);
  const std::string s(text);
  const double width = advance(cr, s);
  const double left = anchor == Anchor::Left     ? x
                      : anchor == Anchor::Center ? x - width / 2
                                                 : x - width;
  cairo_move_to(cr, left, y + kDigitHeight * size / 2);
  cairo_show_text(cr, s.c_str());
  cairo_new_path(cr);
}

void draw_vertical_text(cairo_t* cr, std::string_view text, double x, double y, double size) {
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, -M_PI / 2);
  draw_text(cr, text, 0, 0, size, Anchor::Center);
  cairo_restore(cr);
}

}  // namespace neomesh
