// A unit cube with a spherical hole of radius 0.25 in its centre: tetrahedra.
// Mesh with: gmsh -3 box_with_hole.geo -format msh41 -o box.msh
DefineConstant[ h = {0.12, Name "edge length"} ];
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Sphere(2) = {0.5, 0.5, 0.5, 0.25};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = h / 2;

// The box's six faces and the sphere, told apart by their bounding boxes.
e = 1e-6;
sphere() = Surface In BoundingBox{0.25 - e, 0.25 - e, 0.25 - e, 0.75 + e, 0.75 + e, 0.75 + e};
Physical Surface("sphere", 2) = {sphere()};
all() = Surface{:};
Physical Surface("box", 1) = {all()};
Physical Surface("box", 1) -= {sphere()};
Physical Volume("solid", 10) = {3};

Mesh.Optimize = 0;  // neomesh does the smoothing (see plate_with_holes.geo)
Mesh.Smoothing = 0;
