// Mesh files: OBJ, OFF, PLY (ascii and binary) and STL (ascii and binary).
//
// We read the face lists ourselves instead of through OpenMesh's readers. OpenMesh builds a
// half-edge mesh while reading, so it duplicates the vertices of faces at complex edges and
// refuses faces with repeated indices, telling nobody (hard case 6); its text readers use
// `stream >> float`, which fails on "nan" and then leaves every later value of the file at
// zero or uninitialised (measured with OpenMesh 9.0: an ascii PLY with one "nan" coordinate
// loads with 0 faces and reports success). Here every face as written reaches the report:
// fanned, dropped with a reason, or kept, and duplicatedVertices stays 0.
//
// Untrusted sizes: a header's counts are checked against the bytes the file actually has
// before anything is reserved, and list lengths are bounded by the data left.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/memory.h"
#include "geometry/mesh.h"

namespace penumbra::geo {
namespace {

constexpr std::int64_t kInvalid = -2;  // an index that could not be parsed or resolved
constexpr std::int64_t kAbsent = -1;   // an optional OBJ index (vt, vn) not given
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

bool nextLine(std::string_view& text, std::string_view& line) {
  if (text.empty()) return false;
  const std::size_t nl = text.find('\n');
  line = text.substr(0, nl);
  text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
  return true;
}

std::string_view nextToken(std::string_view& s) {
  std::size_t b = 0;
  while (b < s.size() && isSpace(s[b])) ++b;
  std::size_t e = b;
  while (e < s.size() && !isSpace(s[e])) ++e;
  const std::string_view token = s.substr(b, e - b);
  s.remove_prefix(e);
  return token;
}

// Malformed numbers become NaN so that the faces using them are dropped as non-finite. Floats
// are parsed as float, not through double, so that every value is the nearest float.
template <typename T>
T parseReal(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  T v = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || end != token.data() + token.size()) return std::numeric_limits<T>::quiet_NaN();
  // Out of range: strtof/strtod give the overflowed infinity or the underflowed (sub)normal.
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(token);
    if constexpr (std::is_same_v<T, float>)
      return std::strtof(copy.c_str(), nullptr);
    else
      return std::strtod(copy.c_str(), nullptr);
  }
  return ec == std::errc() ? v : std::numeric_limits<T>::quiet_NaN();
}
double parseFloat(std::string_view token) { return parseReal<float>(token); }

bool equalsLower(std::string_view token, std::string_view lower) {
  return token.size() == lower.size() && std::equal(token.begin(), token.end(), lower.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

bool parseInt(std::string_view token, std::int64_t& v) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  return !token.empty() && ec == std::errc() && end == token.data() + token.size();
}

std::string str(std::uint64_t n) { return std::to_string(n); }

// Rejects headers that claim more elements than the file can hold, before allocating
// (bad-input list: "headers claiming 10^9 vertices").
void checkClaimedSize(const std::string& path, long double minimumBytes, std::size_t available,
                      const std::string& claim) {
  if (minimumBytes > static_cast<long double>(available) + 1.0L)
    throw Error(path, "header claims " + claim + ", more than the " + str(available) + " bytes of the file can hold");
}

// Counts one face as written and says whether it can be used.
bool acceptFace(std::span<const std::int64_t> face, std::size_t vertexCount, MeshReport& r) {
  ++r.inputFaces;
  for (std::int64_t i : face) {
    if (i < 0 || static_cast<std::uint64_t>(i) >= vertexCount) {
      ++r.droppedInvalidIndex;
      return false;
    }
  }
  if (face.size() < 3) {
    ++r.droppedDegenerate;
    return false;
  }
  return true;
}

// Polygons are fanned from their first corner: exact for convex ones; for a concave one the
// signed areas still add up to the polygon and its boundary edges are kept.
void fanTriangulate(std::span<const std::int64_t> face, TriangleMesh& mesh, MeshReport& r) {
  if (face.size() > 3) ++r.polygonsTriangulated;
  for (std::size_t k = 1; k + 1 < face.size(); ++k) mesh.triangles.emplace_back(face[0], face[k], face[k + 1]);
}

// Flat list of polygons, kept until all vertices are known (OBJ and PLY may refer forward).
struct FaceList {
  std::vector<std::int64_t> indices;
  std::vector<std::size_t> start{0};
  void close() { start.push_back(indices.size()); }
  std::size_t size() const { return start.size() - 1; }
  std::span<const std::int64_t> operator[](std::size_t f) const {
    return {indices.data() + start[f], start[f + 1] - start[f]};
  }
};

void addFaces(const FaceList& faces, TriangleMesh& mesh, MeshReport& r) {
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (acceptFace(faces[f], mesh.positions.size(), r)) fanTriangulate(faces[f], mesh, r);
  }
}

