// handlab-cli xr: the OpenXR runtime this machine has, and what it offers a study.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/offscreen_eyes.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"
#include "core/task/scene_layout.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "core/xr/headset_view.h"
#include "core/xr/openxr_hand_source.h"
#include "core/xr/openxr_runtime.h"

namespace handlab::cli {
namespace {

double seconds_option(const Arguments& args) {
  const double seconds = args.number("seconds");
  if (!(seconds > 0 && seconds <= 3600)) throw UsageError("--seconds must be between 0 and 3600");
  return seconds;
}

std::vector<OptionSpec> xr_list_options() {
  return {{"json", "OUT", "write what was found as JSON (- for standard output)"}};
}

CommandHelp xr_list_help() {
  return {"xr list",
          {"[json]"},
          "The OpenXR runtime the loader finds (XR_RUNTIME_JSON, else the active runtime), its "
          "headset, whether it tracks hands (XR_EXT_hand_tracking) and which graphics it takes. "
          "Exit status 1 where no runtime answers."};
}

void write_runtime_json(std::ostream& out, const xr::OpenXrRuntimeInfo& info) {
  util::JsonWriter json(out);
  json.begin_object().field("found", info.found);
  if (!info.found) {
    json.field("error", info.error).end_object();
    return;
  }
  json.field("runtime_name", info.runtime_name).field("runtime_version", info.runtime_version);
  json.field("hand_tracking_extension", info.hand_tracking_extension)
      .field("vulkan2", info.vulkan2)
      .field("opengl", info.opengl)
      .field("headless", info.headless);
  json.key("extensions").begin_array();
  for (const std::string& e : info.extensions) json.value(e);
  json.end_array();
  json.key("system").begin_object().field("found", info.system_found);
  if (info.system_found)
    json.field("name", info.system_name)
        .field("vendor_id", double(info.vendor_id))
        .field("tracks_hands", info.system_tracks_hands)
        .field("orientation_tracking", info.orientation_tracking)
        .field("position_tracking", info.position_tracking);
  else
    json.field("error", info.system_error);
  json.end_object().end_object();
}

int xr_list(const std::vector<std::string>& argv) {
  const Arguments args(xr_list_options(), argv, 0);
  if (args.help_requested()) return print_help(xr_list_help(), args);
  const xr::OpenXrRuntimeInfo info = xr::probe_openxr_runtime();
  if (args.has("json"))
    util::write_output(args.text("json"),
                       [&](std::ostream& out) { write_runtime_json(out, info); });
  if (!info.found) throw std::runtime_error(info.error + " (docs/hmd.md says how to start one)");
  if (args.text("json") != "-") std::cout << xr::runtime_description(info);
  return 0;
}

std::vector<OptionSpec> xr_hands_options() {
  return {{"seconds", "S", "how long to record", "5"},
          {"out", "FILE", "the frames as handlab's recording (.hlrec), for tracking info --fit"},
          {"json", "OUT", "write what was recorded as JSON (- for standard output)"}};
}

CommandHelp xr_hands_help() {
  return {"xr hands",
          {"[seconds] [out] [json]"},
          "Records the hands the OpenXR runtime tracks (XR_EXT_hand_tracking, in a session with no "
          "graphics: XR_MND_headless) as tracked frames: each hand's 26 joints read as the "
          "tracked hand a session reads."};
}

struct HandRecording {
  std::vector<tracking::TrackedFrame> frames;
  int left = 0, right = 0;
  double seconds = 0.0;
};

HandRecording record_hands(xr::OpenXrHandSource& source, double seconds) {
  HandRecording r;
  const auto start = std::chrono::steady_clock::now();
  const auto end = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(seconds));
  while (!source.ended() && std::chrono::steady_clock::now() < end) {
    if (!source.wait_for_frame(
            std::min(end, std::chrono::steady_clock::now() + std::chrono::milliseconds(100))))
      continue;
    if (auto f = source.next()) {
      for (const auto& h : f->hands) ++(h.side == tracking::Side::kLeft ? r.left : r.right);
      r.frames.push_back(std::move(*f));
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

int xr_hands(const std::vector<std::string>& argv) {
  const Arguments args(xr_hands_options(), argv, 0);
  if (args.help_requested()) return print_help(xr_hands_help(), args);
  const double seconds = seconds_option(args);
  std::string error;
  auto source = xr::OpenXrHandSource::open(error);
  if (!source) throw std::runtime_error(error + " (docs/hmd.md)");
  const HandRecording r = record_hands(*source, seconds);
  if (args.has("out")) tracking::write_hlrec(r.frames, args.text("out"));
  const double rate =
      r.frames.size() > 1
          ? double(r.frames.size() - 1) / (r.frames.back().timestamp - r.frames.front().timestamp)
          : 0.0;
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter json(out);
      json.begin_object()
          .field("runtime_name", source->runtime_name())
          .field("frames", int(r.frames.size()))
          .field("frame_rate_hz", std::isfinite(rate) ? rate : 0.0)
          .field("left_hands", r.left)
          .field("right_hands", r.right)
          .field("ended_by_runtime", source->ended())
          .end_object();
    });
  if (args.text("json") != "-")
    std::cout << "OpenXR hands from " << source->runtime_name() << ": " << r.frames.size()
              << " frames in " << r.seconds << " s (" << rate << " Hz), " << r.left << " left and "
              << r.right << " right hands"
              << (args.has("out") ? ", written to " + args.text("out") : std::string()) << "\n";
  return 0;
}

std::vector<OptionSpec> xr_show_options() {
  return {
      {"seconds", "S", "how long to show it", "3"},
      {"cube", "METRES", "the cube's side", "0.06"},
      {"eye-width", "PX", "draw each eye at most this wide (0: as the runtime recommends)", "0"},
      {"screenshot", "DIR", "write each eye's last swapchain image, read back from it, as PNG"},
      {"json", "OUT", "write how the frames went as JSON (- for standard output)"}};
}

CommandHelp xr_show_help() {
  return {"xr show",
          {"[seconds] [cube] [eye-width] [screenshot] [json]"},
          "Shows the task scene (the cube on zone A, zone B) in the headset: each eye drawn with "
          "the runtime's view of it into its swapchain (XR_KHR_vulkan_enable2), paced by the "
          "runtime's frame loop, and read back from the swapchain to check the cube is where the "
          "eye's projection puts it."};
}

// Where the last frame put the cube's centre in each eye (pixels): a check of the cameras
// against the world, not against themselves (a near object is further right in the left eye,
// and a table below the eyes is in the picture's lower half).
void write_cube_pixels(util::JsonWriter& json, const xr::DisplayFrame& last,
                       const Eigen::Vector3f& centre) {
  for (int e = 0; e < 2; ++e) {
    Eigen::Vector2f p(-1.0f, -1.0f);
    const render::Image& image = last.read_back[std::size_t(e)];
    render::project_to_pixel(last.cameras[std::size_t(e)], image.width, image.height, centre, &p);
    json.key(e == 0 ? "cube_pixel_left" : "cube_pixel_right")
        .begin_array()
        .value(double(p.x()))
        .value(double(p.y()))
        .end_array();
  }
}

void write_show_json(std::ostream& out, const xr::HeadsetView& headset,
                     const std::string& end_state, const Eigen::Vector3f& cube) {
  const xr::HeadsetCounts counts = headset.counts();
  util::JsonWriter json(out);
  json.begin_object()
      .field("runtime_name", headset.runtime_name())
      .field("eye_width", headset.eye_width())
      .field("eye_height", headset.eye_height())
      .field("frames_drawn", int(counts.shown))
      .field("frames_waited", int(counts.loop.waits))
      .field("frames_begun", int(counts.loop.begins))
      .field("frames_ended", int(counts.loop.ends))
      .field("cube_seen_left", int(counts.cube_seen[0]))
      .field("cube_seen_right", int(counts.cube_seen[1]))
      .field("read_back_as_drawn", int(counts.read_back_as_drawn));
  if (counts.shown) write_cube_pixels(json, headset.last_frame(), cube);
  json.field("end_state", end_state).end_object();
}

int xr_show(const std::vector<std::string>& argv) {
  const Arguments args(xr_show_options(), argv, 0);
  if (args.help_requested()) return print_help(xr_show_help(), args);
  const double seconds = seconds_option(args);
  task::SceneLayout layout;
  layout.cube_size = args.number("cube");
  if (!(layout.cube_size >= 0.005 && layout.cube_size <= 0.1))
    throw UsageError("--cube must be between 0.005 and 0.1 m");
  std::string error, end_state;
  std::mutex state_mutex;
  auto headset = xr::HeadsetView::open(
      error, offscreen_eyes(),
      [&](const std::string& state) {
        std::lock_guard lock(state_mutex);
        end_state = state;
      },
      int(args.integer("eye-width")));
  if (!headset) throw std::runtime_error(error + " (docs/hmd.md)");
  const Eigen::Isometry3d cube = task::cube_start_pose(layout);
  const Eigen::Vector3f centre = cube.translation().cast<float>();
  headset->show(render::draw_task_scene(layout, cube), centre);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!headset->ended() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  headset->close();  // the session ended, its last state reported
  if (!headset->error().empty()) throw std::runtime_error(headset->error());
  const xr::HeadsetCounts counts = headset->counts();
  const xr::DisplayFrame last = headset->last_frame();
  if (args.has("screenshot") && counts.shown) {
    std::filesystem::create_directories(args.text("screenshot"));
    render::write_png(last.read_back[0], args.text("screenshot") + "/eye-left.png");
    render::write_png(last.read_back[1], args.text("screenshot") + "/eye-right.png");
  }
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_show_json(out, *headset, end_state, centre);
    });
  if (!counts.shown)
    throw std::runtime_error("the headset's runtime asked for no frame (session " + end_state +
                             ")");
  if (args.text("json") != "-")
    std::cout << "headset " << headset->runtime_name() << ": " << counts.shown << " frames drawn ("
              << headset->eye_width() << " x " << headset->eye_height()
              << " an eye), the cube where each eye's projection puts it in " << counts.cube_seen[0]
              << " (left) and " << counts.cube_seen[1] << " (right), read back as drawn in "
              << counts.read_back_as_drawn << "; session " << end_state << "\n";
  return 0;
}

}  // namespace

int run_xr(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::cout << family_usage({{xr_list_help(), xr_list_options()},
                               {xr_hands_help(), xr_hands_options()},
                               {xr_show_help(), xr_show_options()}})
              << "\nOpenXR: the headset and its hand tracking (docs/hmd.md).\n";
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "list") return xr_list(rest);
  if (argv[0] == "hands") return xr_hands(rest);
  if (argv[0] == "show") return xr_show(rest);
  throw UsageError("unknown xr command '" + argv[0] + "' (list, hands, show)");
}

}  // namespace handlab::cli
