// The compiled part of the Python package `neomesh` (python/neomesh/__init__.py): a thin layer
// over the public C++ API (include/neomesh). Keyword options are read through the option table
// (src/api/option_table.hpp), results and iteration rows become dicts through the JSON report's
// code (src/report/run_report.hpp), so that Python and the command line cannot drift apart.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <neomesh/neomesh.hpp>

#include <omp.h>

#include "api/option_table.hpp"
#include "api/thread_count.hpp"
#include "keywords.hpp"
#include "report/quality_report.hpp"
#include "report/run_report.hpp"

#ifdef NEOMESH_MPI4PY
#include <mpi4py/mpi4py.h>
#endif
#ifdef NEOMESH_PETSC4PY
#include <petsc4py/petsc4py.h>
#endif

namespace py = pybind11;

namespace neomesh::python {

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

// JSON (the report's) as Python objects: through the json module, so that numbers, nulls and
// nesting come out exactly as the command line's report file reads back.
py::object to_python(const nlohmann::json& json) {
  // Never destroyed: it would outlive the interpreter.
  static const auto* loads = new py::object(py::module_::import("json").attr("loads"));
  return (*loads)(json.dump());
}

MPI_Comm to_comm(const py::object& comm) {
  if (comm.is_none()) return MPI_COMM_WORLD;
#ifdef NEOMESH_MPI4PY
  if (MPI_Comm* c = PyMPIComm_Get(comm.ptr())) return *c;
  throw py::error_already_set();
#else
  throw Error("comm: this neomesh was built without mpi4py");
#endif
}

InvertedCells inverted_cells(bool allow) {
  return allow ? InvertedCells::Keep : InvertedCells::Refuse;
}

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

// `values` of the first process on every process of `comm`.
template <typename T>
void broadcast(std::vector<T>& values, MPI_Comm comm) {
  std::uint64_t size = values.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm);
  values.resize(size);
  MPI_Bcast(values.data(), static_cast<int>(size * sizeof(T)), MPI_BYTE, 0, comm);
}

// The whole mesh with `fields` by cell number, on every process (collective).
MeshArrays gather_everywhere(const Mesh& mesh, const std::vector<Field>& fields = {}) {
  MeshArrays a = mesh.gather(fields);
  const MPI_Comm comm = mesh.comm();
  broadcast(a.coordinates, comm);
  broadcast(a.cells, comm);
  broadcast(a.types, comm);
  for (Field& f : a.cell_fields) broadcast(f.values, comm);
  return a;
}