// double -> float without the undefined behaviour of converting values beyond float's range.
float toFloat(double d) {
  if (std::abs(d) > std::numeric_limits<float>::max())
    return d > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  return static_cast<float>(d);
}

glm::vec3 toVec3(const double* v) { return {toFloat(v[0]), toFloat(v[1]), toFloat(v[2])}; }

// ---- OBJ ---------------------------------------------------------------------------------

// 1-based, or negative relative to the `count` elements read so far. Positive indices are
// checked against the final count later, as some writers refer forward.
std::int64_t objIndex(std::string_view token, std::size_t count) {
  if (token.empty()) return kAbsent;
  std::int64_t i = 0;
  if (!parseInt(token, i) || i == 0) return kInvalid;
  if (i > 0) return i - 1;
  const std::int64_t resolved = static_cast<std::int64_t>(count) + i;
  return resolved >= 0 ? resolved : kInvalid;
}

// An OBJ file as written: faces keep their material group (the `usemtl` in force, 0 = none).
struct ObjData {
  std::vector<glm::vec3> v, vn;
  std::vector<glm::vec2> vt;
  FaceList faces;  // three entries per corner: v, vt, vn
  std::vector<std::uint32_t> faceGroup;
  std::vector<std::string> groups{""};  // usemtl names in order of first use; [0] = none
  std::vector<std::string> libraries;   // mtllib arguments, as written
  std::size_t linesAndPoints = 0;       // `l` and `p` statements
  bool colours = false;                 // `v x y z r g b`
};

