#include "core/store/frame_record.h"

#include <bit>
#include <cstring>
#include <stdexcept>

#include "core/tracking/recording_io.h"

namespace handlab::store {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the frame encoding is written little-endian as in memory");

constexpr std::uint8_t kEncoding = 1;
constexpr std::size_t kHeader = 16;  // encoding, flags, phase, pad, angles u16, bones u16, time f64

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {}
  void v(const Eigen::Vector3f& p) { put(p.data(), 12); }
  void q(const Eigen::Quaternionf& r) { put(r.coeffs().data(), 16); }
  void put(const void* p, std::size_t n) {
    const std::size_t at = out_.size();
    out_.resize(at + n);
    std::memcpy(out_.data() + at, p, n);
  }

 private:
  std::vector<std::uint8_t>& out_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) : in_(in) {}
  void get(void* p, std::size_t n) {
    if (at_ + n > in_.size()) throw std::runtime_error("frame record is truncated");
    std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  Eigen::Vector3f v() {
    Eigen::Vector3f p;
    get(p.data(), 12);
    return p;
  }
  Eigen::Quaternionf q() {
    Eigen::Quaternionf r;
    get(r.coeffs().data(), 16);
    return r;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
};

}  // namespace

void encode_frame(const FrameRecord& frame, std::vector<std::uint8_t>& out) {
  if (frame.bone_positions.size() != frame.bone_rotations.size())
    throw std::invalid_argument("a frame needs a rotation for every bone position");
  out.clear();
  const std::uint8_t flags =
      std::uint8_t((frame.thumb_contact ? 2 : 0) | (frame.index_contact ? 4 : 0));
  const std::uint16_t angles = std::uint16_t(frame.angles.size());
  const std::uint16_t bones = std::uint16_t(frame.bone_positions.size());
  const std::vector<std::uint8_t> tracked = tracking::encode_frame(frame.tracked);
  const std::uint32_t tracked_size = std::uint32_t(tracked.size());
  out.reserve(kHeader + 4 + tracked.size() + 4 * (7 + angles + 7 * bones + 7));
  Writer w(out);
  const std::uint8_t head[4] = {kEncoding, flags, frame.task_phase, 0};
  w.put(head, 4);
  w.put(&angles, 2);
  w.put(&bones, 2);
  w.put(&frame.time, 8);
  w.put(&tracked_size, 4);
  w.put(tracked.data(), tracked.size());
  w.v(frame.root_position);
  w.q(frame.root_rotation);
  w.put(frame.angles.data(), 4 * frame.angles.size());
  for (std::size_t b = 0; b < bones; ++b) {
    w.v(frame.bone_positions[b]);
    w.q(frame.bone_rotations[b]);
  }
  w.v(frame.cube_position);
  w.q(frame.cube_rotation);
}

FrameRecord decode_frame(std::span<const std::uint8_t> blob) {
  Reader r(blob);
  std::uint8_t head[4];
  r.get(head, 4);
  if (head[0] != kEncoding)
    throw std::runtime_error("frame record has encoding " + std::to_string(head[0]) +
                             ", this handlab reads 1");
  FrameRecord frame;
  std::uint16_t angles, bones;
  r.get(&angles, 2);
  r.get(&bones, 2);
  r.get(&frame.time, 8);
  std::uint32_t tracked_size;
  r.get(&tracked_size, 4);
  std::vector<std::uint8_t> tracked(tracked_size);
  r.get(tracked.data(), tracked_size);
  std::size_t consumed = 0;
  frame.tracked = tracking::decode_frame(tracked.data(), tracked.size(), &consumed);
  if (consumed != tracked.size())
    throw std::runtime_error("frame record's tracked frame is damaged");
  frame.thumb_contact = head[1] & 2;
  frame.index_contact = head[1] & 4;
  frame.task_phase = head[2];
  frame.root_position = r.v();
  frame.root_rotation = r.q();
  frame.angles.resize(angles);
  r.get(frame.angles.data(), 4 * std::size_t(angles));
  for (std::uint16_t b = 0; b < bones; ++b) {
    frame.bone_positions.push_back(r.v());
    frame.bone_rotations.push_back(r.q());
  }
  frame.cube_position = r.v();
  frame.cube_rotation = r.q();
  if (!r.done()) throw std::runtime_error("frame record has trailing bytes");
  return frame;
}

}  // namespace handlab::store
