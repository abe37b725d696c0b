#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "core/tracking/degraded_recording.h"
#include "core/tracking/frame_source.h"
#include "core/tracking/leap_json.h"
#include "core/tracking/lz_string.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_value.h"

namespace handlab::tracking {
namespace {

// Sample recordings ship in data/leap; test-only data lives in tests/data.
std::string data(const std::string& name) {
  const bool recording = name.rfind("leap/", 0) == 0;
  return std::string(HANDLAB_SOURCE_DIR) + (recording ? "/data/" : "/tests/data/") + name;
}
std::string tmp(const std::string& name) {
  return std::string(HANDLAB_TEST_TMP) + "/" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(LzString, ReferenceVectors) {
  // Made with the reference lz-string 1.5.0 (tests/data/lzstring/make_vectors.js).
  const auto vectors = util::JsonValue::parse(slurp(data("lzstring/vectors.json")));
  ASSERT_GE(vectors.size(), 10u);
  for (const auto& v : vectors.as_array())
    EXPECT_EQ(lz_decompress_base64(v["base64"].as_string()), v["plain"].as_string())
        << v["base64"].as_string();
}

TEST(LzString, CorruptInputIsAnError) {
  EXPECT_THROW(lz_decompress_base64(""), LzStringError);
  EXPECT_THROW(lz_decompress_base64("BYUwNmD2A0A*DukBOYAmQ"), LzStringError);  // '*' is not base64
  EXPECT_THROW(lz_decompress_base64("BYUwNmD2A0AEDu"), LzStringError);         // truncated
}

struct Expected {
  const char* file;
  std::size_t frames;
  const char* version;
};

class RealRecording : public ::testing::TestWithParam<Expected> {};

TEST_P(RealRecording, ReadsCompletely) {
  const Expected e = GetParam();
  const Recording r = read_recording(data(std::string("leap/") + e.file));
  EXPECT_EQ(r.frames_in_file, e.frames);
  EXPECT_EQ(r.frames.size(), e.frames);
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_EQ(r.format_version, e.version);
  for (std::size_t i = 1; i < r.frames.size(); ++i)
    EXPECT_GT(r.frames[i].timestamp, r.frames[i - 1].timestamp);
  for (const auto& f : r.frames)
    for (const auto& h : f.hands) {
      EXPECT_LT(h.palm_position.norm(), 1.0);  // metres, in front of the device
      EXPECT_NEAR(h.palm_normal.norm(), 1.0, 1e-9);
    }
  // The encoding round-trips bit for bit.
  for (const auto& f : r.frames) {
    const auto bytes = encode_frame(f);
    std::size_t used = 0;
    const TrackedFrame back = decode_frame(bytes.data(), bytes.size(), &used);
    EXPECT_EQ(used, bytes.size());
    EXPECT_EQ(encode_frame(back), bytes);
  }
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealRecording,
                         ::testing::Values(Expected{"pinch.json.lz", 307, "0.1"},
                                           Expected{"pinch-57fps.json.lz", 133, "2"},
                                           Expected{"grab.json.lz", 374, "0.1"},
                                           Expected{"wave.json.lz", 111, "0.1"},
                                           Expected{"confidence2.json.lz", 368, "0.1"}),
                         [](const ::testing::TestParamInfo<Expected>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(RealRecording, PinchThumbIndexDistanceRange) {
  const Recording r = read_recording(data("leap/pinch.json.lz"));
  double lo = INFINITY, hi = 0;
  for (const auto& f : r.frames)
    for (const auto& h : f.hands) {
      lo = std::min(lo, thumb_index_distance(h));
      hi = std::max(hi, thumb_index_distance(h));
    }
  EXPECT_NEAR(lo * 1000, 18.0, 0.05);
  EXPECT_NEAR(hi * 1000, 113.0, 0.05);
}

TEST(RealRecording, PackedFormatHasCarpAndBases) {
  const Recording r = read_recording(data("leap/pinch-57fps.json.lz"));
  const auto& h = r.frames.front().hands.front();
  EXPECT_FALSE(h.derived & kDerivedCarp);
  EXPECT_TRUE(h.bone_bases.has_value());
  EXPECT_LT((h.joints[0][0] - h.joints[0][1]).norm(), 1e-9);  // zero-length thumb metacarpal
  const Recording old = read_recording(data("leap/pinch.json.lz"));
  EXPECT_TRUE(old.frames.front().hands.front().derived & kDerivedCarp);
}

TEST(HandlabRecording, WritesAndReadsBackExactly) {
  const Recording r = read_recording(data("leap/pinch-57fps.json.lz"));
  write_hlrec(r.frames, tmp("pinch.hlrec"));
  const Recording back = read_recording(tmp("pinch.hlrec"));
  ASSERT_EQ(back.frames.size(), r.frames.size());
  for (std::size_t i = 0; i < r.frames.size(); ++i)
    EXPECT_EQ(encode_frame(back.frames[i]), encode_frame(r.frames[i]));
}

// Corrupted copies: an error or a partial read with reasons, never a crash.
TEST(CorruptRecording, TruncatedAndFlipped) {
  const std::string original = slurp(data("leap/pinch.json.lz"));
  spit(tmp("truncated.json.lz"), original.substr(0, original.size() / 2));
  EXPECT_THROW(read_recording(tmp("truncated.json.lz")), std::runtime_error);
  std::mt19937 rng(3);
  int errors = 0, partial = 0;
  for (int trial = 0; trial < 30; ++trial) {
    std::string copy = original;
    for (int k = 0; k < 3; ++k) copy[rng() % copy.size()] = "ABCxyz019+/*#"[rng() % 13];
    spit(tmp("flipped.json.lz"), copy);
    try {
      const Recording r = read_recording(tmp("flipped.json.lz"));
      if (!r.rejected.empty()) ++partial;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("flipped.json.lz"), std::string::npos) << e.what();
      ++errors;
    }
  }
  EXPECT_GT(errors + partial, 0);
  spit(tmp("empty.json.lz"), "");
  EXPECT_THROW(read_recording(tmp("empty.json.lz")), std::runtime_error);
  EXPECT_THROW(read_recording(tmp("no-such-file.json")), std::runtime_error);
}

TEST(CorruptRecording, BadFramesAreRejectedWithReasonsAndTheRestKept) {
  // A real recording decompressed, then edited frame by frame.
  const std::string json = lz_decompress_base64(slurp(data("leap/pinch.json.lz")));
  // Edit the real text: a NaN (not JSON at all), then a palm 10 m away and a frame whose
  // hands are missing.
  std::string edited = json;
  auto replace_nth = [&](const std::string& what, const std::string& with, int n) {
    std::size_t at = 0;
    for (int k = 0; k <= n; ++k) {
      at = edited.find(what, k == 0 ? 0 : at + 1);
      ASSERT_NE(at, std::string::npos);
    }
    edited.replace(at, what.size(), with);
  };
  replace_nth("\"palmPosition\":[", "\"palmPosition\":[NaN, ", 5);
  replace_nth("\"palmPosition\":[", "\"palmPosition\":[10000, ", 9);
  spit(tmp("edited.json"), edited);
  // NaN is not JSON: the whole document fails to parse, and the error names the file.
  EXPECT_THROW(read_recording(tmp("edited.json")), std::runtime_error);

  edited = json;
  replace_nth("\"palmPosition\":[", "\"palmPosition\":[10000, 0, 0], \"x\":[", 9);
  replace_nth("\"hands\":[", "\"hand\":[", 20);
  spit(tmp("edited.json"), edited);
  const Recording r = read_recording(tmp("edited.json"));
  EXPECT_EQ(r.frames_in_file, 307u);
  EXPECT_EQ(r.rejected.size(), 2u);
  EXPECT_EQ(r.frames.size(), 305u);
  bool far = false, missing = false;
  for (const auto& rej : r.rejected) {
    far |= rej.reason.find("m from the device") != std::string::npos;
    missing |= rej.reason.find("missing hands") != std::string::npos;
  }
  EXPECT_TRUE(far);
  EXPECT_TRUE(missing);
}

TEST(LeapMessage, V6FrameAndBadMessages) {
  const std::string message = R"({"id": 5, "timestamp": 1000000, "hands": [], "pointables": []})";
  std::string error;
  const auto frame = parse_leap_message(message, &error);
  ASSERT_TRUE(frame) << error;
  EXPECT_DOUBLE_EQ(frame->timestamp, 1.0);
  EXPECT_TRUE(frame->hands.empty());
  EXPECT_FALSE(parse_leap_message("{\"id\": 5", &error));
  EXPECT_NE(error.find("JSON"), std::string::npos);
  EXPECT_FALSE(parse_leap_message(R"({"id": 5, "timestamp": 1})", &error));
  EXPECT_NE(error.find("hands"), std::string::npos);
}

// What a replayed recording sends: every frame of the two recording formats written as the
// service's message and read back to the same frame (to the rounding of mm and µs), with
// the derived fields still marked derived and the bases kept.
TEST(LeapMessage, RecordingsRoundTripThroughTheServiceMessage) {
  for (const char* name : {"leap/pinch.json.lz", "leap/pinch-57fps.json.lz"}) {
    const Recording recording = read_recording(data(name));
    for (const TrackedFrame& f : recording.frames) {
      std::string error;
      const auto back = parse_leap_message(leap_message(f, 110.0), &error);
      ASSERT_TRUE(back) << name << " frame " << f.id << ": " << error;
      EXPECT_EQ(back->id, f.id);
      EXPECT_NEAR(back->timestamp, f.timestamp, 1e-6);
      ASSERT_EQ(back->hands.size(), f.hands.size());
      for (std::size_t i = 0; i < f.hands.size(); ++i) {
        const TrackedHand &a = f.hands[i], &b = back->hands[i];
        EXPECT_EQ(b.id, a.id);
        EXPECT_EQ(b.side, a.side);
        EXPECT_EQ(b.derived, a.derived);
        EXPECT_DOUBLE_EQ(b.pinch_strength, a.pinch_strength);
        EXPECT_LT((b.palm_position - a.palm_position).norm(), 1e-12);
        EXPECT_LT((b.palm_normal - a.palm_normal).norm(), 1e-12);
        EXPECT_LT((b.wrist - a.wrist).norm(), 1e-12);
        for (int d = 0; d < 5; ++d)
          for (int k = 0; k < 5; ++k)
            EXPECT_LT((b.joints[d][k] - a.joints[d][k]).norm(), 1e-12) << d << " " << k;
        ASSERT_EQ(b.bone_bases.has_value(), a.bone_bases.has_value());
        if (a.bone_bases) {
          for (int d = 0; d < 5; ++d)
            for (int bone = 0; bone < 4; ++bone)
              EXPECT_TRUE((*b.bone_bases)[d][bone].isApprox((*a.bone_bases)[d][bone], 1e-12));
        }
      }
    }
  }
}

}  // namespace
}  // namespace handlab::tracking

namespace handlab::tracking {
namespace {

TEST(CorruptRecording, RepeatedAndBackwardTimestampsAreRejected) {
  const std::string doc = R"({"metadata": {"formatVersion": 1}, "frames": [
      {"id": 1, "timestamp": 1000, "hands": []},
      {"id": 2, "timestamp": 1000, "hands": []},
      {"id": 3, "timestamp": 500, "hands": []},
      {"id": 4, "timestamp": 2000, "hands": []},
      "not a frame"]})";
  const Recording r = parse_playback(doc, "test.json");
  EXPECT_EQ(r.frames_in_file, 5u);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[1].id, 4);
  ASSERT_EQ(r.rejected.size(), 3u);
  EXPECT_EQ(r.rejected[0].index, 1u);
  EXPECT_NE(r.rejected[0].reason.find("timestamp"), std::string::npos);
  EXPECT_NE(r.rejected[2].reason.find("not an object"), std::string::npos);
}

}  // namespace
}  // namespace handlab::tracking

