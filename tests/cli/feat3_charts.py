"""FEAT3 meshes of the shared corpus whose charts are in a file of their own
(../shared/corpus/README.md): mesh name -> chart file. Stdlib only: bench/ scripts import it too."""
CHARTS = {"screws_2d_mesh_quad_smaller_360_1": "screws_2d_chart_bezier_24_28_smaller.xml",
          "screws_2d_mesh_quad_opt_ss_smaller_360_1": "screws_2d_chart_bezier_24_28_smaller.xml",
          "screws_2d_mesh_quad_360_1": "screws_2d_chart_bezier_24_28.xml",
          "screws_2d_mesh_quad_opt_ss_360_1": "screws_2d_chart_bezier_24_28.xml",
          "screws_2d_mesh_tria_360_1": "screws_2d_chart_bezier_24_28.xml",
          "screws_3d_mesh_hexa_360_1": "screws_3d_chart_surfacemesh_7200_7200.xml"}
