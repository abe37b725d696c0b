// Simulated studies as Slurm batch jobs (`simulate --slurm DIR`, docs/cluster.md): a job array
// whose tasks each run one shard of one study (simulate --shard), and a merge job that
// depends on it (afterok) and joins each study's shards (merge). A task writes its part under
// a temporary name and renames it when complete, and skips a part that is there: rerunning an
// array index finishes a study, and `simulate --status DIR` tells from the files alone which
// parts are done, running, stopped or missing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace handlab::studies {

struct SlurmStudy {
  int participants = 20;
  std::uint64_t seed = 0;
};

struct SlurmSeries {
  std::string dir;       // absolute: the scripts, parts/, logs/ and the merged studies
  std::string cli;       // absolute path of handlab-cli, as the nodes see it
  std::string protocol;  // absolute path of the protocol, as the nodes see it
  std::vector<SlurmStudy> studies;
  int per_task = 1;  // participants a task runs
  // Tasks one job array may hold: the cluster's MaxArraySize (Slurm's default 1001). A series
  // of more tasks is submitted as several arrays, each told its first task by
  // HANDLAB_TASK_OFFSET.
  int max_array = 1001;
  // Passed on to every task's `simulate` (--world, --frames, --set ...), each a word.
  std::vector<std::string> simulate_options;
  std::string partition, time, mem;  // #SBATCH --partition, --time, --mem (empty: the site's)
  // A command run once every study is merged (power --pipeline --from DIR), as words; empty:
  // none.
  std::vector<std::string> then;
};

// Shards a study is cut into (its tasks), and the array's task count.
int shards_of(const SlurmSeries& series, const SlurmStudy& study);
int array_tasks(const SlurmSeries& series);

// The arrays a series is submitted as: the first task of each and how many it runs.
struct ArrayChunk {
  int offset = 0, tasks = 0;
};
std::vector<ArrayChunk> array_chunks(const SlurmSeries& series);

// Indices as Slurm's --array takes them: "0-3,7,9-10" (ascending input).
std::string index_ranges(const std::vector<int>& indices);

// The sbatch commands that rerun the array tasks given (indices into tasks.tsv) on a cluster
// where none of the series' jobs runs any more, then the merge and `then` after them; `JOB`
// stands for the job id sbatch printed for the line before.
std::vector<std::string> rerun_commands(const SlurmSeries& series, const std::vector<int>& tasks);

// Where a study's shard (1-based) and the merged study go.
std::string part_path(const SlurmSeries& series, const SlurmStudy& study, int shard);
std::string study_path(const std::string& dir, const SlurmStudy& study);

// The batch scripts: the job array's, the merge job's, and the one of `then`.
std::string array_script(const SlurmSeries& series);
std::string merge_script(const SlurmSeries& series);
std::string then_script(const SlurmSeries& series);

// Writes DIR/series.json (what `status` reads), DIR/tasks.tsv (each array task's study and
// shard), the scripts (array.sh, merge.sh, then.sh), and makes DIR/parts and DIR/logs.
// Throws std::runtime_error if DIR holds another series.
void write_slurm_series(const SlurmSeries& series);
SlurmSeries read_slurm_series(const std::string& dir);

enum class PartState { kDone, kRunning, kStopped, kMissing };
struct SeriesStatus {
  struct Study {
    SlurmStudy study;
    std::string path;
    bool merged = false;           // the merged study is there and whole
    bool merged_partial = false;   // it is there without every participant (merge --partial)
    std::vector<PartState> parts;  // per shard
  };
  std::vector<Study> studies;
  std::vector<int> unfinished_tasks;  // array indices whose part is not done (nor merged)
};
// From the files alone: a part is done when it is there; stopped when its task left a note that
// it ended without it (a failure, scancel, the time limit: rerun its index); running while its
// temporary file is there without that note (or its node died under it); missing otherwise.
// A study is merged when its merged study is there and holds every planned participant.
SeriesStatus series_status(const SlurmSeries& series);

}  // namespace handlab::studies
