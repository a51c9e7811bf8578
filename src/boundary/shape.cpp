#include "boundary/shape.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <vector>

#include <muParser.h>
#include <Eigen/Dense>

#include "core/error.hpp"

namespace neomesh {

namespace {

std::string numbers(const Point& p, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += fmt::format("{}{:g}", i ? "," : "", p[i]);
  return s;
}

class Plane final : public Surface {
 public:
  Plane(const Point& point, const Point& normal) : point_(point), normal_(normal.normalized()) {}
  Point closest_point(const Point& p) const override {
    return p - normal_.dot(p - point_) * normal_;
  }
  Point normal(const Point&) const override { return normal_; }
  Matrix3 shape_operator(const Point&) const override { return Matrix3::Zero(); }
  bool is_flat() const override { return true; }
  std::string describe() const override {
    return fmt::format("plane through ({}) with normal ({})", numbers(point_, 3),
                       numbers(normal_, 3));
  }

 private:
  Point point_, normal_;
};

class Sphere final : public Surface {
 public:
  Sphere(const Point& centre, double radius, int dim)
      : centre_(centre), radius_(radius), dim_(dim) {}
  Point closest_point(const Point& p) const override {
    const Point r = p - centre_;
    const double n = r.norm();
    return n > 0.0 ? Point(centre_ + (radius_ / n) * r) : p;  // the centre: no closest point
  }
  Point normal(const Point& q) const override { return (q - centre_).normalized(); }
  Matrix3 shape_operator(const Point& q) const override {
    const Point n = normal(q);
    Matrix3 s = (Matrix3::Identity() - n * n.transpose()) / radius_;
    if (dim_ == 2) s(2, 2) = 0.0;  // a circle: curved in the plane only
    return s;
  }
  std::string describe() const override {
    return fmt::format("{} about ({}) of radius {:g}", dim_ == 2 ? "circle" : "sphere",
                       numbers(centre_, dim_), radius_);
  }

 private:
  Point centre_;
  double radius_;
  int dim_;
};

class Cylinder final : public Surface {
 public:
  Cylinder(const Point& point, const Point& axis, double radius)
      : point_(point), axis_(axis.normalized()), radius_(radius) {}
  Point closest_point(const Point& p) const override {
    const Point foot = point_ + axis_.dot(p - point_) * axis_;
    const Point r = p - foot;
    const double n = r.norm();
    return n > 0.0 ? Point(foot + (radius_ / n) * r) : p;
  }
  Point normal(const Point& q) const override {
    const Point r = q - point_;
    return (r - axis_.dot(r) * axis_).normalized();
  }
  Matrix3 shape_operator(const Point& q) const override {
    const Point n = normal(q);
    return (Matrix3::Identity() - n * n.transpose() - axis_ * axis_.transpose()) / radius_;
  }
  std::string describe() const override {
    return fmt::format("cylinder about the axis through ({}) along ({}) of radius {:g}",
                       numbers(point_, 3), numbers(axis_, 3), radius_);
  }

 private:
  Point point_, axis_;
  double radius_;
};

// The zero set of φ.
class LevelSet final : public Surface {
 public:
  LevelSet(const std::string& expression, int dim) : phi_(expression, dim) {}
  Point closest_point(const Point& p) const override { return phi_.to_level(p); }
  Point normal(const Point& q) const override { return phi_.gradient(q).normalized(); }
  Matrix3 shape_operator(const Point& q) const override { return phi_.shape_operator(q); }
  std::string describe() const override {
    return fmt::format("level set {} = 0", phi_.expression());
  }

 private:
  LevelSetFunction phi_;
};

class Line final : public Curve {
 public:
  Line(const Point& point, const Point& direction)
      : point_(point), direction_(direction.normalized()) {}
  Point closest_point(const Point& p) const override {
    return point_ + direction_.dot(p - point_) * direction_;
  }
  Point tangent(const Point&) const override { return direction_; }
  Point curvature(const Point&) const override { return Point::Zero(); }
  bool is_straight() const override { return true; }

