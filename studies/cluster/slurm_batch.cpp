#include "studies/cluster/slurm_batch.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/store/study_store.h"
#include "core/util/json_value.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::studies {
namespace {

// A word for bash, single-quoted.
std::string quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& text, bool executable) {
  util::write_output_bytes(path, text);
  if (executable)
    std::filesystem::permissions(path,
                                 std::filesystem::perms::owner_exec |
                                     std::filesystem::perms::group_exec |
                                     std::filesystem::perms::others_exec,
                                 std::filesystem::perm_options::add);
}

// The #SBATCH lines every job of the series shares.
std::string site_directives(const SlurmSeries& s) {
  std::string out;
  if (!s.partition.empty()) out += "#SBATCH --partition=" + s.partition + "\n";
  if (!s.time.empty()) out += "#SBATCH --time=" + s.time + "\n";
  if (!s.mem.empty()) out += "#SBATCH --mem=" + s.mem + "\n";
  return out;
}

std::string series_json(const SlurmSeries& s) {
  std::ostringstream out;
  util::JsonWriter w(out);
  w.begin_object()
      .field("cli", s.cli)
      .field("protocol", s.protocol)
      .field("per_task", s.per_task)
      .field("max_array", s.max_array)
      .key("simulate_options")
      .string_array(s.simulate_options)
      .field("partition", s.partition)
      .field("time", s.time)
      .field("mem", s.mem)
      .key("then")
      .string_array(s.then)
      .key("studies")
      .begin_array();
  for (const SlurmStudy& study : s.studies)
    w.begin_object()
        .field("participants", study.participants)
        .field("seed", std::to_string(study.seed))  // a string: 64 bits, more than a double holds
        .end_object();
  w.end_array().end_object();
  out << "\n";
  return out.str();
}

std::string study_name(const SlurmStudy& s) {
  return "n" + std::to_string(s.participants) + "-seed" + std::to_string(s.seed);
}

std::string words(const std::vector<std::string>& ws) {
  std::string out;
  for (const std::string& w : ws) out += (out.empty() ? "" : " ") + quoted(w);
  return out;
}

}  // namespace

int shards_of(const SlurmSeries& s, const SlurmStudy& study) {
  return (study.participants + s.per_task - 1) / s.per_task;
}

int array_tasks(const SlurmSeries& s) {
  int tasks = 0;
  for (const SlurmStudy& study : s.studies) tasks += shards_of(s, study);
  return tasks;
}

std::vector<ArrayChunk> array_chunks(const SlurmSeries& s) {
  std::vector<ArrayChunk> chunks;
  const int tasks = array_tasks(s);
  for (int offset = 0; offset < tasks; offset += s.max_array)
    chunks.push_back({offset, std::min(s.max_array, tasks - offset)});
  return chunks;
}

std::string index_ranges(const std::vector<int>& indices) {
  std::string out;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    out += (out.empty() ? "" : ",") + std::to_string(indices[k]);
    if (end > k) out += (end == k + 1 ? "," : "-") + std::to_string(indices[end]);
    k = end + 1;
  }
  return out;
}

std::vector<std::string> rerun_commands(const SlurmSeries& s, const std::vector<int>& tasks) {
  std::vector<std::string> commands;
  for (const ArrayChunk& chunk : array_chunks(s)) {
    std::vector<int> indices;
    for (int t : tasks)
      if (t >= chunk.offset && t < chunk.offset + chunk.tasks) indices.push_back(t - chunk.offset);
    if (indices.empty()) continue;
    commands.push_back("sbatch --array=" + index_ranges(indices) +
                       (chunk.offset == 0
                            ? ""
                            : " --export=ALL,HANDLAB_TASK_OFFSET=" + std::to_string(chunk.offset)) +
                       " " + quoted(s.dir + "/array.sh"));
  }
  const std::string after = commands.size() == 1 ? "JOB" : "JOB1:JOB2:...";
  commands.push_back("sbatch --dependency=afterok:" + after + " " + quoted(s.dir + "/merge.sh"));
  if (!s.then.empty())
    commands.push_back("sbatch --dependency=afterok:JOB " + quoted(s.dir + "/then.sh"));
  return commands;
}

