#include "report/render.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include <cairo.h>
#include <gtest/gtest.h>

#include <neomesh/generate.hpp>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

// An n × n grid of unit-square quads on [0, n]², slightly sheared so that cells differ.
MeshArrays quad_grid(int n) {
  MeshArrays mesh;
  mesh.dim = mesh.coordinate_dim = 2;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.coordinates.push_back(i + 0.15 * j * j / n);
      mesh.coordinates.push_back(j);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t v = j * (n + 1) + i;  // Gmsh order: counter-clockwise
      mesh.cells.insert(mesh.cells.end(), {v, v + 1, v + n + 2, v + n + 1});
      mesh.types.push_back(CellType::Quadrilateral);
    }
  return mesh;
}

// A 2:1 rectangle [0, 2] × [0, 1] of 2 × 3 × 3 counter-clockwise triangles.
MeshArrays triangle_strip() {
  MeshArrays mesh;
  mesh.dim = mesh.coordinate_dim = 2;
  const int nx = 6, ny = 3;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      mesh.coordinates.push_back(2.0 * i / nx);
      mesh.coordinates.push_back(1.0 * j / ny);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int64_t v = j * (nx + 1) + i;
      mesh.cells.insert(mesh.cells.end(), {v, v + 1, v + nx + 2, v, v + nx + 2, v + nx + 1});
      mesh.types.insert(mesh.types.end(), 2, CellType::Triangle);
    }
  return mesh;
}

// The unit sphere as a surface mesh: the 6 faces of the cube [-1, 1]³, each n × n quads,
// pushed out onto the sphere, every quad counter-clockwise seen from outside.
MeshArrays cubed_sphere(int n) {
  MeshArrays mesh;
  mesh.dim = 2;
  mesh.coordinate_dim = 3;
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      const auto first = static_cast<std::int64_t>(mesh.coordinates.size() / 3);
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          double p[3];
          p[axis] = side;
          p[(axis + 1) % 3] = -1.0 + 2.0 * i / n;
          p[(axis + 2) % 3] = -1.0 + 2.0 * j / n;
          const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
          mesh.coordinates.insert(mesh.coordinates.end(), {p[0] / r, p[1] / r, p[2] / r});
        }
      // (axis+1, axis+2, axis) is right-handed: the grid turns counter-clockwise about +axis.
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const std::int64_t v = first + j * (n + 1) + i;
          if (side > 0)
            mesh.cells.insert(mesh.cells.end(), {v, v + 1, v + n + 2, v + n + 1});
          else
            mesh.cells.insert(mesh.cells.end(), {v, v + n + 1, v + n + 2, v + 1});
          mesh.types.push_back(CellType::Quadrilateral);
        }
    }
  return mesh;
}

std::vector<double> ramp(std::size_t n) {
  std::vector<double> values;
  for (std::size_t c = 0; c < n; ++c) values.push_back(0.2 + 0.8 * c / (n - 1));
  return values;
}

struct Png {
  int width = 0, height = 0;
  double non_white_fraction = 0;
};

Png read_png(const std::filesystem::path& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
  Png png{cairo_image_surface_get_width(s), cairo_image_surface_get_height(s), 0};
  cairo_surface_flush(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  long non_white = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const auto pixel = reinterpret_cast<const std::uint32_t*>(data + y * stride)[x];
      non_white += (pixel & 0xffffff) != 0xffffff;
    }
  png.non_white_fraction = static_cast<double>(non_white) / (png.width * png.height);
  cairo_surface_destroy(s);
  return png;
}