 private:
  Point point_, direction_;
};

// FEAT3's Bezier chart: the closest point of each segment by Newton's method on
// f(t) = B'(t)·(B(t) − p) = 0, started at the best of kBezierSamples + 1 samples (a segment of
// degree ≤ 5 bends too little for two local minima between neighbouring samples); segments
// whose control polygon's box is farther than the best point so far are skipped.
class BezierCurve final : public Surface {
 public:
  BezierCurve(std::vector<Point> controls, std::vector<int> starts) {
    if (starts.size() < 2) fail("a Bezier curve needs at least two points");
    for (std::size_t i = 0; i + 1 < starts.size(); ++i) {
      const int n = starts[i + 1] - starts[i];
      if (n < 1 || n > kMaxDegree || starts[i + 1] >= static_cast<int>(controls.size()))
        fail("Bezier segment {} has degree {}; expected 1 to {}", i, n, kMaxDegree);
      Segment s;
      s.control.assign(controls.begin() + starts[i], controls.begin() + starts[i + 1] + 1);
      s.lo = s.hi = s.control[0];
      for (const Point& c : s.control) {
        s.lo = s.lo.cwiseMin(c);
        s.hi = s.hi.cwiseMax(c);
      }
      segments_.push_back(std::move(s));
    }
  }
  Point closest_point(const Point& p) const override {
    const Hit h = closest(p);
    return value(segments_[h.segment], h.t, 0);
  }
  Point normal(const Point& q) const override {
    const Point t = unit_tangent(closest(q));
    return {t.y(), -t.x(), 0.0};
  }
  // For the normal (T_y, −T_x): dn/ds is dT/ds turned the same way, and S = (T · dn/ds) T Tᵀ.
  Matrix3 shape_operator(const Point& q) const override {
    const Hit h = closest(q);
    const Segment& s = segments_[h.segment];
    const Point d1 = value(s, h.t, 1), d2 = value(s, h.t, 2);
    const double speed = d1.norm();
    if (!(speed > 0)) return Matrix3::Zero();
    const Point t = d1 / speed;
    const Point bend = (d2 - d2.dot(t) * t) / (speed * speed);  // dT/ds
    const double curvature = t.x() * bend.y() - t.y() * bend.x();
    return curvature * t * t.transpose();
  }
  std::string describe() const override {
    return fmt::format("Bezier curve of {} segments (exact)", segments_.size());
  }

 private:
  static constexpr int kMaxDegree = 5;
  static constexpr int kBezierSamples = 16;
  static constexpr int kNewtonSteps = 50;
  struct Segment {
    std::vector<Point> control;
    Point lo, hi;  // box of the control polygon, which holds the segment
  };
  struct Hit {
    int segment = 0;
    double t = 0.0;
    double distance = std::numeric_limits<double>::infinity();
  };

  // The k-th derivative (k ≤ 2) of the segment at t, by de Casteljau on the differenced
  // control points.
  static Point value(const Segment& s, double t, int k) {
    std::vector<Point> c = s.control;
    for (int j = 0; j < k; ++j) {
      const int n = static_cast<int>(c.size()) - 1;
      if (n == 0) return Point::Zero();
      for (int i = 0; i < n; ++i) c[i] = n * (c[i + 1] - c[i]);
      c.pop_back();
    }
    for (std::size_t n = c.size(); n > 1; --n)
      for (std::size_t i = 0; i + 1 < n; ++i) c[i] = (1 - t) * c[i] + t * c[i + 1];
    return c[0];
  }

  Point unit_tangent(const Hit& h) const {
    const Segment& s = segments_[h.segment];
    Point d = value(s, h.t, 1);
    if (!(d.norm() > 0)) d = s.control.back() - s.control.front();  // a cusp: the chord
    return d.normalized();
  }