// The rest of a statement without surrounding blanks: material names may contain spaces
// ("usemtl Material name with many, many spaces", tests/fuzz/corpus/obj).
std::string_view trimmed(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

ObjData parseObj(std::string_view text) {
  ObjData d;
  std::uint32_t group = 0;
  std::string_view line;
  while (nextLine(text, line)) {
    line = line.substr(0, line.find('#'));  // some writers put comments after a statement
    const std::string_view key = nextToken(line);
    if (key == "v" || key == "vn") {
      double c[3];
      for (double& x : c) x = parseFloat(nextToken(line));
      (key == "v" ? d.v : d.vn).push_back(toVec3(c));
      if (key == "v" && !d.colours) {  // x y z [w] or x y z r g b
        int extra = 0;
        while (!nextToken(line).empty()) ++extra;
        d.colours = extra >= 3;
      }
    } else if (key == "vt") {
      const std::string_view u = nextToken(line), w = nextToken(line);
      d.vt.emplace_back(u.empty() ? 0.0 : parseFloat(u), w.empty() ? 0.0 : parseFloat(w));
    } else if (key == "f") {
      for (std::string_view corner = nextToken(line); !corner.empty(); corner = nextToken(line)) {
        const std::size_t s1 = corner.find('/');
        const std::string_view rest = s1 == std::string_view::npos ? std::string_view{} : corner.substr(s1 + 1);
        const std::size_t s2 = rest.find('/');
        const std::int64_t iv = objIndex(corner.substr(0, s1), d.v.size());
        d.faces.indices.push_back(iv == kAbsent ? kInvalid : iv);
        d.faces.indices.push_back(objIndex(rest.substr(0, s2), d.vt.size()));
        d.faces.indices.push_back(s2 == std::string_view::npos ? kAbsent : objIndex(rest.substr(s2 + 1), d.vn.size()));
      }
      d.faces.close();
      d.faceGroup.push_back(group);
    } else if (key == "usemtl") {
      const std::string name(trimmed(line));
      const auto it = std::find(d.groups.begin(), d.groups.end(), name);
      group = std::uint32_t(it - d.groups.begin());
      if (it == d.groups.end()) d.groups.push_back(name);
    } else if (key == "mtllib") {
      if (const std::string_view rest = trimmed(line); !rest.empty()) d.libraries.emplace_back(rest);
    } else if (key == "l" || key == "p") {
      ++d.linesAndPoints;  // no surface: counted in the report
    }                      // other statements (o, g, s, ...) carry nothing a shadow needs
  }
  return d;
}

// The mesh of the faces of `group` (all faces when group < 0), counted in `report`.
TriangleMesh buildObjMesh(const ObjData& d, std::int64_t group, MeshReport& report) {
  const auto &v = d.v, &vn = d.vn;
  const auto& vt = d.vt;
  const FaceList& faces = d.faces;
  const auto& faceGroup = d.faceGroup;
  report.inputVertices = v.size();
  if (group < 0) report.ignoredElements = d.linesAndPoints, report.vertexColours = d.colours;
  const auto inGroup = [&](std::size_t f) { return group < 0 || std::int64_t(faceGroup[f]) == group; };

  // Attributes are kept only when every used corner has a valid one: the mesh stores one
  // normal and uv per position, and a half-filled array would be worse than none.
  std::vector<std::uint8_t> usable(faces.size(), 0);
  std::vector<std::int64_t> face;
  bool allUv = !vt.empty(), allNormal = !vn.empty(), anyFace = false;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (!inGroup(f)) continue;
    const std::span<const std::int64_t> corners = faces[f];
    face.clear();
    for (std::size_t k = 0; k < corners.size(); k += 3) face.push_back(corners[k]);
    if (!acceptFace(face, v.size(), report)) continue;
    usable[f] = 1;
    anyFace = true;
    for (std::size_t k = 0; k < corners.size(); k += 3) {
      allUv = allUv && corners[k + 1] >= 0 && corners[k + 1] < std::int64_t(vt.size());
      allNormal = allNormal && corners[k + 2] >= 0 && corners[k + 2] < std::int64_t(vn.size());
    }
  }
  allUv = allUv && anyFace;
  allNormal = allNormal && anyFace;

  TriangleMesh mesh;
  if (!allUv && !allNormal) mesh.positions = v;
  using Key = std::array<std::int64_t, 3>;  // v, vt, vn
  const auto hash = [](const Key& k) {
    return std::hash<std::uint64_t>()(std::uint64_t(k[0]) * 1000003u ^ std::uint64_t(k[1]) * 7919u ^
                                      std::uint64_t(k[2]) << 21);
  };
  std::unordered_map<Key, std::int64_t, decltype(hash)> vertexOf(16, hash);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (!usable[f]) continue;
    const std::span<const std::int64_t> corners = faces[f];
    face.clear();
    for (std::size_t k = 0; k < corners.size(); k += 3) {
      if (!allUv && !allNormal) {
        face.push_back(corners[k]);
        continue;
      }
      const Key key{corners[k], allUv ? corners[k + 1] : kAbsent, allNormal ? corners[k + 2] : kAbsent};
      auto [it, added] = vertexOf.try_emplace(key, std::int64_t(mesh.positions.size()));
      if (added) {
        mesh.positions.push_back(v[key[0]]);
        if (allUv) mesh.uvs.push_back(vt[key[1]]);
        if (allNormal) mesh.normals.push_back(vn[key[2]]);
      }
      face.push_back(it->second);
    }
    fanTriangulate(face, mesh, report);
  }
  return mesh;
}