TEST(RenderMesh, QuadGridToPngFillsMostOfThePicture) {
  const auto dir = testing::scratch_dir("render_quads");
  const MeshArrays mesh = quad_grid(4);
  const auto values = ramp(mesh.types.size());
  RenderOptions options;
  options.width = 800;
  options.title = "4 x 4 quads";
  options.field_name = "scaled Jacobian";
  render_mesh(mesh, values, dir / "quads.png", options);

  const Png png = read_png(dir / "quads.png");
  EXPECT_EQ(png.width, 800);
  EXPECT_GT(png.height, 400);  // a square mesh plus the title
  EXPECT_GT(png.non_white_fraction, 0.3);
  EXPECT_LT(png.non_white_fraction, 0.9);    // margins and legend stay white
  std::vector<std::filesystem::path> files;  // the picture and no temporary file
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    files.push_back(entry.path().filename());
  EXPECT_EQ(files, std::vector<std::filesystem::path>{"quads.png"});
}

TEST(RenderMesh, TrianglesWithInvertedCellsToPng) {
  const auto dir = testing::scratch_dir("render_triangles");
  const MeshArrays mesh = triangle_strip();
  auto values = ramp(mesh.types.size());
  values[3] = std::numeric_limits<double>::infinity();
  values[7] = std::numeric_limits<double>::quiet_NaN();
  RenderOptions options;
  options.width = 600;
  options.field_name = "energy";
  options.log_scale = true;
  render_mesh(mesh, values, dir / "triangles.png", options);

  const Png png = read_png(dir / "triangles.png");
  EXPECT_EQ(png.width, 600);
  EXPECT_GT(png.non_white_fraction, 0.3);
}

TEST(RenderMesh, SvgByExtension) {
  const auto dir = testing::scratch_dir("render_svg");
  const MeshArrays mesh = quad_grid(4);
  render_mesh(mesh, ramp(mesh.types.size()), dir / "quads.SVG");
  std::ifstream in(dir / "quads.SVG");
  std::string head(5, '\0');
  in.read(head.data(), 5);
  EXPECT_TRUE(head == "<?xml" || head.starts_with("<svg")) << head;
}

TEST(RenderMesh, ConstantFieldAndManySmallCellsStillDraw) {
  const auto dir = testing::scratch_dir("render_constant");
  const MeshArrays mesh = quad_grid(150);  // cells of about 3 pixels: edges would be noise
  const std::vector<double> values(mesh.types.size(), 1.0);
  RenderOptions options;
  options.width = 500;
  render_mesh(mesh, values, dir / "fine.png", options);
  EXPECT_GT(read_png(dir / "fine.png").non_white_fraction, 0.3);
}

TEST(RenderMesh, WholeMeshOfTriangles) {
  const auto dir = testing::scratch_dir("render_whole_mesh");
  const Mesh mesh = Mesh::generate({.name = "box-tri", .size = 8});
  render_mesh(mesh, ramp(mesh.num_cells()), dir / "box.png");
  const Png png = read_png(dir / "box.png");
  EXPECT_EQ(png.width, 1200);
  EXPECT_GT(png.non_white_fraction, 0.3);
}

// The share of the picture's pixels in viridis' dark purple end (shaded or not) and in its
// yellow end.
struct Ends {
  double purple = 0, yellow = 0;
};
Ends colour_ends(const std::filesystem::path& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
  const int width = cairo_image_surface_get_width(s), height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  cairo_surface_flush(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  Ends ends;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto pixel = reinterpret_cast<const std::uint32_t*>(data + y * stride)[x];
      const int r = (pixel >> 16) & 0xff, g = (pixel >> 8) & 0xff, b = pixel & 0xff;
      ends.purple += g < 20 && b > 40 && r < 2 * b;
      ends.yellow += r > 60 && g > r / 2 && b < r / 3;
    }
  cairo_surface_destroy(s);
  ends.purple /= width * height, ends.yellow /= width * height;
  return ends;
}

