#include "compare/frame_file.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/files.h"

namespace penumbra {
namespace {

constexpr char kMagic[8] = {'P', 'N', 'M', 'B', 'F', 'R', 'M', '1'};
// Far above any frame this renderer makes (a 16384^2 image with 128 samples a pixel is 2^35
// floats): a count past it is a corrupt file, refused before anything is allocated.
constexpr std::uint64_t kMostElements = std::uint64_t(1) << 36;

class Writer {
 public:
  void bytes(const void* p, std::size_t n) {
    if (n > 0) out_.append(static_cast<const char*>(p), n);  // an empty vector's data() may be null
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    value(std::uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void image(const Image& i) {
    value(std::int32_t(i.width)), value(std::int32_t(i.height)), value(std::int32_t(i.channels));
    vector(i.data);
  }
  void text(const std::string& s) {
    value(std::uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  const std::string& data() const { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(std::string data, std::string path) : data_(std::move(data)), path_(std::move(path)) {}
  void bytes(void* p, std::size_t n) {
    if (n > data_.size() - at_) throw Error(path_, "a frame file cut short");
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not get
    std::memcpy(p, data_.data() + at_, n);
    at_ += n;
  }
  template <class T>
  T value() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  std::uint64_t count(std::size_t elementSize) {
    const auto n = value<std::uint64_t>();
    if (n > kMostElements || n * elementSize > data_.size() - at_) throw Error(path_, "a frame file cut short");
    return n;
  }
  template <class T>
  std::vector<T> vector() {
    std::vector<T> v(count(sizeof(T)));
    bytes(v.data(), v.size() * sizeof(T));
    return v;
  }
  Image image() {
    Image i;
    i.width = value<std::int32_t>(), i.height = value<std::int32_t>(), i.channels = value<std::int32_t>();
    i.data = vector<float>();
    if (i.width < 0 || i.height < 0 || i.channels < 0 || i.data.size() != std::size_t(i.width) * i.height * i.channels)
      throw Error(path_, "a frame file whose image size does not match its data");
    return i;
  }
  std::string text() {
    std::string s(count(1), '\0');
    bytes(s.data(), s.size());
    return s;
  }
  bool atEnd() const { return at_ == data_.size(); }

 private:
  std::string data_;
  std::string path_;
  std::size_t at_ = 0;
};

}  // namespace

void writeFrameFile(const std::string& path, const FrameResult& f) {
  Writer w;
  w.bytes(kMagic, sizeof kMagic);
  w.image(f.color), w.image(f.colorVariance);
  w.value(std::uint64_t(f.lights.size()));
  for (const LightResult& l : f.lights) {
    w.image(l.visibility), w.vector(l.perSample), w.value(std::int32_t(l.samples)), w.vector(l.unshadowed);
    w.image(l.visibilityVariance);
  }
  const CpuGBuffer& g = f.gbuffer;
  w.value(std::int32_t(g.width)), w.value(std::int32_t(g.height));
  w.vector(g.position), w.vector(g.normal), w.vector(g.valid), w.vector(g.shadingNormal), w.vector(g.baseColor);
  w.vector(g.material);
  w.value(std::uint8_t(g.camera.has_value())), w.value(g.camera.value_or(glm::vec3(0.0f))), w.value(g.origin);
  w.value(std::uint64_t(f.memoryBytes));
  w.value(std::uint64_t(f.statistics.size()));
  for (const auto& [k, v] : f.statistics) w.text(k), w.value(v);
  writeAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(w.data().data(), std::streamsize(w.data().size()));
    out.close();
    if (!out) throw Error(path, "cannot write the frame file");
  });
}

FrameResult readFrameFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot read the frame file");
  Reader r(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), path);
  char magic[sizeof kMagic];
  r.bytes(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) throw Error(path, "not a penumbra frame file");
  FrameResult f;
  f.color = r.image(), f.colorVariance = r.image();
  f.lights.resize(r.count(1));
  for (LightResult& l : f.lights) {
    l.visibility = r.image(), l.perSample = r.vector<float>(), l.samples = r.value<std::int32_t>();
    l.unshadowed = r.vector<std::uint8_t>(), l.visibilityVariance = r.image();
  }
  CpuGBuffer& g = f.gbuffer;
  g.width = r.value<std::int32_t>(), g.height = r.value<std::int32_t>();
  g.position = r.vector<glm::vec3>(), g.normal = r.vector<glm::vec3>(), g.valid = r.vector<std::uint8_t>();
  g.shadingNormal = r.vector<glm::vec3>(), g.baseColor = r.vector<glm::vec3>(), g.material = r.vector<glm::vec3>();
  const bool camera = r.value<std::uint8_t>() != 0;
  const auto position = r.value<glm::vec3>();
  if (camera) g.camera = position;
  g.origin = r.value<glm::dvec3>();
  f.memoryBytes = std::size_t(r.value<std::uint64_t>());
  const std::uint64_t stats = r.count(1);
  for (std::uint64_t i = 0; i < stats; ++i) {
    std::string k = r.text();
    f.statistics.emplace_back(std::move(k), r.value<double>());
  }
  if (!r.atEnd()) throw Error(path, "a frame file with bytes after its end");
  return f;
}

}  // namespace penumbra
