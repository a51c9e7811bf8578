// A meshed cube and a separate meshed square beside it: 3D and 2D cells in one file.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Rectangle(100) = {2, 0, 0, 1, 1};
Mesh.MeshSizeMax = 0.6;
Physical Surface("sheet", 1) = {100};
Physical Volume("solid", 10) = {1};
