#include <qverify/exact/number_text.hpp>
#include <qverify/scene/json_tree.hpp>
#include <qverify/scene/scene.hpp>

#include <algorithm>
#include <map>
#include <set>

namespace qverify {

namespace {

using Kind = JsonNode::Kind;

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

/// Validating reader: every failure names the file and the JSON path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const { throw InputError(file_, path, what); }

  const JsonNode& object(const JsonNode& n, const std::string& path) const {
    if (n.kind != Kind::object) fail(path, std::string("expected an object, found ") + n.kind_name());
    return n;
  }
  const JsonNode& array(const JsonNode& n, const std::string& path) const {
    if (n.kind != Kind::array) fail(path, std::string("expected an array, found ") + n.kind_name());
    return n;
  }

  /// Unknown keys are errors, except keys starting with "x-".
  void keys(const JsonNode& obj, const std::string& path, std::initializer_list<const char*> allowed) const {
    for (const auto& m : obj.members) {
      if (m.first.rfind("x-", 0) == 0) continue;
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return m.first == a; })) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(join(path, m.first), "unknown key \"" + m.first + "\" (expected one of: " + list + "; or an x- key)");
      }
    }
  }

  const JsonNode& required(const JsonNode& obj, const std::string& path, const char* key) const {
    const JsonNode* n = obj.find(key);
    if (!n) fail(join(path, key), "missing required key \"" + std::string(key) + "\"");
    return *n;
  }

  std::string string(const JsonNode& n, const std::string& path) const {
    if (n.kind != Kind::string) fail(path, std::string("expected a string, found ") + n.kind_name());
    return n.text;
  }

  Num number(const JsonNode& n, const std::string& path) const {
    std::string err;
    std::optional<Rational> v;
    if (n.kind == Kind::number) v = parse_decimal(n.text, err);
    else if (n.kind == Kind::string) v = parse_rational(n.text, err);
    else fail(path, std::string("expected a number (or a decimal or \"p/q\" string), found ") + n.kind_name());
    if (!v) fail(path, err);
    return Num{*v, path, n.text};
  }

  std::vector<Num> numbers(const JsonNode& n, const std::string& path, std::size_t count) const {
    array(n, path);
    if (n.items.size() != count)
      fail(path, "expected " + std::to_string(count) + " numbers, found " + std::to_string(n.items.size()));
    std::vector<Num> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(number(n.items[i], at(path, i)));
    return out;
  }

  /// count x count numbers, row by row.
  std::vector<Num> square(const JsonNode& n, const std::string& path, std::size_t count) const {
    array(n, path);
    if (n.items.size() != count)
      fail(path, "expected " + std::to_string(count) + " rows, found " + std::to_string(n.items.size()));
    std::vector<Num> out;
    for (std::size_t i = 0; i < count; ++i) {
      auto row = numbers(n.items[i], at(path, i), count);
      out.insert(out.end(), row.begin(), row.end());
    }
    return out;
  }

  /// A radius or a tangent: only its square enters the matrix, and 0 is legal (a point, a line: a
  /// degenerate quadric, which is a status, not an error); a negative value is a mistake.
  void nonnegative(const Num& x) const {
    if (x.value < 0) fail(x.path, "must be >= 0, found " + x.value.str());
  }
  void nonzero_vector(const std::vector<Num>& v, const std::string& path, const char* what) const {
    if (std::all_of(v.begin(), v.end(), [](const Num& x) { return x.value == 0; }))
      fail(path, std::string(what) + " must be a non-zero vector");
  }

 private:
  std::string file_;
};

