#include "mesh/cgns_reader.hpp"
#include "mesh/cgns_library.hpp"

#include <gtest/gtest.h>

#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

void ok(int status) {
  ASSERT_EQ(status, CG_OK) << cg_get_error();
}

// Two unit squares side by side (nodes 1 2 3 below, 4 5 6 above), the three edges at y = 0 in a
// BAR_2 section named by a BC "floor" (ElementRange), the left side's vertices in a BC "left"
// at vertices (PointList, the default GridLocation Vertex) of the family "inflow".
std::filesystem::path two_squares() {
  const auto path = testing::scratch_dir("ReadCgns") / "squares.cgns";
  int file = 0, base = 0, zone = 0, index = 0;
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &file));
  ok(cg_base_write(file, "Base", 2, 2, &base));
  const cgsize_t size[3] = {6, 2, 0};
  ok(cg_zone_write(file, base, "Zone", size, CGNS_ENUMV(Unstructured), &zone));
  const double x[6] = {0, 1, 2, 0, 1, 2}, y[6] = {0, 0, 0, 1, 1, 1};
  ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", x, &index));
  ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", y, &index));
  const cgsize_t quads[8] = {1, 2, 5, 4, 2, 3, 6, 5}, bars[4] = {1, 2, 2, 3};
  ok(cg_section_write(file, base, zone, "fluid", CGNS_ENUMV(QUAD_4), 1, 2, 0, quads, &index));
  ok(cg_section_write(file, base, zone, "bottom", CGNS_ENUMV(BAR_2), 3, 4, 0, bars, &index));
  const cgsize_t range[2] = {3, 4}, left[2] = {1, 4};
  ok(cg_boco_write(file, base, zone, "floor", CGNS_ENUMV(BCWall), CGNS_ENUMV(ElementRange), 2,
                   range, &index));
  ok(cg_boco_write(file, base, zone, "left", CGNS_ENUMV(BCInflow), CGNS_ENUMV(PointList), 2, left,
                   &index));
  ok(cg_goto(file, base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", index, "end"));
  ok(cg_famname_write("inflow"));
  ok(cg_close(file));
  return path;
}

TEST(ReadCgns, BoundaryConditionsAtElementsAndAtVerticesAreFacetGroupsNamedByTheirFamily) {
  const InputMesh mesh = read_cgns(two_squares());
  EXPECT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.num_vertices(), 6);
  EXPECT_EQ(mesh.num_cells(), 2);
  ASSERT_EQ(mesh.groups.size(), 3u);
  EXPECT_EQ(mesh.groups[0].name, "floor");  // facet groups first, numbered as they come
  EXPECT_EQ(mesh.groups[1].name, "inflow");
  EXPECT_EQ(mesh.groups[2].name, "fluid");
  EXPECT_EQ(mesh.facets.size(), 2);        // the floor's edges
  ASSERT_EQ(mesh.vertex_sets.size(), 1u);  // the left side, whose edge input_topology finds
  EXPECT_EQ(mesh.vertex_sets[0].name, "inflow");
  EXPECT_EQ(mesh.vertex_sets[0].vertices, (std::vector<std::int64_t>{0, 3}));
}

}  // namespace
}  // namespace neomesh
