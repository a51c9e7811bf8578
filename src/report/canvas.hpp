// A cairo drawing surface for one picture file, PNG or SVG by the file's extension, plus the
// few text helpers the pictures share. The file is an AtomicFile: it appears only when
// finish() succeeds, so a failed run never leaves a partial picture.
//
// Units: one user unit is one pixel (PNG) or one point (SVG); y grows downwards.
#pragma once

#include <filesystem>
#include <string_view>

#include <cairo.h>

#include "core/atomic_file.hpp"
#include "report/colormap.hpp"

namespace neomesh {

enum class PictureFormat { Png, Svg };

// The format for `path` (.png or .svg, any case); throws Error for anything else.
PictureFormat picture_format(const std::filesystem::path& path);

class Canvas {
 public:
  // A white width × height picture for `path`. Throws Error if the format is unknown or
  // the directory is not writable.
  Canvas(const std::filesystem::path& path, int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Writes the picture and commits the file; throws Error on any failure.
  void finish();

 private:
  std::filesystem::path path_;
  PictureFormat format_;
  int width_, height_;
  AtomicFile file_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

void set_colour(cairo_t* cr, const Rgb& c, double alpha = 1.0);

enum class Anchor { Left, Center, Right };

// Draws one line of UTF-8 text of font size `size`, horizontally anchored at x and
// vertically centred on the height of its digits at y.
void draw_text(cairo_t* cr, std::string_view text, double x, double y, double size,
               Anchor anchor = Anchor::Left, bool bold = false);
// The same, turned a quarter counter-clockwise (for y-axis labels), centred at (x, y).
void draw_vertical_text(cairo_t* cr, std::string_view text, double x, double y, double size);
// The advance width of text drawn by draw_text (works before any canvas exists).
double text_width(std::string_view text, double size, bool bold = false);

}  // namespace neomesh
