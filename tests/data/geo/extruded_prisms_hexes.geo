// Two unit squares side by side, the left in triangles and the right in quadrilaterals,
// extruded in three layers: wedges next to hexahedra.
lc = 0.25;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {2, 0, 0, lc};
Point(4) = {2, 1, 0, lc};
Point(5) = {1, 1, 0, lc};
Point(6) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{2, 3, 4, 7} = 5;
Transfinite Surface{2};
Recombine Surface{2};
out[] = Extrude {0, 0, 1} { Surface{1, 2}; Layers{3}; Recombine; };
Physical Volume("solid", 10) = {out[1], out[7]};
