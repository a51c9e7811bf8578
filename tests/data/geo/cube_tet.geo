// Unit cube, tetrahedra; bottom and top faces and the volume are named physical groups.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = 0.5;
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {6};
Physical Volume("solid", 10) = {1};
