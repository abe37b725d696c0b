#include "core/tracking/leap_json.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace handlab::tracking {
namespace {

using util::JsonValue;

constexpr double kMm = 0.001;
constexpr double kMaxDistance = 1.5;  // m from the device; the Leap sees about 0.6 m
constexpr const char* kDigitNames[5] = {"thumb", "index", "middle", "ring", "pinky"};
// Metacarpal length over the three phalanges' (Buchholz et al. 1992), to derive carp positions.
constexpr double kMetacarpalRatio[5] = {0.0, 0.771, 0.686, 0.651, 0.713};

class FrameError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

double number(const JsonValue& v, const char* what) {
  if (!v.is_number()) throw FrameError(std::string(what) + " is not a number");
  const double x = v.as_number();
  if (!std::isfinite(x)) throw FrameError(std::string(what) + " is not finite");
  return x;
}

Eigen::Vector3d vec3(const JsonValue& v, const char* what, double scale = 1.0) {
  if (!v.is_array() || v.size() != 3) throw FrameError(std::string(what) + " is not a 3-vector");
  return scale * Eigen::Vector3d(number(v[0], what), number(v[1], what), number(v[2], what));
}

const JsonValue& member(const JsonValue& object, const char* key) {
  const JsonValue* v = object.find(key);
  if (!v) throw FrameError(std::string("missing ") + key);
  return *v;
}

Eigen::Vector3d position(const JsonValue& object, const char* key) {
  const Eigen::Vector3d p = vec3(member(object, key), key, kMm);
  if (p.norm() > kMaxDistance)
    throw FrameError(std::string(key) + " is " + std::to_string(p.norm()) + " m from the device");
  return p;
}

Eigen::Vector3d unit(const JsonValue& object, const char* key) {
  const Eigen::Vector3d v = vec3(member(object, key), key);
  if (std::abs(v.norm() - 1.0) > 0.1) throw FrameError(std::string(key) + " is not a unit vector");
  return v.normalized();
}

double fraction(const JsonValue& object, const char* key, double fallback) {
  const JsonValue* v = object.find(key);
  if (!v) return fallback;
  const double x = number(*v, key);
  if (x < -1e-6 || x > 1.0 + 1e-6) throw FrameError(std::string(key) + " is outside [0, 1]");
  return x;
}

TrackedFrame parse_frame_or_throw(const JsonValue& frame) {
  if (!frame.is_object()) throw FrameError("the frame is not an object");
  TrackedFrame out;
  out.id = std::int64_t(number(member(frame, "id"), "id"));
  out.timestamp = number(member(frame, "timestamp"), "timestamp") * 1e-6;  // microseconds
  const JsonValue* hands = frame.find("hands");
  if (!hands || !hands->is_array()) throw FrameError("missing hands");
  if (hands->size() > 2) throw FrameError("more than two hands");
  const JsonValue* pointables = frame.find("pointables");
  for (const auto& h : hands->as_array()) {
    TrackedHand hand;
    hand.id = std::int32_t(number(member(h, "id"), "hand id"));
    const std::string& type = member(h, "type").as_string();
    if (type != "left" && type != "right") throw FrameError("hand type '" + type + "'");
    hand.side = type == "left" ? Side::kLeft : Side::kRight;
    hand.palm_position = position(h, "palmPosition");
    hand.palm_normal = unit(h, "palmNormal");
    hand.direction = unit(h, "direction");
    hand.confidence = fraction(h, "confidence", 1.0);
    hand.pinch_strength = fraction(h, "pinchStrength", 0.0);
    hand.grab_strength = fraction(h, "grabStrength", 0.0);
    std::array<bool, 5> seen{};
    bool have_carp = true, have_bases = true;
    std::array<std::array<Eigen::Matrix3d, 4>, 5> bases;
    if (pointables && pointables->is_array()) {
      int order = 0;
      for (const auto& p : pointables->as_array()) {
        if (number(member(p, "handId"), "handId") != hand.id) continue;
        if (const JsonValue* tool = p.find("tool"); tool && tool->is_bool() && tool->as_bool())
          continue;
        // Packed recordings omit "type"; the service numbers a finger hand id * 10 + digit.
        int digit = order++;
        if (const JsonValue* type = p.find("type")) {
          digit = int(number(*type, "pointable type"));
        } else if (const JsonValue* id = p.find("id")) {
          const double offset = number(*id, "pointable id") - 10.0 * hand.id;
          if (offset >= 0 && offset <= 4) digit = int(offset);
        }
        if (digit < 0 || digit > 4) throw FrameError("pointable type " + std::to_string(digit));
        if (seen[std::size_t(digit)])
          throw FrameError(std::string("two ") + kDigitNames[digit] + " pointables");
        seen[std::size_t(digit)] = true;
        auto& j = hand.joints[std::size_t(digit)];
        j[1] = position(p, "mcpPosition");
        j[2] = position(p, "pipPosition");
        j[3] = position(p, "dipPosition");
        j[4] = p.find("btipPosition") ? position(p, "btipPosition") : position(p, "tipPosition");
        if (p.find("carpPosition"))
          j[0] = position(p, "carpPosition");
        else
          have_carp = false;
        const JsonValue* b = p.find("bases");
        if (b && b->is_array() && b->size() == 4) {
          for (int bone = 0; bone < 4; ++bone) {
            const JsonValue& m = (*b)[std::size_t(bone)];
            if (!m.is_array() || m.size() != 3) throw FrameError("bases are not 3x3");
            for (int axis = 0; axis < 3; ++axis)
              bases[std::size_t(digit)][std::size_t(bone)].col(axis) =
                  vec3(m[std::size_t(axis)], "basis");
          }
        } else {
          have_bases = false;
        }
      }
    }
    for (int d = 0; d < 5; ++d)
      if (!seen[std::size_t(d)])
        throw FrameError("hand " + std::to_string(hand.id) + " lacks the " + kDigitNames[d]);
    for (const auto& digit : hand.joints)
      for (int k = 1; k < 5; ++k)
        if ((digit[std::size_t(k)] - hand.palm_position).norm() > 0.4)
          throw FrameError("a joint lies more than 0.4 m from the palm");
    // Derived fields, flagged: see docs/tracking.md.
    const auto& middle = hand.joints[2];
    const double middle_phalanges = (middle[2] - middle[1]).norm() +
                                    (middle[3] - middle[2]).norm() + (middle[4] - middle[3]).norm();
    if (!have_carp) {
      hand.derived |= kDerivedCarp;
      hand.joints[0][0] = hand.joints[0][1];  // the thumb's metacarpal has zero length
      for (int d = 1; d < 5; ++d) {
        auto& j = hand.joints[std::size_t(d)];
        const double phalanges = (j[2] - j[1]).norm() + (j[3] - j[2]).norm() + (j[4] - j[3]).norm();
        j[0] = j[1] - kMetacarpalRatio[d] * phalanges * hand.direction;
      }
    }
    if (const JsonValue* wrist = h.find("wrist")) {
      hand.wrist = vec3(*wrist, "wrist", kMm);
    } else {
      hand.derived |= kDerivedWrist;
      // The palm centre sits 0.25 HL from the wrist crease; the middle finger's phalanges
      // are 0.544 HL (Buchholz et al. 1992).
      hand.wrist = hand.palm_position - 0.25 * (middle_phalanges / 0.544) * hand.direction;
    }
    if (have_bases) hand.bone_bases = bases;
    out.hands.push_back(hand);
  }
  return out;
}

// Packed (formatVersion 2) frames: arrays in the order of the key table in frames[0].
JsonValue unpack(const JsonValue& keys, const JsonValue& values);

JsonValue unpack_object(const JsonValue& keys, const JsonValue& values) {
  if (!values.is_array() || values.size() != keys.size())
    throw FrameError("packed record does not match the key table");
  JsonValue::Object object;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const JsonValue& key = keys[i];
    if (key.is_string()) {
      object.emplace_back(key.as_string(), values[i]);
    } else if (key.is_object() && key.size() == 1) {
      const auto& [name, spec] = key.as_object().front();
      object.emplace_back(name, unpack(spec, values[i]));
    } else {
      throw FrameError("unreadable key table");
    }
  }
  return JsonValue(std::move(object));
}