TEST(RenderMesh, ThreeDimensionalMeshShowsItsBoundaryAndACutShowsInside) {
  const auto dir = testing::scratch_dir("render_3d");
  const MeshArrays cube = Mesh::generate({.name = "box-hex", .size = 4}).gather();
  // The cells inside at the bottom of the colour range, those at the boundary at the top.
  std::vector<double> values;
  for (std::size_t c = 0; c < cube.types.size(); ++c) {
    bool boundary = false;
    for (int i = 0; i < 8; ++i)
      for (int a = 0; a < 3; ++a) {
        const double x = cube.coordinates[3 * cube.cells[8 * c + i] + a];
        boundary = boundary || std::abs(x) > 1 - 1e-9;  // the box is [-1, 1]³
      }
    values.push_back(boundary ? 1.0 : 0.0);
  }
  render_mesh(cube, values, dir / "whole.png");
  const Ends whole = colour_ends(dir / "whole.png");
  EXPECT_GT(whole.yellow, 0.2);
  EXPECT_LT(whole.purple, 1e-3);  // the inside is hidden (only the bar's end is purple)

  RenderOptions cut;
  for (int axis = 0; axis < 3; ++axis) {
    cut.cut = RenderOptions::Cut{.axis = axis, .position = std::nullopt};
    render_mesh(cube, values, dir / "cut.png", cut);
    const Ends inside = colour_ends(dir / "cut.png");
    EXPECT_GT(inside.purple, 0.02) << "axis " << axis;
    EXPECT_GT(inside.yellow, 0.1) << "axis " << axis;
  }
  // A plane beyond the mesh on the eye's side keeps every cell: the boundary alone again.
  cut.cut = RenderOptions::Cut{.axis = 0, .position = 10.0};
  render_mesh(cube, values, dir / "all.png", cut);
  EXPECT_LT(colour_ends(dir / "all.png").purple, 1e-3);
}

// A surface mesh is drawn as its cells in perspective: a sphere coloured by height (z) fills a
// disc of the picture, the legend's range is the field's, and a cut shows the inside of the
// far half, darker (its cells turn their back to the eye).
TEST(RenderMesh, SurfaceSphereIsDrawnInPerspective) {
  const auto dir = testing::scratch_dir("render_surface");
  const MeshArrays sphere = cubed_sphere(8);
  std::vector<double> height;
  for (std::size_t c = 0; c < sphere.types.size(); ++c) {
    double z = 0;
    for (int i = 0; i < 4; ++i) z += sphere.coordinates[3 * sphere.cells[4 * c + i] + 2] / 4;
    height.push_back(z);
  }
  RenderOptions options;
  options.width = 600;
  options.field_name = "z";
  const ColourBarRange range = render_mesh(sphere, height, dir / "sphere.png", options);
  EXPECT_DOUBLE_EQ(range.min, *std::min_element(height.begin(), height.end()));
  EXPECT_DOUBLE_EQ(range.max, *std::max_element(height.begin(), height.end()));
  const Png png = read_png(dir / "sphere.png");
  EXPECT_EQ(png.width, 600);
  EXPECT_GT(png.height, 300);
  EXPECT_GT(png.non_white_fraction, 0.2);  // a disc of about half the map's width and more
  EXPECT_LT(png.non_white_fraction, 0.8);
  // Seen from above (elevation 25°) the top's yellow shows and the bottom's purple is hidden
  // but for the colour bar's end; cut open, the far half's inside shows its purple bottom.
  const Ends whole = colour_ends(dir / "sphere.png");
  EXPECT_GT(whole.yellow, 0.02);
  EXPECT_LT(whole.purple, 2e-3);
  options.cut = RenderOptions::Cut{.axis = 0, .position = std::nullopt};
  render_mesh(sphere, height, dir / "cut.png", options);
  EXPECT_GT(colour_ends(dir / "cut.png").purple, 2 * whole.purple + 1e-3);
}

