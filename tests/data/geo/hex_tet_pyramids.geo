// A unit cube of hexahedra glued to a unit cube of tetrahedra: Gmsh puts pyramids on the
// tetrahedral side of the shared quadrilateral face.
SetFactory("Built-in");
lc = 0.34;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 4;
Transfinite Surface{1};
Recombine Surface{1};
hex[] = Extrude {0, 0, 1} { Surface{1}; Layers{3}; Recombine; };
tet[] = Extrude {0, 0, 1} { Surface{hex[0]}; };
Physical Volume("solid", 10) = {hex[1], tet[1]};
