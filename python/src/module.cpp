// The `octomotion._octomotion` extension: Scene (py_scene.h), plan, the trade study, and the
// library's exceptions as Python classes. NumPy arrays of states are read in place (float64,
// C-contiguous) and checked without the GIL.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include <ompl/util/Console.h>

#include "py_scene.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace octomotion::python {
namespace {

// The exception classes, made once at import and kept for the process's lifetime.
py::object* g_error = nullptr;
py::object* g_file_error = nullptr;
py::object* g_invalid_argument = nullptr;

std::string shapeText(const py::array& a) {
  std::ostringstream s;
  s << '(';
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

// The states of check_many as they are: an (N, dof) float64 C-contiguous array, else TypeError
// (not an array, another dtype) or ValueError (shape, layout) naming what was given.
py::array statesArray(const py::object& object, int dof, const char* what) {
  const std::string expected = std::string(what) +
                               ": expected a C-contiguous float64 array of shape (N, " +
                               std::to_string(dof) + ")";
  if (!py::isinstance<py::array>(object)) {
    throw py::type_error(expected + ", got " +
                         std::string(py::str(object.get_type().attr("__name__"))));
  }
  py::array a = py::reinterpret_borrow<py::array>(object);
  if (!a.dtype().equal(py::dtype::of<double>())) {
    throw py::type_error(expected + ", got dtype " + std::string(py::str(a.dtype())) +
                         " (convert with Q.astype(numpy.float64))");
  }
  if (a.ndim() != 2 || a.shape(1) != dof)
    throw py::value_error(expected + ", got shape " + shapeText(a));
  if (!(a.flags() & py::array::c_style)) {
    throw py::value_error(expected + ", got a non-contiguous array of shape " + shapeText(a) +
                          " (use numpy.ascontiguousarray)");
  }
  return a;
}

// One state (any sequence of dof numbers), copied.
std::vector<double> stateArg(const py::object& object, int dof, const char* what) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(what) + ": expected " + std::to_string(dof) + " numbers");
  }
  if (a.ndim() != 1 || a.shape(0) != dof) {
    throw py::value_error(std::string(what) + ": expected shape (" + std::to_string(dof) +
                          ",), got shape " + shapeText(a));
  }
  return std::vector<double>(a.data(), a.data() + dof);
}

// A pose argument: None (identity), a translation (3 numbers) or a 4×4 matrix.
Eigen::Matrix4d poseArg(const py::object& object, const char* what) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (object.is_none()) return m;
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(what) + ": expected a 4x4 matrix or 3 numbers");
  }
  if (a.ndim() == 1 && a.shape(0) == 3) {
    m.topRightCorner<3, 1>() = Eigen::Vector3d(a.data()[0], a.data()[1], a.data()[2]);
    return m;
  }
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw py::value_error(std::string(what) + ": expected a 4x4 matrix or 3 numbers, got shape " +
                          shapeText(a));
  }
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = a.data()[r * 4 + c];
  }
  return m;
}

std::optional<std::vector<double>> optionalState(const py::object& object, int dof,
                                                 const char* what) {
  if (object.is_none()) return std::nullopt;
  return stateArg(object, dof, what);
}

unsigned threadCount(int threads) {
  if (threads < 0) throw py::value_error("check_many: threads must be >= 0 (0: one per core)");
  if (threads == 0) return std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(threads);
}

ShapeArgs shapeArgs(std::optional<std::vector<double>> box, std::optional<double> sphere,
                    std::optional<std::vector<double>> cylinder, std::optional<std::string> mesh,
                    std::optional<std::vector<double>> scale) {
  return ShapeArgs{std::move(box), sphere, std::move(cylinder), std::move(mesh), std::move(scale)};
}

py::object makeExceptionClass(const char* name, py::tuple bases, const char* doc) {
  py::object type = py::module_::import("builtins").attr("type");
  return type(name, bases, py::dict("__module__"_a = "octomotion", "__doc__"_a = doc));
}

}  // namespace
}  // namespace octomotion::python