std::string part_path(const SlurmSeries& s, const SlurmStudy& study, int shard) {
  return s.dir + "/parts/" + study_name(study) + "/shard-" + std::to_string(shard) + "-of-" +
         std::to_string(shards_of(s, study)) + ".db";
}

std::string study_path(const std::string& dir, const SlurmStudy& study) {
  return dir + "/study-" + study_name(study) + ".db";
}

std::string array_script(const SlurmSeries& s) {
  std::ostringstream out;
  out << "#!/bin/bash\n"
      << "# A simulated series on Slurm, written by handlab-cli (docs/cluster.md). Array task i\n"
      << "# runs the shard on line i + 1 of tasks.tsv (participants, seed, shard, shards), i its\n"
      << "# index plus HANDLAB_TASK_OFFSET (a series of more tasks than an array may hold is\n"
      << "# submitted as several arrays).\n"
      << "# Rerunning a task whose part is there does nothing; one stopped midway starts its\n"
      << "# part again.\n"
      << "#SBATCH --job-name=handlab-simulate\n"
      << "#SBATCH --array=0-" << std::min(array_tasks(s), s.max_array) - 1 << "\n"
      << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
      << "#SBATCH --output=" << s.dir << "/logs/task-%a.out\n"
      << site_directives(s) << "set -euo pipefail\n"
      << "dir=" << quoted(s.dir) << "\n"
      << "i=${1:-$((${HANDLAB_TASK_OFFSET:-0} + SLURM_ARRAY_TASK_ID))}\n"
      << "read -r participants seed shard shards < <(sed -n \"$((i + 1))p\" \"$dir/tasks.tsv\")\n"
      << "part=$dir/parts/n$participants-seed$seed/shard-$shard-of-$shards.db\n"
      << "if [ -e \"$part\" ]; then echo \"$part: done already\"; exit 0; fi\n"
      << "mkdir -p \"$(dirname \"$part\")\"\n"
      << "rm -f \"$part.tmp\" \"$part.tmp\"-* \"$part.tmp\".* \"$part.stopped\"\n"
      << "# A task that ends without its part (a failure, scancel, the time limit) says so.\n"
      << "trap 'exit 143' TERM\n"
      << "trap 'status=$?; [ -e \"$part\" ] || echo \"task $i stopped with status $status at "
         "$(date -u +%FT%TZ)\" >\"$part.stopped\"' EXIT\n"
      << "echo \"$(date -u +%FT%TZ) task $i on $(hostname): seed $seed, shard $shard/$shards\"\n"
      << quoted(s.cli) << " simulate --protocol " << quoted(s.protocol)
      << " --participants \"$participants\" --seed \"$seed\" --shard \"$shard/$shards\" --jobs 1"
      << (s.simulate_options.empty() ? "" : " " + words(s.simulate_options))
      << " --db \"$part.tmp\"\n"
      << "mv \"$part.tmp\" \"$part\"\n"
      << "echo \"$(date -u +%FT%TZ) task $i done: $part\"\n";
  return out.str();
}

std::string merge_script(const SlurmSeries& s) {
  std::ostringstream out;
  out << "#!/bin/bash\n"
      << "# Joins each study's parts once they are all there (handlab-cli merge); a study "
         "merged\n# whole already is left as it is, a partial one (merge --partial) is merged "
         "again\n# with its parts. Written by handlab-cli (docs/cluster.md).\n"
      << "#SBATCH --job-name=handlab-merge\n"
      << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
      << "#SBATCH --output=" << s.dir << "/logs/merge.out\n"
      << site_directives(s) << "set -euo pipefail\n"
      << "merge_study() {\n"
      << "  local out=$1; shift\n"
      << "  " << quoted(s.cli) << " merge --update --out \"$out\" \"$@\"\n"
      << "}\n";
  for (const SlurmStudy& study : s.studies) {
    out << "merge_study " << quoted(study_path(s.dir, study));
    for (int shard = 1; shard <= shards_of(s, study); ++shard)
      out << " \\\n  " << quoted(part_path(s, study, shard));
    out << "\n";
  }
  return out.str();
}