JsonValue unpack(const JsonValue& spec, const JsonValue& values) {
  // [[keys]]: an array of records; [keys]: one record.
  if (spec.is_array() && spec.size() == 1 && spec[0].is_array()) {
    if (!values.is_array()) throw FrameError("packed list is not an array");
    JsonValue::Array items;
    for (const auto& v : values.as_array()) items.push_back(unpack_object(spec[0], v));
    return JsonValue(std::move(items));
  }
  return unpack_object(spec, values);
}

std::string number_text(double x) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, r.ptr);
}

void append_number(std::string& out, double x) {
  out += number_text(x);
}

void append_vec3(std::string& out, const char* key, const Eigen::Vector3d& v, double scale) {
  out += '"';
  out += key;
  out += "\":[";
  for (int k = 0; k < 3; ++k) {
    if (k) out += ',';
    append_number(out, scale * v[k]);
  }
  out += ']';
}

}  // namespace

std::string leap_message(const TrackedFrame& frame, double frame_rate_hz) {
  constexpr double kToMm = 1000.0;
  std::string out = "{\"id\":";
  append_number(out, double(frame.id));
  out += ",\"timestamp\":";
  append_number(out, std::round(frame.timestamp * 1e6));
  out += ",\"currentFrameRate\":";
  append_number(out, frame_rate_hz);
  out += ",\"hands\":[";
  for (std::size_t i = 0; i < frame.hands.size(); ++i) {
    const TrackedHand& h = frame.hands[i];
    if (i) out += ',';
    out += "{\"id\":";
    append_number(out, h.id);
    out += h.side == Side::kLeft ? ",\"type\":\"left\"," : ",\"type\":\"right\",";
    append_vec3(out, "palmPosition", h.palm_position, kToMm);
    out += ',';
    append_vec3(out, "palmNormal", h.palm_normal, 1.0);
    out += ',';
    append_vec3(out, "direction", h.direction, 1.0);
    if (!(h.derived & kDerivedWrist)) {
      out += ',';
      append_vec3(out, "wrist", h.wrist, kToMm);
    }
    out += ",\"confidence\":";
    append_number(out, h.confidence);
    out += ",\"pinchStrength\":";
    append_number(out, h.pinch_strength);
    out += ",\"grabStrength\":";
    append_number(out, h.grab_strength);
    out += '}';
  }
  out += "],\"pointables\":[";
  bool first = true;
  for (const TrackedHand& h : frame.hands) {
    for (int d = 0; d < 5; ++d) {
      const auto& j = h.joints[std::size_t(d)];
      if (!first) out += ',';
      first = false;
      out += "{\"id\":";
      append_number(out, 10.0 * h.id + d);
      out += ",\"handId\":";
      append_number(out, h.id);
      out += ",\"type\":";
      append_number(out, d);
      out += ",\"tool\":false,";
      if (!(h.derived & kDerivedCarp)) {
        append_vec3(out, "carpPosition", j[0], kToMm);
        out += ',';
      }
      constexpr std::pair<const char*, std::size_t> kJoints[] = {{"mcpPosition", 1},
                                                                 {"pipPosition", 2},
                                                                 {"dipPosition", 3},
                                                                 {"btipPosition", 4},
                                                                 {"tipPosition", 4}};
      for (const auto& [key, k] : kJoints) {
        append_vec3(out, key, j[k], kToMm);
        out += ',';
      }
      append_vec3(out, "direction", (j[4] - j[3]).normalized(), 1.0);
      if (h.bone_bases) {
        out += ",\"bases\":[";
        for (int bone = 0; bone < 4; ++bone) {
          if (bone) out += ',';
          out += '[';
          for (int axis = 0; axis < 3; ++axis) {
            if (axis) out += ',';
            const Eigen::Vector3d c = (*h.bone_bases)[std::size_t(d)][std::size_t(bone)].col(axis);
            out += '[';
            for (int k = 0; k < 3; ++k) {
              if (k) out += ',';
              append_number(out, c[k]);
            }
            out += ']';
          }
          out += ']';
        }
        out += ']';
      }
      out += '}';
    }
  }
  out += "]}";
  return out;
}

