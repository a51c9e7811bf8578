#include "formats/cgns_reader.hpp"
#include "formats/cgns_library.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.hpp"
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

// Two zones side by side, as Pointwise writes a block each: "left" two unit squares on [0, 2] x
// [0, 1] (section "fluid"), "right" two on [2, 4] (sections "fluid" and "solid"), its nodes
// numbered from the far side, and the x = 2 of its two interface nodes `gap` to the right. Each
// zone has the edges at y = 0 as a section "bottom" under a BC "wall"; the vertex solution "p"
// (each node's x) and the cell solution "rho" (the cells' numbers in the zone), and "left" alone
// a vertex solution "t". With `connected`, each zone has a 1-to-1 connectivity naming the
// interface nodes and the other zone's matching nodes.
std::filesystem::path two_zones(bool connected, double gap) {
  const auto path =
      testing::scratch_dir("ReadCgns") /
      (std::string(connected ? "connected" : "apart") + (gap > 0 ? "_gap" : "") + ".cgns");
  int file = 0, base = 0, zone = 0, index = 0;
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &file));
  ok(cg_base_write(file, "Base", 2, 2, &base));
  struct Zone {
    const char* name;
    std::vector<double> x, y;
    std::vector<cgsize_t> fluid, solid, bars, interface, donor;
  };
  const Zone zones[2] = {{"left",
                          {0, 1, 2, 0, 1, 2},
                          {0, 0, 0, 1, 1, 1},
                          {1, 2, 5, 4, 2, 3, 6, 5},
                          {},
                          {1, 2, 2, 3},
                          {3, 6},
                          {5, 6}},
                         {"right",
                          {4, 4, 3, 3, 2 + gap, 2 + gap},
                          {0, 1, 0, 1, 0, 1},
                          {5, 3, 4, 6},
                          {3, 1, 2, 4},
                          {5, 3, 3, 1},
                          {5, 6},
                          {3, 6}}};
  for (int z = 0; z < 2; ++z) {
    const Zone& d = zones[z];
    const cgsize_t cells = static_cast<cgsize_t>((d.fluid.size() + d.solid.size()) / 4);
    const cgsize_t size[3] = {6, cells, 0};
    ok(cg_zone_write(file, base, d.name, size, CGNS_ENUMV(Unstructured), &zone));
    ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", d.x.data(), &index));
    ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", d.y.data(), &index));
    cgsize_t end = static_cast<cgsize_t>(d.fluid.size() / 4);
    ok(cg_section_write(file, base, zone, "fluid", CGNS_ENUMV(QUAD_4), 1, end, 0, d.fluid.data(),
                        &index));
    if (!d.solid.empty()) {
      ok(cg_section_write(file, base, zone, "solid", CGNS_ENUMV(QUAD_4), end + 1, end + 1, 0,
                          d.solid.data(), &index));
      ++end;
    }
    ok(cg_section_write(file, base, zone, "bottom", CGNS_ENUMV(BAR_2), end + 1, end + 2, 0,
                        d.bars.data(), &index));
    const cgsize_t range[2] = {end + 1, end + 2};
    ok(cg_boco_write(file, base, zone, "wall", CGNS_ENUMV(BCWall), CGNS_ENUMV(ElementRange), 2,
                     range, &index));
    if (connected)
      ok(cg_conn_write(file, base, zone, "interface", CGNS_ENUMV(Vertex), CGNS_ENUMV(Abutting1to1),
                       CGNS_ENUMV(PointList), 2, d.interface.data(), zones[1 - z].name,
                       CGNS_ENUMV(Unstructured), CGNS_ENUMV(PointListDonor), CGNS_ENUMV(Integer), 2,
                       d.donor.data(), &index));
    int solution = 0;
    ok(cg_sol_write(file, base, zone, "Nodes", CGNS_ENUMV(Vertex), &solution));
    ok(cg_field_write(file, base, zone, solution, CGNS_ENUMV(RealDouble), "p", d.x.data(), &index));
    if (z == 0)
      ok(cg_field_write(file, base, zone, solution, CGNS_ENUMV(RealDouble), "t", d.y.data(),
                        &index));
    const std::vector<double> rho = {1, 2};
    ok(cg_sol_write(file, base, zone, "Cells", CGNS_ENUMV(CellCenter), &solution));
    ok(cg_field_write(file, base, zone, solution, CGNS_ENUMV(RealDouble), "rho", rho.data(),
                      &index));
  }
  ok(cg_close(file));
  return path;
}