std::string then_script(const SlurmSeries& s) {
  std::ostringstream out;
  out << "#!/bin/bash\n"
      << "# Runs once every study of the series is merged. Written by handlab-cli.\n"
      << "#SBATCH --job-name=handlab-then\n"
      << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
      << "#SBATCH --output=" << s.dir << "/logs/then.out\n"
      << site_directives(s) << "set -euo pipefail\n"
      << words(s.then) << "\n";
  return out.str();
}

void write_slurm_series(const SlurmSeries& s) {
  if (s.studies.empty() || s.per_task < 1 || s.max_array < 1)
    throw std::invalid_argument("a series needs studies, participants a task and array tasks");
  for (const SlurmStudy& study : s.studies)
    if (study.participants < 1) throw std::invalid_argument("a study needs participants");
  std::filesystem::create_directories(s.dir + "/parts");
  std::filesystem::create_directories(s.dir + "/logs");
  const std::string plan = s.dir + "/series.json", json = series_json(s);
  if (std::filesystem::exists(plan) && read_file(plan) != json)
    throw std::runtime_error(s.dir +
                             " holds another series (its series.json differs): use another "
                             "directory");
  write_file(plan, json, false);
  std::ostringstream tasks;
  for (const SlurmStudy& study : s.studies)
    for (int shard = 1; shard <= shards_of(s, study); ++shard)
      tasks << study.participants << '\t' << study.seed << '\t' << shard << '\t'
            << shards_of(s, study) << '\n';
  write_file(s.dir + "/tasks.tsv", tasks.str(), false);
  write_file(s.dir + "/array.sh", array_script(s), true);
  write_file(s.dir + "/merge.sh", merge_script(s), true);
  if (!s.then.empty()) write_file(s.dir + "/then.sh", then_script(s), true);
}

SlurmSeries read_slurm_series(const std::string& dir) {
  const std::string plan = dir + "/series.json";
  if (!std::filesystem::exists(plan))
    throw std::runtime_error(dir +
                             " holds no series (no series.json): write one with "
                             "simulate --slurm");
  SlurmSeries s;
  try {
    const util::JsonValue j = util::JsonValue::parse(read_file(plan));
    s.dir = std::filesystem::absolute(dir).lexically_normal().string();
    if (!s.dir.empty() && s.dir.back() == '/') s.dir.pop_back();
    s.cli = j["cli"].as_string();
    s.protocol = j["protocol"].as_string();
    s.per_task = int(j["per_task"].as_number());
    s.max_array = int(j["max_array"].as_number());
    for (const util::JsonValue& o : j["simulate_options"].as_array())
      s.simulate_options.push_back(o.as_string());
    for (const util::JsonValue& o : j["then"].as_array()) s.then.push_back(o.as_string());
    for (const util::JsonValue& study : j["studies"].as_array())
      s.studies.push_back(
          {int(study["participants"].as_number()), std::stoull(study["seed"].as_string())});
    s.partition = j["partition"].as_string();
    s.time = j["time"].as_string();
    s.mem = j["mem"].as_string();
  } catch (const std::exception& e) {
    throw std::runtime_error(plan + " is not a series handlab-cli wrote: " + e.what());
  }
  return s;
}

SeriesStatus series_status(const SlurmSeries& s) {
  SeriesStatus status;
  int task = 0;
  for (const SlurmStudy& study : s.studies) {
    SeriesStatus::Study st;
    st.study = study;
    st.path = study_path(s.dir, study);
    if (std::filesystem::exists(st.path)) {
      const bool partial =
          store::StudyStore(st.path, store::StudyStore::Access::kReadOnly).completeness().partial();
      st.merged = !partial;
      st.merged_partial = partial;
    }
    for (int shard = 1; shard <= shards_of(s, study); ++shard, ++task) {
      const std::string part = part_path(s, study, shard);
      const PartState state = std::filesystem::exists(part)                ? PartState::kDone
                              : std::filesystem::exists(part + ".stopped") ? PartState::kStopped
                              : std::filesystem::exists(part + ".tmp") ||
                                      std::filesystem::exists(part + ".tmp.creating")
                                  ? PartState::kRunning
                                  : PartState::kMissing;
      st.parts.push_back(state);
      if (state != PartState::kDone && !st.merged) status.unfinished_tasks.push_back(task);
    }
    status.studies.push_back(st);
  }
  return status;
}

}  // namespace handlab::studies
