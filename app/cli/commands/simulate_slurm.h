// simulate --slurm DIR and simulate --status DIR: a simulated series written as Slurm batch
// jobs and submitted with sbatch, and its progress read from the files.
#pragma once

#include "app/cli/arguments.h"
#include "studies/cluster/slurm_batch.h"

namespace handlab::cli {

// The options every command that writes a Slurm series takes beside its own --slurm DIR:
// --per-task, --partition, --time, --mem, --dry-run.
std::vector<OptionSpec> slurm_option_specs();
// Whether any of them was given (they go with --slurm).
bool has_slurm_options(const Arguments& args);
// A series' settings from those options and --slurm DIR and --protocol FILE (made absolute,
// as the nodes will read them), handlab-cli's own path; its studies and options are the
// command's to add.
studies::SlurmSeries series_settings(const Arguments& args);

// Writes the series' scripts and, unless `dry_run`, submits the array and the merge job that
// depends on it (afterok). Prints what it did.
void submit_slurm_series(const studies::SlurmSeries& series, bool dry_run);

// Prints the series in `dir`: each study's parts done, started and missing, and how to rerun
// what is unfinished; with `json` (a path or -) the same as JSON.
void print_series_status(const std::string& dir, const std::string& json);

}  // namespace handlab::cli