// The vertices' x coordinates, sorted.
std::vector<double> sorted_x(const InputMesh& mesh) {
  std::vector<double> x;
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v) x.push_back(mesh.coords[v * mesh.dim]);
  std::sort(x.begin(), x.end());
  return x;
}

TEST(ReadCgns, ZonesAreJoinedByTheirConnectivityIntoOneMeshWithGroupsByName) {
  // (the interface nodes of "right" off by 1e-9: joined all the same, at "left"'s coordinates)
  const InputMesh mesh = read_cgns(two_zones(true, 1e-9));
  EXPECT_EQ(mesh.num_vertices(), 10);
  EXPECT_EQ(sorted_x(mesh), (std::vector<double>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4}));
  ASSERT_EQ(mesh.num_cells(), 4);
  // Cells zone after zone, each section's group: "fluid" of both zones is one group.
  ASSERT_EQ(mesh.groups.size(), 3u);
  EXPECT_EQ(mesh.groups[0].name, "wall");
  EXPECT_EQ(mesh.groups[1].name, "fluid");
  EXPECT_EQ(mesh.groups[2].name, "solid");
  EXPECT_EQ(mesh.cell_tags, (std::vector<int>{mesh.groups[1].tag, mesh.groups[1].tag,
                                              mesh.groups[1].tag, mesh.groups[2].tag}));
  // The third cell ("right"'s first) shares the interface with the second.
  const auto cell = [&](PetscInt c) {
    std::vector<PetscInt> v(mesh.cell_vertices.begin() + mesh.cell_offsets[c],
                            mesh.cell_vertices.begin() + mesh.cell_offsets[c + 1]);
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<PetscInt> shared;
  std::ranges::set_intersection(cell(1), cell(2), std::back_inserter(shared));
  EXPECT_EQ(shared.size(), 2u);
  EXPECT_EQ(mesh.element_tag, (std::vector<std::int64_t>{1, 2, 5, 6}));  // zone after zone
  EXPECT_EQ(mesh.facets.size(), 4);                                      // both zones' "wall"
  EXPECT_TRUE(std::all_of(mesh.facets.tags.begin(), mesh.facets.tags.end(),
                          [&](int t) { return t == mesh.groups[0].tag; }));
  // "p" and "rho", which both zones have, and not "t": "p" is each vertex's x (the first zone's
  // value where zones share it), "rho" the cells' numbers in their zones.
  ASSERT_EQ(mesh.point_data.size(), 1u);
  EXPECT_EQ(mesh.point_data[0].name, "p");
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_EQ(mesh.point_data[0].values[v], mesh.coords[v * mesh.dim]);
  ASSERT_EQ(mesh.cell_data.size(), 1u);
  EXPECT_EQ(mesh.cell_data[0].values, (std::vector<double>{1, 2, 1, 2}));
}

TEST(ReadCgns, ZonesWithoutConnectivityAreJoinedWhereTheirCoordinatesAreEqual) {
  EXPECT_EQ(read_cgns(two_zones(false, 0)).num_vertices(), 10);
  EXPECT_EQ(read_cgns(two_zones(false, 1e-9)).num_vertices(), 12);  // not equal: apart
}

TEST(ReadCgns, AStructuredZoneIsRefusedInOneLineNamingIt) {
  const auto path = testing::scratch_dir("ReadCgns") / "structured.cgns";
  int file = 0, base = 0, zone = 0, index = 0;
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &file));
  ok(cg_base_write(file, "Base", 2, 2, &base));
  const cgsize_t size[6] = {2, 2, 1, 1, 0, 0};  // 2 x 2 vertices, 1 x 1 cells
  ok(cg_zone_write(file, base, "block", size, CGNS_ENUMV(Structured), &zone));
  const double x[4] = {0, 1, 0, 1}, y[4] = {0, 0, 1, 1};
  ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", x, &index));
  ok(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", y, &index));
  ok(cg_close(file));
  try {
    read_cgns(path);
    FAIL() << "read";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("structured.cgns: zone 'block' is a structured grid"), std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace neomesh