  static Hit closest_on(const Segment& s, const Point& p) {
    Hit best;
    for (int k = 0; k <= kBezierSamples; ++k) {
      const double t = static_cast<double>(k) / kBezierSamples;
      const double d = (value(s, t, 0) - p).norm();
      if (d < best.distance) best.t = t, best.distance = d;
    }
    double t = best.t;
    for (int it = 0; it < kNewtonSteps; ++it) {
      const Point r = value(s, t, 0) - p, d1 = value(s, t, 1), d2 = value(s, t, 2);
      const double f = d1.dot(r), df = d2.dot(r) + d1.dot(d1);
      if (!(df > 0)) break;  // not near a minimum: keep the sample
      const double next = std::clamp(t - f / df, 0.0, 1.0);
      const bool done = std::abs(next - t) <= 1e-16;
      t = next;
      if (done) break;
    }
    const double d = (value(s, t, 0) - p).norm();
    if (d <= best.distance) best.t = t, best.distance = d;
    return best;
  }

  Hit closest(const Point& p) const {
    Hit best;
    for (int i = 0; i < static_cast<int>(segments_.size()); ++i) {
      const Segment& s = segments_[i];
      const Point gap = (s.lo - p).cwiseMax(p - s.hi).cwiseMax(0.0);
      if (gap.norm() > best.distance) continue;
      Hit h = closest_on(s, p);
      if (h.distance < best.distance) {
        h.segment = i;
        best = h;
      }
    }
    return best;
  }

  std::vector<Segment> segments_;
};

// A 2D curve swept along z: its closest point, normal and bending in the (x, y) plane, z kept;
// all in the local frame, local = Rᵀ (world − offset) + origin.
class Extrusion final : public Surface {
 public:
  Extrusion(std::unique_ptr<Surface> curve, const Matrix3& rotation, const Point& origin,
            const Point& offset)
      : curve_(std::move(curve)), rotation_(rotation), origin_(origin), offset_(offset) {}
  Point closest_point(const Point& p) const override {
    const Point local = to_local(p);
    Point q = curve_->closest_point(flat(local));
    q.z() = local.z();
    return to_world(q);
  }
  Point normal(const Point& q) const override {
    return rotation_ * flat(curve_->normal(flat(to_local(q))));
  }
  Matrix3 shape_operator(const Point& q) const override {
    Matrix3 s = curve_->shape_operator(flat(to_local(q)));
    s.row(2).setZero();
    s.col(2).setZero();
    return rotation_ * s * rotation_.transpose();
  }
  std::string describe() const override {
    return fmt::format("{} extruded along z", curve_->describe());
  }

 private:
  static Point flat(const Point& p) { return {p.x(), p.y(), 0.0}; }
  Point to_local(const Point& p) const { return rotation_.transpose() * (p - offset_) + origin_; }
  Point to_world(const Point& p) const { return rotation_ * (p - origin_) + offset_; }
  std::unique_ptr<Surface> curve_;
  Matrix3 rotation_;
  Point origin_, offset_;
};

// Newton's method on the two surfaces' tangent planes: each step moves to the point of the
// planes' intersection line closest to the current point.
class Intersection final : public Curve {
 public:
  Intersection(const Surface& a, const Surface& b) : a_(a), b_(b) {}
  Point closest_point(const Point& p) const override {
    Point y = p;
    for (int it = 0; it < 30; ++it) {
      const Point ca = a_.closest_point(y), cb = b_.closest_point(y);
      const Point na = a_.normal(ca), nb = b_.normal(cb);
      const double c = na.dot(nb);
      const double det = 1.0 - c * c;
      if (!(det > 1e-12)) return ca;  // tangent surfaces: no well-defined ridge
      const double ra = na.dot(y - ca), rb = nb.dot(y - cb);
      const double la = (ra - c * rb) / det, lb = (rb - c * ra) / det;
      const Point step = la * na + lb * nb;
      y -= step;
      if (step.norm() <= 1e-15 * (1.0 + y.norm())) break;
    }
    return y;
  }
  Point tangent(const Point& q) const override {
    return a_.normal(a_.closest_point(q)).cross(b_.normal(b_.closest_point(q))).normalized();
  }
  // dt/ds by central differences along the curve.
  Point curvature(const Point& q) const override {
    const Point t = tangent(q);
    const double h = 1e-4 * (1.0 + q.norm());
    const Point ahead = closest_point(q + h * t), behind = closest_point(q - h * t);
    Point t1 = tangent(ahead), t0 = tangent(behind);
    if (t1.dot(t) < 0) t1 = -t1;
    if (t0.dot(t) < 0) t0 = -t0;
    return (t1 - t0) / (ahead - behind).norm();
  }