PYBIND11_MODULE(_octomotion, m) {
  using namespace octomotion::python;
  using octomotion::python::Scene;
  m.doc() = "octomotion's collision checking and planning (see docs/python.md)";
  // OMPL's informational lines would flood an interactive session.
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  g_error = new py::object(makeExceptionClass(
      "Error", py::make_tuple(py::handle(PyExc_RuntimeError)), "Any octomotion failure."));
  g_file_error = new py::object(makeExceptionClass("FileError", py::make_tuple(*g_error),
                                                   "A file that is missing, unreadable or wrong."));
  g_invalid_argument = new py::object(
      makeExceptionClass("InvalidArgument", py::make_tuple(*g_error, py::handle(PyExc_ValueError)),
                         "A value the library does not accept."));
  m.attr("Error") = *g_error;
  m.attr("FileError") = *g_file_error;
  m.attr("InvalidArgument") = *g_invalid_argument;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const octomotion::FileError& e) {
      PyErr_SetString(g_file_error->ptr(), e.what());
    } catch (const octomotion::InvalidArgument& e) {
      PyErr_SetString(g_invalid_argument->ptr(), e.what());
    } catch (const octomotion::Error& e) {
      PyErr_SetString(g_error->ptr(), e.what());
    }
  });

  py::class_<Reason>(m, "Reason", "Why a state is invalid (Scene.explain).")
      .def_readonly("kind", &Reason::kind)
      .def_readonly("link", &Reason::link)
      .def_readonly("other", &Reason::other)
      .def_readonly("exact", &Reason::exact)
      .def_readonly("margin", &Reason::margin)
      .def_readonly("value", &Reason::value)
      .def_readonly("lower", &Reason::lower)
      .def_readonly("upper", &Reason::upper)
      .def_readonly("text", &Reason::text)
      .def("__str__", [](const Reason& r) { return r.text; })
      .def("__repr__",
           [](const Reason& r) { return "<octomotion.Reason " + r.kind + ": " + r.text + ">"; });

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene",
                                            "A loaded scene: robot, environment, checker.")
      .def_property_readonly("dof", &Scene::dof)
      .def_property_readonly("joint_names", &Scene::jointNames)
      .def_property_readonly("free_flying", &Scene::freeFlying)
      .def_property_readonly("checker", &Scene::checkerName)
      .def_property_readonly("resolution", &Scene::resolution)
      .def_property_readonly("path", &Scene::path)
      .def_property_readonly("bounds",
                             [](const Scene& s) {
                               const auto [low, high] = s.bounds();
                               return py::make_tuple(py::array_t<double>(py::cast(low)),
                                                     py::array_t<double>(py::cast(high)));
                             })
      .def_property_readonly("object_names", &Scene::objectNames)
      .def_property_readonly("attached_names", &Scene::attachedNames)
      .def(
          "check",
          [](const Scene& s, const py::object& q) {
            const std::vector<double> v = stateArg(q, s.dof(), "check");
            return s.check(v.data());
          },
          "q"_a)
      .def(
          "check_many",
          [](const Scene& s, const py::object& Q, int threads) {
            const py::array a = statesArray(Q, s.dof(), "check_many");
            const unsigned n = threadCount(threads);
            const std::size_t rows = static_cast<std::size_t>(a.shape(0));
            py::array_t<bool> valid(static_cast<py::ssize_t>(rows));
            const double* data = static_cast<const double*>(a.data());
            auto* out = reinterpret_cast<std::uint8_t*>(valid.mutable_data());
            {
              py::gil_scoped_release release;
              s.checkMany(data, rows, out, n);
            }
            return valid;
          },
          "Q"_a, "threads"_a = 1)
      .def(
          "clearance",
          [](const Scene& s, const py::object& q) {
            const std::vector<double> v = stateArg(q, s.dof(), "clearance");
            return s.clearance(v.data());
          },
          "q"_a)
      .def(
          "explain",
          [](const Scene& s, const py::object& q) {
            const std::vector<double> v = stateArg(q, s.dof(), "explain");
            return s.explain(v.data());
          },
          "q"_a)
      .def(
          "forward_kinematics",
          [](const Scene& s, const py::object& q) {
            const std::vector<double> v = stateArg(q, s.dof(), "forward_kinematics");
            py::dict poses;
            for (const auto& [link, X_WL] : s.forwardKinematics(v.data())) {
              poses[py::str(link)] = py::array_t<double>(py::cast(X_WL));
            }
            return poses;
          },
          "q"_a)
      .def(
          "add_object",
          [](Scene& s, const std::string& name, std::optional<std::vector<double>> box,
             std::optional<double> sphere, std::optional<std::vector<double>> cylinder,
             std::optional<std::string> mesh, std::optional<std::vector<double>> scale,
             const py::object& pose) {
            s.addObject(name, shapeArgs(box, sphere, cylinder, mesh, scale), poseArg(pose, "pose"));
          },
          "name"_a, py::kw_only(), "box"_a = py::none(), "sphere"_a = py::none(),
          "cylinder"_a = py::none(), "mesh"_a = py::none(), "scale"_a = py::none(),
          "pose"_a = py::none())
      .def("remove_object", &Scene::removeObject, "name"_a)
      .def(
          "move_object",
          [](Scene& s, const std::string& name, const py::object& pose) {
            s.moveObject(name, poseArg(pose, "pose"));
          },
          "name"_a, "pose"_a)
      .def(
          "attach_object",
          [](Scene& s, const std::string& name, const std::string& link,
             std::optional<std::vector<double>> box, std::optional<double> sphere,
             std::optional<std::vector<double>> cylinder, std::optional<std::string> mesh,
             std::optional<std::vector<double>> scale, const py::object& pose,
             const std::vector<std::string>& touch_links) {
            s.attachObject(name, link, shapeArgs(box, sphere, cylinder, mesh, scale),
                           poseArg(pose, "pose"), touch_links);
          },
          "name"_a, "link"_a, py::kw_only(), "box"_a = py::none(), "sphere"_a = py::none(),
          "cylinder"_a = py::none(), "mesh"_a = py::none(), "scale"_a = py::none(),
          "pose"_a = py::none(), "touch_links"_a = std::vector<std::string>{})
      .def(
          "detach_object",
          [](Scene& s, const std::string& name, const py::object& leave_at) {
            const auto q = optionalState(leave_at, s.dof(), "detach_object: leave_at");
            s.detachObject(name, q ? &*q : nullptr);
          },
          "name"_a, "leave_at"_a = py::none())
      .def("__repr__", [](const Scene& s) {
        return "<octomotion.Scene " + s.path() + ": " + std::to_string(s.dof()) + " dof, checker " +
               s.checkerName() + ">";
      });

  m.def(
      "_load_scene",
      [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags,
         bool require_free_start_goal, bool fit_universe_to_reach) {
        py::gil_scoped_release release;
        return std::make_shared<Scene>(path, flags, require_free_start_goal, fit_universe_to_reach);
      },
      "path"_a, "flags"_a, "require_free_start_goal"_a, "fit_universe_to_reach"_a);

  m.def(
      "plan",
      [](Scene& s, const std::string& planner, std::optional<double> time,
         std::optional<std::uint64_t> seed, const py::object& start, const py::object& goal,
         double interpolation) -> py::object {
        const auto start_q = optionalState(start, s.dof(), "plan: start");
        const auto goal_q = optionalState(goal, s.dof(), "plan: goal");
        std::size_t states = 0;
        std::vector<double> path;
        {
          py::gil_scoped_release release;
          path = s.plan(planner, time, seed, start_q ? &*start_q : nullptr,
                        goal_q ? &*goal_q : nullptr, interpolation, states);
        }
        if (states == 0) return py::none();
        py::array_t<double> out(
            {static_cast<py::ssize_t>(states), static_cast<py::ssize_t>(s.dof())});
        std::copy(path.begin(), path.end(), out.mutable_data());
        return std::move(out);
      },
      "scene"_a, "planner"_a = "RRTConnect", "time"_a = 1.0, "seed"_a = py::none(),
      "start"_a = py::none(), "goal"_a = py::none(), "interpolation"_a = 0.0);

  m.def(
      "_trade_study",
      [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags) {
        py::gil_scoped_release release;
        return tradeStudy(path, flags);
      },
      "path"_a, "flags"_a);

  m.def(
      "_bench_set",
      [](const std::string& dir, const std::vector<std::string>& checkers, const std::string& robot,
         const std::string& srdf, const std::map<std::string, double>& fixed, std::size_t runs,
         std::size_t limit, double recheck_density, const std::string& log_dir,
         const std::vector<std::pair<std::string, std::string>>& flags) {
        octomotion::tools::ProblemSetOptions options;
        options.dir = dir;
        options.checkers.clear();
        for (const std::string& name : checkers)
          options.checkers.push_back(octomotion::parseCheckerKind(name));
        options.urdf = robot;
        options.srdf = srdf;
        options.fixed = fixed;
        options.runs = runs;
        options.limit = limit;
        options.recheck_density = recheck_density;
        BenchSetResult result;
        {
          py::gil_scoped_release release;
          result = benchSet(std::move(options), flags, log_dir);
        }
        py::list summary;
        for (const octomotion::tools::SetSummary& s : result.summary) {
          summary.append(py::dict(
              "set"_a = s.set, "checker"_a = std::string(octomotion::checkerKindName(s.checker)),
              "resolution"_a = s.resolution, "problems"_a = s.problems, "runs"_a = s.runs,
              "solved"_a = s.solved, "load_errors"_a = s.load_errors,
              "median_seconds"_a = s.median_seconds, "p90_seconds"_a = s.p90_seconds,
              "state_checks"_a = s.state_checks, "motion_checks"_a = s.motion_checks,
              "recheck_states"_a = s.recheck_states, "recheck_colliding"_a = s.recheck_colliding));
        }
        return py::make_tuple(result.runs_csv, summary, result.logs, result.seconds);
      },
      "dir"_a, "checkers"_a, "robot"_a, "srdf"_a, "fixed"_a, "runs"_a, "limit"_a,
      "recheck_density"_a, "log_dir"_a, "flags"_a);
}
