#include "app/cli/commands/simulate_slurm.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "core/util/count_text.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

// Runs `command` and returns what it printed (stdout, trimmed); throws with its output when it
// fails or cannot run.
std::string run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    out.append(buffer.data(), n);
  const int status = pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string first = out.substr(0, out.find('\n'));
    throw std::runtime_error(command.substr(0, command.find(' ')) + " failed" +
                             (WIFEXITED(status) && WEXITSTATUS(status) == 127
                                  ? " (not found: is Slurm's client installed?)"
                                  : ": " + first));
  }
  return out;
}

const char* state_name(studies::PartState s) {
  switch (s) {
    case studies::PartState::kDone:
      return "done";
    case studies::PartState::kRunning:
      return "running";
    case studies::PartState::kStopped:
      return "stopped";
    case studies::PartState::kMissing:
      return "missing";
  }
  return "?";
}

// The cluster's MaxArraySize (scontrol show config), or Slurm's default where it cannot be
// asked (no Slurm client here: a dry run).
int cluster_max_array() {
  try {
    std::istringstream config(run_command("scontrol show config"));
    for (std::string line; std::getline(config, line);)
      if (line.rfind("MaxArraySize", 0) == 0) return std::stoi(line.substr(line.find('=') + 1));
  } catch (const std::exception&) {
  }
  return 1001;
}

// A value that goes into an #SBATCH line, which Slurm splits at spaces and ends at a newline.
std::string directive_value(const Arguments& args, const std::string& option) {
  const std::string value = args.text(option);
  if (value.empty() || value.find_first_of(" \t\n\r'\"") != std::string::npos)
    throw UsageError("--" + option + " '" + value +
                     "': Slurm's #SBATCH lines take a value without spaces or quotes");
  return value;
}

}  // namespace

std::vector<OptionSpec> slurm_option_specs() {
  return {
      {"per-task", "K", "with --slurm: participants an array task runs", "1"},
      {"partition", "P", "with --slurm: the partition (#SBATCH --partition)"},
      {"time", "LIMIT", "with --slurm: a task's time limit (#SBATCH --time, e.g. 0:30:00)"},
      {"mem", "SIZE", "with --slurm: a task's memory (#SBATCH --mem, e.g. 1G)"},
      {"max-array", "N",
       "with --slurm: tasks a job array may hold (default: the cluster's MaxArraySize)"},
      {"dry-run", "", "with --slurm: write and print the scripts, submit nothing"},
  };
}

bool has_slurm_options(const Arguments& args) {
  for (const OptionSpec& spec : slurm_option_specs())
    if (args.has(spec.name)) return true;
  return false;
}

studies::SlurmSeries series_settings(const Arguments& args) {
  studies::SlurmSeries series;
  series.dir = std::filesystem::absolute(args.text("slurm")).lexically_normal().string();
  if (series.dir.size() > 1 && series.dir.back() == '/') series.dir.pop_back();
  if (series.dir.find_first_of(" \t\n\r'\"") != std::string::npos)
    throw UsageError("--slurm " + series.dir +
                     ": Slurm's #SBATCH --output line cannot hold a path with spaces or quotes");
  series.cli = std::filesystem::canonical("/proc/self/exe").string();
  series.protocol = std::filesystem::canonical(args.text("protocol")).string();
  series.per_task = int(args.integer("per-task"));
  if (series.per_task < 1) throw UsageError("--per-task must be 1 or more");
  if (args.has("partition")) series.partition = directive_value(args, "partition");
  if (args.has("time")) series.time = directive_value(args, "time");
  if (args.has("mem")) series.mem = directive_value(args, "mem");
  series.max_array = args.has("max-array") ? int(args.integer("max-array")) : cluster_max_array();
  if (series.max_array < 1) throw UsageError("--max-array must be 1 or more");
  return series;
}

