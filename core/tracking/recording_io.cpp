#include "core/tracking/recording_io.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/tracking/lz_string.h"
#include "core/util/data_files.h"
#include "core/util/output_file.h"

namespace handlab::tracking {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the .hlrec encoding assumes a little-endian host");

constexpr char kMagic[4] = {'H', 'L', 'R', 'C'};
constexpr std::uint32_t kVersion = 1;

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {}
  template <typename T>
  void put(const T& value) {
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &value, sizeof(T));
  }
  void put(const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) put(v[k]);
  }

 private:
  std::vector<std::uint8_t>& out_;
};

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  template <typename T>
  T get() {
    if (at_ + sizeof(T) > size_) throw std::runtime_error("truncated frame record");
    T value;
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  Eigen::Vector3d vec3() {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = get<double>();
    return v;
  }
  std::size_t at() const { return at_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::vector<std::uint8_t> encode_frame(const TrackedFrame& frame) {
  std::vector<std::uint8_t> out;
  Writer w(out);
  w.put(frame.timestamp);
  w.put(frame.id);
  w.put(std::uint8_t(frame.hands.size()));
  for (const TrackedHand& h : frame.hands) {
    w.put(h.id);
    w.put(std::uint8_t(h.side));
    w.put(h.derived);
    w.put(std::uint8_t(h.bone_bases.has_value()));
    w.put(h.confidence);
    w.put(h.pinch_strength);
    w.put(h.grab_strength);
    w.put(h.palm_position);
    w.put(h.palm_normal);
    w.put(h.direction);
    w.put(h.wrist);
    for (const auto& digit : h.joints)
      for (const auto& p : digit) w.put(p);
    if (h.bone_bases)
      for (const auto& digit : *h.bone_bases)
        for (const auto& m : digit)
          for (int k = 0; k < 9; ++k) w.put(m.data()[k]);
  }
  return out;
}

TrackedFrame decode_frame(const std::uint8_t* data, std::size_t size, std::size_t* consumed) {
  Reader r(data, size);
  TrackedFrame frame;
  frame.timestamp = r.get<double>();
  frame.id = r.get<std::int64_t>();
  const int hands = r.get<std::uint8_t>();
  if (hands > 2) throw std::runtime_error("frame record with more than two hands");
  for (int i = 0; i < hands; ++i) {
    TrackedHand h;
    h.id = r.get<std::int32_t>();
    const auto side = r.get<std::uint8_t>();
    if (side > 1) throw std::runtime_error("frame record with an unknown hand side");
    h.side = Side(side);
    h.derived = r.get<std::uint8_t>();
    const bool has_bases = r.get<std::uint8_t>() != 0;
    h.confidence = r.get<double>();
    h.pinch_strength = r.get<double>();
    h.grab_strength = r.get<double>();
    h.palm_position = r.vec3();
    h.palm_normal = r.vec3();
    h.direction = r.vec3();
    h.wrist = r.vec3();
    for (auto& digit : h.joints)
      for (auto& p : digit) p = r.vec3();
    if (has_bases) {
      h.bone_bases.emplace();
      for (auto& digit : *h.bone_bases)
        for (auto& m : digit)
          for (int k = 0; k < 9; ++k) m.data()[k] = r.get<double>();
    }
    frame.hands.push_back(h);
  }
  if (consumed) *consumed = r.at();
  return frame;
}

void write_hlrec(const std::vector<TrackedFrame>& frames, const std::string& path) {
  std::vector<std::uint8_t> out;
  Writer w(out);
  for (char c : kMagic) w.put(c);
  w.put(kVersion);
  w.put(std::uint64_t(frames.size()));
  for (const auto& f : frames) {
    const auto record = encode_frame(f);
    w.put(std::uint32_t(record.size()));
    const std::size_t at = out.size();
    out.resize(at + record.size());
    std::memcpy(out.data() + at, record.data(), record.size());
  }
  util::write_output_bytes(path,
                           std::string_view(reinterpret_cast<const char*>(out.data()), out.size()));
}

Recording read_recording(const std::string& named) {
  const std::string path = util::find_data_file(named);
  const std::string bytes = read_file(path);
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0) {
    Recording recording;
    recording.source = path;
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    Reader header(data + 4, bytes.size() - 4);
    try {
      const auto version = header.get<std::uint32_t>();
      if (version != kVersion)
        throw std::runtime_error("handlab recording version " + std::to_string(version) +
                                 " is newer than this program");
      recording.format_version = "handlab " + std::to_string(version);
      recording.frames_in_file = std::size_t(header.get<std::uint64_t>());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
    std::size_t at = 4 + header.at();
    for (std::size_t i = 0; i < recording.frames_in_file; ++i) {
      try {
        Reader length(data + at, bytes.size() - at);
        const auto n = length.get<std::uint32_t>();
        if (at + 4 + n > bytes.size()) throw std::runtime_error("truncated frame record");
        std::size_t used = 0;
        recording.frames.push_back(decode_frame(data + at + 4, n, &used));
        at += 4 + n;
      } catch (const std::runtime_error& e) {
        for (std::size_t j = i; j < recording.frames_in_file; ++j)
          recording.rejected.push_back({j, e.what()});
        break;
      }
    }
    if (recording.frames.empty() && recording.frames_in_file > 0)
      throw std::runtime_error(path + ": no readable frame");
    return recording;
  }
  std::string json;
  if (ends_with(path, ".lz")) {
    try {
      json = lz_decompress_base64(bytes);
    } catch (const LzStringError& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
  } else {
    json = bytes;
  }
  Recording recording = parse_playback(json, path);
  if (recording.frames.empty() && recording.frames_in_file > 0) {
    throw std::runtime_error(
        path + ": no usable frame (" + std::to_string(recording.rejected.size()) +
        " rejected, first: frame " + std::to_string(recording.rejected.front().index) + ": " +
        recording.rejected.front().reason + ")");
  }
  return recording;
}

}  // namespace handlab::tracking