py::array_t<double> matrix(const std::vector<double>& values, py::ssize_t columns) {
  py::array_t<double> out({static_cast<py::ssize_t>(values.size()) / columns, columns});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

template <typename T>
py::array_t<T> vector(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// Per-cell fields by cell number, as {name: array} (n or n × components).
py::dict field_dict(const std::vector<Field>& fields) {
  py::dict out;
  for (const Field& f : fields)
    out[py::str(f.name)] =
        f.components == 1 ? py::array(vector(f.values)) : py::array(matrix(f.values, f.components));
  return out;
}

// The file's groups and data (MeshArrays' second part) on every process, as a dict for
// neomesh._meshio.to_meshio (collective).
py::dict file_data(const Mesh& mesh) {
  MeshArrays a = mesh.gather();
  const MPI_Comm comm = mesh.comm();
  // Names and shapes travel as JSON text, the values as arrays.
  nlohmann::json header = {{"groups", nlohmann::json::array()},
                           {"point_data", nlohmann::json::array()},
                           {"cell_data", nlohmann::json::array()}};
  for (const MeshGroup& g : a.groups) header["groups"].push_back({g.dim, g.tag, g.name});
  for (const char* key : {"point_data", "cell_data"})
    for (const Field& f : key == std::string("point_data") ? a.point_data : a.cell_data)
      header[key].push_back({f.name, f.components});
  const std::string text = header.dump();
  std::vector<char> bytes(text.begin(), text.end());
  broadcast(bytes, comm);
  header = nlohmann::json::parse(bytes.begin(), bytes.end());
  broadcast(a.cell_tags, comm);
  broadcast(a.entity_offsets, comm);
  broadcast(a.entity_vertices, comm);
  broadcast(a.entity_tags, comm);
  py::dict out;
  out["groups"] = to_python(header["groups"]);
  out["cell_tags"] = vector(a.cell_tags);
  out["entity_offsets"] = vector(a.entity_offsets);
  out["entity_vertices"] = vector(a.entity_vertices);
  out["entity_tags"] = vector(a.entity_tags);
  for (auto [key, data] :
       {std::pair("point_data", &a.point_data), std::pair("cell_data", &a.cell_data)}) {
    data->resize(header[key].size());
    py::dict arrays;
    for (std::size_t i = 0; i < data->size(); ++i) {
      Field& f = (*data)[i];
      f.name = header[key][i][0];
      f.components = header[key][i][1];
      broadcast(f.values, comm);
      arrays[py::str(f.name)] = f.components == 1 ? py::array(vector(f.values))
                                                  : py::array(matrix(f.values, f.components));
    }
    out[key] = arrays;
  }
  return out;
}

// The coordinates of every vertex (n × coordinate_dim, by vertex number), on every process.
py::array_t<double> points(const Mesh& mesh) {
  const MeshArrays a = gather_everywhere(mesh);
  return matrix(a.coordinates, a.coordinate_dim);
}

// Moves this process' vertices to their rows of `points` (n × coordinate_dim, by vertex
// number).
void set_points(Mesh& mesh, const Points& points) {
  const int d = mesh.coordinate_dim();
  if (points.ndim() != 2 || points.shape(1) != d || points.shape(0) != mesh.num_vertices())
    throw Error(
        fmt::format("points: expected an array of {} × {} coordinates", mesh.num_vertices(), d));
  const std::vector<std::int64_t> numbers = mesh.vertex_numbers();
  std::vector<double> owned(numbers.size() * d);
  const double* all = points.data();
  for (std::size_t i = 0; i < numbers.size(); ++i)
    for (int j = 0; j < d; ++j) owned[i * d + j] = all[numbers[i] * d + j];
  mesh.set_coordinates(owned);
}

Mesh from_arrays(const Points& points, const py::array_t<std::int64_t>& cells,
                 const py::array_t<std::uint8_t>& types, const py::object& comm,
                 const std::string& name, bool allow_inverted) {
  if (points.ndim() != 2) throw Error("points: expected an array of n × dim coordinates");
  const MPI_Comm c = to_comm(comm);
  const int dim = static_cast<int>(points.shape(1));
  const bool root = rank_of(c) == 0;  // the others pass nothing: from_arrays distributes
  std::vector<CellType> cell_types;
  if (root)
    for (py::ssize_t i = 0; i < types.size(); ++i) {
      if (types.data()[i] >= kNumCellTypes) throw Error("cells: unknown cell type");
      cell_types.push_back(static_cast<CellType>(types.data()[i]));
    }
  const std::span<const double> coordinates(points.data(), root ? points.size() : 0);
  const std::span<const std::int64_t> vertices(cells.data(), root ? cells.size() : 0);
  py::gil_scoped_release release;
  return Mesh::from_arrays(c, dim, coordinates, vertices, cell_types, name,
                           inverted_cells(allow_inverted));
}

// What a call of the Optimizer sees of Python: the progress callback, and Ctrl-C. Both run
// with the GIL, once per iteration; an exception they raise goes through the C++ code to the
// caller. A handle, not an object: the C++ code copies the observer without the GIL, and
// `progress` outlives the call.
Observer python_observer(const py::object& progress) {
  Observer observer;
  observer.iteration = [progress = py::handle(progress)](const IterationRecord& row) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!progress.is_none()) progress(to_python(to_json(row)));
  };
  return observer;
}

