// Flow around a cylinder with a boundary layer: the channel of cylinder_channel.geo (the DFG
// benchmark's 2.2 x 0.41, cylinder of radius 0.05 at (0.2, 0.2)) with a layer of quads on
// the cylinder: first height 5e-4, growing by 1.25 per layer to a thickness of 0.01, as a
// CFD user designs it for y+. Triangles outside, graded from h_min to h_max.
// Mesh with: gmsh -2 cylinder_channel_bl.geo -format msh41 -o channel_bl.msh
DefineConstant[ h_min = {0.008, Name "edge length on the cylinder"},
                h_max = {0.04, Name "edge length far from it"} ];

Point(1) = {0, 0, 0, h_max};
Point(2) = {2.2, 0, 0, h_max};
Point(3) = {2.2, 0.41, 0, h_max};
Point(4) = {0, 0.41, 0, h_max};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};

r = 0.05;
Point(5) = {0.2, 0.2, 0, h_min};
Point(6) = {0.2 + r, 0.2, 0, h_min};
Point(7) = {0.2, 0.2 + r, 0, h_min};
Point(8) = {0.2 - r, 0.2, 0, h_min};
Point(9) = {0.2, 0.2 - r, 0, h_min};
Circle(5) = {6, 5, 7};
Circle(6) = {7, 5, 8};
Circle(7) = {8, 5, 9};
Circle(8) = {9, 5, 6};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

// Grading: h grows linearly with the distance to the cylinder.
Field[1] = Distance;
Field[1].CurvesList = {5, 6, 7, 8};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_min;
Field[2].SizeMax = h_max;
Field[2].DistMin = 0.0;
Field[2].DistMax = 0.41;
Background Field = 2;

// The boundary layer: quads (Recombine) extruded from the cylinder.
Field[3] = BoundaryLayer;
Field[3].CurvesList = {5, 6, 7, 8};
Field[3].Size = 5e-4;
Field[3].Ratio = 1.25;
Field[3].Thickness = 0.01;
Field[3].Quads = 1;
BoundaryLayer Field = 3;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;

Physical Curve("wall", 1) = {1, 3};
Physical Curve("inflow", 2) = {4};
Physical Curve("outflow", 3) = {2};
Physical Curve("cylinder", 4) = {5, 6, 7, 8};
Physical Surface("fluid", 10) = {1};

Mesh.Algorithm = 6;
Mesh.Smoothing = 0;  // neomesh does the smoothing (see plate_with_holes.geo)