void submit_slurm_series(const studies::SlurmSeries& series, bool dry_run) {
  studies::write_slurm_series(series);
  const std::string array = series.dir + "/array.sh", merge = series.dir + "/merge.sh";
  const std::string then = series.dir + "/then.sh";
  const std::size_t n = series.studies.size();
  std::cout << n << (n == 1 ? " study" : " studies") << ": " << studies::array_tasks(series)
            << " array tasks of up to " << series.per_task
            << (series.per_task == 1 ? " participant" : " participants") << ", then a merge job"
            << (series.then.empty() ? "" : " and " + series.then[1]) << "; scripts in "
            << series.dir << "\n";
  const std::vector<studies::ArrayChunk> chunks = studies::array_chunks(series);
  auto array_command = [&](const studies::ArrayChunk& c) {
    return "sbatch --parsable --array=0-" + std::to_string(c.tasks - 1) +
           (c.offset == 0 ? "" : " --export=ALL,HANDLAB_TASK_OFFSET=" + std::to_string(c.offset)) +
           " '" + array + "'";
  };
  if (dry_run) {
    std::cout << "\n";
    for (const studies::ArrayChunk& c : chunks) std::cout << array_command(c) << "\n";
    std::cout << "sbatch --dependency=afterok";
    for (std::size_t k = 0; k < chunks.size(); ++k)
      std::cout << ":ARRAY" << (chunks.size() == 1 ? "" : std::to_string(k + 1)) << "_JOB_ID";
    std::cout << " '" << merge << "'\n";
    if (!series.then.empty())
      std::cout << "sbatch --dependency=afterok:MERGE_JOB_ID '" << then << "'\n";
    std::cout << "\n--- " << array << "\n"
              << studies::array_script(series) << "--- " << merge << "\n"
              << studies::merge_script(series);
    if (!series.then.empty()) std::cout << "--- " << then << "\n" << studies::then_script(series);
    return;
  }
  auto job_id = [](const std::string& parsable) {
    return parsable.substr(0, parsable.find(';'));  // "id;cluster"
  };
  std::vector<std::string> arrays;
  for (const studies::ArrayChunk& c : chunks)
    arrays.push_back(job_id(run_command(array_command(c))));
  std::string after;
  for (const std::string& id : arrays) after += ":" + id;
  const std::string merge_job =
      job_id(run_command("sbatch --parsable --dependency=afterok" + after + " '" + merge + "'"));
  std::string then_job;
  if (!series.then.empty())
    then_job = job_id(
        run_command("sbatch --parsable --dependency=afterok:" + merge_job + " '" + then + "'"));
  util::write_output(series.dir + "/jobs.txt", [&](std::ostream& out) {
    for (const std::string& id : arrays) out << "array " << id << "\n";
    out << "merge " << merge_job << "\n";
    if (!then_job.empty()) out << "then " << then_job << "\n";
  });
  std::string array_ids;
  for (const std::string& id : arrays) array_ids += (array_ids.empty() ? "" : ", ") + id;
  std::cout << "submitted: array job" << (arrays.size() == 1 ? " " : "s ") << array_ids
            << ", merge job " << merge_job << " (after the array" << (arrays.size() == 1 ? "" : "s")
            << " succeed" << (arrays.size() == 1 ? "s" : "") << ")"
            << (then_job.empty()
                    ? ""
                    : ", " + series.then[1] + " job " + then_job + " (after the merge)")
            << "\nprogress: handlab-cli simulate --status " << series.dir << "\n";
}

namespace {

// A row per study (up to 20 of them), the totals, and what to do next.
void print_series_table(const studies::SlurmSeries& series, const studies::SeriesStatus& status) {
  const std::size_t n = status.studies.size();
  std::cout << series.dir << ": " << n << (n == 1 ? " study, " : " studies, ")
            << studies::array_tasks(series) << " parts\n";
  std::printf("%-4s %-22s %6s %8s %8s %8s  %s\n", "N", "seed", "done", "running", "stopped",
              "missing", "merged");
  int total[4] = {0, 0, 0, 0}, merged = 0;
  for (const auto& s : status.studies) {
    int count[4] = {0, 0, 0, 0};
    for (studies::PartState p : s.parts) ++count[int(p)];
    for (int k = 0; k < 4; ++k) total[k] += count[k];
    merged += s.merged;
    if (n <= 20)
      std::printf("%-4d %-22llu %6d %8d %8d %8d  %s\n", s.study.participants,
                  static_cast<unsigned long long>(s.study.seed), count[0], count[1], count[2],
                  count[3],
                  s.merged           ? "yes"
                  : s.merged_partial ? "partial"
                                     : "no");
  }
  if (n > 20)
    std::printf("%-27s %6d %8d %8d %8d  %d of %zu\n", "all", total[0], total[1], total[2], total[3],
                merged, n);
  if (status.unfinished_tasks.empty()) {
    std::cout << "every part is done";
    if (merged < int(n))
      std::cout << "; " << util::count_text(int(n) - merged, "study", "studies")
                << " not merged whole: sbatch " << series.dir << "/merge.sh (or bash it)";
    std::cout << "\n";
    return;
  }
  std::cout << "unfinished array tasks: " << studies::index_ranges(status.unfinished_tasks) << "\n";
  if (total[2] > 0)
    std::cout << "stopped parts: their tasks' logs are in " << series.dir << "/logs\n";
  std::cout << "once none of the series' jobs runs, rerun them (JOB: the job ids sbatch "
               "printed for the lines before):\n";
  for (const std::string& c : studies::rerun_commands(series, status.unfinished_tasks))
    std::cout << "  " << c << "\n";
}

void write_series_json(std::ostream& out, const studies::SlurmSeries& series,
                       const studies::SeriesStatus& status) {
  util::JsonWriter w(out);
  w.begin_object().field("dir", series.dir).key("studies").begin_array();
  for (const auto& s : status.studies) {
    w.begin_object()
        .field("participants", s.study.participants)
        .field("seed", std::to_string(s.study.seed))
        .field("path", s.path)
        .field("merged", s.merged)
        .field("merged_partial", s.merged_partial)
        .key("parts")
        .begin_array();
    for (studies::PartState p : s.parts) w.value(state_name(p));
    w.end_array().end_object();
  }
  w.end_array().key("unfinished_tasks").begin_array();
  for (int i : status.unfinished_tasks) w.value(i);
  w.end_array().end_object();
  out << "\n";
}

}  // namespace

void print_series_status(const std::string& dir, const std::string& json) {
  const studies::SlurmSeries series = studies::read_slurm_series(dir);
  const studies::SeriesStatus status = studies::series_status(series);
  if (json != "-") print_series_table(series, status);
  if (!json.empty())
    util::write_output(json, [&](std::ostream& out) { write_series_json(out, series, status); });
}

}  // namespace handlab::cli