// A Python function d(points) on an (n, dim) array of the cells' centroids, n distances back.
SizeField function_field(py::function f) {
  const std::string description =
      fmt::format("|d| of the Python function {}",
                  py::str(py::getattr(f, "__qualname__", py::repr(f))).cast<std::string>());
  // The C++ code copies the field without the GIL: copies share the function through a
  // shared_ptr, and the last one lets it go with the GIL.
  const std::shared_ptr<py::function> held(new py::function(std::move(f)), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
  return SizeField::distances(
      [held](std::span<const double> points, std::span<double> d) {
        py::gil_scoped_acquire gil;
        const py::function& f = *held;
        const py::ssize_t n = static_cast<py::ssize_t>(d.size());
        const py::ssize_t dim = n > 0 ? static_cast<py::ssize_t>(points.size()) / n : 0;
        py::array_t<double> at({n, dim});
        std::copy(points.begin(), points.end(), at.mutable_data());
        at.attr("setflags")(py::arg("write") = false);
        const auto got = Points::ensure(f(at));
        if (!got) throw py::error_already_set();
        if (got.size() != n)
          throw Error(fmt::format("the size field function returned {} values for {} points",
                                  got.size(), n));
        std::copy_n(got.data(), n, d.begin());
      },
      description);
}

SizeField to_size_field(const py::object& field) {
  if (py::isinstance<SizeField>(field)) return field.cast<SizeField>();
  if (py::isinstance<py::str>(field)) return SizeField::level_set(field.cast<std::string>());
  if (py::isinstance<LevelSet>(field)) {
    const LevelSet& phi = field.cast<const LevelSet&>();
    SizeField f = SizeField::level_set(phi.expression());
    f.set_time(phi.time());
    return f;
  }
  if (PyCallable_Check(field.ptr())) return function_field(field.cast<py::function>());
  throw py::type_error(
      "size_field: expected a callable d(points), an expression string, a neomesh.SizeField or "
      "a neomesh.LevelSet");
}

// A Python Optimizer: the C++ one, and the mesh it moves.
struct PyOptimizer {
  explicit PyOptimizer(Mesh& m) : mesh(m), optimizer(m) {}
  Mesh& mesh;
  Optimizer optimizer;

  // Runs `call` without the GIL, on the command line's thread count (the same mesh to the last
  // bit), restored afterwards; on an exception (a Python one from a callback, Ctrl-C, an Error)
  // the mesh keeps the coordinates it had before the call.
  template <typename Call>
  Result run(const py::object& progress, Call call) {
    const std::vector<double> before = mesh.coordinates();
    const Observer observer = python_observer(progress);
    const int threads = omp_get_max_threads();
    if (const int t = run_thread_count(mesh); t > 0) omp_set_num_threads(t);
    try {
      py::gil_scoped_release release;
      Result result = call(observer);
      omp_set_num_threads(threads);
      return result;
    } catch (...) {
      omp_set_num_threads(threads);
      mesh.set_coordinates(before);
      optimizer.forget_warm_start();
      throw;
    }
  }

  py::object smooth(const py::object& progress, const py::kwargs& kwargs) {
    const SmoothOptions options = keyword_options<SmoothOptions>(kwargs, "smooth");
    const Result result =
        run(progress, [&](const Observer& o) { return optimizer.smooth(options, o); });
    nlohmann::json report = result_report(result, mesh);
    report.update(smooth_report(options, result));
    return to_python(report);
  }

  py::object adapt(const py::object& size_field, const py::object& fit, const py::object& progress,
                   const py::kwargs& kwargs) {
    const AdaptOptions options = keyword_options<AdaptOptions>(kwargs, "adapt");
    const SizeField field = to_size_field(size_field);
    std::optional<LevelSet> phi;
    if (!fit.is_none() && !(py::isinstance<py::bool_>(fit) && !fit.cast<bool>())) {
      if (py::isinstance<LevelSet>(fit))
        phi = fit.cast<LevelSet>();
      else if (py::isinstance<py::bool_>(fit) && py::isinstance<LevelSet>(size_field))
        phi = size_field.cast<LevelSet>();
      else if (py::isinstance<py::bool_>(fit) && py::isinstance<py::str>(size_field))
        phi = LevelSet::expression(size_field.cast<std::string>());
      else
        throw py::type_error(
            "fit: expected a neomesh.LevelSet, or True with a level set (expression or LevelSet) "
            "as the size field");
    }
    const Result result = run(progress, [&](const Observer& o) {
      return phi ? optimizer.adapt(field, *phi, options, o) : optimizer.adapt(field, options, o);
    });
    nlohmann::json report = result_report(result, mesh);
    report.update(adapt_report(options, result, field.description()));
    return to_python(report);
  }
};

py::object option_descriptions(const std::string& task) {
  if (task == "smooth") return to_python(option_list<SmoothOptions>());
  if (task == "adapt") return to_python(option_list<AdaptOptions>());
  throw py::value_error("task: expected 'smooth' or 'adapt'");
}

}  // namespace

}  // namespace neomesh::python