// The surface mesh of a Mesh (its gathered arrays have 3 coordinates per vertex) renders the
// same picture as its arrays.
TEST(RenderMesh, SurfaceMeshFromArrays) {
  const auto dir = testing::scratch_dir("render_surface_mesh");
  const MeshArrays sphere = cubed_sphere(4);
  const Mesh mesh = Mesh::from_arrays(MPI_COMM_WORLD, 3, sphere.coordinates, sphere.cells,
                                      sphere.types, "cubed sphere");
  ASSERT_EQ(mesh.dim(), 2);
  ASSERT_EQ(mesh.coordinate_dim(), 3);
  std::vector<double> by_number = ramp(sphere.types.size()), local;
  for (std::int64_t c : mesh.cell_numbers()) local.push_back(by_number[c]);
  render_mesh(mesh, local, dir / "mesh.png");
  render_mesh(sphere, by_number, dir / "arrays.png");
  EXPECT_TRUE(testing::read_file(dir / "mesh.png") == testing::read_file(dir / "arrays.png"));
}

TEST(RenderMesh, OptionsOfTheOtherDimensionAreRefused) {
  const auto dir = testing::scratch_dir("render_dimension_options");
  const MeshArrays cube = Mesh::generate({.name = "box-hex", .size = 1}).gather();
  RenderOptions window;
  window.window = {0.0, 1.0, 0.0, 1.0};
  EXPECT_THROW(render_mesh(cube, std::vector<double>(1, 1.0), dir / "never.png", window), Error);
  RenderOptions cut;
  cut.cut = RenderOptions::Cut{.axis = 0, .position = std::nullopt};
  const MeshArrays square = quad_grid(2);
  EXPECT_THROW(render_mesh(square, ramp(4), dir / "never.png", cut), Error);
  MeshArrays flat = quad_grid(2);  // 2D cells in a 3D mesh
  flat.dim = flat.coordinate_dim = 3;
  flat.coordinates.resize(9 * 3, 0.0);
  EXPECT_THROW(render_mesh(flat, ramp(4), dir / "never.png"), Error);
  MeshArrays three_for_two = quad_grid(2);  // 2 coordinates per vertex are read as 3
  three_for_two.coordinate_dim = 3;
  three_for_two.dim = 3;
  EXPECT_THROW(render_mesh(three_for_two, ramp(4), dir / "never.png"), Error);
  const MeshArrays sphere = cubed_sphere(2);  // a surface: drawn whole, like a 3D mesh
  EXPECT_THROW(render_mesh(sphere, ramp(sphere.types.size()), dir / "never.png", window), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(RenderMesh, BadOutputPathsFailWithoutWriting) {
  const auto dir = testing::scratch_dir("render_errors");
  const MeshArrays mesh = quad_grid(2);
  const auto values = ramp(mesh.types.size());
  EXPECT_THROW(render_mesh(mesh, values, dir / "mesh.jpg"), Error);
  EXPECT_THROW(render_mesh(mesh, values, dir / "missing" / "mesh.png"), Error);
  RenderOptions empty_range;
  empty_range.min = 2.0, empty_range.max = 1.0;
  EXPECT_THROW(render_mesh(mesh, values, dir / "mesh.png", empty_range), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(RenderMesh, ArraysThatMakeNoMeshAreRefused) {
  const auto dir = testing::scratch_dir("render_bad_arrays");
  MeshArrays mesh = quad_grid(2);
  EXPECT_THROW(render_mesh(mesh, ramp(3), dir / "mesh.png"), Error);  // 4 cells
  mesh.cells.back() = 9;                                              // 9 vertices: 0..8
  EXPECT_THROW(render_mesh(mesh, ramp(4), dir / "mesh.png"), Error);
  mesh = quad_grid(2);
  mesh.cells.pop_back();
  EXPECT_THROW(render_mesh(mesh, ramp(4), dir / "mesh.png"), Error);
  mesh = quad_grid(2);
  mesh.types[1] = CellType::Tetrahedron;
  EXPECT_THROW(render_mesh(mesh, ramp(4), dir / "mesh.png"), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace neomesh
