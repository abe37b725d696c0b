// The study's protocol as the tests read it, and a protocol's text with one passage changed
// (a variant of a protocol, written out by a test).
#pragma once

#include <unistd.h>

#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "tests/support/test_files.h"

namespace handlab::test {

inline const std::string kStudy =
    std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021.json";

// `text` with the first `from` replaced by `to`; a test failure if there is no `from`.
inline std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The study's text (or a variant of it) with one practice trial per condition before block 1,
// which the study file, as the paper, does not have: for the tests of what practice trials do.
inline std::string with_practice(std::string study_text) {
  return with(std::move(study_text), "\"trials_per_condition\": 0", "\"trials_per_condition\": 1");
}

// The study with practice trials as a file under the test directory, one a process, since
// tests run side by side.
inline std::string study_with_practice() {
  const std::string path =
      fresh_path("study-with-practice-" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << with_practice(file_bytes(kStudy));
  return path;
}

// tests/openxr/headset-protocol.json (two 2-second trials) naming `session` (a JSON object)
// as its sessions' defaults, as a file `name`.json under the test directory.
inline std::string headset_protocol_with_session(const std::string& session,
                                                 const std::string& name) {
  const std::string text =
      file_bytes(std::string(HANDLAB_SOURCE_DIR) + "/tests/openxr/headset-protocol.json");
  const std::string path = fresh_path(name + ".json");
  std::ofstream(path) << with(text, "{", "{\"session\": " + session + ",");
  return path;
}

}  // namespace handlab::test
