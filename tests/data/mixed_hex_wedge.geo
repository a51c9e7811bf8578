// A channel block of hexahedra beside one of wedges (extruded quads and triangles), with
// named boundary groups.
h = 0.25;
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Point(5) = {2, 0, 0, h}; Point(6) = {2, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4} = 5;
Transfinite Surface{1}; Recombine Surface{1};
a[] = Extrude {0, 0, 1} { Surface{1}; Layers{4}; Recombine; };
b[] = Extrude {0, 0, 1} { Surface{2}; Layers{4}; Recombine; };
Physical Volume("fluid") = {a[1], b[1]};
Physical Surface("bottom") = {1, 2};
Physical Surface("top") = {a[0], b[0]};
Physical Surface("inlet") = {a[5]};
Physical Surface("outlet") = {b[3]};
