// handlab-cli as a user calls it: exit status, one-line errors, the files it writes.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/render/image.h"
#include "core/util/build_info.h"
#include "core/util/json_value.h"
#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/under_sanitizers.h"

namespace handlab {
namespace {

using Result = test::CliResult;
using handlab::test::run_cli;

// The version is CMakeLists.txt's, with the commit the build was made from.
TEST(Cli, VersionNamesTheVersionAndTheCommit) {
  const Result r = run_cli("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "handlab-cli " + util::version_line() + "\n");
  EXPECT_NE(util::build_commit(), "") << r.out;
  EXPECT_EQ(util::program_version().find_first_not_of("0123456789."), std::string::npos);
}

// study info: the study, its schema, and the version that made it.
TEST(Cli, StudyInfoShowsTheVersionsThatWroteTheStudy) {
  const std::string db = handlab::test::fresh_path("cli_info.db");
  ASSERT_EQ(run_cli("study create --protocol " + std::string(HANDLAB_SOURCE_DIR) +
                    "/studies/fine-manipulation-2021.json --db " + db)
                .status,
            0);
  const Result text = run_cli("study info --db " + db);
  ASSERT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("handlab " + util::version_line()), std::string::npos) << text.out;
  const Result json = run_cli("study info --db " + db + " --json -");
  ASSERT_EQ(json.status, 0) << json.out;
  const util::JsonValue doc = util::JsonValue::parse(json.out);
  EXPECT_EQ(doc["schema_version"].as_number(), 7);
  ASSERT_EQ(doc["programs"].size(), 1u);
  EXPECT_EQ(doc["programs"][0]["version"].as_string(), util::program_version());
  EXPECT_EQ(doc["programs"][0]["commit"].as_string(), util::build_commit());
  EXPECT_EQ(run_cli("study info").status, 2);
}

TEST(Cli, HelpListsCommandsAndEachCommandHasHelp) {
  const Result r = run_cli("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("render"), std::string::npos);
  // Every name stands apart from its summary, the longest too.
  for (const char* name : {"  replications  ", "  participant  ", "  analyze  "})
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  const Result h = run_cli("render --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.out.find("--width"), std::string::npos);
}

// The "--name" words of `text`.
std::set<std::string> option_words(const std::string& text) {
  std::set<std::string> words;
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at + 2)) {
    std::size_t end = at + 2;
    while (end < text.size() &&
           (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-'))
      ++end;
    if (end > at + 2) words.insert(text.substr(at, end - at));
  }
  return words;
}

// Every command's usage is written from its option table (app/cli/command_help.h): each
// option a usage line names is one its --help lists, a family's list of its subcommands says
// what each subcommand's own --help says, a usage that leaves options out says so, and
// each option says its default once.
TEST(Cli, EveryUsageNamesOnlyTheOptionsItsTableHas) {
  const Result top = run_cli("--help");
  std::vector<std::string> commands;
  for (std::size_t at = top.out.find("\n  "); at != std::string::npos;
       at = top.out.find("\n  ", at + 1))
    commands.push_back(top.out.substr(at + 3, top.out.find(' ', at + 3) - at - 3));
  ASSERT_GE(commands.size(), 15u) << top.out;
  int checked = 0;
  for (const std::string& command : commands) {
    const Result own = run_cli(command + " --help");
    ASSERT_EQ(own.status, 0) << command << ": " << own.out;
    ASSERT_EQ(own.out.rfind("Usage: handlab-cli " + command + " ", 0), 0u) << own.out;
    std::vector<std::string> lines;  // the usage lines: a family's list its subcommands
    for (std::size_t at = 0; at < own.out.size();) {
      const std::size_t end = own.out.find('\n', at);
      const std::string line = own.out.substr(at, end - at);
      if (line.find("handlab-cli " + command) == std::string::npos) break;
      lines.push_back(line);
      at = end + 1;
    }
    for (const std::string& line : lines) {
      const std::string called = line.substr(line.find("handlab-cli ") + 12);
      const std::string sub = called.substr(
          command.size() + 1, called.find(' ', command.size() + 1) - command.size() - 1);
      const bool family = !sub.empty() && sub[0] != '-' && sub[0] != '[' &&
                          std::islower(static_cast<unsigned char>(sub[0])) &&
                          own.out.find("\nOptions:\n") == std::string::npos;
      const Result help = family ? run_cli(command + " " + sub + " --help") : own;
      ASSERT_EQ(help.status, 0) << line;
      const std::string table = help.out.substr(help.out.find("\nOptions:\n"));
      const std::set<std::string> listed = option_words(table);
      // An option says its default once: in its words, or as the table's value.
      for (std::size_t at = table.find('\n'); at != std::string::npos;
           at = table.find('\n', at + 1)) {
        const std::string row = table.substr(at + 1, table.find('\n', at + 1) - at - 1);
        const std::size_t first = row.find("default");
        EXPECT_TRUE(first == std::string::npos ||
                    row.find("default", first + 1) == std::string::npos)
            << row;
      }
      for (const std::string& word : option_words(line)) {
        EXPECT_TRUE(listed.count(word)) << line << ": " << word;
      }
      if (family) {
        EXPECT_NE(help.out.find(line.substr(7)), std::string::npos)
            << "the family's line is not " << command << " " << sub << "'s own:\n"
            << help.out;
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 30);
  EXPECT_EQ(run_cli("render --help").out.rfind("Usage: handlab-cli render [options]\n", 0), 0u);
}

TEST(Cli, ErrorsAreOneLineWithNonZeroStatus) {
  for (const char* args : {"no-such-command", "render --width", "render --width abc",
                           "render --bogus 1", "render --out /no/such/dir/x.png"}) {
    const Result r = run_cli(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << args << ": " << r.out;
  }
}

TEST(Cli, RenderWritesThePicture) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/cli_scene.png";
  std::filesystem::remove(path);
  const Result r = run_cli("render --out " + path + " --width 320 --height 200");
  ASSERT_EQ(r.status, 0) << r.out;
  int w = 0, h = 0;
  ASSERT_TRUE(handlab::render::read_png_size(path, &w, &h));
  EXPECT_EQ(w, 320);
  EXPECT_EQ(h, 200);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  return path;
}

const char* kGood =
    "id,cond,block,y\n"
    "s1,a,1,1.5\ns1,b,1,2.5\ns1,a,2,1.7\ns1,b,2,2.9\n"
    "s2,a,1,1.1\ns2,b,1,2.0\ns2,a,2,1.2\ns2,b,2,2.2\n"
    "s3,a,1,0.9\ns3,b,1,2.2\ns3,a,2,1.0\ns3,b,2,2.4\n";

TEST(CliHand, WritesSkinFleshAndPicture) {
  const std::string dir = std::string(HANDLAB_TEST_TMP) + "/";
  const Result r = run_cli("hand --length 0.214 --out " + dir + "hand.obj --tets " + dir +
                           "hand.vtk --png " + dir + "hand.png --pair --json " + dir + "hand.json");
  ASSERT_EQ(r.status, 0) << r.out;
  std::FILE* vtk = std::fopen((dir + "hand.vtk").c_str(), "rb");
  ASSERT_NE(vtk, nullptr);
  char line[256];
  int cells = 0;
  while (std::fgets(line, sizeof line, vtk))
    if (std::sscanf(line, "CELLS %d", &cells) == 1) break;
  std::fclose(vtk);
  EXPECT_GE(cells, 2000);
  EXPECT_LE(cells, 2800);
  int w = 0, h = 0;
  EXPECT_TRUE(handlab::render::read_png_size(dir + "hand.png", &w, &h));
  const Result tracked = run_cli("hand --tracked --length 0.18");
  EXPECT_EQ(tracked.status, 0);
  EXPECT_NE(tracked.out.find("tracked (Leap) skeleton"), std::string::npos);
  EXPECT_NE(run_cli("hand --length 0.5").status, 0);
}

TEST(CliTracking, InfoJsonAndBadFiles) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const std::string json = std::string(HANDLAB_TEST_TMP) + "/pinch_info.json";
  const Result r = run_cli("tracking info " + recording + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("18.0 to 113.0 mm"), std::string::npos) << r.out;
  std::FILE* f = std::fopen(json.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  std::string text(1 << 16, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  for (const char* key :
       {"\"format_version\"", "\"frames\": 307", "\"frames_with_hands\": 307", "\"hands\"",
        "\"duration_s\"", "\"fps_mean\"", "\"rejected\": []", "\"thumb_index_mm\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  const std::string csv = std::string(HANDLAB_TEST_TMP) + "/pinch.csv";
  EXPECT_EQ(run_cli("tracking convert " + recording + " --out " + csv).status, 0);
  // A truncated copy: nothing usable remains, so a one-line error and a non-zero status.
  const std::string truncated =
      write_temp("cut.json.lz", "N4IgZgTghgtgpgZxALgNqgMYFcITgOwBcAxaeAJSkLhQEZaBWAOgGYBOAJg");
  const Result bad = run_cli("tracking info " + truncated);
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
  EXPECT_NE(bad.out.find("cut.json.lz"), std::string::npos) << bad.out;
}

// The recording read as OpenXR's 26 joints: the fit's residual is the mapping's error, and the
// Leap's own joints fit the same on this recording (0.8 mm, at most 2.5 mm).
TEST(CliTracking, InfoViaOpenXrFitsAsTheLeapsJoints) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const Result r = run_cli("tracking info " + recording + " --fit --via-openxr --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* key : {"\"via_openxr\": true", "\"frames\": 307"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  const Result text = run_cli("tracking info " + recording + " --fit --via-openxr");
  EXPECT_NE(text.out.find("read through OpenXR's 26 joints"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("residual mean 0.8 mm, max 2.5 mm"), std::string::npos) << text.out;
}

// A protocol's "session" defaults hold where no option says otherwise: the headset and
// OpenXR's hands named there are opened (and, with no runtime, refused in one line); the
// options choose otherwise; the Leap, which only the app reads live, is refused by name.
TEST(CliSession, TheProtocolsSessionDefaultsHoldWhereNoOptionIsGiven) {
  auto study = [](const std::string& session, const std::string& name) {
    const std::string protocol = handlab::test::headset_protocol_with_session(session, name);
    const std::string db = handlab::test::fresh_path(name + ".db");
    EXPECT_EQ(run_cli("study create --protocol " + protocol + " --db " + db).status, 0);
    EXPECT_EQ(run_cli("participant add --db " + db +
                      " --id P1 --age 30 --sex F --handedness right --hand-length 0.18 "
                      "--vr-experience none")
                  .status,
              0);
    return db;
  };
  const std::string headset = study(R"({"display": "headset", "tracker": "scripted"})", "cli_hs");
  const std::string hands = study(R"({"tracker": "openxr"})", "cli_hands");
  const std::string leap = study(R"({"tracker": "leap"})", "cli_leap");
  const std::string missing = std::string(HANDLAB_TEST_TMP) + "/no-such-runtime.json";
  setenv("XR_RUNTIME_JSON", missing.c_str(), 1);
  const Result by_default = run_cli("session run --db " + headset + " --participant P1");
  const Result on_hands = run_cli("session run --db " + hands + " --participant P1");
  const Result chosen = run_cli("session run --db " + headset +
                                " --participant P1 --tracker scripted --display none --quiet");
  unsetenv("XR_RUNTIME_JSON");
  EXPECT_EQ(by_default.status, 1);
  EXPECT_NE(by_default.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos)
      << by_default.out;
  EXPECT_EQ(chosen.status, 0) << chosen.out;
  // The hands without the headset: a session with no graphics, which no runtime gives here.
  EXPECT_EQ(on_hands.status, 1);
  EXPECT_NE(on_hands.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos) << on_hands.out;
  const Result on_leap = run_cli("session run --db " + leap + " --participant P1");
  EXPECT_NE(on_leap.status, 0);
  EXPECT_NE(on_leap.out.find("the protocol's session tracker is the Leap"), std::string::npos)
      << on_leap.out;
}

// Where no OpenXR runtime answers, each xr command says so in one line (the loader's own log
// silenced) and fails; a real runtime is the `openxr` test's (tests/openxr).
TEST(CliXr, WithoutARuntimeEachCommandSaysSoInOneLine) {
  const std::string missing = std::string(HANDLAB_TEST_TMP) + "/no-such-runtime.json";
  setenv("XR_RUNTIME_JSON", missing.c_str(), 1);
  const Result list = run_cli("xr list");
  const Result json = run_cli("xr list --json -");
  const Result hands = run_cli("xr hands --seconds 1");
  const Result zero = run_cli("xr hands --seconds 0");
  const Result show = run_cli("xr show --seconds 1");
  const std::string db = handlab::test::fresh_path("cli_xr.db");
  ASSERT_EQ(run_cli("study create --protocol " + std::string(HANDLAB_SOURCE_DIR) +
                    "/tests/openxr/headset-protocol.json --db " + db)
                .status,
            0);
  ASSERT_EQ(run_cli("participant add --db " + db +
                    " --id P1 --age 30 --sex F --handedness right --hand-length 0.18 "
                    "--vr-experience none")
                .status,
            0);
  const Result session = run_cli("session run --db " + db + " --participant P1 --tracker openxr");
  const Result shown = run_cli("session run --db " + db + " --participant P1 --display headset");
  const Result both =
      run_cli("session run --db " + db + " --participant P1 --tracker openxr --display headset");
  unsetenv("XR_RUNTIME_JSON");
  EXPECT_EQ(shown.status, 1);
  EXPECT_EQ(std::count(shown.out.begin(), shown.out.end(), '\n'), 1) << shown.out;
  EXPECT_NE(shown.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos) << shown.out;
  EXPECT_EQ(both.status, 1);
  EXPECT_EQ(std::count(both.out.begin(), both.out.end(), '\n'), 1) << both.out;
  EXPECT_EQ(session.status, 1);
  EXPECT_EQ(std::count(session.out.begin(), session.out.end(), '\n'), 1) << session.out;
  EXPECT_NE(session.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos) << session.out;
  EXPECT_EQ(list.status, 1);
  EXPECT_EQ(list.out,
            "handlab-cli xr: no OpenXR runtime answered: XR_ERROR_RUNTIME_UNAVAILABLE (docs/hmd.md "
            "says how to start one)\n");
  EXPECT_NE(json.out.find("\"found\": false"), std::string::npos) << json.out;
  EXPECT_EQ(hands.status, 1);
  EXPECT_EQ(std::count(hands.out.begin(), hands.out.end(), '\n'), 1) << hands.out;
  EXPECT_NE(hands.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos) << hands.out;
  EXPECT_EQ(zero.status, 2) << zero.out;
  EXPECT_EQ(show.status, 1);
  EXPECT_EQ(std::count(show.out.begin(), show.out.end(), '\n'), 1) << show.out;
  EXPECT_NE(show.out.find("XR_ERROR_RUNTIME_UNAVAILABLE"), std::string::npos) << show.out;
}

TEST(CliRetarget, SummaryKeysAndDeterministicCsv) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const std::string dir = std::string(HANDLAB_TEST_TMP) + "/";
  for (const char* strategy : {"ours", "naive"}) {
    const std::string base = dir + "retarget_" + strategy;
    ASSERT_EQ(run_cli("retarget " + recording + " --strategy " + strategy + " --csv " + base +
                      "_1.csv --json " + base + ".json")
                  .status,
              0);
    // Extra timing runs (fresh retargeters) change no result, only how frames are timed.
    ASSERT_EQ(run_cli("retarget " + recording + " --strategy " + strategy + " --csv " + base +
                      "_2.csv --timing-runs 3 --json " + base + "_3.json")
                  .status,
              0);
    auto slurp = [](const std::string& path) {
      std::FILE* f = std::fopen(path.c_str(), "rb");
      std::string text(1 << 20, '\0');
      text.resize(f ? std::fread(text.data(), 1, text.size(), f) : 0);
      if (f) std::fclose(f);
      return text;
    };
    EXPECT_EQ(slurp(base + "_1.csv"), slurp(base + "_2.csv")) << strategy;
    EXPECT_NE(slurp(base + "_3.json").find("\"runs\": 3"), std::string::npos) << strategy;
    const std::string json = slurp(base + ".json");
    for (const char* key :
         {"\"frames\": 307", "\"time_us\"", "\"median\"", "\"p99\"", "\"iterations\"",
          "\"tip_error_mm\"", "\"pinky\"", "\"pinch_frames\"", "\"pinch_tip_error_mm\"",
          "\"pinch_gap_error_mm\"", "\"joint_limit_violation_max_rad\""})
      EXPECT_NE(json.find(key), std::string::npos) << strategy << " " << key;
    const auto at = json.find("\"joint_limit_violation_max_rad\": ");
    ASSERT_NE(at, std::string::npos);
    EXPECT_LT(std::strtod(json.c_str() + at + 33, nullptr), 1e-9) << strategy;
  }
  EXPECT_EQ(run_cli("retarget " + recording + " --strategy magic").status, 2);
  EXPECT_EQ(run_cli("retarget " + recording + " --timing-runs 0").status, 2);
}

// The recording degraded as low tracking confidence degrades it (noise, jumping fingers,
// another frame rate): the frames resampled, the degradation in the summary, the same seed
// the same per-frame results, nonsense refused with a one-line error.
TEST(CliRetarget, DegradedAsLowConfidenceTracking) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const std::string base = std::string(HANDLAB_TEST_TMP) + "/retarget_degraded";
  const std::string degrade = " --frame-rate 74 --joint-noise 0.002 --jump-chance 0.02";
  const Result r =
      run_cli("retarget " + recording + degrade + " --csv " + base + "_1.csv --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* key : {"\"frames\": 199", "\"degradation\"", "\"joint_noise_m\": 0.002",
                          "\"frame_rate_hz\": 74", "\"seed\": 1"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  ASSERT_EQ(run_cli("retarget " + recording + degrade + " --csv " + base + "_2.csv").status, 0);
  EXPECT_EQ(handlab::test::file_bytes(base + "_1.csv"), handlab::test::file_bytes(base + "_2.csv"));
  const Result bad = run_cli("retarget " + recording + " --jump-chance 2");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--jump-chance must be 0 to 1"), std::string::npos) << bad.out;
  EXPECT_EQ(run_cli("retarget " + recording + " --frame-rate 5").status, 2);
  EXPECT_EQ(run_cli("retarget " + recording + " --degrade-seed -1").status, 2);
  // A usage error before the recording is read.
  EXPECT_EQ(run_cli("retarget /no/such/recording.json.lz --joint-noise 1").status, 2);
}

TEST(CliRetarget, DrawsThePinchPicture) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const std::string png = std::string(HANDLAB_TEST_TMP) + "/retarget_pinch.png";
  std::remove(png.c_str());
  const Result r = run_cli("retarget " + recording + " --picture " + png + " --json /dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("frame 133040"), std::string::npos) << r.out;  // the strongest pinch
  int width = 0, height = 0;
  ASSERT_TRUE(handlab::render::read_png_size(png, &width, &height));
  EXPECT_EQ(width, 1500);
  EXPECT_EQ(height, 600);
  EXPECT_EQ(run_cli("retarget " + recording + " --picture " + png + " --frame 1").status, 1);
}

// A real recording on the soft hand: played, and held still in one of its poses (index 40).
TEST(CliSim, ReplayDrivesTheSoftHandByARecording) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const std::string json = test::fresh_path("sim_replay.json");
  const Result held =
      run_cli("sim replay " + recording + " --hold --frame 40 --duration 2 --json " + json);
  ASSERT_EQ(held.status, 0) << held.out;
  EXPECT_NE(held.out.find("held still"), std::string::npos) << held.out;
  EXPECT_NE(held.out.find("ms a step by part: evaluate"), std::string::npos) << held.out;
  const std::string text = test::file_bytes(json);
  for (const char* key :
       {"\"strategy\": \"ours\"", "\"hold\": true", "\"frame\": 40", "\"newton_iterations\": 1",
        "\"steps\": 240", "\"step_ms_median\"", "\"step_ms_p95\"", "\"factorizations\"",
        "\"linear_iterations_per_step\"", "\"fastest_node_last_half_second_m_s\"",
        "\"timer_seconds\"", "\"factorize\""})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;
  const std::size_t at = text.find("\"fastest_node_last_half_second_m_s\": ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_LT(std::stod(text.substr(at + 37)), 1e-3) << "m/s: the held hand came to rest";
  // A physics change reaches the hand: pose 0 comes to rest where short steps iterate again (the
  // default), and cycles under one Newton iteration a step without them (docs/simulator.md, "The
  // short step's iterations").
  const std::string resting = test::fresh_path("sim_replay_resting.json");
  const std::string pose0 = "sim replay " + recording + " --hold --duration 2 --threads 2";
  ASSERT_EQ(run_cli(pose0 + " --json " + resting).status, 0);
  const util::JsonValue rest = util::JsonValue::parse(test::file_bytes(resting));
  EXPECT_LT(rest["fastest_node_last_half_second_m_s"].as_number(), 1e-3) << "m/s";
  const std::string cycling = test::fresh_path("sim_replay_cycling.json");
  const Result cycled = run_cli(pose0 + " --physics short_step_excess=0 --json " + cycling);
  ASSERT_EQ(cycled.status, 0) << cycled.out;
  EXPECT_NE(cycled.out.find("held still, short_step_excess=0)"), std::string::npos) << cycled.out;
  const util::JsonValue cycle = util::JsonValue::parse(test::file_bytes(cycling));
  EXPECT_NE(cycle["factorizations"].as_number(), rest["factorizations"].as_number());
  // Which poses cycle is the path's: in the sanitizers' build, rounding apart, pose 0 rests
  // either way (40 factorisations against the default's 50).
  if (!test::kUnderSanitizers) {
    EXPECT_GT(cycle["fastest_node_last_half_second_m_s"].as_number(), 0.01) << "m/s";
  }
  EXPECT_EQ(cycle["physics"][0].as_string(), "short_step_excess=0");
  EXPECT_EQ(run_cli("sim replay " + recording + " --physics short_step_excess=-1").status, 2);
  const Result played = run_cli("sim replay " + recording + " --strategy naive");
  ASSERT_EQ(played.status, 0) << played.out;
  EXPECT_NE(played.out.find("naive"), std::string::npos) << played.out;
  EXPECT_EQ(run_cli("sim replay").status, 2);
  EXPECT_EQ(run_cli("sim replay " + recording + " --strategy best").status, 2);
  EXPECT_EQ(run_cli("sim replay " + recording + " --hold --duration 0").status, 2);
  EXPECT_EQ(run_cli("sim replay " + recording + " --frame 40").status, 2);
  EXPECT_EQ(run_cli("sim replay " + recording + " --hold --frame 100000").status, 2);
  EXPECT_EQ(run_cli("sim replay /nonexistent.json.lz").status, 1);
}

// A kicked cube alone on the floor: the grid's table and its summary, one kick's JSON (rest
// as null when it never came to rest), the bounds refused.
TEST(CliSim, SettleFollowsAKickedCube) {
  const Result grid = run_cli("sim settle --duration 1");
  ASSERT_EQ(grid.status, 0) << grid.out;
  EXPECT_NE(grid.out.find("energy allows mm"), std::string::npos) << grid.out;
  EXPECT_NE(grid.out.find("40 kicks: "), std::string::npos) << grid.out;
  EXPECT_EQ(std::count(grid.out.begin(), grid.out.end(), '\n'), 3 + 40 + 2) << grid.out;
  const std::string json = test::fresh_path("sim_settle.json");
  ASSERT_EQ(run_cli("sim settle --cube 0.06 --speed 0.5 --spin 0 --json " + json).status, 0);
  const std::string text = test::file_bytes(json);
  for (const char* key :
       {"\"cube_m\": 0.06", "\"floor_stiffness_n_m\": 10000", "\"time_step_s\"",
        "\"speed_m_s\": 0.5", "\"spin_rad_s\": 0", "\"rest_time_s\": 0.", "\"travelled_m\"",
        "\"slide_bound_m\"", "\"highest_rise_m\"", "\"start_energy_j\"", "\"highest_energy_j\"",
        "\"kicks_gaining_energy\": 0"})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;
  ASSERT_EQ(run_cli("sim settle --speed 0.5 --spin 0 --duration 0.1 --json " + json).status, 0);
  EXPECT_NE(test::file_bytes(json).find("\"rest_time_s\": null"), std::string::npos)
      << "still sliding at 0.1 s";
  EXPECT_EQ(run_cli("sim settle --cube 0.5").status, 2);
  EXPECT_EQ(run_cli("sim settle --spin -1").status, 2);
  EXPECT_EQ(run_cli("sim settle --speed 0 --spin 0").status, 2);
  EXPECT_EQ(run_cli("sim settle --duration 0.05").status, 2);
  EXPECT_EQ(run_cli("sim settle --newton-iterations 0").status, 2);
  EXPECT_EQ(run_cli("sim settle extra").status, 2);
}

TEST(CliSim, BenchReportsTheMeshAndStepTimes) {
  const std::string json = test::fresh_path("sim_bench.json");
  const std::string steps = test::fresh_path("sim_steps.csv");
  const Result r =
      run_cli("sim bench --duration 0.4 --threads 1 --direct-steps 2 --runs 2 --json " + json +
              " --steps " + steps);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("median"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("approach"), std::string::npos) << "the phases: " << r.out;
  EXPECT_NE(r.out.find("at the p99 or over: evaluate"), std::string::npos) << "timers: " << r.out;
  EXPECT_NE(r.out.find(", factorise "), std::string::npos) << r.out;
  const std::string text = test::file_bytes(json);
  for (const char* key : {"\"scale\": 1",
                          "\"tets\"",
                          "\"nodes\"",
                          "\"dofs\"",
                          "\"steps\": 48",
                          "\"threads\": 1",
                          "\"direct_steps\": 2",
                          "\"refresh_steps\": 20",
                          "\"runs\": 2",
                          "\"halfway_gap\": 1000",
                          "\"step_ms\"",
                          "\"median\"",
                          "\"p95\"",
                          "\"p99\"",
                          "\"newton_iterations\"",
                          "\"linear_iterations\"",
                          "\"factorizations\"",
                          "\"direct_solves\"",
                          "\"failed_cg\"",
                          "\"phases\"",
                          "\"name\": \"shape\"",
                          "\"name\": \"approach\"",
                          "\"median_ms\"",
                          "\"timers\"",
                          "\"slowest_steps\"",
                          "\"name\": \"factorize\"",
                          "\"name\": \"rest\"",
                          "\"slowest_mean_ms\""})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;
  const std::string csv = test::file_bytes(steps);
  EXPECT_EQ(csv.rfind("step,time_s,step_ms,newton_iterations,linear_iterations,factorizations,"
                      "contacts,halvings,direct_solves,failed_cg,evaluate_ms,line_search_ms,"
                      "assemble_ms,"
                      "factorize_ms,cg_ms,direct_solve_ms\n",
                      0),
            0u)
      << csv.substr(0, 200);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 49) << "a header and 48 steps";
  const std::size_t header_end = csv.find('\n');
  const std::string row =
      csv.substr(header_end + 1, csv.find('\n', header_end + 1) - header_end - 1);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), 15) << "16 fields, as the header: " << row;
  EXPECT_EQ(run_cli("sim bench --threads 0").status, 2);
  EXPECT_EQ(run_cli("sim bench --max-linear-iterations -1").status, 2);
  EXPECT_EQ(run_cli("sim bench --direct-steps -1").status, 2);
  EXPECT_EQ(run_cli("sim bench --refresh-steps -1").status, 2);
  EXPECT_EQ(run_cli("sim bench --runs 0").status, 2);
  EXPECT_EQ(run_cli("sim bench --halfway-gap -1").status, 2);
  EXPECT_EQ(run_cli("sim bench --scale 3").status, 2);
  EXPECT_EQ(run_cli("sim bench --physics contact_keeps_face=2").status, 2);
  // --physics changes the simulator timed: half the step, twice the steps.
  const std::string halved = test::fresh_path("sim_bench_halved.json");
  ASSERT_EQ(run_cli("sim bench --duration 0.4 --threads 1 --physics time_step=0.004166666666666667 "
                    "--json " +
                    halved)
                .status,
            0);
  const std::string halved_text = test::file_bytes(halved);
  for (const char* key : {"\"steps\": 96", "\"time_step=0.004166666666666667\""})
    EXPECT_NE(halved_text.find(key), std::string::npos) << key << " in " << halved_text;
  EXPECT_NE(text.find("\"posture\": \"solved\""), std::string::npos) << text;
  // --posture times the functional posture's pinch: another placement, other contacts.
  const Result functional =
      run_cli("sim bench --duration 0.4 --threads 1 --posture functional --json -");
  ASSERT_EQ(functional.status, 0) << functional.out;
  EXPECT_NE(functional.out.find("\"posture\": \"functional\""), std::string::npos)
      << functional.out;
  EXPECT_EQ(run_cli("sim bench --posture bent").status, 2);
  // In the terminal, what was timed when it is not the default pinch.
  const Result told =
      run_cli("sim bench --duration 0.1 --threads 1 --posture functional --physics time_step=0.01");
  ASSERT_EQ(told.status, 0) << told.out;
  EXPECT_EQ(told.out.rfind("functional posture, time_step=0.01\n", 0), 0u) << told.out;
  EXPECT_EQ(r.out.find("posture"), std::string::npos)
      << "the default pinch says nothing: " << r.out;
  // With --json -, standard output is the JSON alone.
  const Result piped = run_cli("sim bench --duration 0.4 --json -");
  ASSERT_EQ(piped.status, 0) << piped.out;
  EXPECT_EQ(util::JsonValue::parse(piped.out)["steps"].as_number(), 48) << piped.out;
  const Result pinch = run_cli("sim pinch --cube 0.06 --json -");
  ASSERT_EQ(pinch.status, 0) << pinch.out;
  EXPECT_TRUE(util::JsonValue::parse(pinch.out)["held"].as_bool()) << pinch.out;
  EXPECT_EQ(util::JsonValue::parse(pinch.out)["newton_iterations_a_pass"].as_number(), 1);
  EXPECT_EQ(run_cli("sim pinch --cube 2").status, 2);
  EXPECT_EQ(run_cli("sim pinch --newton-iterations 0").status, 2);
  EXPECT_EQ(run_cli("sim pinch --skin-samples 3").status, 2);
  EXPECT_EQ(run_cli("sim bench --skin-samples -1").status, 2);
  EXPECT_EQ(run_cli("sim wobble").status, 2);
  EXPECT_EQ(run_cli("sim pinch --help").status, 0);
}

// Real pinches on the soft hand: pinch-57fps.json.lz's one closing, retargeted by Naive, takes
// the 6 cm cube and holds it (docs/simulator.md); each row's keys; the refusals.
TEST(CliSim, PinchesRunARecordingsClosingOnTheSoftHand) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch-57fps.json.lz";
  const Result r = run_cli("sim pinches --recording " + recording +
                           " --strategy naive --cube 0.06 --jobs 1 --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const util::JsonValue doc = util::JsonValue::parse(r.out);
  ASSERT_EQ(doc["pinches"].size(), 1u) << r.out;
  const util::JsonValue p = doc["pinches"][0];
  for (const char* key : {"recording",         "strategy",
                          "cube_size_m",       "moment_s",
                          "closed_s",          "widest_m",
                          "narrowest_m",       "closing_speed_m_s",
                          "tilt_deg",          "takes_cube",
                          "outcome",           "pushed_mm",
                          "grip_at_lift_n",    "touch_lead_ms",
                          "turn_at_touch_deg", "held",
                          "released",          "lift_m",
                          "slip_mm",           "max_penetration_mm",
                          "peak_grip_n",       "top_load_before_closing_n"})
    EXPECT_NE(p.find(key), nullptr) << key;
  EXPECT_TRUE(p["takes_cube"].as_bool());
  EXPECT_TRUE(p["held"].as_bool());
  EXPECT_EQ(p["outcome"].as_string(), "held");
  EXPECT_GT(p["widest_m"].as_number(), 0.06);
  EXPECT_LT(p["narrowest_m"].as_number(), 0.06);
  EXPECT_LT(p["moment_s"].as_number(), p["closed_s"].as_number());
  EXPECT_EQ(run_cli("sim pinches").status, 2) << "no recording";
  EXPECT_EQ(run_cli("sim pinches --recording " + recording + " --strategy both").status, 2);
  EXPECT_EQ(run_cli("sim pinches --recording " + recording + " --cube 2").status, 2);
  EXPECT_EQ(run_cli("sim pinches --help").status, 0);
}

// The grasp map's parts: a closing known to hold (the 6 cm cube's scripted pinch, 3 mm past
// the faces, its hand placed by the pinch's rule) and one known to lose the cube (the 1 cm
// cube in the functional posture under eight times a real recording's tracker jitter, which
// shakes its pads by 1.8 and 2.5 mm RMS at up to 56 cm/s, a quarter of its side: it is knocked
// away before the pinch closes; the map's `pad_jitter`), each closing's keys in the JSON, and the
// refusals.
TEST(CliSim, GraspMapsAClosingThatHoldsAndOneThatLosesTheCube) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const auto closing = [](const std::string& cube, const std::string& spec,
                          const std::string& more = "") {
    const Result r =
        run_cli("sim grasp --cube " + cube + " --jobs 1 --closing " + spec + more + " --json -");
    EXPECT_EQ(r.status, 0) << r.out;
    const util::JsonValue doc = util::JsonValue::parse(r.out);
    EXPECT_EQ(doc["factors"].size(), 9u);
    const bool functional = more.find("functional") != std::string::npos;
    EXPECT_EQ(doc["posture"].as_string(), functional ? "functional" : "solved");
    EXPECT_EQ(doc.find("functional_posture") != nullptr, functional);
    EXPECT_EQ(doc["cubes"].size(), 1u);
    EXPECT_EQ(doc["cubes"][0]["cube_size_m"].as_number(), std::stod(cube));
    EXPECT_EQ(doc["cubes"][0]["pad_jitter"].is_null(), more.find("jitter") == std::string::npos)
        << "a recording's jitter with --jitter-from alone";
    const util::JsonValue o = doc["cubes"][0]["closings"][0];
    for (const char* key : {"factor",
                            "level",
                            "closing",
                            "values",
                            "held",
                            "released",
                            "lift_m",
                            "slip_mm",
                            "max_penetration_mm",
                            "peak_grip_n",
                            "turn_deg",
                            "pinch_error_mm",
                            "pinch_clearance_mm",
                            "placement_pad_error_mm",
                            "open_clearance_mm",
                            "placed_by_rule",
                            "meets_pinch_rule",
                            "top_load_before_closing_n",
                            "inverted_tets",
                            "within_half",
                            "loss",
                            "pushed_mm",
                            "grip_at_lift_n",
                            "touch_lead_ms",
                            "turn_at_touch_deg"})
      EXPECT_NE(o.find(key), nullptr) << key;
    EXPECT_EQ(o["values"].size(), 9u);
    EXPECT_EQ(doc["human_distribution"]["parameters"].size(), 9u);
    return o;
  };
  const util::JsonValue holds = closing("0.06", "over_closure=3");
  EXPECT_TRUE(holds["held"].as_bool());
  EXPECT_TRUE(holds["released"].as_bool());
  EXPECT_LT(holds["slip_mm"].as_number(), 0.1);
  EXPECT_EQ(holds["closing"].as_string(), "the scripted pinch");
  EXPECT_GT(holds["peak_grip_n"].as_number(), 0.0);
  EXPECT_TRUE(holds["placed_by_rule"].as_bool());
  EXPECT_TRUE(holds["meets_pinch_rule"].as_bool());
  EXPECT_GE(holds["pinch_clearance_mm"].as_number(), 2.0);
  EXPECT_LT(holds["top_load_before_closing_n"].as_number(), 5.0) << "the rule keeps the top free";
  const util::JsonValue loses =
      closing("0.01", "jitter=8", " --posture functional --jitter-from " + recording);
  EXPECT_FALSE(loses["held"].as_bool());
  EXPECT_LT(loses["lift_m"].as_number(), 0.01);
  EXPECT_EQ(loses["closing"].as_string(), "jitter 8 x");
  EXPECT_NEAR(loses["values"]["jitter"].as_number(), 8.0, 1e-9);
  // How it was lost (pinch_loss.h): pushed away, more than a quarter of its side, before the pads
  // held it, so there was no grip at the lift; or slipped at the lift out of a grip. Which one the
  // jitter leaves is the path's: the sanitizers' build, rounding apart, slips it with 1.0 N.
  const std::string loss = loses["loss"].as_string();
  if (!test::kUnderSanitizers) {
    EXPECT_EQ(loss, "pushed_away");
  }
  if (loss == "pushed_away") {
    EXPECT_GT(loses["pushed_mm"].as_number(), 2.5);
    EXPECT_EQ(loses["grip_at_lift_n"].as_number(), 0.0);
  } else {
    EXPECT_EQ(loss, "slipped_at_lift");
    EXPECT_GT(loses["grip_at_lift_n"].as_number(), 0.0);
  }
  EXPECT_EQ(holds["loss"].as_string(), "held");
  EXPECT_GT(holds["grip_at_lift_n"].as_number(), 0.0);
  EXPECT_EQ(run_cli("sim grasp --closing squeeze=3").status, 2);
  EXPECT_EQ(run_cli("sim grasp --closing over_closure=40").status, 2);
  EXPECT_EQ(run_cli("sim grasp --factor tilt").status, 2);
  EXPECT_EQ(run_cli("sim grasp --cube 2").status, 2);
  EXPECT_EQ(run_cli("sim grasp --grid none").status, 2) << "no grid and no draws";
  EXPECT_EQ(run_cli("sim grasp --closing jitter=1").status, 2) << "jitter without a recording";
  EXPECT_EQ(run_cli("sim grasp --physics friction=-1").status, 2);
  EXPECT_EQ(run_cli("sim grasp --posture bent").status, 2);
  EXPECT_EQ(run_cli("sim grasp --physics grip=1").status, 2);
}

// With a recording's jitter, each cube's map says what the jitter factor's levels do at the
// scripted pinch's pads: the real recording's own moves each pad a few tenths of a millimetre
// (docs/simulator.md), and eight times it eight times as far.
TEST(CliSim, GraspMapSaysTheJitterAtThePads) {
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const Result r = run_cli("sim grasp --cube 0.01 --jobs 1 --closing jitter=1 --jitter-from " +
                           recording + " --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const util::JsonValue levels = util::JsonValue::parse(r.out)["cubes"][0]["pad_jitter"];
  ASSERT_EQ(levels.size(), 4u) << "the jitter factor's levels but 0: 1, 2, 4, 8";
  const util::JsonValue once = levels[0];
  EXPECT_EQ(once["jitter"].as_number(), 1.0);
  for (const char* key : {"thumb_rms_mm", "index_rms_mm", "along_rms_mm", "across_rms_mm",
                          "relative_speed_rms_cm_s", "relative_speed_max_cm_s"}) {
    EXPECT_GT(once[key].as_number(), 0.0) << key;
    EXPECT_NEAR(levels[3][key].as_number(), 8 * once[key].as_number(),
                0.05 * 8 * once[key].as_number())
        << key;
  }
  EXPECT_GT(once["thumb_rms_mm"].as_number(), 0.1);
  EXPECT_LT(once["thumb_rms_mm"].as_number(), 0.5);
}

// The map placed in the functional posture (--posture functional): named in the JSON with the
// posture's angles and their sources; the light cube's scripted pinch held with its top free
// (the solved posture's knuckles press it with 23.5 N).
TEST(CliSim, GraspMapPlacesThePinchInAFunctionalPosture) {
  const Result r = run_cli(
      "sim grasp --cube 0.01 --jobs 1 --closing over_closure=3 --posture functional "
      "--json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const util::JsonValue doc = util::JsonValue::parse(r.out);
  EXPECT_EQ(doc["posture"].as_string(), "functional");
  const util::JsonValue angles = doc["functional_posture"]["angles"];
  ASSERT_EQ(angles.size(), 9u);
  for (std::size_t i = 0; i < angles.size(); ++i) {
    EXPECT_FALSE(angles[i]["source"].as_string().empty());
    EXPECT_NE(angles[i].find("angle_deg"), nullptr);
  }
  EXPECT_GT(doc["functional_posture"]["weight_m_per_rad"].as_number(), 0.0);
  const util::JsonValue o = doc["cubes"][0]["closings"][0];
  EXPECT_TRUE(o["held"].as_bool());
  EXPECT_LT(o["top_load_before_closing_n"].as_number(), 1.0);
}

// Repeats: a closing as given and with its cube moved, each a row with its repeat and shift;
// the counts of closings held every time, never and sometimes; set beside itself, every run
// matched with its own repeat.
TEST(CliSim, GraspMapRepeatsEachClosingWithTheCubeMoved) {
  const std::string out = std::string(HANDLAB_TEST_TMP) + "/repeats.json";
  const Result r =
      run_cli("sim grasp --cube 0.01 --jobs 2 --closing over_closure=3 --repeats 2 --json " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("the scripted pinch (repeat 1)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("repeated, 1 closing: held in every repeat"), std::string::npos) << r.out;
  std::ifstream file(out);
  std::stringstream text;
  text << file.rdbuf();
  const util::JsonValue doc = util::JsonValue::parse(text.str());
  const util::JsonValue cube = doc["cubes"][0];
  ASSERT_EQ(cube["closings"].size(), 2u);
  EXPECT_EQ(cube["closings"][0]["repeat"].as_number(), 0);
  EXPECT_EQ(cube["closings"][1]["repeat"].as_number(), 1);
  EXPECT_EQ(cube["closings"][0]["cube_shift_mm"][0].as_number(), 0);
  const double x = cube["closings"][1]["cube_shift_mm"][0].as_number(),
               z = cube["closings"][1]["cube_shift_mm"][1].as_number();
  EXPECT_GT(std::hypot(x, z), 0.0);
  EXPECT_LE(std::hypot(x, z), 0.1);
  const util::JsonValue repeats = cube["repeats"];
  EXPECT_EQ(repeats["per_closing"].as_number(), 2);
  EXPECT_EQ(repeats["all"]["closings"].as_number(), 1);
  const int held =
      int(cube["closings"][0]["held"].as_bool()) + int(cube["closings"][1]["held"].as_bool());
  EXPECT_EQ(repeats["all"]["held_every_time"].as_number(), held == 2 ? 1 : 0);
  EXPECT_EQ(repeats["all"]["held_never"].as_number(), held == 0 ? 1 : 0);
  EXPECT_EQ(repeats["all"]["held_sometimes"].as_number(), held == 1 ? 1 : 0);
  EXPECT_EQ(repeats["within_half"]["closings"].as_number(), 1);
  const Result again = run_cli(
      "sim grasp --cube 0.01 --jobs 2 --closing over_closure=3 "
      "--repeats 2 --against " +
      out + " --json -");
  ASSERT_EQ(again.status, 0) << again.out;
  const util::JsonValue against = util::JsonValue::parse(again.out)["cubes"][0]["against"];
  EXPECT_EQ(against["in_both"].as_number(), 2);
  EXPECT_EQ(against["held_before_lost_after"].size(), 0u) << "the same runs, the same outcomes";
  EXPECT_EQ(against["lost_before_held_after"].size(), 0u);
  ASSERT_EQ(against["by_closing"].size(), 1u) << "the closing's repeats counted together";
  const util::JsonValue counted = against["by_closing"][0];
  EXPECT_EQ(counted["closing"].as_string(), "the scripted pinch") << "over_closure=3 is it";
  EXPECT_EQ(counted["runs_before"].as_number(), 2);
  EXPECT_EQ(counted["held_before"].as_number(), held);
  EXPECT_EQ(counted["runs_after"].as_number(), 2);
  EXPECT_EQ(counted["difference"].as_number(), 0);
  EXPECT_LT(counted["difference_low"].as_number(), 0);
  EXPECT_GT(counted["difference_high"].as_number(), 0);
  EXPECT_EQ(against["held_less_often"].as_number(), 0);
  EXPECT_EQ(against["held_more_often"].as_number(), 0);
  EXPECT_EQ(run_cli("sim grasp --cube 0.01 --closing over_closure=3 --repeats 0").status, 2);
  EXPECT_EQ(run_cli("sim grasp --cube 0.01 --closing over_closure=3 --repeats 101").status, 2);
}

// Several closings at once (--closing repeated): each with its repeats, which move the cube
// and come out as when that closing runs alone.
TEST(CliSim, GraspMapRunsSeveralClosingsEachAsAlone) {
  const Result both = run_cli(
      "sim grasp --cube 0.01 --jobs 2 --closing over_closure=3 --closing over_closure=5 "
      "--repeats 2 --json -");
  ASSERT_EQ(both.status, 0) << both.out;
  const Result alone =
      run_cli("sim grasp --cube 0.01 --jobs 2 --closing over_closure=5 --repeats 2 --json -");
  ASSERT_EQ(alone.status, 0) << alone.out;
  const util::JsonValue runs = util::JsonValue::parse(both.out)["cubes"][0]["closings"];
  const util::JsonValue own = util::JsonValue::parse(alone.out)["cubes"][0]["closings"];
  ASSERT_EQ(runs.size(), 4u);
  ASSERT_EQ(own.size(), 2u);
  EXPECT_EQ(runs[0]["closing"].as_string(), "the scripted pinch");
  EXPECT_NE(runs[2]["closing"].as_string(), runs[0]["closing"].as_string());
  EXPECT_EQ(util::JsonValue::parse(both.out)["cubes"][0]["repeats"]["all"]["closings"].as_number(),
            2);
  for (std::size_t r = 0; r < 2; ++r) {
    const util::JsonValue a = runs[2 + r], b = own[r];
    EXPECT_EQ(a["closing"].as_string(), b["closing"].as_string());
    EXPECT_EQ(a["repeat"].as_number(), double(r));
    EXPECT_EQ(a["cube_shift_mm"][0].as_number(), b["cube_shift_mm"][0].as_number());
    EXPECT_EQ(a["cube_shift_mm"][1].as_number(), b["cube_shift_mm"][1].as_number());
    EXPECT_EQ(a["held"].as_bool(), b["held"].as_bool());
    EXPECT_EQ(a["slip_mm"].as_number(), b["slip_mm"].as_number()) << "the same run to the bit";
  }
  EXPECT_NE(runs[1]["cube_shift_mm"][0].as_number(), runs[3]["cube_shift_mm"][0].as_number())
      << "each closing's repeats move the cube by what the closing is";
  const Result help = run_cli("sim grasp --help");
  EXPECT_NE(help.out.find("--closing NAME=VALUE,... ["), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("......"), std::string::npos) << "a repeatable value's dots once";
}

// A map set beside one written before (--against): a map whose 1 cm cube held the closing
// under eight times the tracker's jitter, which today's physics loses (knocked away), and lost
// the scripted pinch, which it holds; and a map without that cube.
TEST(CliSim, GraspMapSetsEachClosingBesideTheMapBefore) {
  // A map of two closings: eight times the jitter (lost today: the map's parts above) and the
  // scripted pinch (held).
  const auto map_before = [](const std::string& name, double cube, bool jittered_held,
                             bool pinch_held) {
    const std::string held[] = {jittered_held ? "true" : "false", pinch_held ? "true" : "false"};
    std::string closings;
    const char* jitters[] = {"8", "0"};
    for (int i = 0; i < 2; ++i)
      closings += std::string(i ? "," : "") +
                  R"({"factor": "jitter", "level": 0, "values": {"over_closure": 3,)" +
                  R"( "tilt_yaw": 0, "tilt_pitch": 0, "offset_along": 0,)" +
                  R"( "lead": 0, "closing_speed": 0, "lift_acceleration": 0, "hold": 5,)" +
                  R"( "jitter": )" + jitters[i] + R"(}, "held": )" + held[i] +
                  R"(, "released": true})";
    return write_temp(name, R"({"cubes": [{"cube_size_m": )" + std::to_string(cube) +
                                R"(, "closings": [)" + closings + "]}]}");
  };
  const std::string before = map_before("before-map.json", 0.01, true, false);
  const std::string recording = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz";
  const auto against = [](const std::string& spec, const std::string& map,
                          const std::string& more = "") {
    const Result r = run_cli("sim grasp --cube 0.01 --jobs 1 --closing " + spec + more +
                             " --against " + map + " --json -");
    EXPECT_EQ(r.status, 0) << r.out;
    return util::JsonValue::parse(r.out)["cubes"][0];
  };
  const util::JsonValue lost =
      against("jitter=8", before, " --posture functional --jitter-from " + recording)["against"];
  EXPECT_EQ(lost["in_both"].as_number(), 1);
  EXPECT_EQ(lost["held_before"].as_number(), 1);
  EXPECT_EQ(lost["held_after"].as_number(), 0);
  EXPECT_EQ(lost["held_and_released_before"].as_number(), 1);
  EXPECT_EQ(lost["held_and_released_after"].as_number(), 0);
  ASSERT_EQ(lost["held_before_lost_after"].size(), 1u);
  EXPECT_EQ(lost["held_before_lost_after"][0].as_string(), "jitter 8 x");
  EXPECT_EQ(lost["lost_before_held_after"].size(), 0u);
  const util::JsonValue won = against("over_closure=3", before)["against"];
  EXPECT_EQ(won["in_both"].as_number(), 1);
  EXPECT_EQ(won["held_before_lost_after"].size(), 0u);
  ASSERT_EQ(won["lost_before_held_after"].size(), 1u);
  EXPECT_EQ(won["lost_before_held_after"][0].as_string(), "the scripted pinch");
  // The scripted pinch lost in five repeats before, held in both now: a change two runs resolve
  // (Newcombe's interval of 2 of 2 against 0 of 5 lies above zero).
  std::string five;
  for (int r = 0; r < 5; ++r)
    five += std::string(r ? "," : "") + R"({"factor": "", "level": 0, "repeat": )" +
            std::to_string(r) +
            R"(, "values": {"over_closure": 3, "tilt_yaw": 0, "tilt_pitch": 0,)" +
            R"( "offset_along": 0, "lead": 0, "closing_speed": 0, "lift_acceleration": 0,)" +
            R"( "hold": 5, "jitter": 0}, "held": false, "released": false})";
  const std::string lost_five = write_temp(
      "lost-five.json", R"({"cubes": [{"cube_size_m": 0.01, "closings": [)" + five + "]}]}");
  const Result rerun = run_cli(
      "sim grasp --cube 0.01 --jobs 2 --closing over_closure=3 --repeats 2 "
      "--against " +
      lost_five + " --json -");
  ASSERT_EQ(rerun.status, 0) << rerun.out;
  const util::JsonValue rates = util::JsonValue::parse(rerun.out)["cubes"][0]["against"];
  ASSERT_EQ(rates["by_closing"].size(), 1u);
  EXPECT_EQ(rates["by_closing"][0]["runs_before"].as_number(), 5);
  EXPECT_EQ(rates["by_closing"][0]["held_after"].as_number(), 2);
  EXPECT_GT(rates["by_closing"][0]["difference_low"].as_number(), 0);
  EXPECT_EQ(rates["held_more_often"].as_number(), 1);
  EXPECT_EQ(rates["held_less_often"].as_number(), 0);
  const std::string other = map_before("other-cube.json", 0.06, true, true);
  const Result text =
      run_cli("sim grasp --cube 0.01 --jobs 1 --closing over_closure=3 --against " + other);
  EXPECT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("the map before has no 10 mm cube"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("within half of every range: 1 of 1 held"), std::string::npos);
  EXPECT_EQ(run_cli("sim grasp --closing over_closure=3 --against " +
                    write_temp("not-a-map.json", "{\"cubes\": 3}"))
                .status,
            2);
  EXPECT_EQ(run_cli("sim grasp --closing over_closure=3 --against /nonexistent/map.json").status,
            2);
}

TEST(CliAnalyze, ReportsAndWritesJson) {
  const std::string csv = write_temp("good.csv", kGood);
  const std::string json = std::string(HANDLAB_TEST_TMP) + "/good.json";
  const Result r =
      run_cli("analyze --csv " + csv + " --subject id --dv y --within cond,block --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("cond "), std::string::npos);
  EXPECT_NE(r.out.find("F(1, 2) = "), std::string::npos) << r.out;
  std::FILE* f = std::fopen(json.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  std::string text(1 << 16, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  for (const char* key : {"\"design\"", "\"n_subjects\": 3", "\"dropped_subjects\"", "\"anova\"",
                          "\"effect\": \"cond:block\"", "\"mauchly_W\"", "\"p_gg\"", "\"posthoc\"",
                          "\"contrast\": \"a - b\"", "\"p_tukey\"", "\"descriptives\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
}

TEST(CliAnalyze, BadInputGivesOneClearLine) {
  struct Case {
    const char* name;
    std::string csv;
    const char* args;
    const char* expect;  // what the message must mention
  };
  const std::vector<Case> cases = {
      {"missing_column", kGood, "--subject id --dv time --within cond", "'time'"},
      {"non_numeric", "id,cond,y\ns1,a,1\ns1,b,2\ns2,a,x7\ns2,b,3\n",
       "--subject id --dv y --within cond", "line 4, column 'y'"},
      {"one_level", "id,cond,y\ns1,a,1\ns2,a,2\n", "--subject id --dv y --within cond", "'cond'"},
      {"nan_value", "id,cond,y\ns1,a,1\ns1,b,NaN\ns2,a,1\ns2,b,3\n",
       "--subject id --dv y --within cond", "line 3, column 'y'"},
      {"inf_value", "id,cond,y\ns1,a,1\ns1,b,2\ns2,a,inf\ns2,b,3\n",
       "--subject id --dv y --within cond", "line 4, column 'y'"},
      // NA is a missing observation: s1 then lacks a cell and is dropped.
      {"na_value", "id,cond,y\ns1,a,1\ns1,b,NA\ns2,a,1\ns2,b,3\n",
       "--subject id --dv y --within cond", "fewer than two participants have every within cell"},
      {"empty", "", "--subject id --dv y --within cond", "empty"},
      {"header_only", "id,cond,y\n", "--subject id --dv y --within cond", "no data rows"},
      {"ragged", "id,cond,y\ns1,a,1\ns1,b\n", "--subject id --dv y --within cond", "line 3"},
      {"nonparametric_text", "id,cond,q\ns1,a,3\ns1,b,good\ns2,a,1\ns2,b,2\n",
       "--subject id --within cond --nonparametric q", "line 3, column 'q'"},
  };
  for (const Case& c : cases) {
    const std::string csv = write_temp(std::string(c.name) + ".csv", c.csv);
    const Result r = run_cli("analyze --csv " + csv + " " + c.args);
    EXPECT_EQ(r.status, 1) << c.name << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << ": " << r.out;
  }
  const Result missing =
      run_cli("analyze --csv /no/such/file.csv --subject id --dv y --within cond");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.out.find("/no/such/file.csv"), std::string::npos);
  const Result usage = run_cli("analyze --csv x.csv --dv y --within cond");
  EXPECT_EQ(usage.status, 2);
  EXPECT_NE(usage.out.find("--subject"), std::string::npos);
}

}  // namespace
}  // namespace handlab