TriangleMesh loadObj(std::string_view text, MeshReport& report) { return buildObjMesh(parseObj(text), -1, report); }

// ---- OFF ---------------------------------------------------------------------------------

// Next line with content, '#' comments removed.
bool nextContentLine(std::string_view& text, std::string_view& line) {
  while (nextLine(text, line)) {
    line = line.substr(0, line.find('#'));
    std::string_view probe = line;
    if (!nextToken(probe).empty()) return true;
  }
  return false;
}

TriangleMesh loadOff(const std::string& path, std::string_view text, MeshReport& report) {
  const std::size_t fileSize = text.size();
  std::string_view line;
  if (!nextContentLine(text, line)) throw Error(path, "empty file");
  const std::string_view keyword = nextToken(line);
  // Header [ST][C][N]OFF; the 4D and n-dimensional variants have no meaning here.
  if (!keyword.ends_with("OFF")) throw Error(path, "not an OFF file (no OFF header)");
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  const bool hasUv = prefix.starts_with("ST");
  if (hasUv) prefix.remove_prefix(2);
  if (prefix.starts_with("C")) prefix.remove_prefix(1);
  const bool hasNormal = prefix.starts_with("N");
  if (hasNormal) prefix.remove_prefix(1);
  if (!prefix.empty()) throw Error(path, "unsupported OFF variant " + std::string(keyword));

  std::string_view counts = line;
  std::string_view probe = line;
  const std::string_view first = nextToken(probe);
  if (first == "BINARY") throw Error(path, "binary OFF is not supported");
  if (first.empty() && !nextContentLine(text, counts)) throw Error(path, "missing vertex and face counts");
  std::int64_t nv = 0, nf = 0;
  if (!parseInt(nextToken(counts), nv) || !parseInt(nextToken(counts), nf) || nv < 0 || nf < 0)
    throw Error(path, "bad vertex and face counts in the OFF header");
  // Smallest records: "0 0 0\n" (6 bytes) and "3 0 0 0\n" (8 bytes).
  checkClaimedSize(path, 6.0L * nv + 8.0L * nf, fileSize, str(nv) + " vertices and " + str(nf) + " faces");

  TriangleMesh mesh;
  mesh.positions.reserve(nv);
  std::vector<double> values;
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!nextContentLine(text, line)) throw Error(path, "truncated: " + str(i) + " of " + str(nv) + " vertices");
    values.clear();
    for (std::string_view t = nextToken(line); !t.empty(); t = nextToken(line)) values.push_back(parseFloat(t));
    values.resize(std::max<std::size_t>(values.size(), 3), kNaN);
    mesh.positions.push_back(toVec3(values.data()));
    // Vertex line: x y z [nx ny nz] [colour] [s t]; colour has a variable length, so the
    // texture coordinates are taken from the end.
    if (hasNormal) mesh.normals.push_back(values.size() >= 6 ? toVec3(&values[3]) : glm::vec3(0));
    if (hasUv && values.size() >= 5)
      mesh.uvs.emplace_back(values[values.size() - 2], values[values.size() - 1]);
    else if (hasUv)
      mesh.uvs.emplace_back(0.0f);
  }
  report.inputVertices = mesh.positions.size();

  std::vector<std::int64_t> face;
  for (std::int64_t i = 0; i < nf; ++i) {
    if (!nextContentLine(text, line)) throw Error(path, "truncated: " + str(i) + " of " + str(nf) + " faces");
    face.clear();
    std::int64_t n = 0;
    if (!parseInt(nextToken(line), n) || n < 0) {
      face.push_back(kInvalid);
    } else {
      for (std::int64_t k = 0; k < n; ++k) {
        std::int64_t index = kInvalid;
        const std::string_view t = nextToken(line);
        if (t.empty() || !parseInt(t, index)) {
          face.push_back(kInvalid);  // fewer indices than announced
          break;
        }
        face.push_back(index);
      }
    }
    if (acceptFace(face, mesh.positions.size(), report)) fanTriangulate(face, mesh, report);
  }
  return mesh;
}

