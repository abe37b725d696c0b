// A simulated series as Slurm jobs (studies/cluster/slurm_batch.h): a task per shard of each
// study, written as tasks.tsv lines the array script reads; the state of every part read from
// the files alone; a directory that holds another series refused; a series larger than the
// cluster's MaxArraySize cut into arrays, and the tasks to rerun named in each.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "studies/cluster/slurm_batch.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

SlurmSeries two_studies(const std::string& dir) {
  SlurmSeries s;
  s.dir = dir;
  s.cli = "/opt/handlab/bin/handlab-cli";
  s.protocol = "/data/protocol's copy.json";  // a quote, as a path may have
  s.studies = {{5, 7}, {3, 18446744073709551615ull}};
  s.per_task = 2;
  s.simulate_options = {"--world", "proxy"};
  return s;
}

TEST(SlurmBatch, ATaskPerShardWithItsLineInTheTaskTable) {
  const std::string dir = test::fresh_path("slurm_batch_series");
  std::filesystem::remove_all(dir);
  const SlurmSeries s = two_studies(dir);
  EXPECT_EQ(shards_of(s, s.studies[0]), 3);
  EXPECT_EQ(shards_of(s, s.studies[1]), 2);
  EXPECT_EQ(array_tasks(s), 5);
  write_slurm_series(s);
  EXPECT_EQ(test::file_bytes(dir + "/tasks.tsv"),
            "5\t7\t1\t3\n5\t7\t2\t3\n5\t7\t3\t3\n"
            "3\t18446744073709551615\t1\t2\n3\t18446744073709551615\t2\t2\n");
  const std::string array = test::file_bytes(dir + "/array.sh");
  EXPECT_NE(array.find("#SBATCH --array=0-4\n"), std::string::npos) << array;
  EXPECT_NE(array.find("'/data/protocol'\\''s copy.json'"), std::string::npos) << array;
  EXPECT_NE(array.find("'--world' 'proxy'"), std::string::npos) << array;
  EXPECT_EQ(part_path(s, s.studies[1], 2),
            dir + "/parts/n3-seed18446744073709551615/shard-2-of-2.db");
  const std::string merge = test::file_bytes(dir + "/merge.sh");
  EXPECT_NE(merge.find("merge_study '" + dir + "/study-n5-seed7.db' \\\n  '" + dir +
                       "/parts/n5-seed7/shard-1-of-3.db'"),
            std::string::npos)
      << merge;
  EXPECT_FALSE(std::filesystem::exists(dir + "/then.sh"));
  // Read back as written (the 64-bit seed too); another series in the same folder refused.
  const SlurmSeries again = read_slurm_series(dir);
  ASSERT_EQ(again.studies.size(), 2u);
  EXPECT_EQ(again.studies[1].seed, 18446744073709551615ull);
  EXPECT_EQ(again.simulate_options, s.simulate_options);
  write_slurm_series(again);  // the same series again: its scripts rewritten
  SlurmSeries other = s;
  other.per_task = 1;
  EXPECT_THROW(write_slurm_series(other), std::runtime_error);
}

TEST(SlurmBatch, EachPartsStateFromTheFilesAlone) {
  const std::string dir = test::fresh_path("slurm_batch_status");
  std::filesystem::remove_all(dir);
  const SlurmSeries s = two_studies(dir);
  write_slurm_series(s);
  auto touch = [](const std::string& path) {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path) << "x";
  };
  touch(part_path(s, s.studies[0], 1));           // done
  touch(part_path(s, s.studies[0], 2) + ".tmp");  // running
  touch(part_path(s, s.studies[0], 3) + ".tmp");  // stopped
  touch(part_path(s, s.studies[0], 3) + ".stopped");
  // Merged (its parts since removed): a study whose plan is whole; the first study merged
  // from some of its parts only (merge --partial) is not.
  store::StudyDefinition definition{"s", "{}", 1, {"f"}, {{"a", {"a"}}}, 0};
  store::StudyStore::create(study_path(dir, s.studies[1]), definition);  // no plan: whole
  definition.planned_participants = 3;                                   // and none of them there
  store::StudyStore::create(study_path(dir, s.studies[0]), definition);
  const SeriesStatus status = series_status(s);
  ASSERT_EQ(status.studies.size(), 2u);
  EXPECT_EQ(status.studies[0].parts,
            (std::vector<PartState>{PartState::kDone, PartState::kRunning, PartState::kStopped}));
  EXPECT_FALSE(status.studies[0].merged);
  EXPECT_TRUE(status.studies[0].merged_partial);
  EXPECT_TRUE(status.studies[1].merged);
  EXPECT_FALSE(status.studies[1].merged_partial);
  EXPECT_EQ(status.unfinished_tasks, (std::vector<int>{1, 2}));
}

TEST(SlurmBatch, MoreTasksThanAnArrayMayHoldGoInSeveralArraysTheirTasksOffset) {
  const std::string dir = test::fresh_path("slurm_batch_chunks");
  std::filesystem::remove_all(dir);
  SlurmSeries s = two_studies(dir);
  s.max_array = 2;
  s.then = {"/opt/handlab/bin/handlab-cli", "power", "--from", dir};
  const auto chunks = array_chunks(s);
  ASSERT_EQ(chunks.size(), 3u);
  EXPECT_EQ(chunks[0].offset, 0);
  EXPECT_EQ(chunks[1].offset, 2);
  EXPECT_EQ(chunks[2].offset, 4);
  EXPECT_EQ(chunks[2].tasks, 1);
  write_slurm_series(s);
  const std::string array = test::file_bytes(dir + "/array.sh");
  EXPECT_NE(array.find("#SBATCH --array=0-1\n"), std::string::npos) << array;
  EXPECT_NE(array.find("$((${HANDLAB_TASK_OFFSET:-0} + SLURM_ARRAY_TASK_ID))"), std::string::npos);
  EXPECT_EQ(read_slurm_series(dir).max_array, 2);
  // Tasks 1 and 4 to rerun: index 1 of the first array, index 0 of the third; then the merge
  // after both and the power after the merge.
  const auto commands = rerun_commands(s, {1, 4});
  ASSERT_EQ(commands.size(), 4u);
  EXPECT_EQ(commands[0], "sbatch --array=1 '" + dir + "/array.sh'");
  EXPECT_EQ(commands[1],
            "sbatch --array=0 --export=ALL,HANDLAB_TASK_OFFSET=4 '" + dir + "/array.sh'");
  EXPECT_EQ(commands[2], "sbatch --dependency=afterok:JOB1:JOB2:... '" + dir + "/merge.sh'");
  EXPECT_EQ(commands[3], "sbatch --dependency=afterok:JOB '" + dir + "/then.sh'");
}

TEST(SlurmBatch, IndicesAsRangesAsSlurmsArrayTakesThem) {
  EXPECT_EQ(index_ranges({}), "");
  EXPECT_EQ(index_ranges({4}), "4");
  EXPECT_EQ(index_ranges({0, 1, 2, 3, 7, 9, 10, 12, 13, 14}), "0-3,7,9,10,12-14");
}

TEST(SlurmBatch, ASeriesFileThatIsNotOneIsRefusedByName) {
  const std::string dir = test::fresh_path("slurm_batch_bad");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/series.json") << "{\"cli\": \"x\"}";
  try {
    read_slurm_series(dir);
    FAIL() << "read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/series.json is not a series"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace handlab::studies