std::optional<TrackedFrame> parse_leap_frame(const JsonValue& frame, std::string* error) {
  try {
    return parse_frame_or_throw(frame);
  } catch (const FrameError& e) {
    if (error) *error = e.what();
  } catch (const util::JsonError& e) {
    if (error) *error = e.what();
  }
  return std::nullopt;
}

std::optional<TrackedFrame> parse_leap_message(std::string_view json, std::string* error) {
  try {
    return parse_leap_frame(JsonValue::parse(json), error);
  } catch (const util::JsonError& e) {
    if (error) *error = e.what();
    return std::nullopt;
  }
}

Recording parse_playback(std::string_view json, const std::string& source) {
  Recording recording;
  recording.source = source;
  JsonValue document;
  try {
    document = JsonValue::parse(json);
  } catch (const util::JsonError& e) {
    throw std::runtime_error(source + ": not a LeapJS Playback recording: " + e.what());
  }
  const JsonValue* frames = document.find("frames");
  if (!frames || !frames->is_array()) throw std::runtime_error(source + ": no frames array");
  double version = 0.1;
  if (const JsonValue* metadata = document.find("metadata"))
    if (const JsonValue* v = metadata->find("formatVersion"); v && v->is_number())
      version = v->as_number();
  recording.format_version = number_text(version);
  const bool packed = version >= 2;
  const auto& items = frames->as_array();
  std::size_t first = 0;
  const JsonValue* keys = nullptr;
  if (packed) {
    if (items.empty() || !items[0].is_array())
      throw std::runtime_error(source + ": packed recording without a key table");
    keys = &items[0];
    first = 1;
  }
  recording.frames_in_file = items.size() - first;
  recording.frames.reserve(recording.frames_in_file);
  double last_time = -INFINITY;
  for (std::size_t i = first; i < items.size(); ++i) {
    std::string error;
    std::optional<TrackedFrame> frame;
    if (packed) {
      try {
        frame = parse_leap_frame(unpack_object(*keys, items[i]), &error);
      } catch (const FrameError& e) {
        error = e.what();
      } catch (const util::JsonError& e) {
        error = e.what();
      }
    } else {
      frame = parse_leap_frame(items[i], &error);
    }
    if (frame && frame->timestamp <= last_time) {
      error = "timestamp repeats or goes backwards";
      frame.reset();
    }
    if (!frame) {
      recording.rejected.push_back({i - first, error});
      continue;
    }
    last_time = frame->timestamp;
    recording.frames.push_back(std::move(*frame));
  }
  return recording;
}

}  // namespace handlab::tracking