#include "core/tracking/hand_fitting.h"

namespace handlab::tracking {
namespace {

// Real frames fitted by the tracked skeleton measured from the same recording.
TEST_P(RealRecording, FramesAreFittedByTheTrackedSkeleton) {
  const Recording r = read_recording(data(std::string("leap/") + GetParam().file));
  for (Side side : {Side::kLeft, Side::kRight}) {
    auto fitter = TrackedHandFitter::for_recording(r.frames, side);
    if (!fitter) continue;
    double sum = 0.0, worst = 0.0;
    int n = 0;
    for (const auto& f : r.frames)
      if (const TrackedHand* h = f.hand(side)) {
        const hand::FitResult fit = fitter->fit(*h);
        sum += fit.rms_residual;
        worst = std::max(worst, fit.max_residual);
        ++n;
      }
    std::printf("%s %s hand: %d frames, mean RMS residual %.2f mm, max %.2f mm\n", GetParam().file,
                side == Side::kLeft ? "left" : "right", n, 1000 * sum / n, 1000 * worst);
    EXPECT_LT(sum / n, 0.002);
    EXPECT_LT(worst, 0.015);
  }
}

TEST(TrackedHandFitting, HandLengthFromFrames) {
  const Recording r = read_recording(data("leap/pinch.json.lz"));
  const auto length = estimate_hand_length(r.frames, Side::kRight);
  ASSERT_TRUE(length);
  EXPECT_GT(*length, 0.14);
  EXPECT_LT(*length, 0.22);
  EXPECT_FALSE(estimate_hand_length(r.frames, Side::kLeft));
}

}  // namespace
}  // namespace handlab::tracking

