"""The mixed 3D test mesh of make_vtk.py and make_vtu.py."""
# hex (0-7), wedge (8-13, VTK order: base normal away from the top), unused point 14,
# pyramid (15-19), tet (20-23), and a point 24 used by a vertex cell only.
P = [(0,0,0),(1,0,0),(1,1,0),(0,1,0),(0,0,1),(1,0,1),(1,1,1),(0,1,1),
     (2,0,0),(2,1,0),(3,0,0),(2,0,1),(2,1,1),(3,0,1),
     (9,9,9),
     (4,0,0),(5,0,0),(5,1,0),(4,1,0),(4.5,0.5,1),
     (6,0,0),(7,0,0),(6,1,0),(6,0,1),
     (8,8,8)]
C = [(12, list(range(8))), (1, [24]), (13, list(range(8, 14))), (3, [0, 8]),
     (14, [15,16,17,18,19]), (10, [20,21,22,23])]