using namespace neomesh;
using namespace neomesh::python;

PYBIND11_MODULE(_neomesh, m) {
  m.doc() = "neomesh's compiled core; use the package neomesh.";
  m.attr("__version__") = NEOMESH_VERSION_STRING;

  // PETSc and MPI: petsc4py's and mpi4py's when they are installed (they then own the
  // initialization and finalization), otherwise a Session of our own until the interpreter exits.
  bool petsc_up = false;
#ifdef NEOMESH_MPI4PY
  if (import_mpi4py() < 0) throw py::error_already_set();
#endif
#ifdef NEOMESH_PETSC4PY
  if (import_petsc4py() < 0) throw py::error_already_set();
  petsc_up = true;
#endif
  if (!petsc_up) {
    auto* session = new Session();
    py::module_::import("atexit").attr("register")(py::cpp_function([session] { delete session; }));
  }

  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<OptionError> option_error(m, "OptionError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const KeywordError& e) {
      option_error(e.what());
    } catch (const OptionError& e) {
      option_error(python_message(e.what()).c_str());
    } catch (const Error& e) {
      error(python_message(e.what()).c_str());
    }
  });

  m.def("_options", &option_descriptions, py::arg("task"),
        "The options of 'smooth' or 'adapt' from the option table: name, field, default, "
        "thesis, help, group, type, choices.");

  py::class_<SizeField>(m, "SizeField",
                        "Where cells should be small: the distance d to a surface (desired "
                        "relative volume floor + |d|^power), a metric, or per-cell values.")
      .def_static(
          "circle",
          [](double cx, double cy, double r) {
            return SizeField::sphere({cx, cy}, r);
          },
          py::arg("cx"), py::arg("cy"), py::arg("r"))
      .def_static(
          "sphere",
          [](double cx, double cy, double cz, double r) {
            return SizeField::sphere({cx, cy, cz}, r);
          },
          py::arg("cx"), py::arg("cy"), py::arg("cz"), py::arg("r"))
      .def_static("plane", &SizeField::plane, py::arg("point"), py::arg("normal"))
      .def_static("box", &SizeField::box, py::arg("lower"), py::arg("upper"))
      .def_static("level_set", &SizeField::level_set, py::arg("expression"),
                  "d = |phi(x, y, z, t)| of a muparser expression")
      .def_static("function", &function_field, py::arg("distance"),
                  "d(points): a Python function on an (n, dim) array of cell centroids, "
                  "returning n distances (one call per evaluation)")
      .def_static("metric", &SizeField::metric, py::arg("entries"),
                  "the metric of the expressions m11, m12, m22 (2D) or m11, m12, m13, m22, m23, "
                  "m33 (3D)")
      .def_static("cell_values", &SizeField::cell_values, py::arg("values"),
                  "relative volumes per cell, by cell number")
      .def_static(
          "read_cell_values",
          [](const std::string& file) { return SizeField::read_cell_values(file); },
          py::arg("file"),
          "one relative volume per line, in the mesh's cell order (adapt --volumes)")
      .def_static("vertex_metric", &SizeField::vertex_metric, py::arg("mesh"), py::arg("array"),
                  "the metric per vertex in the input file's point data `array` (--metric-data)")
      .def_static(
          "read_vertex_metric",
          [](const Mesh& mesh, const std::string& file) {
            return SizeField::read_vertex_metric(mesh, file);
          },
          py::arg("mesh"), py::arg("file"),
          "one metric per line, in the mesh's vertex order (--metric-file)")
      .def(
          "stretched",
          [](const SizeField& f, double normal, double tangent, double width, double grading) {
            return f.stretched(
                {.normal = normal, .tangent = tangent, .width = width, .grading = grading});
          },
          py::arg("normal"), py::arg("tangent"), py::arg("width"), py::arg("grading") = 4.0)
      .def("set_time", &SizeField::set_time, py::arg("t"))
      .def_property_readonly("anisotropic", &SizeField::anisotropic)
      .def_property_readonly("description", &SizeField::description)
      .def("__repr__",
           [](const SizeField& f) { return "<neomesh.SizeField " + f.description() + ">"; });

  py::class_<LevelSet>(m, "LevelSet",
                       "phi < 0 on one side, phi = 0 the interface that adapt(..., fit=...) "
                       "pulls a chain of edges or surface of faces onto.")
      .def_static(
          "circle",
          [](double cx, double cy, double r) {
            return LevelSet::sphere({cx, cy}, r);
          },
          py::arg("cx"), py::arg("cy"), py::arg("r"))
      .def_static(
          "sphere",
          [](double cx, double cy, double cz, double r) {
            return LevelSet::sphere({cx, cy, cz}, r);
          },
          py::arg("cx"), py::arg("cy"), py::arg("cz"), py::arg("r"))
      .def_static("plane", &LevelSet::plane, py::arg("point"), py::arg("normal"))
      .def_static(
          "expression", [](const std::string& phi) { return LevelSet::expression(phi); },
          py::arg("phi"), "phi(x, y, z, t) as a muparser expression, best a signed distance")
      .def("set_time", &LevelSet::set_time, py::arg("t"))
      .def_property_readonly("time", &LevelSet::time)
      .def_property_readonly("expression_text", [](const LevelSet& l) { return l.expression(); })
      .def("__repr__",
           [](const LevelSet& l) { return "<neomesh.LevelSet " + l.expression() + " = 0>"; });

  py::class_<Mesh>(m, "Mesh", py::dynamic_attr(),
                   "A mesh whose vertices neomesh moves; the connectivity never changes.")
      .def_static(
          "read",
          [](const py::object& path, const py::object& comm, bool allow_inverted) {
            // A FEAT3 mesh with its chart files comes as a list of paths.
            std::vector<std::filesystem::path> paths;
            if (py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__"))
              paths.emplace_back(py::str(path).cast<std::string>());
            else
              for (const py::handle p : path) paths.emplace_back(py::str(p).cast<std::string>());
            const MPI_Comm c = to_comm(comm);
            py::gil_scoped_release release;
            return Mesh::read(paths, c, inverted_cells(allow_inverted));
          },
          py::arg("path"), py::arg("comm") = py::none(), py::arg("allow_inverted") = true,
          "Reads a mesh file (.msh, .vtu, .vtk, .mesh, .exo, .cgns, FEAT3 .xml; a list of paths: a "
          "FEAT3 mesh and its chart files) and distributes it over comm (an mpi4py communicator; "
          "default: COMM_WORLD). Inverted cells are kept "
          "for smooth() to untangle unless allow_inverted is False.")
      .def_static("_from_arrays", &from_arrays, py::arg("points"), py::arg("cells"),
                  py::arg("types"), py::arg("comm"), py::arg("name"), py::arg("allow_inverted"))
      .def_static(
          "generate",
          [](const std::string& name, int size, double amplitude, unsigned seed, double jitter,
             double rotate_degrees, const py::object& comm) {
            const GenerateOptions options{.name = name,
                                          .size = size,
                                          .amplitude = amplitude,
                                          .seed = seed,
                                          .jitter = jitter,
                                          .rotate_degrees = rotate_degrees};
            const MPI_Comm c = to_comm(comm);
            py::gil_scoped_release release;
            return Mesh::generate(options, c);
          },
          py::arg("name") = "box-quad", py::arg("size") = 4, py::arg("amplitude") = 0.2,
          py::arg("seed") = 1, py::arg("jitter") = 0.0, py::arg("rotate_degrees") = 0.0,
          py::arg("comm") = py::none(),
          "One of the thesis' test meshes (as `neomesh generate`): square-midpoint, "
          "box-quad, box-hex, annulus-tri, ...")
#ifdef NEOMESH_PETSC4PY
      .def_static(
          "from_dm",
          [](py::object dm, const std::string& name, bool allow_inverted) {
            DM d = PyPetscDM_Get(dm.ptr());
            if (!d && PyErr_Occurred()) throw py::error_already_set();
            py::gil_scoped_release release;
            return Mesh::from_dm(d, name, inverted_cells(allow_inverted));
          },
          py::arg("dm"), py::arg("name") = "mesh from a DMPlex", py::arg("allow_inverted") = false,
          "Takes over a petsc4py DMPlex (serial or distributed): its cells and coordinates, "
          "vertices numbered as DMPlexGetVertexNumbering does (vertex_numbers). The DM is not "
          "changed.")
      .def_property_readonly(
          "dm",
          [](const Mesh& mesh) {
            return py::reinterpret_steal<py::object>(PyPetscDM_New(mesh.dm()));
          },
          "neomesh's own distributed DMPlex (petsc4py), at the current coordinates")
#endif
#ifdef NEOMESH_MPI4PY
      .def_property_readonly(
          "comm",
          [](const Mesh& mesh) {
            return py::reinterpret_steal<py::object>(PyMPIComm_New(mesh.comm()));
          },
          "the mpi4py communicator the mesh is distributed over")
#endif
      .def_property_readonly("dim", &Mesh::dim, "the dimension of the cells")
      .def_property_readonly("coordinate_dim", &Mesh::coordinate_dim,
                             "coordinates per vertex: dim, or 3 for a surface mesh")
      .def_property_readonly("name", &Mesh::name)
      .def_property_readonly("num_cells", &Mesh::num_cells)
      .def_property_readonly("num_vertices", &Mesh::num_vertices)
      .def_property(
          "points", &points, &set_points,
          "every vertex's coordinates (num_vertices × coordinate_dim, by vertex number) on every "
          "process; assigning moves the vertices (collective)")
      .def(
          "_arrays",
          [](const Mesh& mesh) {
            const MeshArrays a = gather_everywhere(mesh);
            std::vector<std::uint8_t> types;
            for (CellType t : a.types) types.push_back(static_cast<std::uint8_t>(t));
            return py::make_tuple(matrix(a.coordinates, a.coordinate_dim), vector(a.cells),
                                  vector(types));
          },
          "points, flat cell vertices and cell types, on every process (collective)")
      .def("_file_data", &file_data,
           "the file's groups, entities in groups and data, on every process (collective)")
      .def_property_readonly(
          "vertex_numbers", [](const Mesh& mesh) { return vector(mesh.vertex_numbers()); },
          "the vertices this process owns, by number")
      .def_property_readonly(
          "local_points",
          [](const Mesh& mesh) { return matrix(mesh.coordinates(), mesh.coordinate_dim()); },
          "the coordinates of vertex_numbers, on this process")
      .def(
          "quality",
          [](const Mesh& mesh) {
            return field_dict(gather_everywhere(mesh, mesh.quality_by_cell()).cell_fields);
          },
          "Per cell, by cell number: volume, scaled_jacobian, min_angle, max_angle, edge_ratio, "
          "inverse_mean_ratio, inverted (collective).")
      .def(
          "quality_summary", [](const Mesh& mesh) { return to_python(to_json(mesh.quality())); },
          "Cell counts and min/mean/max of each metric, as the report's quality section.")
      .def(
          "write",
          [](const Mesh& mesh, const std::string& path) {
            py::gil_scoped_release release;
            mesh.write(path);
          },
          py::arg("path"),
          "Writes the mesh (.msh keeps the input's groups; .vtu with the cell quality fields) "
          "atomically (collective).")
      .def("__repr__", [](const Mesh& mesh) {
        return fmt::format("<neomesh.Mesh {}: {}D, {} cells, {} vertices>", mesh.name(), mesh.dim(),
                           mesh.num_cells(), mesh.num_vertices());
      });

  py::class_<PyOptimizer>(m, "_Optimizer")
      .def(py::init<Mesh&>(), py::arg("mesh"), py::keep_alive<1, 2>())
      .def("smooth", &PyOptimizer::smooth, py::arg("progress") = py::none())
      .def("adapt", &PyOptimizer::adapt, py::arg("size_field"), py::arg("fit") = py::none(),
           py::arg("progress") = py::none())
      .def("forget_warm_start", [](PyOptimizer& o) { o.optimizer.forget_warm_start(); })
      .def(
          "write",
          [](const PyOptimizer& o, const std::string& path) {
            py::gil_scoped_release release;
            o.mesh.write(path, o.optimizer.cell_fields(), o.optimizer.vertex_fields(),
                         o.optimizer.facet_groups());
          },
          py::arg("path"))
      .def("cell_fields", [](const PyOptimizer& o) {
        return field_dict(gather_everywhere(o.mesh, o.optimizer.cell_fields()).cell_fields);
      });
}