// ---- PLY ---------------------------------------------------------------------------------

struct PlyType {
  std::size_t size = 4;
  char kind = 'f';  // 'i' signed, 'u' unsigned, 'f' IEEE float
};

bool plyType(std::string_view name, PlyType& t) {
  static const std::tuple<std::string_view, std::string_view, PlyType> kTypes[] = {
      {"char", "int8", {1, 'i'}},     {"uchar", "uint8", {1, 'u'}},   {"short", "int16", {2, 'i'}},
      {"ushort", "uint16", {2, 'u'}}, {"int", "int32", {4, 'i'}},     {"uint", "uint32", {4, 'u'}},
      {"float", "float32", {4, 'f'}}, {"double", "float64", {8, 'f'}}};
  for (const auto& [name0, name1, type] : kTypes) {
    if (name == name0 || name == name1) {
      t = type;
      return true;
    }
  }
  return false;
}

struct PlyProperty {
  std::string name;
  PlyType type;
  bool isList = false;
  PlyType countType;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

// Reads one value at a time from an ascii or binary PLY body (or a binary STL). Malformed ascii
// numbers read as NaN; false means the data ran out.
class ValueReader {
 public:
  ValueReader(std::string_view body, PlyFormat format) : rest_(body), format_(format) {}
  std::size_t bytesLeft() const { return rest_.size(); }
  bool ascii() const { return format_ == PlyFormat::Ascii; }

  bool read(PlyType type, double& value) {
    if (ascii()) {
      const std::string_view token = nextToken(rest_);
      value = type.kind == 'f' && type.size == 4 ? parseFloat(token) : parseReal<double>(token);
      return !token.empty();
    }
    if (rest_.size() < type.size) return false;
    // Assemble the value from the bytes in file order; no host-endianness assumption.
    std::uint64_t u = 0;
    for (std::size_t i = 0; i < type.size; ++i) {
      const std::size_t byte = format_ == PlyFormat::BinaryLittle ? type.size - 1 - i : i;
      u = u << 8 | static_cast<unsigned char>(rest_[byte]);
    }
    rest_.remove_prefix(type.size);
    const unsigned bits = 8 * static_cast<unsigned>(type.size);
    if (type.kind == 'f')
      value = type.size == 4 ? std::bit_cast<float>(static_cast<std::uint32_t>(u)) : std::bit_cast<double>(u);
    else if (type.kind == 'i' && bits < 64 && (u >> (bits - 1)) != 0)
      value = static_cast<double>(static_cast<std::int64_t>(u) - (std::int64_t{1} << bits));
    else
      value = static_cast<double>(u);
    return true;
  }