 private:
  const Surface& a_;
  const Surface& b_;
};

// The comma-separated numbers of a shape spec; throws unless there are `count` finite ones.
std::vector<double> parse_numbers(std::string_view spec, std::string_view list, std::size_t count,
                                  std::string_view expected) {
  std::vector<double> values;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view field = list.substr(start, comma - start);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (field.empty() || ec != std::errc() || end != field.data() + field.size() ||
        !std::isfinite(v))
      fail("boundary.shapes: '{}': expected {}", spec, expected);
    values.push_back(v);
    start = comma + 1;
  }
  if (values.size() != count) fail("boundary.shapes: '{}': expected {}", spec, expected);
  return values;
}

}  // namespace

// The parser keeps the addresses of its variables: both live together on the heap.
struct LevelSetFunction::Impl {
  std::string expression;
  int dim;
  double x[4] = {0, 0, 0, 0};  // x, y, z, t
  mu::Parser parser;
};

LevelSetFunction::LevelSetFunction(const std::string& expression, int dim, bool with_time)
    : impl_(std::make_unique<Impl>()) {
  impl_->expression = expression;
  impl_->dim = dim;
  try {
    impl_->parser.DefineVar("x", &impl_->x[0]);
    impl_->parser.DefineVar("y", &impl_->x[1]);
    impl_->parser.DefineVar("z", &impl_->x[2]);
    if (with_time) impl_->parser.DefineVar("t", &impl_->x[3]);
    impl_->parser.SetExpr(expression);
    impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    fail("level set '{}': {}", expression, e.GetMsg());
  }
}
LevelSetFunction::~LevelSetFunction() = default;
LevelSetFunction::LevelSetFunction(LevelSetFunction&&) noexcept = default;

void LevelSetFunction::set_time(double t) {
  impl_->x[3] = t;
}

const std::string& LevelSetFunction::expression() const {
  return impl_->expression;
}

double LevelSetFunction::value(const Point& p) const {
  for (int i = 0; i < 3; ++i) impl_->x[i] = i < impl_->dim ? p[i] : 0.0;
  try {
    return impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    fail("level set '{}': {}", impl_->expression, e.GetMsg());
  }
}

Point LevelSetFunction::gradient(const Point& p) const {
  Point g = Point::Zero();
  const double h = 1e-6 * (1.0 + p.norm());
  for (int i = 0; i < impl_->dim; ++i) {
    Point a = p, b = p;
    a[i] += h;
    b[i] -= h;
    g[i] = (value(a) - value(b)) / (2 * h);
  }
  return g;
}

// Newton steps along ∇φ: the foot of the gradient flow, the closest point to first order.
Point LevelSetFunction::to_level(const Point& p, double level) const {
  Point q = p;
  for (int it = 0; it < 50; ++it) {
    const double phi = value(q) - level;
    const Point g = gradient(q);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0.0)) break;
    const Point step = (phi / g2) * g;
    q -= step;
    if (step.norm() <= 1e-15 * (1.0 + q.norm())) break;
  }
  return q;
}

// ∇(∇φ/|∇φ|) = P ∇²φ P / |∇φ|, ∇²φ by central differences of ∇φ.
Matrix3 LevelSetFunction::shape_operator(const Point& q) const {
  const Point g = gradient(q);
  const double norm = g.norm();
  if (!(norm > 0)) return Matrix3::Zero();
  Matrix3 hessian = Matrix3::Zero();
  const double h = 1e-4 * (1.0 + q.norm());
  for (int i = 0; i < impl_->dim; ++i) {
    Point a = q, b = q;
    a[i] += h;
    b[i] -= h;
    hessian.col(i) = (gradient(a) - gradient(b)) / (2 * h);
  }
  const Point n = g / norm;
  const Matrix3 p = Matrix3::Identity() - n * n.transpose();
  return p * (0.5 * (hessian + hessian.transpose())) * p / norm;
}

