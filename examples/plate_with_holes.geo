// A 4 x 2 plate with three round holes: the classic "perforated plate" of structural
// analysis. Triangles by default; `-setnumber quads 1` recombines them into quadrilaterals.
// Mesh with: gmsh -2 plate_with_holes.geo -format msh41 -o plate.msh
// Parameters (gmsh -setnumber NAME VALUE): h = target edge length, quads = 0/1.
DefineConstant[ h = {0.2, Name "edge length"}, quads = {0, Name "recombine into quads"} ];

Point(1) = {0, 0, 0, h};
Point(2) = {4, 0, 0, h};
Point(3) = {4, 2, 0, h};
Point(4) = {0, 2, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};

// Holes: centre x, centre y, radius. Finer edges on the holes (h/2).
holes[] = {1.0, 1.0, 0.4,   2.4, 0.7, 0.3,   3.2, 1.4, 0.35};
For i In {0 : #holes[] / 3 - 1}
  cx = holes[3 * i]; cy = holes[3 * i + 1]; r = holes[3 * i + 2];
  p = 10 * (i + 1);  // points p..p+4, curves p..p+3, curve loop p
  Point(p) = {cx, cy, 0, h / 2};
  Point(p + 1) = {cx + r, cy, 0, h / 2};
  Point(p + 2) = {cx, cy + r, 0, h / 2};
  Point(p + 3) = {cx - r, cy, 0, h / 2};
  Point(p + 4) = {cx, cy - r, 0, h / 2};
  Circle(p) = {p + 1, p, p + 2};
  Circle(p + 1) = {p + 2, p, p + 3};
  Circle(p + 2) = {p + 3, p, p + 4};
  Circle(p + 3) = {p + 4, p, p + 1};
  Curve Loop(p) = {p, p + 1, p + 2, p + 3};
  hole_loops[i] = p;
  hole_curves[{4 * i : 4 * i + 3}] = {p, p + 1, p + 2, p + 3};
EndFor
Plane Surface(1) = {1, hole_loops[]};

Physical Curve("outer", 1) = {1, 2, 3, 4};
Physical Curve("holes", 2) = {hole_curves[]};
Physical Surface("plate", 10) = {1};

Mesh.Algorithm = 6;  // Frontal-Delaunay
// neomesh does the smoothing: Gmsh's own Laplacian smoothing pass is off, so that the
// example starts from the raw mesh (examples/README.md has numbers for both).
Mesh.Smoothing = 0;
If (quads)
  Recombine Surface{1};
  Mesh.RecombinationAlgorithm = 3;  // blossom full-quad: quadrilaterals only
EndIf