 private:
  std::string_view rest_;
  PlyFormat format_;
};

TriangleMesh loadPly(const std::string& path, std::string_view text, MeshReport& report) {
  std::string_view line;
  if (!nextLine(text, line) || nextToken(line) != "ply") throw Error(path, "not a PLY file");
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (!ended && nextLine(text, line)) {
    const std::string_view key = nextToken(line);
    if (key == "format") {
      const std::string_view f = nextToken(line);
      if (f == "ascii") {
        format = PlyFormat::Ascii;
      } else if (f == "binary_little_endian" || f == "binary_big_endian") {
        format = f == "binary_big_endian" ? PlyFormat::BinaryBig : PlyFormat::BinaryLittle;
      } else {
        throw Error(path, "unknown PLY format '" + std::string(f) + "'");
      }
    } else if (key == "element") {
      PlyElement e;
      e.name = nextToken(line);
      std::int64_t count = 0;
      if (!parseInt(nextToken(line), count) || count < 0)
        throw Error(path, "bad count for PLY element '" + e.name + "'");
      e.count = static_cast<std::uint64_t>(count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw Error(path, "PLY property before any element");
      PlyProperty p;
      std::string_view type = nextToken(line);
      if (type == "list") {
        p.isList = true;
        if (!plyType(nextToken(line), p.countType)) throw Error(path, "bad PLY list count type");
        type = nextToken(line);
      }
      if (!plyType(type, p.type)) throw Error(path, "unknown PLY property type '" + std::string(type) + "'");
      p.name = nextToken(line);
      elements.back().properties.push_back(p);
    } else if (key == "end_header") {
      ended = true;
    }  // comment, obj_info
  }
  if (!ended) throw Error(path, "PLY header has no end_header");

  long double minimumBytes = 0;
  std::string claim;
  for (const PlyElement& e : elements) {
    std::size_t bytes = 0;
    for (const PlyProperty& p : e.properties)
      bytes += format == PlyFormat::Ascii ? 2 : (p.isList ? p.countType : p.type).size;
    minimumBytes += static_cast<long double>(e.count) * bytes;
    claim += (claim.empty() ? "" : " and ") + str(e.count) + " " + e.name + " elements";
  }
  checkClaimedSize(path, minimumBytes, text.size(), claim);

  TriangleMesh mesh;
  FaceList faces;
  bool sawVertices = false;
  ValueReader in(text, format);
  for (const PlyElement& e : elements) {
    enum Role { X, Y, Z, NX, NY, NZ, U, V, Indices, Other };
    std::vector<Role> roles;
    bool hasNormal = false, hasUv = false;
    for (const PlyProperty& p : e.properties) {
      static const std::pair<std::string_view, Role> kVertexRoles[] = {
          {"x", X}, {"y", Y},         {"z", Z},         {"nx", NX}, {"ny", NY}, {"nz", NZ},       {"u", U},
          {"s", U}, {"texture_u", U}, {"texture_s", U}, {"v", V},   {"t", V},   {"texture_v", V}, {"texture_t", V}};
      Role role = Other;
      if (e.name == "vertex" && !p.isList) {
        for (const auto& [n, r] : kVertexRoles) role = n == p.name ? r : role;
      } else if (e.name == "face" && p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        role = Indices;
      }
      hasNormal = hasNormal || role == NX;
      hasUv = hasUv || role == U;
      roles.push_back(role);
    }
    if (e.name == "vertex")
      for (const PlyProperty& p : e.properties)
        report.vertexColours = report.vertexColours || p.name == "red" || p.name == "green" || p.name == "blue";
    if (e.name == "edge") report.ignoredElements += e.count;
    if (e.name == "vertex") {
      // A second vertex element would append positions without the first one's normals or
      // uvs (found by fuzzing: tests/fuzz/regressions/ply/); the format has one.
      if (sawVertices) throw Error(path, "PLY file has more than one vertex element");
      const auto once = [&](Role r) { return std::count(roles.begin(), roles.end(), r) == 1; };
      if (!once(X) || !once(Y) || !once(Z)) throw Error(path, "PLY vertices need x, y and z properties");
      sawVertices = true;
      mesh.positions.reserve(e.count);
    }
    for (std::uint64_t i = 0; i < e.count && !e.properties.empty(); ++i) {
      double values[Other] = {kNaN, kNaN, kNaN, 0, 0, 0, 0, 0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        const auto truncated = [&] {
          return Error(path, "truncated in PLY element '" + e.name + "' (" + str(i) + " of " + str(e.count) + ")");
        };
        double value = 0.0;
        if (!in.read(p.isList ? p.countType : p.type, value)) throw truncated();
        if (!p.isList) {
          if (roles[k] != Other) values[roles[k]] = value;
          continue;
        }
        // A list length must be an integer that the remaining data can hold.
        const std::size_t minItemBytes = in.ascii() ? 2 : p.type.size;
        if (!(value >= 0.0) || value != std::floor(value) ||
            value * minItemBytes > static_cast<double>(in.bytesLeft()) + 1.0)
          throw Error(path, "bad list length in PLY element '" + e.name + "' #" + str(i));
        for (std::uint64_t j = 0; j < static_cast<std::uint64_t>(value); ++j) {
          double item = 0.0;
          if (!in.read(p.type, item)) throw truncated();
          if (roles[k] == Indices)
            faces.indices.push_back(
                item >= 0.0 && item == std::floor(item) && item < 0x1p62 ? static_cast<std::int64_t>(item) : kInvalid);
        }
        if (roles[k] == Indices) faces.close();
      }
      if (e.name == "vertex") {
        mesh.positions.push_back(toVec3(&values[X]));
        if (hasNormal) mesh.normals.push_back(toVec3(&values[NX]));
        if (hasUv) mesh.uvs.emplace_back(toFloat(values[U]), toFloat(values[V]));
      }
    }
  }
  if (!sawVertices) throw Error(path, "PLY file has no vertex element");
  report.inputVertices = mesh.positions.size();
  addFaces(faces, mesh, report);
  return mesh;
}

// ---- STL ---------------------------------------------------------------------------------

// Whether `text` reads as an ascii STL: "solid" first and at least one "vertex" line (binary
// files may begin with "solid" too, so the keyword alone decides nothing).
bool looksAsciiStl(std::string_view text) {
  std::string_view t = text;
  std::string_view line;
  if (!nextLine(t, line) || !equalsLower(nextToken(line), "solid")) return false;
  while (nextLine(t, line))
    if (equalsLower(nextToken(line), "vertex")) return true;
  return false;
}

TriangleMesh loadStl(const std::string& path, std::string_view text, MeshReport& report) {
  TriangleMesh mesh;
  FaceList faces;
  // Binary iff the size matches the facet count exactly: binary files may begin with "solid".
  double count = 0;
  if (text.size() >= 84) ValueReader(text.substr(80), PlyFormat::BinaryLittle).read({4, 'u'}, count);
  const auto facetCount = static_cast<std::uint64_t>(count);
  const bool binary = text.size() >= 84 && 84 + 50 * facetCount == text.size();
  if (!binary && !looksAsciiStl(text)) {
    // Neither: a binary file whose header count disagrees with its size. Say how many facets
    // each claims rather than parse it as ascii and report "0 triangles, 0 dropped".
    if (text.empty()) throw Error(path, "empty file");
    if (text.size() < 84)
      throw Error(path, "not an STL file: " + str(text.size()) +
                            " bytes, shorter than a binary header (84) and no ascii 'solid' with vertices");
    const std::uint64_t held = (text.size() - 84) / 50, extra = (text.size() - 84) % 50;
    auto triangles = [](std::uint64_t n) { return str(n) + (n == 1 ? " triangle" : " triangles"); };
    throw Error(path, "binary STL header claims " + triangles(facetCount) + " (" + str(84 + 50 * facetCount) +
                          " bytes), the file has " + str(text.size()) + " bytes (" + triangles(held) +
                          (extra ? " and " + str(extra) + " bytes more" : std::string()) + ")" +
                          (facetCount > held ? ": truncated" : ""));
  }
  if (binary) {
    mesh.positions.reserve(3 * facetCount);
    ValueReader in(text.substr(84), PlyFormat::BinaryLittle);
    double v[12], attribute;
    for (std::uint64_t f = 0; f < facetCount; ++f) {
      for (double& x : v) in.read({4, 'f'}, x);
      in.read({2, 'u'}, attribute);
      for (int k = 3; k < 12; k += 3) {  // after the facet normal
        faces.indices.push_back(static_cast<std::int64_t>(mesh.positions.size()));
        mesh.positions.push_back(toVec3(&v[k]));
      }
      faces.close();
    }
  } else {
    // ascii: "outer loop" vertex* "endloop"; a loop without three vertices is kept as a polygon.
    std::string_view line;
    while (nextLine(text, line)) {
      const std::string_view key = nextToken(line);
      if (equalsLower(key, "vertex")) {
        double c[3];
        for (double& x : c) x = parseFloat(nextToken(line));
        faces.indices.push_back(static_cast<std::int64_t>(mesh.positions.size()));
        mesh.positions.push_back(toVec3(c));
      } else if (equalsLower(key, "endloop")) {
        faces.close();
      } else if (equalsLower(key, "outer")) {
        faces.indices.resize(faces.start.back());  // vertices outside a loop are ignored
      }
    }
  }
  report.inputVertices = mesh.positions.size();
  addFaces(faces, mesh, report);
  return mesh;
}

std::string readFile(const std::string& path) {
  if (const std::string why = fileProblem(path); !why.empty()) throw Error(path, why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  std::string data;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path, "cannot read file");
  in.seekg(0, std::ios::beg);
  data.resize(static_cast<std::size_t>(size));
  if (!in.read(data.data(), size)) throw Error(path, "cannot read file");
  return data;
}

void checkCleaningMemory(const std::string& path, const TriangleMesh& mesh) {
  // Cleaning needs several times the parsed mesh (welding, sorted half-edges): refuse a mesh
  // this process cannot clean before starting, rather than die of std::bad_alloc in it.
  checkMemory(path, "cleaning " + str(mesh.triangles.size()) + " triangles",
              double(mesh.triangles.size()) * kCleanBytesPerTriangle);
}

}  // namespace

ObjFile loadObjFile(const std::string& path) {
  const ObjData d = parseObj(readFile(path));
  ObjFile out;
  out.libraries = d.libraries;
  std::vector<std::uint8_t> used(d.groups.size(), 0);
  for (std::uint32_t g : d.faceGroup) used[g] = 1;
  MeshReport total;
  std::size_t kept = 0;
  for (std::size_t g = 0; g < d.groups.size(); ++g) {
    // A usemtl followed by no face makes no part; faces before any usemtl are group 0.
    if (!used[g]) continue;
    ObjPart part;
    part.material = d.groups[g];
    part.mesh = buildObjMesh(d, std::int64_t(g), part.report);
    checkCleaningMemory(path, part.mesh);
    cleanMesh(part.mesh, part.report);
    kept += part.mesh.triangles.size();
    total.inputFaces += part.report.inputFaces;
    total.polygonsTriangulated += part.report.polygonsTriangulated;
    total.droppedInvalidIndex += part.report.droppedInvalidIndex;
    total.droppedDegenerate += part.report.droppedDegenerate;
    total.droppedNonFinite += part.report.droppedNonFinite;
    total.droppedDuplicate += part.report.droppedDuplicate;
    out.parts.push_back(std::move(part));
  }
  total.ignoredElements = d.linesAndPoints, total.vertexColours = d.colours;
  if (kept == 0) throw Error(path, "no triangles left (" + total.summary() + ")");
  // Said once, with the file's first part.
  if (!out.parts.empty())
    out.parts.front().report.ignoredElements = d.linesAndPoints, out.parts.front().report.vertexColours = d.colours;
  return out;
}

TriangleMesh loadMeshFile(const std::string& path, MeshReport& report) {
  report = MeshReport{};
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw Error(path, "unsupported mesh format '" + ext + "' (expected .obj, .off, .ply or .stl)");
  const std::string data = readFile(path);
  TriangleMesh mesh;
  if (ext == ".obj")
    mesh = loadObj(data, report);
  else if (ext == ".off")
    mesh = loadOff(path, data, report);
  else if (ext == ".ply")
    mesh = loadPly(path, data, report);
  else
    mesh = loadStl(path, data, report);
  checkCleaningMemory(path, mesh);
  cleanMesh(mesh, report);
  if (mesh.triangles.empty()) throw Error(path, "no triangles left (" + report.summary() + ")");
  return mesh;
}

}  // namespace penumbra::geo
