// Unit cube, 2x2x2 hexahedra (transfinite + recombined); bottom, top and volume named.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {6};
Physical Volume("solid", 10) = {1};