QuadricSpec read_quadric(const Reader& r, const JsonNode& n, const std::string& path) {
  r.object(n, path);
  QuadricSpec q;
  q.path = path;
  static const std::pair<const char*, Shape> shapes[] = {{"matrix", Shape::matrix},       {"coefficients", Shape::coefficients},
                                                         {"sphere", Shape::sphere},       {"ellipsoid", Shape::ellipsoid},
                                                         {"cylinder", Shape::cylinder},   {"cone", Shape::cone}};
  r.keys(n, path, {"id", "matrix", "coefficients", "sphere", "ellipsoid", "cylinder", "cone"});
  const JsonNode* body = nullptr;
  std::string key;
  for (const auto& [name, shape] : shapes) {
    if (const JsonNode* b = n.find(name)) {
      if (body) r.fail(join(path, name), "a quadric has exactly one shape key; found both \"" + key + "\" and \"" + name + "\"");
      body = b;
      key = name;
      q.shape = shape;
    }
  }
  if (!body) r.fail(path, "missing shape key (one of: matrix, coefficients, sphere, ellipsoid, cylinder, cone)");
  const std::string bp = join(path, key);
  switch (q.shape) {
    case Shape::matrix: {
      q.params = r.square(*body, bp, 4);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const Num &a = q.params[static_cast<std::size_t>(4 * i + j)], &b = q.params[static_cast<std::size_t>(4 * j + i)];
          if (a.value != b.value)  // named at the entry below the diagonal, as the library and Python do
            r.fail(b.path, "matrix is not symmetric: " + b.path.substr(bp.size()) + " = " + b.value.str() + " but " +
                               a.path.substr(bp.size()) + " = " + a.value.str());
        }
      break;
    }
    case Shape::coefficients: {
      r.object(*body, bp);
      static const char* names[] = {"xx", "yy", "zz", "xy", "xz", "yz", "x", "y", "z", "c"};
      r.keys(*body, bp, {"xx", "yy", "zz", "xy", "xz", "yz", "x", "y", "z", "c"});
      for (const char* nm : names) {
        const JsonNode* c = body->find(nm);
        q.params.push_back(c ? r.number(*c, join(bp, nm)) : Num{Rational(0), join(bp, nm), ""});
      }
      break;
    }
    case Shape::sphere: {
      r.object(*body, bp);
      r.keys(*body, bp, {"center", "radius"});
      q.params = r.numbers(r.required(*body, bp, "center"), join(bp, "center"), 3);
      q.params.push_back(r.number(r.required(*body, bp, "radius"), join(bp, "radius")));
      r.nonnegative(q.params[3]);
      break;
    }
    case Shape::ellipsoid: {
      r.object(*body, bp);
      r.keys(*body, bp, {"center", "radii", "axes"});
      q.params = r.numbers(r.required(*body, bp, "center"), join(bp, "center"), 3);
      auto radii = r.numbers(r.required(*body, bp, "radii"), join(bp, "radii"), 3);
      for (const Num& x : radii) r.nonnegative(x);
      q.params.insert(q.params.end(), radii.begin(), radii.end());
      std::vector<Num> axes;
      if (const JsonNode* a = body->find("axes")) {
        // a singular axes matrix flattens the ellipsoid, as a zero radius does: a degenerate quadric (a
        // status), not an error
        axes = r.square(*a, join(bp, "axes"), 3);
      } else {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) axes.push_back(Num{Rational(i == j ? 1 : 0), join(bp, "axes"), ""});
      }
      q.params.insert(q.params.end(), axes.begin(), axes.end());
      break;
    }
    case Shape::cylinder:
    case Shape::cone: {
      const bool cyl = q.shape == Shape::cylinder;
      const char* first = cyl ? "point" : "apex";
      const char* last = cyl ? "radius" : "tan_half_angle";
      r.object(*body, bp);
      if (cyl) r.keys(*body, bp, {"point", "axis", "radius"});
      else r.keys(*body, bp, {"apex", "axis", "tan_half_angle"});
      q.params = r.numbers(r.required(*body, bp, first), join(bp, first), 3);
      auto axis = r.numbers(r.required(*body, bp, "axis"), join(bp, "axis"), 3);
      r.nonzero_vector(axis, join(bp, "axis"), "axis");
      q.params.insert(q.params.end(), axis.begin(), axis.end());
      q.params.push_back(r.number(r.required(*body, bp, last), join(bp, last)));
      r.nonnegative(q.params.back());
      break;
    }
  }
  return q;
}