std::unique_ptr<Surface> make_plane(const Point& point, const Point& normal) {
  return std::make_unique<Plane>(point, normal);
}
std::unique_ptr<Surface> make_sphere(const Point& centre, double radius, int dim) {
  return std::make_unique<Sphere>(centre, radius, dim);
}
std::unique_ptr<Surface> make_cylinder(const Point& point, const Point& axis, double radius) {
  return std::make_unique<Cylinder>(point, axis, radius);
}
std::unique_ptr<Surface> make_level_set(const std::string& expression, int dim) {
  return std::make_unique<LevelSet>(expression, dim);
}
std::unique_ptr<Surface> make_bezier(std::vector<Point> controls, std::vector<int> starts) {
  return std::make_unique<BezierCurve>(std::move(controls), std::move(starts));
}
std::unique_ptr<Surface> make_extrusion(std::unique_ptr<Surface> curve, const Matrix3& rotation,
                                        const Point& origin, const Point& offset) {
  return std::make_unique<Extrusion>(std::move(curve), rotation, origin, offset);
}
std::unique_ptr<Curve> make_line(const Point& point, const Point& direction) {
  return std::make_unique<Line>(point, direction);
}
std::unique_ptr<Curve> make_intersection(const Surface& a, const Surface& b) {
  return std::make_unique<Intersection>(a, b);
}

std::unique_ptr<Surface> parse_shape(std::string_view spec, int dim) {
  const auto colon = spec.find(':');
  if (colon == std::string_view::npos)
    fail(
        "boundary.shapes: '{}': expected KIND:PARAMETERS (circle, sphere, line, plane, cylinder or "
        "levelset)",
        spec);
  const std::string_view kind = spec.substr(0, colon), rest = spec.substr(colon + 1);
  auto need_dim = [&](int d) {
    if (dim != d)
      fail("boundary.shapes: '{}': a {} needs a {}D mesh, this one is {}D", spec, kind, d, dim);
  };
  if (kind == "circle") {
    need_dim(2);
    const auto v = parse_numbers(spec, rest, 3, "circle:cx,cy,r");
    if (!(v[2] > 0)) fail("boundary.shapes: '{}': the radius must be positive", spec);
    return make_sphere({v[0], v[1], 0.0}, v[2], 2);
  }
  if (kind == "sphere") {
    need_dim(3);
    const auto v = parse_numbers(spec, rest, 4, "sphere:cx,cy,cz,r");
    if (!(v[3] > 0)) fail("boundary.shapes: '{}': the radius must be positive", spec);
    return make_sphere({v[0], v[1], v[2]}, v[3], 3);
  }
  if (kind == "line") {
    need_dim(2);
    const auto v = parse_numbers(spec, rest, 4, "line:px,py,nx,ny (a point and the normal)");
    const Point n(v[2], v[3], 0.0);
    if (!(n.norm() > 0)) fail("boundary.shapes: '{}': the normal must not be zero", spec);
    return make_plane({v[0], v[1], 0.0}, n);
  }
  if (kind == "plane") {
    need_dim(3);
    const auto v = parse_numbers(spec, rest, 6, "plane:px,py,pz,nx,ny,nz (a point and the normal)");
    const Point n(v[3], v[4], v[5]);
    if (!(n.norm() > 0)) fail("boundary.shapes: '{}': the normal must not be zero", spec);
    return make_plane({v[0], v[1], v[2]}, n);
  }
  if (kind == "cylinder") {
    need_dim(3);
    const auto v = parse_numbers(spec, rest, 7, "cylinder:px,py,pz,ax,ay,az,r");
    const Point axis(v[3], v[4], v[5]);
    if (!(axis.norm() > 0)) fail("boundary.shapes: '{}': the axis must not be zero", spec);
    if (!(v[6] > 0)) fail("boundary.shapes: '{}': the radius must be positive", spec);
    return make_cylinder({v[0], v[1], v[2]}, axis, v[6]);
  }
  if (kind == "levelset") {
    if (rest.empty()) fail("boundary.shapes: '{}': expected levelset:EXPRESSION", spec);
    return make_level_set(std::string(rest), dim);
  }
  fail(
      "boundary.shapes: '{}': unknown shape '{}' (circle, sphere, line, plane, cylinder or "
      "levelset)",
      spec, kind);
}

}  // namespace neomesh