#include "core/tracking/frame_source.h"

namespace handlab::tracking {
namespace {

// A recording degraded as low tracking confidence degrades it: each joint's noise has the
// standard deviation asked for; a jumping finger turns rigidly about its knuckle (its bones
// keep their lengths) for a few frames at a time; resampled, the frames come at the rate;
// the same seed gives the same frames, another seed others; nonsense is refused.
TEST(DegradedRecording, NoiseJumpsAndRateAsAsked) {
  const Recording recording = read_recording(data("leap/pinch.json.lz"));
  const std::vector<TrackedFrame>& frames = recording.frames;
  Degradation noisy;
  noisy.joint_noise = 0.002;
  const std::vector<TrackedFrame> a = degrade(frames, noisy);
  ASSERT_EQ(a.size(), frames.size());
  double sum = 0.0;
  long count = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (std::size_t h = 0; h < frames[i].hands.size(); ++h)
      for (std::size_t d = 0; d < 5; ++d)
        for (std::size_t k = 0; k < 5; ++k) {
          const Eigen::Vector3d e = a[i].hands[h].joints[d][k] - frames[i].hands[h].joints[d][k];
          sum += e.squaredNorm();
          count += 3;
        }
  ASSERT_GT(count, 10000);
  EXPECT_NEAR(std::sqrt(sum / double(count)), 0.002, 0.0001);
  EXPECT_EQ(degrade(frames, noisy)[7].hands.at(0).joints[1][4], a[7].hands.at(0).joints[1][4]);
  noisy.seed = 2;
  EXPECT_NE(degrade(frames, noisy)[7].hands.at(0).joints[1][4], a[7].hands.at(0).joints[1][4]);

  Degradation jumpy;
  jumpy.jump_chance = 0.05;
  const std::vector<TrackedFrame> b = degrade(frames, jumpy);
  int moved = 0, still = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (std::size_t h = 0; h < frames[i].hands.size(); ++h)
      for (std::size_t d = 0; d < 5; ++d) {
        const auto& was = frames[i].hands[h].joints[d];
        const auto& now = b[i].hands[h].joints[d];
        EXPECT_EQ(now[1], was[1]) << "the knuckle stays";
        for (std::size_t k = 1; k < 4; ++k)
          EXPECT_NEAR((now[k + 1] - now[k]).norm(), (was[k + 1] - was[k]).norm(), 1e-12);
        ((now[4] - was[4]).norm() > 1e-9 ? moved : still) += 1;
      }
  // Each jump lasts three frames: about three in 1 / 0.05 + 3 frames of a finger are moved.
  const double share = double(moved) / double(moved + still);
  EXPECT_GT(share, 0.08);
  EXPECT_LT(share, 0.18);

  Degradation slow;
  slow.rate_hz = 74.0;
  const std::vector<TrackedFrame> c = degrade(frames, slow);
  const double span = frames.back().timestamp - frames.front().timestamp;
  EXPECT_NEAR(double(c.size()), span * 74.0, 2.0);
  EXPECT_NEAR(c[1].timestamp - c[0].timestamp, 1.0 / 74.0, 1e-9);

  Degradation bad;
  bad.jump_chance = 1.5;
  EXPECT_THROW(degrade(frames, bad), std::invalid_argument);
  bad = {};
  bad.joint_noise = -1.0;
  EXPECT_THROW(degrade(frames, bad), std::invalid_argument);
}

TEST(Replay, AsFastAsPossibleAndRealTime) {
  const Recording r = read_recording(data("leap/wave.json.lz"));
  RecordingReplay fast(r.frames);
  std::size_t n = 0;
  while (fast.next()) ++n;
  EXPECT_EQ(n, r.frames.size());
  double slept = 0.0;
  ReplayOptions realtime;
  realtime.pace = ReplayPace::kRealTime;
  realtime.sleep = [&](double s) { slept += s; };
  RecordingReplay paced(r.frames, realtime);
  while (paced.next()) {
  }
  EXPECT_NEAR(slept, r.frames.back().timestamp - r.frames.front().timestamp, 1e-9);
}

TEST(Replay, ResampledToAFixedRate) {
  const Recording r = read_recording(data("leap/pinch-57fps.json.lz"));
  ReplayOptions options;
  options.pace = ReplayPace::kResampled;
  options.rate_hz = 120.0;
  RecordingReplay replay(r.frames, options);
  std::vector<TrackedFrame> out;
  while (auto f = replay.next()) out.push_back(*f);
  const double duration = r.frames.back().timestamp - r.frames.front().timestamp;
  EXPECT_EQ(out.size(), std::size_t(std::floor(duration * 120.0 + 1e-9)) + 1);
  for (std::size_t i = 1; i < out.size(); ++i)
    EXPECT_NEAR(out[i].timestamp - out[i - 1].timestamp, 1.0 / 120, 1e-9);
  for (const auto& f : out)
    for (const auto& h : f.hands) {
      EXPECT_NEAR(h.palm_normal.norm(), 1.0, 1e-9);
      EXPECT_NEAR(h.palm_normal.dot(h.direction), 0.0, 1e-9);
      ASSERT_TRUE(h.bone_bases.has_value());
      const Eigen::Matrix3d& m = (*h.bone_bases)[1][2];
      EXPECT_TRUE((m.transpose() * m).isIdentity(1e-9));
    }
  // At a recorded timestamp the interpolation returns the recorded positions.
  const TrackedFrame at = interpolate(r.frames[10], r.frames[11], r.frames[10].timestamp);
  EXPECT_LT((at.hands[0].joints[1][4] - r.frames[10].hands[0].joints[1][4]).norm(), 1e-12);
  const TrackedFrame mid = interpolate(r.frames[10], r.frames[11],
                                       0.5 * (r.frames[10].timestamp + r.frames[11].timestamp));
  EXPECT_LT((mid.hands[0].palm_position -
             0.5 * (r.frames[10].hands[0].palm_position + r.frames[11].hands[0].palm_position))
                .norm(),
            1e-12);
}

}  // namespace
}  // namespace handlab::tracking