/// A request list: "all" or an array of {"quadric": ID, "<other>": ID}.
std::vector<Pair> read_requests(const Reader& r, const JsonNode* n, const std::string& path, const char* other,
                                const std::map<std::string, std::size_t>& quadrics,
                                const std::map<std::string, std::size_t>& others, const char* other_kind) {
  std::vector<Pair> out;
  constexpr std::size_t kMaxPairs = 1000000;  // bounded work: refuse instead of exhausting memory
  if (!n || (n->kind == Kind::string && n->text == "all")) {
    if (quadrics.size() * std::max<std::size_t>(others.size(), 1) > kMaxPairs && !others.empty())
      r.fail(path, "\"all\" asks for " + std::to_string(quadrics.size() * others.size()) + " pairs (limit " +
                       std::to_string(kMaxPairs) + "); list the wanted pairs instead");
    for (std::size_t q = 0; q < quadrics.size(); ++q)
      for (std::size_t o = 0; o < others.size(); ++o) out.push_back({q, o});
    return out;
  }
  if (n->kind == Kind::string) r.fail(path, "expected \"all\" or an array of requests, found \"" + n->text + "\"");
  r.array(*n, path);
  if (n->items.size() > kMaxPairs)
    r.fail(path, std::to_string(n->items.size()) + " pairs requested (limit " + std::to_string(kMaxPairs) + ")");
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (std::size_t i = 0; i < n->items.size(); ++i) {
    const std::string ip = at(path, i);
    const JsonNode& item = r.object(n->items[i], ip);
    r.keys(item, ip, {"quadric", other});
    const std::string qid = r.string(r.required(item, ip, "quadric"), join(ip, "quadric"));
    const std::string oid = r.string(r.required(item, ip, other), join(ip, other));
    const auto qi = quadrics.find(qid);
    if (qi == quadrics.end()) r.fail(join(ip, "quadric"), "no quadric with id \"" + qid + "\"");
    const auto oi = others.find(oid);
    if (oi == others.end()) r.fail(join(ip, other), "no " + std::string(other_kind) + " with id \"" + oid + "\"");
    if (!seen.insert({qi->second, oi->second}).second)
      r.fail(ip, "duplicate request (" + qid + ", " + oid + ")");
    out.push_back({qi->second, oi->second});
  }
  // Keep scene order (quadric, then light/mirror), independent of listing order.
  std::sort(out.begin(), out.end(), [](const Pair& a, const Pair& b) {
    return a.quadric != b.quadric ? a.quadric < b.quadric : a.other < b.other;
  });
  return out;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file) {
  const JsonNode root = parse_json_tree(text, file);
  Reader r(file);
  Scene sc;
  sc.file = file;
  r.object(root, "");
  r.keys(root, "", {"format", "name", "quadrics", "lights", "mirrors", "requests", "camera"});
  const std::string format = r.string(r.required(root, "", "format"), "format");
  if (format != "qverify-scene/1") r.fail("format", "unsupported format \"" + format + "\" (expected \"qverify-scene/1\")");
  if (const JsonNode* nm = root.find("name")) sc.name = r.string(*nm, "name");
  else {
    const auto slash = file.find_last_of('/');
    sc.name = file.substr(slash == std::string::npos ? 0 : slash + 1);
  }

  std::map<std::string, std::string> ids;  // id -> path of its first use
  auto read_id = [&](const JsonNode& obj, const std::string& path) {
    const std::string id = r.string(r.required(obj, path, "id"), join(path, "id"));
    if (id.empty()) r.fail(join(path, "id"), "id must be a non-empty string");
    const auto [it, fresh] = ids.emplace(id, path);
    if (!fresh) r.fail(join(path, "id"), "duplicate id \"" + id + "\" (already used by " + it->second + ")");
    return id;
  };

  const JsonNode& qs = r.array(r.required(root, "", "quadrics"), "quadrics");
  std::map<std::string, std::size_t> qindex, lindex, mindex;
  for (std::size_t i = 0; i < qs.items.size(); ++i) {
    const std::string p = at("quadrics", i);
    r.object(qs.items[i], p);
    QuadricSpec q = read_quadric(r, qs.items[i], p);
    q.id = read_id(qs.items[i], p);
    qindex[q.id] = i;
    sc.quadrics.push_back(std::move(q));
  }
  if (const JsonNode* ls = root.find("lights")) {
    r.array(*ls, "lights");
    for (std::size_t i = 0; i < ls->items.size(); ++i) {
      const std::string p = at("lights", i);
      const JsonNode& n = r.object(ls->items[i], p);
      r.keys(n, p, {"id", "position", "direction"});
      LightSpec l;
      l.path = p;
      const JsonNode* pos = n.find("position");
      const JsonNode* dir = n.find("direction");
      if (pos && dir) r.fail(join(p, "direction"), "a light has either \"position\" or \"direction\", not both");
      if (!pos && !dir) r.fail(p, "missing \"position\" (point light) or \"direction\" (parallel light)");
      l.parallel = dir != nullptr;
      l.xyz = r.numbers(pos ? *pos : *dir, join(p, pos ? "position" : "direction"), 3);
      if (dir) r.nonzero_vector(l.xyz, join(p, "direction"), "direction");
      l.id = read_id(n, p);
      lindex[l.id] = i;
      sc.lights.push_back(std::move(l));
    }
  }
  if (const JsonNode* ms = root.find("mirrors")) {
    r.array(*ms, "mirrors");
    for (std::size_t i = 0; i < ms->items.size(); ++i) {
      const std::string p = at("mirrors", i);
      const JsonNode& n = r.object(ms->items[i], p);
      r.keys(n, p, {"id", "plane"});
      MirrorSpec m;
      m.path = p;
      m.plane = r.numbers(r.required(n, p, "plane"), join(p, "plane"), 4);
      if (m.plane[0].value == 0 && m.plane[1].value == 0 && m.plane[2].value == 0)
        r.fail(join(p, "plane"), "the normal (a, b, c) of a mirror plane must be non-zero");
      m.id = read_id(n, p);
      mindex[m.id] = i;
      sc.mirrors.push_back(std::move(m));
    }
  }
  const JsonNode* req = root.find("requests");
  if (req) {
    r.object(*req, "requests");
    r.keys(*req, "requests", {"shadows", "reflections"});
  }
  sc.shadows = read_requests(r, req ? req->find("shadows") : nullptr, "requests.shadows", "light", qindex, lindex, "light");
  sc.reflections =
      read_requests(r, req ? req->find("reflections") : nullptr, "requests.reflections", "mirror", qindex, mindex, "mirror");

  if (const JsonNode* cam = root.find("camera")) {
    const std::string p = "camera";
    r.object(*cam, p);
    r.keys(*cam, p, {"eye", "look_at", "up", "fov_y_deg", "width", "height"});
    sc.has_camera = true;
    CameraSpec& c = sc.camera;
    c.eye = r.numbers(r.required(*cam, p, "eye"), "camera.eye", 3);
    c.look_at = r.numbers(r.required(*cam, p, "look_at"), "camera.look_at", 3);
    if (const JsonNode* up = cam->find("up")) c.up = r.numbers(*up, "camera.up", 3);
    else c.up = {Num{0, "camera.up", ""}, Num{0, "camera.up", ""}, Num{1, "camera.up", ""}};
    if (const JsonNode* f = cam->find("fov_y_deg")) c.fov_y_deg = r.number(*f, "camera.fov_y_deg");
    else c.fov_y_deg = Num{40, "camera.fov_y_deg", ""};
    if (!(c.fov_y_deg.value > 0 && c.fov_y_deg.value < 180)) r.fail("camera.fov_y_deg", "must be in (0, 180) degrees");
    auto pixels = [&](const char* key, long dflt) {
      const JsonNode* n = cam->find(key);
      if (!n) return dflt;
      const Num v = r.number(*n, join(p, key));
      if (!(v.value >= 1 && v.value <= 16384) || denominator(v.value) != 1)
        r.fail(join(p, key), "must be a whole number of pixels from 1 to 16384");
      return static_cast<long>(numerator(v.value).convert_to<long>());
    };
    c.width = pixels("width", 640);
    c.height = pixels("height", 480);
    Vec3<Rational> e, l, u;
    for (int i = 0; i < 3; ++i) {
      e(i) = c.eye[static_cast<std::size_t>(i)].value;
      l(i) = c.look_at[static_cast<std::size_t>(i)].value;
      u(i) = c.up[static_cast<std::size_t>(i)].value;
    }
    if (e == l) r.fail("camera.look_at", "look_at must differ from eye");
    if ((l - e).cross(u) == Vec3<Rational>::Zero()) r.fail("camera.up", "up must not be parallel to the viewing direction");
  }
  return sc;
}

Scene load_scene(const std::string& file) { return parse_scene(read_text_file(file, JsonLimits{}.max_bytes), file); }

namespace {
std::vector<Pair> complement(const std::vector<Pair>& requested, std::size_t nq, std::size_t no) {
  std::set<std::pair<std::size_t, std::size_t>> req;
  for (const Pair& p : requested) req.insert({p.quadric, p.other});
  std::vector<Pair> out;
  for (std::size_t q = 0; q < nq; ++q)
    for (std::size_t o = 0; o < no; ++o)
      if (!req.count({q, o})) out.push_back({q, o});
  return out;
}
}  // namespace

std::vector<Pair> Scene::skipped_shadows() const { return complement(shadows, quadrics.size(), lights.size()); }
std::vector<Pair> Scene::skipped_reflections() const { return complement(reflections, quadrics.size(), mirrors.size()); }

}  // namespace qverify
